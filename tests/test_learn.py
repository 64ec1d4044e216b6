"""The learning path's pictures: drawn by ga_rotors.view.diagrams, committed, shown on a page.

The exercises' worked solutions on docs/learn/*.md run in tests/test_docs.py.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from ga_rotors.errors import InputError
from ga_rotors.view.diagrams import PICTURES, draw_all, reflect

LEARN = Path(__file__).resolve().parents[1] / "docs" / "learn"


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    return draw_all(tmp_path_factory.mktemp("pictures"))


def test_every_picture_is_drawn_legibly(drawn):
    from PIL import Image

    assert [p.stem for p in drawn] == list(PICTURES)
    for path in drawn:
        with Image.open(path) as image:
            assert image.info["dpi"][0] == pytest.approx(150, abs=0.5), path.name
            assert min(image.size) >= 450, path.name
            pixels = np.asarray(image.convert("RGB")).reshape(-1, 3)
            colours = np.unique(pixels, axis=0).shape[0]
            assert colours > 50, f"{path.name} looks blank ({colours} colours)"


def test_every_picture_is_committed_and_shown_on_a_page():
    committed = {p.stem for p in (LEARN / "images").glob("*.png")}
    assert committed == set(PICTURES), "run: python -m ga_rotors.view.diagrams docs/learn/images"
    shown = set()
    for page in LEARN.glob("*.md"):
        shown |= set(re.findall(r"\]\(images/(\w+)\.png\)", page.read_text(encoding="utf-8")))
    assert shown == set(PICTURES)


def test_vector_formats_on_request(tmp_path):
    (svg,) = draw_all(tmp_path, fmt="svg", names=["reflection"])
    assert svg.read_text(encoding="utf-8").lstrip().startswith("<?xml")
    (pdf,) = draw_all(tmp_path, fmt="pdf", names=["reflection"])
    assert pdf.read_bytes().startswith(b"%PDF")
    with pytest.raises(InputError, match="fmt"):
        draw_all(tmp_path, fmt="gif", names=["reflection"])


def test_the_pages_of_the_path_are_linked_from_its_index():
    index = (LEARN / "index.md").read_text(encoding="utf-8")
    pages = {p.name for p in LEARN.glob("*.md")} - {"index.md"}
    assert set(re.findall(r"\]\(([\w-]+\.md)\)", index)) == pages


finite = st.floats(-10, 10, allow_nan=False)


@given(arrays(np.float64, 3, elements=finite), arrays(np.float64, 3, elements=finite))
def test_reflection_is_the_linear_algebra_mirror(v, n):
    if np.linalg.norm(n) < 1e-3:
        return
    u = n / np.linalg.norm(n)
    image = reflect(v, n)
    scale = 1e-12 * (1 + np.linalg.norm(v))
    assert np.allclose(image, v - 2 * (v @ u) * u, atol=scale)
    assert np.allclose(reflect(image, n), v, atol=scale)


def test_every_exercise_has_a_folded_solution_that_checks_itself():
    fence = re.compile(r"^```python[ \t]*\n(.*?)^```", re.S | re.M)
    for page in sorted(LEARN.glob("*.md")):
        if page.name == "index.md":
            continue
        text = page.read_text(encoding="utf-8")
        solutions = re.findall(r"<details[^>]*>(.*?)</details>", text, re.S)
        assert solutions, f"{page.name}: no worked solution"
        for solution in solutions:
            code = "\n".join(fence.findall(solution))
            assert "assert " in code, f"{page.name}: a worked solution that checks nothing"


# The claims of "From rotors to motors" (docs/learn/motors.md), for any input: ga_rotors.motor
# against clifford's own Cl(3,0,1) products.

unit_vectors = (
    arrays(np.float64, 3, elements=st.floats(-1, 1))
    .filter(lambda n: np.linalg.norm(n) > 0.1)
    .map(lambda n: n / np.linalg.norm(n))
)
offsets = st.floats(-5, 5, allow_nan=False)


def _pga_plane(normal, offset):
    from ga_rotors import motor

    return motor.to_multivector(motor.plane(normal, offset), "plane")


@given(unit_vectors, offsets, offsets)
def test_parallel_mirrors_compose_to_the_translator_by_twice_their_distance(n, d1, d2):
    from ga_rotors import motor

    a, b = _pga_plane(n, d1), _pga_plane(n, d2)
    assert np.allclose(motor.from_multivector(b * a), motor.from_translation(2 * (d2 - d1) * n),
                       atol=1e-12)  # fmt: skip


@given(unit_vectors, unit_vectors, arrays(np.float64, 3, elements=offsets))
def test_mirrors_through_a_line_compose_to_the_turn_by_twice_their_angle(u, w, p):
    from ga_rotors import motor

    # two planes through the line (p, u): normals n ⊥ u and m ⊥ u, an angle beta apart
    n = np.cross(u, w)
    assume(np.linalg.norm(n) > 0.1)
    n /= np.linalg.norm(n)
    beta = 0.4
    m = np.cos(beta) * n + np.sin(beta) * np.cross(u, n)
    a, b = _pga_plane(n, n @ p), _pga_plane(m, m @ p)
    turn = motor.from_screw(motor.line(p, u), 2 * beta)
    assert np.allclose(motor.from_multivector(b * a), turn, atol=1e-12)


@given(
    arrays(np.float64, 3, elements=st.floats(-3, 3)),
    arrays(np.float64, 3, elements=st.floats(-3, 3)),
    arrays(np.float64, 4, elements=st.floats(-1, 1)).filter(lambda q: np.linalg.norm(q) > 0.1),
    arrays(np.float64, 3, elements=offsets),
    arrays(np.float64, 3, elements=offsets),
)
def test_every_point_moves_by_the_commutator_with_the_space_velocity_line(w, v, q, t, x):
    from ga_rotors import motor

    M = motor.from_pose(q / np.linalg.norm(q), t)
    B = motor.velocity_line(w, v)
    B_s = motor.to_multivector(np.r_[0.0, motor.sandwich_line(M, B), 0.0])
    P = motor.to_multivector(motor.point(x), "point")
    Pdot = motor.from_multivector(0.5 * (B_s * P - P * B_s), "point")
    assert Pdot[3] == 0.0  # a direction: an ideal point
    # the body point at x, moved for a time h either way along M(h) = M exp(h B / 2)
    body = motor.apply(motor.inverse(M), x)
    h = 1e-5
    ahead, behind = (motor.apply(motor.compose(M, motor.exp(0.5 * s * h * B)), body)
                     for s in (1.0, -1.0))  # fmt: skip
    rate = (ahead - behind) / (2 * h)
    scale = 1e-6 * (1 + np.linalg.norm(w) * (1 + np.linalg.norm(x - t)) + np.linalg.norm(v))
    assert np.allclose([-Pdot[2], Pdot[1], -Pdot[0]], rate, atol=scale)


@given(unit_vectors, st.floats(0.1, 3.0), arrays(np.float64, 3, elements=st.floats(-3, 3)))
def test_the_velocity_line_is_a_screw_of_pitch_w_dot_v_over_w_squared(u, rate, v):
    from ga_rotors import motor

    w = rate * u
    _, angle, pitch = motor.to_screw(motor.exp(0.5 * motor.velocity_line(w, v)))
    assert np.isclose(angle, rate)
    assert np.isclose(pitch, (w @ v) / (w @ w), atol=1e-12)
    # with ω·v = 0 it is a line: B = −|ω| L, L the unit line along ω about which the body turns
    v_perp = v - (v @ u) * u
    axis, _, pitch = motor.to_screw(motor.exp(0.5 * motor.velocity_line(w, v_perp)))
    assert np.isclose(pitch, 0.0, atol=1e-12)
    assert np.allclose(motor.velocity_line(w, v_perp), -rate * axis, atol=1e-12)
