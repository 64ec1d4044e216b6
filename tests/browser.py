"""Headless Chromium for the tests that look at a page the way a reader does.

Debian's ``chromium`` package (installed by .ci/run); tests using :func:`load` skip with a
notice where it is absent. The page is opened from a file with every host name mapped to
nowhere, so a page that needed the network would fail to render.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

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


def load(page: Path, query: str, workdir: Path, size=(1300, 900)) -> tuple[str, Path]:
    """Open ``page?query``; return (the DOM after its scripts ran, a screenshot's path)."""
    exe = require_chromium()
    shot = workdir / "screenshot.png"
    profile = workdir / "profile"
    profile.mkdir()
    done = subprocess.run(
        [
            exe,
            *FLAGS,
            f"--user-data-dir={profile}",
            f"--window-size={size[0]},{size[1]}",
            "--virtual-time-budget=10000",
            f"--screenshot={shot}",
            "--dump-dom",
            f"{page.resolve().as_uri()}?{query}",
        ],
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout, shot
