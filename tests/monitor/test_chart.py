"""The chart drawings as a person sees them: braille text with ticks and a legend, and PNG and
SVG pictures whose lines are where the data says, in the series' colours."""

from __future__ import annotations

import math
import re
import struct
import zlib

from ros2lite.monitor.chart import (
    PALETTE,
    Chart,
    Line,
    braille,
    layout,
    nice_ticks,
    png,
    ranges,
    svg,
    thin,
)

ANSI = re.compile(r'\x1b\[[0-9;]*m')


def read_png(data: bytes) -> tuple[int, int, bytes]:
    """(width, height, RGB rows) of an 8-bit RGB PNG, filters undone (no imaging library)."""
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    pos, idat, width, height = 8, b'', 0, 0
    while pos < len(data):
        (size,) = struct.unpack('>I', data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + size]
        if kind == b'IHDR':
            width, height, depth, colour = struct.unpack('>IIBB', body[:10])
            assert (depth, colour) == (8, 2)
        elif kind == b'IDAT':
            idat += body
        pos += 12 + size
    raw = zlib.decompress(idat)
    stride = width * 3
    out = bytearray()
    prev = bytearray(stride)
    for y in range(height):
        f, line = (
            raw[y * (stride + 1)],
            bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)]),
        )
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = prev[i]
            c = prev[i - 3] if i >= 3 else 0
            if f == 1:
                line[i] = (line[i] + a) & 0xFF
            elif f == 2:
                line[i] = (line[i] + b) & 0xFF
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 0xFF
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 0xFF
        out += line
        prev = line
    return width, height, bytes(out)


def ramp() -> Chart:
    xs = [i / 10 for i in range(101)]
    return Chart(
        [
            Line('/up', xs, xs, PALETTE[0], '= 10'),
            Line('/down', xs, [10 - x for x in xs], PALETTE[1]),
        ],
        x_label='time (s)',
    )


def test_ticks_are_round() -> None:
    assert nice_ticks(0, 10, 5) == [0, 2, 4, 6, 8, 10]
    assert nice_ticks(0.13, 0.61, 4) == [0.2, 0.4, 0.6]
    assert nice_ticks(0.13, 0.61, 8) == [0.2, 0.3, 0.4, 0.5, 0.6]
    assert nice_ticks(-3, 3, 3) == [-2, 0, 2]


def test_thinning_keeps_extremes_and_costs_per_column() -> None:
    xs = [i / 1000 for i in range(10_000)]
    ys = [math.sin(x * 20) for x in xs]
    kept = thin(xs, ys, 0, 10, 100)
    assert len(kept) <= 4 * 101
    assert max(y for _, y in kept) == max(ys) and min(y for _, y in kept) == min(ys)
    broken = thin([0, 1, 2, 3], [0, math.nan, 2, 3], 0, 3, 10)
    assert math.isnan(broken[1][0]) and broken[0] == (0, 0) and broken[-1] == (3, 3)


def test_braille_draws_lines_ticks_and_a_legend() -> None:
    text = braille(ramp(), 60, 16)
    lines = text.split('\n')
    assert len(lines) == 16 and all(len(ANSI.sub('', ln)) <= 60 for ln in lines)
    assert '\x1b[38;2;31;119;180m' in text  # the first series' colour
    plain = braille(ramp(), 60, 16, colour=False)
    assert '\x1b' not in plain
    rows = plain.split('\n')
    assert '/up = 10' in rows[0] and '/down' in rows[0]
    plot_rows = rows[1:-2]
    # the rising line starts bottom left and ends top right; the falling one the other way
    first_col = next(r.index('┤') if '┤' in r else r.index('│') for r in plot_rows) + 1
    assert plot_rows[-1][first_col] != ' ' and plot_rows[0][first_col] != ' '
    assert plot_rows[0].rstrip()[-1] != ' ' and plot_rows[-1].rstrip()[-1] != ' '
    assert any(0x2800 < ord(ch) <= 0x28FF for ch in plot_rows[len(plot_rows) // 2])
    assert rows[-2].lstrip().startswith('└') and '┬' in rows[-2]
    assert rows[-1].split()[:2] == ['0', '5'] and rows[-1].endswith('time (s)')


def test_png_has_the_lines_where_the_data_is() -> None:
    chart = ramp()
    width, height, rgb = read_png(png(chart, 400, 300))
    assert (width, height) == (400, 300)

    def colour_at(x: float, y: float, want: tuple[int, int, int]) -> bool:
        # within a pixel or two of the exact spot (the lines are two pixels wide)
        for dy in (-2, -1, 0, 1, 2):
            for dx in (-2, -1, 0, 1, 2):
                i = ((round(y) + dy) * width + round(x) + dx) * 3
                if tuple(rgb[i : i + 3]) == want:
                    return True
        return False

    frame = layout(chart, 400, 300)
    (x0, x1), (y0, y1) = ranges(chart)
    for t in (3.0, 5.5, 7.0, 9.5):  # clear of the legend box at the top left
        px = frame.left + (t - x0) / (x1 - x0) * (frame.right - frame.left)
        up = frame.bottom - (t - y0) / (y1 - y0) * (frame.bottom - frame.top)
        down = frame.bottom - (10 - t - y0) / (y1 - y0) * (frame.bottom - frame.top)
        assert colour_at(px, up, PALETTE[0]), t
        assert colour_at(px, down, PALETTE[1]), t


def test_svg_is_a_document_with_a_polyline_per_series() -> None:
    text = svg(ramp(), 640, 400)
    assert text.startswith('<svg xmlns="http://www.w3.org/2000/svg" width="640" height="400"')
    assert text.count('stroke="#1f77b4" stroke-width="2"') == 1  # the /up line
    assert text.count('stroke="#ff7f0e" stroke-width="2"') == 1
    assert '>/up  = 10</text>' in text and '>time (s)</text>' in text
    assert text.rstrip().endswith('</svg>')
