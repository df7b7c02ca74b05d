"""The twist multiplexer's rule alone: the highest-priority input heard within its timeout
drives; a lower one drives again once the higher one's timeout has passed."""

from __future__ import annotations

from ros2lite.sim.mux import TwistMux

TIAGO_LIKE = (('joy_vel', 100, 0.5), ('key_vel', 90, 0.5), ('nav_vel', 10, 0.5))


def test_a_higher_input_outranks_a_lower_one_within_its_timeout() -> None:
    mux = TwistMux(TIAGO_LIKE)
    assert mux.names == ['joy_vel', 'key_vel', 'nav_vel']
    assert mux.admits('nav_vel', 0.75)
    assert mux.admits('key_vel', 1.0)
    assert not mux.admits('nav_vel', 1.25)
    assert not mux.admits('nav_vel', 1.5)  # key_vel heard 0.5 s ago: still live
    assert mux.admits('nav_vel', 1.75)  # key_vel's timeout has passed
    assert mux.admits('joy_vel', 2.0)  # the highest always drives


def test_an_input_without_timeout_stays_live_once_heard() -> None:
    mux = TwistMux((('a', 2, 0.0), ('b', 1, 0.5)))
    assert mux.admits('b', 0.0)
    assert mux.admits('a', 1.0)
    assert not mux.admits('b', 100.0)


def test_a_lone_input_always_drives() -> None:
    mux = TwistMux((('cmd_vel', 0, 0.0),))
    assert mux.admits('cmd_vel', 0.0)
    assert mux.admits('cmd_vel', 5.0)
