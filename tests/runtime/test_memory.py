"""Nodes keep large freed buffers for reuse: publishing a large message no longer pays a page
fault per page of every buffer it makes; the user's own malloc settings win."""

from __future__ import annotations

import os
import subprocess
import sys
from typing import Any

import pytest

# a node publishing 1 MiB images: the tuning result and the minor page faults of 30 publishes
PROBE = r'''
import resource
from array import array
import ros2lite
from ros2lite.runtime.memory import keep_large_buffers
from ros2lite.msgs.sensor_msgs.msg import Image
ros2lite.init([])
node = ros2lite.Node('memory_probe', enable_rosout=False)
pub = node.create_publisher(Image, 'memory_probe', 10)
image = Image(height=512, width=512, encoding='rgba8', step=2048,
              data=array('B', bytes(range(256))) * 4096)
for _ in range(10):
    pub.publish(image)
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(30):
    pub.publish(image)
print(keep_large_buffers(), resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
ros2lite.shutdown()
'''


def _probe(**env: str) -> tuple[bool, int]:
    clean = {
        k: v
        for k, v in os.environ.items()
        if not k.startswith('MALLOC_') and k not in ('GLIBC_TUNABLES', 'ROS2LITE_MALLOC_TUNING')
    }
    out = subprocess.run(
        [sys.executable, '-c', PROBE],
        env={**clean, **env},
        capture_output=True,
        text=True,
        check=True,
        timeout=60,
    ).stdout.split()
    return out[0] == 'True', int(out[1])


@pytest.mark.skipif(not sys.platform.startswith('linux'), reason='glibc malloc tuning')
def test_large_messages_reuse_buffers_instead_of_mapping_them_per_message(
    ros_router: Any,
) -> None:
    tuned, faults = _probe()
    assert tuned
    untuned, faults_off = _probe(ROS2LITE_MALLOC_TUNING='0')
    assert not untuned
    # untuned, every publish maps fresh pages (hundreds of faults per 1 MiB buffer)
    assert faults_off > 30 * 200
    assert faults < faults_off / 10


@pytest.mark.skipif(not sys.platform.startswith('linux'), reason='glibc malloc tuning')
def test_the_users_own_malloc_settings_win(ros_router: Any) -> None:
    tuned, _ = _probe(MALLOC_TRIM_THRESHOLD_='1048576')
    assert not tuned


SINK = r'''
import ros2lite
from ros2lite.msgs.std_msgs.msg import String
ros2lite.init([])
node = ros2lite.Node('memory_sink', enable_rosout=False)
node.create_subscription(String, 'memory_big', lambda m: print(len(m.data), flush=True), 10)
print('ready', flush=True)
ros2lite.spin(node)
'''

# publishes 'small', then six 16 MiB strings, each once the sink (its output file: argv[1])
# said it had the one before
SOURCE = r'''
import sys, time
import ros2lite
from ros2lite.msgs.std_msgs.msg import String
ros2lite.init([])
node = ros2lite.Node('memory_source', enable_rosout=False)
pub = node.create_publisher(String, 'memory_big', 10)
def heard():
    return len(open(sys.argv[1]).read().split()) - 1
deadline = time.monotonic() + 30
while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
    time.sleep(0.05)
big = String(data='z' * (16 << 20))
for msg in [String(data='small')] + [big] * 6:
    before = heard()
    pub.publish(msg)
    deadline = time.monotonic() + 10
    while heard() == before and time.monotonic() < deadline:
        time.sleep(0.05)
ros2lite.shutdown()
'''


@pytest.mark.skipif(not sys.platform.startswith('linux'), reason='glibc malloc tuning')
def test_memory_returns_after_large_samples(ros_router: Any, tmp_path: Any) -> None:
    """R-W5: a listener kept ~200 MB after a few 16 MiB samples (freed, but kept by malloc)."""
    from tests.spinning import wait_until

    out = tmp_path / 'sink.txt'
    with open(out, 'w') as f:
        sink = subprocess.Popen([sys.executable, '-c', SINK], stdout=f)
    try:
        wait_until(lambda: 'ready' in out.read_text(), timeout=30)

        def rss_mib() -> int:
            with open(f'/proc/{sink.pid}/status') as status:
                line = next(x for x in status if x.startswith('VmRSS:'))
            return int(line.split()[1]) // 1024

        base = rss_mib()
        source = subprocess.run(
            [sys.executable, '-c', SOURCE, str(out)], capture_output=True, text=True, timeout=90
        )
        heard = out.read_text().split()[1:]
        assert heard.count('16777216') >= 4, (heard, source.stderr)
        # the freed samples go back to the system within a release period or two
        wait_until(lambda: rss_mib() < base + 64, timeout=15)
    finally:
        sink.terminate()
        sink.wait(timeout=10)
