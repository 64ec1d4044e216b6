"""The summary's compiled passes against the numpy formulas they replace, bit for bit:
the azimuth's unwrap (numpy's np.unwrap of the arctangents, also piece by piece), the
norm drift (numpy's norm), gravity's invariants (body.energy, body.momentum,
quaternion.rotate)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors.scene import load_scene, run_scene
from ga_rotors.scene import summary as S


def _axis(rng, n):
    """x, y of an axis turning about z by random steps (and |ψ| jumps beyond π), with
    rows exactly on the x axis (y = ±0, azimuth 0, ±π) and steps of exactly ±π."""
    steps = rng.normal(0.0, rng.choice([0.1, 1.0, 3.0]), n)
    x, y = np.cos(np.cumsum(steps)), np.sin(np.cumsum(steps))
    on_axis = rng.integers(0, n, 6)
    x[on_axis] = rng.choice([-1.0, 1.0, 0.5], 6)
    y[on_axis] = rng.choice([0.0, -0.0], 6)
    return x, y


@pytest.mark.parametrize("seed", range(30))
def test_azimuth_is_numpys_unwrap_whole_and_in_pieces(seed):
    # ψ read at some rows, piece after piece (each with the previous piece's last row in
    # front), equals np.unwrap of the whole run's arctangents at those rows, bit for bit
    rng = np.random.default_rng(seed)
    x, y = _axis(rng, int(rng.integers(2, 4000)))
    # the C library's atan2, as the compiled pass calls it (numpy's may differ by an ulp)
    whole = np.unwrap([math.atan2(b, a) for a, b in zip(x, y, strict=True)])
    cuts = np.sort(rng.integers(1, x.size, int(rng.integers(0, 4))))
    state = (math.atan2(y[0], x[0]), 0.0)
    start = 0
    for stop in [*cuts, x.size]:
        if stop <= start:
            continue
        rows = np.arange(start, stop)  # row 0 of the piece: the previous piece's last
        front = max(start - 1, 0)
        px, py = x[front:stop], y[front:stop]
        wanted = np.unique(rng.integers(1, px.size, 5)) if px.size > 1 else np.empty(0, int)
        out = np.empty(wanted.size)
        state = S._azimuth_loop(px, py, *state, wanted, out)
        assert np.array_equal(out, whole[front + wanted]), (seed, start)
        assert state[0] == math.atan2(y[stop - 1], x[stop - 1])
        assert state[0] + state[1] == whole[stop - 1]
        start = rows[-1] + 1


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
