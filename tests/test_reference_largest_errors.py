"""Exact.largest_errors (what a run's summary prints) against the maxima of Exact.errors
(what the error quantities hold), and the cross-check's largest angle and its time
against quaternion.distance's maximum and first row holding it: equal bit for bit, where
the screening they do is hardest — errors at the rounding level, near-ties and exact
ties, angles next to π, orientations off unit by up to the tolerance, and more rows than
one screening block."""

from __future__ import annotations

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors.crosscheck import cross_check
from ga_rotors.scene import load_scene, run_scene

ROWS = 3000  # about three screening blocks


@pytest.fixture(scope="module")
def reference():
    exact = load_scene("heavy_top").exact_solution
    t = np.linspace(0.0, 5.0, ROWS)
    q_ref, w_ref, _ = exact.state(t)
    return exact, t, q_ref, w_ref


def _turned(q_ref, angles, rng, off_unit=0.0):
    axes = rng.normal(size=(angles.size, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    q = Q.multiply(q_ref, Q.from_rotation_vector(axes * angles[:, None]))
    return q * (1.0 + rng.uniform(-off_unit, off_unit, size=(angles.size, 1)))


CASES = {
    "rounding_level": lambda rng: 10.0 ** rng.uniform(-17, -14, ROWS),
    "spread_of_magnitudes": lambda rng: 10.0 ** rng.uniform(-12, 0.4, ROWS),
    "near_ties": lambda rng: 1e-9 * (1.0 + 1e-15 * rng.integers(0, 4, ROWS)),
    "next_to_pi": lambda rng: np.pi - 10.0 ** rng.uniform(-9, -1, ROWS),
    "growing": lambda rng: 1e-10 * np.linspace(0.0, 1.0, ROWS) ** 2,
}


@pytest.mark.parametrize("off_unit", [0.0, 0.9e-6])
@pytest.mark.parametrize("case", list(CASES))
def test_largest_errors_are_the_maxima_of_errors_bit_for_bit(reference, case, off_unit):
    exact, t, q_ref, w_ref = reference
    for seed in range(4):
        rng = np.random.default_rng(seed)
        quats = {
            "rotor": _turned(q_ref, CASES[case](rng), rng, off_unit),
            "short": _turned(q_ref[:1234], CASES[case](rng)[:1234], rng, off_unit),
        }
        w = w_ref + rng.normal(size=w_ref.shape) * 10.0 ** rng.uniform(-16, -3, (ROWS, 1))
        dw, dq = exact.errors(t, w, quats)
        top_w, top_q = exact.largest_errors(t, w, quats)
        assert top_w == dw.max()
        for name in quats:
            assert top_q[name] == dq[name].max(), (case, seed, name)


def test_largest_errors_of_nothing_and_of_a_non_unit_orientation(reference):
    exact, t, q_ref, _ = reference
    assert exact.largest_errors(t, None, {"rotor": q_ref[:0]}) == (None, {"rotor": None})
    bad = q_ref.copy()
    bad[7] *= 2.0  # off unit beyond the tolerance: refused as Q.distance refuses it
    with pytest.raises(Exception, match="unit") as caught:
        exact.errors(t, None, {"rotor": bad})
    with pytest.raises(type(caught.value), match="unit"):
        exact.largest_errors(t, None, {"rotor": bad})


@pytest.fixture(scope="module")
def two_paths():
    scene = load_scene("heavy_top")
    tr = run_scene(scene.replace({"time.duration": (ROWS - 1) * scene.data["time"]["output_step"]}))
    assert tr.t.size == ROWS
    return tr, Q.normalize(tr.quaternions())


@pytest.mark.parametrize("off_unit", [0.0, 0.9e-6])
@pytest.mark.parametrize("case", list(CASES))
def test_cross_check_is_the_largest_distance_at_its_first_row(two_paths, case, off_unit):
    tr, q = two_paths
    for seed in range(4):
        rng = np.random.default_rng(seed)
        rotor = _turned(q, CASES[case](rng), rng, off_unit)
        quaternion = _turned(q, CASES[case](rng), rng, off_unit)
        if seed % 2:  # the largest angle again, exactly, on an earlier row: that one is reported
            top = int(np.argmax(Q.distance(rotor, quaternion)))
            early = int(rng.integers(0, top + 1))
            rotor[early], quaternion[early] = rotor[top], quaternion[top]
        d = Q.distance(rotor, quaternion)
        [c] = cross_check(tr, {"rotor": rotor, "quaternion": quaternion})
        assert (c.max_angle, c.at_time, c.samples) == (d.max(), tr.t[np.argmax(d)], ROWS)


@pytest.mark.parametrize("bad", ["nan", "off_unit"])
def test_cross_check_of_a_non_finite_or_non_unit_row_is_distances(two_paths, bad):
    tr, q = two_paths
    other = q.copy()
    if bad == "nan":
        other[2500, 1] = np.nan
    else:  # beyond the tolerance
        other[2500] *= 2.0
    with pytest.raises(Exception) as caught:
        Q.distance(q, other)
    with pytest.raises(type(caught.value)) as got:
        cross_check(tr, {"rotor": q, "quaternion": other})
    assert str(got.value) == str(caught.value)
