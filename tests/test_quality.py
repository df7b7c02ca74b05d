"""House rules a machine can check: lint, types, and the library/CLI boundary."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_clean() -> None:
    proc = subprocess.run(
        [sys.executable, '-m', 'ruff', 'check', 'ros2lite', 'tests', 'benchmarks'],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_ruff_format_clean() -> None:
    proc = subprocess.run(
        [sys.executable, '-m', 'ruff', 'format', '--check', 'ros2lite', 'tests', 'benchmarks'],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_mypy_clean() -> None:
    proc = subprocess.run([sys.executable, '-m', 'mypy'], cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_only_cli_imports_click_or_rich() -> None:
    """Outside cli/ nothing imports click or rich, save the demos' views (`*_view.py` under
    demos/), which may import rich lazily: indented, inside the function that draws."""
    pattern = re.compile(r'^\s*(import|from)\s+(click|rich)\b', re.MULTILINE)
    top_level = re.compile(r'^(import|from)\s+rich\b|^\s*(import|from)\s+click\b', re.MULTILINE)
    offenders = []
    for p in (ROOT / 'ros2lite').rglob('*.py'):
        parts = p.relative_to(ROOT / 'ros2lite').parts
        if parts[0] == 'cli':
            continue
        view = parts[0] == 'demos' and p.name.endswith('_view.py')
        if (top_level if view else pattern).search(p.read_text()):
            offenders.append(str(p.relative_to(ROOT)))
    assert offenders == []


def test_only_transport_imports_zenoh() -> None:
    """One seam to Zenoh: every declaration, put, query and session lives in transport/."""
    pattern = re.compile(r'^\s*(import|from)\s+zenoh\b', re.MULTILINE)
    offenders = [
        str(p.relative_to(ROOT))
        for p in (ROOT / 'ros2lite').rglob('*.py')
        if p.relative_to(ROOT / 'ros2lite').parts[0] != 'transport'
        and pattern.search(p.read_text())
    ]
    assert offenders == []
