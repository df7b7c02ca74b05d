"""Which router and domain a process talks to, from the environment (no zenoh needed)."""

from __future__ import annotations

import ctypes
import errno
import sys

import pytest

from ros2lite.transport import endpoints as ep
from ros2lite.transport.errors import ConfigError


def test_reading_them_loads_no_zenoh() -> None:
    import subprocess

    code = (
        'import sys, ros2lite.transport.endpoints as e; '
        'e.router_endpoint(); e.domain_id(); print("zenoh" in sys.modules)'
    )
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == 'False'


def _strtoul_as_rcl(raw: str) -> int | None:
    """rcl_get_default_domain_id on `raw`, through the C library's own strtoul (None where
    rcl refuses the value); SIZE_MAX is rmw's default domain, which rmw_zenoh reads as 0."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.strtoul.restype = ctypes.c_ulong
    libc.strtoul.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p), ctypes.c_int]
    if raw == '':
        return 0
    end = ctypes.c_char_p()
    ctypes.set_errno(0)
    number = libc.strtoul(raw.encode(), ctypes.byref(end), 0)
    if number == 0 and end.value:
        return None
    if number == 2**64 - 1 and ctypes.get_errno() == errno.ERANGE:
        return None
    return 0 if number == 2**64 - 1 else number


# rcl's cases: octal, hex, signs, blanks, junk after a number, overflow, DDS's 232 limit
DOMAIN_TABLE = [
    '',
    '0',
    '7',
    ' 7 ',
    '\t12',
    '010',
    '08',
    '0x2b',
    '0X2B',
    '0x',
    '43abc',
    'abc',
    '0abc',
    '1e3',
    '5.5',
    '+5',
    '-0',
    '-1',
    '-2',
    '232',
    '233',
    '999',
    '18446744073709551615',
    '18446744073709551616',
    ' ',
    '00',
    '0777',
]


@pytest.mark.parametrize('raw', DOMAIN_TABLE)
def test_domain_id_as_rcl_reads_it(raw: str) -> None:
    expected = _strtoul_as_rcl(raw)
    if expected is None:
        with pytest.raises(ConfigError, match='ROS_DOMAIN_ID is'):
            ep.domain_id({'ROS_DOMAIN_ID': raw})
    else:
        assert ep.domain_id({'ROS_DOMAIN_ID': raw}) == expected


def test_domain_id_table_spot_checks() -> None:
    """The table's oracle itself, on the values the findings name."""
    assert [_strtoul_as_rcl(v) for v in ('010', '0x2b', '43abc', 'abc', '-1', '233')] == [
        8,
        43,
        43,
        None,
        0,
        233,
    ]


def test_router_endpoint() -> None:
    assert ep.router_endpoint(env={}) == "tcp/127.0.0.1:7447"
    assert ep.router_endpoint(env={"ROS2LITE_ROUTER": "tcp/127.0.0.1:9"}) == "tcp/127.0.0.1:9"
    assert ep.router_endpoint("tcp/[::1]:5", env={"ROS2LITE_ROUTER": "x/y"}) == "tcp/[::1]:5"
    with pytest.raises(ConfigError, match="protocol"):
        ep.router_endpoint("localhost:7447", env={})


def test_endpoint_host_port() -> None:
    assert ep.endpoint_host_port("tcp/127.0.0.1:7447") == ("tcp", "127.0.0.1", 7447)
    assert ep.endpoint_host_port("tcp/[::1]:7447#iface=lo") == ("tcp", "::1", 7447)
    assert ep.endpoint_host_port("tls/localhost:1?x=y") == ("tls", "localhost", 1)
    assert ep.endpoint_host_port("unixsock-stream//tmp/sock") is None
    assert ep.endpoint_host_port("nonsense") is None


def test_router_check_attempts() -> None:
    assert ep.router_check_attempts({}) == 1
    assert ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": " 3 "}) == 3
    assert ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": "0"}) == 0
    assert ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": "-1"}) == -1
    with pytest.raises(ConfigError, match="ZENOH_ROUTER_CHECK_ATTEMPTS must be an integer"):
        ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": "many"})


def test_secure_default_is_handed_down() -> None:
    """transport knows nothing of security: whether the default router is the TLS one is
    the caller's value (ros2lite.daemon.connect decides it from ros2lite.security)."""
    assert ep.router_endpoint(env={}, secure=True) == "tls/127.0.0.1:7447"
    assert ep.router_endpoint(env={"ROS_SECURITY_ENABLE": "true"}) == "tcp/127.0.0.1:7447"
    assert ep.router_endpoint("tcp/127.0.0.1:9", env={}, secure=True) == "tcp/127.0.0.1:9"
