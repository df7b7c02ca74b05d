"""view_frames' text and picture for a known tree, without a graph: the Graphviz text exactly
as tf2_tools writes it, and a PDF whose every frame name and label poppler finds."""

from __future__ import annotations

import shutil
import subprocess
import time
from pathlib import Path

import pytest

from ros2lite.bundled.tf2_tools.frames import Frame, parse, to_dot, to_graph
from ros2lite.bundled.tf2_tools.pdf import to_pdf
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.tf2 import Buffer

# tf2's own text (a frame's line ends in a space, as tf2 writes it)
YAML = (
    'turtle1: \n'
    "  parent: 'world'\n"
    "  broadcaster: 'default_authority'\n"
    '  rate: 20.000\n'
    '  most_recent_transform: 1700000004.950000\n'
    '  oldest_transform: 1700000000.000000\n'
    '  buffer_length: 4.950\n'
    'turtle2: \n'
    "  parent: 'world'\n"
    "  broadcaster: 'default_authority'\n"
    '  rate: 10000.000\n'
    '  most_recent_transform: 0.000000\n'
    '  oldest_transform: 0.000000\n'
    '  buffer_length: 0.000\n'
)


def test_parse_and_dot() -> None:
    frames = parse(YAML)
    assert [(f.name, f.parent) for f in frames] == [('turtle1', 'world'), ('turtle2', 'world')]
    assert to_dot(frames, 1700000005.5) == (
        'digraph G {\n'
        '"world" -> "turtle1"[label=" Broadcaster: default_authority\\nAverage rate: 20.0\\n'
        'Buffer length: 4.95\\nMost recent transform: 1700000004.95\\n'
        'Oldest transform: 1700000000.0\\n"];\n'
        '"world" -> "turtle2"[label=" Broadcaster: default_authority\\nAverage rate: 10000.0\\n'
        'Buffer length: 0.0\\nMost recent transform: 0.0\\nOldest transform: 0.0\\n"];\n'
        'edge [style=invis];\n'
        ' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n'
        '"Recorded at time: 1700000005.5"[ shape=plaintext ] ;\n'
        '}->"world";\n}'
    )
    assert parse('[]') == () and to_dot((), 1.0) == 'digraph G { "No tf data received" }'
    for bad in ('- 1', 'a: [b', 'a: 3\n- b'):
        with pytest.raises(ValueError):
            parse(bad)
    # an entry that is not a frame is left out with a line; the others stay
    for bad in ('a: {parent: b}', 'a: 3', 'a: {parent: b, rate: x}'):
        skipped: list[str] = []
        assert parse(YAML + bad, skipped) == frames
        assert len(skipped) == 1 and "entry for 'a'" in skipped[0]


def pdf_text(pdf: Path) -> str:
    return subprocess.run(
        ['pdftotext', str(pdf), '-'], capture_output=True, text=True, check=True
    ).stdout


def ink(pdf: Path) -> int:
    """How much of the page, rendered by pdftoppm, is not white (colour channels below 255)."""
    root = pdf.parent / f'{pdf.stem}-page'
    subprocess.run(['pdftoppm', '-r', '50', '-singlefile', str(pdf), str(root)], check=True)
    ppm = root.with_name(root.name + '.ppm').read_bytes()
    magic, width, height, depth, pixels = ppm.split(maxsplit=4)
    assert magic == b'P6' and depth == b'255'
    assert len(pixels) == int(width) * int(height) * 3 and pixels.count(b'\xff') > 0
    return len(pixels) - pixels.count(b'\xff')


def needs_poppler() -> None:
    if shutil.which('pdftoppm') is None or shutil.which('pdftotext') is None:
        pytest.skip('poppler-utils is not installed: PDF tests need pdftoppm and pdftotext')


def test_pdf_shows_every_frame(tmp_path: Path) -> None:
    needs_poppler()
    frames = (*parse(YAML), Frame('carrot1', 'turtle1', 'default_authority', 20.0, 4.95, 2, 1))
    pdf = tmp_path / 'frames.pdf'
    pdf.write_bytes(to_pdf(frames, 1700000005.5))
    words = pdf_text(pdf).split()
    for name in ('world', 'turtle1', 'turtle2', 'carrot1', 'view_frames', 'Result'):
        assert name in words
    assert 'default_authority' in words and '1700000005.5' in words
    assert ink(pdf) > 500
    empty = tmp_path / 'empty.pdf'
    empty.write_bytes(to_pdf((), 1.0))
    assert 'No tf data received' in pdf_text(empty)


# frame names no one should send, and one that is merely long
HOSTILE = (
    'evil\x1b]0;PWNED\x07',  # OSC 0: retitles a terminal
    'line\n@ros2_lv/forged: x',  # a line break and a colon
    "quote'd \"both\"",
    'Z' * 5000,  # over YAML's 1,024 characters of a simple key
    'true',  # a YAML word
)


def _buffer(children: list[tuple[str, str]]) -> Buffer:
    buffer = Buffer()
    for parent, child in children:
        t = TransformStamped()
        t.header.frame_id = parent
        t.child_frame_id = child
        t.header.stamp.sec = 100
        t.transform.rotation.w = 1.0
        buffer.set_transform(t, 'default_authority')
    return buffer


def test_hostile_frame_names_are_drawn_escaped_with_the_rest(tmp_path: Path) -> None:
    needs_poppler()
    tree = [('world', 'base_link'), *(('base_link', name) for name in HOSTILE)]
    skipped: list[str] = []
    frames = parse(_buffer(tree).all_frames_as_yaml(), skipped)
    assert skipped == []
    assert sorted(f.name for f in frames) == sorted(['base_link', *HOSTILE])
    dot = to_dot(frames, 1.0)
    assert '\x1b' not in dot and '\x07' not in dot
    assert '"base_link" -> "evil\\\\x1b]0;PWNED\\\\x07"' in dot
    assert '"base_link" -> "line\\\\x0a@ros2_lv/forged: x"' in dot
    assert '"base_link" -> "quote\'d \\"both\\""' in dot
    assert dot.count(' -> ') == 1 + len(HOSTILE)
    graph = to_graph(frames)
    assert all(ch.isprintable() for name in graph.nodes for ch in name)
    pdf = tmp_path / 'frames.pdf'
    pdf.write_bytes(to_pdf(frames, 1.0))
    text = pdf_text(pdf)
    assert 'base_link' in text.split() and 'evil\\x1b]0;PWNED\\x07' in text


def test_raw_control_characters_from_a_peer_are_read_escaped() -> None:
    # tf2 itself writes names unescaped: a peer's answer may hold raw ESC and BEL
    raw = YAML + YAML.split('turtle2')[0].replace('turtle1', 'evil\x1b]0;PWNED\x07')
    skipped: list[str] = []
    frames = parse(raw, skipped)
    assert [f.name for f in frames] == ['turtle1', 'turtle2', 'evil\\x1b]0;PWNED\\x07']
    assert skipped == ['frame names with control characters are shown escaped']


def test_two_thousand_frames_take_seconds(tmp_path: Path) -> None:
    # the layout was quadratic (grandalf builds its graph so): 500 / 1,000 / 2,000 frames took
    # 8.7 s / 29 s / ~250 s; a tree is now laid out in linear time (about 6 s here, with fpdf
    # drawing most of it, on a loaded 2-core machine)
    buffer = _buffer([('map', f'sensor_{i}') for i in range(2000)])
    started = time.monotonic()
    frames = parse(buffer.all_frames_as_yaml())
    assert len(frames) == 2000
    to_dot(frames, 1.0)
    pdf = to_pdf(frames, 1.0)
    assert time.monotonic() - started < 60, time.monotonic() - started
    (tmp_path / 'big.pdf').write_bytes(pdf)
    assert pdf.startswith(b'%PDF')
