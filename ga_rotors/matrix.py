r"""Rotation matrices (..., 3, 3) ↔ unit quaternions (..., 4).

:math:`M v = q v q^*`: the matrix of the active rotation (columns are the images of the body
axes). Matrices must be orthonormal with determinant +1 within
:data:`ORTHONORMAL_TOLERANCE`; reflections and skewed or scaled matrices are rejected.

Examples
--------
>>> import numpy as np
>>> m = from_quaternion([0.0, 0.0, 0.0, 1.0])          # half-turn about z
>>> m.round(15) + 0.0
array([[-1.,  0.,  0.],
       [ 0., -1.,  0.],
       [ 0.,  0.,  1.]])
>>> to_quaternion(m)
array([0., 0., 0., 1.])
"""

from __future__ import annotations

import numpy as np

from . import _kernels as K
from ._batch import Batch, put, residue, row4
from ._jit import jit
from ._validate import UNIT_TOLERANCE, as_float_array
from .errors import InputError

__all__ = ["ORTHONORMAL_TOLERANCE", "check_rotation_matrix", "from_quaternion", "to_quaternion"]

#: Largest entry of |MᵀM − I| accepted. A matrix s·R with |s − 1| = δ has MᵀM − I = (2δ + δ²) I,
#: so this matches the quaternion unit tolerance (δ = UNIT_TOLERANCE = 1e-6) with δ² to spare.
ORTHONORMAL_TOLERANCE = 2.0 * UNIT_TOLERANCE + 2.0 * UNIT_TOLERANCE**2


@jit
def _to_quaternion_loop(m, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.quat_from_matrix(
            (m[n, 0, 0], m[n, 0, 1], m[n, 0, 2], m[n, 1, 0], m[n, 1, 1], m[n, 1, 2],
             m[n, 2, 0], m[n, 2, 1], m[n, 2, 2])
        )  # fmt: skip
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def _from_quaternion_loop(q, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.matrix_from_quat(K.qunit(row4(q, n), tol))
        for k in range(9):
            out[n, k // 3, k % 3] = r[k]
        bad += residue(r)
    return bad == 0.0


def check_rotation_matrix(m, name: str = "m") -> np.ndarray:
    """``m`` as a float array of rotation matrices, or :class:`InputError`.

    Requires shape (..., 3, 3), finite entries, max |MᵀM − I| ≤ ORTHONORMAL_TOLERANCE and
    det M > 0 (det −1 is a reflection, which no rotation produces).

    Examples
    --------
    >>> check_rotation_matrix(np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: m: expected a rotation (det +1), got det -1 at index (): ...
    >>> check_rotation_matrix(2 * np.eye(3))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: m: expected an orthonormal matrix (max |MᵀM - I| <= 2e-06), ...
    """
    a = as_float_array(m, name)
    if a.ndim < 2 or a.shape[-2:] != (3, 3):
        raise InputError(f"{name}: expected an array of shape (..., 3, 3), got shape {a.shape}")
    gram = np.einsum("...ki,...kj->...ij", a, a) - np.eye(3)
    dev = np.abs(gram).max(axis=(-2, -1))
    bad = ~(dev <= ORTHONORMAL_TOLERANCE)
    if np.any(bad):
        where = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        raise InputError(
            f"{name}: expected an orthonormal matrix "
            f"(max |MᵀM - I| <= {ORTHONORMAL_TOLERANCE:.2g}), got {dev[where]:.3g} at index {where}"
        )
    det = np.linalg.det(a)
    if np.any(det < 0):
        where = tuple(int(i) for i in np.argwhere(det < 0)[0]) if det.ndim else ()
        raise InputError(
            f"{name}: expected a rotation (det +1), got det {det[where]:.3g} at index {where}: "
            "a reflection"
        )
    return a


def to_quaternion(m) -> np.ndarray:
    """Unit quaternion (w ≥ 0) of rotation matrices (..., 3, 3).

    The component with the largest square (the largest of tr M, m₀₀, m₁₁, m₂₂) comes from a
    square root and the other three are divided by it, so no division by a small number
    happens anywhere: exact at half-turns (trace −1), where the notes' formulas divide by
    4q₀ = 0. At w = 0 the sign is fixed by that largest component being positive.
    A matrix accepted within :data:`ORTHONORMAL_TOLERANCE` is first divided by its RMS
    column length, so s·R gives R's quaternion to round-off; any other deviation moves
    the result by at most about its own size (≤ 2e-6 rad).

    Examples
    --------
    >>> to_quaternion(np.diag([1.0, -1.0, -1.0]))          # half-turn about x
    array([0., 1., 0., 0.])
    >>> to_quaternion(np.eye(3))
    array([1., 0., 0., 0.])
    """
    a = check_rotation_matrix(m, "m")
    lead = a.shape[:-2]
    # Divide by the RMS column length first: the branch formulas (4w² = 1 + tr M, ...)
    # assume |columns| = 1, and a matrix s·R accepted within the tolerance would otherwise
    # turn into a rotation off by ~(s − 1) rad instead of R itself.
    a = a / np.sqrt(np.einsum("...ij,...ij->...", a, a) / 3.0)[..., None, None]
    flat = np.ascontiguousarray(a.reshape((-1, 3, 3)))
    out = np.empty((flat.shape[0], 4))
    if not _to_quaternion_loop(flat, out):  # pragma: no cover - inputs were checked finite
        raise InputError("m: conversion produced a non-finite quaternion")
    return out.reshape((*lead, 4))


def from_quaternion(q) -> np.ndarray:
    r"""Rotation matrices (..., 3, 3) of unit quaternions: :math:`M v = q v q^*`.

    Examples
    --------
    >>> from_quaternion([1.0, 0, 0, 0])
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    b = Batch((q, "q", 4))
    out = np.empty((b.n, 3, 3))
    b.fail(_from_quaternion_loop(b.flat[0], out, UNIT_TOLERANCE), out, unit=("q",))
    return out.reshape((*b.shape, 3, 3))
