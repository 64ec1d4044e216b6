"""The viewer in a real browser: it renders, the slider's time shows that time's orientation.

Opened in headless Chromium (tests/browser.py), offline; the state is read back from the
page's DOM (``#readouts`` data attributes and readout text) and compared with the
trajectory's own arrays, the Euler angles with scipy's ``Rotation``.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

pytest.importorskip("plotly")

from browser import DevTools, load
from scipy.spatial.transform import Rotation

from ga_rotors import simulate
from ga_rotors.view import View


@pytest.fixture(scope="module")
def run():
    # An asymmetric body tumbling near its intermediate axis: every component of q moves.
    return simulate((1.0, 2.0, 3.0), [0.9, 0.1, 0.3, 0.3], [0.05, 2.0, 0.3], duration=4.0,
                    step=1e-3, paths=("rotor", "quaternion"))  # fmt: skip


def _rows(dom: str) -> dict:
    rows = {}
    for path, body in re.findall(r'<tr data-path="(\w+)">(.*?)</tr>', dom, re.S):
        cells = dict(re.findall(r'<td class="(\w+)[^"]*"[^>]*>([^<]*)</td>', body))
        q = re.search(r'data-q="([^"]*)"', body).group(1)
        rows[path] = cells, json.loads(q)
    return rows


@pytest.mark.parametrize("t_wanted", [0.0, 1.2345, 4.0])
def test_slider_time_shows_the_trajectorys_orientation(run, tmp_path, t_wanted):
    page = View.from_trajectory(run, title="tumbling").save(tmp_path / "view.html")
    dom, _shot = load(page, f"t={t_wanted}", tmp_path)
    state = re.search(r'id="readouts" data-index="(\d+)" data-time="([^"]+)"', dom)
    assert state, "the page never drew its readouts"
    t_shown = float(state.group(2))
    j = int(np.argmin(np.abs(run.t - t_shown)))
    assert run.t[j] == pytest.approx(t_shown, abs=1e-12)  # a sample of the run, not interpolated
    assert abs(t_shown - t_wanted) <= 4.0 / 599  # the nearest of the page's ≤ 600 frames

    rows = _rows(dom)
    assert set(rows) == {"rotor", "quaternion"}
    # The rotor path's coefficients on clifford's blades (1, e12, e13, e23) and
    # R = w − x e23 − y e31 − z e12 (e31 = −e13) give q = (R₀, −R₂₃, R₁₃, −R₁₂).
    r0, r12, r13, r23 = run["rotor_blades"][j]
    assert rows["rotor"][1] == pytest.approx([r0, -r23, r13, -r12], abs=1e-14)
    assert rows["quaternion"][1] == pytest.approx(run.q[j].tolist(), abs=1e-14)
    psi, theta, phi = Rotation.from_quat(run.q[j], scalar_first=True).as_euler("ZYZ", True)
    shown = [float(a) for a in re.findall(r"(-?[\d.]+)°", rows["quaternion"][0]["euler"])]
    assert shown == pytest.approx([psi, theta, phi], abs=2e-3)
    assert rows["quaternion"][0]["gimbal"] == "no"


def test_page_renders_a_picture_that_moves_with_the_slider(run, tmp_path):
    from matplotlib.image import imread

    page = View.from_trajectory(run).save(tmp_path / "view.html")
    figures = []
    for t in (0.0, 2.0):
        (tmp_path / f"t{t}").mkdir()
        _, shot = load(page, f"t={t}", tmp_path / f"t{t}")
        pixels = imread(shot)[..., :3]
        assert pixels.shape[:2] == (900, 1300)
        figures.append(pixels[100:600])  # the 3-D scenes, below the slider
    for figure in figures:
        not_white = (figure < 0.95).any(axis=-1).mean()
        colours = np.unique((figure * 255).astype(np.uint8).reshape(-1, 3), axis=0).shape[0]
        assert not_white > 0.05, f"only {not_white:.1%} of the figure is drawn"
        assert colours > 200, f"{colours} colours: the WebGL scenes did not render"
    moved = (np.abs(figures[0] - figures[1]) > 0.1).any(axis=-1).mean()
    assert moved > 0.01, "the body and vectors did not move between t = 0 and t = 2"


def test_gimbal_lock_is_flagged_on_the_page(tmp_path):
    # Spin about the body's z axis from the identity: θ = 0 exactly at every sample.
    tr = simulate((1.0, 1.0, 2.0), [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0], duration=1.0,
                  step=1e-2, paths=("quaternion",))  # fmt: skip
    page = View.from_trajectory(tr).save(tmp_path / "view.html")
    dom, _ = load(page, "t=0.5", tmp_path)
    cells, q = _rows(dom)["quaternion"]
    assert cells["gimbal"].startswith("LOCKED")
    # Half a radian about z (RK4 at h|ω| = 0.01: error ~1e-12) and exactly the run's sample.
    assert q == pytest.approx([np.cos(0.25), 0.0, 0.0, np.sin(0.25)], abs=1e-10)
    assert q == pytest.approx(tr.q[50].tolist(), abs=1e-14)


_STATE = """JSON.stringify({
    i: +document.getElementById("readouts").dataset.index,
    t: +document.getElementById("readouts").dataset.time,
    q: JSON.parse(document.querySelector('tr[data-path="quaternion"] .q').dataset.q),
    button: document.getElementById("play").textContent,
})"""


def test_a_user_drags_the_slider_and_presses_play(run, tmp_path):
    """Through Chromium's DevTools protocol: mouse events on the slider and the button."""
    import time

    page = View.from_trajectory(run).save(tmp_path / "view.html")
    chrome = DevTools(page.resolve().as_uri(), tmp_path)
    try:
        chrome.wait_for("document.body.dataset.ready === 'true'")
        frames = chrome.evaluate("+document.getElementById('slider').max") + 1
        left, top, width, height = chrome.evaluate(
            "(() => { const r = document.getElementById('slider').getBoundingClientRect();"
            " return [r.left, r.top, r.width, r.height]; })()"
        )

        def click(x, y):
            for kind in ("mousePressed", "mouseReleased"):
                event = {"type": kind, "x": x, "y": y, "button": "left", "clickCount": 1}
                chrome.send("Input.dispatchMouseEvent", event)

        click(left + 0.7 * width, top + height / 2)
        state = json.loads(chrome.evaluate(_STATE))
        # The thumb lands near 70% of the track (the thumb's own width shifts it a little).
        assert abs(state["i"] / (frames - 1) - 0.7) < 0.03
        j = int(np.argmin(np.abs(run.t - state["t"])))
        assert run.t[j] == pytest.approx(state["t"], abs=1e-12)
        assert state["q"] == pytest.approx(run.q[j].tolist(), abs=1e-14)

        play = chrome.evaluate(
            "(() => { const r = document.getElementById('play').getBoundingClientRect();"
            " return [r.left + r.width / 2, r.top + r.height / 2]; })()"
        )
        click(*play)
        assert json.loads(chrome.evaluate(_STATE))["button"] == "pause"
        chrome.wait_for(f"+document.getElementById('readouts').dataset.index > {state['i'] + 5}")
        click(*play)  # pause
        paused = json.loads(chrome.evaluate(_STATE))
        time.sleep(0.5)
        still = json.loads(chrome.evaluate(_STATE))
        assert paused["button"] == still["button"] == "play" and still["i"] == paused["i"]
        j = int(np.argmin(np.abs(run.t - still["t"])))
        assert still["q"] == pytest.approx(run.q[j].tolist(), abs=1e-14)
    finally:
        chrome.close()
