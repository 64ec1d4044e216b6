"""The viewer in a real browser: what it shows at a time is the run's state there, and every
element it claims to draw is drawn, in its colour, where the run puts it.

One headless Chromium for the module (tests/browser.py), offline, software rendering. The
state is read back from the page (``#readouts`` data attributes and text, each canvas'
``data-camera``) and compared with the trajectory's own arrays and with scipy's
``Rotation`` (Euler angles, ω and L in space); the screenshot is checked with colour masks at
the places the test computes itself from the run.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from browser import one_browser, rgb, share_near
from scipy.spatial.transform import Rotation

from ga_rotors import simulate
from ga_rotors.view import Line, View, ViewData
from ga_rotors.view.page import ELEMENTS

#: The issue's budget for the page ``ga-rotors view heavy_top`` writes.
PAGE_BYTES = 1_500_000


@pytest.fixture(scope="module")
def chrome(tmp_path_factory):
    yield from one_browser(tmp_path_factory)


@pytest.fixture(scope="module")
def run():
    # An asymmetric body tumbling near its intermediate axis: every component of q moves.
    return simulate((1.0, 2.0, 3.0), [0.9, 0.1, 0.3, 0.3], [0.05, 2.0, 0.3], duration=4.0,
                    step=1e-3, paths=("rotor", "quaternion"))  # fmt: skip


@pytest.fixture(scope="module")
def page(run, tmp_path_factory):
    return View.from_trajectory(run, title="tumbling").save(tmp_path_factory.mktemp("p") / "v.html")


_STATE = """JSON.stringify({
    i: +document.getElementById("readouts").dataset.index,
    t: +document.getElementById("readouts").dataset.time,
    rows: Object.fromEntries([...document.querySelectorAll("#readouts tbody tr")].map((r) => [
        r.dataset.path, {q: JSON.parse(r.querySelector(".q").dataset.q),
                         euler: r.querySelector(".euler").textContent,
                         gimbal: r.querySelector(".gimbal").textContent}])),
    button: document.getElementById("play").textContent,
    drawn: Object.fromEntries([...document.querySelectorAll("#legend li")].map((li) =>
        [li.dataset.element, li.dataset.drawn === "true"])),
    panels: [...document.querySelectorAll("canvas")].map((c) => {
        const r = c.getBoundingClientRect();
        return {left: r.left, top: r.top, width: r.width, height: r.height,
                camera: JSON.parse(c.dataset.camera || "null"),
                elements: JSON.parse(c.dataset.elements || "{}")};
    }),
    readyMs: +document.body.dataset.readyMs,
})"""


def _state(chrome) -> dict:
    return json.loads(chrome.evaluate(_STATE))


@pytest.mark.parametrize("t_wanted", [0.0, 1.2345, 4.0])
def test_slider_time_shows_the_trajectorys_orientation(chrome, run, page, t_wanted):
    chrome.open(page, f"t={t_wanted}")
    state = _state(chrome)
    t_shown = state["t"]
    j = int(np.argmin(np.abs(run.t - t_shown)))
    assert run.t[j] == pytest.approx(t_shown, abs=1e-12)  # a sample of the run, not interpolated
    assert abs(t_shown - t_wanted) <= 4.0 / 599  # the nearest of the page's ≤ 600 frames
    rows = state["rows"]
    assert set(rows) == {"rotor", "quaternion"}
    # The rotor path's coefficients on clifford's blades (1, e12, e13, e23) and
    # R = w − x e23 − y e31 − z e12 (e31 = −e13) give q = (R₀, −R₂₃, R₁₃, −R₁₂).
    r0, r12, r13, r23 = run["rotor_blades"][j]
    assert rows["rotor"]["q"] == pytest.approx([r0, -r23, r13, -r12], abs=1e-14)
    assert rows["quaternion"]["q"] == pytest.approx(run.q[j].tolist(), abs=1e-14)
    psi, theta, phi = Rotation.from_quat(run.q[j], scalar_first=True).as_euler("ZYZ", True)
    shown = [float(a) for a in re.findall(r"(-?[\d.]+)°", rows["quaternion"]["euler"])]
    assert shown == pytest.approx([psi, theta, phi], abs=2e-3)
    assert rows["quaternion"]["gimbal"] == "no"


def _panels(shot, state):
    boxes = [(int(p["top"]), int(p["left"]), int(p["height"]), int(p["width"]))
             for p in state["panels"]]  # fmt: skip
    return [shot[top : top + height, left : left + width] for top, left, height, width in boxes]


def test_the_picture_is_drawn_and_moves_with_the_slider(chrome, page):
    pictures = []
    for t in (0.0, 2.0):
        chrome.open(page, f"t={t}")
        shot = chrome.screenshot()
        assert shot.shape[:2] == (900, 1300)
        pictures.append(np.concatenate(_panels(shot, _state(chrome)), axis=1))
    for picture in pictures:
        drawn = (picture < 0.95).any(axis=-1).mean()
        colours = np.unique((picture * 255).astype(np.uint8).reshape(-1, 3), axis=0).shape[0]
        assert drawn > 0.05, f"only {drawn:.1%} of the pictures is drawn"
        assert colours > 200, f"{colours} colours: the shaded body was not drawn"
    moved = (np.abs(pictures[0] - pictures[1]) > 0.1).any(axis=-1).mean()
    assert moved > 0.01, "the body and vectors did not move between t = 0 and t = 2"


def test_gimbal_lock_is_flagged_on_the_page(chrome, tmp_path):
    # Spin about the body's z axis from the identity: θ = 0 exactly at every sample.
    tr = simulate((1.0, 1.0, 2.0), [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0], duration=1.0,
                  step=1e-2, paths=("quaternion",))  # fmt: skip
    chrome.open(View.from_trajectory(tr).save(tmp_path / "view.html"), "t=0.5")
    row = _state(chrome)["rows"]["quaternion"]
    assert row["gimbal"].startswith("LOCKED")
    # Half a radian about z (RK4 at h|ω| = 0.01: error ~1e-12) and exactly the run's sample.
    assert row["q"] == pytest.approx([np.cos(0.25), 0.0, 0.0, np.sin(0.25)], abs=1e-10)
    assert row["q"] == pytest.approx(tr.q[50].tolist(), abs=1e-14)


def _click(chrome, x, y):
    for kind in ("mousePressed", "mouseReleased"):
        event = {"type": kind, "x": x, "y": y, "button": "left", "clickCount": 1}
        chrome.send("Input.dispatchMouseEvent", event)


def test_a_user_drags_the_slider_and_presses_play(chrome, run, page):
    """Through Chromium's DevTools protocol: mouse events on the slider and the button."""
    import time

    chrome.open(page)
    frames = chrome.evaluate("+document.getElementById('slider').max") + 1
    left, top, width, height = chrome.evaluate(
        "(() => { const r = document.getElementById('slider').getBoundingClientRect();"
        " return [r.left, r.top, r.width, r.height]; })()"
    )
    _click(chrome, left + 0.7 * width, top + height / 2)
    state = _state(chrome)
    # The thumb lands near 70% of the track (the thumb's own width shifts it a little).
    assert abs(state["i"] / (frames - 1) - 0.7) < 0.03
    j = int(np.argmin(np.abs(run.t - state["t"])))
    assert run.t[j] == pytest.approx(state["t"], abs=1e-12)
    assert state["rows"]["quaternion"]["q"] == pytest.approx(run.q[j].tolist(), abs=1e-14)

    play = chrome.evaluate(
        "(() => { const r = document.getElementById('play').getBoundingClientRect();"
        " return [r.left + r.width / 2, r.top + r.height / 2]; })()"
    )
    _click(chrome, *play)
    assert _state(chrome)["button"] == "pause"
    chrome.wait_for(f"+document.getElementById('readouts').dataset.index > {state['i'] + 5}")
    _click(chrome, *play)  # pause
    paused = _state(chrome)
    time.sleep(0.5)
    still = _state(chrome)
    assert paused["button"] == still["button"] == "play" and still["i"] == paused["i"]
    j = int(np.argmin(np.abs(run.t - still["t"])))
    assert still["rows"]["quaternion"]["q"] == pytest.approx(run.q[j].tolist(), abs=1e-14)


def test_dragging_a_picture_turns_the_view_and_double_click_resets_it(chrome, page):
    chrome.open(page, "t=1")
    before = _state(chrome)["panels"]
    p = before[0]
    x, y = p["left"] + p["width"] / 2, p["top"] + p["height"] / 2
    for kind, dx in (("mousePressed", 0), ("mouseMoved", 60), ("mouseReleased", 60)):
        chrome.send(
            "Input.dispatchMouseEvent",
            {"type": kind, "x": x + dx, "y": y, "button": "left", "buttons": 1, "clickCount": 1},
        )
    after = _state(chrome)["panels"]
    for b, a in zip(before, after, strict=True):  # every path's picture turns together
        assert not np.allclose(a["camera"]["right"], b["camera"]["right"])
        assert a["elements"]["omega"] != b["elements"]["omega"]
    chrome.send(
        "Input.dispatchMouseEvent",
        {"type": "mousePressed", "x": x, "y": y, "button": "left", "clickCount": 2},
    )
    chrome.send(
        "Input.dispatchMouseEvent",
        {"type": "mouseReleased", "x": x, "y": y, "button": "left", "clickCount": 2},
    )
    assert np.allclose(_state(chrome)["panels"][0]["camera"]["right"], p["camera"]["right"])


# ---------------------------------------------------------------- the heavy top, element by element


@pytest.fixture(scope="module")
def heavy_top(tmp_path_factory):
    """``ga-rotors view heavy_top`` (the whole 3 s run) and the run itself, as the oracle."""
    from ga_rotors.cli import main
    from ga_rotors.scene import load_scene, run_scene

    out = tmp_path_factory.mktemp("heavy") / "heavy_top.view.html"
    assert main(["view", "heavy_top", "--out", str(out)]) == 0
    scene = load_scene("heavy_top")
    return out, scene, run_scene(scene)


def test_the_heavy_top_page_draws_each_element_where_the_run_puts_it(chrome, heavy_top):
    page, scene, tr = heavy_top
    size = page.stat().st_size
    print(f"\nga-rotors view heavy_top: {size / 1e6:.3f} MB", end="")
    assert size < PAGE_BYTES
    chrome.open(page, "t=1.5")
    state = _state(chrome)
    print(f"; first frame drawn {state['readyMs']:.0f} ms after navigation (not a benchmark)")
    data = json.loads(re.search(r'id="view-data">(.*?)</script>', page.read_text(), re.S)[1])

    # The legend lists the elements, and each says it was drawn.
    expected = {"body", "pivot", "e1", "e2", "e3", "omega", "L", "plane", "trace"}
    assert set(state["drawn"]) == expected and all(state["drawn"].values()), state["drawn"]

    # Where each element belongs, from the run (scipy for the rotation): ω and L at the
    # sample shown, each scaled by its largest length over the run.
    j = int(np.flatnonzero(tr.t == state["t"])[0])
    moments = np.asarray(scene.body.moments)
    rotation = Rotation.from_quat(tr.q[j], scalar_first=True)
    omega = rotation.apply(tr.w[j]) / np.linalg.norm(tr.w, axis=1).max()
    L = rotation.apply(tr.w[j] * moments) / np.linalg.norm(tr.w * moments, axis=1).max()
    lengths = {v["key"]: v["length"] for v in data["vectors"]}
    per_metre = 1.0 / data["metresPerUnit"]
    com = rotation.apply(scene.data["effects"][0]["pivot_to_com"]) * per_metre
    w, x, y, z = tr.q[j]
    alpha, u = 2 * np.arctan2(np.linalg.norm([x, y, z]), w), np.array([x, y, z])
    u /= np.linalg.norm(u)
    a = np.array([1.0, 0, 0]) - u[0] * u  # the plane's direction nearest space x
    a /= np.linalg.norm(a)
    arc_middle = 0.9 * (a * np.cos(alpha / 2) + np.cross(u, a) * np.sin(alpha / 2))
    places = {
        "omega": omega * lengths["omega"],
        "L": L * lengths["L"],
        "pivot": np.zeros(3),
        "plane": arc_middle,
        "trace": rotation.apply([0.0, 0.0, 1.0]),  # the disk's symmetry axis, on the sphere
        **{f"e{k + 1}": com + rotation.apply(np.eye(3)[k]) * data["body"]["axisLength"]
           for k in range(3)},
    }  # fmt: skip

    shot = chrome.screenshot()
    for panel in state["panels"]:
        cam = panel["camera"]

        def screen(p, panel=panel, cam=cam):
            return (
                panel["left"] + cam["cx"] + cam["scale"] * np.dot(p, cam["right"]),
                panel["top"] + cam["cy"] - cam["scale"] * np.dot(p, cam["up"]),
            )

        for key, place in places.items():
            xy = screen(place)
            reported = panel["elements"][key]
            at = np.subtract(xy, [panel["left"], panel["top"]])
            assert np.allclose(reported, at, atol=0.6), key
            if key.startswith("e"):  # a body axis may be behind the body: placed, not seen
                continue
            colour = rgb(ELEMENTS[key][1])
            found = share_near(shot, xy, colour, radius=5 if key == "pivot" else 3)
            assert found > 0.05, f"{key}: not drawn at {xy} in {ELEMENTS[key][1]}"
        # ω and L: their shafts too, beyond the body (ω, thinner, is painted over L).
        for key in ("omega", "L"):
            along = [share_near(shot, screen(f * places[key]), rgb(ELEMENTS[key][1])) > 0.05
                     for f in (0.72, 0.8, 0.88, 0.95)]  # fmt: skip
            assert sum(along) >= 3, f"{key}: its shaft is not drawn ({along})"
        # The body: a shaded grey disk around its centre of mass.
        x0, y0, x1, y1 = panel["elements"]["body"]
        cx, cy = np.subtract(screen(com), [panel["left"], panel["top"]])
        assert x0 < cx < x1 and y0 < cy < y1
        region = shot[int(panel["top"] + y0) : int(panel["top"] + y1),
                      int(panel["left"] + x0) : int(panel["left"] + x1)]  # fmt: skip
        lightness = region.mean(axis=-1)
        grey = (np.ptp(region, axis=-1) < 0.12) & (lightness > 0.3) & (lightness < 0.85)
        # At least half the disk's projected area, π r² |n·eye| (less what ω, L and the axes
        # cover), is body-grey.
        r = scene.data["body"]["radius"] * per_metre * cam["scale"]
        seen = np.pi * r * r * abs(np.dot(rotation.apply([0.0, 0.0, 1.0]), cam["eye"]))
        assert grey.sum() > max(0.5 * seen, 100), f"{grey.sum()} body-grey pixels of {seen:.0f}"
        # The rotor's plane: a light tint of its colour over the white inside its rim.
        b = np.cross(u, a)
        tinted = 0
        for angle in np.linspace(0, 2 * np.pi, 16, endpoint=False):
            px, py = screen(0.7 * (a * np.cos(angle) + b * np.sin(angle)))
            r_, _, b_ = shot[int(np.rint(py)), int(np.rint(px))]
            tinted += r_ > 0.9 and r_ - b_ > 0.08
        assert tinted >= 4, f"the plane's tint at {tinted} of 16 points"
        # The pivot: a black ring with a white middle.
        px, py = screen(np.zeros(3))
        assert shot[int(np.rint(py)), int(np.rint(px))].min() > 0.9

    # Each legend entry shows its element's colour.
    boxes = json.loads(chrome.evaluate(
        "JSON.stringify([...document.querySelectorAll('#legend li')].map((li) => {"
        " const r = li.querySelector('svg').getBoundingClientRect();"
        " return [li.dataset.element, r.left, r.top, r.width, r.height]; }))"
    ))  # fmt: skip
    for key, left, top, width, height in boxes:
        swatch = shot[int(top) : int(top + height), int(left) : int(left + width)]
        assert (np.linalg.norm(swatch - rgb(ELEMENTS[key][1]), axis=-1) < 0.15).any(), key


def test_a_moving_body_and_a_line_in_space_are_drawn(chrome, tmp_path):
    """Room for rigid motion: the body follows a per-sample position; a line is drawn."""
    t = np.linspace(0.0, 1.0, 11)
    position = np.outer(t - 0.5, [0.0, 2.0, 0.0])
    line = Line("velocity", "velocity line", position, np.tile([0.0, 1.0, 0.2], (11, 1)), "#7b3294")
    d = ViewData(t, {"rotor": np.tile([1.0, 0, 0, 0], (11, 1))}, np.tile([0, 0, 1.0], (11, 1)),
                 (1.0, 1.0, 2.0), positions={"rotor": position}, lines=[line])  # fmt: skip
    page = View(d).save(tmp_path / "moving.html")
    boxes = []
    for frame in (0, 10):
        chrome.open(page, f"frame={frame}")
        state = _state(chrome)
        assert state["drawn"]["velocity"]
        panel = state["panels"][0]
        boxes.append(panel["elements"]["body"])
        shot = chrome.screenshot()
        lx, ly = panel["elements"]["velocity"]
        assert share_near(shot, (panel["left"] + lx, panel["top"] + ly), rgb("#7b3294"), 6) > 0
    assert boxes[1][0] > boxes[0][0] + 50  # the body moved right (+y is to the right here)
