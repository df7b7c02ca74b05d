"""The package index's errors: one PackageNotFoundError for every face that looks a package up."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.exceptions import Ros2liteError
from ros2lite.pkg.errors import NotHereError, PackageFileError, PackageNotFoundError
from ros2lite.pkg.index import PackageIndex


def test_one_class_under_every_name(monkeypatch: pytest.MonkeyPatch) -> None:
    """ros2lite's own lookups, and code written for ROS catching ament_index_python's error
    (a KeyError there), all meet the same class."""
    import importlib

    import ros2lite.pkg.ament_index as ament_index
    import ros2lite.pkg.executables as executables
    from ros2lite.pkg.environment import COMPAT_DIR

    monkeypatch.syspath_prepend(str(COMPAT_DIR))  # what `ros2lite env` gives a ROS shell
    ament_face = importlib.import_module('ament_index_python.packages').PackageNotFoundError
    assert ament_face is executables.PackageNotFoundError is ament_index.PackageNotFoundError
    assert ament_face is PackageNotFoundError
    assert issubclass(PackageNotFoundError, (Ros2liteError, KeyError, LookupError))
    assert issubclass(NotHereError, PackageNotFoundError)
    with pytest.raises(KeyError):
        ament_index.get_package_share_directory('no_such_package_anywhere')


def test_message_is_not_quoted_and_explained_only_when_shown() -> None:
    asked: list[int] = []

    def explain() -> str:
        asked.append(1)
        return 'it is over there'

    e = PackageNotFoundError('p', ['q'], explain=explain)
    assert asked == []  # caught and dropped, it costs no search
    assert str(e) == "Package 'p' not found; it is over there"
    assert str(e) == "Package 'p' not found; it is over there" and asked == [1]
    assert str(PackageNotFoundError('py_pubsb', ['py_pubsub'])) == (
        "Package 'py_pubsb' not found; did you mean: py_pubsub?"
    )
    assert str(PackageNotFoundError('x', message='Package not found')) == 'Package not found'


def test_file_errors_are_one_line_with_file_and_line(tmp_path: Path) -> None:
    e = PackageFileError(tmp_path / 'p' / 'setup.py', 3, 'not valid Python: invalid syntax')
    assert str(e) == f'{tmp_path}/p/setup.py:3: not valid Python: invalid syntax'
    assert (e.package, e.line) == ('p', 3)
    assert str(PackageFileError(tmp_path / 'setup.py', None, 'missing')) == (
        f'{tmp_path}/setup.py: missing'
    )


def test_the_index_words_each_case(tmp_path: Path) -> None:
    ws = tmp_path / 'ws'
    (ws / 'src' / 'broken').mkdir(parents=True)
    (ws / 'src' / 'broken' / 'package.xml').write_text('<package>\n<name>broken\n</package>\n')
    index = PackageIndex({}, cwd=ws)
    assert str(index.not_found('broken')) == (
        f"Package 'broken' not found; {ws}/src/broken/package.xml:3: not valid XML: mismatched tag"
    )
    gazebo = index.not_found('gazebo_plugins', 'Package not found')
    assert isinstance(gazebo, NotHereError)
    assert str(gazebo).startswith('Package not found; gazebo_plugins belongs to Gazebo')
    assert str(index.not_found('nowhere_at_all')) == "Package 'nowhere_at_all' not found"
    # a folder named otherwise: the name in the broken file still finds its line
    (ws / 'src' / 'repo').mkdir()
    (ws / 'src' / 'repo' / 'package.xml').write_text('<package>\n<name>in_repo</name>\n<x>\n')
    assert str(PackageIndex({}, cwd=ws).not_found('in_repo')) == (
        f"Package 'in_repo' not found; {ws}/src/repo/package.xml:4: not valid XML: no element found"
    )
    assert index.why_missing('turtlesim') == ''  # it is found: nothing to explain
