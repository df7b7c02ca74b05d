"""The frame tree as tf2 describes it (`Buffer.all_frames_as_yaml()`, the text of the
`tf2_frames` service), and the pictures made of it: view_frames' Graphviz text, and a graph
for the layout rqt_graph uses (frames as ellipses, each edge's label on the edge).

The YAML comes from another process (a node's service) or our own buffer; either way it is
read with `safe_yaml` and each entry checked, so a malformed answer is an error, not a crash.
"""

from __future__ import annotations

from dataclasses import dataclass

from ros2lite.bundled.rqt_graph.model import Graph


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


def parse(text: str) -> tuple[Frame, ...]:
    """The frames of tf2's YAML (an empty tree is `[]` or nothing), in its order; raises
    ValueError naming what is wrong."""
    from ros2lite.util import safe_yaml

    data = safe_yaml.load(text, 'the frame tree')
    if data is None or data == []:
        return ()
    if not isinstance(data, dict):
        raise ValueError('the frame tree is not a mapping of frames')
    frames = []
    for name, entry in data.items():
        if not isinstance(entry, dict) or not isinstance(entry.get('parent'), str):
            raise ValueError(f"the frame tree's entry for {name!r} has no parent")
        # numbers are kept as the YAML typed them, so the labels print them as tf2_tools does
        numbers: dict[str, float] = {}
        for key in _NUMBERS:
            value = entry.get(key)
            if not isinstance(value, (int, float)) or isinstance(value, bool):
                raise ValueError(f"the frame tree's entry for {name!r} has no {key}")
            numbers[key] = value
        frames.append(
            Frame(str(name), entry['parent'], str(entry.get('broadcaster', '')), **numbers)
        )
    return tuple(frames)


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
        label = f.label().replace('\n', '\\n') + '\\n'
        out.append(f'"{f.parent}" -> "{f.name}"[label=" {label}"];\n')
        if f.parent not in names:
            root = f.parent
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
    """The tree for rqt_graph's layout, top down: a frame per vertex, and on each edge from
    parent to child a note with the edge's label."""
    names = sorted({f.name for f in frames} | {f.parent for f in frames})
    notes = tuple(note_name(f) for f in frames)
    edges = []
    for f in frames:
        edges += [(f.parent, note_name(f)), (note_name(f), f.name)]
    labels = tuple((note_name(f), f.label()) for f in frames)
    return Graph(tuple(names), (), tuple(edges), notes=notes, labels=labels, top_down=True)
