"""Type-system benchmarks: CDR codecs against rosbags, and CLI start-up."""

from __future__ import annotations

import math
import os
import sys
from array import array
from typing import Any

from common import rate, report, wall


def sample_messages() -> dict[str, Any]:
    """The five benchmark messages, built with ros2lite classes."""
    from ros2lite.interfaces import get_interface

    Header = get_interface('std_msgs/msg/Header')
    Time = get_interface('builtin_interfaces/msg/Time')
    hdr = Header(stamp=Time(sec=1700000000, nanosec=123456789), frame_id='base_link')
    imu = get_interface('sensor_msgs/msg/Imu')(header=hdr)
    imu.orientation.w = 0.7
    imu.angular_velocity.z = 0.25
    imu.linear_acceleration.z = 9.81
    imu.orientation_covariance = [0.01 * i for i in range(9)]
    scan = get_interface('sensor_msgs/msg/LaserScan')(
        header=hdr,
        angle_min=-math.pi,
        angle_max=math.pi,
        angle_increment=2 * math.pi / 1080,
        range_min=0.1,
        range_max=30.0,
        ranges=array('f', [1.0 + (i % 100) * 0.01 for i in range(1080)]),
        intensities=array('f', [100.0] * 1080),
    )
    image = get_interface('sensor_msgs/msg/Image')(
        header=hdr,
        height=480,
        width=640,
        encoding='rgb8',
        is_bigendian=0,
        step=640 * 3,
        data=array('B', bytes(range(256)) * 3600),
    )
    TS = get_interface('geometry_msgs/msg/TransformStamped')
    transforms = []
    for i in range(10):
        t = TS(header=hdr, child_frame_id=f'link_{i}')
        t.transform.translation.x = float(i)
        t.transform.rotation.w = 1.0
        transforms.append(t)
    tf = get_interface('tf2_msgs/msg/TFMessage')(transforms=transforms)
    return {
        'std_msgs/msg/String': get_interface('std_msgs/msg/String')(data='Hello World: 1'),
        'sensor_msgs/msg/Imu': imu,
        'sensor_msgs/msg/LaserScan': scan,
        'sensor_msgs/msg/Image': image,
        'tf2_msgs/msg/TFMessage': tf,
    }


def bench_cdr() -> list[float]:
    from rosbags.typesys import Stores, get_typestore

    from ros2lite import interfaces

    store = get_typestore(Stores.ROS2_JAZZY)
    ratios = []
    for name, msg in sample_messages().items():
        data = interfaces.serialize(msg)
        theirs = store.deserialize_cdr(data, name)
        assert bytes(store.serialize_cdr(theirs, name)) == data, name
        short = name.rsplit('/', 1)[1]
        ours_ser = rate(lambda m=msg: interfaces.serialize(m))
        base_ser = rate(lambda m=theirs, n=name: store.serialize_cdr(m, n))
        report(f'cdr_serialize_{short}', ours_ser, 'msg/s', ours_ser / base_ser)
        ours_des = rate(lambda d=data, n=name: interfaces.deserialize(n, d))
        base_des = rate(lambda d=data, n=name: store.deserialize_cdr(d, n))
        report(f'cdr_deserialize_{short}', ours_des, 'msg/s', ours_des / base_des)
        ratios += [ours_ser / base_ser, ours_des / base_des]
    gmean = math.exp(sum(math.log(r) for r in ratios) / len(ratios))
    report('cdr_geomean', gmean, 'ratio', gmean)
    report('cdr_min', min(ratios), 'ratio', min(ratios))
    return ratios


def bench_help() -> None:
    exe = os.path.join(os.path.dirname(sys.executable), 'ros2lite')
    ours = wall([exe, '--help'])
    base = wall([sys.executable, '-c', 'import click'])
    # ratio as "times the baseline" here: the target is <= 1.5
    report('cli_help_wall', ours * 1000, 'ms', ours / base)


BENCHES = {'cdr': bench_cdr, 'help': bench_help}
