"""The lost-message table of `topic echo` stays bounded when every sample claims a new
publisher, and forgets publishers that left the graph."""

from __future__ import annotations

from ros2lite.monitor.stats import LostMessageCounter


def test_a_new_gid_per_sample_costs_a_bounded_table() -> None:
    counter = LostMessageCounter(max_publishers=100)
    for i in range(100_000):
        counter.observe(i, i.to_bytes(16, 'little'))
    assert counter.publishers == 100
    # the most recent publishers are the ones kept, and still counted
    counter.observe(99_999 + 5, (99_999).to_bytes(16, 'little'))
    assert counter.drain() == [(4, 4)]


def test_prune_keeps_only_publishers_in_the_graph() -> None:
    counter = LostMessageCounter()
    for n in range(10):
        counter.observe(1, bytes([n]) * 16)
    counter.prune({bytes([3]) * 16})
    assert counter.publishers == 1
    counter.observe(5, bytes([3]) * 16)
    assert counter.drain() == [(3, 3)]


def test_undrained_events_are_merged_not_piled_up() -> None:
    counter = LostMessageCounter()
    gid = b'\x01' * 16
    for i in range(0, 3 * LostMessageCounter.MAX_EVENTS * 2, 2):
        counter.observe(i, gid)
    events = counter.drain()
    assert len(events) == LostMessageCounter.MAX_EVENTS
    assert sum(change for change, _ in events) == counter.total == events[-1][1]
