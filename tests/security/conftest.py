"""The CLI runner of tests/cli, for the security verbs' checks here."""

from tests.cli.conftest import run

__all__ = ['run']
