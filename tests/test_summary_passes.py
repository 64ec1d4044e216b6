"""The summary's compiled passes against the numpy formulas they replace, bit for bit:
the azimuth's unwrap (numpy's np.unwrap, also piece by piece), the norm drift (numpy's
norm), gravity's invariants (body.energy, body.momentum, quaternion.rotate)."""

from __future__ import annotations

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors.scene import load_scene, run_scene
from ga_rotors.scene import summary as S


def _angles(rng, n):
    steps = rng.normal(0.0, rng.choice([0.1, 1.0, 3.0]), n)
    raw = np.arctan2(np.sin(np.cumsum(steps)), np.cos(np.cumsum(steps)))
    raw[rng.integers(0, n, 3)] = rng.choice([np.pi, -np.pi], 3)  # jumps of exactly ±π too
    return raw


@pytest.mark.parametrize("seed", range(20))
def test_unwrap_is_numpys_whole_and_in_pieces(seed):
    rng = np.random.default_rng(seed)
    raw = _angles(rng, int(rng.integers(2, 4000)))
    whole, _ = S._unwrap(raw, None)
    assert np.array_equal(whole, np.unwrap(raw))
    cut = int(rng.integers(1, raw.size))
    first, carried = S._unwrap(raw[:cut], None)
    rest, _ = S._unwrap(raw[cut:], carried)
    assert np.array_equal(np.concatenate([first, rest]), whole)


def test_norm_drift_is_numpys():
    rng = np.random.default_rng(3)
    a = rng.normal(size=(5000, 4))
    a /= np.linalg.norm(a, axis=1)[:, None]
    a *= 1.0 + rng.normal(0.0, 1e-11, (5000, 1))
    assert S._largest_norm_drift(a) == np.abs(np.linalg.norm(a, axis=-1) - 1.0).max()
    a[17, 2] = np.nan
    assert np.isnan(S._largest_norm_drift(a))
    assert S._largest_norm_drift(a[:0]) < 0.0  # no rows: nothing to report


def test_gravity_invariants_are_the_numpy_formulas():
    scene = load_scene("heavy_top").replace({"time.duration": 0.5})
    tr = run_scene(scene)
    q = Q.normalize(tr.quaternions())
    body, w = scene.body, tr.w
    weight, r = scene.gravity
    rows = {key: dev for key, _, dev, _ in S.invariant_series(scene, tr, q)}
    total = body.energy(w) - Q.rotate(q, r) @ weight
    scale = float(body.energy(w[0]) + np.linalg.norm(weight) * np.linalg.norm(r))
    assert np.array_equal(rows["total_energy"], np.abs(total - total[0]) / scale)
    space = Q.rotate(q, body.momentum(w))
    up = -weight / np.linalg.norm(weight)
    l0 = float(np.linalg.norm(space[0]))
    assert np.array_equal(rows["vertical_momentum"], np.abs(space @ up - space[0] @ up) / l0)
    axial = body.momentum(w)[:, 2]
    assert np.array_equal(rows["axial_momentum"], np.abs(axial - axial[0]) / l0)
