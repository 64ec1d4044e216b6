"""Notebook display: scenes and trajectories show summary tables, a trajectory its viewer,
symbolic multivectors their LaTeX."""

from __future__ import annotations

import html

import pytest

from ga_rotors import simulate
from ga_rotors.errors import GimbalLockWarning, IntegrationStoppedWarning
from ga_rotors.scene import load_scene, run_scene


def test_a_scene_shows_what_it_resolves_to():
    scene = load_scene("heavy_top")
    text = scene._repr_html_()
    for line in scene.describe().splitlines():
        key, _, value = line.removeprefix("# ").partition(": ")
        assert f'<th style="text-align: left; padding-right: 1em">{html.escape(key)}</th>' in text
        assert f"<td>{html.escape(value)}</td>" in text


def test_untrusted_scene_text_is_escaped():
    scene = load_scene("spinning_disk").replace({"scene.description": "<script>alert(1)</script>"})
    text = scene._repr_html_()
    assert "<script>" not in text and "&lt;script&gt;alert(1)&lt;/script&gt;" in text


def test_a_trajectory_shows_its_samples_paths_and_arrays():
    scene = load_scene("heavy_top").replace({"time.duration": 0.05})
    tr = run_scene(scene)
    text = tr._repr_html_()
    assert f"{len(tr.t)} samples" in text and "<b>heavy_top</b>" in text
    for name in tr.names[1:]:
        assert f'<th style="text-align: left; padding-right: 1em">{name}</th>' in text
    assert "path rotor" in text and "complete" in text


def test_a_path_that_stopped_early_says_so():
    # The Euler path starts at θ = 0 (locked) and stops when its state stops being finite.
    with pytest.warns(GimbalLockWarning), pytest.warns(IntegrationStoppedWarning):
        tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.5,
                      step=0.1, paths=("quaternion", "euler"))  # fmt: skip
    status = tr.meta["paths"]["euler"]
    if status["complete"]:
        pytest.skip("the Euler path ran to the end here")
    assert f"ended at t = {status['ended_at']}" in tr._repr_html_()


def test_a_trajectory_plays_in_the_viewer_and_each_cell_stays_light():
    import re

    tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.1, 0.0, 1.0], duration=0.5, step=0.1)
    view = tr.view(title="disk")
    cell = view._repr_html_()
    assert cell.startswith("<iframe srcdoc=") and html.unescape(cell).count("<script>") == 1
    assert view.data.paths["rotor"].shape == (6, 4)
    # The page in the cell is the saved page: its script and its data, no library (each cell
    # of a notebook used to carry 6 MB of plotly.js). A longer run adds only its samples.
    longer = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.1, 0.0, 1.0], duration=50.0,
                      step=0.1).view()._repr_html_()  # fmt: skip
    assert len(cell) < 150_000 and len(longer) < 600_000
    assert not re.search(r"<script[^>]*src=", html.unescape(cell))


def test_a_symbolic_multivector_shows_its_latex():
    import sympy

    from ga_rotors.symbolic.algebra import CliffordAlgebra

    # Cl(0,2): i = e1, j = e2, k = e12; a rotor-like element with symbolic coefficients.
    cl = CliffordAlgebra(0, 2)
    i, j = cl.blade(1), cl.blade(2)
    assert (i * j)._repr_latex_() == "$e_{12}$"
    assert (i * i)._repr_latex_() == "$-1$"
    a = sympy.Symbol("alpha")
    x = sympy.cos(a / 2) - (i * j) * sympy.sin(a / 2) + (a + 1) * i
    assert x._repr_latex_() == (
        r"$\cos{\left(\frac{\alpha}{2} \right)} + \left(\alpha + 1\right) e_{1}"
        r" - \sin{\left(\frac{\alpha}{2} \right)} e_{12}$"
    )
    assert cl.scalar(0)._repr_latex_() == "$0$"
