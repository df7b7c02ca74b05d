"""Contexts: opening against a router (and failing fast without one), sys.argv as rclpy reads
it, the shared entity-id counter, and shutdown waking a spinning executor."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

import ros2lite
from ros2lite.context import Context
from ros2lite.exceptions import NotInitializedException
from ros2lite.node import Node
from tests.conftest import free_port


def test_client_mode_init_without_router_fails_fast_and_clearly(
    ros_router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    # a node runs without a router (see tests/test_router_survival.py); a client cannot
    from ros2lite.transport.errors import RouterUnavailableError

    monkeypatch.setenv('ZENOH_CONFIG_OVERRIDE', 'mode="client"')
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    ctx = Context()
    start = time.monotonic()
    with pytest.raises(RouterUnavailableError) as info:
        ros2lite.init([], context=ctx, router=endpoint)
    assert time.monotonic() - start < 3.0
    assert endpoint in str(info.value)
    assert 'ros2lite daemon start' in str(info.value)
    assert not ctx.ok()


def test_lifecycle(ros_router: str) -> None:
    ctx = Context()
    assert not ctx.ok()
    with pytest.raises(NotInitializedException):
        Node('early', context=ctx)
    assert ros2lite.init([], context=ctx) is ctx
    assert ctx.ok() and ros2lite.ok(context=ctx)
    assert 0 < len(ctx.zid) <= 32 and int(ctx.zid, 16) > 0  # zenoh drops leading zeros
    with pytest.raises(RuntimeError, match='once'):
        ctx.init([])
    ros2lite.shutdown(context=ctx)
    assert not ctx.ok()
    ros2lite.try_shutdown(context=ctx)  # a second shutdown is harmless
    ctx.init([])  # and the context can be used again
    assert ctx.ok()
    ctx.shutdown()


def test_with_statement_shuts_down(ros_router: str) -> None:
    ctx = Context()
    with ros2lite.init([], context=ctx):
        node = Node('scoped', context=ctx)
        assert ctx.ok()
    assert not ctx.ok()
    assert node._token is None  # nodes are destroyed with their context


def test_args_none_means_sys_argv(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(
        'sys.argv', ['prog', 'user_arg', '--ros-args', '-r', '__node:=renamed', '-p', 'answer:=42']
    )
    ctx = Context()
    ctx.init(None)
    try:
        node = Node('original', context=ctx)
        assert node.get_name() == 'renamed'
        assert node.declare_parameter('answer', 0).value == 42
    finally:
        ctx.shutdown()
    ctx.init([])  # an explicit list ignores sys.argv
    try:
        assert Node('original', context=ctx).get_name() == 'original'
    finally:
        ctx.shutdown()


def test_nodes_and_endpoints_share_one_id_counter(ros_context: Any) -> None:
    a = Node('a', context=ros_context, enable_rosout=False, start_parameter_services=False)
    pub = a.create_publisher('std_msgs/msg/String', 'x', 10)
    b = Node('b', context=ros_context, enable_rosout=False)
    # ids 1 and 2 are a's /parameter_events publisher and ~/get_type_description service
    assert (a.node_id, pub._ep.entity_id, b.node_id) == (0, 3, 4)


def test_shutdown_from_another_thread_ends_spin(ros_router: str) -> None:
    ctx = Context().init([])
    node = Node('spinner', context=ctx)
    done = threading.Event()

    def spin() -> None:
        ros2lite.spin(node, executor=ros2lite.SingleThreadedExecutor(context=ctx))
        done.set()

    thread = threading.Thread(target=spin, daemon=True)
    thread.start()
    time.sleep(0.1)
    assert not done.is_set()
    ctx.shutdown()
    assert done.wait(3.0)


def test_try_shutdown_beside_a_shutdown_on_another_thread(ros_router: str) -> None:
    """try_shutdown() waits for a shutdown under way instead of starting a second one
    (which would find the session gone and raise)."""
    ctx = Context().init([])
    Node('twice', context=ctx)
    errors: list[BaseException] = []

    def close() -> None:
        try:
            ros2lite.try_shutdown(context=ctx)
        except BaseException as e:  # what the test looks for
            errors.append(e)

    threads = [threading.Thread(target=close) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(30)
    assert errors == []
    assert not ctx.ok()


def test_process_exits_cleanly_without_shutdown(ros_router: str) -> None:
    # a live subscription's threads must not hang or abort the interpreter at exit
    import subprocess
    import sys

    code = (
        'import ros2lite\n'
        'from ros2lite.msgs.std_msgs.msg import String\n'
        'ros2lite.init([])\n'
        "n = ros2lite.Node('exiter')\n"
        "n.create_subscription(String, '/exit_test', print, 10)\n"
        "n.create_publisher(String, '/exit_test', 10).publish(String(data='x'))\n"
        'raise SystemExit(3)\n'
    )
    proc = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, timeout=20)
    assert proc.returncode == 3, proc.stderr


def test_exit_waits_for_a_shutdown_under_way_on_another_thread(ros_router: str) -> None:
    """A daemon thread's shutdown() ends the main thread's loop before the session has
    closed; the interpreter must not stop that thread halfway (inside zenoh it aborts)."""
    import subprocess
    import sys

    code = (
        'import threading, time\n'
        'import ros2lite\n'
        'from ros2lite.context import default_context\n'
        'ros2lite.init([])\n'
        "ros2lite.Node('closing')\n"
        'ctx = default_context()\n'
        'real = ctx.session\n'
        'class SlowClose:\n'
        '    def __getattr__(self, name): return getattr(real, name)\n'
        '    def close(self):\n'
        '        time.sleep(0.5)\n'
        '        real.close()\n'
        "        print('closed', flush=True)\n"
        'ctx.session = SlowClose()\n'
        'threading.Thread(target=ros2lite.shutdown, daemon=True).start()\n'
        'while ros2lite.ok():\n'
        '    time.sleep(0.01)\n'
    )
    proc = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, timeout=30)
    assert (proc.returncode, proc.stdout, proc.stderr) == (0, 'closed\n', '')


def test_the_session_is_let_go_inside_the_shutdown(ros_router: str) -> None:
    """Dropping a zenoh session releases the GIL; if the last reference went after the
    shutdown lock (on a daemon thread), the interpreter's exit could stop that thread inside
    zenoh, which aborts the process."""
    ctx = Context().init([])
    held: list[bool] = []

    class Probe:
        def __init__(self, real: Any) -> None:
            self.real = real

        def close(self) -> None:
            self.real.close()

        def __del__(self) -> None:
            held.append(ctx._shutdown_lock._is_owned())  # type: ignore[attr-defined]

    ctx.session = Probe(ctx.session)  # type: ignore[assignment]
    ctx.shutdown()
    assert held == [True]


SIGTERM_PROGRAM = r'''
import signal, sys, time
import ros2lite
from ros2lite.executors import ExternalShutdownException
mode = sys.argv[1]
ros2lite.init([])
node = ros2lite.Node('sigterm_program', enable_rosout=False)
print('ready', flush=True)
if mode == 'spin':
    try:
        ros2lite.spin(node)
    except ExternalShutdownException:
        print('external shutdown', flush=True)
elif mode == 'loop':
    while ros2lite.ok():        # a program that never spins still gets out
        time.sleep(0.02)
    print('left loop', flush=True)
ros2lite.try_shutdown()
if mode == 'after':
    print('shut down', flush=True)
    time.sleep(30)              # nothing of ours is open: SIGTERM must kill as usual
'''


@pytest.mark.parametrize(
    ('mode', 'said', 'code'),
    [('spin', 'external shutdown', 0), ('loop', 'left loop', 0), ('after', 'shut down', -15)],
)
def test_sigterm(processes: Any, mode: str, said: str, code: int) -> None:
    import signal

    proc = processes.python(SIGTERM_PROGRAM, mode)
    assert proc.stdout.readline() == 'ready\n'
    if mode == 'after':
        assert proc.stdout.readline() == 'shut down\n'
        said = ''
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=10)
    assert (out.strip(), proc.returncode) == (said, code), err
    assert 'Traceback' not in err


def test_rclpy_context_rules(ros_router: str) -> None:
    from ros2lite.signals import SignalHandlerOptions, get_current_signal_handlers_options

    ctx = Context()
    with pytest.raises(RuntimeError, match='initialized'):
        ctx.shutdown()  # a context never initialised cannot be shut down
    with pytest.raises(RuntimeError):
        Context().init([], domain_id=-1)
    with pytest.raises(UnicodeEncodeError):
        Context().init(['prog', 'undecodable \udcc3'])
    with ctx:  # a `with` initialises it (as rclpy's does)
        assert ctx.ok() and ctx.get_domain_id() == ctx.domain_id
    assert not ctx.ok()
    ros2lite.init([])
    try:
        assert get_current_signal_handlers_options() == SignalHandlerOptions.ALL
    finally:
        ros2lite.shutdown()
    assert get_current_signal_handlers_options() == SignalHandlerOptions.NO
