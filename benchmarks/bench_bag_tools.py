"""Bag tools: `bag cut` of a 1 GiB bag (ten minutes of a 100 KB camera stream at 17 Hz and a
100 Hz IMU) to its middle minute, as the CLI runs it, against copying the whole file
(issue 37's bar: under 5 s). The cut copies the chunks inside the minute as bytes and
re-encodes only the two edge chunks."""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from common import report

RUNS = 3
T0 = 1_700_000_000_000_000_000


def _make_bag(bag: Path) -> None:
    from ros2lite.bag import Writer
    from ros2lite.interfaces import get_interface, serialize

    Image = get_interface("sensor_msgs/msg/CompressedImage")
    Imu = get_interface("sensor_msgs/msg/Imu")
    image = serialize(Image(format="jpeg", data=bytes(range(256)) * 400))  # ~100 KB
    imu = serialize(Imu())
    with Writer(bag) as w:
        cam = w.create_topic("/camera/image/compressed", "sensor_msgs/msg/CompressedImage")
        acc = w.create_topic("/imu", "sensor_msgs/msg/Imu")
        period = 10_000_000  # 100 Hz
        for i in range(600 * 100):
            t = T0 + i * period
            w.write_raw(acc, imu, t, t)
            if i % 6 == 0:  # ~17 Hz
                w.write_raw(cam, image, t + 1, t + 1)


def bench_cut() -> None:
    with tempfile.TemporaryDirectory(dir=os.environ.get("BENCH_TMP")) as tmp:
        bag = Path(tmp) / "big"
        _make_bag(bag)
        [mcap] = list(bag.glob("*.mcap"))
        size = mcap.stat().st_size
        if size < 10**9:
            raise RuntimeError(f"bag is only {size} bytes")
        cuts, copies = [], []
        for k in range(RUNS):
            out = Path(tmp) / f"cut{k}"
            start = time.perf_counter()
            subprocess.run(
                [
                    sys.executable,
                    "-m",
                    "ros2lite",
                    "bag",
                    "cut",
                    str(bag),
                    "-o",
                    str(out),
                    "--start",
                    "4:30",
                    "--end",
                    "5:30",
                ],
                check=True,
                stdout=subprocess.DEVNULL,
            )
            cuts.append(time.perf_counter() - start)
            copy = Path(tmp) / f"copy{k}.mcap"
            start = time.perf_counter()
            shutil.copyfile(mcap, copy)
            copies.append(time.perf_counter() - start)
            copy.unlink()
            shutil.rmtree(out)
    cut, copy = statistics.median(cuts), statistics.median(copies)
    print(f"  bag {size / 1e9:.2f} GB, copy {copy:.2f} s, cut {cut:.2f} s", file=sys.stderr)
    report("bag_cut_1gb_middle_minute", cut, "s", cut / copy)


BENCHES: dict[str, Any] = {"bag_cut": bench_cut}
