"""The turtlesim world stepped directly: known trajectories, walls, teleports, pens, goals."""

from __future__ import annotations

import itertools
import math
import random

import pytest

from ros2lite.bundled.turtlesim import sim


def world() -> sim.World:
    w = sim.World(random.Random(1))
    w.spawn('', sim.WIDTH / 2, sim.HEIGHT / 2, 0.0)
    return w


def run(w: sim.World, steps: int) -> list[sim.TurtleUpdate]:
    out: list[sim.TurtleUpdate] = []
    for _ in range(steps):
        out.extend(w.step())
    return out


def test_the_world_is_turtlesims() -> None:
    assert abs(sim.WIDTH - 11.088889) < 1e-6
    w = world()
    t = w.turtles['turtle1']
    # spawn coordinates are float32, as in the Spawn request: the log shows 5.544445
    assert f'{t.x:f}' == f'{t.y:f}' == '5.544445' and t.theta == 0.0
    assert w.background == (69, 86, 255)
    assert (t.pen.rgb, t.pen.width, t.pen.off) == ((0xB3, 0xB8, 0xFF), 3, False)


def test_constant_twist_moves_for_one_second_then_stops() -> None:
    w = world()
    t = w.turtles['turtle1']
    x0 = t.x
    t.command(1.0, 0.0, 0.0, w.time, holonomic=False)
    updates = run(w, 100)
    # 62 steps of 16 ms fit in the one second a command lasts
    assert t.x == pytest.approx(x0 + 62 * sim.DT * 1.0)
    assert updates[61].pose.linear_velocity == pytest.approx(1.0)
    assert updates[62].pose.linear_velocity == 0.0


def test_a_circle_comes_back_to_its_start() -> None:
    w = world()
    t = w.turtles['turtle1']
    x0, y0 = t.x, t.y
    # 2 rad/s for 3.14 s: one full turn; re-commanded every half second as teleop would
    for _ in range(8):
        t.command(1.0, 0.0, 2.0 * math.pi / (50 * 8 * sim.DT), w.time, holonomic=False)
        run(w, 50)
    assert (t.x, t.y) == pytest.approx((x0, y0), abs=1e-6)
    assert abs(sim.normalize_angle(t.theta)) < 1e-6


def test_pose_is_published_every_step_with_velocities() -> None:
    w = world()
    w.turtles['turtle1'].command(2.0, 0.0, 1.5, w.time, holonomic=False)
    (update,) = w.step()
    assert update.name == 'turtle1'
    assert update.pose.linear_velocity == 2.0 and update.pose.angular_velocity == 1.5
    assert update.pose.theta == pytest.approx(sim.f32(1.5 * sim.DT))


def test_wall_clamps_and_reports_screen_coordinates() -> None:
    w = world()
    t = w.turtles['turtle1']
    t.command(0.0, 0.0, 0.0, w.time, holonomic=False)
    t.teleport_absolute(11.0, 10.0, 0.0)
    t.command(10.0, 0.0, 0.0, w.time, holonomic=False)
    updates = run(w, 5)
    hits = [e for u in updates for e in u.events if isinstance(e, sim.WallHit)]
    assert hits, updates
    assert hits[0].x == pytest.approx(11.0 + 10.0 * sim.DT)  # teleported, then moved
    assert hits[0].y == pytest.approx(sim.HEIGHT - 10.0)  # y counted from the top, as printed
    assert t.x == sim.WIDTH and t.y == pytest.approx(10.0)
    # the top wall: y beyond the height is clamped to it
    t.teleport_absolute(3.0, 50.0, math.pi / 2)
    run(w, 1)
    assert t.y == sim.HEIGHT


def test_teleports_apply_at_the_next_step_and_draw() -> None:
    w = world()
    t = w.turtles['turtle1']
    t.teleport_absolute(1.0, 1.0, 0.5)
    assert t.x != 1.0  # queued, as turtlesim does
    w.step()
    assert (t.x, t.y, t.theta) == pytest.approx((1.0, 1.0, 0.5))
    # the jump was drawn with the pen: the middle of the line is pen-coloured
    mid = sim._px((1.0 + sim.WIDTH / 2) / 2, (1.0 + sim.HEIGHT / 2) / 2)
    assert w.canvas.pixel(round(mid[0]), round(mid[1])) == sim.DEFAULT_PEN
    t.teleport_relative(2.0, math.pi / 2 - 0.5)
    w.step()
    assert (t.x, t.y) == pytest.approx((1.0, 3.0))
    assert t.theta == pytest.approx(math.pi / 2)


def test_pen_off_draws_nothing_and_colour_sensor_reads_the_canvas() -> None:
    w = world()
    t = w.turtles['turtle1']
    t.set_pen(255, 0, 0, 5, off=False)
    t.command(1.0, 0.0, 0.0, w.time, holonomic=False)
    updates = run(w, 10)
    assert updates[0].color == sim.EMPTY_PIXEL  # nothing drawn under it yet
    assert updates[-1].color == (255, 0, 0)  # its own red trail
    t.set_pen(0, 0, 0, 0, off=True)
    t.teleport_absolute(2.0, 2.0, 0.0)
    t.command(1.0, 0.0, 0.0, w.time, holonomic=False)
    run(w, 20)
    px, py = sim._px(2.3, 2.0)
    assert not w.canvas.is_drawn(round(px), round(py))
    assert t.pen.rgb == (255, 0, 0)  # off keeps the colour
    t.set_pen(1, 2, 3, 0, off=False)
    assert (t.pen.rgb, t.pen.width) == ((1, 2, 3), 1)  # width 0: a 1 px pen
    w.clear()
    assert not any(w.canvas.pixels[3::4])


def test_holonomic_strafes_only_when_enabled() -> None:
    w = world()
    t = w.turtles['turtle1']
    y0 = t.y
    t.command(0.0, 1.0, 0.0, w.time, holonomic=False)
    run(w, 10)
    assert t.y == y0
    w.holonomic = True
    t.command(0.0, 1.0, 0.0, w.time, holonomic=True)
    updates = run(w, 10)
    assert t.y == pytest.approx(y0 + 10 * sim.DT)
    assert updates[-1].pose.linear_velocity == 1.0


def test_spawn_kill_and_names() -> None:
    w = world()
    assert w.spawn('', 1, 1, 0) == 'turtle2'
    assert w.spawn('turtle2', 1, 1, 0) == ''  # taken: turtlesim answers an empty name
    assert w.spawn('turtle3', 1, 1, 0) == 'turtle3'
    assert w.spawn('', 1, 1, 0) == 'turtle4'  # turtle3 is skipped
    assert w.kill('turtle2') and not w.kill('turtle2')
    assert [u.name for u in w.step()] == ['turtle1', 'turtle3', 'turtle4']
    w.turtles['turtle1'].command(1.0, 0.0, 0.0, w.time, holonomic=False)
    run(w, 5)
    w.reset()
    assert list(w.turtles) == ['turtle1']
    assert w.turtles['turtle1'].x == pytest.approx(sim.WIDTH / 2, abs=1e-6)
    assert not any(w.canvas.pixels[3::4])
    assert w.spawn('', 1, 1, 0) == 'turtle2'


def test_rotate_absolute_turns_at_one_rad_per_second_to_within_002() -> None:
    w = world()
    t = w.turtles['turtle1']
    goal = sim.RotateGoal(math.pi / 2)
    assert t.start_goal(goal) is None
    updates = run(w, 200)
    events = [e for u in updates for e in u.events]
    feedback = [e.remaining for e in events if isinstance(e, sim.GoalFeedback)]
    (done,) = [e for e in events if isinstance(e, sim.GoalDone)]
    assert done.outcome == 'succeeded' and done.goal is goal
    assert feedback[0] == pytest.approx(math.pi / 2, abs=1e-6)
    assert all(a > b for a, b in itertools.pairwise(feedback))  # closing in
    assert abs(t.theta - math.pi / 2) < sim.GOAL_TOLERANCE
    assert goal.delta == pytest.approx(-t.theta, abs=sim.DT)  # start minus now
    # ~1.57 s at 1 rad/s
    assert len(feedback) == pytest.approx(math.pi / 2 / sim.DT, abs=3)
    assert t.ang == 0.0


def test_a_new_goal_aborts_the_running_one_and_twists_abort_too() -> None:
    w = world()
    t = w.turtles['turtle1']
    first = sim.RotateGoal(3.0)
    t.start_goal(first)
    run(w, 10)
    second = sim.RotateGoal(-1.0)
    aborted = t.start_goal(second)
    assert aborted is not None and aborted.goal is first and aborted.outcome == 'aborted'
    run(w, 5)
    assert t.ang == -1.0  # now turning the other way
    by_twist = t.command(0.0, 0.0, 0.0, w.time, holonomic=False)
    assert by_twist is not None and by_twist.goal is second
    assert t.goal is None


def test_a_cancel_request_ends_the_goal_at_the_next_step() -> None:
    w = world()
    t = w.turtles['turtle1']
    goal = sim.RotateGoal(2.0)
    t.start_goal(goal)
    run(w, 5)
    goal.cancel_requested = True
    (update,) = w.step()
    assert [e.outcome for e in update.events if isinstance(e, sim.GoalDone)] == ['canceled']
    assert t.goal is None and t.ang == 0.0


def test_normalize_angle_range() -> None:
    for a in (-10.0, -math.pi, 0.0, 3.0, math.pi, 7.5):
        n = sim.normalize_angle(a)
        assert -sim.PI <= n < sim.PI
        assert math.cos(n) == pytest.approx(math.cos(a), abs=1e-6)


def test_strokes_are_logged_for_a_view_only_when_asked() -> None:
    w = world()
    t = w.turtles['turtle1']
    t.command(1.0, 0.0, 0.0, w.time, holonomic=False)
    w.step()
    assert w.canvas.drain() == []
    w.canvas.keep_strokes = True
    w.step()
    w.clear()
    strokes = w.canvas.drain()
    assert [s[0] for s in strokes] == ['line', 'clear']
    assert strokes[0][5:] == (sim.DEFAULT_PEN, 3)
