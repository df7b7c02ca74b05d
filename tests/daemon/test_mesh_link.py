"""Two meshed daemons across a lossy link that is cut for 5 s (network namespaces, a veth
pair, tc/nftables): reliable delivery loses nothing, the flow is back at once when the link
is, the recorded bag is whole, and services answer across the link afterwards.

The scenario lives in benchmarks/bench_link.py, which prints the same numbers."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[2] / 'benchmarks'


def test_reliable_across_a_lossy_cut_link(tmp_path: Path) -> None:
    sys.path.insert(0, str(BENCHMARKS))
    try:
        from bench_link import COUNT, Unavailable, cross
    finally:
        sys.path.remove(str(BENCHMARKS))
    try:
        outcome = cross(tmp_path)
    except Unavailable as exc:
        pytest.skip(f'no network namespaces here: {exc}')
    assert outcome.published == COUNT
    for who in ('reliable', 'echo'):
        assert outcome.missing(who) == 0, (who, outcome.impairment)
    assert outcome.bag == COUNT
    assert 0 <= outcome.recovery < 2.0, outcome.recovery
    assert outcome.hz_after_cut
    assert outcome.param_get == 'Boolean value is: False', outcome.param_get
    assert outcome.service_call
