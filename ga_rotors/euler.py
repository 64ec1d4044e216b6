r"""Euler angles ↔ unit quaternions for all 12 axis orders, intrinsic and extrinsic.

Sequences follow scipy's naming: three letters, upper case for intrinsic rotations about
the moving axes ('ZYX': about z, then the new y′, then the newer x″), lower case for
extrinsic rotations about the fixed axes ('xyz': about x, then y, then z, all fixed). An
extrinsic sequence equals its reversed intrinsic twin with the angles reversed:
'xyz' (α, β, γ) = 'ZYX' (γ, β, α) =
:math:`q_z(\gamma) \otimes q_y(\beta) \otimes q_x(\alpha)`.

* The paper's angles: intrinsic 'ZYZ' (ψ precession, θ nutation, φ spin),
  :math:`q = q_z(\psi) \otimes q_y(\theta) \otimes q_z(\varphi)`.
* The notes' aerospace angles: intrinsic 'ZYX' (yaw, pitch, roll).

Angles come back with the first and third in (−π, π] and the middle one in [0, π]
(proper Euler, first axis = last) or [−π/2, π/2] (Tait–Bryan, three distinct axes).

Gimbal lock (middle angle within :data:`GIMBAL_TOLERANCE` of 0 or π, resp. ±π/2): only the
sum or the difference of the first and third angles is defined. The third angle of the
sequence as written is set to 0 (scipy's rule), a
:class:`~ga_rotors.errors.GimbalLockWarning` is issued, and ``return_gimbal=True`` also
returns a boolean mask. Never NaN, and the angles still describe the rotation.

Examples
--------
>>> import numpy as np
>>> q = to_quaternion("ZYZ", [0.3, 0.2, 0.1])
>>> from_quaternion(q, "ZYZ")
array([0.3, 0.2, 0.1])
>>> from_quaternion(q, "zyx").round(6)
array([ 0.405732,  0.190954, -0.059833])
"""

from __future__ import annotations

import warnings

import numpy as np

from . import _kernels as K
from ._batch import Batch, put, residue, row3, row4
from ._jit import jit
from ._validate import UNIT_TOLERANCE, as_float_array
from .errors import GimbalLockWarning, InputError

__all__ = ["GIMBAL_TOLERANCE", "SEQUENCES", "from_quaternion", "parse_sequence", "to_quaternion"]

_ORDERS = tuple(a + b + c for a in "XYZ" for b in "XYZ" for c in "XYZ" if a != b and b != c)
#: The 24 valid sequences: 12 intrinsic (upper case) then 12 extrinsic (lower case).
SEQUENCES: tuple[str, ...] = _ORDERS + tuple(s.lower() for s in _ORDERS)

#: Distance (rad) of the middle angle from its singular value below which the first and
#: third angles are treated as locked together. Quaternions built from angles exactly at
#: the singularity land within ~2e-16 of it (cos(π/2) is 6e-17, not 0); 1e-14 leaves
#: a factor 50 for a few more roundings. Setting the third angle to 0 moves the rotation
#: by at most twice this distance, 2e-14 rad. Beyond it the angles are computed in full:
#: the rotation they describe is exact, though the first and third individually carry
#: errors ~1e-16/(distance).
GIMBAL_TOLERANCE = 1e-14


def parse_sequence(seq) -> tuple[int, int, int, bool]:
    """(i, j, k, extrinsic) of a sequence string; axes 0, 1, 2 are x, y, z.

    Examples
    --------
    >>> parse_sequence("ZYX")
    (2, 1, 0, False)
    >>> parse_sequence("zyz")
    (2, 1, 2, True)
    >>> parse_sequence("ZZY")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: seq: expected three axes from 'XYZ' (intrinsic) or 'xyz' ...
    """
    if not isinstance(seq, str) or seq not in SEQUENCES:
        raise InputError(
            "seq: expected three axes from 'XYZ' (intrinsic) or 'xyz' (extrinsic), one case "
            "only, no axis twice in a row, such as 'ZYZ', 'ZYX' or 'xyz' (24 valid: "
            f"{', '.join(SEQUENCES)}); got {seq!r}"
        )
    i, j, k = ("xyz".index(c) for c in seq.lower())
    return i, j, k, seq.islower()


@jit
def _to_quaternion_loop(angles, out, i, j, k, extrinsic):
    bad = 0.0
    for n in range(out.shape[0]):
        a, b, c = row3(angles, n)
        if extrinsic:
            r = K.quat_from_euler(k, j, i, c, b, a)
        else:
            r = K.quat_from_euler(i, j, k, a, b, c)
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def _from_quaternion_loop(q, out, locked, i, j, k, extrinsic, tol, gimbal_tol):
    bad = 0.0
    for n in range(out.shape[0]):
        u = K.qunit(row4(q, n), tol)
        if extrinsic:
            c, b, a, lock = K.euler_from_quat(u, k, j, i, True, gimbal_tol)
        else:
            a, b, c, lock = K.euler_from_quat(u, i, j, k, False, gimbal_tol)
        put(out, n, (a, b, c))
        locked[n] = lock != 0.0
        bad += residue((a, b, c))
    return bad == 0.0


def to_quaternion(seq: str, angles, degrees: bool = False) -> np.ndarray:
    r"""Unit quaternions (..., 4) of Euler angles (..., 3) in sequence ``seq``.

    Intrinsic 'IJK' with angles (a, b, c) is :math:`q_i(a) \otimes q_j(b) \otimes q_k(c)`;
    extrinsic 'ijk' is :math:`q_k(c) \otimes q_j(b) \otimes q_i(a)`.

    Examples
    --------
    >>> to_quaternion("ZYX", [90.0, 0.0, 0.0], degrees=True).round(15)     # yaw 90°
    array([0.707107, 0.      , 0.      , 0.707107])
    >>> np.allclose(to_quaternion("xyz", [0.1, 0.2, 0.3]), to_quaternion("ZYX", [0.3, 0.2, 0.1]))
    True
    """
    i, j, k, extrinsic = parse_sequence(seq)
    if degrees:
        angles = np.radians(as_float_array(angles, "angles", finite=False))
    b = Batch((angles, "angles", 3))
    out = b.empty(4)
    b.fail(_to_quaternion_loop(b.flat[0], out, i, j, k, extrinsic), out)
    return b.shaped(out)


def from_quaternion(q, seq: str, degrees: bool = False, return_gimbal: bool = False):
    """Euler angles (..., 3) of unit quaternions in sequence ``seq``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternions (renormalised within UNIT_TOLERANCE).
    seq : str
        One of :data:`SEQUENCES`.
    degrees : bool
        Return degrees.
    return_gimbal : bool
        Also return a boolean array (...) marking gimbal-locked items.

    Returns
    -------
    angles : ndarray, shape (..., 3)
    locked : ndarray of bool, shape (...), only with ``return_gimbal=True``

    Warns
    -----
    GimbalLockWarning
        When any item is at gimbal lock (its third angle is then 0).

    Examples
    --------
    >>> import warnings
    >>> q = to_quaternion("ZYZ", [0.3, 0.0, 0.5])           # nutation 0: locked
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     angles, locked = from_quaternion(q, "ZYZ", return_gimbal=True)
    >>> angles, locked
    (array([0.8, 0. , 0. ]), True)
    """
    i, j, k, extrinsic = parse_sequence(seq)
    b = Batch((q, "q", 4))
    out = b.empty(3)
    locked = np.empty(b.n, dtype=np.bool_)
    ok = _from_quaternion_loop(
        b.flat[0], out, locked, i, j, k, extrinsic, UNIT_TOLERANCE, GIMBAL_TOLERANCE
    )
    b.fail(ok, out, unit=("q",))
    angles = b.shaped(out)
    if degrees:
        angles = np.degrees(angles)
    mask = locked.reshape(b.shape)
    if mask.any():
        warnings.warn(
            f"gimbal lock in sequence {seq!r} at {int(mask.sum())} of {b.n} rotations: only "
            "the sum or difference of the first and third angles is defined; the third "
            "angle is set to 0 (the rotation is unchanged)",
            GimbalLockWarning,
            stacklevel=2,
        )
    if return_gimbal:
        return angles, (bool(mask) if mask.ndim == 0 else mask)
    return angles
