"""The normal quantile behind a sweep's normal draws (ga_rotors.sweep._normal), against
the exact function (mpmath at 40 digits) and its own fit."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors.sweep import _fit_normal, _normal
from ga_rotors.sweep.spec import _BELOW_ONE

#: The most a quantile may be off, in units in the last place of the exact value
#: (measured: 5.5 at most over 6·10⁴ random u, tails included, 0.9 on average; scipy's
#: ndtri: 3.6).
ULPS = 6.0


def _exact(u: float):
    with mp.workdps(40):
        p = mp.mpf(u) if u < 0.5 else 1 - mp.mpf(u)
        x = _fit_normal._exact(p) if p < mp.mpf(1) / 2 else mp.mpf(0)
        return x if u < 0.5 else -x


def _ulps(u: float) -> float:
    exact = _exact(u)
    got = _normal.inverse_normal(u)
    if exact == 0:
        return 0.0 if got == 0 else math.inf
    with mp.workdps(40):
        return float(abs(mp.mpf(got) - exact) / abs(np.spacing(float(exact))))


def _draw_u(k: int) -> float:
    """The u a draw makes of k = its output >> 11: (k + ½)·2⁻⁵³, 1 taken as below one."""
    return min((k + 0.5) * 2.0**-53, _BELOW_ONE)


@settings(max_examples=300, deadline=None)
@given(k=st.integers(0, 2**53 - 1))
def test_the_quantile_of_any_draw_is_within_a_few_ulps_of_the_exact_one(k):
    assert _ulps(_draw_u(k)) <= ULPS


@settings(max_examples=200, deadline=None)
@given(e=st.floats(math.log(1 / 0.075), 54 * math.log(2)), upper=st.booleans())
def test_the_tails_are_within_a_few_ulps_down_to_the_smallest_draw(e, upper):
    # uniform in -ln p: the far tails as often as the near ones
    k = int(math.exp(-e) * 2**53)
    k = 2**53 - 1 - k if upper else k
    assert _ulps(_draw_u(k)) <= ULPS


@pytest.mark.parametrize(
    "u",
    [
        pytest.param(2.0**-54, id="smallest draw"),
        pytest.param(_BELOW_ONE, id="largest draw"),
        pytest.param(0.5, id="centre"),
        pytest.param(0.5 + 2.0**-53, id="just above the centre"),
        pytest.param(0.5 - _normal.CENTRAL, id="lower seam"),
        pytest.param(np.nextafter(0.5 - _normal.CENTRAL, 0), id="below the lower seam"),
        pytest.param(0.5 + _normal.CENTRAL, id="upper seam"),
        pytest.param(np.nextafter(0.5 + _normal.CENTRAL, 1), id="above the upper seam"),
        pytest.param(0.8413447460685429, id="Phi(1)"),
        pytest.param(0.975, id="0.975"),
    ],
)
def test_hard_cases(u):
    assert _ulps(float(u)) <= ULPS


def test_the_centre_is_zero_and_the_pieces_meet():
    assert _normal.inverse_normal(0.5) == 0.0
    d = 2.0**-30
    for seam in (0.5 - _normal.CENTRAL, 0.5 + _normal.CENTRAL):
        # across the seam the step is the derivative's, 1/phi(x): no jump between the pieces
        step = _normal.inverse_normal(seam + d) - _normal.inverse_normal(seam - d)
        x = _normal.inverse_normal(seam)
        slope = math.sqrt(2 * math.pi) * math.exp(x * x / 2)
        assert step / (2 * d * slope) == pytest.approx(1, abs=1e-6)


@settings(max_examples=200, deadline=None)
@given(k=st.integers(2**52, 2**53 - 1))
def test_the_quantile_is_odd_about_the_centre(k):
    # u ≥ ½ and 1 − u are both exact, and both pieces see the same |u − ½| or min(u, 1 − u)
    u = _draw_u(k)
    assert _normal.inverse_normal(1.0 - u) == -_normal.inverse_normal(u)


def test_a_million_draws_are_standard_normal():
    from scipy import stats

    k = np.random.default_rng(11).integers(0, 2**53, size=10**6, dtype=np.uint64)
    u = np.minimum((k.astype(np.float64) + 0.5) * 2.0**-53, _BELOW_ONE)
    out = u.reshape(1, -1).copy()
    from ga_rotors.sweep import spec

    spec._from_uniform(np.array([True]), np.zeros(1), np.ones(1), out)
    x = out[0]
    assert abs(x.mean()) < 5 / 1000 and abs(x.std() - 1) < 5 / 1000  # 5 sigma of 10^6
    assert stats.kstest(x, "norm").pvalue > 1e-3


@pytest.mark.parametrize("piece", ["central", "tail"])
def test_the_coefficients_are_those_of_the_fit(piece):
    # The fit run again (mpmath, a few seconds): the stored float64 coefficients give
    # the refitted function to within 10^-15 across the piece.
    with mp.workdps(40):
        _, p, q = getattr(_fit_normal, piece)()
        if piece == "central":
            xs = [mp.mpf(v) for v in np.linspace(0.0, 0.180625, 41)]
            stored = (_normal._CENTRAL_P, _normal._CENTRAL_Q)
        else:
            xs = [mp.mpf(v) for v in np.linspace(0.0, 6.125 - 1.6, 41)]
            stored = (_normal._TAIL_P, _normal._TAIL_Q)
        for x in xs:
            fitted = mp.polyval(p[::-1], x) / mp.polyval(q[::-1], x)
            kept = mp.polyval([mp.mpf(c) for c in stored[0][::-1]], x) / mp.polyval(
                [mp.mpf(c) for c in stored[1][::-1]], x
            )
            assert abs(kept / fitted - 1) < 1e-15
