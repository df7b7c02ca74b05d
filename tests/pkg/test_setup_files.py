"""Console scripts from setup.py and setup.cfg, read without running either."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.pkg.setup_files import parse_console_script, read_python_package


def test_tutorial_setup_py(tmp_path: Path) -> None:
    (tmp_path / 'setup.py').write_text(
        'import os\n'
        'from glob import glob\n'
        'from setuptools import find_packages, setup\n\n'
        "package_name = 'py_pubsub'\n\n"
        'setup(\n'
        '    name=package_name,\n'
        "    data_files=[(os.path.join('share', package_name, 'launch'), glob('launch/*'))],\n"
        '    entry_points={\n'
        "        'console_scripts': [\n"
        "            'talker = py_pubsub.publisher_member_function:main',\n"
        "            f'listener = {package_name}.subscriber_member_function:main',\n"
        "            'odd = ' + package_name + '.odd:Runner.run',\n"
        "            'broken = not a target',\n"
        '        ],\n'
        '    },\n'
        ')\n'
    )
    info = read_python_package(tmp_path)
    assert info.console_scripts == {
        'talker': 'py_pubsub.publisher_member_function:main',
        'listener': 'py_pubsub.subscriber_member_function:main',
        'odd': 'py_pubsub.odd:Runner.run',
    }
    assert info.package_root == tmp_path
    # colcon (setuptools) would refuse the package for the line that does not parse
    assert [str(p) for p in info.problems] == [
        f"{tmp_path}/setup.py:15: entry point 'broken = not a target': expected "
        "'name = package.module:function'"
    ]


def test_setup_py_is_never_executed(tmp_path: Path) -> None:
    marker = tmp_path / 'ran'
    (tmp_path / 'setup.py').write_text(
        f"open({str(marker)!r}, 'w').close()\n"
        "from setuptools import setup\n"
        "setup(entry_points={'console_scripts': [__import__('os').getcwd()]})\n"
    )
    info = read_python_package(tmp_path)
    assert not marker.exists()
    assert info.console_scripts == {}


def test_setup_cfg_and_package_dir(tmp_path: Path) -> None:
    (tmp_path / 'setup.cfg').write_text(
        '[develop]\nscript_dir=$base/lib/pkg\n'
        '[options]\npackage_dir =\n    =src\n'
        '[options.entry_points]\nconsole_scripts =\n    tool = pkg.tool:main\n'
    )
    info = read_python_package(tmp_path)
    assert info.console_scripts == {'tool': 'pkg.tool:main'}
    assert info.package_root == (tmp_path / 'src').resolve()


def test_package_dir_cannot_escape(tmp_path: Path) -> None:
    (tmp_path / 'setup.py').write_text(
        "from setuptools import setup\nsetup(package_dir={'': '../..'})\n"
    )
    assert read_python_package(tmp_path).package_root == tmp_path


def test_console_script_lines() -> None:
    assert parse_console_script(' a-b = x.y:z [extra] ') == ('a-b', 'x.y:z')
    assert parse_console_script('a = x') == ('a', 'x')
    assert parse_console_script('a = x; import os') is None
    assert parse_console_script('a = x:__import__("os")') is None


_SETUP_HEAD = "from setuptools import setup\n\npackage_name = 'p'\n\n"


@pytest.mark.parametrize(
    ('files', 'problem'),
    [
        (
            {'setup.py': _SETUP_HEAD + 'setup(\n    name=package_name,\n'},
            "setup.py:5: not valid Python: '(' was never closed",
        ),
        (
            {'setup.py': 'import setuptools\n\nprint(1)\n'},
            'setup.py:1: no setup() call: colcon cannot build the package',
        ),
        (
            {
                'setup.py': _SETUP_HEAD
                + "setup(\n    entry_points={\n        'console_scripts': [\n"
                "            'ok = p.ok:main',\n"
                "            'talker = p.talker:main:extra',\n"
                '        ],\n    },\n)\n'
            },
            "setup.py:9: entry point 'talker = p.talker:main:extra': expected "
            "'name = package.module:function'",
        ),
        (
            {'setup.cfg': 'script_dir=$base/lib/p\n'},
            'setup.cfg:1: not valid INI: a line before the first [section]',
        ),
        (
            {'setup.cfg': '[options.entry_points]\nconsole_scripts =\n    talker p.talker:main\n'},
            "setup.cfg:3: entry point 'talker p.talker:main': expected "
            "'name = package.module:function'",
        ),
        ({}, 'setup.py: missing: an ament_python package needs one'),
    ],
)
def test_what_colcon_would_refuse_is_named_with_file_and_line(
    tmp_path: Path, files: dict[str, str], problem: str
) -> None:
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    assert [str(p) for p in read_python_package(tmp_path).problems] == [f'{tmp_path}/{problem}']


def test_a_setup_py_linked_to_dev_zero_is_not_read_without_end(tmp_path: Path) -> None:
    """R5-P1: only a regular file is read, and only so much of it."""
    from ros2lite.pkg.setup_files import _read_text

    link = tmp_path / 'setup.py'
    link.symlink_to('/dev/zero')
    assert _read_text(link) is None
