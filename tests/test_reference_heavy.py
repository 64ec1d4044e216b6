"""The exact heavy symmetric top against an independent 30-digit Taylor integration
(tests/mp_oracle.py), its invariants, nutation bounds and period, and its guards."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mp_oracle import integrate

from ga_rotors import _kernels as K
from ga_rotors.errors import InputError, PrecisionError
from ga_rotors.reference.heavy_top import HeavyTop

TIMES = (0.5, 3.0, 7.0)


def _qy(angle):
    return (math.cos(angle / 2), 0.0, math.sin(angle / 2), 0.0)


def _unit(q):
    q = np.asarray(q, float)
    return q / np.linalg.norm(q)


CASES = {
    "fast_top_released_at_rest_in_precession": ((1.0, 1.0, 0.5), 1.0, _qy(0.5), (0, 0, 10.0)),
    "general_tilted_state": ((2.0, 2.0, 1.0), 3.0, (0.9, 0.3, 0.3, 0.1), (0.5, -0.2, 8.0)),
    "oblate_slow_top_released_with_precession": ((1.0, 1.0, 2.0), 2.0, _qy(1.0), (0.3, 0, 1.0)),
    "looping_nutation_past_horizontal": ((1.0, 1.0, 0.3), 1.0, (0.6, 0.2, -0.5, 0.4), (1, -0.5, 3)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_matches_30_digit_integration_within_its_own_bound(name):
    inertia, mgl, q0, w0 = CASES[name]
    q0 = _unit(q0)
    top = HeavyTop(inertia, mgl, q0, w0)
    s = top.state(TIMES)
    for i, ref in enumerate(integrate(inertia, q0, w0, TIMES, mgl=mgl)):
        ref = np.array([float(x) for x in ref])
        err = K.geodesic_angle(tuple(ref[:4]), tuple(s.q[i]))
        assert err <= s.error[i] <= 1e-11, (TIMES[i], err, s.error[i])
        # ω from angle rates: a few ulps of each term, terms up to |ω| / sin θ_min.
        assert np.abs(ref[4:] - s.w[i]).max() <= 64 * 2.2e-16 * (1 + np.abs(w0).max())


def test_invariants_and_nutation_bounds():
    inertia, mgl, q0, w0 = CASES["general_tilted_state"]
    top = HeavyTop(inertia, mgl, _unit(q0), w0)
    nut = top.nutation()
    t = np.linspace(0, 4 * nut.period, 4001)
    s = top.state(t)
    energy = top.energy(s.q, s.w)
    assert np.abs(energy - energy[0]).max() <= 64 * 2.2e-16 * abs(energy[0])
    z_axis = np.array([K.qrotate(tuple(q), (0.0, 0.0, 1.0)) for q in s.q])
    theta = np.arccos(np.clip(z_axis[:, 2], -1, 1))
    # sampled extremes approach the bounds to O((2π/4000)²) of the nutation amplitude
    slack = (nut.theta_max - nut.theta_min) * (2 * math.pi * 4 / 4000) ** 2
    assert nut.theta_min - 1e-12 <= theta.min() <= nut.theta_min + slack
    assert nut.theta_max - slack <= theta.max() <= nut.theta_max + 1e-12
    lb = s.w * np.array(inertia)
    lz = np.array([K.qrotate(tuple(q), tuple(v))[2] for q, v in zip(s.q, lb, strict=True)])
    assert np.abs(lz - lz[0]).max() <= 64 * 2.2e-16 * np.abs(w0 * np.array(inertia)).max()
    # θ repeats with the nutation period, and ψ advances by mean_precession × period
    s2 = top.state([0.0, nut.period])
    z0, z1 = (K.qrotate(tuple(q), (0.0, 0.0, 1.0)) for q in s2.q)
    assert abs(z0[2] - z1[2]) <= 1e-13
    dpsi = math.remainder(math.atan2(z1[1], z1[0]) - math.atan2(z0[1], z0[0]), 2 * math.pi)
    want = math.remainder(nut.mean_precession * nut.period, 2 * math.pi)
    assert abs(dpsi - want) <= 1e-12


def test_fast_top_precession_approaches_mgl_over_spin_momentum():
    # Gyroscopic limit: mean precession → mgl / (I3 ω3) with relative error O(mgl I⊥/(I3 ω3)²).
    for spin in (50.0, 500.0):
        top = HeavyTop((1.0, 1.0, 0.5), 1.0, _qy(0.5), (0, 0, spin))
        approx = 1.0 / (0.5 * spin)
        rel = abs(top.nutation().mean_precession - approx) / approx
        assert rel <= 4 * 1.0 * 1.0 / (0.5 * spin) ** 2


def test_guards():
    with pytest.raises(InputError, match="I1 == I2"):
        HeavyTop((1.0, 2.0, 3.0), 1.0, _qy(0.3), (0, 0, 1))
    with pytest.raises(InputError, match="vertical"):
        HeavyTop((1.0, 1.0, 0.5), 1.0, (1.0, 0, 0, 0), (0, 0, 1))
    with pytest.raises(InputError, match="mgl"):
        HeavyTop((1.0, 1.0, 0.5), -1.0, _qy(0.3), (0, 0, 1))
    top = HeavyTop((1.0, 1.0, 0.5), 1.0, _qy(0.5), (0, 0, 10.0))
    with pytest.raises(PrecisionError, match="exceeds max_error"):
        top.state([1e8])
