"""`daemon status`: ros2cli's line, then which router serves the endpoint."""

from __future__ import annotations

from ros2lite import daemon

from ..conftest import run_process
from .conftest import Private


def test_not_running(private: Private) -> None:
    result = run_process('daemon', 'status', env=private.env)
    assert (result.code, result.err) == (0, '')
    assert result.out == ('The daemon is not running\n'
                          f'No Zenoh router answers at {private.endpoint}\n')


def test_running(private: Private) -> None:
    started = daemon.start(private.endpoint)
    result = run_process('daemon', 'status', env=private.env)
    assert (result.code, result.err) == (0, '')
    assert result.out == ('The daemon is running\n'
                          f'Serving {private.endpoint} (ros2lite daemon, pid {started.pid})\n')


def test_foreign_router(private: Private) -> None:
    import zenoh

    from ros2lite.transport.config import router_config
    router = zenoh.open(router_config(private.endpoint, env={}))
    try:
        result = run_process('daemon', 'status', env=private.env)
        assert result.out == ('The daemon is running\n'
                              f'Serving {private.endpoint} (a Zenoh router not started by '
                              'ros2lite)\n')
        start = run_process('daemon', 'start', env=private.env)
        assert start.out == ('The daemon is already running\n'
                             'A Zenoh router not started by ros2lite answers at '
                             f'{private.endpoint}\n')
        stop = run_process('daemon', 'stop', env=private.env)
        assert stop.out == ('The daemon is not running\n'
                            f'A Zenoh router not started by ros2lite answers at '
                            f'{private.endpoint}; not stopping it\n')
        assert all(r.code == 0 for r in (result, start, stop))
        assert daemon.router_answers(private.endpoint)  # left alone
    finally:
        router.close()
