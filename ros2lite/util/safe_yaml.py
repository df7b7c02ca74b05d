"""Loading YAML that came from outside (command-line values, parameter and QoS files, bag
metadata) with bounded cost.

`yaml.safe_load` runs no code, but it still trusts the document's shape: a few lines of
anchors and aliases ("billion laughs") describe a value of billions of elements that costs
nothing to load and everything to walk, print or turn into a message; and a deeply nested
document exhausts the parser's recursion. :func:`load` composes the document first, measures
the value it would make with every alias expanded, and refuses it past `max_values`; deep
nesting is refused the same way. Errors are :class:`YamlInputError` with one readable line
(line and column, never a ``Mark`` object's repr).
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any

from ros2lite.exceptions import Ros2liteError

if TYPE_CHECKING:
    import yaml

__all__ = ['MAX_DEPTH', 'MAX_VALUES', 'YamlInputError', 'load', 'yaml_key', 'yaml_text']

# scalars + collections of the fully expanded value; generous for any hand-written input and
# for parameter files, far below what exhausts memory
MAX_VALUES = 1_000_000
MAX_DEPTH = 100


class YamlInputError(Ros2liteError, ValueError):
    """YAML that cannot be used: not well-formed (`syntax` is True), or too big or too deep
    once aliases are expanded."""

    def __init__(self, message: str, *, syntax: bool = False, detail: str = '') -> None:
        super().__init__(message)
        self.syntax = syntax
        self.detail = detail or message  # the problem without the `what` prefix


def _describe(e: yaml.YAMLError) -> str:
    """A YAMLError as one line: the problem and where it is."""
    problem = getattr(e, 'problem', None) or getattr(e, 'context', None)
    mark = getattr(e, 'problem_mark', None) or getattr(e, 'context_mark', None)
    text = ' '.join(str(problem).split()) if problem else ' '.join(str(e).split())
    if mark is not None:
        text += f' (line {mark.line + 1}, column {mark.column + 1})'
    return text


def _syntax(what: str, e: yaml.YAMLError) -> YamlInputError:
    why = _describe(e)
    return YamlInputError(f'{what} is not valid YAML: {why}', syntax=True, detail=why)


def _expanded_size(root: yaml.Node, limit: int, what: str) -> int:
    """How many values the composed node `root` makes with aliases expanded (stops counting
    past `limit`); raises YamlInputError when nesting goes deeper than MAX_DEPTH."""
    from yaml.nodes import MappingNode, SequenceNode

    sizes: dict[int, int] = {}
    # iterative post-order walk: (node, depth, children done?)
    stack: list[tuple[yaml.Node, int, bool]] = [(root, 1, False)]
    on_path: set[int] = set()
    while stack:
        node, depth, done = stack.pop()
        key = id(node)
        if key in sizes and not done:
            continue
        if depth > MAX_DEPTH:
            raise YamlInputError(f'{what} is nested deeper than {MAX_DEPTH} levels')
        if isinstance(node, SequenceNode):
            children = list(node.value)
        elif isinstance(node, MappingNode):
            children = [part for pair in node.value for part in pair]
        else:
            sizes[key] = 1
            continue
        if not done:
            if key in on_path:  # a recursive alias (`&a [*a]`)
                raise YamlInputError(f'{what} refers to itself through an alias')
            on_path.add(key)
            stack.append((node, depth, True))
            stack.extend((child, depth + 1, False) for child in children)
            continue
        on_path.discard(key)
        total = 1 + sum(sizes.get(id(child), 1) for child in children)
        sizes[key] = min(total, limit + 1)
    return sizes.get(id(root), 1)


def load(
    text: str,
    what: str = 'YAML',
    *,
    max_values: int = MAX_VALUES,
    loader_class: type[yaml.SafeLoader] | type[yaml.CSafeLoader] | None = None,
) -> Any:
    """The value of a YAML document, like `yaml.safe_load` (tags of Python objects are
    refused), or YamlInputError naming `what` (see the module doc). `loader_class`, a
    SafeLoader subclass, may construct values its own way (e.g. keep repeated keys), or be
    libyaml's CSafeLoader for speed; the bounds hold all the same."""
    import yaml

    try:
        # the reader checks the characters as it is made: a control character (a hostile
        # name in a frame tree) raises here, and is the same syntax error as any other
        loader = (loader_class or yaml.SafeLoader)(text)
    except yaml.YAMLError as e:
        raise _syntax(what, e) from None
    try:
        try:
            node = loader.get_single_node()
        except RecursionError:
            raise YamlInputError(f'{what} is nested too deeply') from None
        except yaml.YAMLError as e:
            raise _syntax(what, e) from None
        if node is None:
            return None
        if _expanded_size(node, max_values, what) > max_values:
            raise YamlInputError(
                f'{what} expands to more than {max_values} values through its aliases '
                '(anchors and * references); write the values out or make it smaller'
            )
        try:
            return loader.construct_document(node)
        except yaml.YAMLError as e:
            raise _syntax(what, e) from None
    finally:
        loader.dispose()


# a name written as ROS's tools write it (plain, or in single quotes as a value); any other
# name (a control character, a quote, a line break, a colon, longer than YAML's 1,024
# characters of a simple key) is written as a double-quoted YAML scalar with escapes, so one
# odd name from the wire never spoils the text for the other names
_PLAIN = re.compile(r'[A-Za-z_/][A-Za-z0-9_/.~+-]{0,999}')
_QUOTABLE = re.compile(r"[ -&(-~]{0,1000}")  # printable ASCII but the single quote
_WORDS = {'true', 'false', 'yes', 'no', 'on', 'off', 'null', 'y', 'n'}  # YAML reads otherwise


def _quoted(text: str) -> str:
    out = ['"']
    for ch in text:
        code = ord(ch)
        if ch in '"\\':
            out.append('\\' + ch)
        elif 0x20 <= code < 0x7F:
            out.append(ch)
        elif code < 0x10000:
            out.append(f'\\u{code:04x}')
        else:
            out.append(f'\\U{code:08x}')
    out.append('"')
    return ''.join(out)


def yaml_key(name: str) -> str:
    """A mapping's key line for `name` (tf2's frame YAML starts each frame so)."""
    if _PLAIN.fullmatch(name) and name.lower() not in _WORDS:
        return f'{name}: \n'
    quoted = _quoted(name)
    # an explicit key has no length limit
    return f'{quoted}: \n' if len(quoted) <= 1000 else f'? {quoted}\n: \n'


def yaml_text(value: str) -> str:
    """`value` as a YAML scalar: single-quoted as tf2 writes names, else double-quoted."""
    return f"'{value}'" if _QUOTABLE.fullmatch(value) else _quoted(value)
