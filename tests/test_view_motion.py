"""The viewer of a body moving through space, in a real browser: ``ga-rotors view
thrown_racket`` moves the racket along its flight, draws the centre of mass' trail and the
velocity line (the instantaneous screw axis) where the run puts them, frames the whole
flight, and plays.

The oracles are the run's own arrays and the screw axis written out here: the point a of
the axis is where the velocity of the body point at a, v_origin + ω × (a − p), lies along ω.
"""

from __future__ import annotations

import json
import re
import time

import numpy as np
import pytest
from browser import one_browser, rgb, share_near

from ga_rotors import quaternion as Q
from ga_rotors.view.data import VELOCITY_LINE
from ga_rotors.view.page import ELEMENTS

PAGE_BYTES = 1_500_000

_STATE = """JSON.stringify({
    i: +document.getElementById("readouts").dataset.index,
    t: +document.getElementById("readouts").dataset.time,
    q: Object.fromEntries([...document.querySelectorAll("#readouts tbody tr")].map((r) =>
        [r.dataset.path, JSON.parse(r.querySelector(".q").dataset.q)])),
    button: document.getElementById("play").textContent,
    drawn: Object.fromEntries([...document.querySelectorAll("#legend li")].map((li) =>
        [li.dataset.element, li.dataset.drawn === "true"])),
    panels: [...document.querySelectorAll("canvas")].map((c) => {
        const r = c.getBoundingClientRect();
        return {left: r.left, top: r.top, width: r.width, height: r.height,
                camera: JSON.parse(c.dataset.camera || "null"),
                elements: JSON.parse(c.dataset.elements || "{}")};
    }),
})"""


@pytest.fixture(scope="module")
def chrome(tmp_path_factory):
    yield from one_browser(tmp_path_factory)


@pytest.fixture(scope="module")
def racket(tmp_path_factory):
    """``ga-rotors view thrown_racket`` and the run itself, the oracle."""
    from ga_rotors.cli import main
    from ga_rotors.scene import load_scene, run_scene

    out = tmp_path_factory.mktemp("racket") / "thrown_racket.view.html"
    assert main(["view", "thrown_racket", "--out", str(out)]) == 0
    scene = load_scene("thrown_racket")
    data = json.loads(re.search(r'id="view-data">(.*?)</script>', out.read_text(), re.S)[1])
    return out, scene, run_scene(scene), data


def _state(chrome) -> dict:
    return json.loads(chrome.evaluate(_STATE))


def _affine(drawn, metres):
    """(k, c) with drawn = k (metres − c), fitted; and the largest misfit (drawing units)."""
    a, b = np.asarray(metres).reshape(-1, 3), np.asarray(drawn).reshape(-1, 3)
    am, bm = a.mean(axis=0), b.mean(axis=0)
    k = float(((a - am) * (b - bm)).sum() / ((a - am) ** 2).sum())
    c = am - bm / k
    return k, c, float(np.abs(k * (a - c) - b).max())


def test_the_page_is_light_and_places_the_flight_where_the_run_puts_it(racket):
    page, scene, tr, data = racket
    assert page.stat().st_size < PAGE_BYTES
    frames = np.array([int(np.argmin(np.abs(tr.t - t))) for t in data["t"]])
    assert np.allclose(tr.t[frames], data["t"], rtol=0, atol=1e-12)
    s = np.array(scene.data["body"]["centre_of_mass"])
    k = c = None
    for p in data["paths"]:
        name = p["name"]
        # the body's origin: one scale and one shift for every frame of every path
        found = _affine(p["position"], tr.positions(name)[frames])
        if k is None:
            k, c, misfit = found
        else:
            misfit = np.abs(k * (tr.positions(name)[frames] - c) - np.array(p["position"])).max()
        assert misfit < 2e-5
        # the trail: the centre of mass, origin + q s q*
        centre = tr.positions(name) + Q.rotate(Q.normalize(tr.quaternions(name)), s)
        trail = np.array(p["trail"])
        assert trail.shape[0] == tr.t.size  # every sample (within MAX_TRACE)
        assert np.abs(k * (centre - c) - trail).max() < 2e-5
    assert data["metresPerUnit"] == pytest.approx(1.0 / k, rel=1e-6)
    # the velocity line: along ω in space, through points whose velocity is along ω
    (line,) = data["lines"]
    assert line["key"] == "velocity" and line["colour"] == VELOCITY_LINE[1]
    q = Q.normalize(tr.quaternions())[frames]
    w_space = Q.rotate(q, tr.w[frames])
    u = w_space / np.linalg.norm(w_space, axis=1)[:, None]
    assert np.abs(np.array(line["direction"]) - u).max() < 2e-6
    a = np.array(line["point"]) / k + c  # metres
    p0 = tr.positions()[frames]
    v_at_a = tr.velocities()[frames] + np.cross(w_space, a - p0)
    across = np.linalg.norm(np.cross(v_at_a, u), axis=1)
    speed = np.linalg.norm(tr.velocities()[frames], axis=1)
    assert (across < 1e-4 * speed + 1e-9).all()


def test_every_element_is_drawn_the_flight_is_framed_and_the_body_moves(chrome, racket):
    page, _, tr, data = racket
    boxes = []
    for t in (0.1, 0.6, 1.0):
        chrome.open(page, f"t={t}")
        state = _state(chrome)
        expected = {"body", "e1", "e2", "e3", "omega", "L", "plane", "trace", "trail",
                    "velocity"}  # fmt: skip
        assert set(state["drawn"]) == expected and all(state["drawn"].values()), state["drawn"]
        j = int(np.flatnonzero(tr.t == state["t"])[0])
        for path, q in state["q"].items():  # the readouts are the run's state at that time
            assert q == pytest.approx(Q.normalize(tr.quaternions(path)[j]).tolist(), abs=1e-14)
        shot = chrome.screenshot()
        for panel, p in zip(state["panels"], data["paths"], strict=True):
            cam = panel["camera"]

            def screen(x, panel=panel, cam=cam):
                return (cam["cx"] + cam["scale"] * np.dot(x, cam["right"]),
                        cam["cy"] - cam["scale"] * np.dot(x, cam["up"]))  # fmt: skip

            # the whole flight is in the picture
            for x in p["trail"]:
                sx, sy = screen(x)
                assert 0 <= sx <= panel["width"] and 0 <= sy <= panel["height"]
            # the trail is drawn in its colour where it says (its current point)
            lx, ly = panel["elements"]["trail"]
            found = share_near(shot, (panel["left"] + lx, panel["top"] + ly),
                          rgb(ELEMENTS["trail"][1]), 6)  # fmt: skip
            assert found > 0.02, f"trail not drawn at ({lx:.0f}, {ly:.0f})"
            # the velocity line: anchored at its point of the run, and drawn along its axis
            # in its colour (dashed, and here and there under the body or a vector)
            i = state["i"]
            point, direction = (np.array(data["lines"][0][k][i]) for k in ("point", "direction"))
            assert np.allclose(panel["elements"]["velocity"], screen(point), atol=0.6)
            seen = 0
            for s in (-0.9, -0.7, -0.5, 0.5, 0.7, 0.9):
                sx, sy = screen(point + s * direction)
                if 8 < sx < panel["width"] - 8 and 8 < sy < panel["height"] - 8:
                    xy = (panel["left"] + sx, panel["top"] + sy)
                    seen += share_near(shot, xy, rgb(VELOCITY_LINE[1]), 5) > 0.02
            assert seen >= 3, f"the velocity line is seen at {seen} of 6 points along it"
            # the body's box holds its centre of mass, the trail's current point
            k = int(p["trailUpTo"][i]) - 1
            cx, cy = screen(p["trail"][k])
            x0, y0, x1, y1 = panel["elements"]["body"]
            assert x0 - 1 <= cx <= x1 + 1 and y0 - 1 <= cy <= y1 + 1
        boxes.append(state["panels"][0]["elements"]["body"])
    # the racket flies across the picture (its horizontal travel runs left to right)
    assert boxes[2][0] > boxes[0][0] + 100


def test_play_pause_and_the_slider_move_the_flight(chrome, racket):
    page, _, tr, data = racket
    chrome.open(page)
    before = _state(chrome)["panels"][0]["elements"]["trail"]
    chrome.evaluate("(() => { const s = document.getElementById('slider'); s.value = '70';"
                    " s.dispatchEvent(new Event('input')); })()")  # fmt: skip
    state = _state(chrome)
    assert state["i"] == 70 and state["t"] == pytest.approx(data["t"][70])
    assert state["panels"][0]["elements"]["trail"] != before
    chrome.evaluate("document.getElementById('play').click()")
    assert _state(chrome)["button"] == "pause"
    chrome.wait_for("+document.getElementById('readouts').dataset.index > 75")
    chrome.evaluate("document.getElementById('play').click()")
    paused = _state(chrome)
    time.sleep(0.3)
    still = _state(chrome)
    assert still["button"] == "play" and still["i"] == paused["i"]
    j = int(np.flatnonzero(tr.t == still["t"])[0])
    assert still["q"]["motor"] == pytest.approx(
        Q.normalize(tr.quaternions("motor")[j]).tolist(), abs=1e-14
    )


def test_a_saved_result_of_a_moving_body_views_as_its_run(racket, tmp_path):
    """``ga-rotors view RESULT`` of a racket's npz result: the same flight as the run's page
    (the quaternion path's origin needs the centre of mass, from the saved scene)."""
    from ga_rotors.cli import main
    from ga_rotors.scene import Scene

    _, scene, _, data = racket
    moved = Scene({**scene.to_dict(), "output": {**scene.data["output"], "data": ["npz"]}})
    (tmp_path / "racket.toml").write_text(moved.to_toml())
    assert main(["run", str(tmp_path / "racket.toml"), "--out", str(tmp_path / "out"),
                 "--no-progress"]) == 0  # fmt: skip
    out = tmp_path / "saved.html"
    assert main(["view", str(tmp_path / "out"), "--out", str(out)]) == 0
    saved = json.loads(re.search(r'id="view-data">(.*?)</script>', out.read_text(), re.S)[1])
    for a, b in zip(saved["paths"], data["paths"], strict=True):
        assert a["name"] == b["name"]
        assert np.allclose(a["trail"], b["trail"], atol=1e-5)
        assert np.allclose(a["position"], b["position"], atol=1e-5)
    assert np.allclose(saved["lines"][0]["point"], data["lines"][0]["point"], atol=1e-5)
