"""`bag convert` on the command line: repeated `-i URI [STORAGE_ID]`, the output-options file,
and ros2bag's one-line errors."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from ros2lite.bag import Reader

DATA = Path(__file__).parents[2] / "bag" / "data"


def convert(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "ros2lite", "bag", "convert", *args],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=cwd,
    )


def test_inputs_with_and_without_storage_id(tmp_path: Path) -> None:
    (tmp_path / "out.yaml").write_text(
        "output_bags:\n- uri: strings\n  topics: [c_strings]\n- uri: everything\n  all: true\n"
    )
    a, b = DATA / "mcap" / "convert_a", DATA / "mcap" / "convert_b"
    result = convert("-i", str(a), "-i", str(b), "mcap", "-o", "out.yaml", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with Reader(tmp_path / "strings") as r:
        assert r.message_count == 50
    with Reader(tmp_path / "everything") as r:
        assert r.message_count == 225


def test_errors_are_one_line(tmp_path: Path) -> None:
    a = str(DATA / "mcap" / "convert_a")
    (tmp_path / "out.yaml").write_text("output_bags:\n- uri: x\n  all_topics: yes please\n")
    (tmp_path / "good.yaml").write_text("output_bags:\n- uri: x\n  all_topics: true\n")
    for args, message in [
        (["-i", a, "mcap", "extra", "-o", "out.yaml"], "--input expects 1 or 2 arguments, 3"),
        (["-i", a, "ros1", "-o", "out.yaml"], "Unknown storage id 'ros1'"),
        (["-i", a, "-o", "missing.yaml"], "Cannot read 'missing.yaml'"),
        (["-i", a, "-o", "out.yaml"], "'all_topics' must be true or false"),
        (["-i", str(tmp_path / "nothing"), "-o", "good.yaml"], "does not exist"),
    ]:
        result = convert(*args, cwd=tmp_path)
        assert result.returncode == 1, (args, result.stderr)
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("[ERROR] [ros2bag]: "), result.stderr
        assert message in lines[0], (message, lines[0])
    assert not (tmp_path / "x").exists()
