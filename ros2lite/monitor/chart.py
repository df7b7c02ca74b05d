"""Drawing a line chart three ways from one layout: braille text for any terminal (SSH, tmux),
and a list of shapes (lines, text, rectangles) in pixels that an SVG writer, a PNG painter
(Pillow, which fpdf2 already brings) and a tkinter canvas each draw as they are.

Only what plots need: autoscaled or fixed axes with round ticks, a legend with a readout per
line, lines thinned to about two points per column (the first and the extremes of the samples
falling there, so a 1 kHz series costs the same to draw as a 10 Hz one) and broken at NaN.
"""

from __future__ import annotations

import bisect
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from xml.sax.saxutils import escape

__all__ = [
    'PALETTE',
    'Chart',
    'Line',
    'Shape',
    'braille',
    'layout',
    'nice_ticks',
    'png',
    'svg',
]

# matplotlib's 'tab10', the colours rqt_plot's lines have
PALETTE: tuple[tuple[int, int, int], ...] = (
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
)
BACKGROUND = (255, 255, 255)
GRID = (225, 225, 225)
INK = (40, 40, 40)


@dataclass
class Line:
    """One series: points in order, a colour, and what the legend says beside its label."""

    label: str
    xs: Sequence[float]
    ys: Sequence[float]
    colour: tuple[int, int, int] = PALETTE[0]
    note: str = ''
    ordered: bool = False  # xs never fall (a time series, a profile): drawn the fast way


@dataclass
class Chart:
    """What to draw; a range left None is fitted to the data (autoscale)."""

    lines: list[Line]
    x_range: tuple[float, float] | None = None
    y_range: tuple[float, float] | None = None
    x_label: str = ''
    title: str = ''
    status: str = ''  # one more line under the chart (paused, keys)


def nice_ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """Round values (1, 2 or 5 times a power of ten apart) from `lo` to `hi`, about `count`."""
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
        return [lo] if math.isfinite(lo) else []
    raw = (hi - lo) / max(count, 1)
    power = 10 ** math.floor(math.log10(raw))
    step = next(m * power for m in (1, 2, 5, 10) if m * power >= raw)
    first = math.ceil(lo / step - 1e-9) * step
    ticks = []
    n = 0
    while first + n * step <= hi + step * 1e-9:
        ticks.append(round(first + n * step, 12))
        n += 1
    return ticks


def tick_text(value: float, ticks: Sequence[float]) -> str:
    """A tick's label with as many decimals as the ticks' spacing needs."""
    step = abs(ticks[1] - ticks[0]) if len(ticks) > 1 else abs(value) or 1.0
    decimals = max(0, -math.floor(math.log10(step))) if step > 0 else 0
    if abs(value) >= 1e6 or (value != 0 and abs(value) < 1e-4):
        return f'{value:.3g}'
    return f'{value:.{decimals}f}'


def _finite(values: Sequence[float]) -> list[float]:
    """The real numbers among `values` (the sum tells at C speed when all are)."""
    if math.isfinite(sum(values)):
        return list(values)
    return [v for v in values if math.isfinite(v)]


def _extremes(values: Sequence[float]) -> list[float]:
    """The lowest and highest real number of `values` (none if it has none)."""
    finite = _finite(values)
    return [min(finite), max(finite)] if finite else []


def ranges(chart: Chart) -> tuple[tuple[float, float], tuple[float, float]]:
    """The x and y ranges drawn: the chart's own, or the data's with a margin on y."""

    def fitted(values: list[float], margin: float) -> tuple[float, float]:
        if not values:
            return (0.0, 1.0)
        lo, hi = min(values), max(values)
        if hi - lo < 1e-12 * max(1.0, abs(hi)):
            pad = max(abs(hi) * 0.05, 0.5)
            return (lo - pad, hi + pad)
        pad = (hi - lo) * margin
        return (lo - pad, hi + pad)

    x = chart.x_range or fitted([v for ln in chart.lines for v in _extremes(ln.xs)], 0.0)
    y = chart.y_range or fitted([v for ln in chart.lines for v in _extremes(ln.ys)], 0.05)
    if x[1] <= x[0]:
        x = (x[0], x[0] + 1.0)
    if y[1] <= y[0]:
        y = (y[0], y[0] + 1.0)
    return x, y


def thin(
    xs: Sequence[float],
    ys: Sequence[float],
    x0: float,
    x1: float,
    columns: int,
    ordered: bool = False,
) -> list[tuple[float, float]]:
    """The points to draw: per column the first point there, its lowest and highest and the
    last, in order; (nan, nan) where the line breaks (a NaN sample). `ordered` (xs never
    fall) allows the fast way."""
    if (
        ordered
        and isinstance(xs, list)
        and isinstance(ys, list)
        and len(xs) > 4 * columns
        and x1 > x0
        and math.isfinite(sum(xs))
    ):
        return _thin_sorted(xs, ys, x0, x1, columns)
    return _thin_any(xs, ys, x0, x1, columns)


def _thin_sorted(
    xs: list[float], ys: list[float], x0: float, x1: float, columns: int
) -> list[tuple[float, float]]:
    """`thin` of points in x order: each column's samples found by bisection and reduced by
    min/max at C speed; a column holding a non-finite value takes the general way."""
    out: list[tuple[float, float]] = []
    step = (x1 - x0) / columns
    start = bisect.bisect_left(xs, x0) if xs[0] < x0 else 0
    if start > 0:
        start -= 1  # the point before the window, so the line runs in from the edge
    column = int((xs[start] - x0) // step)
    n = len(xs)
    while start < n:
        end = bisect.bisect_left(xs, x0 + (column + 1) * step, start)
        if end <= start:
            end = start + 1
        chunk = ys[start:end]
        if not math.isfinite(sum(chunk)):
            out += _thin_any(xs[start:end], chunk, x0, x1, columns)
        else:
            first = (xs[start], chunk[0])
            out.append(first)
            if len(chunk) > 1:
                lo, hi = min(chunk), max(chunk)
                i_lo, i_hi = chunk.index(lo), chunk.index(hi)
                for i in sorted({i_lo, i_hi} - {0}):
                    out.append((xs[start + i], chunk[i]))
                if end - 1 - start not in (0, i_lo, i_hi):
                    out.append((xs[end - 1], chunk[-1]))
        start = end
        if start < n:
            column = int((xs[start] - x0) // step)
    return out


def _thin_any(
    xs: Sequence[float], ys: Sequence[float], x0: float, x1: float, columns: int
) -> list[tuple[float, float]]:
    out: list[tuple[float, float]] = []
    scale = columns / (x1 - x0) if x1 > x0 else 0.0
    col: int | None = None
    first = lo = hi = last = (math.nan, math.nan)

    def flush() -> None:
        extra = sorted({lo, hi} - {first}, key=lambda p: p[0])
        out.extend(extra)
        if last != first and last not in extra:
            out.append(last)

    for x, y in zip(xs, ys, strict=False):
        if not (math.isfinite(x) and math.isfinite(y)):
            if col is not None:
                flush()
                out.append((math.nan, math.nan))
            col = None
            continue
        c = int((x - x0) * scale)
        if c == col:
            if y < lo[1]:
                lo = (x, y)
            elif y > hi[1]:
                hi = (x, y)
            last = (x, y)
            continue
        if col is not None:
            flush()
        out.append((x, y))
        col = c
        first = lo = hi = last = (x, y)
    if col is not None:
        flush()
    return out


# -- braille text ------------------------------------------------------------------------------

_BITS = ((0x01, 0x08), (0x02, 0x10), (0x04, 0x20), (0x40, 0x80))  # [row][column] of a cell
_RESET = '\x1b[0m'
_SGR = re.compile('\x1b\\[[0-9;]*m')


def _sgr(colour: tuple[int, int, int]) -> str:
    return f'\x1b[38;2;{colour[0]};{colour[1]};{colour[2]}m'


def braille(chart: Chart, width: int, height: int, *, colour: bool = True) -> str:
    """The chart in `width` x `height` terminal cells: legend, plot with y ticks, x axis and
    its ticks (and the status line, if any); lines joined by newlines, ANSI colours if asked."""
    (x0, x1), (y0, y1) = ranges(chart)
    status_rows = 1 if chart.status else 0
    rows = max(height - 3 - status_rows, 2)
    y_ticks = nice_ticks(y0, y1, max(2, rows // 3))
    labels = [tick_text(v, y_ticks) for v in y_ticks]
    margin = max((len(s) for s in labels), default=1) + 1
    cols = max(width - margin - 1, 4)
    dot_w, dot_h = cols * 2, rows * 4
    cells = [[0] * cols for _ in range(rows)]
    tint: list[list[int]] = [[-1] * cols for _ in range(rows)]

    def dot(px: int, py: int, which: int) -> None:
        if 0 <= px < dot_w and 0 <= py < dot_h:
            cy, cx = py // 4, px // 2
            cells[cy][cx] |= _BITS[py % 4][px % 2]
            tint[cy][cx] = which

    def to_dot(x: float, y: float) -> tuple[int, int]:
        return (
            round((x - x0) / (x1 - x0) * (dot_w - 1)),
            round((y1 - y) / (y1 - y0) * (dot_h - 1)),
        )

    for which, ln in enumerate(chart.lines):
        prev: tuple[int, int] | None = None
        for x, y in thin(ln.xs, ln.ys, x0, x1, dot_w, ln.ordered):
            if not math.isfinite(x):
                prev = None
                continue
            here = to_dot(x, y)
            if prev is None:
                dot(*here, which)
            else:
                for px, py in _segment(prev, here, dot_w, dot_h):
                    dot(px, py, which)
            prev = here

    out: list[str] = []
    legend = []
    for ln in chart.lines:
        mark = (_sgr(ln.colour) + '━━' + _RESET) if colour else '──'
        legend.append(f'{mark} {ln.label}' + (f' {ln.note}' if ln.note else ''))
    head = (chart.title + '  ' if chart.title else '') + '   '.join(legend)
    out.append(head)
    tick_rows = {
        min(rows - 1, max(0, round((y1 - v) / (y1 - y0) * (rows - 1)))): s
        for v, s in zip(y_ticks, labels, strict=True)
    }
    for r in range(rows):
        label = tick_rows.get(r)
        prefix = (label.rjust(margin - 1) + ' ┤') if label is not None else ' ' * margin + '│'
        text = []
        current = -1
        for c in range(cols):
            bits = cells[r][c]
            ch = chr(0x2800 + bits) if bits else ' '
            if colour and bits and tint[r][c] != current:
                current = tint[r][c]
                text.append(_sgr(chart.lines[current].colour))
            elif colour and not bits and current != -1:
                current = -1
                text.append(_RESET)
            text.append(ch)
        if colour and current != -1:
            text.append(_RESET)
        out.append(prefix + ''.join(text))
    x_ticks = nice_ticks(x0, x1, max(2, cols // 12))
    axis = ['─'] * cols
    under = [' '] * (cols + margin + 12)
    for v in x_ticks:
        c = round((v - x0) / (x1 - x0) * (cols - 1))
        if 0 <= c < cols:
            axis[c] = '┬'
            s = tick_text(v, x_ticks)
            start = max(0, margin + 1 + c - len(s) // 2)
            if all(ch == ' ' for ch in under[max(0, start - 1) : start + len(s) + 1]):
                under[start : start + len(s)] = list(s)
    out.append(' ' * margin + '└' + ''.join(axis))
    label = chart.x_label
    end = min(width, len(under))
    if label and len(label) + 8 < end:
        # the axis' name at the right end, in place of the tick labels it would run into
        start = end - len(label)
        while start > 0 and under[start - 1] != ' ':
            start -= 1
        under[start - 1 : end] = [' '] * (end - start + 1)
        under[end - len(label) : end] = list(label)
    out.append(''.join(under).rstrip())
    if chart.status:
        out.append(chart.status)
    return '\n'.join(_crop(line, width, colour) for line in out)


def _crop(line: str, width: int, colour: bool) -> str:
    """`line` cut to `width` visible cells (escape sequences take none)."""
    if len(line) <= width or len(_SGR.sub('', line)) <= width:
        return line
    visible = 0
    out = []
    i = 0
    while i < len(line):
        if line[i] == '\x1b':
            j = line.index('m', i) + 1
            out.append(line[i:j])
            i = j
            continue
        if visible >= width:
            break
        out.append(line[i])
        visible += 1
        i += 1
    text = ''.join(out)
    return text + _RESET if colour and '\x1b' in text else text


def _segment(a: tuple[int, int], b: tuple[int, int], w: int, h: int) -> list[tuple[int, int]]:
    """The dots from a to b (Bresenham), clipped loosely to the canvas."""
    (x, y), (x2, y2) = a, b
    dx, dy = abs(x2 - x), -abs(y2 - y)
    if max(dx, -dy) > 4 * (w + h):  # far off the canvas: draw only the visible end
        return [b]
    sx, sy = (1 if x < x2 else -1), (1 if y < y2 else -1)
    err = dx + dy
    dots = []
    while True:
        dots.append((x, y))
        if x == x2 and y == y2:
            return dots
        e2 = 2 * err
        if e2 >= dy:
            err += dy
            x += sx
        if e2 <= dx:
            err += dx
            y += sy


# -- shapes in pixels (SVG, PNG, a tkinter canvas) ---------------------------------------------


@dataclass
class Shape:
    """One thing to paint: 'line' (points, colour, width), 'text' (at points[0], anchored
    'start' | 'middle' | 'end' horizontally and centred vertically), 'rect' (two corners,
    filled with colour, outlined with `outline`)."""

    kind: str
    points: list[tuple[float, float]]
    colour: tuple[int, int, int] = INK
    width: float = 1.0
    text: str = ''
    anchor: str = 'start'
    outline: tuple[int, int, int] | None = None


@dataclass
class Frame:
    """Where the plot area sits in a picture, for readers of a layout (tests, a window)."""

    left: float
    top: float
    right: float
    bottom: float
    shapes: list[Shape] = field(default_factory=list)


FONT = 12  # px: the text size of a picture


def layout(chart: Chart, width: int, height: int) -> Frame:
    """The chart as shapes in a `width` x `height` pixel picture: frame, grid and ticks,
    the lines (thinned to the plot's pixel columns), a legend box at the top left."""
    (x0, x1), (y0, y1) = ranges(chart)
    y_ticks = nice_ticks(y0, y1, max(2, height // 70))
    y_labels = [tick_text(v, y_ticks) for v in y_ticks]
    char_w = FONT * 0.62
    left = 14 + char_w * max((len(s) for s in y_labels), default=1)
    top = 12 + (FONT + 8 if chart.title else 0)
    right = width - 16
    bottom = height - (2.4 * FONT + 12 + (FONT + 4 if chart.x_label else 0))
    frame = Frame(left, top, right, bottom)
    shapes = frame.shapes
    shapes.append(Shape('rect', [(0, 0), (width, height)], BACKGROUND))

    def px(x: float) -> float:
        return left + (x - x0) / (x1 - x0) * (right - left)

    def py(y: float) -> float:
        return bottom - (y - y0) / (y1 - y0) * (bottom - top)

    x_ticks = nice_ticks(x0, x1, max(2, int((right - left) // 90)))
    for v in x_ticks:
        shapes.append(Shape('line', [(px(v), top), (px(v), bottom)], GRID))
    for v in y_ticks:
        shapes.append(Shape('line', [(left, py(v)), (right, py(v))], GRID))
    columns = max(int(right - left), 1)
    for ln in chart.lines:
        run: list[tuple[float, float]] = []
        for x, y in thin(ln.xs, ln.ys, x0, x1, columns, ln.ordered):
            if not math.isfinite(x):
                if len(run) > 1:
                    shapes.append(Shape('line', run, ln.colour, 2.0))
                elif run:
                    shapes.append(
                        Shape('line', [run[0], (run[0][0] + 1, run[0][1])], ln.colour, 2.0)
                    )
                run = []
                continue
            run.append((_clamp(px(x), -width, 2 * width), _clamp(py(y), -height, 2 * height)))
        if len(run) > 1:
            shapes.append(Shape('line', run, ln.colour, 2.0))
        elif run:
            shapes.append(Shape('line', [run[0], (run[0][0] + 1, run[0][1])], ln.colour, 2.0))
    # what lies outside the plot area is covered again, then the frame
    shapes += [
        Shape('rect', [(0, 0), (width, top)], BACKGROUND),
        Shape('rect', [(0, bottom + 1), (width, height)], BACKGROUND),
        Shape('rect', [(0, 0), (left, height)], BACKGROUND),
        Shape('rect', [(right + 1, 0), (width, height)], BACKGROUND),
    ]
    if chart.title:
        shapes.append(Shape('text', [(width / 2, 6 + FONT / 2)], text=chart.title, anchor='middle'))
    for v in x_ticks:
        shapes.append(Shape('line', [(px(v), bottom), (px(v), bottom + 4)], INK))
        shapes.append(
            Shape(
                'text',
                [(px(v), bottom + 6 + FONT / 2)],
                text=tick_text(v, x_ticks),
                anchor='middle',
            )
        )
    for v, s in zip(y_ticks, y_labels, strict=True):
        shapes.append(Shape('line', [(left - 4, py(v)), (left, py(v))], INK))
        shapes.append(Shape('text', [(left - 7, py(v))], text=s, anchor='end'))
    if chart.x_label:
        shapes.append(
            Shape(
                'text',
                [((left + right) / 2, height - 6 - FONT / 2)],
                text=chart.x_label,
                anchor='middle',
            )
        )
    shapes.append(
        Shape(
            'line', [(left, top), (right, top), (right, bottom), (left, bottom), (left, top)], INK
        )
    )
    if chart.lines:
        texts = [ln.label + (f'  {ln.note}' if ln.note else '') for ln in chart.lines]
        box_w = 34 + char_w * max(len(t) for t in texts)
        row = FONT + 6
        bx, by = left + 8, top + 8
        shapes.append(
            Shape(
                'rect',
                [(bx, by), (bx + box_w, by + row * len(texts) + 6)],
                BACKGROUND,
                outline=GRID,
            )
        )
        for i, (ln, t) in enumerate(zip(chart.lines, texts, strict=True)):
            y = by + 3 + row * i + row / 2
            shapes.append(Shape('line', [(bx + 6, y), (bx + 24, y)], ln.colour, 3.0))
            shapes.append(Shape('text', [(bx + 30, y)], text=t))
    return frame


def _clamp(v: float, lo: float, hi: float) -> float:
    return lo if v < lo else hi if v > hi else v


def _hex(colour: tuple[int, int, int]) -> str:
    return '#{:02x}{:02x}{:02x}'.format(*colour)


def svg(chart: Chart, width: int = 800, height: int = 480) -> str:
    """The chart as an SVG document."""
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="{FONT}">'
    ]
    for s in layout(chart, width, height).shapes:
        if s.kind == 'rect':
            (ax, ay), (bx, by) = s.points
            stroke = f' stroke="{_hex(s.outline)}"' if s.outline else ''
            out.append(
                f'<rect x="{ax:.1f}" y="{ay:.1f}" width="{bx - ax:.1f}" height="{by - ay:.1f}" '
                f'fill="{_hex(s.colour)}"{stroke}/>'
            )
        elif s.kind == 'line':
            pts = ' '.join(f'{x:.1f},{y:.1f}' for x, y in s.points)
            out.append(
                f'<polyline points="{pts}" fill="none" stroke="{_hex(s.colour)}" '
                f'stroke-width="{s.width:g}" stroke-linejoin="round"/>'
            )
        else:
            ((x, y),) = s.points
            out.append(
                f'<text x="{x:.1f}" y="{y:.1f}" text-anchor="{s.anchor}" '
                f'dominant-baseline="central" fill="{_hex(s.colour)}">{escape(s.text)}</text>'
            )
    out.append('</svg>')
    return '\n'.join(out) + '\n'


def png(chart: Chart, width: int = 800, height: int = 480) -> bytes:
    """The chart as PNG bytes, painted with Pillow (lines without smoothing, so each line's
    colour is in the picture exactly)."""
    import io

    from PIL import Image, ImageDraw, ImageFont

    image = Image.new('RGB', (width, height), BACKGROUND)
    draw = ImageDraw.Draw(image)
    try:
        font: ImageFont.ImageFont | ImageFont.FreeTypeFont = ImageFont.load_default(size=FONT)
    except TypeError:  # Pillow before 10.1: the bitmap font only
        font = ImageFont.load_default()
    anchors = {'start': 'lm', 'middle': 'mm', 'end': 'rm'}
    for s in layout(chart, width, height).shapes:
        if s.kind == 'rect':
            (ax, ay), (bx, by) = s.points
            draw.rectangle([ax, ay, bx, by], fill=s.colour, outline=s.outline)
        elif s.kind == 'line':
            draw.line(s.points, fill=s.colour, width=max(1, round(s.width)), joint='curve')
        else:
            draw.text(s.points[0], s.text, fill=s.colour, font=font, anchor=anchors[s.anchor])
    buffer = io.BytesIO()
    image.save(buffer, format='PNG')
    return buffer.getvalue()
