"""`security generate_policy` from a live graph, and its output fed to `generate_artifacts`:
the permissions made that way are enough for the same nodes to run on a secured graph."""

from __future__ import annotations

import os
import sys
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path
from typing import Any

from tests.spinning import free_port, wait_until
from tests.transport.test_security import environ, start_node


def test_no_nodes(run: Callable[..., Any], ros_router: str, tmp_path: Path) -> None:
    result = run('security', 'generate_policy', str(tmp_path / 'p.xml'))
    assert result.code == 1
    assert result.err == 'No nodes detected in the ROS graph. No policy file was generated.\n'
    assert not (tmp_path / 'p.xml').exists()


def test_round_trip(
    run: Callable[..., Any], ros_router: str, processes: Any, tmp_path: Path
) -> None:
    import zenoh

    from ros2lite.daemon.router import router_security
    from ros2lite.graph import snapshot
    from ros2lite.transport.config import router_config
    from ros2lite.transport.open import open_session

    for exe, enclave in (('talker', '/gp/talker'), ('listener', '/gp/listener')):
        processes.start(
            [
                sys.executable,
                '-m',
                'ros2lite',
                'run',
                'demo_nodes_py',
                exe,
                '--ros-args',
                '--enclave',
                enclave,
            ]
        )
    session = open_session()
    try:
        domain = int(os.environ['ROS_DOMAIN_ID'])

        def both_visible() -> bool:  # by enclave: other tests' talkers may still be about
            seen = {(e.enclave, e.kind.value, e.topic_name) for e in snapshot(session, domain)}
            return {('/gp/talker', 'MP', '/chatter'), ('/gp/listener', 'MS', '/chatter')} <= seen

        wait_until(both_visible, timeout=20)
    finally:
        session.close()
    policy = tmp_path / 'policy.xml'
    result = run('security', 'generate_policy', str(policy))
    assert result.code == 0, result.err
    root = ET.fromstring(policy.read_text())

    def listed(enclave: str, node: str, path: str) -> list[str]:
        found = root.find(f'enclaves/enclave[@path="{enclave}"]/profiles/profile[@node="{node}"]')
        assert found is not None, policy.read_text()
        return [e.text or '' for e in found.findall(path)]

    assert listed('/gp/talker', 'talker', 'topics[@publish="ALLOW"]/topic') == [
        'chatter',
        'parameter_events',
        'rosout',
    ]
    assert listed('/gp/listener', 'listener', 'topics[@subscribe="ALLOW"]/topic') == ['chatter']
    assert '~/get_parameters' in listed('/gp/talker', 'talker', 'services[@reply="ALLOW"]/service')
    for proc in processes.procs:
        processes.stop(proc)

    keystore = tmp_path / 'ks'
    made = run('security', 'generate_artifacts', '-k', str(keystore), '-p', str(policy))
    assert made.code == 0, made.err
    assert run('security', 'list_enclaves', str(keystore)).out == '/gp/listener\n/gp/talker\n'

    # the generated permissions run the same nodes on a secured graph
    secure = {
        'ROS_SECURITY_ENABLE': 'true',
        'ROS_SECURITY_STRATEGY': 'Enforce',
        'ROS_SECURITY_KEYSTORE': str(keystore),
        'ROS2LITE_ROUTER': f'tls/127.0.0.1:{free_port()}',
        'ROS_DOMAIN_ID': os.environ['ROS_DOMAIN_ID'],
    }
    router = zenoh.open(router_config(env=secure, security=router_security(secure)))
    procs: list[Any] = []
    try:
        env = environ(secure)
        listener = start_node(procs, env, 'listener', '/gp/listener')
        start_node(procs, env, 'talker', '/gp/talker')
        listener.wait_for('I heard: [Hello World:')
    finally:
        for proc in procs:
            proc.terminate()
            proc.wait(timeout=5)
        router.close()
