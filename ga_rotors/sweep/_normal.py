"""The inverse of the standard normal CDF, compiled: what a sweep's normal draw is made of.

``inverse_normal(u)`` is the x with Φ(x) = u, for u in (0, 1), in two rational pieces
fitted to the exact function by :mod:`ga_rotors.sweep._fit_normal` (which prints the
coefficients below):

* central, |u − ½| ≤ :data:`CENTRAL` (85 % of the draws): x = q·P(s)/Q(s), with q = u − ½
  (exact: a draw's u is a multiple of 2⁻⁵⁴) and s = CENTRAL² − q²;
* tails: p = min(u, 1 − u) (1 − u exact for u ≥ ½), r = √(−ln p), and
  x = ∓P(r − r₀)/Q(r − r₀), negative for u < ½.

Both pieces have every coefficient positive in their variable, which is never negative
on its piece, so the Horner sums do not cancel. Measured against mpmath (40 digits) on
the sweep's own u (``tests/test_sweep_normal.py``): within 6 units in the last place,
about 0.9 on average; scipy's ``ndtri``, what the draws used before (draws version 1),
is within 4 and 0.6 on the same points. The central piece of a whole row of u is
computed in a loop LLVM vectorises (:func:`central` has no branch); only the tails take
a logarithm (:func:`ga_rotors.sweep.spec._from_uniform`; measured there: two million
draws in chunks of 65,536, 7 ms of CPU, against 19 ms with scipy's ``ndtri`` called per
draw).
"""

from __future__ import annotations

import math

from .._jit import jit

#: |u − ½| up to which the central piece applies.
CENTRAL = 0.425
_CENTRAL_SQUARED = 0.180625  # CENTRAL², as the fit takes it
#: r₀: where the tails' variable starts (r = √(−ln 0.075) = 1.60943… at the pieces' seam).
_TAIL_FROM = 1.6

#: The central piece's numerator and denominator, in s.
_CENTRAL_P = (
    3.3871328727963665,
    153.75096195270046,
    2738.052819868619,
    24327.72035666084,
    113615.82933968923,
    270151.74946982117,
    291760.2273855831,
    109717.2717923883,
    6361.411034316011,
)
_CENTRAL_Q = (
    1.0,
    48.3979145767834,
    931.7590778029831,
    9123.301689644235,
    48278.924375093266,
    135780.55437764726,
    186631.00454499823,
    103858.08732762057,
    14700.271900043124,
)
#: The tails' numerator and denominator, in r − r₀.
_TAIL_P = (
    1.4234371107496837,
    4.652972072099006,
    5.8779162865043375,
    3.8475958079920285,
    1.4502940165094196,
    0.32542131186560264,
    0.04229363505283927,
    0.0028255337180991234,
    6.962167896474107e-05,
)
_TAIL_Q = (
    1.0,
    2.069092733733761,
    1.7334747919589204,
    0.7629767996778275,
    0.19092307360022556,
    0.026974225223613618,
    0.001919617084995809,
    4.922576198855312e-05,
    3.438474355018292e-11,
)


@jit(inline="always")
def _horner(c, x):
    """c[0] + c[1]·x + … + c[8]·x⁸, Horner's order (the same in every caller)."""
    return ((((((((c[8] * x + c[7]) * x + c[6]) * x + c[5]) * x + c[4]) * x + c[3]) * x
             + c[2]) * x + c[1]) * x + c[0])  # fmt: skip


@jit(inline="always")
def central(u):
    """The central piece at u, meant for |u − ½| ≤ :data:`CENTRAL` (anything, elsewhere).

    Examples
    --------
    >>> central(0.5), round(central(0.9), 12)
    (0.0, 1.281551565545)
    """
    q = u - 0.5
    s = _CENTRAL_SQUARED - q * q
    return q * (_horner(_CENTRAL_P, s) / _horner(_CENTRAL_Q, s))


@jit(inline="always")
def tail(u):
    """The tail piece at u, meant for |u − ½| > :data:`CENTRAL`.

    Examples
    --------
    >>> round(tail(0.025), 12), round(tail(1e-10), 10)
    (-1.95996398454, -6.3613409024)
    """
    p = min(u, 1.0 - u)
    r = math.sqrt(-math.log(p)) - _TAIL_FROM
    x = _horner(_TAIL_P, r) / _horner(_TAIL_Q, r)
    return -x if u < 0.5 else x


@jit(inline="always")
def in_tail(u):
    """Whether u lies in a tail, where :func:`inverse_normal` takes :func:`tail`.

    Examples
    --------
    >>> in_tail(0.5), in_tail(0.075), in_tail(0.0749)
    (False, False, True)
    """
    return abs(u - 0.5) > CENTRAL


@jit(inline="always")
def inverse_normal(u):
    """x with Φ(x) = u, the standard normal's quantile, for 0 < u < 1.

    Examples
    --------
    >>> round(inverse_normal(0.8413447460685429), 12)  # Φ(1)
    1.0
    """
    return tail(u) if in_tail(u) else central(u)
