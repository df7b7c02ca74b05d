"""The frame tree as a one-page PDF, drawn with fpdf2 on the layout rqt_graph uses (grandalf,
top down): frames in ellipses, each edge's label beside it, and view_frames' legend box with
the time it was recorded. No Graphviz needed."""

from __future__ import annotations

from ros2lite.bundled.rqt_graph.layout import layout
from ros2lite.bundled.tf2_tools.frames import Frame, to_graph

FONT = ('helvetica', '', 10.0)  # a PDF core font: nothing to embed
LINE = 12.0  # pt between lines of a label
MARGIN = 24.0
LEGEND = ('view_frames Result', 'Recorded at time: {}')
FRAME_COLOUR = (0x1F, 0x4E, 0x79)


def _latin1(text: str) -> str:
    """What a core font can show (frame names are ASCII in practice; anything else becomes
    '?' rather than failing the whole file)."""
    return text.encode('latin-1', 'replace').decode('latin-1')


def to_pdf(frames: tuple[Frame, ...], recorded_at: float) -> bytes:
    """The PDF's bytes."""
    from fpdf import FPDF

    measure = FPDF(unit='pt')
    measure.set_font(*FONT)
    # a core font's width is the sum of its characters' (no kerning): measured once per
    # character, as fpdf's own measure costs a third of a millisecond a call
    glyphs: dict[str, float] = {}

    def line_width(line: str) -> float:
        total = 0.0
        for ch in line:
            w = glyphs.get(ch)
            if w is None:
                w = glyphs[ch] = measure.get_string_width(ch)
            total += w
        return total

    def width(text: str) -> float:
        return max(line_width(_latin1(line)) for line in text.split('\n'))

    graph = to_graph(frames)
    notes = set(graph.notes)

    sizes: dict[str, tuple[float, float]] = {}

    def size(name: str, _topic: bool) -> tuple[float, float]:
        known = sizes.get(name)
        if known is None:
            known = sizes[name] = measured(name)
        return known

    def measured(name: str) -> tuple[float, float]:
        text = graph.text(name)
        lines = text.count('\n') + 1
        if name in notes:
            return (width(text) + 8, lines * LINE + 4)
        return (width(text) * 1.3 + 24, 30.0)

    legend = [LEGEND[0], LEGEND[1].format(recorded_at)] if frames else ['No tf data received']
    legend_w = max(width(text) for text in legend) + 24
    legend_h = len(legend) * LINE + 16
    lay = layout(graph, size, layer_gap=28, node_gap=24, margin=MARGIN)
    top = MARGIN + legend_h + 16  # the tree starts below the legend
    page_w = max(lay.width, legend_w + 2 * MARGIN)
    page_h = lay.height + top - MARGIN

    pdf = FPDF(unit='pt', format=(page_w, page_h))
    pdf.set_auto_page_break(False)
    pdf.set_margin(0)
    pdf.add_page()
    pdf.set_title('view_frames Result')
    pdf.set_creator('ros2lite view_frames')
    pdf.set_font(*FONT)

    def text_lines(x: float, y: float, text: str) -> None:
        lines = text.split('\n')
        first = y - (len(lines) - 1) * LINE / 2
        for i, line in enumerate(lines):
            line = _latin1(line)
            pdf.text(x - line_width(line) / 2, first + i * LINE + 3.5, line)

    # the legend, as view_frames' bold cluster box
    pdf.set_line_width(2)
    pdf.rect((page_w - legend_w) / 2, MARGIN, legend_w, legend_h)
    pdf.set_line_width(0.8)
    text_lines(page_w / 2, MARGIN + legend_h / 2, '\n'.join(legend))
    dy = top - MARGIN
    for _, target, points in lay.edges:
        path = [(x, y + dy) for x, y in points]
        box = lay.boxes[target]
        if not box.is_note:  # end on the ellipse's top, with an arrowhead
            end = (box.x, box.y + dy - box.h / 2)
            path[-1] = end
            pdf.set_fill_color(0, 0, 0)
            pdf.polygon([end, (end[0] - 4, end[1] - 9), (end[0] + 4, end[1] - 9)], style='F')
            path[-1] = (end[0], end[1] - 8)
        pdf.polyline(path)
    for box in lay.boxes.values():
        x, y = box.x, box.y + dy
        if box.is_note:
            text_lines(x, y, graph.text(box.name))
            continue
        pdf.set_draw_color(*FRAME_COLOUR)
        pdf.set_fill_color(255, 255, 255)
        pdf.ellipse(x - box.w / 2, y - box.h / 2, box.w, box.h, style='DF')
        pdf.set_draw_color(0, 0, 0)
        text_lines(x, y, box.name)
    return bytes(pdf.output())
