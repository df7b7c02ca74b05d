"""Bags crafted to attack the reader: a schema name or a .db3 type column holding Python
source, a self-containing type. Nothing runs, nothing recurses; the bytes stay readable."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest
from mcap.writer import Writer

from ros2lite.bag import Reader

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
