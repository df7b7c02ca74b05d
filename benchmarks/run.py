"""ros2lite benchmarks: each line is `name value unit ratio-vs-baseline`.

Every baseline is measured in the same run on the same machine, so ratios are comparable across
machines even when absolute numbers are not. Each `bench_*.py` module next to this file exports
`BENCHES = {name: function}`; `python benchmarks/run.py [name …]` runs all or some of them.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent


def discover() -> dict[str, Callable[[], Any]]:
    sys.path.insert(0, str(HERE))
    benches: dict[str, Callable[[], Any]] = {}
    for path in sorted(HERE.glob('bench_*.py')):
        benches.update(importlib.import_module(path.stem).BENCHES)
    return benches


def main() -> None:
    benches = discover()
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('only', nargs='*', help=f'benchmarks to run: {", ".join(benches)}')
    args = parser.parse_args()
    unknown = [n for n in args.only if n not in benches]
    if unknown:
        parser.error(f'unknown benchmark(s): {", ".join(unknown)}')
    for name, fn in benches.items():
        if not args.only or name in args.only:
            fn()


if __name__ == '__main__':
    main()
