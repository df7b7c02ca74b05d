"""`bag cut` and `bag filter` on the command line: times as offsets, durations and absolute
times, topic choices, what the new bag holds, and ros2bag's one-line errors."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ros2lite.bag import Reader, Writer
from ros2lite.msgs.std_msgs.msg import String

T0 = 1_700_000_000_000_000_000
S = 1_000_000_000


def make_bag(path: Path) -> None:
    with Writer(path, chunk_size=2048) as w:
        for i in range(200):  # 20 s at 10 Hz on /a, 5 Hz on /b
            w.write("/a", String(data=f"a{i}"), T0 + i * S // 10)
            if i % 2 == 0:
                w.write("/b", String(data=f"b{i}"), T0 + i * S // 10 + 1)


def counts(bag: Path) -> dict[str, int]:
    with Reader(bag) as r:
        return {
            t.topic_metadata.name: t.message_count for t in r.metadata.topics_with_message_count
        }


def test_cut_by_offset_duration_and_absolute_time(run: Any, tmp_path: Path) -> None:
    make_bag(tmp_path / "src")
    result = run(
        "bag",
        "cut",
        str(tmp_path / "src"),
        "-o",
        str(tmp_path / "c1"),
        "--start",
        "5",
        "--end",
        "0:10",
    )
    assert result.code == 0, result.err
    assert "Wrote 76 messages on 2 topics" in result.out and "chunks copied" in result.out
    assert counts(tmp_path / "c1") == {"/a": 51, "/b": 25}
    absolute = f"{(T0 + 15 * S) / S:.1f}"
    result = run(
        "bag", "cut", str(tmp_path / "src"), "-o", str(tmp_path / "c2"), "--start", absolute
    )
    assert result.code == 0, result.err
    assert counts(tmp_path / "c2") == {"/a": 50, "/b": 25}


def test_filter_by_topics_and_exclude(run: Any, tmp_path: Path) -> None:
    make_bag(tmp_path / "src")
    assert (
        run(
            "bag", "filter", str(tmp_path / "src"), "-o", str(tmp_path / "f1"), "--topics", "/b"
        ).code
        == 0
    )
    assert counts(tmp_path / "f1") == {"/b": 100}
    result = run(
        "bag",
        "filter",
        str(tmp_path / "src"),
        "-o",
        str(tmp_path / "f2"),
        "--exclude",
        "/b",
        "--end",
        "1",
    )
    assert result.code == 0, result.err
    assert counts(tmp_path / "f2") == {"/a": 11}


def test_errors_are_one_line(run: Any, tmp_path: Path) -> None:
    make_bag(tmp_path / "src")
    src = str(tmp_path / "src")
    for args, message in [
        (["cut", src, "-o", str(tmp_path / "x"), "--start", "soon"], "Bad time 'soon'"),
        (["cut", src, "-o", str(tmp_path / "x"), "--start", "9", "--end", "3"], "before its start"),
        (["cut", src, "-o", src], "already exists"),
        (["cut", str(tmp_path / "none"), "-o", str(tmp_path / "x")], "does not exist"),
        (["filter", src, "-o", str(tmp_path / "x"), "--topics", "/zz"], "no topic /zz"),
        (["filter", src, "-o", str(tmp_path / "x")], "give --topics, --exclude or both"),
    ]:
        result = run("bag", *args)
        assert result.code != 0, args
        assert message in result.err and len(result.err.strip().splitlines()) == 1, (
            args,
            result.err,
        )
    assert not (tmp_path / "x").exists()
