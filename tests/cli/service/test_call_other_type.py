"""`service call` to a name served with another type says so instead of waiting in silence."""

from __future__ import annotations

from typing import Any

from tests.cli.conftest import run_process


def test_call_says_the_type_the_service_has(adder: Any) -> None:
    result = run_process('service', 'call', '/math/add', 'std_srvs/srv/Trigger', '--timeout', '3')
    assert result.code == 1
    assert (
        "WARNING: service '/math/add' is served as example_interfaces/srv/AddTwoInts, not "
        'std_srvs/srv/Trigger; nothing will answer until a server of std_srvs/srv/Trigger '
        'appears\n'
    ) in result.err
    assert result.err.endswith("Timed out after 3 s waiting for service '/math/add'\n")
