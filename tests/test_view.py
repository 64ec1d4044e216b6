"""The viewer's data, page and command, without a browser (tests/test_view_browser.py opens it).

Oracles: the closed-form moments of uniform solids (ga_rotors.shapes, and m(b² + c²)/5 for an
ellipsoid), scipy's Rotation for the frames, strict JSON for the page's data.
"""

from __future__ import annotations

import contextlib
import html
import io
import json
import re
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from ga_rotors import quaternion as Q
from ga_rotors import simulate
from ga_rotors.cli import main
from ga_rotors.errors import GimbalLockWarning, InputError, IntegrationStoppedWarning
from ga_rotors.scene import Scene, load_scene
from ga_rotors.view import Line, View, ViewData, from_trajectory
from ga_rotors.view.data import symmetry_axis
from ga_rotors.view.geometry import KINDS, THIN, Solid, from_inertia, from_scene
from ga_rotors.view.page import ELEMENTS, MAX_FRAMES, page_html, payload

#: The page's budget (issue 31): a page a student opens at once.
PAGE_BYTES = 1_500_000
ONE = np.array([[1.0, 0.0, 0.0, 0.0]])


def _embedded(text: str, element_id: str):
    m = re.search(rf'<script type="application/json" id="{element_id}">(.*?)</script>', text, re.S)

    def refuse(name):  # NaN, Infinity: what Python's json accepts and JSON.parse does not
        raise ValueError(f"not JSON: {name}")

    return json.loads(m.group(1), parse_constant=refuse)


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
    d = ViewData(np.array([0.0]), {"rotor": ONE}, np.zeros((1, 3)), moments)
    assert d.symmetry_direction.tolist() == np.eye(3)[axis].tolist()


@pytest.mark.parametrize(
    ("t", "paths", "w", "key"),
    [
        ([0.0, 1.0], {}, np.zeros((2, 3)), "paths"),
        ([0.0, 1.0], {"rotor": np.zeros((2, 3))}, np.zeros((2, 3)), "paths['rotor']"),
        ([0.0, 1.0], {"rotor": np.full((2, 4), np.nan)}, np.zeros((2, 3)), "paths['rotor']"),
        ([0.0, 1.0], {"rotor": np.ones((3, 4))}, np.zeros((2, 3)), "paths['rotor']"),
        ([0.0, 1.0], {"rotor": np.ones((2, 4))}, np.zeros((2, 2)), "w"),
        ([0.0, 1.0], {"rotor": np.ones((2, 4))}, np.full((2, 3), 1j), "w: expected real numbers"),
        ([0.0, 1.0j], {"rotor": np.ones((2, 4))}, np.zeros((2, 3)), "t: expected real numbers"),
        (["0", "1"], {"rotor": np.ones((2, 4))}, np.zeros((2, 3)), "t: expected real numbers"),
        ([0.0, np.inf], {"rotor": np.ones((2, 4))}, np.zeros((2, 3)), "t: contains inf"),
        ([1.0, 0.0], {"rotor": np.ones((2, 4))}, np.zeros((2, 3)),
         "t: expected strictly increasing times, got t[1] = 0 after t[0] = 1"),
        ([0.0, 0.0], {"rotor": np.ones((2, 4))}, np.zeros((2, 3)), "strictly increasing"),
    ],
)  # fmt: skip
def test_bad_view_data_names_its_key_in_one_line(t, paths, w, key):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # complex values were cast with a ComplexWarning
        with pytest.raises(InputError, match=re.escape(key)) as caught:
            ViewData(np.array(t), paths, w, (1.0, 1.0, 2.0))
    assert "\n" not in str(caught.value)


def test_an_angular_momentum_beyond_float64_is_refused_not_written_as_infinity():
    # |Iω| overflows although ω and I are finite: the page once held "LMax":Infinity.
    w = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1e300]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy RuntimeWarning before the error
        with pytest.raises(InputError, match=r"^L: L = Iω overflows float64 at t = 1 s"):
            ViewData(np.array([0.0, 1.0]), {"rotor": np.vstack([ONE, ONE])}, w, (1e10, 1e10, 2e10))
    # Finite but huge vectors: their lengths are taken without overflow, the JSON is strict.
    big = np.array([[1e308, 1e308, 0.0]])
    d = ViewData(np.array([0.0]), {"rotor": ONE}, big, (1e-3, 1e-3, 1e-3))
    data = _embedded(page_html(d), "view-data")
    assert data["vectors"][0]["max"] == pytest.approx(np.sqrt(2) * 1e308)
    assert data["vectors"][0]["values"][0] == pytest.approx([0.707107, 0.707107, 0.0])


def test_control_characters_and_markup_never_reach_the_page_raw():
    evil = "top\x1b]0;pwned\x07\u202e</script><script>alert(1)</script><!--\n"
    d = ViewData(np.array([0.0]), {evil: ONE}, np.zeros((1, 3)), (1.0, 1.0, 2.0), title=evil,
                 description=evil)  # fmt: skip
    text = page_html(d)
    assert "<script>alert(1)" not in text
    assert not re.search(r"[\x00-\x08\x0b-\x1f\x7f\u202e]", text)  # \n is the only one kept
    shown = "top\\x1b]0;pwned\\x07\\u202e</script><script>alert(1)</script><!--\\n"
    assert _embedded(text, "view-data")["title"] == shown
    assert f"<h1>{html.escape(shown)}</h1>" in text
    assert _embedded(text, "view-data")["paths"][0]["name"] == shown


def test_the_page_carries_every_paths_orientation_thinned_to_max_frames():
    tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.1, 2.0, 0.1], duration=3.0, step=1e-3,
                  paths=("rotor", "quaternion"))  # fmt: skip
    d = payload(from_trajectory(tr))
    assert len(d["t"]) == MAX_FRAMES and d["t"][0] == 0.0 and d["t"][-1] == 3.0
    j = np.searchsorted(tr.t, d["t"])
    for p in d["paths"]:
        assert np.allclose(p["q"], tr.q[j], atol=1e-14)  # rotor and quaternion paths agree
    # ω and L = I ω in the body frame, each scaled by its largest length over the run.
    omega, L = d["vectors"]
    assert omega["max"] == pytest.approx(np.linalg.norm(tr.w, axis=1).max(), rel=1e-14)
    L_body = tr.w * [1.0, 2.0, 3.0]
    assert L["max"] == pytest.approx(np.linalg.norm(L_body, axis=1).max(), rel=1e-14)
    assert np.allclose(np.array(L["values"]) * L["max"], L_body[j], atol=1e-5 * L["max"])


def test_a_path_that_stopped_early_says_when():
    # The Euler path starts at θ = 0 (locked) and stops when its state stops being finite.
    with pytest.warns(GimbalLockWarning), pytest.warns(IntegrationStoppedWarning):
        tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.5,
                      step=0.1, paths=("quaternion", "euler"))  # fmt: skip
    if tr.euler.shape[0] == tr.t.shape[0]:
        pytest.skip("the Euler path ran to the end here")
    euler = next(p for p in payload(from_trajectory(tr))["paths"] if p["name"] == "euler")
    assert euler["endedAt"] == tr.t[tr.euler.shape[0] - 1]
    assert euler["frames"] == tr.euler.shape[0]


def test_a_tensor_body_is_drawn_in_the_frame_it_was_written_in():
    from ga_rotors.body import RigidBody

    turn = Rotation.from_rotvec([0.2, -0.3, 0.4])
    tensor = turn.as_matrix() @ np.diag([1.0, 2.0, 2.5]) @ turn.as_matrix().T
    body = RigidBody.from_tensor(tensor)
    tr = simulate(body, [1.0, 0, 0, 0], [0.3, 1.0, 0.2], duration=0.5, step=1e-2,
                  paths=("quaternion",))  # fmt: skip
    d = from_trajectory(tr, body)
    assert np.allclose(d.inertia, tensor, atol=1e-14)
    assert np.allclose(d.paths["quaternion"], tr.q, atol=1e-15)  # the readouts: the run's q
    # The symmetry axis (I₁ = 1 stands apart) and the ellipsoid's axes: the tensor's own.
    assert np.allclose(abs(d.symmetry_direction @ turn.apply([1.0, 0, 0])), 1.0, atol=1e-12)
    shape_axes = Rotation.from_quat(d.solid.rotation, scalar_first=True).as_matrix()
    assert np.allclose(np.abs(shape_axes.T @ turn.as_matrix()), np.eye(3)[[0, 1, 2]], atol=1e-9)
    # L in space is the run's: q (T ω) q*.
    L = Q.rotate(tr.q, d.L)
    assert np.allclose(L, Rotation.from_quat(tr.q, scalar_first=True).apply(tr.w @ tensor.T))


TENSOR_SCENE = {
    "scene": {"name": "tilted"},
    "body": {"tensor": [[2.0, 0.3, 0.0], [0.3, 1.0, 0.1], [0.0, 0.1, 1.5]], "mass": 10.0},
    "initial": {"angular_velocity": {"body": [0.0, 0.0, 1.0], "units": "rad/s"}},
    "time": {"duration": 0.2, "output_step": 0.01},
    "integrator": {"step": 0.01, "paths": ["rotor", "quaternion"]},
}


@pytest.mark.parametrize("frame", ["principal", "written"])
def test_a_scene_is_drawn_the_same_whichever_frame_its_run_is_in(frame):
    """Runs of earlier versions were integrated and written in the principal frame and name
    no frame; a run that names its frame (meta["body_frame"], as run_scene's do) is in the
    frame the scene's file is written in. Either way the body, L and the trace are the same
    in space."""
    from ga_rotors.body import RigidBody
    from ga_rotors.scene import run_scene
    from ga_rotors.trajectory import Trajectory

    scene = Scene(TENSOR_SCENE)
    tr = run_scene(scene)
    assert "body_frame" in tr.meta  # the scene's own frame
    p = np.array(scene.principal_rotation)
    assert not np.allclose(p, [1, 0, 0, 0])
    if frame == "principal":  # the same motion, as an earlier version wrote it
        meta = {k: v for k, v in tr.meta.items() if k != "body_frame"}
        tr = Trajectory(
            {"t": tr.t, "w": Q.rotate(Q.conjugate(p), tr.w), "q": Q.multiply(tr.q, p)},
            meta=meta,
        )
    d = View.from_scene(scene, tr).data
    q = d.paths["quaternion"]
    L_space = Q.rotate(q, d.L)
    tensor = np.array(TENSOR_SCENE["body"]["tensor"])
    principal = RigidBody.from_tensor(tensor)
    ref_q = tr.q if frame == "written" else Q.multiply(tr.q, Q.conjugate(p))  # written frame
    ref_w = tr.w if frame == "written" else Q.rotate(p, tr.w)
    assert np.allclose(L_space, Q.rotate(ref_q, ref_w @ tensor.T), atol=1e-12)
    # The body's shape axes in space: the tensor's principal axes, turned by the motion.
    axes = Rotation.from_quat(Q.multiply(q[-1], d.solid.rotation), scalar_first=True).as_matrix()
    truth = Rotation.from_quat(Q.multiply(ref_q[-1], principal.principal_rotation),
                               scalar_first=True).as_matrix()  # fmt: skip
    assert np.allclose(np.abs(axes.T @ truth), np.eye(3), atol=1e-9)


def test_the_heavy_top_is_a_disk_on_its_pivot_not_an_egg():
    scene = load_scene("heavy_top")
    solid = from_scene(scene)
    radius = scene.data["body"]["radius"]
    com = scene.data["effects"][scene.gravity_index]["pivot_to_com"]
    assert (solid.kind, solid.size, solid.pivot) == ("disk", (radius,), (0.0, 0.0, 0.0))
    v, _, _ = solid.mesh()
    rho = np.hypot(v[:, 0], v[:, 1])
    assert rho.max() == pytest.approx(radius) and np.ptp(v[:, 0]) == pytest.approx(2 * radius)
    assert np.abs(v[:, 2] - com[2]).max() == pytest.approx(THIN * radius / 2)  # flat at the COM
    # The ellipsoid of the moments about the pivot, drawn before, was an egg 1.6× as tall.
    egg = from_inertia(scene.body.moments)
    assert max(egg.size) / min(egg.size) < 2 and np.ptp(v[:, 2]) < 0.1 * radius
    d = View.from_scene(scene.replace({"time.duration": 0.01})).data
    body = payload(d)["body"]
    assert body["pivot"] == [0.0, 0.0, 0.0] and body["centre"][2] > 0


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_shape_is_drawn_with_its_dimensions_and_faces_outward(kind):
    dims = {
        "disk": (0.3,),
        "ring": (0.3,),
        "sphere": (0.3,),
        "cylinder": (0.3, 0.8),
        "rod": (1.0, 0.05),
        "box": (0.1, 0.06, 0.02),
        "ellipsoid": (0.1, 0.2, 0.3),
    }[kind]
    v, faces, tones = Solid(kind, dims).mesh()
    extent = np.ptp(v, axis=0)
    expected = {"disk": (0.6, 0.6, THIN * 0.3), "ring": (0.6 + THIN * 0.3,) * 2 + (THIN * 0.3,),
                "sphere": (0.6,) * 3, "cylinder": (0.6, 0.6, 0.8), "rod": (0.1, 0.1, 1.0),
                "box": (0.1, 0.06, 0.02), "ellipsoid": (0.2, 0.4, 0.6)}[kind]  # fmt: skip
    assert extent == pytest.approx(expected, rel=0.01)
    assert set(tones) == {0, 1} and len(tones) == len(faces)
    if kind != "ring":  # convex: every face's normal points away from the centre
        for f in faces:
            p = v[f]
            assert np.dot(np.cross(p[1] - p[0], p[2] - p[0]), p.mean(axis=0)) > 0


@given(st.tuples(*[st.floats(0.01, 10.0)] * 3), st.floats(0.1, 100.0))
def test_the_ellipsoid_of_moments_has_those_moments(semi, mass):
    # A uniform solid ellipsoid: I₁ = m(b² + c²)/5, and so on (closed form).
    a, b, c = semi
    moments = (mass * (b * b + c * c) / 5, mass * (a * a + c * c) / 5, mass * (a * a + b * b) / 5)
    solid = from_inertia(moments, mass)
    sizes = np.maximum(semi, THIN * max(semi) / 2)  # the thinnest drawn is THIN/2 of the largest
    axes = Rotation.from_quat(solid.rotation, scalar_first=True).as_matrix()
    assert np.allclose(sorted(solid.size), sorted(sizes), rtol=1e-9)
    assert np.allclose(np.abs(axes) @ solid.size, sizes, rtol=1e-6) or len(set(semi)) < 3


def test_the_body_axes_vectors_and_plane_have_colours_apart_from_each_other():
    def rgb(hex_):
        return np.array([int(hex_[k : k + 2], 16) for k in (1, 3, 5)], dtype=float)

    axes = [rgb(ELEMENTS[k][1]) for k in ("e1", "e2", "e3")]
    for key in ("body", "omega", "L", "plane", "trace", "pivot"):
        for axis in axes:
            assert np.linalg.norm(rgb(ELEMENTS[key][1]) - axis) > 100, key
    # Lines and areas apart from one another (the pivot is a ring, told apart by its shape).
    colours = [rgb(c) for k, (_, c) in ELEMENTS.items() if k != "pivot"]
    assert min(np.linalg.norm(x - y) for i, x in enumerate(colours) for y in colours[i + 1 :]) > 60


def test_a_moving_body_and_extra_lines_travel_in_the_pages_data():
    """Room for rigid motion: a per-sample position and a line drawn in space."""
    t = np.linspace(0.0, 1.0, 5)
    position = np.outer(t, [2.0, 0.0, 0.0])
    line = Line("velocity", "velocity line", position, np.tile([1.0, 0, 0], (5, 1)), "#7b3294")
    d = ViewData(t, {"rotor": np.tile(ONE, (5, 1))}, np.zeros((5, 3)), (1.0, 1.0, 2.0),
                 positions={"rotor": position}, lines=[line])  # fmt: skip
    data = payload(d)
    scale = 1.0 / data["metresPerUnit"] if data["metresPerUnit"] else None
    assert data["paths"][0]["position"][-1][0] > data["paths"][0]["position"][0][0]
    assert data["lines"][0]["key"] == "velocity" and data["elements"][-1]["key"] == "velocity"
    assert scale is None  # moments only: the ellipsoid's size is relative
    with pytest.raises(InputError, match=r"lines\['velocity'\]\.point: expected shape \(5, 3\)"):
        ViewData(t, d.paths, d.w, lines=[Line("velocity", "v", position[:3], position[:3])])


def test_the_page_loads_nothing_from_elsewhere_and_carries_no_library():
    tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.1, 1.0], duration=0.1, step=1e-2)
    text = View.from_trajectory(tr).html()
    assert not re.search(r"<(script|link|img|iframe)[^>]*\b(src|href)=", text)
    assert not re.search(r"https?:|//cdn|import\(|fetch\(|XMLHttpRequest", text)
    assert len(text.encode()) < 60_000  # the script and the data of 11 samples


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
    assert data["inertia"] == np.diag(scene.body.moments).tolist()
    assert data["body"]["label"] == "uniform disk: radius 0.05 m"
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
        ("huge_w", ["{tmp}/x.npz"], "L: L = Iω overflows float64 at t = 0 s"),
        ("complex_t", ["{tmp}/x.npz"], "x.npz: t: expected finite real numbers, got complex128"),
        ("back_t", ["{tmp}/x.npz"], "x.npz: t: expected strictly increasing times, got t[2] = 0"),
        ("bad_q", ["{tmp}/x.npz"], "x.npz: q: expected shape (n, 4), got (3, 3)"),
        ("bad_rotor", ["{tmp}/x.npz"], "x.npz: rotor_blades: expected shape (n, 4), got (2, 4, 2)"),
    ],
)
def test_view_command_errors_are_one_line(tmp_path, make, argv, message):
    if make == "lonely_npz":
        np.savez(tmp_path / "x.npz", t=np.zeros(2))
    if make not in (None, "empty_dir", "lonely_npz"):
        scene = load_scene("spinning_disk")
        if make == "huge_w":  # moments of 1e3 kg·m²: I ω overflows where ω = 1e307 does not
            scene = Scene({"body": {"moments": [1e3, 1e3, 2e3]}, "time": {"duration": 1.0},
                           "integrator": {"step": 0.5}})  # fmt: skip
        (tmp_path / "x.scene.toml").write_text(scene.to_toml())
        good = {"t": np.arange(3.0), "w": np.zeros((3, 3)), "q": np.tile([1.0, 0, 0, 0], (3, 1))}
        bad = {"nan_w": {"w": np.full((3, 3), np.nan)}, "bad_q": {"q": np.zeros((3, 3))},
               "bad_rotor": {"rotor_blades": np.ones((2, 4, 2))},
               "huge_w": {"w": np.full((3, 3), 1e307)},
               "complex_t": {"t": np.arange(3.0) + 1j},
               "back_t": {"t": np.array([0.0, 1.0, 0.5])}}[make]  # fmt: skip
        np.savez(tmp_path / "x.npz", **(good | bad))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # one line, and no numpy RuntimeWarning before it
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
    # ga-rotors view heavy_top: the whole 3 s run, 600 frames of two paths, within budget.
    size = (tmp_path / "heavy_top.view.html").stat().st_size
    print(f"ga-rotors view heavy_top: {size / 1e6:.3f} MB")
    assert size < PAGE_BYTES
