r"""The Euler-angle path: the paper's z–y′–z″ angles :math:`(\psi, \theta, \phi)` integrated
from body :math:`\omega`.

State: :math:`(\psi, \theta, \phi)` in radians, advanced with the rates of
:func:`ga_rotors._kernels.zyz_rates`, which divide by :math:`\sin\theta`. Near
:math:`\sin\theta = 0` the rates grow like :math:`1/\sin\theta` and a fixed step stops
resolving them; at :math:`\sin\theta = 0` exactly they are undefined. The path keeps
going (that is the paper's method, and showing what it does is the point) but watches every
step and reports:

* ``unresolved_steps``: steps that start where :math:`h \lvert \dot\psi \rvert` exceeds
  :data:`UNRESOLVED_TURN`, i.e. the step would turn :math:`\psi` by more than 0.1 rad
  while :math:`\dot\psi \propto 1/\sin\theta` changes on the time scale
  :math:`1/\lvert \dot\psi \rvert`, so RK4's error expansion no longer applies;
* ``first_unresolved``: the time of the first such step;
* ``min_abs_sin_theta``: the smallest :math:`\lvert \sin\theta \rvert` seen at a step start;
* ``pole_crossings``: how often :math:`\sin\theta` changed sign between steps (the
  discrete path stepped across :math:`\theta = 0` or :math:`\pi`, which the exact motion
  never does: :math:`\theta \ge 0` there);
* ``max_turn``: the largest :math:`h \lvert \dot\psi \rvert`.

If the state stops being finite (:math:`\sin\theta = 0` hit exactly), the loop stops and returns the
finite samples it has; the report says when.
"""

from __future__ import annotations

from math import cos, inf, sin

import numpy as np

from .._jit import jit
from .._kernels import quat_from_euler, zyz_rates
from ..integrators._arith import axpy3 as axpy  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import load3 as load  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import rk4_sum3 as rk4_sum  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import store3 as store  # noqa: F401 (a slot, bound by name)

# The slot kernels and state helpers are the OrientationPath protocol, bound by name
# (ga_rotors.paths), compiled and unchecked: internal, so not in __all__.
__all__ = ["DIM", "NSTATS", "STATS", "UNRESOLVED_TURN"]

DIM = 3

#: A step is "unresolved" when it would turn :math:`\psi` by more than this many radians.
#: RK4's local error for a rotation at rate :math:`\lambda` is :math:`\sim (h\lambda)^5/5!`
#: relative: 1e-7 at :math:`h\lambda = 0.1`, and beyond it the :math:`1/\sin\theta` growth
#: of the rates within the step dominates.
UNRESOLVED_TURN = 0.1

#: Layout of the watch statistics array.
STATS = (
    "unresolved_steps",
    "first_unresolved",
    "min_abs_sin_theta",
    "pole_crossings",
    "max_turn",
    "_last_sign",
)
NSTATS = len(STATS)
_INITIAL_STATS = (0.0, np.inf, np.inf, 0.0, 0.0, 0.0)


@jit
def rate(x, w):
    r""":math:`(\dot\psi, \dot\theta, \dot\phi)` from the angles and body :math:`\omega`
    (:func:`ga_rotors._kernels.zyz_rates`).

    Examples
    --------
    >>> rate((0.1, 0.5, 0.3), (0.0, 0.0, 10.0))
    (0.0, 0.0, 10.0)
    """
    return zyz_rates(x, w)


@jit
def to_quat(x):
    r""":math:`q = q_z(\psi) \otimes q_y(\theta) \otimes q_z(\phi)`, the convention that
    defines the angles.

    Examples
    --------
    >>> to_quat((0.0, np.pi / 2, 0.0))  # a quarter turn about y
    (0.7071067811865476, 0.0, 0.7071067811865475, 0.0)
    """
    return quat_from_euler(2, 1, 2, x[0], x[1], x[2])


@jit
def watch(t, x, w, h, stats):
    r"""Record how close the step starts to :math:`\sin\theta = 0` and whether :math:`h`
    resolves the rates.

    Examples
    --------
    A step of 10 ms at :math:`\theta = 0.01` rad with :math:`\omega = (1, 0, 10)` turns
    :math:`\psi` by :math:`h \lvert \dot\psi \rvert \approx 1` rad, more than
    :data:`UNRESOLVED_TURN`:

    >>> stats = initial_stats()
    >>> watch(0.0, (0.0, 0.01, 0.0), (1.0, 0.0, 10.0), 1e-2, stats)
    >>> report(stats)  # doctest: +NORMALIZE_WHITESPACE
    {'unresolved_steps': 1, 'first_unresolved': 0.0, 'min_abs_sin_theta': 0.00999983,
     'pole_crossings': 0, 'max_turn': 1.00002}
    """
    st = sin(x[1])
    num = abs(w[1] * sin(x[2]) - w[0] * cos(x[2]))  # |ψ̇ sin θ|
    den = abs(st)
    if h * num > UNRESOLVED_TURN * den or den == 0.0:
        if stats[0] == 0.0:
            stats[1] = t
        stats[0] += 1.0
    if den < stats[2]:
        stats[2] = den
    turn = h * num / den if den > 0.0 else inf
    if turn > stats[4]:
        stats[4] = turn
    sign = 1.0 if st > 0.0 else (-1.0 if st < 0.0 else 0.0)
    if sign != 0.0:
        if stats[5] != 0.0 and sign != stats[5]:
            stats[3] += 1.0
        stats[5] = sign


def initial_stats() -> np.ndarray:
    """A fresh statistics array for :func:`watch`."""
    return np.array(_INITIAL_STATS, dtype=np.float64)


def report(stats: np.ndarray) -> dict:
    """The watch statistics as a plain dict (``None`` where nothing was seen)."""
    out = {name: float(v) for name, v in zip(STATS, stats, strict=True) if not name.startswith("_")}
    out["unresolved_steps"] = int(out["unresolved_steps"])
    out["pole_crossings"] = int(out["pole_crossings"])
    if not np.isfinite(out["first_unresolved"]):
        out["first_unresolved"] = None
    return out


def initial_state(angles: np.ndarray) -> np.ndarray:
    r"""The path's state: the ZYZ angles :math:`(\psi, \theta, \phi)` themselves.

    Examples
    --------
    >>> initial_state((0.1, 0.2, 0.3))
    array([0.1, 0.2, 0.3])
    """
    return np.array(angles, dtype=np.float64)


def quaternions(states: np.ndarray) -> np.ndarray:
    r"""Unit quaternions (..., 4) of ZYZ angle arrays (..., 3).

    Examples
    --------
    :math:`\theta = 90^\circ` alone is a quarter turn about y:
    :math:`q = (\cos 45^\circ, 0, \sin 45^\circ, 0)`.

    >>> quaternions([0.0, np.pi / 2, 0.0])
    array([0.70710678, 0.        , 0.70710678, 0.        ])
    """
    from ..euler import to_quaternion

    return to_quaternion("ZYZ", states)
