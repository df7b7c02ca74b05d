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
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

from bench_node import N_MESSAGES, RUNS, STRING, _key, node_run
from common import environment, free_port, report, router_process

CONNECTS = 30
ENCLAVE = '/bench/node'


def _overlaid(values: dict[str, str | None]) -> dict[str, str]:
    """This process' environment with `values` set (None: removed)."""
    env = {k: v for k, v in os.environ.items() if k not in values}
    env.update({k: v for k, v in values.items() if v is not None})
    return env


def _environment(values: dict[str, str | None]) -> contextlib.AbstractContextManager[None]:
    return environment(_overlaid(values))


def _router(endpoint: str, env: dict[str, str | None]) -> contextlib.AbstractContextManager[Any]:
    return router_process(endpoint, _overlaid(env), configured=True)


def _connect_ms(env: dict[str, str | None]) -> float:
    from ros2lite.daemon.security import session_security
    from ros2lite.transport.open import open_session

    times = []
    with _environment(env):
        for _ in range(CONNECTS):
            t0 = time.perf_counter()
            session = open_session(mode='client', security=session_security())
            times.append(time.perf_counter() - t0)
            session.close()
    return statistics.median(times) * 1000


def bench_security() -> None:
    from ros2lite.security.keystore import create_enclave, create_keystore

    domain = str(random.randint(100, 232))
    plain_endpoint = f'tcp/127.0.0.1:{free_port()}'
    tls_endpoint = f'tls/127.0.0.1:{free_port()}'
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
                        key = _key(STRING, '/bench_chatter')  # in this graph's domain
                        rates[name].append(node_run('string', N_MESSAGES, key, 'spin'))
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


BENCHES = {'security': bench_security}
