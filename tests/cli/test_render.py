"""Names from outside reach a terminal escaped (R-W9/R-A33): a node name, a bag's topic or a
datagram holding terminal controls is shown as ``\\x1b…`` on a TTY, so it cannot clear the
screen or retitle the window; piped, the output stays byte for byte what came."""

from __future__ import annotations

import io
import os
import pty
import select
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from ros2lite.cli import render

from .graph_helpers import private_domain

HOSTILE = 'esc\x1b[31mRED\x1b]0;TITLE\x07'


class Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_shown_escapes_only_on_a_terminal() -> None:
    text = f'/{HOSTILE}\t\u202eevil\x9b2J\n'
    assert render.shown(text, Tty()) == '/esc\\x1b[31mRED\\x1b]0;TITLE\\x07\t\\u202eevil\\x9b2J\n'
    assert render.shown(text, io.StringIO()) == text


def on_tty(args: list[str], *, until: str = '', timeout: float = 20.0) -> str:
    """Run the CLI with stdout and stderr on a pseudo-terminal; what it wrote there."""
    controller, terminal = pty.openpty()
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', *args],
        stdin=subprocess.DEVNULL,
        stdout=terminal,
        stderr=terminal,
        env={**os.environ, 'ROS2LITE_NO_DAEMON': '1'},
    )
    os.close(terminal)
    out = b''
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            ready, _, _ = select.select([controller], [], [], 0.2)
            if ready:
                try:
                    chunk = os.read(controller, 4096)
                except OSError:  # the terminal closed: the process is done
                    break
                if not chunk:
                    break
                out += chunk
            elif proc.poll() is not None:
                break
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        os.close(controller)
    return out.decode(errors='replace')


def test_node_list_on_a_terminal(
    alien_session: Any, ros_router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    domain = private_domain(monkeypatch)
    key = f'@ros2_lv/{domain}/{os.urandom(16).hex()}/0/1/NN/%/%/{HOSTILE}'
    token = alien_session.liveliness().declare_token(key)
    try:
        out = ''
        deadline = time.monotonic() + 20
        while 'RED' not in out and time.monotonic() < deadline:
            out = on_tty(['node', 'list', '--no-daemon'])
        assert '/esc\\x1b[31mRED\\x1b]0;TITLE\\x07' in out, out
        assert '\x1b' not in out and '\x07' not in out
        piped = subprocess.run(
            [sys.executable, '-m', 'ros2lite', 'node', 'list', '--no-daemon'],
            capture_output=True,
            text=True,
            timeout=30,
        )
        # piped, nothing is rewritten by us (click itself drops colour codes off a terminal)
        assert '/escRED\x1b]0;TITLE\x07\n' in piped.stdout, piped.stdout
    finally:
        token.undeclare()


def test_bag_info_on_a_terminal(tmp_path: Path) -> None:
    from mcap.writer import Writer

    topic = '/t\x1b]0;BAGTITLE\x07\x1b[31m'
    path = tmp_path / 'hostile.mcap'
    with path.open('wb') as f:
        writer = Writer(f)
        writer.start(profile='ros2', library='test')
        schema = writer.register_schema(
            name='std_msgs/msg/String', encoding='ros2msg', data=b'string data'
        )
        channel = writer.register_channel(
            topic=topic, message_encoding='cdr', schema_id=schema, metadata={}
        )
        writer.add_message(
            channel_id=channel, log_time=1, publish_time=1, data=b'\0\1\0\0\1\0\0\0\0'
        )
        writer.finish()
    for args in (['bag', 'info', str(path)], ['bag', 'info', '--topic-name', str(path)]):
        out = on_tty(args)
        assert '/t\\x1b]0;BAGTITLE\\x07\\x1b[31m' in out, out
        assert '\x1b' not in out and '\x07' not in out


def test_multicast_datagram_on_a_terminal() -> None:
    import socket

    from tests.spinning import free_port
    from tests.tools.test_multicast import multicast_on_loopback

    port = free_port()
    if not multicast_on_loopback(port):
        pytest.skip('this machine has no multicast route on loopback')
    controller, terminal = pty.openpty()
    proc = subprocess.Popen(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'multicast',
            'receive',
            '--port',
            str(port),
            '--interface',
            '127.0.0.1',
            '-t',
            '20',
        ],
        stdin=subprocess.DEVNULL,
        stdout=terminal,
        stderr=terminal,
    )
    os.close(terminal)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton('127.0.0.1'))
    sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
    out = b''
    try:
        deadline = time.monotonic() + 20
        while b'Received' not in out and time.monotonic() < deadline:
            sock.sendto(b'\xff\xfe\x80garbage\x1b]0;MCTITLE\x07', ('225.0.0.1', port))
            if select.select([controller], [], [], 0.2)[0]:
                try:
                    out += os.read(controller, 4096)
                except OSError:
                    break
    finally:
        sock.close()
        proc.wait(timeout=20)
        os.close(controller)
    text = out.decode(errors='replace')
    assert 'garbage\\x1b]0;MCTITLE\\x07' in text, text
    assert '\x1b' not in text
