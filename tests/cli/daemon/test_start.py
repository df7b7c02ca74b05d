"""`daemon start` on a private endpoint: ros2cli's words first, details after."""

from __future__ import annotations

from ros2lite import daemon

from ..conftest import run_process
from .conftest import Private


def test_start_then_already_running(private: Private) -> None:
    first = run_process('daemon', 'start', env=private.env)
    assert (first.code, first.out, first.err) == (0, 'The daemon has been started\n', '')
    st = daemon.status(private.endpoint)
    assert st.running and st.ours and st.pid
    again = run_process('daemon', 'start', env=private.env)
    assert (again.code, again.out, again.err) == (0, 'The daemon is already running\n', '')
    assert daemon.status(private.endpoint).pid == st.pid  # no second router


def test_debug_tells_where_the_log_is(private: Private) -> None:
    result = run_process('daemon', 'start', '-d', env=private.env)
    assert result.code == 0
    first, second = result.out.splitlines()
    assert first == 'The daemon has been started'
    log = second.removeprefix('Log: ')
    assert second.startswith('Log: ') and log.startswith(str(private.runtime))
    with open(log) as fh:
        assert 'serving' in fh.read()


def test_global_router_option_and_listen(private: Private) -> None:
    # --router picks the endpoint (over the environment); --listen sets what the router opens
    env = {**private.env, 'ROS2LITE_ROUTER': 'tcp/127.0.0.1:1'}
    result = run_process(
        '--router', private.endpoint, 'daemon', 'start', '--listen', private.endpoint, env=env
    )
    assert (result.code, result.out) == (0, 'The daemon has been started\n')
    st = daemon.status(private.endpoint)
    assert st.running and st.info is not None and st.info.listen == [private.endpoint]


def test_connect_meshes_two_routers(private: Private) -> None:
    from tests.conftest import free_port

    second = f'tcp/127.0.0.1:{free_port()}'
    assert run_process('daemon', 'start', env=private.env).code == 0
    result = run_process(
        '--router', second, 'daemon', 'start', '--connect', private.endpoint, env=private.env
    )
    try:
        assert (result.code, result.out) == (0, 'The daemon has been started\n')
        info = daemon.status(second).info
        assert info is not None and info.connect == [private.endpoint]
    finally:
        run_process('--router', second, 'daemon', 'stop', env=private.env)


def test_bad_listen_endpoint_is_one_line_error(private: Private) -> None:
    result = run_process('daemon', 'start', '--listen', 'nonsense', env=private.env)
    assert result.code == 1 and result.out == ''
    assert result.err.count('\n') == 1 and 'Traceback' not in result.err
    assert not daemon.status(private.endpoint).running
