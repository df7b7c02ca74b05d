"""The plot library without a router: rqt_plot's series names, field paths checked against
message types, bounded series, and what a fed plot holds (CSV rows, x-y, snapshots)."""

from __future__ import annotations

import math

import pytest

from ros2lite.interfaces import get_interface
from ros2lite.interfaces.convert import message_to_csv
from ros2lite.monitor.plot import (
    FieldPath,
    Plot,
    PlotError,
    Series,
    SeriesSpec,
    expand_specs,
    resolve_specs,
    split_topic,
    to_chart,
)

TOPICS = ['/turtle1/pose', '/turtle1', '/scan', '/odom', '/turtle1/cmd_vel']
Pose = get_interface('geometry_msgs/msg/Pose')
Odometry = get_interface('nav_msgs/msg/Odometry')
LaserScan = get_interface('sensor_msgs/msg/LaserScan')
Float64 = get_interface('std_msgs/msg/Float64')


def test_the_longest_topic_is_the_topic() -> None:
    assert split_topic('/turtle1/pose/x', TOPICS) == ('/turtle1/pose', 'x')
    assert split_topic('/turtle1/color', TOPICS) == ('/turtle1', 'color')
    assert split_topic('/scan', TOPICS) == ('/scan', '')
    assert split_topic('/scanner/x', TOPICS) is None  # a prefix only at a field boundary


def test_siblings_of_the_last_field_are_series_of_their_own() -> None:
    specs = expand_specs('/odom/pose/pose/position/x:y', TOPICS)
    assert [s.label for s in specs] == ['/odom/pose/pose/position/x', '/odom/pose/pose/position/y']
    specs = expand_specs('/turtle1/pose/x,y,theta', TOPICS)
    assert [str(s.path) for s in specs] == ['x', 'y', 'theta']
    assert str(expand_specs('/scan/ranges[3]', TOPICS)[0].path) == 'ranges[3]'
    with pytest.raises(PlotError, match="no topic in the graph matches '/nothing/x'"):
        expand_specs('/nothing/x', TOPICS)


def test_paths_read_fields_and_elements() -> None:
    odom = Odometry()
    odom.pose.pose.position.x = 2.5
    assert FieldPath.parse('pose/pose/position/x').get(odom) == 2.5
    assert FieldPath.parse('pose.pose.position.x').get(odom) == 2.5  # echo's --field dots
    scan = LaserScan(ranges=[1.0, 2.0, 3.0])
    assert FieldPath.parse('ranges[1]').get(scan) == 2.0
    assert FieldPath.parse('ranges[-1]').get(scan) == 3.0
    with pytest.raises(PlotError, match='is not a field path'):
        FieldPath.parse('ranges[x]')


@pytest.mark.parametrize(
    ('path', 'cls', 'kind_or_error'),
    [
        ('position/x', Pose, 'number'),
        ('ranges', LaserScan, 'array'),
        ('ranges[0]', LaserScan, 'number'),
        ('data', Float64, 'number'),
        ('header/stamp/sec', LaserScan, 'number'),
        ('position/q', Pose, "has no field 'q' \\(its fields: x, y, z\\)"),
        ('header/frame_id', LaserScan, 'is a string, not a number'),
        ('position', Pose, 'is a whole message .*name one of its numbers: x, y, z'),
        ('position/x/y', Pose, "field 'x' is a float64, it has no fields"),
        ('position[0]', Pose, 'is not an array to index'),
    ],
)
def test_paths_are_checked_against_the_type(path: str, cls: type, kind_or_error: str) -> None:
    if kind_or_error in ('number', 'array'):
        assert FieldPath.parse(path).check(cls) == kind_or_error
    else:
        with pytest.raises(PlotError, match=kind_or_error):
            FieldPath.parse(path).check(cls)


def test_a_series_is_bounded_by_count_and_by_its_time_window() -> None:
    series = Series(SeriesSpec('/a', FieldPath.parse('data')), capacity=100)
    for i in range(1000):
        series.add(i * 0.01, float(i))
    ts, vs = series.points()
    assert len(ts) == 100 and vs[0] == 900.0 and vs[-1] == 999.0 and series.count == 1000
    series.trim(9.5)
    ts, _ = series.points()
    assert ts[0] >= 9.5 and len(ts) == 50
    assert series.points(9.9)[0][0] >= 9.9
    assert series.rate(live=False) == pytest.approx(100.0)


def test_a_live_plot_keeps_only_its_time_window() -> None:
    plot = Plot([SeriesSpec('/a', FieldPath.parse('data'))], window=2.0)
    for i in range(1000):
        plot.feed('/a', Float64(data=float(i)), 100.0 + i * 0.01)
    ts, _ = plot.series[0].points()
    assert plot.now() == pytest.approx(9.99)
    assert len(ts) <= 201 + 64  # trimmed every 64 messages
    chart = to_chart(plot, window=2.0)
    assert chart.x_range == pytest.approx((7.99, 9.99))
    assert chart.lines[0].xs[0] >= 7.99 - 1e-9 and len(chart.lines[0].xs) <= 201


def test_csv_rows_hold_what_topic_echo_csv_writes() -> None:
    rows: list[list[str]] = []
    specs = expand_specs('/turtle1/pose/position/x:z', ['/turtle1/pose'])
    plot = Plot(specs, rows=rows, window=None)
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = 1 / 3, 2.0, -7.125
    plot.feed('/turtle1/pose', pose, 5.0)
    plot.feed('/turtle1/pose', pose, 5.25)
    assert plot.csv_header() == ['time', '/turtle1/pose/position/x', '/turtle1/pose/position/z']
    echoed = message_to_csv(pose.position).split(',')
    assert rows == [['0.000000', echoed[0], echoed[2]], ['0.250000', echoed[0], echoed[2]]]


def test_xy_and_snapshot_plots() -> None:
    plot = Plot(expand_specs('/odom/pose/pose/position/x,y', TOPICS), mode='xy')
    odom = Odometry()
    for i in range(5):
        odom.pose.pose.position.x, odom.pose.pose.position.y = float(i), float(i * i)
        plot.feed('/odom', odom, float(i))
    assert plot.xy_points() == ([0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 1.0, 4.0, 9.0, 16.0])
    chart = to_chart(plot)
    assert chart.lines[0].note == '= (4, 16)' and chart.x_label == 'pose/pose/position/x'
    with pytest.raises(PlotError, match='takes two values'):
        Plot(expand_specs('/odom/pose/pose/position/x', TOPICS), mode='xy')

    snap = Plot(expand_specs('/scan/ranges', TOPICS), mode='snapshot')
    snap.check('/scan', LaserScan)
    snap.feed('/scan', LaserScan(ranges=[1.0, math.inf, 3.0]), 1.0)
    snap.feed('/scan', LaserScan(ranges=[4.0, 5.0]), 1.1)
    assert snap.series[0].points() == ([0.0, 1.0], [4.0, 5.0])  # the newest array only
    with pytest.raises(PlotError, match='is one number; --snapshot plots arrays'):
        Plot(expand_specs('/scan/ranges[0]', TOPICS), mode='snapshot').check('/scan', LaserScan)


def test_header_stamps_as_time() -> None:
    plot = Plot(expand_specs('/scan/range_max', TOPICS), header_stamp=True, window=None)
    plot.check('/scan', LaserScan)
    for sec, nanosec in ((10, 0), (10, 500_000_000), (12, 0)):
        scan = LaserScan(range_max=float(sec))
        scan.header.stamp.sec, scan.header.stamp.nanosec = sec, nanosec
        plot.feed('/scan', scan, 999.0)  # the arrival time is not used
    assert plot.series[0].points()[0] == [0.0, 0.5, 2.0]
    with pytest.raises(PlotError, match='has no header'):
        Plot(expand_specs('/odom2/data', ['/odom2']), header_stamp=True).check('/odom2', Float64)


def test_resolving_waits_for_a_topic_and_fails_fast_on_a_typo() -> None:
    seen: list[list[str]] = [[], ['/other'], ['/other', '/turtle1/pose']]
    waited: list[str] = []
    specs = resolve_specs(
        ['/turtle1/pose/x'], lambda: seen.pop(0) if len(seen) > 1 else seen[0], waited.append, 0
    )
    assert specs == [SeriesSpec('/turtle1/pose', FieldPath.parse('x'))]
    assert waited == ['/turtle1/pose/x']  # said once
    with pytest.raises(PlotError, match='is not a field path'):
        resolve_specs(['/a/b[c]'], lambda: [], None, 0)
    with pytest.raises(PlotError, match='no topic in the graph'):
        resolve_specs(['/a/b'], lambda: [], None, 0, timeout=0)
