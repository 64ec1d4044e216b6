r"""A prescribed body angular velocity with an exact orientation: coning.

The orientation :math:`q(t) = q_0 \otimes q_z(at) \otimes q_x(bt)` (a spin :math:`a`
about a body :math:`z` axis that itself turns about :math:`x` at rate :math:`b`) has the
body angular velocity

.. math::

    \omega(t) = q_x(bt)^* \,(0, 0, a)\, q_x(bt) + (b, 0, 0) = (b,\ a \sin bt,\ a \cos bt):

:math:`\omega` changes direction all the time, so methods that freeze :math:`\omega` over
a step (Lie–Euler, MuJoCo's exponential map) show their order, and Magnus methods can be
measured against the exact answer.
"""

from __future__ import annotations

from math import cos, sin

import numpy as np

from .._jit import jit
from .._validate import as_float_array, require_unit
from ..errors import InputError

__all__ = ["Coning", "coning_rate"]


@jit
def coning_rate(t, p):
    r"""Body :math:`\omega(t) = (b,\ a \sin bt,\ a \cos bt)` with :math:`p = (a, b)`.

    Examples
    --------
    >>> coning_rate(0.0, (0.2, 2.0))
    (2.0, 0.0, 0.2)
    >>> [round(c, 12) for c in coning_rate(np.pi / 4, (0.2, 2.0))]  # b t = π/2
    [2.0, 0.2, 0.0]
    >>> coning_rate(0.0, np.array([]))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: p: coning_rate takes p = (a, b); got fewer values
    """
    if len(p) < 2:  # a compiled kernel reads no bounds: this one is public
        raise InputError("coning_rate takes p = (a, b); got fewer values", "p")
    a, b = p[0], p[1]
    return (b, a * sin(b * t), a * cos(b * t))


class Coning:
    """Exact orientation for the prescribed rate :func:`coning_rate`.

    Examples
    --------
    >>> c = Coning(2.0, 0.5)
    >>> q = c.at([0.0, 1.0])
    >>> bool(np.allclose(q[0], (1, 0, 0, 0)))
    True
    """

    def __init__(self, a: float, b: float, orientation=(1.0, 0.0, 0.0, 0.0)):
        self.params = (float(a), float(b))
        self.q0 = require_unit(as_float_array(orientation, "orientation", last=4), "orientation")

    def at(self, t) -> np.ndarray:
        """Orientations (n, 4) at times ``t``."""
        from .. import quaternion as Q

        t = np.atleast_1d(as_float_array(t, "t")).ravel()
        a, b = self.params
        spin = Q.from_axis_angle((0.0, 0.0, 1.0), a * t)
        turn = Q.from_axis_angle((1.0, 0.0, 0.0), b * t)
        return Q.multiply(self.q0, Q.multiply(spin, turn))
