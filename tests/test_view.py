"""The viewer's data, page and command, without a browser (tests/test_view_browser.py opens it)."""

from __future__ import annotations

import contextlib
import html
import io
import json
import re
import warnings

import numpy as np
import pytest

pytest.importorskip("plotly")

from ga_rotors import quaternion as Q
from ga_rotors import simulate
from ga_rotors.cli import main
from ga_rotors.errors import GimbalLockWarning, InputError, IntegrationStoppedWarning
from ga_rotors.scene import load_scene
from ga_rotors.view import View, ViewData, from_trajectory
from ga_rotors.view.data import symmetry_axis
from ga_rotors.view.page import MAX_FRAMES, _payload, page_html


def _embedded(text: str, element_id: str):
    m = re.search(rf'<script type="application/json" id="{element_id}">(.*?)</script>', text, re.S)
    return json.loads(m.group(1))


def _cli(*argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(list(argv))
    return status, out.getvalue(), err.getvalue()


@pytest.mark.parametrize(
    ("moments", "axis"),
    [
        ((1, 1, 2), 2),
        ((2, 1, 1), 0),
        ((1, 2, 1), 1),
        ((1, 2, 3), 2),
        ((3, 2, 1), 0),
        ((1, 1, 1), 2),
    ],
)
def test_symmetry_axis_is_the_moment_that_stands_apart(moments, axis):
    assert symmetry_axis(moments) == axis


@pytest.mark.parametrize(
    ("paths", "w", "key"),
    [
        ({}, np.zeros((2, 3)), "paths"),
        ({"rotor": np.zeros((2, 3))}, np.zeros((2, 3)), "paths['rotor']"),
        ({"rotor": np.full((2, 4), np.nan)}, np.zeros((2, 3)), "paths['rotor']"),
        ({"rotor": np.ones((3, 4))}, np.zeros((2, 3)), "paths['rotor']"),
        ({"rotor": np.ones((2, 4))}, np.zeros((2, 2)), "w"),
    ],
)
def test_bad_view_data_names_its_key(paths, w, key):
    with pytest.raises(InputError, match=re.escape(key)):
        ViewData(np.array([0.0, 1.0]), paths, w, (1.0, 1.0, 2.0))


def test_the_page_carries_every_paths_orientation_thinned_to_max_frames():
    tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.1, 2.0, 0.1], duration=3.0, step=1e-3,
                  paths=("rotor", "quaternion"))  # fmt: skip
    d = _payload(from_trajectory(tr))
    assert len(d["t"]) == MAX_FRAMES and d["t"][0] == 0.0 and d["t"][-1] == 3.0
    for p in d["paths"]:
        j = np.searchsorted(tr.t, d["t"])
        assert np.allclose(p["q"], tr.q[j], atol=1e-14)  # rotor and quaternion paths agree
    # L = I ω, drawn in space, is what the page rotates by q.
    assert np.allclose(d["L"], np.array(d["w"]) * [1.0, 2.0, 3.0])


def test_a_path_that_stopped_early_says_when():
    # The Euler-angle path stops when sin θ hits 0 exactly: spin about z from the identity.
    # The Euler path starts at θ = 0 (locked) and stops when its state stops being finite.
    with pytest.warns(GimbalLockWarning), pytest.warns(IntegrationStoppedWarning):
        tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.5,
                      step=0.1, paths=("quaternion", "euler"))  # fmt: skip
    if tr.euler.shape[0] == tr.t.shape[0]:
        pytest.skip("the Euler path ran to the end here")
    euler = next(p for p in _payload(from_trajectory(tr))["paths"] if p["name"] == "euler")
    assert euler["endedAt"] == tr.t[tr.euler.shape[0] - 1]
    assert euler["frames"] == tr.euler.shape[0]


def test_a_tensor_body_is_drawn_in_its_principal_frame():
    from ga_rotors.body import RigidBody

    c, s = np.cos(0.4), np.sin(0.4)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    tensor = R @ np.diag([1.0, 2.0, 2.5]) @ R.T
    body = RigidBody.from_tensor(tensor)
    tr = simulate(body, [1.0, 0, 0, 0], [0.3, 1.0, 0.2], duration=0.5, step=1e-2)
    user = from_trajectory(tr)  # the user's body frame
    d = from_trajectory(tr, moments=body.moments, principal=body.principal_rotation)
    P = np.array(body.principal_rotation)
    assert np.allclose(d.paths["rotor"], Q.multiply(user.paths["rotor"], P), atol=1e-14)
    # L in space is the same whichever frame draws it: q (T ω) q* = q_P (I_P ω_P) q_P*.
    L_user = Q.rotate(user.paths["rotor"], tr.w @ tensor.T)
    L_principal = Q.rotate(d.paths["rotor"], d.w * np.array(body.moments))
    assert np.allclose(L_user, L_principal, atol=1e-12)


def test_untrusted_titles_cannot_leave_their_element():
    evil = "</script><script>alert(1)</script><!--"
    d = ViewData(np.array([0.0]), {"rotor": np.array([[1.0, 0, 0, 0]])}, np.zeros((1, 3)),
                 (1.0, 1.0, 2.0), title=evil, description=evil)  # fmt: skip
    text = page_html(d)
    assert "<script>alert(1)" not in text
    assert _embedded(text, "view-data")["title"] == evil
    assert f"<h1>{html.escape(evil)}</h1>" in text
    assert f'<p id="description">{html.escape(evil)}</p>' in text


def test_the_page_loads_nothing_from_elsewhere():
    tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.1, 1.0], duration=0.1, step=1e-2)
    text = View.from_trajectory(tr).html()
    assert not re.search(r"<(script|link|img|iframe)[^>]*\b(src|href)=", text)
    assert "Plotly.newPlot" in text and "plotly.js" in text.lower()


def test_notebook_display_is_an_isolated_frame_holding_the_page():
    tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.1, 1.0], duration=0.1, step=1e-2)
    v = View.from_trajectory(tr, title='a "quoted" title')
    frame = v._repr_html_()
    srcdoc = re.match(r'<iframe srcdoc="([^"]*)"', frame).group(1)
    assert html.unescape(srcdoc) == v.html()


def test_view_command_on_a_scene(tmp_path):
    out = tmp_path / "disk.html"
    status, text, err = _cli("view", "spinning_disk", "--duration", "0.2", "--out", str(out))
    assert (status, err) == (0, "")
    assert f"wrote {out}" in text
    data = _embedded(out.read_text(encoding="utf-8"), "view-data")
    assert data["title"] == "spinning_disk" and data["t"][-1] == pytest.approx(0.2)
    about = html.escape(load_scene("spinning_disk").description)  # what the run is about
    assert f'<p id="description">{about}</p>' in out.read_text(encoding="utf-8")
    assert next(p["name"] for p in data["paths"]) == load_scene("spinning_disk").paths[0]


def test_view_command_on_a_saved_result(tmp_path):
    from ga_rotors.scene import run_scene, write_outputs

    scene = load_scene("heavy_top").replace({"time.duration": 0.2, "output.data": ["npz"]})
    write_outputs(scene, run_scene(scene), tmp_path / "res", None)
    status, _text, err = _cli("view", str(tmp_path / "res"))
    assert (status, err) == (0, "")
    page = tmp_path / "res" / "heavy_top.view.html"
    data = _embedded(page.read_text(encoding="utf-8"), "view-data")
    assert data["moments"] == list(scene.body.moments)
    # The same page from the .npz file itself, written where --out says.
    status, _, _ = _cli("view", str(tmp_path / "res" / "heavy_top.npz"), "--out",
                        str(tmp_path / "b.html"))  # fmt: skip
    assert status == 0
    assert _embedded((tmp_path / "b.html").read_text(encoding="utf-8"), "view-data") == data


@pytest.mark.parametrize(
    ("make", "argv", "message"),
    [
        (None, ["no_such_scene"], "no_such_scene: no such file"),
        ("empty_dir", ["{tmp}"], "no .npz result here"),
        ("lonely_npz", ["{tmp}/x.npz"], "no x.scene.toml beside it"),
        ("empty_dir", ["{tmp}", "--duration", "1"], "--duration: applies to a scene"),
        (None, ["spinning_disk", "--duration", "-1"], "time.duration"),
        ("nan_w", ["{tmp}/x.npz"], "x.npz: w: expected finite numbers"),
        ("bad_q", ["{tmp}/x.npz"], "x.npz: q: expected shape (n, 4), got (3, 3)"),
        ("bad_rotor", ["{tmp}/x.npz"], "x.npz: rotor_blades: expected shape (n, 4), got (2, 4, 2)"),
    ],
)
def test_view_command_errors_are_one_line(tmp_path, make, argv, message):
    if make == "lonely_npz":
        np.savez(tmp_path / "x.npz", t=np.zeros(2))
    if make in ("nan_w", "bad_q", "bad_rotor"):
        (tmp_path / "x.scene.toml").write_text(load_scene("spinning_disk").to_toml())
        good = {"t": np.arange(3.0), "w": np.zeros((3, 3)), "q": np.tile([1.0, 0, 0, 0], (3, 1))}
        bad = {"nan_w": {"w": np.full((3, 3), np.nan)}, "bad_q": {"q": np.zeros((3, 3))},
               "bad_rotor": {"rotor_blades": np.ones((2, 4, 2))}}[make]  # fmt: skip
        np.savez(tmp_path / "x.npz", **(good | bad))
    status, _, err = _cli("view", *[a.format(tmp=tmp_path) for a in argv])
    assert status == 2
    assert err.count("\n") == 1 and message in err, err
    assert not list(tmp_path.glob("*.html"))


def test_run_names_the_view_command_that_shows_its_result(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene = load_scene("spinning_disk").replace({"time.duration": 0.2, "output.data": ["npz"]})
    (tmp_path / "disk.toml").write_text(scene.to_toml(), encoding="utf-8")
    status, text, _ = _cli("run", "disk.toml", "--out", "res", "--no-progress")
    assert status == 0
    line = next(x for x in text.splitlines() if x.startswith("see it move: "))
    command = line.removeprefix("see it move: ga-rotors ").split(" (")[0].split()
    assert command == ["view", "res"]
    assert _cli(*command)[0] == 0  # the command it names works
    assert (tmp_path / "res" / "spinning_disk.view.html").is_file()


def test_the_commands_docs_view_shows_run(tmp_path, monkeypatch):
    from pathlib import Path

    page = Path(__file__).resolve().parents[1] / "docs" / "view.md"
    block = re.search(r"```console\n(.*?)```", page.read_text(encoding="utf-8"), re.S).group(1)
    commands = [line.split("#")[0].split() for line in block.splitlines()]
    commands = [c[1:] for c in commands if c and c[0] == "ga-rotors"]
    assert [c[0] for c in commands] == ["view", "view", "run", "view"]
    monkeypatch.chdir(tmp_path)
    for argv in commands:
        with warnings.catch_warnings():  # fast_spinner's step-limit line is printed, not raised
            warnings.simplefilter("ignore")
            status, _, err = _cli(*argv, *(["--no-progress"] if argv[0] == "run" else []))
        assert status == 0, (argv, err)
    written = sorted(p.name for p in tmp_path.rglob("*.html"))
    assert written == ["fast_spinner.view.html", "heavy_top.view.html", "top.html"]
