"""Figures a reader can read: resolution, panel letters, no offset text, every path visible
or its overlap stated, torqued scenes' energy balance."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from ga_rotors.paper import figures as paper_figures
from ga_rotors.scene import Scene, load_scene, run_scene
from ga_rotors.scene.figures import draw, energy_balance

ROOT = Path(__file__).resolve().parents[1]


def _torqued(effects, plots=("invariants",)):
    return Scene({
        "scene": {"name": "pushed"},
        "body": {"moments": [1.0, 2.0, 3.0]},
        "initial": {"angular_velocity": {"body": [0.3, 0.1, 1.0], "units": "rad/s"}},
        "time": {"duration": 2.0, "output_step": 0.01},
        "integrator": {"step": 1e-3},
        "effects": effects,
        "output": {"plots": list(plots)},
    })  # fmt: skip


@pytest.mark.parametrize(
    "effect",
    [
        {"type": "body_torque", "torque": [0.0, 0.2, 0.5]},
        {"type": "damping", "coefficient": 0.3},
    ],
    ids=["body_torque", "damping"],
)
def test_a_torqued_scene_shows_energy_against_the_work_done(effect):
    scene = _torqued([effect])
    tr = run_scene(scene)
    gain, work = energy_balance(scene, tr, tr.quaternions())
    # dE/dt = τ·ω: the trapezoid on 0.01 s samples agrees to its own O(Δt²) error.
    assert np.abs(gain - work).max() <= 1e-3 * np.abs(gain).max()
    if effect["type"] == "damping":
        assert work[-1] < 0  # dissipated
    fig = draw(scene, tr)
    (ax,) = fig.axes
    labels = [line.get_label() for line in ax.get_lines()]
    assert labels == ["kinetic energy gained E − E₀", "work done by the torques ∫τ·ω dt"]


def test_scene_figures_have_panel_letters_and_no_offset_text():
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    scene = load_scene("paper_0.001deg").replace({"time.duration": 1.0})
    fig = draw(scene, run_scene(scene))
    FigureCanvasAgg(fig).draw()
    letters = [ax.get_title(loc="left") for ax in fig.axes]
    assert letters == [f"({c})" for c in "abcdefgh"[: len(fig.axes)]]
    assert all(ax.yaxis.get_offset_text().get_text() == "" for ax in fig.axes)


def test_a_hidden_path_says_where_it_is():
    scene = load_scene("spinning_disk").replace({"time.duration": 1.0})
    fig = draw(scene, run_scene(scene))
    labels = [line.get_label() for line in fig.axes[-1].get_lines()]
    assert labels[0] == "rotor"
    assert labels[1].startswith("quaternion (dashed): on the\nrotor line, ≤ ")


@pytest.mark.parametrize(
    ("ylabel", "values", "label"),
    [
        ("ω z3 (rad/s)", 15.72 - 7e-9 * np.arange(5), "ω z3 − 15.72 (1e-8 rad/s)"),
        ("ω x3 (rad/s)", -3.49e-7 + 0 * np.arange(5), "ω x3 (1e-7 rad/s)"),
        ("θ (°)", np.linspace(0, 45, 5), "θ (°)"),
    ],
)
def test_panels_carry_their_reference_and_power_in_the_label(ylabel, values, label):
    shift, scale, shown = paper_figures._readable(ylabel, [(None, values)], log=False)
    assert shown == label
    y = (values - shift) / scale
    assert np.abs(y).max() < 1e4 and (np.ptp(y) == 0 or np.ptp(y) > 1e-3)


def test_a_space_torque_shows_its_balance_law():
    # A constant space-frame torque: L(t) − τ t is conserved, and the panel says so.
    scene = _torqued([{"type": "space_torque", "torque": [0.4, 0.0, 0.0]}])
    (ax,) = draw(scene, run_scene(scene)).axes
    assert [line.get_label() for line in ax.get_lines()] == ["L − τ t"]


def test_committed_paper_and_scene_figures_are_150_dpi():
    figures = ROOT / "docs" / "figures"
    pngs = sorted([*figures.glob("*.png"), *(figures / "scenes").glob("*.png")])
    assert len(pngs) >= len(paper_figures.FIGURES)
    for png in pngs:
        with Image.open(png) as image:
            assert image.info.get("dpi", (0, 0))[0] >= 149.5, png.name


@pytest.mark.parametrize("fmt", ["svg", "pdf"])
def test_paper_figures_in_vector_formats_on_request(tmp_path, fmt):
    from ga_rotors.cli import main

    assert main(["paper", "--out", str(tmp_path), "--figures-only", "--format", fmt]) == 0
    written = sorted(p.stem for p in tmp_path.iterdir())
    assert written == sorted(paper_figures.FIGURES)
    head = (tmp_path / f"errors.{fmt}").read_bytes()[:200]
    assert head.startswith(b"%PDF") if fmt == "pdf" else b"<svg" in head or b"<?xml" in head


def test_a_user_torque_is_not_run_again_to_draw_its_figure(tmp_path, monkeypatch):
    import sys

    from ga_rotors.trust import allow_user_code

    name = f"push_{tmp_path.name}"
    (tmp_path / f"{name}.py").write_text(
        "import numba\n\n@numba.njit(cache=False)\ndef push(t, q, w, p):\n"
        "    return (0.0, 0.0, p[0])\n"
    )
    (tmp_path / "pushed.toml").write_text(
        '[body]\nshape = "sphere"\nmass = 1.0\nradius = 1.0\n'
        '[time]\nduration = 0.1\n[integrator]\nstep = 0.01\npaths = ["quaternion"]\n'
        f'[[effects]]\ntype = "user"\nfunction = "{name}:push"\nparams = [0.5]\n'
        '[output]\nplots = ["invariants"]\n'
    )
    monkeypatch.setattr(sys, "path", list(sys.path))
    scene = load_scene(tmp_path / "pushed.toml")
    with allow_user_code(tmp_path):
        tr = run_scene(scene)
    sys.modules.pop(name, None)
    (ax,) = draw(scene, tr).axes  # outside the opt-in: nothing is imported or run
    assert ax.texts[0].get_text().startswith("energy balance not drawn")
    assert name not in sys.modules


RUN = """
[scene]
name = "wobble"
description = "a short wobbling disk"

[body]
shape = "disk"
mass = 2.0
radius = 0.075

[initial.angular_velocity]
body = [0.2, 0.0, 15.0]
units = "rad/s"

[time]
duration = 0.2
output_step = 0.01

[integrator]
step = 0.001
paths = ["rotor", "quaternion"]

[output]
plots = ["omega", "error"]
figure_format = "pdf"
"""


def test_a_scene_figure_in_the_format_the_scene_or_the_command_asks(tmp_path, capsys):
    from ga_rotors.cli import main
    from ga_rotors.scene.figures import DIGEST_PREFIX, data_digest

    path = tmp_path / "wobble.toml"
    path.write_text(RUN)
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    pdf = (out / "wobble.pdf").read_bytes()
    scene = load_scene(path)
    digest = DIGEST_PREFIX + data_digest(scene, run_scene(scene))
    assert pdf.startswith(b"%PDF-") and digest.encode() in pdf
    assert not (out / "wobble.png").exists()
    # --format overrides the scene's key, and the resolved scene written back says so.
    assert main(["run", str(path), "--out", str(out), "--no-progress", "--format", "svg"]) == 0
    svg = (out / "wobble.svg").read_text(encoding="utf-8")
    scene = scene.replace({"output.figure_format": "svg"})  # part of what the digest covers
    digest = DIGEST_PREFIX + data_digest(scene, run_scene(scene))
    assert "<svg" in svg and f"<dc:description>{digest}</dc:description>" in svg
    assert 'figure_format = "svg"' in (out / "wobble.scene.toml").read_text(encoding="utf-8")
    capsys.readouterr()


def test_a_bad_figure_format_is_one_line_naming_the_file_and_key(tmp_path, capsys):
    from ga_rotors.cli import main

    path = tmp_path / "wobble.toml"
    path.write_text(RUN.replace('figure_format = "pdf"', 'figure_format = "jpg"'))
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err == (
        f"ga-rotors: error: {path}: output.figure_format: unknown value 'jpg' "
        "(did you mean 'png'?); expected one of png, svg, pdf\n"
    )
    assert not (tmp_path / "out").exists()
    with pytest.raises(SystemExit) as stop:  # argparse: usage and one error line
        main(["run", str(path), "--format", "jpg"])
    assert stop.value.code == 2
    assert "argument --format: invalid choice: 'jpg'" in capsys.readouterr().err


def test_paper_and_scene_figures_offer_the_same_formats():
    from ga_rotors.paper.reproduce import FORMATS

    assert FORMATS == tuple(paper_figures.FIGURE_FORMATS)


def test_near_zero_rates_under_another_line_are_dashed_and_said_so():
    # The spinning disk: ω1 and ω2 stay within a few hundredths of a rad/s of 0 while
    # ω3 is 15.7 rad/s, so at the panel's scale ω2 is drawn on ω1.
    scene = load_scene("spinning_disk").replace({"time.duration": 1.0})
    fig = draw(scene, run_scene(scene))
    omega = fig.axes[2]
    labels = [line.get_label() for line in omega.get_lines()]
    assert labels[0] == "ω1" and labels[2] == "ω3"
    assert labels[1].startswith("ω2 (dashed): on the\nω1 line, ≤ ")
    assert omega.get_lines()[1].get_linestyle() == "--"


def test_a_long_description_is_a_title_of_two_lines_cut_at_a_word():
    scene = load_scene("heavy_top").replace({"time.duration": 0.1})
    title = draw(scene, run_scene(scene))._suptitle.get_text()
    lines = title.split("\n")
    assert len(lines) == 2 and lines[0].startswith("heavy_top: A heavy symmetric top")
    assert all(len(line) <= 110 for line in lines) and lines[1].endswith("…")
    words = {w.strip(".,;:") for w in scene.description.split()}
    assert lines[1][:-1].split()[-1].strip(".,;:") in words  # the last word shown is whole
