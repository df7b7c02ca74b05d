"""The committed .pyi stubs are exactly what the generator makes, and they tell the truth about
the run-time classes."""

from __future__ import annotations

import ast
import fnmatch
import importlib
import shutil
from pathlib import Path

import pytest

from ros2lite.interfaces.registry import BUNDLED
from ros2lite.interfaces.stubs import HEADER, check_stubs, generate_stubs, main, write_stubs

ROOT = Path(__file__).resolve().parents[2]


def test_committed_stubs_are_the_generated_ones() -> None:
    # a hand edit, a new definition without a regenerated stub, or a stub left behind by a
    # removed package all show up here; `python -m ros2lite.interfaces.stubs` fixes them
    assert check_stubs() == []
    assert main(['--check']) == 0


def test_every_bundled_package_has_its_stubs() -> None:
    stubs = generate_stubs()
    packages = {p.name for p in BUNDLED.iterdir() if p.is_dir() and not p.name.startswith('_')}
    assert {rel.split('/')[0] for rel in stubs} == packages
    for rel in stubs:
        assert (BUNDLED / rel).read_text(encoding='utf-8').startswith(HEADER)


def test_the_wheel_ships_the_stubs() -> None:
    tomllib = pytest.importorskip('tomllib')  # Python 3.11+
    config = tomllib.loads((ROOT / 'pyproject.toml').read_text())
    patterns = config['tool']['setuptools']['package-data']['ros2lite.msgs']
    for rel in generate_stubs():
        assert any(fnmatch.fnmatch(rel, p) for p in patterns), rel


def _stub_classes(path: Path) -> dict[str, ast.ClassDef]:
    tree = ast.parse(path.read_text(encoding='utf-8'))
    return {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}


def _init_params(cls: ast.ClassDef) -> list[str]:
    init = next(n for n in cls.body if isinstance(n, ast.FunctionDef) and n.name == '__init__')
    return [a.arg for a in init.args.kwonlyargs]


def _constants(cls: ast.ClassDef) -> dict[str, object]:
    found = {}
    for node in cls.body:
        if isinstance(node, ast.AnnAssign) and node.value is not None:
            target = node.target
            assert isinstance(target, ast.Name)
            if target.id.isupper():
                found[target.id] = ast.literal_eval(node.value)
    return found


@pytest.mark.parametrize(
    'module',
    [
        'std_msgs.msg',
        'geometry_msgs.msg',
        'sensor_msgs.msg',
        'visualization_msgs.msg',
        'rcl_interfaces.msg',
        'example_interfaces.srv',
        'turtlesim.srv',
        'action_tutorials_interfaces.action',
        'turtlesim.action',
    ],
)
def test_stubs_describe_the_runtime_classes(module: str) -> None:
    """Every class the stub names exists behind the import hook, with the same fields in the
    same order, the same constants, and services/actions with the parts the stub gives."""
    pkg, kind = module.split('.')
    runtime = importlib.import_module(f'ros2lite.msgs.{module}')
    classes = _stub_classes(BUNDLED / pkg / kind / '__init__.pyi')
    assert classes
    assert set(dir(runtime)) <= set(classes)
    for name, cls in classes.items():
        real = getattr(runtime, name)
        if '_Message' in {b.id for b in cls.bases if isinstance(b, ast.Name)}:
            assert _init_params(cls) == list(real.get_fields_and_field_types()), name
            for const, value in _constants(cls).items():
                assert getattr(real, const) == value, (name, const)
            real()  # the stub's "every parameter has a default" holds
        else:  # a service or an action: its parts are the classes the stub aliases
            _check_aliases(cls, real)


def _check_aliases(cls: ast.ClassDef, real: type) -> None:
    for node in cls.body:
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            assert node.value is not None
            part = getattr(real, node.target.id)
            assert part.__name__ == ast.unparse(node.value).rsplit('.', 1)[-1], node.target.id
        elif isinstance(node, ast.ClassDef):  # an action's Impl
            _check_aliases(node, getattr(real, node.name))


def test_write_stubs_rewrites_stale_and_removes_left_over_stubs(tmp_path: Path) -> None:
    root = tmp_path / 'msgs'
    for pkg in ('builtin_interfaces', 'std_msgs', 'service_msgs', 'std_srvs'):
        shutil.copytree(BUNDLED / pkg, root / pkg, ignore=shutil.ignore_patterns('*.pyi'))
    assert 'missing: std_msgs/msg/__init__.pyi' in check_stubs(root)
    written = write_stubs(root)
    assert 'std_srvs/srv/__init__.pyi' in written
    assert check_stubs(root) == []
    # the stubs of a package do not depend on which other packages sit beside it
    assert (root / 'std_msgs/msg/__init__.pyi').read_text() == (
        BUNDLED / 'std_msgs/msg/__init__.pyi'
    ).read_text()
    (root / 'std_msgs/msg/__init__.pyi').write_text('# edited by hand\n')
    for definition in (root / 'std_srvs/srv').glob('*.srv'):
        definition.unlink()  # the package keeps no services: their stub is left over
    assert check_stubs(root) == [
        'stale: std_msgs/msg/__init__.pyi',
        'left over: std_srvs/srv/__init__.pyi',
    ]
    assert write_stubs(root) == ['std_msgs/msg/__init__.pyi']
    assert check_stubs(root) == []


def test_write_stubs_does_not_follow_a_symlink(tmp_path: Path) -> None:
    root = tmp_path / 'msgs'
    shutil.copytree(BUNDLED / 'builtin_interfaces', root / 'builtin_interfaces')
    stub = root / 'builtin_interfaces/msg/__init__.pyi'
    target = tmp_path / 'elsewhere.txt'
    target.write_text('keep me\n')
    stub.unlink()
    stub.symlink_to(target)
    with pytest.raises(OSError, match='symlink'):
        write_stubs(root)
    assert target.read_text() == 'keep me\n'
