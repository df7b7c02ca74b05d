"""House rules a machine can check: lint, types, and the library/CLI boundary."""

from __future__ import annotations

import ast
import importlib
import importlib.util
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_clean() -> None:
    proc = subprocess.run(
        [sys.executable, '-m', 'ruff', 'check', 'ros2lite', 'tests', 'benchmarks'],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_ruff_format_clean() -> None:
    proc = subprocess.run(
        [sys.executable, '-m', 'ruff', 'format', '--check', 'ros2lite', 'tests', 'benchmarks'],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_mypy_clean() -> None:
    proc = subprocess.run([sys.executable, '-m', 'mypy'], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr


# private names that the standard library documents as public API
_STDLIB_UNDERSCORE_API = {('sys', '_getframe'), ('os', '_exit')}


def _declared_private(cls: ast.ClassDef) -> set[str]:
    """The `_names` a class body declares: methods, class attributes, `self._x = …`."""
    names = set()
    for stmt in cls.body:  # class attributes
        targets = stmt.targets if isinstance(stmt, ast.Assign) else []
        if isinstance(stmt, ast.AnnAssign):
            targets = [stmt.target]
        names.update(t.id for t in targets if isinstance(t, ast.Name))
    for node in ast.walk(cls):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            names.add(node.name)
        elif (
            isinstance(node, ast.Attribute)
            and isinstance(node.ctx, ast.Store)
            and isinstance(node.value, ast.Name)
            and node.value.id == 'self'
        ):
            names.add(node.attr)
    return {n for n in names if n.startswith('_')}


def _others_private_reads(tree: ast.AST) -> list[ast.Attribute]:
    """`x._name` reads that reach into another object's insides. Not counted: the object
    itself (`self`, `cls`, `super()`); a name the enclosing class declares itself, read on
    another instance of its kind (`__eq__`, ordering, `Duration + Duration`: privacy is the
    class's, not the instance's); dunders; and the few underscore names the standard library
    documents as public (`sys._getframe`, `os._exit`). A helper or a second class reading a
    class's `_x`, even in the same module, counts: it goes through a public name instead."""
    found = []

    def visit(node: ast.AST, own: frozenset[str]) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.ClassDef):
                visit(child, frozenset(_declared_private(child)))
                continue
            if (
                isinstance(child, ast.Attribute)
                and isinstance(child.ctx, ast.Load)
                and _is_others_private(child, own)
            ):
                found.append(child)
            visit(child, own)

    visit(tree, frozenset())
    return found


def _is_others_private(node: ast.Attribute, own: frozenset[str]) -> bool:
    name = node.attr
    if not name.startswith('_') or (name.startswith('__') and name.endswith('__')):
        return False
    owner = node.value
    if isinstance(owner, ast.Name) and (
        owner.id in ('self', 'cls') or (owner.id, name) in _STDLIB_UNDERSCORE_API
    ):
        return False
    func = owner.func if isinstance(owner, ast.Call) else None
    is_super = isinstance(func, ast.Name) and func.id == 'super'
    return not is_super and name not in own


# reads of other objects' private attributes in ros2lite/: may only fall (lower it when it does)
# What is left, each for a reason: NodeWork's `_scheduled` flag on entities (scheduling.py's
# own state, read per sample on receive threads; test_scheduling_state keeps it there); the
# executor's reads of an entity's `_node` (per dispatch on the hot path; a public `node` would
# clash with user Waitables' own attributes); `_TYPE_NAME`, the name every generated message
# class carries (rosidl's `_TYPE_SUPPORT` habit).
PRIVATE_REACH_CEILING = 10


def test_private_reach() -> None:
    """Objects talk through public names: every `other._private` read couples two modules'
    insides (the scheduling seam's shutdown races lived in such reads)."""
    per_file = {}
    for p in sorted((ROOT / 'ros2lite').rglob('*.py')):
        reads = _others_private_reads(ast.parse(p.read_text()))
        if reads:
            per_file[str(p.relative_to(ROOT))] = len(reads)
    total = sum(per_file.values())
    worst = sorted(per_file.items(), key=lambda kv: -kv[1])[:10]
    assert total <= PRIVATE_REACH_CEILING, f'{total} private reads of other objects: {worst}'
    probe = (
        'def f(self, other):\n    return self._a, other._b, super()._c, other.__len__, cls._d\n'
        'class A:\n    _x = 1\n    def __eq__(self, o):\n        return o._x == self._x and o._y\n'
    )
    assert [n.attr for n in _others_private_reads(ast.parse(probe))] == ['_b', '_y']


def _any_in_annotations(tree: ast.AST) -> int:
    """How many times `Any` (or `typing.Any`) is named in the annotations of a module: its
    functions' parameters and returns, and annotated assignments."""
    annotations: list[ast.expr | None] = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            args = node.args
            every = [*args.posonlyargs, *args.args, *args.kwonlyargs, args.vararg, args.kwarg]
            annotations += [a.annotation for a in every if a is not None]
            annotations.append(node.returns)
        elif isinstance(node, ast.AnnAssign):
            annotations.append(node.annotation)
    return sum(
        1
        for annotation in annotations
        if annotation is not None
        for part in ast.walk(annotation)
        if (isinstance(part, ast.Name) and part.id == 'Any')
        or (isinstance(part, ast.Attribute) and part.attr == 'Any')
    )


# `Any` in ros2lite/'s annotations: may only fall (lower it when it does). What is left is
# mostly where the type is the data's (a message by name, YAML, a parameter's value) or
# forwarded keywords.
ANY_CEILING = 98


def test_any_in_annotations() -> None:
    """A type written as Any checks nothing: where the type is known it is written."""
    total = sum(
        _any_in_annotations(ast.parse(p.read_text())) for p in (ROOT / 'ros2lite').rglob('*.py')
    )
    assert total <= ANY_CEILING, f'{total} Any in annotations (ceiling {ANY_CEILING})'
    probe = (
        'def f(a: Any, *b: int, **c: typing.Any) -> dict[str, Any]:\n'
        '    x: list[Any] = []\n    y = cast(Any, a)\n'
    )
    assert _any_in_annotations(ast.parse(probe)) == 4


# a room a newcomer reads whole: at most 600 lines; rclpy's node and qos modules, which carry
# rclpy's whole API, 700
SIZE_LIMIT = 600
SIZE_LIMITS = {'ros2lite/node.py': 700, 'ros2lite/qos.py': 700}
# modules over their limit while a branch at work splits them; may only shrink
SIZE_LEFT: dict[str, str] = {}


def _oversized(sizes: dict[str, int]) -> list[str]:
    return sorted(p for p, n in sizes.items() if n > SIZE_LIMITS.get(p, SIZE_LIMIT))


def test_module_sizes() -> None:
    """No room grows past what one reading holds; one that has to is split into rooms."""
    sizes = {
        str(p.relative_to(ROOT)): len(p.read_text().splitlines())
        for p in (ROOT / 'ros2lite').rglob('*.py')
    }
    over = _oversized(sizes)
    assert [p for p in over if p not in SIZE_LEFT] == [], sizes
    assert [p for p in SIZE_LEFT if p not in over] == [], 'split: out of SIZE_LEFT'
    probe = {'ros2lite/a.py': 601, 'ros2lite/node.py': 700, 'ros2lite/qos.py': 701}
    assert _oversized(probe) == ['ros2lite/a.py', 'ros2lite/qos.py']


def _scheduling_breaks(sources: dict[str, str], slots: set[str]) -> list[str]:
    """Touches of a NodeWork's `slots` (but its own) or of the banned flags outside
    runtime/scheduling.py."""
    banned = {'_scheduled', '_unqueued_work', '_last_executor'}
    offenders = []
    for path, text in sources.items():
        if path == 'ros2lite/runtime/scheduling.py':
            continue
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Attribute):
                name = node.attr
                mine = isinstance(node.value, ast.Name) and node.value.id in ('self', 'cls')
                if name in banned or (name in slots and not mine):
                    offenders.append(f'{path}:{node.lineno} .{name}')
            elif isinstance(node, ast.Name) and node.id in banned:
                offenders.append(f'{path}:{node.lineno} {node.id}')
    return offenders


def test_scheduling_state() -> None:
    """Only ros2lite/runtime/scheduling.py touches a NodeWork's slots or an entity's
    `_scheduled` flag (the old node fields `_unqueued_work`/`_last_executor` stay gone), so
    which executor runs a node's work is decided in one place."""
    from ros2lite.runtime.scheduling import NodeWork

    slots = set(NodeWork.__slots__)
    files = sorted([*(ROOT / 'ros2lite').rglob('*.py'), *(ROOT / 'tests').rglob('*.py')])
    sources = {str(p.relative_to(ROOT)): p.read_text() for p in files}
    assert _scheduling_breaks(sources, slots) == []
    probe = {
        'ros2lite/runtime/scheduling.py': 'entity._scheduled = True\n',
        'ros2lite/node.py': 'def f(self, work):\n    work._queue.clear()\n    self._queue = 1\n',
        'tests/test_node.py': '_last_executor = None\n',
    }
    assert _scheduling_breaks(probe, {'_queue'}) == [
        'ros2lite/node.py:2 ._queue',
        'tests/test_node.py:1 _last_executor',
    ]


# The map is docs/DESIGN.md §2 itself: its code block (the rooms), its floors line and its list
# of planned rooms. The grammar is written in §2, above the block.
DESIGN = ROOT / 'docs' / 'DESIGN.md'


def _section_2(text: str) -> str:
    return text[text.index('\n## 2.') : text.index('\n## 3.')]


def _strip_notes(text: str) -> str:
    """The map's text without its notes in parentheses (nested ones too)."""
    out, depth = [], 0
    for ch in text:
        depth += (ch == '(') - (ch == ')')
        if depth == 0 and ch != ')':
            out.append(ch)
    return ''.join(out)


def _expand(names: str) -> list[str]:
    """'a_{x,y} b' -> ['a_x', 'a_y', 'b'] (the map's brace shorthand)."""
    out = []
    for word in names.split():
        m = re.fullmatch(r'(.*)\{(.*)\}(.*)', word)
        out += [m[1] + alt + m[3] for alt in m[2].split(',')] if m else [word]
    return out


def _read_map(section: str) -> dict[str, list[str]]:
    """§2's block as {folder under ros2lite/ ('' itself): the names it lists}; a name `x/`
    is a subfolder (its own entry), any other name a module (`x` or `a/x.launch.py`)."""
    block = re.search(r'```\n(.*?)```', section, re.S)
    assert block and block[1].startswith('ros2lite/\n'), '§2 has no ros2lite/ block'
    texts = {'': ''}
    current = ''
    for line in block[1].splitlines()[1:]:
        if not line.startswith(' '):
            break  # tests/, docs/: outside ros2lite/
        first = line.split()[0]
        depth = len(line) - len(line.lstrip())
        if depth == 2 and first.endswith('/'):
            current = first.rstrip('/')
            texts[current] = line.strip()[len(first) :]
            continue
        current = '' if depth == 2 else current
        texts[current] += ' ' + line.strip()
    folders: dict[str, list[str]] = {}
    for top, text in texts.items():
        folders.setdefault(top, [])
        stack = [top]
        words = ' '.join(part.rpartition(':')[2] for part in _strip_notes(text).split('·'))
        tokens = re.findall(r'\[|\]|[^\s\[\]]+', words)
        for i, token in enumerate(tokens):
            if token == ']':
                stack.pop()
            elif token != '[':
                for name in _expand(token):
                    folders[stack[-1]].append(name)
                    if name.endswith('/'):
                        sub = f'{stack[-1]}/{name[:-1]}'.lstrip('/')
                        folders.setdefault(sub, [])
                        if tokens[i + 1 : i + 2] == ['[']:
                            stack.append(sub)
    return folders


def _read_planned(section: str) -> list[str]:
    """The planned rooms: every name in backticks in the list under **Planned rooms**."""
    part = section[section.index('**Planned rooms**') : section.index('**Rules of the house**')]
    return [name for code in re.findall(r'`([^`]+)`', part) for name in _expand(code)]


def _read_floors(section: str) -> dict[int, list[str]]:
    """The floors line of test_floors' rule: `N `names`` pairs."""
    rule = section[section.index('- `test_floors`') :]
    rule = rule[: rule.index('\n- ')]
    floors: dict[int, list[str]] = {}
    for floor, codes in re.findall(r'(?<!\S)(\d) ((?:`[^`]+`\s*)+)', rule):
        floors[int(floor)] = [n for code in re.findall(r'`([^`]+)`', codes) for n in code.split()]
    return floors


def _mapped(folders: dict[str, list[str]], commands: dict[str, list[str]]) -> set[str]:
    """Every path the map names, relative to ros2lite/ (a package by its __init__.py);
    `commands` gives the modules named by rule: a cli command's verbs, a bundled package's
    executables. compat/ and its faces are plain directories."""
    paths = set()
    for folder, names in folders.items():
        prefix = f'{folder}/' if folder else ''
        if folder and not folder.startswith('compat'):
            paths.add(f'{prefix}__init__.py')
        for name in [*names, *commands.get(folder, [])]:
            if not name.endswith('/'):
                paths.add(prefix + (name if name.endswith('.py') else f'{name}.py'))
    return paths


def _by_rule(folders: dict[str, list[str]]) -> dict[str, list[str]]:
    """What the map names by rule: each cli command's VERBS, each bundled package's
    executables as pkg/bundled.py lists them."""
    from ros2lite.pkg.bundled import BUNDLED, STAND_INS

    out: dict[str, list[str]] = {}
    for folder in folders:
        kind, _, name = folder.partition('/')
        if kind == 'cli' and name and '/' not in name:
            out[folder] = list(importlib.import_module(f'ros2lite.cli.{name}').VERBS)
        elif kind == 'bundled' and name and '/' not in name:
            out[folder] = [*BUNDLED.get(name, {}), *STAND_INS.get(name, {})]
    return out


def _map_breaks(
    on_disk: set[str], folders: dict[str, list[str]], commands: dict[str, list[str]],
    planned: list[str],
) -> tuple[list[str], list[str], list[str]]:  # fmt: skip
    """Modules off the map, map names missing, and planned rooms that exist (paths under
    ros2lite/)."""
    mapped = _mapped(folders, commands)
    faces = tuple(f'{f}/' for f in folders if f.startswith('compat/'))
    unmapped = sorted(p for p in on_disk - mapped if not p.startswith(faces))
    missing = sorted(mapped - on_disk)
    built = sorted(
        name
        for name in planned
        if {f'{name}__init__.py', f'{name}.py'} & on_disk
        or any(p.startswith(name) for p in on_disk if name.endswith('/'))
    )
    return unmapped, missing, built


def test_every_module_is_on_the_map() -> None:
    """Each module under ros2lite/ is where docs/DESIGN.md §2 puts it, each module the map
    names exists, and no planned room is built yet: a new module goes where the map says, and
    a module that moves takes the map with it, in the same commit."""
    package = ROOT / 'ros2lite'
    on_disk = {str(p.relative_to(package)) for p in package.rglob('*.py')}
    on_disk = {p for p in on_disk if not p.startswith('msgs/') or p == 'msgs/__init__.py'}
    section = _section_2(DESIGN.read_text())
    folders = _read_map(section)
    unmapped, missing, built = _map_breaks(
        on_disk, folders, _by_rule(folders), _read_planned(section)
    )
    assert unmapped == [], 'modules the map does not name: place them in docs/DESIGN.md §2'
    assert missing == [], 'names of the map that are not on disk'
    assert built == [], 'planned rooms that exist: move them into the block'
    probe = (
        '\n## 2. x\n```\nros2lite/\n  __init__ · face: node (a note: gone) stray\n'
        '  bag/       writer · storage/[mcap/[read]] (protocols)\n'
        '  cli/       main · commands: topic/[common]\n'
        '  compat/    faces: rclpy/\n'
        'tests/ x\n```\n**Planned rooms**: `urdf/` `sim/`\n**Rules of the house**\n## 3.\n'
    )
    folders = _read_map(probe)
    assert folders == {
        '': ['__init__', 'node', 'stray'],
        'bag': ['writer', 'storage/'],
        'bag/storage': ['mcap/'],
        'bag/storage/mcap': ['read'],
        'cli': ['main', 'topic/'],
        'cli/topic': ['common'],
        'compat': ['rclpy/'],
        'compat/rclpy': [],
    }
    probe_disk = {
        '__init__.py', 'node.py', 'late.py', 'bag/__init__.py', 'bag/writer.py',
        'bag/storage/__init__.py', 'bag/storage/mcap/__init__.py', 'bag/storage/mcap/read.py',
        'cli/__init__.py', 'cli/main.py', 'cli/topic/__init__.py', 'cli/topic/common.py',
        'cli/topic/echo.py', 'compat/rclpy/anything.py', 'sim/__init__.py',
    }  # fmt: skip
    by_rule = {'cli/topic': ['echo', 'hz']}
    assert _map_breaks(probe_disk, folders, by_rule, _read_planned(probe)) == (
        ['late.py', 'sim/__init__.py'],
        ['cli/topic/hz.py', 'stray.py'],
        ['sim/'],
    )


def _mirror_breaks(tests: set[str], modules: set[str]) -> list[str]:
    """Test files `<path>/test_<m>.py` (under tests/) where `<m>` names a module of ros2lite/
    (`modules`: paths under ros2lite/) but none at `<path>/<m>.py`, `<path>/<m>/` or `<path>`
    itself (a package's tests in its own folder)."""
    names = {
        (
            p.rpartition('/')[0].rpartition('/')[2] if p.endswith('/__init__.py') else p[:-3]
        ).rpartition('/')[2]
        for p in modules
    }
    breaks = []
    for test in sorted(tests):
        folder, _, file = test.rpartition('/')
        m = file.removeprefix('test_').removesuffix('.py')
        here = f'{folder}/' if folder else ''
        homes = {f'{here}{m}.py', f'{here}{m}/__init__.py'}
        if folder.rpartition('/')[2] == m:
            homes.add(f'{folder}/__init__.py')
        if m in names and not homes & modules:
            breaks.append(test)
    return breaks


def test_tests_mirror() -> None:
    """tests/ mirrors ros2lite/: a test file named for a module sits where that module does,
    so a module's tests are found by its path, and a module that moves takes them along."""
    package, tests = ROOT / 'ros2lite', ROOT / 'tests'
    modules = {str(p.relative_to(package)) for p in package.rglob('*.py')}
    modules = {p for p in modules if not p.startswith('msgs/') or p == 'msgs/__init__.py'}
    found = {str(p.relative_to(tests)) for p in tests.rglob('test_*.py')}
    assert _mirror_breaks(found, modules) == []
    probe_tests = {
        'test_node.py', 'runtime/test_node.py', 'test_keys.py', 'cli/topic/test_topic.py',
        'bag/test_storage.py', 'test_anything_else.py',
    }  # fmt: skip
    probe_modules = {
        'node.py',
        'transport/keys.py',
        'cli/topic/__init__.py',
        'bag/storage/__init__.py',
    }
    assert _mirror_breaks(probe_tests, probe_modules) == ['runtime/test_node.py', 'test_keys.py']


def _is_private(name: str) -> bool:
    return name.startswith('_') and not (name.startswith('__') and name.endswith('__'))


def _package_of(module: str) -> str:
    """What counts as one package for privacy: a distribution (`click`), or one room of
    ros2lite, its first folder (`ros2lite.cli`); a top-level module is a room of its own."""
    parts = module.split('.')
    return '.'.join(parts[:2]) if parts[0] == 'ros2lite' else parts[0]


def _private_imports(sources: dict[str, str]) -> list[str]:
    """Where a module takes another package's private names: `from pkg import _name`,
    a private module of it (`click._utils`, `from .._x import y` out of the room), or
    `mod._name` on a module of another package bound by an import. `if TYPE_CHECKING:`
    imports, `__future__`, dunders and the standard library's documented few are let be."""
    modules = {_module_of(p) for p in sources}
    found = []
    for path, text in sources.items():
        me = _module_of(path)
        package = me if path.endswith('__init__.py') else me.rpartition('.')[0]
        bound: dict[str, str] = {}  # a name bound to a module of another package -> module
        for node, _lazy, typing in _import_statements(ast.parse(text)):
            if typing:
                continue
            if isinstance(node, ast.Import):
                for alias in node.names:
                    target = alias.name if alias.asname else alias.name.split('.')[0]
                    bound[alias.asname or target] = target
                    pairs = [(alias.name, '')]
            else:
                base = package.rsplit('.', node.level - 1)[0] if node.level > 1 else package
                target = (f'{base}.{node.module}' if node.module else base) if node.level else ''
                target = target or node.module or ''
                if target == '__future__':
                    continue
                pairs = [(target, alias.name) for alias in node.names]
                for alias in node.names:
                    sub = f'{target}.{alias.name}'
                    if sub in modules or (not sub.startswith('ros2lite.') and _is_module(sub)):
                        bound[alias.asname or alias.name] = sub
            for target, name in pairs:
                parts = [*target.split('.'), *([name] if name else [])]
                foreign = _package_of(target) != _package_of(me)
                allowed = (parts[0], parts[-1]) in _STDLIB_UNDERSCORE_API
                if foreign and not allowed and any(_is_private(x) for x in parts):
                    found.append(f'{path}:{node.lineno} {".".join(parts)}')
        for node in ast.walk(ast.parse(text)):
            if (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and node.value.id in bound
                and _is_private(node.attr)
                and _package_of(bound[node.value.id]) != _package_of(me)
                and (bound[node.value.id].split('.')[0], node.attr) not in _STDLIB_UNDERSCORE_API
            ):
                found.append(f'{path}:{node.lineno} {bound[node.value.id]}.{node.attr}')
    return sorted(found)


def _is_module(name: str) -> bool:
    """Whether `name` (outside ros2lite) names a module, so `from pkg import name` binds one."""
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False


# each of these takes another package's private name; they may only go (remove the line
# when one does). The first two are rooms' private helpers used across rooms; the last is
# cryptography's only way to check an S/MIME signature (see security/pki.py).
PRIVATE_IMPORTS_LEFT = {
    'ros2lite/compat/rclpy/qos_overriding_options.py '
    'ros2lite.qos_overriding_options._declare_qos_parameters',
    'ros2lite/compat/rclpy/qos_overriding_options.py '
    'ros2lite.qos_overriding_options._get_qos_policy_parameter',
    'ros2lite/security/pki.py cryptography.hazmat.bindings._rust.test_support',
}


def test_no_private_imports() -> None:
    """A package's `_names` are its own to change: no module imports another's (click's
    private parser, which click 9 deletes, was the case in point)."""
    found = {re.sub(r':\d+ ', ' ', f): f for f in _private_imports(_sources())}
    new = sorted(line for key, line in found.items() if key not in PRIVATE_IMPORTS_LEFT)
    assert new == [], f'private names of another package: {new}'
    gone = sorted(PRIVATE_IMPORTS_LEFT - set(found))
    assert gone == [], f'no longer there, remove from PRIVATE_IMPORTS_LEFT: {gone}'
    probe = {
        'ros2lite/cli/parsing.py': 'from __future__ import annotations\n'
        'from click.parser import _Option, OptionParser\nimport click\nimport zenoh as z\n'
        'from click import shell_completion\nimport os, sys\n'
        'x = click._utils.UNSET, z._hidden, shell_completion._resolve_context, click.__all__\n'
        'y = sys._getframe, os._exit, click.echo\n',
        'ros2lite/bag/storage/mcap/read.py': 'from .scan import _scan\n'
        'from ros2lite.qos import _Policy\nfrom .._x import y\n',
        'ros2lite/cli/topic/echo.py': 'from ..common import _helper\n'
        'from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from _typeshed import T\n',
    }
    assert _private_imports(probe) == [
        'ros2lite/bag/storage/mcap/read.py:2 ros2lite.qos._Policy',
        'ros2lite/cli/parsing.py:2 click.parser._Option',
        'ros2lite/cli/parsing.py:7 click._utils',
        'ros2lite/cli/parsing.py:7 click.shell_completion._resolve_context',
        'ros2lite/cli/parsing.py:7 zenoh._hidden',
    ]


# --- imports: floors, laziness, circles (DESIGN.md §2, rules of the house) -------------------
# Every checker below takes the sources as {path relative to the repo: text}, so each rule's
# test also feeds it a small probe that breaks the rule and asserts the probe is caught.


@dataclass(frozen=True)
class _Import:
    """One imported module: `source` imports `target` (fully resolved, dotted) at `line`;
    `lazy` when the import sits inside a function, `typing` under `if TYPE_CHECKING:`."""

    source: str
    target: str
    line: int
    lazy: bool
    typing: bool = False


def _sources() -> dict[str, str]:
    return {
        str(p.relative_to(ROOT)): p.read_text() for p in sorted((ROOT / 'ros2lite').rglob('*.py'))
    }


def _module_of(path: str) -> str:
    parts = path.removesuffix('.py').split('/')
    return '.'.join(parts[:-1] if parts[-1] == '__init__' else parts)


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == 'TYPE_CHECKING') or (
        isinstance(test, ast.Attribute) and test.attr == 'TYPE_CHECKING'
    )


def _import_statements(
    tree: ast.AST,
) -> list[tuple[ast.Import | ast.ImportFrom, bool, bool]]:
    """Every import statement with whether it sits in a function and whether it sits in an
    `if TYPE_CHECKING:` body (its `else:` runs, so is not)."""
    found: list[tuple[ast.Import | ast.ImportFrom, bool, bool]] = []
    functions = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)

    def visit(node: ast.AST, lazy: bool, typing: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child.test):
                for stmt in child.body:
                    visit_one(stmt, lazy, True)
                for stmt in child.orelse:
                    visit_one(stmt, lazy, typing)
            else:
                visit_one(child, lazy, typing)

    def visit_one(node: ast.AST, lazy: bool, typing: bool) -> None:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append((node, lazy, typing))
        visit(node, lazy or isinstance(node, functions), typing)

    visit(tree, False, False)
    return found


def _imports(sources: dict[str, str]) -> list[_Import]:
    """Every import of every module, relative ones resolved; `from pkg import mod` names the
    module, `from mod import name` the module; compat/'s faces (`rclpy`, `launch`...) are
    resolved to ros2lite.compat.<face> when a compat module imports them."""
    modules = {_module_of(p) for p in sources}
    faces = {m.split('.')[2] for m in modules if m.startswith('ros2lite.compat.')}

    def known(name: str) -> str:
        while name and name not in modules:
            name = name.rpartition('.')[0]
        return name

    out = []
    for path, text in sources.items():
        me = _module_of(path)
        package = me if path.endswith('__init__.py') else me.rpartition('.')[0]
        in_compat = me.startswith('ros2lite.compat.')
        for node, lazy, typing in _import_statements(ast.parse(text)):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            else:
                base = package.rsplit('.', node.level - 1)[0] if node.level > 1 else package
                mod = (f'{base}.{node.module}' if node.module else base) if node.level else ''
                mod = mod or node.module or ''
                names = [
                    f'{mod}.{a.name}' if known(f'{mod}.{a.name}') == f'{mod}.{a.name}' else mod
                    for a in node.names
                ]
            for name in names:
                if in_compat and name.split('.')[0] in faces:
                    name = f'ros2lite.compat.{name}'
                if name.split('.')[0] == 'ros2lite':
                    name = known(name) or name
                out.append(_Import(me, name, node.lineno, lazy, typing))
    return out


# docs/DESIGN.md §2's floors; a top-level module not named is on 4, a folder not named on 7
FLOORS = _read_floors(_section_2(DESIGN.read_text()))
_FLOOR_OF = {n.rstrip('/'): floor for floor, names in FLOORS.items() for n in names}


def _existing(package: Path) -> set[Path]:
    """The modules and folders directly under ros2lite/."""
    return {*package.glob('*.py'), *(d for d in package.iterdir() if d.is_dir())}


def _floor(module: str) -> int:
    """A ros2lite module's floor (the package itself, its lazy face, is a top-level module)."""
    parts = module.split('.')
    if len(parts) == 1:
        return 4
    if parts[1] in _FLOOR_OF:
        return _FLOOR_OF[parts[1]]
    return 4 if len(parts) == 2 else 7


def _floor_breaks(sources: dict[str, str]) -> list[str]:
    """Imports going up a floor, and transport/ and security/ importing each other."""
    breaks = []
    for imp in _imports(sources):
        if not imp.target.startswith('ros2lite'):
            continue
        pair = {[*m.split('.'), ''][1] for m in (imp.source, imp.target)}
        up = _floor(imp.target) > _floor(imp.source)
        if up or pair == {'transport', 'security'}:
            breaks.append(f'{imp.source}:{imp.line} -> {imp.target}')
    return breaks


def test_floors() -> None:
    """Every import, in a function or under TYPE_CHECKING too, goes to its own floor or lower
    (docs/DESIGN.md §2), so a lower floor never needs a higher one to load or to be typed
    (it names what is above it through a Protocol of its own); transport/ and security/ never
    meet."""
    assert _floor_breaks(_sources()) == []
    package = ROOT / 'ros2lite'
    named = [n for names in FLOORS.values() for n in names]
    assert sorted(FLOORS) == list(range(8)), 'docs/DESIGN.md §2 names floors 0 to 7'
    gone = [n for n in named if not {package / f'{n}.py', package / n} & _existing(package)]
    assert gone == [], 'floors name rooms that do not exist'
    probe = {
        'ros2lite/util/probe.py': 'def f():\n    from ros2lite.node import Node\n',
        'ros2lite/transport/probe.py': 'from ..security import keystore\n',
        'ros2lite/runtime/probe.py': 'from typing import TYPE_CHECKING\n'
        'if TYPE_CHECKING:\n    from ros2lite.tools import doctor\n',
    }
    assert _floor_breaks(probe) == [
        'ros2lite.util.probe:2 -> ros2lite.node',
        'ros2lite.transport.probe:1 -> ros2lite.security',
        'ros2lite.runtime.probe:3 -> ros2lite.tools',
    ]


def _circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one node (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, ()))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child)
                on_stack.add(child)
                work.append((child, iter(sorted(edges.get(child, ())))))
            elif child in on_stack:
                low[node] = min(low[node], index[child])
    return found


def _import_circles(sources: dict[str, str], *, folders: bool = False) -> list[list[str]]:
    """Circles among ros2lite's modules over every import (in-function and `TYPE_CHECKING`
    ones too: a type named from above closes a circle as surely as an import); with `folders`,
    among its top-level folders (a top-level module stands for itself) over the imports that
    run, as two rooms of one floor may name each other's types without a file circle."""

    def node(module: str) -> str:
        parts = module.split('.')
        folder = len(parts) > 2 or any(p.startswith(f'ros2lite/{parts[-1]}/') for p in sources)
        return '.'.join(parts[:2]) if folders and folder else module

    edges: dict[str, set[str]] = {}
    for imp in _imports(sources):
        a, b = node(imp.source), node(imp.target)
        if b.startswith('ros2lite') and a != b and not (folders and imp.typing):
            edges.setdefault(a, set()).add(b)
    return _circles(edges)


# circles left to a branch at work on them, each with its reason; may only shrink
CIRCLES_LEFT: list[list[str]] = []


def test_no_import_circles() -> None:
    """No module needs itself to load or to be typed, even through an import inside a
    function or under TYPE_CHECKING, and no folder needs another that needs it back: the
    floors then order every import."""
    sources = _sources()
    circles = _import_circles(sources)
    assert [c for c in circles if c not in CIRCLES_LEFT] == []
    assert [c for c in CIRCLES_LEFT if c not in circles] == [], 'gone: out of CIRCLES_LEFT'
    assert _import_circles(sources, folders=True) == []
    probe = {
        'ros2lite/graph.py': 'def f():\n    from ros2lite import context\n',
        'ros2lite/context.py': 'import ros2lite.graph\n',
        'ros2lite/bag/reader.py': 'from ros2lite.launch.api import x\n',
        'ros2lite/launch/api.py': 'def f():\n    from ..bag import writer\n',
        'ros2lite/bag/writer.py': '',
        'ros2lite/runtime/executable.py': 'from typing import TYPE_CHECKING\n'
        'if TYPE_CHECKING:\n    from ros2lite.node import Node\n',
        'ros2lite/node.py': 'from ros2lite.runtime import executable\n',
    }
    assert _import_circles(probe) == [
        ['ros2lite.context', 'ros2lite.graph'],
        ['ros2lite.node', 'ros2lite.runtime.executable'],
    ]
    assert _import_circles(probe, folders=True) == [
        ['ros2lite.bag', 'ros2lite.launch'],
        ['ros2lite.context', 'ros2lite.graph'],
    ]


def _cli_breaks(sources: dict[str, str]) -> list[str]:
    """cli/ reaching under the library (transport/, executors, spinning) or a verb imported
    by anything but its own command."""
    breaks = []
    for imp in _imports(sources):
        parts = imp.source.split('.')
        target = imp.target.split('.')
        if parts[1:2] == ['cli'] and target[1:2] in (['transport'], ['executors']):
            breaks.append(f'{imp.source}:{imp.line} -> {imp.target}')
        verb = target[1:2] == ['cli'] and len(target) == 4
        verb = verb and target[3] not in ('common', 'options')
        verb = verb and imp.source != '.'.join(target[:3])  # its own command may
        if verb and any(p.startswith(f'ros2lite/cli/{target[2]}/') for p in sources):
            breaks.append(f'{imp.source}:{imp.line} -> verb {imp.target}')
    for path, text in sources.items():
        if not path.startswith('ros2lite/cli/'):
            continue
        for node in ast.walk(ast.parse(text)):
            name = getattr(node, 'attr', None) or getattr(node, 'id', None)
            if name in ('spin_once', 'get_global_executor'):
                breaks.append(f'{_module_of(path)}:{node.lineno} {name}')  # type: ignore[attr-defined]
    return breaks


def test_cli_is_thin() -> None:
    """The CLI parses, calls the library and renders: it opens no session, runs no executor,
    and each command owns its verbs, whose VERBS table names exactly its folder's modules."""
    sources = _sources()
    assert _cli_breaks(sources) == []
    package = ROOT / 'ros2lite' / 'cli'
    for folder in sorted(p.parent for p in package.glob('*/__init__.py')):
        verbs = set(importlib.import_module(f'ros2lite.cli.{folder.name}').VERBS)
        files = {p.stem for p in folder.glob('*.py')} - {'__init__', 'common', 'options'}
        assert verbs == files, folder.name
    probe = {
        'ros2lite/cli/topic/__init__.py': 'from . import echo\n',
        'ros2lite/cli/topic/echo.py': 'from ros2lite.executors import x\n',
        'ros2lite/cli/topic/common.py': '',
        'ros2lite/cli/node/list.py': 'from ..topic import echo, common\nspin_once()\n',
        'ros2lite/cli/render.py': 'def f(node):\n    node.context.get_global_executor()\n',
    }
    assert _cli_breaks(probe) == [
        'ros2lite.cli.topic.echo:1 -> ros2lite.executors',
        'ros2lite.cli.node.list:1 -> verb ros2lite.cli.topic.echo',
        'ros2lite.cli.node.list:2 spin_once',
        'ros2lite.cli.render:2 get_global_executor',
    ]


SIGNAL_OWNERS = ('ros2lite/signals.py', 'ros2lite/util/process.py')


def _signal_breaks(sources: dict[str, str]) -> list[str]:
    """Calls that install signal handlers, outside the two modules that own them."""
    setters = {'signal', 'setitimer', 'set_wakeup_fd', 'add_signal_handler'}
    breaks = []
    for path, text in sources.items():
        if path in SIGNAL_OWNERS:
            continue
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Call):
                func = node.func
                name = func.attr if isinstance(func, ast.Attribute) else getattr(func, 'id', '')
                if name in setters:
                    breaks.append(f'{path}:{node.lineno} {name}')
    return breaks


def test_signal_handlers() -> None:
    """Who handles a signal is decided in two places (rclpy's handlers; children and stop
    signals), so no module silently takes SIGINT or SIGTERM from another."""
    assert _signal_breaks(_sources()) == []
    probe = {
        'ros2lite/daemon/router.py': 'import signal\nsignal.signal(signal.SIGHUP, 1)\n',
        'ros2lite/launch/api.py': 'def f(loop):\n    loop.add_signal_handler(2, f)\n',
        'ros2lite/util/process.py': 'import signal\nsignal.signal(2, 0)\n',
    }
    assert _signal_breaks(probe) == [
        'ros2lite/daemon/router.py:2 signal',
        'ros2lite/launch/api.py:2 add_signal_handler',
    ]


# rclpy's executor exceptions are plain Exceptions there, and Terminated is a BaseException
# (like KeyboardInterrupt) so that nothing catching Exception swallows a SIGTERM
OWN_BASES = {
    'ros2lite.executors.ExternalShutdownException',
    'ros2lite.executors.ShutdownException',
    'ros2lite.executors.TimeoutException',
    'ros2lite.executors.ConditionReachedException',
    'ros2lite.util.process.Terminated',
}


def _errors_off_base(modules: list[object]) -> list[str]:
    """Public exception classes defined in `modules` that do not derive from Ros2liteError."""
    from ros2lite.exceptions import Ros2liteError

    found = []
    for module in modules:
        name = getattr(module, '__name__', '')
        for attr, obj in vars(module).items():
            error = isinstance(obj, type) and issubclass(obj, BaseException)
            own = error and obj.__module__ == name and not attr.startswith('_')
            if own and not issubclass(obj, Ros2liteError) and f'{name}.{attr}' not in OWN_BASES:
                found.append(f'{name}.{attr}')
    return found


# modules only their extra's program loads (it brings their dependency); they define no errors
ONLY_WITH_EXTRA = {
    'ros2lite.tools.colcon.extensions': 'colcon: loaded by colcon-core, subclasses its classes',
}


def test_errors_share_one_base() -> None:
    """Every error the library raises on purpose is a Ros2liteError, so the CLI turns each
    into one clear line (save rclpy's own executor exceptions and Terminated)."""
    import types

    names = [
        _module_of(p)
        for p in _sources()
        if not p.startswith(('ros2lite/compat/', 'ros2lite/msgs/'))
        and not p.endswith(('__main__.py', '.launch.py'))
        and _module_of(p) not in ONLY_WITH_EXTRA
    ]
    assert _errors_off_base([importlib.import_module(n) for n in names]) == []
    probe = types.ModuleType('ros2lite.probe')
    exec('class BagGone(KeyError): pass\nclass _Hidden(Exception): pass', vars(probe))
    executors = importlib.import_module('ros2lite.executors')
    assert _errors_off_base([probe, executors]) == ['ros2lite.probe.BagGone']


def _interface_writes(sources: dict[str, str]) -> list[str]:
    """File writes under interfaces/ outside stubs.py (which writes msgs/'s .pyi stubs)."""
    writers = {
        'write_text', 'write_bytes', 'mkdir', 'makedirs', 'unlink', 'rmdir', 'rmtree',
        'copyfile', 'create_new', 'open_for_writing', 'replace_file', 'temp_beside',
        'private_dir',
    }  # fmt: skip
    os_writers = {'replace', 'rename', 'remove', 'write'}  # as os.<name> (str has .replace)
    breaks = []
    for path, text in sources.items():
        if not path.startswith('ros2lite/interfaces/') or path.endswith('/stubs.py'):
            continue
        for node in ast.walk(ast.parse(text)):
            if not isinstance(node, ast.Call):
                continue
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else getattr(func, 'id', '')
            modes: list[ast.expr] = [a for a in node.args[1:2] if isinstance(a, ast.Constant)]
            modes += [k.value for k in node.keywords if k.arg == 'mode']
            writing = name == 'open' and any(
                not isinstance(m, ast.Constant) or set(str(m.value)) & set('wax+') for m in modes
            )
            owner = getattr(func, 'value', None)
            by_os = isinstance(owner, ast.Name) and owner.id == 'os' and name in os_writers
            if name in writers or by_os or writing:
                breaks.append(f'{path}:{node.lineno} {name}')
    return breaks


def test_interfaces_write_nothing() -> None:
    """Parsing, hashing and code generation only read: the one writer is stubs.py, so a
    `ros2lite interface` verb can never change the files it shows."""
    assert _interface_writes(_sources()) == []
    probe = {
        'ros2lite/interfaces/registry.py': 'def f(p):\n    p.write_text("x")\n'
        '    open(p, "a")\n    open(p)\n    open(p, mode="rb")\n    "a".replace("a", "b")\n'
        '    os.replace(p, p)\n',
        'ros2lite/interfaces/stubs.py': 'def f(p):\n    p.write_text("x")\n',
    }
    assert _interface_writes(probe) == [
        'ros2lite/interfaces/registry.py:2 write_text',
        'ros2lite/interfaces/registry.py:3 open',
        'ros2lite/interfaces/registry.py:7 replace',
    ]


def _cli_parsing_breaks(sources: dict[str, str]) -> list[str]:
    """cli/ modules but parsing.py that subclass click's Command/Group/Option/Parameter or
    reach into click's parser."""
    names = {'Command', 'Group', 'Option', 'Parameter', 'Argument', 'MultiCommand'}
    breaks = []
    for path, text in sources.items():
        if not path.startswith('ros2lite/cli/') or path == 'ros2lite/cli/parsing.py':
            continue
        tree = ast.parse(text)
        from_click = {
            alias.asname or alias.name: alias.name
            for node in ast.walk(tree)
            if isinstance(node, ast.ImportFrom) and node.module == 'click'
            for alias in node.names
        }
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and (node.module or '').startswith('click.parser'):
                breaks.append(f'{path}:{node.lineno} click.parser')
            if isinstance(node, ast.ClassDef):
                for base in node.bases:
                    text = ast.unparse(base)
                    clicks = text.removeprefix('click.') if text.startswith('click.') else None
                    if (clicks or from_click.get(text)) in names:
                        breaks.append(f'{path}:{node.lineno} {node.name}({text})')
    return breaks


def test_cli_parsing_in_one_place() -> None:
    """One place parses (cli/parsing.py): no other module subclasses click's
    Command/Group/Option/Parameter or reaches into click's parser."""
    assert _cli_parsing_breaks(_sources()) == []
    probe = {
        'ros2lite/cli/topic/echo.py': 'import click\nfrom click import Option as O\n'
        'class A(click.Command): pass\nclass B(O): pass\nclass C(dict): pass\n',
        'ros2lite/cli/render.py': 'from click.parser import OptionParser\n',
        'ros2lite/cli/parsing.py': 'import click\nclass Command(click.Command): pass\n',
    }
    assert _cli_parsing_breaks(probe) == [
        'ros2lite/cli/topic/echo.py:3 A(click.Command)',
        'ros2lite/cli/topic/echo.py:4 B(O)',
        'ros2lite/cli/render.py:1 click.parser',
    ]


# Modules under ros2lite/ (outside cli/, bundled/, compat/ and the __init__s) that keep imports
# inside functions, each with what importing them at the top would add to every program that
# imports the module (measured: a fresh interpreter imports the module, then its in-function
# targets; Python 3.11). It may only shrink: an entry whose module has none left fails.
LAZY = {
    'action.graph': '+5 modules ~9 ms: graph.py',
    'bag.export': 'pyarrow (an optional extra, ~300 ms) for Parquet, Pillow (~40 ms) for PNG: '
    'each only for its format',
    'bag.rosbag1': 'rosbags (the optional ros1 extra: numpy, ~150 ms), only when a ROS 1 '
    'bag is opened',
    'bag.player': '+19 modules ~11 ms: the interface registry, bag definitions',
    'bag.reader': '+20 modules ~15 ms: the interface registry, bag definitions',
    'bag.recorder': '+35 modules ~33 ms: the interface registry, graph.py',
    'bag.storage.mcap.read': '+42 modules ~44 ms: mcap.reader (+26 ~19 ms: mcap.records)',
    'bag.storage.mcap.recover': '+97 modules ~59 ms: mcap.writer; util.files (tempfile)',
    'bag.storage.mcap.scan': '+26 ~19 ms mcap.records; zstandard, lz4 (C extensions) only '
    'for a compressed damaged chunk',
    'bag.storage.mcap.write': '+97 modules ~59 ms: mcap.writer; util.files (tempfile)',
    'bag.writer': '+18 modules ~10 ms: the interface registry',
    'client': '+27 modules ~16 ms: zenoh, the interface registry',
    'components.manager': '+17 modules ~10 ms: the interface registry',
    'components.registry': '+60 modules ~19 ms: importlib.metadata, tempfile, the package index',
    'components.remote': '+17 modules ~10 ms: the interface registry',
    'context': '+36 modules ~37 ms: zenoh, graph.py, names.py',
    'daemon.__main__': '+59 modules ~47 ms: zenoh, xml.etree, the router process',
    'daemon.connect': '+27 modules ~27 ms: subprocess, xml.etree, the daemon starter',
    'daemon.control': '+8 modules ~16 ms: transport admin, names.py, qos.py',
    'daemon.graph_cache': '+34 modules ~28 ms: zenoh, names.py, qos.py',
    'daemon.paths': '+3 modules ~2 ms: util/files',
    'daemon.probe': '+22 modules ~15 ms: zenoh',
    'daemon.router': '+1 module ~2 ms: the graph cache server',
    'duration': '+35 modules ~18 ms: the interface registry',
    'graph': '+14 modules ~7 ms: zenoh',
    'interfaces.convert': '+26 modules ~16 ms: PyYAML, safe_yaml',
    'launch.api': '+5 modules ~5 ms: the package index',
    'launch.context': '+6 modules ~3 ms: the package index',
    'launch.frontend.builders': '+3 modules ~5 ms: tempfile, launch/ros, names.py',
    'launch.ros': '+39 modules ~27 ms: PyYAML, xml.etree, the package index',
    'launch.sources': '+5 modules ~3 ms: pkg environment',
    'lifecycle.node': '+17 modules ~11 ms: the interface registry',
    'lifecycle.remote': '+17 modules ~11 ms: the interface registry',
    'logging_service': '+26 modules ~14 ms: the interface registry',
    'monitor.chart': '+16 modules ~20 ms: Pillow (PIL), only to write a PNG',
    'monitor.topic': '+17 modules ~11 ms: the interface registry',
    'node': '+30 modules ~32 ms: zenoh, the interface registry',
    'parameter': '+36 modules ~20 ms: the interface registry, safe_yaml',
    'parameter_client': '+21 modules ~21 ms: the interface registry, parameter events',
    'parameters.events': '+36 modules ~35 ms: the interface registry, qos.py',
    'parameters.files': '+29 modules ~18 ms: PyYAML, safe_yaml',
    'parameters.services': '+12 modules ~12 ms: qos.py',
    'parameters.store': '+29 modules ~19 ms: the interface registry',
    'pkg.errors': '+3 modules ~9 ms: difflib (heapq), for close matches in a message shown',
    'pkg.executables': '+64 modules ~28 ms: importlib.metadata, tempfile, setup files',
    'pkg.index': '+62 modules ~22 ms: importlib.metadata, tempfile',
    'pkg.manifest': '+10 modules ~4 ms: xml.etree, util/files',
    'publisher': '+30 modules ~23 ms: zenoh, the interface registry',
    'qos_overriding_options': '+26 modules ~28 ms: the parameter store, publisher.py, names.py',
    'runtime.endpoint': '+34 modules ~21 ms: zenoh, the interface registry',
    'runtime.memory': '+7 modules ~2 ms: ctypes',
    'security.access': '+95 modules ~54 ms: cryptography',
    'security.environment': '+109 modules ~61 ms: cryptography, xml.etree, util/files',
    'security.keystore': '+97 modules ~68 ms: cryptography',
    'security.pki': 'cryptography: an optional Rust test hook, probed when present',
    'service': '+27 modules ~21 ms: zenoh, the interface registry',
    'service_introspection': '+22 modules ~18 ms: the interface registry, interfaces/convert',
    'subscription': '+29 modules ~25 ms: zenoh, the interface registry',
    'time': '+35 modules ~20 ms: the interface registry',
    'tools.connection': '+98 modules ~121 ms: zenoh, node.py, graph.py',
    'tools.doctor': '+106 modules ~67 ms: zenoh, importlib.metadata, subprocess, tempfile',
    'tools.hello': '+ the node and the multicast sockets, only when the verb runs',
    'transport.session': '+2 modules ~1 ms: traceback, for a failing callback',
    'type_description_service': '+39 modules ~27 ms: the interface registry, the parameter store',
    'util.files': '+16 modules ~4 ms: tempfile',
    'util.keyboard': '+2 modules ~0 ms: termios, tty (POSIX only)',
    'util.process': '+13 modules ~5 ms: ctypes, subprocess',
    'util.safe_yaml': '+27 modules ~14 ms: PyYAML',
}


def _lazy_breaks(sources: dict[str, str], lazy: dict[str, str]) -> list[str]:
    """In-function imports in modules that may not have them, and LAZY entries whose module
    has none left."""
    inits = {_module_of(p) for p in sources if p.endswith('__init__.py')}
    free = ('ros2lite.cli.', 'ros2lite.bundled.', 'ros2lite.compat.')
    lazy_in = {i.source for i in _imports(sources) if i.lazy and not i.typing}
    listed = {f'ros2lite.{module}' for module in lazy}
    breaks = [
        f'{module}: imports inside a function'
        for module in sorted(lazy_in - inits - listed)
        if not module.startswith(free)
    ]
    breaks += [f'{module}: in LAZY, none left' for module in sorted(listed - lazy_in)]
    return breaks


def test_lazy_imports() -> None:
    """An import inside a function hides a dependency from the reader and the floors; it is
    kept only where start-up pays for it (the CLI's lazy table, bundled packages, compat's
    faces, the packages' lazy __init__s) or where LAZY says what it would cost."""
    assert _lazy_breaks(_sources(), LAZY) == []
    probe = {
        'ros2lite/graph.py': 'def f():\n    import json\n',
        'ros2lite/node.py': 'import json\n',
        'ros2lite/cli/topic/echo.py': 'def f():\n    import yaml\n',
        'ros2lite/bag/__init__.py': 'def __getattr__(name):\n    import importlib\n',
        'ros2lite/time.py': 'from typing import TYPE_CHECKING\n'
        'if TYPE_CHECKING:\n    from ros2lite.clock import Clock\n'
        'def f():\n    import os\n',
    }
    lazy = {'node': 'was lazy once', 'time': 'os'}
    assert _lazy_breaks(probe, lazy) == [
        'ros2lite.graph: imports inside a function',
        'ros2lite.node: in LAZY, none left',
    ]


def _foreign_imports(sources: dict[str, str]) -> list[str]:
    """click or rich imported outside cli/ (bundled packages' `*_view.py` may import rich inside a
    function), zenoh imported outside transport/ (every import, TYPE_CHECKING exempt)."""
    breaks = []
    for imp in _imports(sources):
        if imp.typing:
            continue  # naming a type loads nothing
        top = imp.target.split('.')[0]
        folder = imp.source.split('.')[1:2]
        view = folder == ['bundled'] and imp.source.endswith('_view') and imp.lazy and top == 'rich'
        if (top in ('click', 'rich') and folder != ['cli'] and not view) or (
            top == 'zenoh' and folder != ['transport']
        ):
            breaks.append(f'{imp.source}:{imp.line} {imp.target}')
    return breaks


def test_only_cli_imports_click_or_rich_and_only_transport_zenoh() -> None:
    """One seam to each: every declaration, put, query and session lives in transport/, and
    only the CLI draws with click and rich (a demo's window view may, when it draws)."""
    assert _foreign_imports(_sources()) == []
    probe = {
        'ros2lite/graph.py': 'def f():\n    import zenoh\n',
        'ros2lite/transport/session.py': 'import zenoh\n',
        'ros2lite/cli/render.py': 'import rich.table\nimport click\n',
        'ros2lite/bundled/turtlesim/window_view.py': 'import rich\ndef f():\n    import rich\n',
        'ros2lite/monitor/stats.py': 'from click import echo\n',
    }
    assert _foreign_imports(probe) == [
        'ros2lite.graph:2 zenoh',
        'ros2lite.bundled.turtlesim.window_view:1 rich',
        'ros2lite.monitor.stats:1 click',
    ]
