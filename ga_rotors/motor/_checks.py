"""Checking motor arguments and naming the bad one, for the public functions of ga_rotors.motor.

The compiled loops only say whether every result was finite (:mod:`ga_rotors._batch`);
:func:`fail` then finds out, on the slow path, which argument was wrong: a non-finite
entry, a motor that is not unit (:func:`require_motor`), a quaternion that is not unit,
a zero where a nonzero value is needed; otherwise the result overflowed.

The linear maps between a motor and its two quaternions (r, d) are read off the generated
kernel :func:`ga_rotors._motor_kernels.dual_parts` once, so NumPy code here uses the same
table as the compiled code.
"""

from __future__ import annotations

import numpy as np

from .. import _motor_kernels as MK
from .._jit import plain
from .._validate import UNIT_TOLERANCE, as_float_array, check_finite
from ..errors import InputError

__all__ = ["DUAL", "fail", "leading_shape", "line_parts", "norm3", "require_motor"]


def _dual_matrix() -> np.ndarray:
    parts = plain(MK.dual_parts)
    rows = [np.concatenate(parts(tuple(e))) for e in np.eye(8)]
    return np.array(rows)


#: (8, 8) signed permutation: ``m @ DUAL`` is (r, d), ``rd @ DUAL.T`` the motor again.
DUAL = _dual_matrix()


def require_motor(m: np.ndarray, name: str, tol: float = UNIT_TOLERANCE) -> None:
    """Raise :class:`InputError` naming the first motor of ``m`` (..., 8) that is not unit.

    Unit within ``tol``: | |r| − 1 | ≤ tol and |r·d| ≤ tol |r| max(1, |d|), with M M̃ =
    |r|² + 2 (r·d) e0123 (the test :func:`ga_rotors.motor._screw.munit` makes in the loops).
    """
    rd = m @ DUAL
    r, d = rd[..., :4], rd[..., 4:]
    n = np.sqrt(np.einsum("...i,...i->...", r, r))
    study = np.einsum("...i,...i->...", r, d)
    size = n * np.maximum(1.0, np.sqrt(np.einsum("...i,...i->...", d, d)))
    bad = ~((np.abs(n - 1.0) <= tol) & (np.abs(study) <= tol * size))
    if np.any(bad):
        where = _first(bad)
        raise InputError(
            f"expected unit motors (M M̃ = 1 to within {tol:g}, relative), got M M̃ = "
            f"{n[where] ** 2:.6g} + {2.0 * study[where]:.3g} e0123 at index {where}; "
            "normalise it first (ga_rotors.motor.normalize)",
            key=name,
        )


def _first(bad: np.ndarray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()


def leading_shape(*specs) -> tuple[int, ...]:
    """The broadcast leading shape of (array, name, item ndim) triples, or InputError
    naming each argument's leading shape (the message :class:`ga_rotors._batch.Batch` gives)."""
    leading = [(name, a.shape[: a.ndim - k]) for a, name, k in specs]
    try:
        return np.broadcast_shapes(*(shape for _, shape in leading))
    except ValueError:
        described = ", ".join(f"{name} {shape}" for name, shape in leading)
        raise InputError(f"leading shapes do not broadcast: {described}") from None


def norm3(v: np.ndarray) -> np.ndarray:
    """|v| over the last axis (length 3) without under- or overflow (1e-300 stays 1e-300)."""
    return np.hypot(np.hypot(v[..., 0], v[..., 1]), v[..., 2])


def line_parts(L, name: str = "L") -> tuple[np.ndarray, np.ndarray]:
    """(the point nearest the origin (..., 3), the unit direction (..., 3)) of lines L (..., 6).

    A line (e01, e02, e03, e12, e13, e23) = (m₁, m₂, m₃, d₃, −d₂, d₁) has direction d and
    moment m = p × d for any point p on it; it is a line only when d·m = 0 (the Plücker
    condition, checked within UNIT_TOLERANCE of |d| max(|d|, |m|): relative, and against
    one length unit for lines near the origin, whose moment may be rounding noise, as
    for the motors' Study condition). Lines without a direction (d = 0: ideal lines, at
    infinity) have no points and are refused.
    """
    a = as_float_array(L, name, last=6)
    d = np.stack([a[..., 5], 0.0 - a[..., 4], a[..., 3]], axis=-1)
    m = a[..., :3]
    size, moment = norm3(d), norm3(m)
    ideal = size == 0.0
    if np.any(ideal):
        raise InputError(
            "expected a line with a direction (e12, e13, e23 not all 0), got an ideal line at "
            f"index {_first(ideal)}",
            key=name,
        )
    along = np.einsum("...i,...i->...", d / size[..., None], m)
    screw = np.abs(along) > UNIT_TOLERANCE * np.maximum(size, moment)
    if np.any(screw):
        raise InputError(
            f"expected a line (direction ⊥ moment), got a screw at index {_first(screw)}", key=name
        )
    u = d / size[..., None]
    return np.cross(u, m / size[..., None]), u


def fail(batch, ok: bool, out: np.ndarray, *, motors=(), unit=(), nonzero=(), what="result"):
    """Raise the error behind a loop that reported a non-finite value (no-op when ``ok``).

    Checks, in order: finiteness of every argument, the unit motors named in ``motors``,
    then :meth:`ga_rotors._batch.Batch.fail`'s checks (unit quaternions in ``unit``,
    nonzero arguments in ``nonzero``, overflow of the result).
    """
    if ok:
        return
    for a, name in zip(batch.arrays, batch.names, strict=True):
        check_finite(a, name)
    for a, name in zip(batch.arrays, batch.names, strict=True):
        if name in motors:
            require_motor(a, name)
    batch.fail(ok, out, unit=unit, nonzero=nonzero, what=what)
