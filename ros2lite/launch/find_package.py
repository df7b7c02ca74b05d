"""Substitutions that find a package (launch_ros's `FindPackagePrefix`, `FindPackageShare`),
through the launch's package index, so a source workspace's packages are found unbuilt.

They stand apart from :mod:`.ros` (which offers them too) because the frontends' ``$(find-pkg-…)``
makes them, and the frontends are read by what :mod:`.ros` itself uses.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .errors import SubstitutionFailure
from .substitutions import (
    SomeSubstitutionsType,
    Substitution,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from ros2lite.pkg.index import Package

    from .context import LaunchContext

__all__ = ['FindPackagePrefix', 'FindPackageShare']


class FindPackagePrefix(Substitution):
    """A package's prefix, as `ros2lite pkg prefix` prints it."""

    def __init__(self, package: SomeSubstitutionsType) -> None:
        self.package = normalize_to_list_of_substitutions(package)

    def find(self, context: LaunchContext) -> Package:
        """The package from the launch's package index (a substitution failure when unknown)."""
        name = perform_substitutions(context, self.package)
        index = context.package_index
        pkg = index.find(name)
        if pkg is None:
            raise SubstitutionFailure(str(index.not_found(name)))
        return pkg

    def perform(self, context: LaunchContext) -> str:
        """The package's prefix directory."""
        return str(self.find(context).prefix)

    def describe(self) -> str:
        """The package, for introspection."""
        return f'FindPackagePrefix(pkg={describe_substitutions(self.package)})'


class FindPackageShare(FindPackagePrefix):
    """A package's share directory (a workspace package's source directory), where its
    launch/, config/ and package.xml are."""

    def perform(self, context: LaunchContext) -> str:
        """The package's share directory (its source directory for a workspace package)."""
        pkg = self.find(context)
        if pkg.share is None:
            raise SubstitutionFailure(f"package '{pkg.name}' has no share directory")
        return str(pkg.share)

    def describe(self) -> str:
        """The package, for introspection."""
        return f'FindPackageShare(pkg={describe_substitutions(self.package)})'
