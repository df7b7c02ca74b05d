"""`action info`: servers are feedback publishers, clients feedback subscribers."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from tests.action.alien import FEEDBACK_HASH, FIB, AlienFibonacciServer
from tests.spinning import wait_until


def test_info(
    run: Callable[..., Any], alien_server: AlienFibonacciServer, alien_session: Any
) -> None:
    import os

    d, zid = os.environ['ROS_DOMAIN_ID'], alien_session.info.zid()
    # an alien client node: a feedback subscription token is all rcl_action looks at
    lv = f'@ros2_lv/{d}/{zid}/7'
    tokens = [
        alien_session.liveliness().declare_token(t)
        for t in (
            f'{lv}/7/NN/%/%robot/fib_client',
            f'{lv}/8/MS/%/%robot/fib_client/%alien_fib%_action%feedback/{FIB}_FeedbackMessage_/'
            f'{FEEDBACK_HASH}/::,10:,:,:,,',
        )
    ]
    try:
        wait_until(
            lambda: 'Action clients: 1' in run('action', 'info', '/alien_fib').out, timeout=15
        )
        info = run('action', 'info', '/alien_fib')
        assert info.code == 0
        assert info.out == (
            'Action: /alien_fib\nAction clients: 1\n    /robot/fib_client\n'
            'Action servers: 1\n    /alien_action_server\n'
        )
        assert run('action', 'info', 'alien_fib', '-t').out == (
            'Action: alien_fib\nAction clients: 1\n'
            '    /robot/fib_client [example_interfaces/action/Fibonacci]\n'
            'Action servers: 1\n'
            '    /alien_action_server [example_interfaces/action/Fibonacci]\n'
        )
        assert (
            run('action', 'info', '/alien_fib', '-c').out
            == 'Action: /alien_fib\nAction clients: 1\nAction servers: 1\n'
        )
    finally:
        for token in tokens:
            token.undeclare()
    nobody = run('action', 'info', '/nobody')
    assert (nobody.code, nobody.out) == (
        0,
        'Action: /nobody\nAction clients: 0\nAction servers: 0\n',
    )
    bad = run('action', 'info', '/bad name')
    assert bad.code == 1 and bad.out == '' and len(bad.err.splitlines()) == 1
