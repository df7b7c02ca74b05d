"""view_frames' text and picture for a known tree, without a graph: the Graphviz text exactly
as tf2_tools writes it, and a PDF whose every frame name and label poppler finds."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from ros2lite.bundled.tf2_tools.frames import Frame, parse, to_dot
from ros2lite.bundled.tf2_tools.pdf import to_pdf

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
    for bad in ('- 1', 'a: {parent: b}', 'a: 3', 'a: {parent: b, rate: x}'):
        with pytest.raises(ValueError):
            parse(bad)


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
