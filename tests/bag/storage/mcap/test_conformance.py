"""The MCAP project's conformance files as an oracle for the scanner and the reader.

Each `<name>.mcap` of the project's conformance data comes with `<name>.json`: every record a
streamed reader must see, in file order, fields as strings. The scanner
(`bag/storage/mcap/scan.records`) must yield exactly its Schema, Channel, Message and
Metadata records; the reader (`McapStorageReader`) must give the same messages, topics and
counts, by the summary where the file has one and by a scan where it has not.

The files are not in this repository: they are read from a cache
(`$ROS2LITE_MCAP_CONFORMANCE`, else `~/.cache/ros2lite/test-data/mcap-conformance`), filled
by a shallow sparse clone of the project's repository with its Git LFS files. Without a
network, git-lfs or the cache, the conformance test skips; the harness check below still
runs, on a file the `mcap` package writes.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest
from mcap.records import Channel, McapRecord, Message, Metadata, Schema
from mcap.writer import Writer

from ros2lite.bag.storage.mcap import McapStorageReader
from ros2lite.bag.storage.mcap.scan import records

MAGIC = b'\x89MCAP0\r\n'
KINDS = ('Schema', 'Channel', 'Message', 'Metadata')
REPOSITORY = 'https://github.com/foxglove/mcap.git'
DATA = 'tests/conformance/data'


def _cache() -> Path:
    home = Path.home() / '.cache' / 'ros2lite' / 'test-data' / 'mcap-conformance'
    return Path(os.environ.get('ROS2LITE_MCAP_CONFORMANCE') or home)


def _usable(data: Path) -> bool:
    """Real MCAP files there (a clone without git-lfs holds only pointers to them)."""
    files = sorted(data.rglob('*.mcap'))
    return bool(files) and all(f.read_bytes()[:8] == MAGIC for f in files)


def _fill(cache: Path) -> str:
    """Clone the conformance data into `cache/data`; what went wrong, or ''."""
    if shutil.which('git') is None or shutil.which('git-lfs') is None:
        return 'git and git-lfs are needed to fetch them'
    cache.mkdir(parents=True, exist_ok=True)
    env = {**os.environ, 'GIT_TERMINAL_PROMPT': '0', 'GIT_LFS_SKIP_SMUDGE': '0'}
    with tempfile.TemporaryDirectory(dir=cache) as tmp:
        repo = Path(tmp) / 'repo'
        steps = [
            ['git', 'clone', '-q', '--depth', '1', '--filter=blob:none', '--sparse', REPOSITORY,
             str(repo)],
            ['git', '-C', str(repo), 'sparse-checkout', 'set', DATA],
            ['git', '-C', str(repo), 'lfs', 'pull', '--include', f'{DATA}/**'],
        ]  # fmt: skip
        for step in steps:
            try:
                done = subprocess.run(step, env=env, capture_output=True, text=True, timeout=300)
            except subprocess.TimeoutExpired:
                return f'{" ".join(step[:3])}: timed out'
            if done.returncode != 0:
                return f'{" ".join(step[:3])}: {done.stderr.strip().splitlines()[-1:]}'
        if not _usable(repo / DATA):
            return 'the clone holds no MCAP files'
        shutil.rmtree(cache / 'data', ignore_errors=True)
        (repo / DATA).rename(cache / 'data')
    return ''


@pytest.fixture(scope='module')
def conformance() -> Path:
    data = _cache() / 'data'
    if not _usable(data):
        why = _fill(_cache())
        if why or not _usable(data):
            pytest.skip(f'MCAP conformance files not in {data}: {why}')
    return data


def _as_json(record: McapRecord) -> dict[str, object]:
    """A record as the conformance files write it: fields by name, sorted, numbers and
    bytes as strings."""

    def data(raw: bytes) -> list[str]:
        return [str(b) for b in raw]

    if isinstance(record, Schema):
        fields: list[list[object]] = [
            ['data', data(record.data)], ['encoding', record.encoding], ['id', str(record.id)],
            ['name', record.name],
        ]  # fmt: skip
    elif isinstance(record, Channel):
        fields = [
            ['id', str(record.id)], ['message_encoding', record.message_encoding],
            ['metadata', dict(record.metadata)], ['schema_id', str(record.schema_id)],
            ['topic', record.topic],
        ]  # fmt: skip
    elif isinstance(record, Message):
        fields = [
            ['channel_id', str(record.channel_id)], ['data', data(record.data)],
            ['log_time', str(record.log_time)], ['publish_time', str(record.publish_time)],
            ['sequence', str(record.sequence)],
        ]  # fmt: skip
    elif isinstance(record, Metadata):
        fields = [['metadata', dict(record.metadata)], ['name', record.name]]
    else:
        raise AssertionError(f'the scan yielded a {type(record).__name__}')
    return {'type': type(record).__name__, 'fields': fields}


def _breaks(mcap: Path, expected: list[dict[str, object]]) -> list[str]:
    """How the scanner and the reader differ from the expected records of `mcap`."""
    want = [r for r in expected if r['type'] in KINDS]
    problems: list[str] = []
    with open(mcap, 'rb') as stream:
        got = [_as_json(r) for r in records(stream, problems)]
    breaks = [f'{mcap.name}: scan: {p}' for p in problems]
    if got != want:
        breaks.append(f'{mcap.name}: scan yields {got} instead of {want}')
    topics: dict[str, str] = {}
    messages = []
    for r in want:
        fields = dict(r['fields'])  # type: ignore[call-overload]
        if r['type'] == 'Channel':
            topics[fields['id']] = fields['topic']
        elif r['type'] == 'Message':
            raw = bytes(int(b) for b in fields['data'])
            times = int(fields['log_time']), int(fields['publish_time'])
            messages.append((topics[fields['channel_id']], raw, *times))
    reader = McapStorageReader(str(mcap))
    try:
        read = list(reader.messages())
        summary = reader.summary()
    finally:
        reader.close()
    if sorted(read) != sorted(messages):
        breaks.append(f'{mcap.name}: the reader gives {read} instead of {messages}')
    if [t for _, _, t, _ in read] != sorted(t for _, _, t, _ in read):
        breaks.append(f'{mcap.name}: the reader is out of log-time order')
    counts = {topic: sum(1 for m in messages if m[0] == topic) for topic in topics.values()}
    if summary.message_count != len(messages) or {t: n for t, n in summary.counts.items() if n} != {
        t: n for t, n in counts.items() if n
    }:
        breaks.append(f'{mcap.name}: the summary counts {summary.counts}, not {counts}')
    return breaks


def test_the_conformance_files(conformance: Path) -> None:
    files = sorted(conformance.rglob('*.mcap'))
    breaks = []
    for mcap in files:
        expected = json.loads(mcap.with_suffix('.json').read_text())['records']
        breaks += _breaks(mcap, expected)
    assert len(files) > 100  # every variant of every case
    assert breaks == []


def test_the_harness_on_a_file_the_mcap_writer_wrote(tmp_path: Path) -> None:
    """The comparison itself, on a file of the `mcap` package's writer and its records as
    the conformance files would list them (hand-written), and on a damaged copy."""
    path = tmp_path / 'small.mcap'
    with open(path, 'wb') as f:
        writer = Writer(f)
        writer.start(profile='', library='')
        schema = writer.register_schema('Example', 'c', b'\x04\x05\x06')
        channel = writer.register_channel('example', 'a', schema, {'foo': 'bar'})
        writer.add_message(channel, log_time=2, data=b'\x01\x02\x03', publish_time=1, sequence=10)
        writer.add_message(channel, log_time=1, data=b'\x07', publish_time=1, sequence=11)
        writer.add_metadata('myMetadata', {'foo': 'bar'})
        writer.finish()
    schema_json = {
        'type': 'Schema',
        'fields': [['data', ['4', '5', '6']], ['encoding', 'c'], ['id', '1'], ['name', 'Example']],
    }
    channel_json = {
        'type': 'Channel',
        'fields': [
            ['id', '1'], ['message_encoding', 'a'], ['metadata', {'foo': 'bar'}],
            ['schema_id', '1'], ['topic', 'example'],
        ],
    }  # fmt: skip

    def message(data: list[str], log: str, seq: str) -> dict[str, object]:
        fields = [['channel_id', '1'], ['data', data], ['log_time', log], ['publish_time', '1']]
        return {'type': 'Message', 'fields': [*fields, ['sequence', seq]]}

    metadata = {
        'type': 'Metadata',
        'fields': [['metadata', {'foo': 'bar'}], ['name', 'myMetadata']],
    }
    # the writer puts metadata out at once, messages in a chunk at the end, and repeats
    # schemas and channels in the summary; the scan sees them in that order
    data_section = [metadata, schema_json, channel_json, message(['1', '2', '3'], '2', '10')]
    data_section += [message(['7'], '1', '11')]
    with open(path, 'rb') as stream:
        got = [_as_json(r) for r in records(stream)]
    assert got == [*data_section, schema_json, channel_json]
    assert _breaks(path, got) == []
    wrong = [*data_section[:3], message(['1', '2', '3'], '3', '10'), *data_section[4:]]
    assert any('scan yields' in b for b in _breaks(path, wrong))
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(path.read_bytes()[:-200])  # no summary, no footer: the scan is reported
    assert any('scan:' in b for b in _breaks(cut, got))
