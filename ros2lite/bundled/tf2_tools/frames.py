"""The frame tree as tf2 describes it (`Buffer.all_frames_as_yaml()`, the text of the
`tf2_frames` service), and the pictures made of it: view_frames' Graphviz text, and a graph
for the layout rqt_graph uses (frames as ellipses, each edge's label on the edge).

The YAML comes from another process (a node's service) or our own buffer; either way it is
read with `safe_yaml` and each entry checked, so a malformed answer is an error, not a crash.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ros2lite.bundled.rqt_graph.model import Graph
from ros2lite.bundled.terminal import visible


@dataclass(frozen=True)
class Frame:
    """One child frame and the transform to it from its parent, as tf2's YAML gives it."""

    name: str
    parent: str
    broadcaster: str
    rate: float
    buffer_length: float
    most_recent_transform: float
    oldest_transform: float

    def label(self) -> str:
        """The edge's label as view_frames and rqt_tf_tree write it (lines joined by '\\n')."""
        return '\n'.join(
            [
                f'Broadcaster: {self.broadcaster}',
                f'Average rate: {self.rate}',
                f'Buffer length: {self.buffer_length}',
                f'Most recent transform: {self.most_recent_transform}',
                f'Oldest transform: {self.oldest_transform}',
            ]
        )


_NUMBERS = ('rate', 'buffer_length', 'most_recent_transform', 'oldest_transform')


def parse(text: str, skipped: list[str] | None = None) -> tuple[Frame, ...]:
    """The frames of tf2's YAML (an empty tree is `[]` or nothing), in its order. An entry
    that is not a frame is left out, and said in `skipped` (one line each); text that is not
    YAML at all raises ValueError naming what is wrong. Raw control characters (a peer that
    writes hostile names unescaped, as tf2 does) are read as their escapes."""
    import yaml

    from ros2lite.util import safe_yaml

    # libyaml where PyYAML has it: 2,000 frames are 345 KB of YAML, 7 s for the pure-Python
    # reader on a loaded machine, 1 s for libyaml
    fast = getattr(yaml, 'CSafeLoader', None) if yaml.__with_libyaml__ else None
    try:
        data = safe_yaml.load(text, 'the frame tree', loader_class=fast)
    except ValueError:
        cleaned = _CONTROLS.sub(lambda m: f'\\x{ord(m.group()):02x}', text)
        if cleaned == text:
            raise
        data = safe_yaml.load(cleaned, 'the frame tree', loader_class=fast)
        if skipped is not None:
            skipped.append('frame names with control characters are shown escaped')
    if data is None or data == []:
        return ()
    if not isinstance(data, dict):
        raise ValueError('the frame tree is not a mapping of frames')
    frames = []
    for name, entry in data.items():
        frame = _frame(name, entry)
        if isinstance(frame, str):
            if skipped is not None:
                skipped.append(frame)
            continue
        frames.append(frame)
    return tuple(frames)


# characters YAML refuses in a document (C0 but tab and line breaks, DEL, C1 but NEL)
_CONTROLS = re.compile('[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x84\x86-\x9f]')


def _frame(name: object, entry: object) -> Frame | str:
    """The frame of one entry, or why it is left out."""
    shown = visible(str(name))[:200]
    if not isinstance(entry, dict) or not isinstance(entry.get('parent'), str):
        return f"skipped the frame tree's entry for '{shown}': it has no parent"
    # numbers are kept as the YAML typed them, so the labels print them as tf2_tools does
    numbers: dict[str, float] = {}
    for key in _NUMBERS:
        value = entry.get(key)
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            return f"skipped the frame tree's entry for '{shown}': it has no {key}"
        numbers[key] = value
    return Frame(str(name), entry['parent'], str(entry.get('broadcaster', '')), **numbers)


# names longer than this are cut in pictures (the files keep what can be shown)
_LONGEST_SHOWN = 256


def shown_name(name: str) -> str:
    """A frame name as a picture shows it: control characters escaped, cut when long."""
    text = visible(name)
    return text if len(text) <= _LONGEST_SHOWN else text[:_LONGEST_SHOWN] + '...'


def _visible_lines(text: str) -> str:
    return '\n'.join(visible(line) for line in text.split('\n'))


def _dot(name: str) -> str:
    """A name inside a Graphviz double-quoted string."""
    return shown_name(name).replace('\\', '\\\\').replace('"', '\\"')


def to_dot(frames: tuple[Frame, ...], recorded_at: float) -> str:
    """view_frames' Graphviz text, as the real tool writes it: an edge per frame labelled
    with its broadcaster, rate and times, and a legend with the time it was recorded,
    linked (invisibly) to a root of the tree."""
    if not frames:
        return 'digraph G { "No tf data received" }'
    names = {f.name for f in frames}
    out = ['digraph G {\n']
    root = ''
    for f in frames:
        label = '\\n'.join(_dot(line) for line in f.label().split('\n')) + '\\n'
        out.append(f'"{_dot(f.parent)}" -> "{_dot(f.name)}"[label=" {label}"];\n')
        if f.parent not in names:
            root = _dot(f.parent)
    out.append('edge [style=invis];\n')
    out.append(' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n')
    out.append(f'"Recorded at time: {recorded_at}"[ shape=plaintext ] ;\n')
    out.append(f'}}->"{root}";\n}}')
    return ''.join(out)


def note_name(frame: Frame) -> str:
    """The name of the vertex holding the label of the edge into `frame` (unique, as each
    frame has one parent)."""
    return f'\0edge to {frame.name}'


def to_graph(frames: tuple[Frame, ...]) -> Graph:
    """The tree for rqt_graph's layout, top down: a frame per vertex (named as shown: control
    characters escaped), and on each edge from parent to child a note with the edge's label."""
    names = sorted({shown_name(f.name) for f in frames} | {shown_name(f.parent) for f in frames})
    notes = tuple(note_name(f) for f in frames)
    edges = []
    for f in frames:
        edges += [(shown_name(f.parent), note_name(f)), (note_name(f), shown_name(f.name))]
    labels = tuple((note_name(f), _visible_lines(f.label())) for f in frames)
    return Graph(tuple(names), (), tuple(edges), notes=notes, labels=labels, top_down=True)
