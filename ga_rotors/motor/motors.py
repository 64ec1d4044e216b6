"""Motors of Cl(3,0,1) as float arrays: build, convert, compose, invert, exp and log.

A motor is a float array of shape (..., 8), the coefficients of (1, e01, e02, e03, e12,
e13, e23, e0123); bivectors (lines, screws, velocities) are float arrays of shape (..., 6),
the coefficients of (e01, e02, e03, e12, e13, e23). Every function broadcasts over leading
axes like a NumPy ufunc and runs in a compiled loop (:mod:`ga_rotors.motor._loops`).

Conventions (docs/conventions.md, "Motors"): the translator by t is T = 1 − ½ e0 t (it
moves points by +t), the rotor of the quaternion q = (w, x, y, z) is w − x e23 − y e31 −
z e12 as in :mod:`ga_rotors.rotor`, and the motor of the pose (q, t) is M = T(t) R(q):
rotate about the origin, then translate. ``compose(M1, M2)`` applies M2 first.

Unit motors (M M̃ = 1) are required wherever a rigid motion is meant: inputs within
:data:`~ga_rotors._validate.UNIT_TOLERANCE` are renormalised (:func:`normalize`), others
raise :class:`~ga_rotors.errors.InputError`.

Examples
--------
>>> T = from_translation([1.0, 0.0, 0.0])
>>> R = from_quaternion([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)])  # 90° about z
>>> q, t = to_pose(compose(T, R))                  # turn, then shift
>>> t
array([1., 0., 0.])
"""

from __future__ import annotations

import numpy as np

from .. import _motor_kernels as MK
from .. import quaternion as Q
from .._batch import Batch
from .._jit import plain
from .._validate import UNIT_TOLERANCE, as_float_array
from ..errors import InputError
from ..matrix import ORTHONORMAL_TOLERANCE, check_rotation_matrix
from ..matrix import to_quaternion as _matrix_quaternion
from . import _loops as L
from ._checks import DUAL, fail, leading_shape, line_parts, norm3

__all__ = [
    "compose",
    "exp",
    "from_dual_quaternion",
    "from_matrix",
    "from_pose",
    "from_quaternion",
    "from_screw",
    "from_translation",
    "inverse",
    "log",
    "normalize",
    "reverse",
    "to_dual_quaternion",
    "to_matrix",
    "to_pose",
    "to_quaternion",
    "to_screw",
    "to_translation",
    "velocities",
    "velocity_line",
]

#: Signs of the reverse on (1, e01, e02, e03, e12, e13, e23, e0123): bivectors change sign.
_REVERSE = np.array([1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, 1.0])
#: The identity motor.
_ONE = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])


def _translator_matrix() -> np.ndarray:
    # T(t) is linear in t: its rows are read off the generated pose kernel (q = 1), so the
    # translator's sign is stated once, in the generator.
    pose = plain(MK.motor_from_pose)
    return np.array([np.subtract(pose((1.0, 0.0, 0.0, 0.0), tuple(e)), _ONE) for e in np.eye(3)])


#: (3, 8): ``t @ _TRANSLATOR + _ONE`` is the translator T(t) = 1 − ½ e0 t.
_TRANSLATOR = _translator_matrix()


# ---------------------------------------------------------------------------- the group


def _multiply(a, b, names) -> np.ndarray:
    batch = Batch((a, names[0], (8,)), (b, names[1], (8,)))
    out = batch.empty(8)
    ok = L.multiply_loop(batch.flat[0], batch.steps[0], batch.flat[1], batch.steps[1], out)
    fail(batch, ok, out, what="product")
    return batch.shaped(out)


def compose(*motors) -> np.ndarray:
    """The geometric product M₁ M₂ ⋯ Mₙ: apply Mₙ first, M₁ last (like quaternion products).

    Broadcasts over leading axes. Any even multivectors are accepted: the product of unit
    motors is a unit motor, and nothing is normalised here.

    Parameters
    ----------
    *motors : array_like, shape (..., 8)
        At least one.

    Examples
    --------
    >>> T = from_translation([0.0, 0.0, 2.0])
    >>> compose(T, T)                                  # translations add
    array([ 1.,  0.,  0., -2.,  0.,  0.,  0.,  0.])
    >>> compose([T, T], T).shape
    (2, 8)
    """
    if not motors:
        raise InputError("expected at least one motor", key="motors")
    if len(motors) == 1:
        return as_float_array(motors[0], "motors[0]", last=8).copy()
    out = _multiply(motors[0], motors[1], ("motors[0]", "motors[1]"))
    for n, m in enumerate(motors[2:], start=2):
        out = _multiply(out, m, (f"motors[:{n}]", f"motors[{n}]"))
    return out


def reverse(M) -> np.ndarray:
    """M̃: the bivector coefficients change sign. For a unit motor, the inverse motion.

    Examples
    --------
    >>> reverse([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0])
    array([ 1., -2., -3., -4., -5., -6., -7.,  8.])
    """
    return as_float_array(M, "M", last=8) * _REVERSE


def _unit(M, name: str = "M") -> np.ndarray:
    """The unit motors of M (renormalised within UNIT_TOLERANCE), or InputError naming ``name``.

    Examples
    --------
    >>> _unit([1.0 + 1e-9, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    array([1., 0., 0., 0., 0., 0., 0., 0.])
    >>> _unit([2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: M: expected unit motors (M M̃ = 1 to within 1e-06, relative), ...
    """
    batch = Batch((M, name, (8,)))
    out = batch.empty(8)
    fail(batch, L.unit_loop(batch.flat[0], out, UNIT_TOLERANCE), out, motors=(name,))
    return batch.shaped(out)


def inverse(M) -> np.ndarray:
    """M⁻¹ = M̃ of a unit motor (checked and renormalised first).

    Examples
    --------
    >>> M = from_pose([0.0, 0.0, 0.0, 1.0], [1.0, 2.0, 3.0])
    >>> compose(M, inverse(M)).round(15) + 0.0
    array([1., 0., 0., 0., 0., 0., 0., 0.])
    """
    return _unit(M) * _REVERSE


def normalize(M) -> np.ndarray:
    """The unit motor of an even multivector M whose rotor part R = (1, e12, e13, e23) ≠ 0.

    M M̃ = |R|² + 2 s e0123 for some s (e0123 is central and squares to zero); the result is
    M (1 − s/|R|² e0123)/|R|, whose M M̃ is exactly 1: the rotor part scaled to unit norm
    and the translation part made to satisfy the Study condition. A motor that drifted
    off unit norm in a long computation comes back to the nearest rigid motion.

    Raises
    ------
    InputError
        For a zero rotor part (a pure ideal element is not a motion).

    Examples
    --------
    >>> normalize([2.0, -2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])   # twice a translator
    array([ 1., -1.,  0.,  0.,  0.,  0.,  0.,  0.])
    >>> normalize([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5])    # the Study part removed
    array([1., 0., 0., 0., 0., 0., 0., 0.])
    """
    batch = Batch((M, "M", (8,)))
    out = batch.empty(8)
    ok = L.normalize_loop(batch.flat[0], out)
    if not ok and np.isfinite(batch.flat[0]).all():
        zero = ~np.any(batch.flat[0][:, [0, 4, 5, 6]] != 0.0, axis=1)
        if np.any(zero):
            where = np.unravel_index(int(np.argmax(zero)), batch.shape)
            raise InputError(
                "expected a nonzero rotor part (1, e12, e13, e23), got zero at index "
                f"{tuple(int(i) for i in where)}",
                key="M",
            )
    fail(batch, ok, out, what="normalised motor")
    return batch.shaped(out)


def exp(B) -> np.ndarray:
    """exp(B) of bivectors B (..., 6): the motor of the screw motion that B generates.

    With B = −½(α L + h e0 u) for a unit line L of direction u, exp(B) turns by α about L
    and slides by h along it (:func:`from_screw`); exp(−½ e0 t) is the translator by t,
    exp(−½ α I₃u) (no e0 part) the rotor of the rotation by α about u through the origin.
    Closed form (dual numbers, :mod:`ga_rotors.motor._screw`): exact at B = 0 and for
    translations, accurate at tiny angles.

    Examples
    --------
    >>> exp([0.0, 0.0, 0.0, 0.0, 0.0, 0.0]) + 0.0
    array([1., 0., 0., 0., 0., 0., 0., 0.])
    >>> to_translation(exp([-0.5, 0.0, 0.0, 0.0, 0.0, 0.0])) + 0.0     # −½ e0 x: by x
    array([1., 0., 0.])
    """
    batch = Batch((B, "B", (6,)))
    out = batch.empty(8)
    fail(batch, L.exp_loop(batch.flat[0], out), out, what="exponential")
    return batch.shaped(out)


def log(M) -> np.ndarray:
    """The bivector B (..., 6) with exp(B) = M for unit motors M (principal logarithm).

    The angle θ = atan2(|R⃗|, R₀) of the rotor part R is in [0, π], so the screw's rotation
    angle 2θ is in [0, 2π]: M and −M (the same motion) have different logs; pass M with a
    non-negative scalar part for the shortest screw (:func:`to_screw` does). Exact at
    M = 1, for translators and at half-turns; at a rotor part of exactly −1 (M = −T) the
    axis is taken along the translation (the z axis when there is none).

    Examples
    --------
    >>> log(from_translation([0.0, 3.0, 0.0]))       # −½ e0 t
    array([ 0. , -1.5,  0. ,  0. ,  0. ,  0. ])
    >>> M = from_pose([0.0, 0.6, 0.8, 0.0], [1.0, 2.0, 3.0])            # a half-turn
    >>> bool(np.allclose(exp(log(M)), M, rtol=0, atol=1e-15))
    True
    """
    batch = Batch((M, "M", (8,)))
    out = batch.empty(6)
    fail(batch, L.log_loop(batch.flat[0], out, UNIT_TOLERANCE), out, motors=("M",), what="log")
    return batch.shaped(out)


# ------------------------------------------------------------------ poses and rotations


def from_pose(q, position) -> np.ndarray:
    """The motor T(t) R(q) of a body at ``position`` t with orientation q (rotate, then shift).

    A body point with body coordinates x is then in space at t + q x q*.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternions (w, x, y, z), body to space (renormalised within UNIT_TOLERANCE).
    position : array_like, shape (..., 3)
        Translations t (where the body origin is).

    Examples
    --------
    >>> M = from_pose([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)], [0.0, 0.0, 5.0])
    >>> M.round(12) + 0.0
    array([ 0.70710678,  0.        ,  0.        , -1.76776695, -0.70710678,
            0.        ,  0.        ,  1.76776695])
    """
    batch = Batch((q, "q", 4), (position, "position", 3))
    out = batch.empty(8)
    f, s = batch.flat, batch.steps
    ok = L.from_pose_loop(f[0], s[0], f[1], s[1], out, UNIT_TOLERANCE)
    fail(batch, ok, out, unit=("q",))
    return batch.shaped(out)


def to_pose(M) -> tuple[np.ndarray, np.ndarray]:
    """(q, t) of unit motors M = T(t) R(q): the unit quaternion (..., 4) and translation (..., 3).

    q keeps the sign of M's scalar part (M and −M give q and −q, the same rotation).

    Examples
    --------
    >>> q, t = to_pose(from_pose([0.0, 1.0, 0.0, 0.0], [1.0, 2.0, 3.0]))
    >>> q, t
    (array([0., 1., 0., 0.]), array([1., 2., 3.]))
    """
    batch = Batch((M, "M", (8,)))
    out = batch.empty(7)
    fail(batch, L.to_pose_loop(batch.flat[0], out, UNIT_TOLERANCE), out, motors=("M",))
    out = batch.shaped(out)
    return out[..., :4], out[..., 4:]


def from_translation(t) -> np.ndarray:
    """The translator T(t) = 1 − ½ e0 t (e0 t = t₁e01 + t₂e02 + t₃e03), which moves points by +t.

    Examples
    --------
    >>> from_translation([2.0, 0.0, 0.0])
    array([ 1., -1.,  0.,  0.,  0.,  0.,  0.,  0.])
    """
    return as_float_array(t, "t", last=3) @ _TRANSLATOR + _ONE


def to_translation(M) -> np.ndarray:
    """The translation t (..., 3) of unit motors M = T(t) R (where M takes the origin).

    Examples
    --------
    >>> to_translation(from_pose([0.0, 0.0, 1.0, 0.0], [4.0, 5.0, 6.0]))
    array([4., 5., 6.])
    """
    return to_pose(M)[1]


def from_quaternion(q) -> np.ndarray:
    """The motor of the rotation q about the origin: its rotor w − x e23 − y e31 − z e12.

    Examples
    --------
    >>> from_quaternion([0.0, 0.0, 0.0, 1.0])           # k ↦ −e12
    array([ 0.,  0.,  0.,  0., -1.,  0.,  0.,  0.])
    """
    return from_pose(q, np.zeros(3))


def to_quaternion(M) -> np.ndarray:
    """The unit quaternion (..., 4) of the rotation part of unit motors M.

    Examples
    --------
    >>> to_quaternion(from_pose([0.6, 0.8, 0.0, 0.0], [1.0, 1.0, 1.0]))
    array([0.6, 0.8, 0. , 0. ])
    """
    return to_pose(M)[0]


def from_matrix(H) -> np.ndarray:
    """The motor of homogeneous matrices H (..., 4, 4) = [[R, t], [0, 1]].

    The rotation block must be a rotation within
    :data:`ga_rotors.matrix.ORTHONORMAL_TOLERANCE` (converted exactly at half-turns) and
    the last row (0, 0, 0, 1) within the same tolerance.

    Examples
    --------
    >>> H = np.diag([-1.0, -1.0, 1.0, 1.0])          # half-turn about z
    >>> H[:3, 3] = [1.0, 2.0, 3.0]
    >>> to_pose(from_matrix(H))
    (array([0., 0., 0., 1.]), array([1., 2., 3.]))
    """
    a = as_float_array(H, "H")
    if a.ndim < 2 or a.shape[-2:] != (4, 4):
        raise InputError(f"expected an array of shape (..., 4, 4), got shape {a.shape}", key="H")
    last = np.abs(a[..., 3, :] - [0.0, 0.0, 0.0, 1.0]).max(axis=-1)
    bad = ~(last <= ORTHONORMAL_TOLERANCE)
    if np.any(bad):
        where = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        raise InputError(
            f"expected the last row (0, 0, 0, 1) of a rigid motion, got {a[where][3].tolist()} "
            f"at index {where}",
            key="H",
        )
    check_rotation_matrix(a[..., :3, :3], "H[..., :3, :3]")
    return from_pose(_matrix_quaternion(a[..., :3, :3]), a[..., :3, 3])


def to_matrix(M) -> np.ndarray:
    """Homogeneous matrices (..., 4, 4) of unit motors: H @ (x, 1) = (M's image of x, 1).

    Examples
    --------
    >>> to_matrix(from_translation([1.0, 2.0, 3.0])) + 0.0
    array([[1., 0., 0., 1.],
           [0., 1., 0., 2.],
           [0., 0., 1., 3.],
           [0., 0., 0., 1.]])
    """
    q, t = to_pose(M)
    out = np.zeros((*t.shape[:-1], 4, 4))
    out[..., :3, :3] = Q.to_matrix(q)
    out[..., :3, 3] = t
    out[..., 3, 3] = 1.0
    return out


def from_dual_quaternion(dq) -> np.ndarray:
    """The motor of unit dual quaternions dq = (q_r, q_d) (..., 8), each part (w, x, y, z).

    The usual dual quaternion of the pose (q, t) is q_r = q, q_d = ½ t q; it is the motor
    R(q_r) − e0123 R(q_d), with R the rotor isomorphism (scipy's
    ``RigidTransform.as_dual_quat(scalar_first=True)`` gives the same 8 numbers).

    Examples
    --------
    >>> from_dual_quaternion([1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0])   # t = x
    array([ 1. , -0.5,  0. ,  0. ,  0. ,  0. ,  0. ,  0. ])
    """
    a = as_float_array(dq, "dq", last=8)
    return _unit((a * _DUAL_SIGNS) @ DUAL.T, "dq")


def to_dual_quaternion(M) -> np.ndarray:
    """The unit dual quaternions (q_r, q_d) (..., 8) of unit motors: the inverse of
    :func:`from_dual_quaternion`.

    Examples
    --------
    >>> to_dual_quaternion(from_translation([0.0, 0.0, 2.0]))
    array([ 1.,  0.,  0.,  0., -0.,  0.,  0.,  1.])
    """
    return (_unit(M) @ DUAL) * _DUAL_SIGNS


#: The dual part changes sign between ga_rotors' d (M = R(r) + e0123 R(d)) and q_d = ½ t q.
_DUAL_SIGNS = np.array([1.0, 1.0, 1.0, 1.0, -1.0, -1.0, -1.0, -1.0])


# ---------------------------------------------------------------------------- screws


def _bivector_parts(B) -> tuple[np.ndarray, np.ndarray]:
    """The vectors (a, b) of bivectors B = R((0, a)) + e0123 R((0, b)) (..., 6)."""
    m = np.concatenate([np.zeros((*B.shape[:-1], 1)), B, np.zeros((*B.shape[:-1], 1))], axis=-1)
    rd = m @ DUAL
    return rd[..., 1:4], rd[..., 5:8]


def _bivector(a, b) -> np.ndarray:
    zero = np.zeros((*a.shape[:-1], 1))
    return (np.concatenate([zero, a, zero, b], axis=-1) @ DUAL.T)[..., 1:7]


def from_screw(axis, angle, pitch=0.0) -> np.ndarray:
    """The screw motion: turn by ``angle`` about the line ``axis``, slide ``pitch·angle`` along it.

    Chasles: every rigid motion is one. The motor is exp(−½(α L + h e0 u)) with L the unit
    line of direction u, α the angle and h = pitch·α the slide. An infinite pitch is a pure
    translation along the axis direction by ``angle`` (a distance then; −inf slides the
    other way), as in Lynch & Park, *Modern Robotics* §3.3.

    Parameters
    ----------
    axis : array_like, shape (..., 6)
        Lines (e01, e02, e03, e12, e13, e23), for instance from
        :func:`ga_rotors.motor.line`; normalised here. Ideal lines (no direction) are refused.
    angle : array_like, shape (...)
        Rotation angle (rad), right-handed about the line's direction.
    pitch : array_like, shape (...)
        Slide per radian of turn, along the line's direction; 0 for a pure rotation.

    Examples
    --------
    >>> z_axis = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]         # the z axis through the origin
    >>> q, t = to_pose(from_screw(z_axis, np.pi, 1.0 / np.pi))   # half-turn, slide 1
    >>> q.round(15) + 0.0, t.round(15) + 0.0
    (array([0., 0., 0., 1.]), array([0., 0., 1.]))
    >>> to_translation(from_screw(z_axis, 2.5, np.inf))
    array([0. , 0. , 2.5])
    """
    L_ = as_float_array(axis, "axis", last=6)
    alpha = as_float_array(angle, "angle")
    h = as_float_array(pitch, "pitch", finite=False)
    if np.isnan(h).any():
        raise InputError("expected numbers or ±inf, got NaN", key="pitch")
    shape = leading_shape((L_, "axis", 1), (alpha, "angle", 0), (h, "pitch", 0))
    point, u = line_parts(L_, "axis")
    moment = np.cross(point, u)
    finite = np.isfinite(h)
    slide = np.where(finite, h, 0.0) * alpha
    a = np.where(finite[..., None], 0.5 * alpha[..., None] * u, 0.0)
    b = np.where(
        finite[..., None],
        -0.5 * (alpha[..., None] * moment + slide[..., None] * u),
        -0.5 * (np.sign(h) * alpha)[..., None] * u,
    )
    return exp(np.broadcast_to(_bivector(a, b), (*shape, 6)))


def to_screw(M) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The screw (axis line (..., 6), angle (...) ∈ [0, π], pitch (...)) of unit motors M.

    The inverse of :func:`from_screw` (Chasles' theorem): M and −M give the same screw.
    A pure translation by t ≠ 0 has the axis through the origin along t, angle |t| and
    pitch +inf; the identity has the z axis, angle 0 and pitch 0. At a half-turn (angle π)
    both directions of the axis describe the motion; the one from the rotor's bivector
    is returned.

    Examples
    --------
    >>> axis, angle, pitch = to_screw(from_translation([0.0, 3.0, 0.0]))   # along y
    >>> axis, angle, pitch
    (array([ 0.,  0.,  0.,  0., -1.,  0.]), 3.0, inf)
    """
    m = _unit(M)
    m = m * np.where(m[..., :1] < 0.0, -1.0, 1.0)
    a, b = _bivector_parts(log(m))
    theta = norm3(a)
    turning = theta > 0.0
    safe = np.where(turning, theta, 1.0)
    u_turn = a / safe[..., None]
    slide = -2.0 * np.einsum("...i,...i->...", b, u_turn)
    perp = b + 0.5 * slide[..., None] * u_turn
    # Pure translations: b = −t/2, the axis along t (z when t = 0).
    tnorm = 2.0 * norm3(b)
    along = -2.0 * b / np.where(tnorm > 0, tnorm, 1.0)[..., None]
    u_shift = np.where((tnorm > 0.0)[..., None], along, [0.0, 0.0, 1.0])
    u = np.where(turning[..., None], u_turn, u_shift)
    moment = np.where(turning[..., None], -perp / safe[..., None], 0.0)
    angle = np.where(turning, 2.0 * theta, tnorm)
    pitch = np.where(turning, slide / np.where(turning, 2.0 * theta, 1.0),
                     np.where(tnorm > 0.0, np.inf, 0.0))  # fmt: skip
    axis = _bivector(-u, moment)  # a line's direction d is the rotor bivector of −d
    if angle.ndim == 0:
        return axis, float(angle), float(pitch)
    return axis, angle, pitch


# ------------------------------------------------------------------------- velocities


def velocity_line(angular_velocity, velocity) -> np.ndarray:
    """The velocity bivector B = −I₃ω − e0 v (..., 6) of angular velocity ω and velocity v.

    With ω and v in the body frame (v the velocity of the body origin, expressed in the
    body axes) the motion obeys Ṁ = ½ M B, the rotor equation Ṙ = ½ R Ω (Ω = −I₃ω) with
    the translation added; for a constant B it is M(t) = M(0) exp(t B / 2). Seen from
    space, the same B is M B M̃. B is a line when ω·v = 0 (a pure rotation about it);
    otherwise a screw: its axis is the instantaneous screw axis.

    Examples
    --------
    >>> B = velocity_line([0.0, 0.0, 1.0], [1.0, 0.0, 0.0])     # turn about z, move along x
    >>> B + 0.0
    array([-1.,  0.,  0., -1.,  0.,  0.])
    >>> velocities(B)
    (array([0., 0., 1.]), array([1., 0., 0.]))
    """
    w = as_float_array(angular_velocity, "angular_velocity", last=3)
    v = as_float_array(velocity, "velocity", last=3)
    shape = (*leading_shape((w, "angular_velocity", 1), (v, "velocity", 1)), 3)
    return _bivector(np.broadcast_to(w, shape), -np.broadcast_to(v, shape))


def velocities(B) -> tuple[np.ndarray, np.ndarray]:
    """(ω, v) of velocity bivectors B (..., 6): the inverse of :func:`velocity_line`.

    Examples
    --------
    >>> velocities(log(from_translation([0.0, 2.0, 0.0])) * 2.0)   # unit time to (0, 2, 0)
    (array([0., 0., 0.]), array([0., 2., 0.]))
    """
    a, b = _bivector_parts(as_float_array(B, "B", last=6))
    return a + 0.0, 0.0 - b
