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
        "from ros2lite.transport.config import open_session\n"
        "assert 'zenoh' in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, timeout=60)
