"""What security costs: node pub→sub throughput on a secured graph against the unsecured one,
and the time to open a session over TLS (mutual authentication) against plain TCP, measured
in the same run.

Arrangement: bench_node's (a router process on a free loopback port, the subscribing node
here, the publishing node in a child process, lossless KEEP_ALL `std_msgs/String`), run
against three graphs, interleaved so drifting load hits all alike:

* ``unsecured``: the default, peer sessions, data on a direct loopback link (the baseline);
* ``unsecured_client``: the same nodes forced to client mode (``ZENOH_CONFIG_OVERRIDE``), so
  every sample crosses the router, as on a secured graph: this splits the cost of routing
  from the cost of TLS and access control;
* ``secured``: ``ROS_SECURITY_ENABLE=true``, Enforce, a temporary keystore: TLS links with
  mutual authentication to a router applying access control.

Connection time: median wall time of opening (and closing) a client session, 30 times, to
a TCP router and to a TLS router (the TLS one presenting and checking certificates).
"""

from __future__ import annotations

import contextlib
import os
import random
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

from bench_node import RUNS, node_run
from common import report

ROUTER = r'''
import sys, os, zenoh
from ros2lite.transport.config import router_config
zenoh.init_log_from_env_or('error')
router = zenoh.open(router_config(sys.argv[1]))
print('ready', flush=True)
sys.stdin.read()
router.close()
'''
CONNECTS = 30
ENCLAVE = '/bench/node'


def _port() -> int:
    with socket.socket() as sock:
        sock.bind(('127.0.0.1', 0))
        return int(sock.getsockname()[1])


@contextlib.contextmanager
def _environment(values: dict[str, str | None]) -> Iterator[None]:
    saved = {k: os.environ.get(k) for k in values}
    for key, value in values.items():
        if value is None:
            os.environ.pop(key, None)
        else:
            os.environ[key] = value
    try:
        yield
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


@contextlib.contextmanager
def _router(endpoint: str, env: dict[str, str | None]) -> Iterator[None]:
    with _environment(env):
        proc = subprocess.Popen(
            [sys.executable, '-c', ROUTER, endpoint],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
    assert proc.stdin is not None and proc.stdout is not None
    try:
        if proc.stdout.readline().strip() != 'ready':
            raise RuntimeError(f'benchmark router at {endpoint} did not start')
        yield
    finally:
        proc.stdin.close()
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def _connect_ms(env: dict[str, str | None]) -> float:
    from ros2lite.transport.config import open_session

    times = []
    with _environment(env):
        for _ in range(CONNECTS):
            t0 = time.perf_counter()
            session = open_session(mode='client')
            times.append(time.perf_counter() - t0)
            session.close()
    return statistics.median(times) * 1000


def bench_security() -> None:
    from ros2lite.security.keystore import create_enclave, create_keystore

    domain = str(random.randint(100, 232))
    plain_endpoint = f'tcp/127.0.0.1:{_port()}'
    tls_endpoint = f'tls/127.0.0.1:{_port()}'
    base: dict[str, str | None] = {
        'ROS_DOMAIN_ID': domain,
        'ZENOH_CONFIG_OVERRIDE': None,
        'ZENOH_SESSION_CONFIG_URI': None,
        'ROS_SECURITY_ENABLE': None,
        'ROS2LITE_NO_DAEMON': '1',
    }
    with tempfile.TemporaryDirectory() as tmp:
        keystore = Path(tmp) / 'ks'
        create_keystore(keystore, {'ROS_DOMAIN_ID': domain})
        create_enclave(keystore, ENCLAVE, {'ROS_DOMAIN_ID': domain})
        plain = {**base, 'ROS2LITE_ROUTER': plain_endpoint}
        client = {**plain, 'ZENOH_CONFIG_OVERRIDE': 'mode="client"'}
        secured = {
            **base,
            'ROS2LITE_ROUTER': tls_endpoint,
            'ROS_SECURITY_ENABLE': 'true',
            'ROS_SECURITY_STRATEGY': 'Enforce',
            'ROS_SECURITY_KEYSTORE': str(keystore),
            'ROS_SECURITY_ENCLAVE_OVERRIDE': ENCLAVE,
        }
        graphs = {'unsecured': plain, 'unsecured_client': client, 'secured': secured}
        rates: dict[str, list[float]] = {name: [] for name in graphs}
        with _router(plain_endpoint, plain), _router(tls_endpoint, secured):
            for _ in range(RUNS):
                for name, env in graphs.items():
                    with _environment(env):
                        rates[name].append(node_run('', _string()))
            connect_tcp = _connect_ms(plain)
            connect_tls = _connect_ms(secured)
    medians = {name: statistics.median(values) for name, values in rates.items()}
    if os.environ.get('BENCH_NODE_VERBOSE'):
        print({name: [round(r) for r in values] for name, values in rates.items()})
    baseline = medians['unsecured']
    report(
        'security_pubsub_string_secured', medians['secured'], 'msg/s', medians['secured'] / baseline
    )
    report(
        'security_pubsub_string_unsecured_client',
        medians['unsecured_client'],
        'msg/s',
        medians['unsecured_client'] / baseline,
    )
    report('security_pubsub_string_unsecured', baseline, 'msg/s', 1.0)
    report('security_connect_tls', connect_tls, 'ms', connect_tls / connect_tcp)
    report('security_connect_tcp', connect_tcp, 'ms', 1.0)


def _string() -> object:
    from ros2lite.interfaces import get_interface

    return get_interface('std_msgs/msg/String')


BENCHES = {'security': bench_security}
