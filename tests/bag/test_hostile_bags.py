"""Bags crafted to attack the reader: a schema name or a .db3 type column holding Python
source, a self-containing type. Nothing runs, nothing recurses; the bytes stay readable."""

from __future__ import annotations

import contextlib
import sqlite3
import time
from pathlib import Path

import pytest
from mcap.writer import Writer

from ros2lite.bag import BagError, Reader

PAYLOAD = b'\x00\x01\x00\x00\x05\x00\x00\x00'
EVIL = [
    'pkg/msg/X(object):\n  import os; os.system("touch {marker}")\nclass Y',
    'pkg/msg/X;__import__("os").system("touch {marker}")',
    'pkg/msg/X\x00',
    'std_msgs/msg/String"]; import os #',
]


def _mcap(path: Path, schema_name: str, text: str) -> Path:
    path.mkdir(parents=True)
    with open(path / f'{path.name}_0.mcap', 'wb') as f:
        w = Writer(f)
        w.start(profile='ros2', library='test')
        sid = w.register_schema(schema_name, 'ros2msg', text.encode())
        cid = w.register_channel('/t', 'cdr', sid, {})
        w.add_message(cid, 1000, PAYLOAD, 1000, 0)
        w.finish()
    return path


@pytest.mark.parametrize('name', EVIL)
def test_a_schema_name_never_runs(tmp_path: Path, name: str) -> None:
    marker = tmp_path / 'PWNED'
    bag = _mcap(tmp_path / 'evil', name.format(marker=marker), 'int32 a\n')
    with Reader(bag) as reader:
        assert list(reader.messages()) == [('/t', PAYLOAD, 1000)]
    assert not marker.exists()


def test_a_db3_type_column_never_runs(tmp_path: Path) -> None:
    marker = tmp_path / 'PWNED'
    bag = tmp_path / 'evil_db3'
    bag.mkdir()
    db = sqlite3.connect(bag / 'evil_db3_0.db3')
    db.executescript(
        'CREATE TABLE topics (id INTEGER PRIMARY KEY, name TEXT, type TEXT, '
        'serialization_format TEXT, offered_qos_profiles TEXT);'
        'CREATE TABLE messages (id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, '
        'data BLOB);'
        'CREATE TABLE message_definitions (id INTEGER PRIMARY KEY, topic_type TEXT, '
        'encoding TEXT, encoded_message_definition TEXT, type_description_hash TEXT);'
    )
    evil = f'pkg/msg/X(object):\n  import os; os.system("touch {marker}")\nclass Y'
    db.execute("INSERT INTO topics VALUES (1, '/t', ?, 'cdr', '')", (evil,))
    db.execute('INSERT INTO messages VALUES (1, 1, 1000, ?)', (PAYLOAD,))
    db.execute("INSERT INTO message_definitions VALUES (1, ?, 'ros2msg', 'int32 a', '')", (evil,))
    db.commit()
    db.close()
    with Reader(bag) as reader:
        assert list(reader.messages()) == [('/t', PAYLOAD, 1000)]
    assert not marker.exists()


def test_a_self_containing_type_is_read_as_bytes(tmp_path: Path) -> None:
    text = 'pkg/Loop next\n'
    bag = _mcap(tmp_path / 'loop', 'pkg/msg/Loop', text)
    with Reader(bag) as reader:
        assert list(reader.messages()) == [('/t', PAYLOAD, 1000)]
        with pytest.raises(ValueError, match='contains itself'):
            reader.deserialize(PAYLOAD, 'pkg/msg/Loop')


def _db3(
    bag: Path, messages_table: str, topics_table: str, rows: list[tuple[object, object]]
) -> Path:
    bag.mkdir()
    db = sqlite3.connect(bag / f'{bag.name}_0.db3')
    db.execute(topics_table)
    db.execute(messages_table)
    db.execute(
        "INSERT INTO topics(id, type, serialization_format, offered_qos_profiles) "
        "VALUES (1, 'std_msgs/msg/String', 'cdr', '')"
    )
    with contextlib.suppress(sqlite3.OperationalError):
        db.execute("UPDATE topics SET name = '/d'")
    for i, (stamp, data) in enumerate(rows):
        if data is None:
            db.execute('INSERT INTO messages(id, topic_id, timestamp) VALUES (?, 1, ?)', (i, stamp))
        else:
            db.execute('INSERT INTO messages VALUES (?, 1, ?, ?)', (i, stamp, data))
    db.commit()
    db.close()
    return bag


TOPICS = (
    'CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT NOT NULL, '
    'serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)'
)
MESSAGES = (
    'CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, '
    'timestamp INTEGER NOT NULL, data BLOB NOT NULL)'
)


def test_db3_rows_of_the_wrong_types_are_counted_and_skipped(tmp_path: Path) -> None:
    """R5-B5: a TEXT timestamp broke arithmetic and a TEXT data broke decoding; such rows are
    now skipped, counted in one line, and the sound rows read."""
    rows: list[tuple[object, object]] = [(1000 + i, PAYLOAD) for i in range(3)]
    rows += [('2023-11-14 1', PAYLOAD), (2000, 'seq:1:text')]
    bag = _db3(tmp_path / 'odd', MESSAGES, TOPICS, rows)
    with Reader(bag) as reader:
        [line] = reader.shortfalls()
        assert list(reader.messages(raw=True)) == [('/d', PAYLOAD, 1000 + i) for i in range(3)]
    assert '2 message row(s) whose timestamp is not an integer or whose data is not a blob' in line


@pytest.mark.parametrize('table', ['topics', 'messages'])
def test_db3_generated_columns_are_refused_before_they_are_computed(
    tmp_path: Path, table: str
) -> None:
    """R5-B5: a topic name generated as 500 M characters took 88 s and 2.5 GB, then aborted
    the process; a generated column is no bag's, and is refused on opening."""
    topics, messages, rows = TOPICS, MESSAGES, [(1000, PAYLOAD)]
    if table == 'topics':
        topics = TOPICS.replace(
            'name TEXT,', "name TEXT GENERATED ALWAYS AS (printf('/%.*c', 500000000, 'x')) VIRTUAL,"
        )
    else:
        messages = MESSAGES.replace(
            'data BLOB NOT NULL', 'data BLOB GENERATED ALWAYS AS (zeroblob(1000000000)) VIRTUAL'
        )
        rows = [(1000, None)]
    bag = _db3(tmp_path / 'gen', messages, topics, rows)
    started = time.monotonic()
    with pytest.raises(BagError, match=f'column {table}.(name|data) is generated, not stored'):
        Reader(bag).summary()
    assert time.monotonic() - started < 5
