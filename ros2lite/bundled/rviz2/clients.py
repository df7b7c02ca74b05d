"""Point budgets per browser: each connected page picks how many points of a cloud or scan it
is sent ("Point budget" in its Global Options, from `--point-budget`), and the clouds are
decimated to each page's budget and sent to that page alone.

A cloud is a client-scoped viser node named under its display's frame node, which the shared
(server) scene places by TF: viser 1.1.1 mounts a client's node under the effective node of
its parent's name, so the per-page points stand where the shared frame is, hide with it,
and need no per-page copy of the pose. Newest wins as before: a page is sent the newest
cloud of each display (viser keeps the newest message per node for each page); nothing
queues per page. The render loop does all the sending; viser's callbacks (a page comes, a
budget is typed, a page goes) only mark the page, under a lock.
"""

from __future__ import annotations

import dataclasses
import threading
from typing import TYPE_CHECKING

from ros2lite.bundled.rviz2.convert import Bytes, Floats, decimate

if TYPE_CHECKING:
    import viser

MIN_BUDGET = 1
MAX_BUDGET = 5_000_000


def clamp(budget: float) -> int:
    """A typed budget as a whole number of points within the box's bounds."""
    return max(MIN_BUDGET, min(MAX_BUDGET, round(budget)))


@dataclasses.dataclass
class Page:
    """One connected browser: its budget and what it was last sent."""

    handle: viser.ClientHandle
    budget: int
    stale: bool = True  # every cloud to be sent again: it just came, or its budget changed
    sent: dict[str, tuple[int, int]] = dataclasses.field(default_factory=dict)
    """Each cloud's label -> (points sent to this page, points in the message)."""
    box: viser.GuiNumberHandle[int] | None = None
    text: viser.GuiMarkdownHandle | None = None


class Clouds:
    """The connected pages and their budgets, and the clouds sent to each."""

    def __init__(
        self, server: viser.ViserServer, budget: int, folder: viser.GuiFolderHandle
    ) -> None:
        self.default = clamp(budget)
        self._folder = folder
        self._lock = threading.Lock()
        # viser's folder takes one `with` at a time: two pages connecting at once (each on
        # a thread of viser's pool) would raise in the second
        self._folder_lock = threading.Lock()
        self._pages: dict[int, Page] = {}
        self._redraw: set[int] = set()  # this render pass: the pages every cloud goes to
        self.decimations = 0  # decimate() calls, for the tests and the curious
        server.on_client_connect(self.connect)
        server.on_client_disconnect(self.disconnect)

    # -- viser's callbacks (its threads) -------------------------------------------------
    def connect(self, client: viser.ClientHandle) -> None:
        """A new page: its own budget box (the default), and every cloud at the next pass."""
        page = Page(client, self.default)
        with self._folder_lock, self._folder:  # the page's own elements in a shared folder
            page.box = box = client.gui.add_number(
                'Point budget',
                initial_value=self.default,
                min=MIN_BUDGET,
                max=MAX_BUDGET,
                step=1,
                hint='most points of each cloud or scan sent to this page',
            )
            page.text = client.gui.add_markdown('')
        box.on_update(lambda _: self.set_budget(client.client_id, box.value))
        with self._lock:
            self._pages[client.client_id] = page

    def disconnect(self, client: viser.ClientHandle) -> None:
        """The page's state goes with it (viser drops its scene and panel elements)."""
        with self._lock:
            self._pages.pop(client.client_id, None)
            self._redraw.discard(client.client_id)

    def set_budget(self, client_id: int, value: float) -> None:
        """A page's new budget: its clouds are sent again at the next pass."""
        budget = clamp(value)
        with self._lock:
            page = self._pages.get(client_id)
            if page is None:
                return
            if budget != page.budget:
                page.budget, page.stale = budget, True
            box = page.box
        if box is not None and box.value != budget:
            box.value = budget  # type: ignore[misc]  # viser's setter, untyped; the bound used

    # -- what the tests and the viewer read ----------------------------------------------
    def page(self, client_id: int) -> Page | None:
        with self._lock:
            return self._pages.get(client_id)

    def budget(self, client_id: int) -> int | None:
        page = self.page(client_id)
        return page.budget if page is not None else None

    def sent(self, client_id: int) -> dict[str, tuple[int, int]]:
        """Each cloud's label -> (points sent to the page, points in the message)."""
        with self._lock:
            page = self._pages.get(client_id)
            return dict(page.sent) if page is not None else {}

    def pages(self) -> list[int]:
        with self._lock:
            return sorted(self._pages)

    # -- the render loop ---------------------------------------------------------------
    def begin(self) -> None:
        """Once per render pass: the pages that came or changed budget since the last one
        are sent every cloud in this pass (each cloud display asks `redraw()`)."""
        with self._lock:
            self._redraw = {i for i, p in self._pages.items() if p.stale}
            for i in self._redraw:
                self._pages[i].stale = False

    def send(
        self,
        name: str,
        label: str,
        points: Floats,
        colours: Bytes,
        point_size: float,
        *,
        everyone: bool,
    ) -> None:
        """The cloud to every page (a new message) or to the pages `begin()` marked, each
        decimated to the page's budget: once per distinct budget, shared by its pages."""
        with self._lock:
            pages = [p for i, p in self._pages.items() if everyone or i in self._redraw]
        by_budget: dict[int, list[Page]] = {}
        for page in pages:
            by_budget.setdefault(page.budget, []).append(page)
        for budget, group in by_budget.items():
            few, few_colours = decimate(points, colours, budget)
            self.decimations += 1
            for page in group:
                page.handle.scene.add_point_cloud(
                    name, few, few_colours, point_size=point_size, point_shading='flat'
                )
                self._note(page, label, (len(few), len(points)))

    def redraw(self) -> bool:
        """Whether some page is to be sent every cloud in this pass."""
        with self._lock:
            return bool(self._redraw)

    def remove(self, name: str, label: str) -> None:
        """A closed display's cloud, from every page."""
        with self._lock:
            pages = list(self._pages.values())
        for page in pages:
            page.handle.scene.remove_by_name(name)
            self._note(page, label, None)

    def _note(self, page: Page, label: str, counts: tuple[int, int] | None) -> None:
        """The page's line for the cloud (RViz's 'Showing N points'), sent when it changed."""
        with self._lock:
            if page.sent.get(label) == counts:
                return
            if counts is None:
                page.sent.pop(label, None)
            else:
                page.sent[label] = counts
            lines = [f'{k}: {n:,} of {m:,} points' for k, (n, m) in sorted(page.sent.items())]
        if page.text is not None:
            page.text.content = '  \n'.join(lines)
