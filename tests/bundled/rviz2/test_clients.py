"""Each page's point budget (ros2lite/bundled/rviz2/clients.py), in this process: a real viser
server, pages that are raw WebSockets speaking viser's subprotocol (each sends the camera
message a browser sends first, which is when viser 1.1.1 counts a connection as a client),
and the bookkeeping read back: a budget per page from its own
box, decimation once per distinct budget, only the pages that came or changed sent a cloud
between messages, a page's state gone with it, a hidden display sending nothing."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from ros2lite.bundled.rviz2.clients import MAX_BUDGET, Clouds
from ros2lite.bundled.rviz2.config import DisplaySpec
from ros2lite.bundled.rviz2.convert import IDENTITY, Pose
from ros2lite.bundled.rviz2.displays import PointCloud2Display
from ros2lite.msgs.builtin_interfaces.msg import Time
from ros2lite.msgs.sensor_msgs.msg import PointCloud2
from tests.bundled.rviz2.browser import raw_page
from tests.bundled.rviz2.scene import cloud
from tests.spinning import free_port, wait_until

N = 20_000
NAME, LABEL = '/PointCloud2.block/points', 'PointCloud2 /block'


@pytest.fixture
def served() -> Iterator[tuple[Any, Clouds]]:
    import viser

    server = viser.ViserServer(host='127.0.0.1', port=free_port(), verbose=False)
    try:
        yield server, Clouds(server, 1000, server.gui.add_folder('Global Options'))
    finally:
        server.stop()


class Pages:
    """Raw WebSocket pages on the server, closed at the end."""

    def __init__(self, server: Any, clouds: Clouds) -> None:
        self.server, self.clouds = server, clouds
        self.open: list[Any] = []

    def connect(self) -> int:
        """A new page, and the client id viser gave it."""
        before = set(self.clouds.pages())
        self.open.append(raw_page(self.server.get_port()))
        new = wait_until(lambda: set(self.clouds.pages()) - before, timeout=20)
        return int(next(iter(new)))

    def close(self) -> None:
        for ws in self.open:
            ws.close()


@pytest.fixture
def pages(served: tuple[Any, Clouds]) -> Iterator[Pages]:
    p = Pages(*served)
    try:
        yield p
    finally:
        p.close()


def block() -> tuple[Any, Any]:
    points = np.zeros((N, 3), np.float32)
    points[:, 0] = np.arange(N) / N
    return points, np.zeros((N, 3), np.uint8)


def test_each_page_gets_its_own_budget_and_loses_it_with_the_page(
    served: tuple[Any, Clouds], pages: Pages, monkeypatch: pytest.MonkeyPatch
) -> None:
    _, clouds = served
    a, b = pages.connect(), pages.connect()
    assert clouds.budget(a) == clouds.budget(b) == 1000  # the --point-budget
    points, colours = block()
    clouds.begin()  # both just came: both are sent the cloud between messages
    assert clouds.redraw()
    clouds.send(NAME, LABEL, points, colours, 0.03, everyone=False)
    assert clouds.sent(a) == clouds.sent(b) == {LABEL: (1000, N)}
    assert clouds.decimations == 1  # one budget, decimated once for both pages
    clouds.begin()
    assert not clouds.redraw()  # nothing came or changed since

    page = clouds.page(a)
    assert page is not None and page.box is not None and page.text is not None
    page.box.value = 100  # type: ignore[misc]  # as typed in a's box (the same callback)
    assert clouds.budget(a) == 100 and clouds.budget(b) == 1000
    clouds.begin()
    assert clouds.redraw()
    clouds.send(NAME, LABEL, points, colours, 0.03, everyone=False)
    assert clouds.sent(a) == {LABEL: (100, N)}  # at once, with the newest cloud
    assert clouds.sent(b) == {LABEL: (1000, N)}  # b was not sent it again
    assert clouds.decimations == 2
    assert page.text.content == f'{LABEL}: 100 of {N:,} points'

    clouds.send(NAME, LABEL, points, colours, 0.03, everyone=True)  # a new message
    assert clouds.sent(a) == {LABEL: (100, N)} and clouds.sent(b) == {LABEL: (1000, N)}
    assert clouds.decimations == 4  # once for each of the two budgets

    page.box.value = 0  # type: ignore[misc]
    assert clouds.budget(a) == 1 and page.box.value == 1  # the box's bounds, shown as used
    clouds.set_budget(a, 1e12)
    assert clouds.budget(a) == MAX_BUDGET

    pages.open[0].close()  # a goes: its state is dropped, b's stays
    wait_until(lambda: clouds.pages() == [b], timeout=20)
    assert clouds.budget(a) is None and clouds.sent(a) == {} and clouds.page(a) is None
    clouds.remove(NAME, LABEL)  # the display closed: b's line goes with it
    assert clouds.sent(b) == {}


class Ctx:
    """What a display draws with, the viewer's part of it: everything at the fixed frame."""

    def __init__(self, server: Any, clouds: Clouds) -> None:
        self.server, self.clouds, self.node, self.image_width = server, clouds, None, 640
        self.messages: list[str] = []

    def place(self, frame: str, ns: int) -> Pose | None:
        return IDENTITY

    def status(self, display: object, text: str) -> None:
        self.messages.append(text)


def test_cloud_display_sends_newest_to_a_new_page_and_nothing_while_hidden(
    served: tuple[Any, Clouds], pages: Pages
) -> None:
    server, clouds = served
    ctx = Ctx(server, clouds)
    display = PointCloud2Display(ctx, DisplaySpec('PointCloud2', '/block'), PointCloud2)  # type: ignore[arg-type]
    a = pages.connect()

    def render() -> None:  # one pass of the viewer's loop
        clouds.begin()
        display.render()

    display.store(cloud(Time(), N))
    render()
    assert clouds.sent(a) == {LABEL: (1000, N)}
    b = pages.connect()
    render()  # no new message: the new page is sent the newest one
    assert clouds.sent(b) == {LABEL: (1000, N)}
    made = clouds.decimations

    display.set_enabled(False)
    c = pages.connect()
    clouds.set_budget(a, 10)
    display.store(cloud(Time(), 50))
    render()
    render()
    assert clouds.decimations == made  # hidden: nothing decimated, nothing sent
    assert clouds.sent(c) == {} and clouds.sent(a) == {LABEL: (1000, N)}
    display.set_enabled(True)  # the newest message, to every page at its budget
    render()
    assert clouds.sent(a) == {LABEL: (10, 50)}
    assert clouds.sent(b) == clouds.sent(c) == {LABEL: (50, 50)}
    assert ctx.messages == []
    display.close()
    assert clouds.sent(a) == clouds.sent(b) == clouds.sent(c) == {}
