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
