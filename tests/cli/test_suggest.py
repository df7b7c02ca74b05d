"""Unknown commands and verbs: the closest match and the choices; lacking ones: why."""

from __future__ import annotations

from collections.abc import Callable

from ros2lite.cli.suggest import closest
from tests.cli.conftest import Result

Run = Callable[..., Result]


def test_closest() -> None:
    names = ['action', 'bag', 'lifecycle', 'param', 'pkg', 'topic']
    assert closest('topci', names) == 'topic'
    assert closest('lif', names) == 'lifecycle'  # a prefix of one name only
    assert closest('p', names) is None  # a prefix of two: no guess
    assert closest('xyzzy', names) is None


def test_unknown_command(run: Run) -> None:
    result = run('topci', 'list')
    assert result.code == 2
    last = result.err.splitlines()[-1]
    assert last.startswith("Error: No such command 'topci'. Did you mean 'topic'? (choose from ")
    assert 'lifecycle, multicast, node' in last
    assert 'extensions' not in last and 'msg' not in last  # hidden ones are not offered
    assert run('xyzzy').err.splitlines()[-1].startswith("Error: No such command 'xyzzy'. (")


def test_unknown_verb(run: Run) -> None:
    result = run('lifecycle', 'sett')
    assert result.code == 2
    assert result.err.splitlines()[-1] == (
        "Error: No such verb 'sett' of 'lifecycle'. Did you mean 'set'? "
        '(choose from get, list, nodes, set)'
    )
    assert "Did you mean 'list'?" in run('topic', 'lst').err


def test_lacking_commands_say_why(run: Run) -> None:
    for args, word in ((['test', 'x.test.py'], 'launch_testing'),):
        result = run(*args)
        assert result.code == 1 and word in result.err and len(result.err.splitlines()) == 1
