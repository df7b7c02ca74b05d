"""`bag info`, `bag reindex` and `bag list` print what ros2cli prints, for rosbag2's own bags."""

from __future__ import annotations

import os
import shutil
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bag import Writer
from ros2lite.interfaces import get_interface

DATA = Path(__file__).parents[2] / "bag" / "data"


@pytest.fixture(autouse=True)
def utc() -> Iterator[None]:
    saved = os.environ.get("TZ")
    os.environ["TZ"] = "UTC"
    time.tzset()
    yield
    if saved is None:
        os.environ.pop("TZ", None)
    else:
        os.environ["TZ"] = saved
    time.tzset()


def test_info_layout_of_a_rosbag2_bag(run: Any) -> None:
    result = run("bag", "info", str(DATA / "mcap" / "bag_with_topics_and_service_events"))
    assert result.code == 0
    size = sum(
        p.stat().st_size for p in (DATA / "mcap" / "bag_with_topics_and_service_events").iterdir()
    )
    assert result.out == (
        "\n"
        "Files:             bag_with_topics_and_service_events.mcap\n"
        f"Bag size:          {size / 1024:.1f} KiB\n"
        "Storage id:        mcap\n"
        "ROS Distro:        \n"
        "Duration:          0.070653944s\n"
        "Start:             Nov  7 2023 08:30:36.270074454 (1699345836.270074454)\n"
        "End:               Nov  7 2023 08:30:36.340728398 (1699345836.340728398)\n"
        "Messages:          2\n"
        "Topic information: Topic: /events/write_split | Type: "
        "rosbag2_interfaces/msg/WriteSplitEvent | Count: 0 | Serialization Format: cdr\n"
        "                   Topic: /test_topic1 | Type: test_msgs/msg/Strings | Count: 1 | "
        "Serialization Format: cdr\n"
        "                   Topic: /test_topic2 | Type: test_msgs/msg/Strings | Count: 1 | "
        "Serialization Format: cdr\n"
        "Service:           2\n"
        "Service information: Service: /test_service1 | Type: test_msgs/srv/BasicTypes | "
        "Event Count: 4 | Serialization Format: cdr\n"
        "                     Service: /test_service2 | Type: test_msgs/srv/BasicTypes | "
        "Event Count: 4 | Serialization Format: cdr\n"
    )


def test_info_of_split_bags_sorting_verbose_names_and_no_metadata(run: Any) -> None:
    bag = DATA / "mcap" / "wbag"
    by_count = run("bag", "info", str(bag), "--sort", "count")
    counts = [
        int(line.split("Count: ")[1].split(" ")[0])
        for line in by_count.out.splitlines()
        if "Count: " in line
    ]
    assert counts == sorted(counts) and sum(counts) == 6074
    assert by_count.out.splitlines()[1:6] == [
        "Files:             wbag_0.mcap",
        *(" " * 19 + f"wbag_{i}.mcap" for i in range(1, 5)),
    ]
    verbose = run("bag", "info", "-v", str(DATA / "mcap" / "talker"))
    assert (
        "Topic: /topic | Type: std_msgs/msg/String | Count: 10 | Size Contribution: "
        "240 B | Serialization Format: cdr"
    ) in verbose.out
    names = run("bag", "info", "-t", str(DATA / "mcap" / "talker"))
    assert names.out == "/parameter_events\n/rosout\n/topic\n"
    both = run("bag", "info", "-t", "-v", str(DATA / "mcap" / "talker"))
    assert "The '-t' parameter will be ignored." in both.err and "Size Contribution" in both.out
    nometa = run("bag", "info", str(DATA / "mcap" / "multiple_files"))
    assert "Messages:          3177\n" in nometa.out
    sqlite = run("bag", "info", str(DATA / "sqlite3" / "talker"))
    assert "Storage id:        sqlite3\n" in sqlite.out and "Messages:          20\n" in sqlite.out


def test_info_reads_only_the_summary_of_our_bag(run: Any, tmp_path: Path) -> None:
    String = get_interface("std_msgs/msg/String")
    with Writer(tmp_path / "ours") as bag:
        for i in range(10):
            bag.write("/chatter", String(data="x"), 1_700_000_000_000_000_000 + i * 10**8)
    (tmp_path / "ours" / "metadata.yaml").unlink()  # force the MCAP summary path
    result = run("bag", "info", str(tmp_path / "ours"))
    assert result.code == 0
    lines = result.out.splitlines()
    assert lines[3:9] == [
        "Storage id:        mcap",
        "ROS Distro:        jazzy",
        "Duration:          0.900000000s",
        "Start:             Nov 14 2023 22:13:20.000000000 (1700000000.000000000)",
        "End:               Nov 14 2023 22:13:20.900000000 (1700000000.900000000)",
        "Messages:          10",
    ]


def test_info_errors(run: Any, tmp_path: Path) -> None:
    missing = run("bag", "info", str(tmp_path / "nope"))
    assert (missing.code, missing.err) == (
        1,
        f"[ERROR] [ros2bag]: Bag path '{tmp_path / 'nope'}' does not exist!\n",
    )
    (tmp_path / "x.mcap").write_bytes(b"garbage")
    bad = run("bag", "info", str(tmp_path / "x.mcap"))
    assert bad.code == 1 and bad.err.startswith("[ERROR] [ros2bag]: ") and bad.err.count("\n") == 1


def test_reindex_and_list(run: Any, tmp_path: Path) -> None:
    bag = tmp_path / "multiple_files"
    shutil.copytree(DATA / "mcap" / "multiple_files", bag)
    assert run("bag", "reindex", str(bag)).code == 0
    info = run("bag", "info", str(bag))
    assert "Messages:          3177\n" in info.out
    not_dir = run("bag", "reindex", str(bag / "metadata.yaml"))
    assert (not_dir.code, not_dir.err) == (1, "[ERROR] [ros2bag]: Must specify a bag directory\n")
    assert run("bag", "list", "storage").out == "mcap\nsqlite3\nrosbag1\n"
    verbose = run("bag", "list", "storage", "-v").out
    assert verbose.startswith("name: mcap\n\tdescription: ")
    assert run("bag", "list", "compressor").out == "zstd\n"
