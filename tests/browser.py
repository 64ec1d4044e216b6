"""Headless Chromium for the tests that look at a page the way a reader does.

Debian's ``chromium`` package (installed by .ci/run); tests using :class:`DevTools` skip with
a notice where it is absent. One browser serves a whole test module (:meth:`DevTools.open`
loads each page in turn). Pages are opened from files with every host name mapped to
nowhere, so a page that needed the network would fail to render. Chromium runs with its
GPU off: what it draws, it draws in software.
"""

from __future__ import annotations

import base64
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--host-resolver-rules=MAP * ~NOTFOUND",
)


def require_chromium() -> str:
    if CHROMIUM is None:
        pytest.skip("headless Chromium not found (apt-get install chromium); page not opened")
    return CHROMIUM


class DevTools:
    """Headless Chromium driven through its DevTools protocol over a pipe (standard library).

    ``--remote-debugging-pipe`` makes Chromium read JSON commands on fd 3 and write replies
    on fd 4, each message ending in a NUL byte. One page is opened; :meth:`evaluate` runs
    JavaScript in it and :meth:`send` sends any protocol command to it (``Input.*`` to
    click or drag as a user would).
    """

    def __init__(self, url: str, workdir: Path, size=(1300, 900)):
        import json
        import os

        exe = require_chromium()
        self._json = json
        to_chrome_r, self._to_chrome = os.pipe()
        self._from_chrome, from_chrome_w = os.pipe()

        def wire():  # in the child: its fd 3 reads our commands, fd 4 writes replies
            os.dup2(to_chrome_r, 3)
            os.dup2(from_chrome_w, 4)

        profile = workdir / "devtools-profile"
        profile.mkdir()
        self.process = subprocess.Popen(
            [exe, *FLAGS, f"--user-data-dir={profile}", f"--window-size={size[0]},{size[1]}",
             "--remote-debugging-pipe", "about:blank"],
            preexec_fn=wire, pass_fds=(3, 4),  # kept open: set by wire() before the close
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )  # fmt: skip
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self._reader = os.fdopen(self._from_chrome, "rb")
        self._next = 0
        self._buffer = b""
        target = self._call("Target.createTarget", {"url": url})["targetId"]
        self.session = self._call("Target.attachToTarget", {"targetId": target, "flatten": True})[
            "sessionId"
        ]
        self.size = size
        # The page's own pixels are the screenshot's: one device pixel per CSS pixel.
        self.send(
            "Emulation.setDeviceMetricsOverride",
            {"width": size[0], "height": size[1], "deviceScaleFactor": 1, "mobile": False},
        )
        self._opened = 0

    def _message(self) -> dict:
        while b"\0" not in self._buffer:
            chunk = self._reader.read1(65536)
            if not chunk:
                raise RuntimeError("Chromium closed the DevTools pipe")
            self._buffer += chunk
        raw, self._buffer = self._buffer.split(b"\0", 1)
        return self._json.loads(raw)

    def _call(self, method: str, params: dict, session: str | None = None) -> dict:
        import os

        self._next += 1
        message = {"id": self._next, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self._to_chrome, self._json.dumps(message).encode() + b"\0")
        while True:
            reply = self._message()
            if reply.get("id") == self._next:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def send(self, method: str, params: dict) -> dict:
        """A protocol command to the page (e.g. ``Input.dispatchMouseEvent``)."""
        return self._call(method, params, self.session)

    def evaluate(self, expression: str):
        """The value of a JavaScript expression in the page (awaited if a promise)."""
        result = self.send(
            "Runtime.evaluate",
            {"expression": expression, "returnByValue": True, "awaitPromise": True},
        )
        if "exceptionDetails" in result:
            raise RuntimeError(result["exceptionDetails"].get("text", "script error"))
        return result["result"].get("value")

    def wait_for(self, expression: str, timeout: float = 60.0):
        import time

        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                value = self.evaluate(expression)
            except RuntimeError:  # the page is still loading: its names are not there yet
                value = None
            if value:
                return value
            time.sleep(0.1)
        raise TimeoutError(f"never true in the page: {expression}")

    def open(self, page: Path, query: str = "", timeout: float = 60.0) -> None:
        """Load ``page?query`` and wait until it has drawn (``body[data-ready]``)."""
        self._opened += 1  # a fresh query each time: never mistaken for the page before
        url = f"{Path(page).resolve().as_uri()}?{query}{'&' if query else ''}load={self._opened}"
        self.send("Page.navigate", {"url": url})
        self.wait_for(
            f"location.href === {self._json.dumps(url)} && "
            "document.body && document.body.dataset.ready === 'true'",
            timeout,
        )

    def screenshot(self):
        """The viewport as an (height, width, 3) float array in [0, 1]."""
        import io

        from matplotlib.image import imread

        png = self.send("Page.captureScreenshot", {"format": "png"})["data"]
        return imread(io.BytesIO(base64.b64decode(png)), format="png")[..., :3]

    def close(self) -> None:
        import os

        try:
            os.close(self._to_chrome)
            self._reader.close()
        finally:
            self.process.kill()
            self.process.wait(timeout=30)


def one_browser(tmp_path_factory, size=(1300, 900)):
    """One headless Chromium for a whole test module: the body of a module-scoped
    fixture (``yield from one_browser(tmp_path_factory)``), skipping where it is absent."""
    require_chromium()
    browser = DevTools("about:blank", tmp_path_factory.mktemp("chrome"), size=size)
    try:
        yield browser
    finally:
        browser.close()


def rgb(hex_colour: str):
    """``#rrggbb`` as three numbers in [0, 1], the scale of a screenshot's pixels."""
    return np.array([int(hex_colour[k : k + 2], 16) for k in (1, 3, 5)]) / 255


def share_near(shot, xy, colour, radius=4, tolerance=0.25) -> float:
    """The share of pixels within ``radius`` of ``xy`` whose colour is within ``tolerance``."""
    x, y = int(np.rint(xy[0])), int(np.rint(xy[1]))
    window = shot[y - radius : y + radius + 1, x - radius : x + radius + 1]
    return float((np.linalg.norm(window - colour, axis=-1) < tolerance).mean())
