"""`service list`, `type`, `find` and `info` against a live server, as ros2cli prints them."""

from __future__ import annotations

from typing import Any


def test_list(adder: Any, run: Any) -> None:
    out = run('service', 'list').out.splitlines()
    assert '/add_two_ints' in out and '/math/add' in out
    assert '/_hidden/add' not in out and out == sorted(out)
    typed = run('service', 'list', '-t').out.splitlines()
    assert '/add_two_ints [example_interfaces/srv/AddTwoInts]' in typed
    assert '/_hidden/add' in run('service', 'list', '--include-hidden-services').out.split()
    assert '/_hidden/add' in run('service', '--include-hidden-services', 'list').out.split()
    assert int(run('service', 'list', '-c').out) == len(out)


def test_type(adder: Any, run: Any) -> None:
    assert run('service', 'type', '/math/add').out == 'example_interfaces/srv/AddTwoInts\n'
    unknown = run('service', 'type', '/no/such/service')
    assert (unknown.code, unknown.out) == (1, '')
    assert unknown.err == "Unknown service '/no/such/service' (not in the graph now)\n"


def test_find(adder: Any, run: Any) -> None:
    found = run('service', 'find', 'example_interfaces/srv/AddTwoInts').out.splitlines()
    assert found == ['/add_two_ints', '/math/add']
    assert run('service', 'find', 'example_interfaces/srv/AddTwoInts', '-c').out == '2\n'
    assert run('service', 'find', 'std_srvs/srv/Trigger').out == ''


def test_info(adder: Any, run: Any) -> None:
    assert run('service', 'info', '/add_two_ints').out == (
        'Type: example_interfaces/srv/AddTwoInts\nClients count: 1\nServices count: 1\n'
    )
    unknown = run('service', 'info', '/nope')
    assert (unknown.code, unknown.err) == (1, "Unknown service '/nope'\n")
