"""ament_index_python's functions, answered by the package index: what the compat face
`ament_index_python` serves to launch files and nodes written for ROS."""

from __future__ import annotations

from pathlib import Path

from .errors import PackageNotFoundError
from .index import PackageIndex

__all__ = [
    'PackageNotFoundError',
    'get_package_prefix',
    'get_package_share_directory',
    'get_package_share_path',
    'get_packages_with_prefixes',
]


def _find(package_name: str) -> tuple[Path, Path | None]:
    index = PackageIndex()
    pkg = index.find(package_name)
    if pkg is None:
        # the package index's one error (a KeyError, as ament_index_python's is), in its words
        raise index.not_found(package_name, f"package '{package_name}' not found")
    return pkg.prefix, pkg.share


def get_package_prefix(package_name: str) -> str:
    """The package's prefix, as `ros2lite pkg prefix` prints it."""
    return str(_find(package_name)[0])


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    """Where the package's launch/, config/ and package.xml are."""
    prefix, share = _find(package_name)
    return str(share if share is not None else prefix / 'share' / package_name)


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    """The share directory as a Path (ament_index_python's newer spelling)."""
    return Path(get_package_share_directory(package_name, print_warning))


def get_packages_with_prefixes() -> dict[str, str]:
    """Every package name → its prefix."""
    return {name: str(pkg.prefix) for name, pkg in PackageIndex().packages().items()}
