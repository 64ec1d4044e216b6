r"""The rotor path: :math:`\dot R = \tfrac12 R \Omega` in Cl(3,0), :math:`\Omega = -I\omega`,
the primary orientation path.

State: the rotor's coefficients on clifford's even blades :math:`(1, e_{12}, e_{13}, e_{23})`.
The arithmetic is :mod:`ga_rotors._rotor_kernels`, generated from clifford's
multiplication table. Binds the template slots ``o_*`` (see :mod:`ga_rotors.integrators.slots`).
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from .._kernels import qnormalize
from .._rotor_kernels import quat_from_rotor, rotor_from_quat, rotor_rate
from ..integrators._arith import axpy4 as axpy  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import load4 as load  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import rk4_sum4 as rk4_sum  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import store4 as store  # noqa: F401 (a slot, bound by name)

# The slot kernels and state helpers are the OrientationPath protocol, bound by name
# (ga_rotors.paths), compiled and unchecked: internal, so not in __all__.
__all__ = ["COMPONENTS", "DIM", "NSTATS"]

DIM = 4
NSTATS = 0
#: Names of the state's components, clifford's even blades in layout order.
COMPONENTS = ("1", "e12", "e13", "e23")


@jit
def rate(x, w):
    r""":math:`\dot R = \tfrac12 R \Omega`.

    Examples
    --------
    At :math:`R = 1`, :math:`\omega = (0, 0, 2)`: :math:`\Omega = -2 e_{12}` and
    :math:`\dot R = -e_{12}`, on the blades :math:`(1, e_{12}, e_{13}, e_{23})`. (The
    quaternion path's :math:`\dot q` there is :math:`k`, and :math:`k \leftrightarrow -e_{12}`.)

    >>> rate((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 2.0))
    (0.0, -1.0, 0.0, -0.0)
    """
    return rotor_rate(x, w)


@jit
def normalize(x):
    r""":math:`R / \lvert R \rvert`: :math:`R \tilde R = \lvert R \rvert^2` on the even
    subalgebra, the Euclidean norm of the coefficients.

    Examples
    --------
    >>> normalize((0.0, 3.0, 0.0, 4.0))
    (0.0, 0.6, 0.0, 0.8)
    """
    return qnormalize(x)


@jit
def to_quat(x):
    r"""The unit quaternion of the rotor.

    Examples
    --------
    :math:`R = w - x e_{23} + y e_{13} - z e_{12}`, read back:

    >>> to_quat((0.5, -0.5, 0.5, -0.5))
    (0.5, 0.5, 0.5, 0.5)
    """
    return quat_from_rotor(x)


@jit
def from_quat(q):
    r"""The rotor of a unit quaternion.

    Examples
    --------
    :math:`k` (a half turn about z) is :math:`-e_{12}`:

    >>> from_quat((0.0, 0.0, 0.0, 1.0))
    (0.0, -1.0, 0.0, -0.0)
    """
    return rotor_from_quat(q)


@jit
def watch(t, x, w, h, stats):
    """Nothing to watch: a rotor has no coordinate singularity.

    Examples
    --------
    No statistics (NSTATS = 0), nothing recorded:

    >>> stats = np.zeros(NSTATS)
    >>> watch(0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 2.0), 1e-3, stats)
    >>> stats.size
    0
    """


def _signed_permutation(kernel) -> np.ndarray:
    # The generated maps are signed permutations; their matrix is the images of the
    # identity rows (plain-Python call: no compiled code needed for four tuples).
    py = getattr(kernel, "py_func", kernel)
    return np.array([py(tuple(row)) for row in np.eye(4)])


def initial_state(q0: np.ndarray) -> np.ndarray:
    r"""The rotor coefficients of the unit quaternion ``q0``.

    Examples
    --------
    :math:`q = (w, x, y, z)` is :math:`R = w - x e_{23} + y e_{13} - z e_{12}`: on the blades
    :math:`(1, e_{12}, e_{13}, e_{23})`,

    >>> initial_state([0.5, 0.5, 0.5, 0.5])
    array([ 0.5, -0.5,  0.5, -0.5])
    """
    return np.asarray(q0, dtype=np.float64) @ _signed_permutation(rotor_from_quat)


def quaternions(states: np.ndarray) -> np.ndarray:
    """Unit quaternions (..., 4) of rotor coefficient arrays (..., 4).

    Examples
    --------
    The inverse of :func:`initial_state`:

    >>> quaternions(initial_state([[0.5, 0.5, 0.5, 0.5], [0.0, 1.0, 0.0, 0.0]]))
    array([[0.5, 0.5, 0.5, 0.5],
           [0. , 1. , 0. , 0. ]])
    """
    return np.asarray(states, dtype=np.float64) @ _signed_permutation(quat_from_rotor)
