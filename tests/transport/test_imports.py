"""Cheap imports matter: the CLI imports these on every call."""

from __future__ import annotations

import subprocess
import sys


def test_keys_qos_attachment_and_daemon_do_not_import_zenoh() -> None:
    code = (
        "import sys\n"
        "import ros2lite.transport, ros2lite.transport.keys, ros2lite.transport.qos\n"
        "import ros2lite.transport.attachment, ros2lite.daemon\n"
        "import ros2lite.names, ros2lite.qos\n"
        "assert 'zenoh' not in sys.modules, 'zenoh imported'\n"
        "from ros2lite.transport.open import open_session\n"
        "assert 'zenoh' in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, timeout=60)


def test_transport_and_security_import_nothing_of_each_other() -> None:
    """Security is a value handed down: transport/ only encodes it, security/ only decides
    it (in-function and TYPE_CHECKING imports count too)."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "ros2lite"
    offenders = []
    for here, other in (("transport", "security"), ("security", "transport")):
        for path in sorted((root / here).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text())):
                names = []
                if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                    names = [node.module, *(f"{node.module}.{a.name}" for a in node.names)]
                elif isinstance(node, ast.Import):
                    names = [a.name for a in node.names]
                if any(n.startswith(f"ros2lite.{other}") for n in names):
                    offenders.append(f"{path.relative_to(root)}:{node.lineno}")
    assert offenders == []
