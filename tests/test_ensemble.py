"""The batched RK4 ensemble: the same trajectory as the single-body RK4, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from ga_rotors.ensemble import benchmark, rk4_free
from ga_rotors.errors import InputError
from ga_rotors.integrators import Problem, get


def test_each_body_follows_the_single_body_rk4_exactly():
    rng = np.random.default_rng(7)
    n = 300  # more than one chunk, and a partial last chunk
    q = rng.normal(size=(4, n))
    q /= np.linalg.norm(q, axis=0)
    w = rng.normal(size=(3, n))
    inertia = (1.0, 2.0, 3.5)
    qe, we = q.copy(), w.copy()
    rk4_free(inertia, qe, we, 0.01, 50)
    for i in (0, 17, 255, 256, 299):
        run = get("rk4").run(Problem(inertia), "quaternion", q[:, i], w[:, i], 0.0, 0.01, 50, 50)
        assert np.array_equal(run.x[-1], qe[:, i]) and np.array_equal(run.w[-1], we[:, i])


def test_rejects_wrong_layout():
    q = np.zeros((3, 4))
    with pytest.raises(InputError, match="q: expected a C-contiguous float64 array"):
        rk4_free((1.0, 2.0, 3.0), q, np.zeros((3, 4)), 0.1, 1)
    with pytest.raises(InputError, match="same number of bodies"):
        rk4_free((1.0, 2.0, 3.0), np.zeros((4, 4)), np.zeros((3, 5)), 0.1, 1)


def test_benchmark_reports_a_rate():
    assert "million body-steps/s" in benchmark(bodies=512, steps=10, repeats=1)
