"""House rules a machine can check: lint, types, and the library/CLI boundary."""

from __future__ import annotations

import ast
import importlib
import re
import subprocess
import sys
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


def test_only_cli_imports_click_or_rich() -> None:
    """Outside cli/ nothing imports click or rich, save the demos' views (`*_view.py` under
    demos/), which may import rich lazily: indented, inside the function that draws."""
    pattern = re.compile(r'^\s*(import|from)\s+(click|rich)\b', re.MULTILINE)
    top_level = re.compile(r'^(import|from)\s+rich\b|^\s*(import|from)\s+click\b', re.MULTILINE)
    offenders = []
    for p in (ROOT / 'ros2lite').rglob('*.py'):
        parts = p.relative_to(ROOT / 'ros2lite').parts
        if parts[0] == 'cli':
            continue
        view = parts[0] == 'demos' and p.name.endswith('_view.py')
        if (top_level if view else pattern).search(p.read_text()):
            offenders.append(str(p.relative_to(ROOT)))
    assert offenders == []


def test_only_transport_imports_zenoh() -> None:
    """One seam to Zenoh: every declaration, put, query and session lives in transport/."""
    pattern = re.compile(r'^\s*(import|from)\s+zenoh\b', re.MULTILINE)
    offenders = [
        str(p.relative_to(ROOT))
        for p in (ROOT / 'ros2lite').rglob('*.py')
        if p.relative_to(ROOT / 'ros2lite').parts[0] != 'transport'
        and pattern.search(p.read_text())
    ]
    assert offenders == []


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
# class carries (rosidl's `_TYPE_SUPPORT` habit); bag/storage/mcap.py's one (being split).
PRIVATE_REACH_CEILING = 11


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


def test_scheduling_state() -> None:
    """Only ros2lite/runtime/scheduling.py touches a NodeWork's slots or an entity's
    `_scheduled` flag (the old node fields `_unqueued_work`/`_last_executor` stay gone), so
    which executor runs a node's work is decided in one place."""
    from ros2lite.runtime.scheduling import NodeWork

    owner = ROOT / 'ros2lite' / 'runtime' / 'scheduling.py'
    slots = set(NodeWork.__slots__)
    banned = {'_scheduled', '_unqueued_work', '_last_executor'}
    offenders = []
    for p in sorted([*(ROOT / 'ros2lite').rglob('*.py'), *(ROOT / 'tests').rglob('*.py')]):
        if p == owner:
            continue
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.Attribute):
                name = node.attr
                mine = isinstance(node.value, ast.Name) and node.value.id in ('self', 'cls')
                if name in banned or (name in slots and not mine):
                    offenders.append(f'{p.relative_to(ROOT)}:{node.lineno} .{name}')
            elif isinstance(node, ast.Name) and node.id in banned:
                offenders.append(f'{p.relative_to(ROOT)}:{node.lineno} {node.id}')
    assert offenders == []


# DESIGN.md §2, the package map, folder by folder ('' is ros2lite/ itself): module names
# (`name` is name.py), `{a,b}` expanded as the map writes them; `sub/` names a subpackage and
# `sub/name` a file in a plain folder (demos' launch files). Keep it in step with the map.
MAP = {
    '': '__init__ __main__ node publisher subscription service client timer executors'
    ' callback_groups task waitable destroyable context signals exceptions type_support qos'
    ' qos_overriding_options event_handler time duration clock time_source logging'
    ' logging_service parameter parameter_client parameter_event_handler service_introspection'
    ' type_description_service serialization topic_endpoint_info utilities wait_for_message'
    ' names message_info node_options rate graph'
    ' action/ lifecycle/ parameters/ runtime/ tools/ util/ transport/ interfaces/ msgs/ daemon/'
    ' bag/ pkg/ launch/ security/ components/ monitor/ demos/ cli/',
    'action': 'client server goals entity graph introspection',
    'lifecycle': 'node state_machine managed_entity publisher remote',
    'parameters': 'store node_api services events files',
    'runtime': 'scheduling executable endpoint delivery bad_samples node_interface memory'
    ' typesupport_checks arguments',
    'tools': 'connection doctor multicast',
    'util': 'files safe_yaml process keyboard',
    'transport': 'handles endpoints config open session receivers pull keys qos attachment'
    ' security admin errors',
    'interfaces': 'parser registry classes hashing text convert errors stubs cdr cdr_gen',
    'msgs': '',
    'daemon': '__main__ router connect probe paths graph_cache control errors',
    'bag': 'writer reader recorder player metadata definitions qos reindex convert errors storage/',
    'bag/storage': 'mcap sqlite3',
    'pkg': 'index bundled workspace manifest setup_files executables runner create templates'
    ' ament_index environment',
    'launch': 'api service context entity actions conditions substitutions events'
    ' event_handlers execute process_spec ros find_package sources output introspection errors'
    ' flow frontend/',
    'launch/frontend': 'loader entity builders substitutions',
    'security': 'keystore pki enclaves policy permissions access environment files errors',
    'components': 'manager registry remote',
    'monitor': 'topic subscription stats',
    'demos': 'runner display terminal demo_nodes_py/ action_tutorials_py/ lifecycle_py/'
    ' lifecycle/ composition/ rclpy_components/ turtlesim/ teleop/ teleop_twist_keyboard/'
    ' rqt_graph/',
    'demos/demo_nodes_py': 'talker listener add_two_ints_{server,client,client_async}'
    ' introspection_{client,service} parameter_blackboard launch/talker_listener.launch.py',
    'demos/action_tutorials_py': 'fibonacci_action_{server,client}',
    'demos/lifecycle_py': 'lifecycle_talker',
    'demos/lifecycle': 'lifecycle_listener',
    'demos/composition': 'talker listener server client',
    'demos/rclpy_components': 'component_container{,_mt}',
    'demos/turtlesim': 'sim node sprite turtlesim_node turtle_teleop_key draw_square mimic'
    ' window_view terminal_view launch/multisim.launch.py',
    'demos/teleop': 'spinning',
    'demos/teleop_twist_keyboard': 'teleop_twist_keyboard',
    'demos/rqt_graph': 'rqt_graph model layout output window_view terminal_view',
    'cli': 'main lazy errors suggest completion numbers deprecated_interfaces common render'
    ' options parsing run launch env doctor extensions extension_points'
    ' action/ bag/ component/ daemon/ interface/ lifecycle/ msg/ multicast/ node/ param/ pkg/'
    ' security/ service/ srv/ topic/',
}
# compat/ by face folder: the faces (and their subfolders) code written for ROS imports; plain
# directories on PYTHONPATH, not a package of ros2lite (no compat/__init__.py)
COMPAT_FACES = (
    'sitecustomize.py rclpy/ rclpy/_lazy.py rclpy/action/ rclpy/lifecycle/ rclpy/impl/ launch/'
    ' launch/events/ launch_ros/ launch_xml/ launch_yaml/ ament_index_python/'
)
# cli/<command>/: its VERBS, plus the shared module the map names
CLI_SHARED = {'bag': 'options'} | dict.fromkeys(
    ('component', 'daemon', 'lifecycle', 'multicast', 'param', 'security', 'topic'), 'common'
)
# modules that exist but the map does not name yet (the next map update places them and empties
# this list; a folder with '/' covers all under it)
NOT_YET_ON_MAP = {
    'cli/doctor/',  # doctor became a command with verbs (hello), as ros2cli's
    'compat/tf2_ros/',
    'demos/foxglove_bridge/',
    'demos/rqt_console/',
    'demos/rqt_tf_tree/',
    # Jazzy's demo_nodes_py executables (issue 23)
    'demos/demo_nodes_py/async_param_client.py',
    'demos/demo_nodes_py/introspection.py',
    'demos/demo_nodes_py/listener_qos.py',
    'demos/demo_nodes_py/listener_serialized.py',
    'demos/demo_nodes_py/matched_event_detect.py',
    'demos/demo_nodes_py/set_parameters_callback.py',
    'demos/demo_nodes_py/talker_qos.py',
    'demos/demo_nodes_py/use_logger_service.py',
    'demos/teleop/keyboard.py',  # the teleop keyboard; util/keyboard.py is the CLI's (issue 24)
    'demos/tf2_ros/',
    'demos/tf2_tools/',
    'demos/turtle_tf2_py/',
    'demos/turtlesim/interfaces.py',
    'pkg/distro.py',
    'tf2/',
}
# modules the map names that other branches are still writing (empty it as they merge)
NOT_YET_BUILT = {
    'cli/doctor.py',  # now cli/doctor/ (above); the map is to follow
}


def _expand(names: str) -> list[str]:
    """'a_{x,y} b' -> ['a_x', 'a_y', 'b'] (the map's brace shorthand)."""
    out = []
    for word in names.split():
        m = re.fullmatch(r'(.*)\{(.*)\}(.*)', word)
        out += [m[1] + alt + m[3] for alt in m[2].split(',')] if m else [word]
    return out


def _mapped() -> set[str]:
    """Every path the map names, relative to ros2lite/ (packages by their __init__.py)."""
    paths = set()
    for folder, names in MAP.items():
        prefix = f'{folder}/' if folder else ''
        if folder != '' or names:
            paths.add(f'{prefix}__init__.py')
        for name in _expand(names):
            if name.endswith('/'):
                paths.add(f'{prefix}{name}__init__.py')
            elif name.endswith('.py'):
                paths.add(prefix + name)
            else:
                paths.add(f'{prefix}{name}.py')
    for face in COMPAT_FACES.split():
        paths.add('compat/' + (f'{face}__init__.py' if face.endswith('/') else face))
    for command in _expand(MAP['cli']):
        if not command.endswith('/'):
            continue
        verbs = list(importlib.import_module(f'ros2lite.cli.{command[:-1]}').VERBS)
        shared = [CLI_SHARED[command[:-1]]] if command[:-1] in CLI_SHARED else []
        paths |= {f'cli/{command}{verb}.py' for verb in [*verbs, *shared]}
    return paths


def test_every_module_is_on_the_map() -> None:
    """Each module under ros2lite/ is where DESIGN.md §2 puts it, and each module the map
    names exists: a new module goes where the map says (or into NOT_YET_ON_MAP until the map
    is updated), and a module that moves takes the map with it."""
    package = ROOT / 'ros2lite'
    on_disk = {
        str(p.relative_to(package))
        for p in package.rglob('*.py')
        if p.relative_to(package).parts[0] != 'msgs' or p.name == '__init__.py'
    }
    on_disk = {p for p in on_disk if not p.startswith('msgs/') or p == 'msgs/__init__.py'}

    def waived(path: str, waivers: set[str]) -> bool:
        return any(path == w or (w.endswith('/') and path.startswith(w)) for w in waivers)

    mapped = _mapped()
    compat_faces = {'compat/' + f for f in COMPAT_FACES.split() if f.endswith('/')}
    in_a_face = {  # compat/: any module inside a face folder (by upstream path) is on the map
        p for p in on_disk if p.startswith('compat/') and p.rpartition('/')[0] + '/' in compat_faces
    }
    unmapped = sorted(p for p in on_disk - mapped - in_a_face if not waived(p, NOT_YET_ON_MAP))
    missing = sorted(p for p in mapped - on_disk if p not in NOT_YET_BUILT)
    assert (unmapped, missing) == ([], []), 'modules off the map, and map names missing'
    # the waiver lists only shrink: an entry the tree or the map has caught up with must go
    stale_waivers = sorted(
        w for w in NOT_YET_ON_MAP if not any(waived(p, {w}) for p in on_disk - mapped)
    )
    stale_waivers += sorted(w for w in NOT_YET_BUILT if w in on_disk or w not in mapped)
    assert stale_waivers == [], 'waived yet placed or built: take them out of the lists'
