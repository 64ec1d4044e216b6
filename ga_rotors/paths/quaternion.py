r"""The quaternion path: :math:`\dot q = \tfrac12 q \otimes (0, \omega)`, the paper's inverse
kinematics by quaternions.

State: the unit quaternion :math:`(w, x, y, z)` of body -> space. Binds the template slots
``o_*`` (see :mod:`ga_rotors.integrators.slots`).
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from .._kernels import qmul_pure, qnormalize
from ..integrators._arith import axpy4 as axpy  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import load4 as load  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import rk4_sum4 as rk4_sum  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import store4 as store  # noqa: F401 (a slot, bound by name)

# The slot kernels and state helpers are the OrientationPath protocol, bound by name
# (ga_rotors.paths), compiled and unchecked: internal, so not in __all__.
__all__ = ["DIM", "NSTATS"]

DIM = 4
NSTATS = 0


@jit
def rate(x, w):
    r""":math:`\dot q = \tfrac12 q \otimes (0, \omega)`.

    Examples
    --------
    >>> rate((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 2.0))  # ½ (0, 0, 0, 2)
    (-0.0, 0.0, 0.0, 1.0)
    """
    d = qmul_pure(x, w)
    return (0.5 * d[0], 0.5 * d[1], 0.5 * d[2], 0.5 * d[3])


@jit
def normalize(x):
    """Back onto the unit sphere.

    Examples
    --------
    >>> normalize((0.0, 3.0, 0.0, 4.0))
    (0.0, 0.6, 0.0, 0.8)
    """
    return qnormalize(x)


@jit
def to_quat(x):
    """The state is the quaternion.

    Examples
    --------
    >>> to_quat((0.5, 0.5, 0.5, 0.5))
    (0.5, 0.5, 0.5, 0.5)
    """
    return x


@jit
def from_quat(q):
    """The state is the quaternion.

    Examples
    --------
    >>> from_quat((0.5, 0.5, 0.5, 0.5))
    (0.5, 0.5, 0.5, 0.5)
    """
    return q


@jit
def watch(t, x, w, h, stats):
    """Nothing to watch: a quaternion has no coordinate singularity.

    Examples
    --------
    No statistics (NSTATS = 0), nothing recorded:

    >>> stats = np.zeros(NSTATS)
    >>> watch(0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 2.0), 1e-3, stats)
    >>> stats.size
    0
    """


def initial_state(q0: np.ndarray) -> np.ndarray:
    """The path's state for the unit quaternion ``q0``: a float64 copy of it.

    Examples
    --------
    >>> q0 = np.array([0.5, 0.5, 0.5, 0.5])
    >>> x = initial_state(q0)
    >>> x, x is q0
    (array([0.5, 0.5, 0.5, 0.5]), False)
    """
    return np.array(q0, dtype=np.float64)


def quaternions(states: np.ndarray) -> np.ndarray:
    """Unit quaternions (..., 4) of path states (..., 4): the states themselves.

    Examples
    --------
    >>> quaternions([[1, 0, 0, 0], [0, 0, 0, 1]])
    array([[1., 0., 0., 0.],
           [0., 0., 0., 1.]])
    """
    return np.asarray(states, dtype=np.float64)
