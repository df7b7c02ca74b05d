"""A real headless Chromium (Debian's, with SwiftShader's WebGL) driven through the DevTools
protocol: open a page, take screenshots as a person sees them, click with the mouse. One
browser serves a whole test module (starting one costs seconds under load); each screenshot
is of the live page, taken again until the test's condition on its pixels holds.

The protocol is spoken over a WebSocket with the `websockets` package (viser's dependency),
so nothing else is installed. Screenshots come back as PNG and are read with Pillow."""

from __future__ import annotations

import base64
import io
import itertools
import json
import os
import shutil
import subprocess
import tempfile
import time
import urllib.request
from typing import Any

CHROMIUM = '/usr/bin/chromium'

# the camera message a viser page sends first, as its wire protocol carries it (msgpack of a
# dict naming its type): viser 1.1.1 counts a connection as a client only from then on
PAGE_CAMERA = {
    'type': 'ViewerCameraMessage',
    'wxyz': (1.0, 0.0, 0.0, 0.0),
    'position': (-6.0, -6.0, 6.0),
    'fov': 1.0,
    'near': 0.01,
    'far': 100.0,
    'image_height': 700,
    'image_width': 900,
    'look_at': (0.0, 0.0, 0.0),
    'up_direction': (0.0, 0.0, 1.0),
}


def raw_page(port: int, **options: Any) -> Any:
    """A viser page that is only its WebSocket: it says its camera, as a browser does, and
    reads what it is sent only when asked (`options` go to websockets' connect)."""
    import msgspec
    import viser
    from websockets.sync.client import connect

    ws = connect(
        f'ws://127.0.0.1:{port}',
        subprotocols=[f'viser-v{viser.__version__}'],  # type: ignore[list-item]
        max_size=None,
        **options,
    )
    ws.send(msgspec.msgpack.encode(PAGE_CAMERA))
    return ws


def chromium() -> str | None:
    """The browser the tests drive, when installed."""
    return CHROMIUM if os.path.exists(CHROMIUM) else shutil.which('chromium')


class Browser:
    """One headless Chromium with one page, closed with `close()`."""

    def __init__(self, width: int = 900, height: int = 700) -> None:
        from websockets.sync.client import connect

        exe = chromium()
        assert exe is not None
        self.profile = tempfile.mkdtemp(prefix='rviz2-chromium-')
        self.proc = subprocess.Popen(
            [
                exe,
                '--headless',
                '--no-sandbox',
                '--use-angle=swiftshader',
                '--enable-unsafe-swiftshader',
                '--disable-background-networking',
                '--disable-component-update',
                '--disable-sync',
                '--disable-quic',
                '--no-first-run',
                f'--user-data-dir={self.profile}',
                # a page nobody looks at still animates (viser's fade-in and frames run on
                # requestAnimationFrame, which a background page would pause)
                '--disable-renderer-backgrounding',
                '--disable-background-timer-throttling',
                '--disable-backgrounding-occluded-windows',
                f'--window-size={width},{height}',
                # chromium picks the port and writes it to DevToolsActivePort: no race with
                # another process for a port chosen here
                '--remote-debugging-port=0',
                'about:blank',
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        self.width, self.height = width, height
        deadline = time.monotonic() + 30
        pages: list[dict[str, Any]] = []
        active = os.path.join(self.profile, 'DevToolsActivePort')
        while time.monotonic() < deadline and self.proc.poll() is None:
            try:
                with open(active) as f:
                    port = int(f.readline())
                with urllib.request.urlopen(f'http://127.0.0.1:{port}/json/list', timeout=2) as r:
                    pages = [p for p in json.load(r) if p.get('type') == 'page']
                if pages:
                    break
            except (OSError, ValueError):  # not written yet, or half written
                pass
            time.sleep(0.1)
        if not pages:
            self.close()
        assert pages, 'chromium did not open its DevTools port'
        self.ws = connect(pages[0]['webSocketDebuggerUrl'], max_size=64 * 1024 * 1024)
        self._ids = itertools.count(1)
        self._events: list[str] = []  # the names of the events read since the last open()
        self.call('Page.enable')
        self.call('Page.bringToFront')
        self.call('Emulation.setFocusEmulationEnabled', enabled=True)

    def call(self, method: str, **params: object) -> dict[str, Any]:
        """One DevTools command and its result (events in between are noted by name)."""
        n = next(self._ids)
        self.ws.send(json.dumps({'id': n, 'method': method, 'params': params}))
        while True:
            reply = json.loads(self.ws.recv(timeout=60))
            if reply.get('id') == n:
                assert 'error' not in reply, reply['error']
                result: dict[str, Any] = reply.get('result', {})
                return result
            if 'method' in reply:
                self._events.append(reply['method'])

    def _event(self, name: str, timeout: float) -> None:
        """Until the event `name` has come (since the last open())."""
        deadline = time.monotonic() + timeout
        while name not in self._events:
            left = deadline - time.monotonic()
            assert left > 0, f'no {name} within {timeout} s'
            try:
                message = json.loads(self.ws.recv(timeout=left))
            except TimeoutError:
                continue
            if 'method' in message:
                self._events.append(message['method'])

    def open(self, url: str) -> None:
        self.call(
            'Emulation.setDeviceMetricsOverride',
            width=self.width,
            height=self.height,
            deviceScaleFactor=1,
            mobile=False,
        )
        self._events.clear()
        self.call('Page.navigate', url=url)
        # until the page has loaded: a page still committing (a new origin gets a new
        # renderer) answers a screenshot with "Not attached to an active page"
        self._event('Page.loadEventFired', 60)

    def evaluate(self, expression: str) -> object:
        result = self.call('Runtime.evaluate', expression=expression, returnByValue=True)
        return result.get('result', {}).get('value')

    def screenshot(self, path: str | None = None) -> Any:
        """The page as a PIL RGB image (saved to `path` too, to look at)."""
        from PIL import Image

        data = base64.b64decode(self.call('Page.captureScreenshot', format='png')['data'])
        if path:
            with open(path, 'wb') as f:
                f.write(data)
        return Image.open(io.BytesIO(data)).convert('RGB')

    def shot(
        self, url: str | None, path: str, ready: Any, timeout: float = 120, settle: float = 2.0
    ) -> Any:
        """`url` opened afresh (None: the page open now), then screenshots of it (each saved
        to `path`, to look at) until `ready(image)` has held on every one for `settle` s:
        the last one, as a person sees the page once it has settled. (A live page passes
        through moments no one would judge it by: an object drawn at the origin in the
        frame before its pose arrives.)"""
        from tests.spinning import wait_until

        if url is not None:
            self.open(url)
        shot: list[Any] = []
        since: list[float] = []  # when ready() began to hold, while it does

        def taken() -> bool:
            shot[:] = [self.screenshot(path)]
            if not ready(shot[0]):
                since.clear()
                return False
            if not since:
                since.append(time.monotonic())
            return time.monotonic() - since[0] >= settle

        wait_until(taken, timeout=timeout, interval=0.5)
        return shot[0]

    def click(self, x: float, y: float) -> None:
        """A left click as a mouse makes it: move, press, release."""
        self.call('Input.dispatchMouseEvent', type='mouseMoved', x=x, y=y)
        for kind in ('mousePressed', 'mouseReleased'):
            self.call(
                'Input.dispatchMouseEvent',
                type=kind,
                x=x,
                y=y,
                button='left',
                buttons=1 if kind == 'mousePressed' else 0,
                clickCount=1,
            )

    def type_text(self, text: str) -> None:
        """Select what the focused input holds (Ctrl+A) and type `text` over it."""
        for kind in ('rawKeyDown', 'keyUp'):
            self.call(
                'Input.dispatchKeyEvent',
                type=kind,
                modifiers=2,  # Ctrl
                key='a',
                code='KeyA',
                windowsVirtualKeyCode=65,
                commands=['selectAll'] if kind == 'rawKeyDown' else [],
            )
        self.call('Input.insertText', text=text)

    def input_centre(self, label: str) -> tuple[float, float] | None:
        """Where the page shows the input labelled `label` (None while it does not)."""
        found = self.evaluate(
            '(() => { for (const l of document.querySelectorAll("label")) {'
            f' if (l.innerText.trim() === {json.dumps(label)} && l.htmlFor) {{'
            ' const i = document.getElementById(l.htmlFor); if (!i) continue;'
            ' const r = i.getBoundingClientRect(); return [r.x + r.width / 2,'
            ' r.y + r.height / 2]; } } return null; })()'
        )
        return (float(found[0]), float(found[1])) if isinstance(found, list) else None

    def button_centre(self, text: str) -> tuple[float, float] | None:
        """Where the page shows the button labelled `text` (None while it does not)."""
        found = self.evaluate(
            '(() => { for (const b of document.querySelectorAll("button")) {'
            f' if (b.innerText.trim() === {json.dumps(text)}) {{'
            ' const r = b.getBoundingClientRect(); return [r.x + r.width / 2,'
            ' r.y + r.height / 2]; } } return null; })()'
        )
        return (float(found[0]), float(found[1])) if isinstance(found, list) else None

    def checkbox_centre(self, label: str) -> tuple[float, float] | None:
        """Where the page shows the one checkbox whose row reads `label` (None while none)."""
        found = self.evaluate(
            '(() => { for (const box of document.querySelectorAll("input[type=checkbox]")) {'
            ' let row = box.parentElement;'
            ' while (row && row.querySelectorAll("input[type=checkbox]").length === 1) {'
            f' if (row.innerText.replace(/\\s+/g, " ").trim() === {json.dumps(label)}) {{'
            ' const r = box.getBoundingClientRect(); return [r.x + r.width / 2,'
            ' r.y + r.height / 2]; } row = row.parentElement; } } return null; })()'
        )
        return (float(found[0]), float(found[1])) if isinstance(found, list) else None

    def close(self) -> None:
        try:
            if hasattr(self, 'ws'):
                self.ws.close()
        finally:
            self.proc.terminate()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
            shutil.rmtree(self.profile, ignore_errors=True)


def count(image: Any, test: Any, box: tuple[int, int, int, int] | None = None) -> int:
    """Pixels of `image` (inside box: left, top, right, bottom) for which test(r, g, b)."""
    region = image.crop(box) if box else image
    return sum(1 for px in region.get_flattened_data() if test(*px))


def red(r: int, g: int, b: int) -> bool:
    return r > 180 and g < 90 and b < 90


def blue(r: int, g: int, b: int) -> bool:
    return b > 180 and r < 90 and g < 90


def magenta(r: int, g: int, b: int) -> bool:
    return r > 140 and b > 140 and g < 100
