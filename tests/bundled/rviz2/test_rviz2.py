"""`ros2lite run rviz2 rviz2` against a real router and a real publisher process, looked at
by a real headless Chromium (SwiftShader's WebGL): screenshots are checked by their pixels
(the scan's red ring, the cloud's blue square, the marker's magenta cube, where TF puts
them), and the "2D Goal Pose" tool is clicked with the DevTools protocol's mouse events, so
the click takes the page's own path (canvas pointer events -> viser's scene click message ->
the tool -> a PoseStamped on /goal_pose)."""

from __future__ import annotations

import math
import sys
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.bundled.rviz2.browser import Browser, blue, chromium, count, magenta, red
from tests.conftest import Processes
from tests.spinning import Listener, free_port, wait_until

pytestmark = pytest.mark.skipif(
    chromium() is None, reason='chromium is not installed (apt-get install chromium)'
)
ROOT = Path(__file__).resolve().parents[3]
SHOTS = Path('/tmp') / 'rviz2-shots'
W, H = 900, 700


def _serving(port: int) -> bool:
    try:
        with urllib.request.urlopen(f'http://127.0.0.1:{port}/', timeout=2):
            return True
    except OSError:
        return False


def _start_viewer(procs: Processes, *args: str) -> str:
    """The viewer, in the test's own processes: stopped when the test ends, so it does not
    go on drawing the scene (and taking the CPU) for the module's later tests."""
    port = free_port()
    proc = procs.cli('run', 'rviz2', 'rviz2', '--port', str(port), *args, cwd=ROOT)
    wait_until(lambda: _serving(port) or proc.poll() is not None, timeout=30)
    assert proc.poll() is None, procs.stop(proc)
    return f'http://127.0.0.1:{port}/'


@pytest.fixture(scope='module')
def scene(ros_router: str) -> Iterator[Processes]:
    """The scene publisher (tests/bundled/rviz2/scene.py), base_link at (1.5, 1.5) of map."""
    procs = Processes()
    procs.start([sys.executable, '-m', 'tests.bundled.rviz2.scene', '1.5'], cwd=ROOT)
    try:
        yield procs
    finally:
        procs.close()


@pytest.fixture(scope='module')
def browser() -> Iterator[Browser]:
    """One Chromium for the module's tests: each opens its own page in it."""
    b = Browser(W, H)
    try:
        yield b
    finally:
        b.close()


# the scene's part of the page: not the panel (right), the banner (top) or the axes (bottom left)
SCENE_BOX = (100, 150, 560, H)


def centroid(
    image: Any, test: Any, box: tuple[int, int, int, int] | None = None
) -> tuple[float, float]:
    """The mean place of the pixels for which test(r, g, b), in the page's coordinates."""
    left, top = (box[0], box[1]) if box else (0, 0)
    region = image.crop(box) if box else image
    xs = ys = n = 0
    for i, px in enumerate(region.get_flattened_data()):
        if test(*px):
            xs += i % region.width
            ys += i // region.width
            n += 1
    return (left + xs / n, top + ys / n) if n else (math.nan, math.nan)


def _shot(browser: Browser, url: str | None, name: str, ready: Any) -> Any:
    """A screenshot of the page, freshly opened, once `ready(image)` holds."""
    SHOTS.mkdir(exist_ok=True)
    return browser.shot(url, str(SHOTS / name), ready)


RVIZ_FILE = """\
Panels: []
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Enabled: true
      Name: Grid
    - Class: rviz_default_plugins/LaserScan
      Enabled: true
      Name: LaserScan
      Topic:
        Value: /scan
        Reliability Policy: Best Effort
    - Class: rviz_default_plugins/MarkerArray
      Enabled: true
      Name: MarkerArray
      Topic:
        Value: /markers
  Global Options:
    Fixed Frame: base_link
  Views:
    Current:
      Class: rviz_default_plugins/Orbit
      Distance: 10.392
      Focal Point: {X: 0, Y: 0, Z: 0}
      Pitch: 0.6155
      Yaw: 3.927
"""


def test_rviz_file_opens_its_fixed_frame_and_displays(
    scene: Processes, browser: Browser, processes: Processes, tmp_path: Path
) -> None:
    config = tmp_path / 'three.rviz'
    config.write_text(RVIZ_FILE)
    url = _start_viewer(processes, '-d', str(config))
    image = _shot(
        browser, url, 'rviz_file.png', lambda im: count(im, red) > 200 and count(im, magenta) > 200
    )
    # the cloud is published with the scan, so a cloud display would have drawn it by now
    assert count(image, blue) == 0  # the file names no PointCloud2 display
    ring, cube = centroid(image, red), centroid(image, magenta)
    # fixed frame base_link: the ring round the laser is at the origin, the screen's centre
    # (the view looks at it from the same place as the default one)
    assert abs(ring[0] - W / 2) < 40 and abs(ring[1] - H / 2) < 40, ring
    assert cube[0] < ring[0] - 80, (ring, cube)  # map (-2, 2) is base_link (-3.5, 0.5)
    # the page the screenshot was of is still open: its panel
    panel = wait_until(
        lambda: (
            'LaserScan /scan' in str(browser.evaluate('document.body.innerText'))
            and browser.evaluate('document.body.innerText')
        ),
        timeout=60,
    )
    assert isinstance(panel, str)
    assert 'LaserScan /scan' in panel and 'MarkerArray /markers' in panel
    assert 'PointCloud2' not in panel


def test_goal_pose_click_publishes_a_pose_stamped(
    scene: Processes, browser: Browser, processes: Processes, ros_context: Any, tmp_path: Path
) -> None:
    from ros2lite.msgs.geometry_msgs.msg import PoseStamped

    # a still page (a grid, fixed frame map): the tool, not the streams, is under test, and
    # SwiftShader redrawing 20 scene updates a second would keep the page from answering
    config = tmp_path / 'grid.rviz'
    config.write_text(
        'Visualization Manager:\n  Displays:\n    - Class: rviz_default_plugins/Grid\n'
        '  Global Options:\n    Fixed Frame: map\n'
    )
    url = _start_viewer(processes, '-d', str(config))
    listener = Listener(ros_context, '/goal_pose', PoseStamped, 10)
    try:
        browser.open(url)
        # the panel settles (its parts arrive one by one and move the button) before the click
        seen: list[object] = [None]

        def settled() -> tuple[float, float] | None:
            where = browser.button_centre('2D Goal Pose')
            still = where is not None and where == seen[0]
            seen[0] = where
            return where if still else None

        wait_until(
            lambda: 'fixed frame: map' in str(browser.evaluate('document.body.innerText')),
            timeout=60,
        )
        button = wait_until(settled, timeout=30, interval=1.0)
        browser.click(*button)
        # (each answer is a round trip page -> viewer -> page: seconds on a loaded machine)
        wait_until(
            lambda: 'click the ground' in str(browser.evaluate('document.body.innerText')),
            timeout=30,
        )
        # the camera looks at map's origin: the canvas centre is (0, 0) on the ground; a click
        # above it is further along the view, map's (1, 1): a heading of 45 degrees
        browser.click(W / 2, H / 2)
        wait_until(
            lambda: 'where it faces' in str(browser.evaluate('document.body.innerText')),
            timeout=30,
        )
        browser.click(W / 2, H / 2 - 100)
        wait_until(lambda: listener.messages, timeout=20)
    finally:
        listener.stop()
    goal = listener.messages[0]
    assert goal.header.frame_id == 'map'
    assert abs(goal.pose.position.x) < 0.2 and abs(goal.pose.position.y) < 0.2, goal.pose
    yaw = 2 * math.atan2(goal.pose.orientation.z, goal.pose.orientation.w)
    assert abs(yaw - math.pi / 4) < 0.1, yaw


def green(r: int, g: int, b: int) -> bool:
    return g > 110 and r < 80 and b < 80


def yellow(r: int, g: int, b: int) -> bool:
    return r > 130 and g > 110 and b < 70 and abs(r - g) < 80


def test_zero_configuration_shows_the_robot_scan_cloud_and_markers_and_follows_a_joint(
    scene: Processes, browser: Browser, processes: Processes, ros_context: Any, tmp_path: Path
) -> None:
    """Zero configuration, with a real robot_state_publisher on the test's URDF (green base,
    yellow arm on a revolute joint) and /joint_states from a process the test controls: the
    scan, cloud, markers and model stand where TF puts them, and a new joint angle swings
    the arm in the next screenshot."""
    import yaml

    from tests.bundled.rviz2.joints import URDF

    params = tmp_path / 'rsp.yaml'
    params.write_text(
        yaml.safe_dump({'robot_state_publisher': {'ros__parameters': {'robot_description': URDF}}})
    )
    processes.cli(
        'run', 'robot_state_publisher', 'robot_state_publisher',
        '--ros-args', '--params-file', str(params), cwd=ROOT,
    )  # fmt: skip
    joints = [sys.executable, '-m', 'tests.bundled.rviz2.joints']
    swing = processes.start([*joints, '0.0'], cwd=ROOT)
    url = _start_viewer(processes)
    colours = (red, blue, magenta, green, yellow)
    image = _shot(
        browser,
        url,
        'zero_config.png',
        lambda im: all(count(im, c, SCENE_BOX) > 100 for c in colours),
    )
    ring, cloud, cube = (centroid(image, c, SCENE_BOX) for c in (red, blue, magenta))
    # the camera looks from (-6, -6, 6) at map's origin: screen-right is map's (1, -1),
    # screen-up (1, 1). The cloud (odom x/y -3..-2, odom = map) is nearest, below the centre;
    # the cube (map -2, 2) is left; the ring, round the laser on base_link at (1.5, 1.5)
    # through map -> odom -> base_link -> laser, is beyond the centre, above the other two.
    assert cloud[1] > H / 2 > ring[1], (ring, cloud)
    assert cube[0] < W / 2 - 80 < ring[0], (ring, cube)
    assert abs(ring[0] - cloud[0]) < 60, (ring, cloud)  # both on the screen's middle line
    base, arm = centroid(image, green, SCENE_BOX), centroid(image, yellow, SCENE_BOX)
    # the robot stands on base_link, the laser's frame: inside the scan's ring
    assert abs(base[0] - ring[0]) < 40 and abs(base[1] - ring[1]) < 40, (ring, base)
    # the arm along base_link's +x: screen-right and up
    assert arm[0] > base[0] + 15 and arm[1] < base[1], (base, arm)
    processes.stop(swing)
    processes.start([*joints, str(math.pi / 2)], cwd=ROOT)
    from ros2lite.msgs.sensor_msgs.msg import JointState

    # the new angle is on /joint_states (robot_state_publisher turns it into TF at once)
    listener = Listener(ros_context, '/joint_states', JointState, 10)
    try:
        wait_until(
            lambda: any(abs(m.position[0] - math.pi / 2) < 1e-6 for m in listener.messages),
            timeout=30,
        )
    finally:
        listener.stop()

    def swung(im: Any) -> bool:
        # (the arm hides part of the base's green, so the arm is compared with itself too)
        a = centroid(im, yellow, SCENE_BOX)
        return count(im, yellow, SCENE_BOX) > 100 and a[0] < min(base[0], arm[0] - 20)

    after = _shot(browser, url, 'robot_swung.png', swung)
    # the arm along base_link's +y now: screen-left and up; the base stayed
    base2, arm2 = centroid(after, green, SCENE_BOX), centroid(after, yellow, SCENE_BOX)
    assert abs(base2[0] - base[0]) < 10 and abs(base2[1] - base[1]) < 10, (base, base2)
    assert arm2[1] < base2[1], (base2, arm2)


BLOCK_FILE = """\
Visualization Manager:
  Displays:
    - Class: rviz_default_plugins/PointCloud2
      Name: Block
      Topic:
        Value: /block
  Global Options:
    Fixed Frame: map
"""
BLOCK_POINTS = 20_000


def _panel_text(page: Browser) -> str:
    return str(page.evaluate('document.body.innerText'))


def test_each_browser_has_its_own_point_budget(
    browser: Browser, processes: Processes, tmp_path: Path
) -> None:
    """Two pages on one viewer and a 20k-point blue block (a 2 m square, in a frame TF puts
    at map's (-2, 2)): one types 100 into its "Point budget" box, the other keeps the
    default. Each page's panel says what it was sent (100 of 20,000, 20,000 of 20,000), and
    its screenshot shows it: the small budget's block is a sprinkle of blue, the other's
    solid, both where TF puts the frame (each page's points hang from the shared frame)."""
    config = tmp_path / 'block.rviz'
    config.write_text(BLOCK_FILE)
    processes.start(
        [sys.executable, '-m', 'tests.bundled.rviz2.block', str(BLOCK_POINTS)], cwd=ROOT
    )
    url = _start_viewer(processes, '-d', str(config))
    whole = f'Block: {BLOCK_POINTS:,} of {BLOCK_POINTS:,} points'
    few = f'Block: 100 of {BLOCK_POINTS:,} points'
    small = Browser(W, H)
    try:
        browser.open(url)
        small.open(url)
        for page in (browser, small):  # each is sent the whole block at the default budget
            wait_until(lambda page=page: whole in _panel_text(page), timeout=60)  # type: ignore[misc]
        seen: list[object] = [None]

        def settled() -> tuple[float, float] | None:
            where = small.input_centre('Point budget')
            still = where is not None and where == seen[0]
            seen[0] = where
            return where if still else None

        box = wait_until(settled, timeout=30, interval=1.0)
        small.click(*box)
        small.type_text('100')
        wait_until(lambda: few in _panel_text(small), timeout=30)
        both = _shot(browser, None, 'budget_default.png', lambda im: count(im, blue, SCENE_BOX) > 0)
        sprinkle = _shot(small, None, 'budget_100.png', lambda im: count(im, blue, SCENE_BOX) > 0)
        # the other page kept its budget (the box is each page's own)
        assert whole in _panel_text(browser) and few not in _panel_text(browser)
        solid_n, sprinkle_n = count(both, blue, SCENE_BOX), count(sprinkle, blue, SCENE_BOX)
        print(f'blue pixels: default budget {solid_n}, budget 100 {sprinkle_n}')
        assert solid_n > 3000, solid_n
        assert 0 < sprinkle_n < solid_n / 5, (solid_n, sprinkle_n)
        # both blocks stand where TF puts their frame: map's (-2, 2) is screen-left of the
        # origin (the screen's centre; screen-right is map's (1, -1))
        a, b = centroid(both, blue, SCENE_BOX), centroid(sprinkle, blue, SCENE_BOX)
        assert a[0] < W / 2 - 90 and abs(a[1] - H / 2) < 40, a
        assert abs(a[0] - b[0]) < 30 and abs(a[1] - b[1]) < 30, (a, b)
    finally:
        small.close()
