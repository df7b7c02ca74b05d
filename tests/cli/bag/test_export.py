"""`bag export` on the command line: the format from the option or the output's suffix, an
image topic to PNG files by default, and one line for what cannot be done (pyarrow missing)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bag import Writer
from ros2lite.msgs.sensor_msgs.msg import Image

CDR_TEST = Path(__file__).parents[2] / "bag" / "data" / "mcap" / "cdr_test"


def test_format_from_option_or_suffix(run: Any, tmp_path: Path) -> None:
    result = run("bag", "export", str(CDR_TEST), "/test_topic", "-o", str(tmp_path / "t.csv"))
    assert result.code == 0, result.err
    assert "Exported 3 messages of '/test_topic'" in result.out
    assert len((tmp_path / "t.csv").read_text().splitlines()) == 3
    result = run(
        "bag", "export", str(CDR_TEST), "test_topic", "--jsonl", "-o", str(tmp_path / "t.txt"),
        "--start", "0.1",
    )  # fmt: skip
    assert result.code == 0, result.err
    assert (tmp_path / "t.txt").read_text().count("\n") == 1
    with Writer(tmp_path / "bag") as w:
        w.write("/img", Image(width=1, height=1, encoding="mono8", step=1, data=b"\x80"), 7)
    assert run("bag", "export", str(tmp_path / "bag"), "/img", "-o", str(tmp_path / "f")).code == 0
    assert [p.name for p in (tmp_path / "f").iterdir()] == ["000000_0.000000007.png"]


def test_errors_are_one_line(run: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # as if the extra were not installed
    for args, message in [
        (["/test_topic", "-o", str(tmp_path / "x")], "Give --csv, --jsonl, --parquet or --png"),
        (["/test_topic", "-o", str(tmp_path / "x.parquet")], "pip install 'ros2lite[parquet]'"),
        (["/nope", "--csv", "-o", str(tmp_path / "x")], "no topic '/nope'"),
        (["/test_topic", "--png", "-o", str(tmp_path / "x")], "only sensor_msgs/msg/Image"),
    ]:
        result = run("bag", "export", str(CDR_TEST), *args)
        assert result.code != 0 and message in result.err, (args, result.err)
        assert len(result.err.strip().splitlines()) == 1
