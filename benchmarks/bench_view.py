"""The viewer's page: its size and how long it takes to open (issue 31: under 1.5 MB and 2 s).

Run from the repository root: ``python benchmarks/bench_view.py [repeats] [scene]``
(default 5 repeats of ``heavy_top``). Writes the page with ``ga-rotors view SCENE`` into a
temporary folder, then opens it ``repeats`` times, each in a fresh headless Chromium (a new
profile: nothing cached) with its GPU off, so everything is drawn in software. Two times per
opening: the page's own (navigation start to its first frame drawn, ``performance.now()``
when the slider's first position is on screen) and the wall time from the navigation
command to that frame, as the test harness sees it. Prints medians with min–max. Needs
Debian's ``chromium``; the browser's own start-up is not counted.

``--screenshot PATH`` also writes the page at t = 2.2 s as a PNG (docs/view.md's picture:
``python benchmarks/bench_view.py 1 heavy_top --screenshot docs/images/view_heavy_top.png``).
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))  # the DevTools driver the browser tests use


def _summary(values: list[float]) -> str:
    return f"{statistics.median(values):.0f} ms ({min(values):.0f}–{max(values):.0f})"


def main(repeats: int = 5, scene: str = "heavy_top", screenshot: str | None = None) -> None:
    from browser import CHROMIUM, DevTools

    from ga_rotors.cli import main as cli

    if CHROMIUM is None:
        raise SystemExit("headless Chromium not found (apt-get install chromium)")
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / f"{scene}.view.html"
        assert cli(["view", scene, "--out", str(page)]) == 0
        in_page, wall = [], []
        for k in range(repeats):
            work = Path(tmp) / f"run{k}"
            work.mkdir()
            chrome = DevTools("about:blank", work)
            try:
                start = time.perf_counter()
                chrome.open(page)
                wall.append((time.perf_counter() - start) * 1e3)
                in_page.append(float(chrome.evaluate("+document.body.dataset.readyMs")))
            finally:
                chrome.close()
        print(f"`python benchmarks/bench_view.py {repeats} {scene}`; median (min–max) of "
              f"{repeats} cold openings, software rendering\n")  # fmt: skip
        print("| page | size | first frame (page's clock) | navigate → first frame (wall) |")
        print("|---|---|---|---|")
        print(
            f"| ga-rotors view {scene} | {page.stat().st_size / 1e6:.3f} MB | "
            f"{_summary(in_page)} | {_summary(wall)} |"
        )
        if screenshot:
            _screenshot(page, Path(tmp), Path(screenshot))


def _screenshot(page: Path, tmp: Path, out: Path) -> None:
    """The page at t = 2.2 s, 1300 × 760 CSS pixels (heading, slider, pictures, legend)."""
    import base64

    from browser import DevTools

    work = tmp / "screenshot"
    work.mkdir()
    chrome = DevTools("about:blank", work, size=(1300, 760))
    try:
        chrome.open(page, "t=2.2")
        png = chrome.send("Page.captureScreenshot", {"format": "png"})["data"]
    finally:
        chrome.close()
    out.write_bytes(base64.b64decode(png))
    print(f"wrote {out}")


if __name__ == "__main__":
    args = sys.argv[1:]
    shot = None
    if "--screenshot" in args:
        k = args.index("--screenshot")
        shot = args[k + 1]
        del args[k : k + 2]
    main(*(int(a) if a.isdigit() else a for a in args), screenshot=shot)
