"""$(find-pkg-share) and $(find-pkg-prefix): packages found through the launch's package
index, an unknown name refused with the close matches."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.launch import ros
from ros2lite.launch.context import LaunchContext
from ros2lite.launch.errors import SubstitutionFailure
from ros2lite.launch.find_package import FindPackagePrefix, FindPackageShare


def test_share_holds_the_package_files_under_its_prefix() -> None:
    context = LaunchContext()
    share = Path(FindPackageShare('turtlesim').perform(context))
    prefix = Path(FindPackagePrefix('turtlesim').perform(context))
    assert (share / 'launch' / 'multisim.launch.py').is_file()
    assert share.is_relative_to(prefix)
    assert FindPackageShare('turtlesim').describe() == "FindPackageShare(pkg='turtlesim')"


@pytest.mark.parametrize('find', [FindPackageShare, FindPackagePrefix])
def test_unknown_package_names_close_matches(find: type[FindPackagePrefix]) -> None:
    with pytest.raises(SubstitutionFailure, match=r"Package 'turtlesm' not found; did you mean"):
        find('turtlesm').perform(LaunchContext())


def test_launch_ros_names_stay_in_ros() -> None:
    assert ros.FindPackageShare is FindPackageShare
    assert ros.FindPackagePrefix is FindPackagePrefix
