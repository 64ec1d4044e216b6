r"""A rigid body: validated inertia, Euler's equations, energy and angular momentum.

Dynamics run in the principal frame, where the inertia tensor is diagonal. A body given
by a full symmetric tensor is diagonalised once; :attr:`RigidBody.principal_rotation` is
the unit quaternion P that takes principal axes to the frame the tensor was written in,
so an orientation q of the principal frame is q ⊗ P* for the user's body frame.
:meth:`RigidBody.to_principal` and :meth:`RigidBody.from_principal` carry a state
(orientation, body angular velocity) between the two frames; everything that solves the
motion (``simulate``, the exact references) works in the principal frame and answers in
the user's.

Euler's equations in the body (principal) frame, torque τ in that frame:

.. math::

    \mathsf{I} \dot\omega = (\mathsf{I} \omega) \times \omega + \tau,

written per component as
:math:`\dot\omega_1 = \frac{I_2 - I_3}{I_1} \omega_2 \omega_3 + \frac{\tau_1}{I_1}` (and cyclic);
the torque-free part is :func:`ga_rotors._kernels.free_euler_rates`, which torque-free loops
call alone (the compiled kernels take tuples and check nothing: the public, checked form is
:meth:`RigidBody.angular_acceleration`). The difference :math:`I_2 - I_3` is exactly zero
for a symmetric body, so ω₁ stays bit-for-bit constant in the torque-free symmetric top, as
the exact solution says.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from ._validate import as_float_array, require_unit
from .errors import InputError

__all__ = [
    "EQUAL_MOMENTS_ULPS",
    "FRAME_CHANGE_ULPS",
    "MIN_MOMENT_RATIO",
    "TRIANGLE_TOLERANCE",
    "RigidBody",
]

#: Relative slack allowed in the triangle inequality I₁ + I₂ ≥ I₃: a flat lamina sits
#: exactly on the boundary (I₃ = I₁ + I₂), and computing it from dimensions may land a few
#: ulps outside. Anything further out is not a physical body and is rejected.
TRIANGLE_TOLERANCE = 1e-12

#: Smallest accepted ratio I_min / I_max. Why a limit, and why this one: Euler's equations
#: use the coefficients (I_j − I_k)/I_i. For a real body the triangle inequality gives
#: |I_j − I_k| ≤ I_i, so every coefficient is at most 1 in size and the equations are never
#: stiff, however thin the body. The triangle check, though, allows a slack of
#: TRIANGLE_TOLERANCE·(I₁ + I₂ + I₃) ≤ 3·TRIANGLE_TOLERANCE·I_max, which exceeds I_min once
#: I_min/I_max < 3·TRIANGLE_TOLERANCE: below that, a body a few ulps outside the triangle
#: could have |(I_j − I_k)/I_i| of any size (I = (1, 1 + 2e-12, 1e-20) passed it with a
#: coefficient of 2e8: a stiff body no method here is built for). With I_min/I_max ≥
#: MIN_MOMENT_RATIO the coefficients stay within 1 + 3 = 4. It is also where float64 stops
#: carrying the thin axis: every moment is known to a relative u = 1.1e-16, so the
#: coefficient of the thin axis carries an absolute error of 2u·I_max/I_min (4.4e-4 at
#: the limit, one digit per decade further).
MIN_MOMENT_RATIO = TRIANGLE_TOLERANCE


def _check_moments(moments: np.ndarray, name: str) -> None:
    if np.any(moments <= 0):
        raise InputError(f"principal moments must be positive, got {tuple(moments)}", key=name)
    # Every loop divides by the moments (ω = L/I, τ/I): each I and 1/I must be a normal
    # float. A subnormal moment (1e-310) made 1/I overflow to inf with no error; a moment
    # above 1/DBL_MIN = 4.5e307 has a subnormal inverse that has lost its digits.
    tiny = np.finfo(float).tiny
    out = (moments < tiny) | (moments > 1.0 / tiny)
    if np.any(out):
        raise InputError(
            f"each principal moment and its inverse must be normal floats "
            f"({tiny:.3g} <= I <= {1.0 / tiny:.3g}), got {tuple(float(m) for m in moments)}; "
            "rescale the units",
            key=name,
        )
    ratio = moments.min() / moments.max()
    if ratio < MIN_MOMENT_RATIO:
        raise InputError(
            f"smallest/largest principal moment = {ratio:.3g} is below "
            f"{MIN_MOMENT_RATIO:g}: too thin a body for double precision (the triangle "
            "inequality can no longer be checked to the size of the smallest moment); "
            "treat the thin axis as having the moment I_max·1e-12 or more",
            key=name,
        )
    total = moments.sum()
    for k in range(3):
        if 2.0 * moments[k] > total * (1.0 + TRIANGLE_TOLERANCE):
            others = [moments[j] for j in range(3) if j != k]
            raise InputError(
                f"moments {tuple(float(m) for m in moments)} violate the triangle "
                f"inequality: I{k + 1} = {moments[k]:g} > {others[0]:g} + {others[1]:g}; "
                "no rigid body has this inertia",
                key=name,
            )


#: Eigenvalues of a diagonalised inertia tensor that differ by at most this many ulps of
#: the largest are one moment: a symmetric eigensolver's eigenvalues carry an error of a
#: few ulps of the norm (LAPACK's backward error bound, times n = 3 and a margin).
EQUAL_MOMENTS_ULPS = 32


#: Components of ω carried into the principal frame that are at most this many ulps of |ω|
#: are rounding of the frame change (each component of P* ω P carries a few) and set to 0.
FRAME_CHANGE_ULPS = 4


def _equal_within_rounding(values: np.ndarray) -> tuple[float, float, float]:
    """Sorted eigenvalues, with those within the eigensolver's rounding made equal."""
    out = [float(v) for v in values]
    tol = EQUAL_MOMENTS_ULPS * np.finfo(np.float64).eps * max(abs(v) for v in out)
    start = 0
    for k in range(1, 4):
        if k == 3 or out[k] - out[k - 1] > tol:
            group = out[start:k]
            out[start:k] = [sum(group) / len(group)] * len(group)
            start = k
    return tuple(out)


def _rotation_exactly(q) -> list[list]:
    """The rotation matrix of the float quaternion ``q`` in rational arithmetic: the
    formula of :func:`ga_rotors.matrix.from_quaternion` divided by |q|², so it is exactly
    orthogonal whatever q's rounding."""
    from fractions import Fraction

    w, x, y, z = (Fraction(float(c)) for c in q)
    n = w * w + x * x + y * y + z * z
    return [
        [(w * w + x * x - y * y - z * z) / n, 2 * (x * y - w * z) / n, 2 * (x * z + w * y) / n],
        [2 * (x * y + w * z) / n, (w * w - x * x + y * y - z * z) / n, 2 * (y * z - w * x) / n],
        [2 * (x * z - w * y) / n, 2 * (y * z + w * x) / n, (w * w - x * x - y * y + z * z) / n],
    ]


def _residual(tensor: np.ndarray, moments, p) -> float:
    """‖M(P) diag(I) M(P)ᵀ − ½(T + Tᵀ)‖_F, exactly, then rounded up: what the body of
    moments I and principal rotation P misses of the tensor T (the eigensolver's error,
    the conversion of its axes to P, the merging of equal moments)."""
    from fractions import Fraction

    m = _rotation_exactly(p)
    inertia = [Fraction(v) for v in moments]
    square = Fraction(0)
    for i in range(3):
        for j in range(3):
            given = (Fraction(float(tensor[i, j])) + Fraction(float(tensor[j, i]))) / 2
            made = sum(m[i][k] * inertia[k] * m[j][k] for k in range(3))
            square += (made - given) ** 2
    return float(np.nextafter(np.sqrt(float(square)) * (1.0 + 4.0 * _EPS), np.inf))


_EPS = float(np.finfo(np.float64).eps)


def _representable(values: np.ndarray, name: str, what: str) -> None:
    """InputError when ``values`` overflowed (the inputs were finite: as_float_array)."""
    if not np.all(np.isfinite(values)):
        raise InputError(
            f"{what} overflows float64 (beyond {np.finfo(float).max:.3g}); rescale the units",
            key=name,
        )


@dataclass(frozen=True)
class RigidBody:
    """Inertia of a rigid body, in its principal frame.

    Parameters
    ----------
    moments : array_like, shape (3,)
        Principal moments (I₁, I₂, I₃), positive, satisfying the triangle inequality.
    principal_rotation : array_like, shape (4,)
        Unit quaternion taking the principal frame to the body frame the user works in
        (identity by default; :meth:`from_tensor` sets it). Renormalised within
        ``UNIT_TOLERANCE``; otherwise :class:`~ga_rotors.errors.InputError`.
    mass : float, optional
        kg: what a body moving through space needs (:func:`ga_rotors.simulate` with
        ``position=``); a body that only turns about a fixed point has none.
    centre_of_mass : array_like, shape (3,)
        Where the centre of mass is in the body frame, from its origin (m; the origin by
        default). The moments are always about the centre of mass; the body frame's
        origin is any point of the body (the handle of a racket, a satellite's docking
        port), and the poses, positions and velocities of a whole motion are that
        origin's.

    Examples
    --------
    >>> body = RigidBody((1.0, 2.0, 3.0))
    >>> body.energy([1.0, 0.0, 1.0])
    2.0
    >>> RigidBody((1.0, 1.0, 3.0))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: moments: ... triangle inequality: I3 = 3 > 1 + 1; ...
    >>> RigidBody((1.0, 2.0, 3.0), mass=0.0)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: mass: expected a positive number of kg, got 0.0
    """

    moments: tuple[float, float, float]
    principal_rotation: tuple[float, float, float, float] = field(default=(1.0, 0.0, 0.0, 0.0))
    #: The symmetric tensor :meth:`from_tensor` diagonalised (None for a body given by
    #: its moments): what :attr:`tensor_residual` measures the body against.
    tensor: tuple | None = field(default=None, compare=False, repr=False)
    mass: float | None = None
    centre_of_mass: tuple[float, float, float] = field(default=(0.0, 0.0, 0.0))

    def __post_init__(self):
        m = as_float_array(self.moments, "moments", last=3)
        if m.shape != (3,):
            raise InputError(f"expected 3 principal moments, got shape {m.shape}", key="moments")
        _check_moments(m, "moments")
        object.__setattr__(self, "moments", tuple(float(x) for x in m))
        p = as_float_array(self.principal_rotation, "principal_rotation", last=4)
        if p.shape != (4,):
            raise InputError(
                f"expected one quaternion of shape (4,), got shape {p.shape}",
                key="principal_rotation",
            )
        p = require_unit(p, "principal_rotation")
        object.__setattr__(self, "principal_rotation", tuple(float(x) for x in p))
        if self.tensor is not None:
            t = as_float_array(self.tensor, "tensor")
            if t.shape != (3, 3):
                raise InputError(f"expected a 3x3 matrix, got shape {t.shape}", key="tensor")
            object.__setattr__(self, "tensor", tuple(tuple(float(v) for v in r) for r in t))
        if self.mass is not None:
            mass = as_float_array(self.mass, "mass")
            tiny = np.finfo(float).tiny
            if mass.shape != () or not tiny <= mass <= 1.0 / tiny:
                raise InputError(f"expected a positive number of kg, got {self.mass!r:.40}",
                                 key="mass")  # fmt: skip
            object.__setattr__(self, "mass", float(mass))
        s = as_float_array(self.centre_of_mass, "centre_of_mass", last=3)
        if s.shape != (3,):
            raise InputError(f"expected one vector of shape (3,), got shape {s.shape}",
                             key="centre_of_mass")  # fmt: skip
        if np.any(s != 0.0) and self.mass is None:
            raise InputError("a centre of mass off the body origin matters only to a body "
                             "moving through space: give its mass too",
                             key="centre_of_mass")  # fmt: skip
        object.__setattr__(self, "centre_of_mass", tuple(float(x) + 0.0 for x in s))

    @classmethod
    def from_tensor(cls, tensor, *, mass=None, centre_of_mass=(0.0, 0.0, 0.0)) -> RigidBody:
        """Diagonalise a symmetric positive-definite inertia tensor.

        Principal axes come out right-handed and sorted by increasing moment. Moments
        that differ by no more than the diagonalisation's own rounding
        (:data:`EQUAL_MOMENTS_ULPS` ulps of the largest) are made exactly equal: a tensor
        written in a turned frame has its equal moments come out a few ulps apart, and
        the body is symmetric all the same (:attr:`is_symmetric`, the closed forms of
        :mod:`ga_rotors.reference.symmetric_top`).

        Examples
        --------
        >>> c, s = np.cos(0.3), np.sin(0.3)
        >>> R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        >>> body = RigidBody.from_tensor(R @ np.diag([1.0, 2.0, 2.5]) @ R.T)
        >>> np.round(body.moments, 12)
        array([1. , 2. , 2.5])
        >>> R = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
        >>> RigidBody.from_tensor(R @ np.diag([1.5, 1.5, 2.0]) @ R.T).is_symmetric
        True
        """
        t = as_float_array(tensor, "inertia tensor")
        if t.shape != (3, 3):
            raise InputError(f"expected a 3x3 matrix, got shape {t.shape}", key="inertia tensor")
        scale = np.abs(t).max()
        if not np.allclose(t, t.T, rtol=0, atol=1e-12 * scale):
            raise InputError(
                "expected a symmetric matrix, got an asymmetric one", key="inertia tensor"
            )
        values, vectors = np.linalg.eigh(0.5 * (t + t.T))
        if values[0] <= 0:
            raise InputError(
                f"expected positive definite, got eigenvalues {tuple(values)}",
                key="inertia tensor",
            )
        if np.linalg.det(vectors) < 0:
            vectors[:, 2] *= -1.0
        from .matrix import to_quaternion  # the one matrix -> quaternion formula

        moments, p = _equal_within_rounding(values), tuple(to_quaternion(vectors))
        return cls(moments, p, tensor=tuple(tuple(float(v) for v in row) for row in t),
                   mass=mass, centre_of_mass=centre_of_mass)

    @functools.cached_property
    def tensor_residual(self) -> float:
        """How far the inertia this body stands for, M(P) diag(moments) M(P)ᵀ, is from
        the tensor it was diagonalised from (Frobenius norm, kg·m², computed exactly and
        rounded up; 0 for a body given by its moments). The body's moments are that
        tensor's eigenvalues to within it (Weyl), its principal axes that tensor's to
        within it over the gap between moments, in radians (Davis–Kahan): how much an
        answer that depends sensitively on them may be off (the asymmetric top next to
        its separatrix, :mod:`ga_rotors.reference.asymmetric_top`).

        Examples
        --------
        >>> c, s = np.cos(0.3), np.sin(0.3)
        >>> R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        >>> body = RigidBody.from_tensor(R @ np.diag([1.0, 2.0, 2.5]) @ R.T)
        >>> 0 < body.tensor_residual < 1e-14, RigidBody((1.0, 2.0, 2.5)).tensor_residual
        (True, 0.0)
        """
        if self.tensor is None:
            return 0.0
        return _residual(np.array(self.tensor), self.moments, self.principal_rotation)

    def to_principal_axes(self, v) -> tuple[float, float, float]:
        """Components of one vector in the user's body axes -> in the principal axes, P* v P.

        Examples
        --------
        >>> from ga_rotors import quaternion as Q
        >>> body = RigidBody((1.0, 2.0, 3.0), Q.from_axis_angle([0.0, 0.0, 1.0], 90, degrees=True))
        >>> [round(x, 15) + 0.0 for x in body.to_principal_axes([1.0, 0.0, 0.0])]
        [0.0, -1.0, 0.0]
        """
        v = as_float_array(v, "v", last=3)
        if v.shape != (3,):
            raise InputError(f"expected one vector of shape (3,), got shape {v.shape}", key="v")
        if self.is_principal:
            return tuple(float(x) for x in v)
        from .quaternion import conjugate, rotate

        return tuple(float(x) for x in rotate(conjugate(np.array(self.principal_rotation)), v))

    def body_point(self, r) -> tuple[float, float, float]:
        """A point of the body given in the user's body frame (from its origin, m) as the
        integration frame sees it: from the centre of mass, in principal axes.

        Examples
        --------
        >>> RigidBody((1.0, 2.0, 3.0), mass=1.0, centre_of_mass=(0.0, 0.5, 0.0)).body_point(
        ...     [0.0, 1.5, 0.0])
        (0.0, 1.0, 0.0)
        """
        r = as_float_array(r, "at", last=3)
        if r.shape != (3,):
            raise InputError(f"expected one vector of shape (3,), got shape {r.shape}", key="at")
        return self.to_principal_axes(r - np.array(self.centre_of_mass))

    @property
    def is_principal(self) -> bool:
        """True when the body frame is the principal frame (``principal_rotation`` = 1).

        Examples
        --------
        >>> RigidBody((1.0, 2.0, 3.0)).is_principal
        True
        """
        return self.principal_rotation == (1.0, 0.0, 0.0, 0.0)

    def to_principal(self, orientation, angular_velocity) -> tuple[np.ndarray, np.ndarray]:
        """A state of the user's body frame in the principal frame: (q ⊗ P, P* ω P).

        Parameters
        ----------
        orientation : array_like, shape (..., 4), or None
            Orientations of the user's body frame (body to space).
        angular_velocity : array_like, shape (..., 3), or None
            Body angular velocities in the user's body frame.

        Returns
        -------
        q, w : ndarray or None
            The same states for the principal frame (returned as given when
            :attr:`is_principal`, so that case is exact); None where None was given.
            Components of ``w`` within :data:`FRAME_CHANGE_ULPS` ulps of ``|w|`` (the
            rounding of the turn) are exactly 0, so ω given along a principal axis is
            exactly along it.

        Examples
        --------
        A body whose principal axes are the user's axes turned by 90° about z:

        >>> from ga_rotors import quaternion as Q
        >>> P = Q.from_axis_angle([0.0, 0.0, 1.0], 90, degrees=True)
        >>> body = RigidBody((1.0, 2.0, 3.0), P)
        >>> q, w = body.to_principal([1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
        >>> w.round(15).tolist()  # the user's x is the principal −y
        [0.0, -1.0, 0.0]
        >>> [a.round(15).tolist() for a in body.from_principal(q, w)]
        [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
        """
        return self._turn(orientation, angular_velocity, inverse=False)

    def from_principal(self, orientation, angular_velocity) -> tuple[np.ndarray, np.ndarray]:
        """A state of the principal frame in the user's body frame: (q ⊗ P*, P ω P*).

        The inverse of :meth:`to_principal`; see there for the parameters.

        Examples
        --------
        >>> from ga_rotors import quaternion as Q
        >>> body = RigidBody((1.0, 2.0, 3.0), Q.from_axis_angle([1.0, 1.0, 0.0], 0.5))
        >>> q, w = body.from_principal(*body.to_principal([0.0, 0.6, 0.0, 0.8], [1.0, 2.0, 3.0]))
        >>> bool(np.allclose(q, [0.0, 0.6, 0.0, 0.8])), bool(np.allclose(w, [1.0, 2.0, 3.0]))
        (True, True)
        """
        return self._turn(orientation, angular_velocity, inverse=True)

    def _turn(self, orientation, angular_velocity, inverse: bool):
        q = None if orientation is None else as_float_array(orientation, "orientation", last=4)
        w = None
        if angular_velocity is not None:
            w = as_float_array(angular_velocity, "angular_velocity", last=3)
        if self.is_principal:
            return q, w
        from .quaternion import conjugate, multiply, rotate

        p = np.array(self.principal_rotation)
        p_star = conjugate(p)
        if q is not None:
            q = multiply(q, p_star if inverse else p)
        if w is not None:
            w = rotate(p if inverse else p_star, w)
            if not inverse:
                # Components within the rotation's rounding of zero are zero: ω given along
                # a principal axis stays on it exactly (steady rotation, not a 1e-17 wobble).
                noise = FRAME_CHANGE_ULPS * np.finfo(np.float64).eps
                w = np.where(np.abs(w) <= noise * np.linalg.norm(w, axis=-1)[..., None], 0.0, w)
        return q, w

    @property
    def is_symmetric(self) -> bool:
        """True when two principal moments are equal (a symmetric top)."""
        i1, i2, i3 = self.moments
        return i1 == i2 or i2 == i3 or i1 == i3

    def energy(self, w) -> np.ndarray | float:
        r"""Kinetic energy :math:`\tfrac12 \omega^\mathsf{T} \mathsf{I} \omega` for body angular
        velocities ω of shape (..., 3).

        ω is in the user's body frame (as ``simulate`` returns it): for a body given by a
        turned tensor it is carried to the principal frame first, ½ Σ Iₖ ωₖ² there.
        Raises InputError when the energy is beyond float64 (never inf).

        Examples
        --------
        >>> from ga_rotors import quaternion as Q
        >>> body = RigidBody((1.0, 2.0, 3.0), Q.from_axis_angle([0.0, 0.0, 1.0], 0.5))
        >>> round(body.energy([1.0, 0.0, 0.0]), 12)  # ½ (cos² 0.5 · 1 + sin² 0.5 · 2)
        0.614924423533
        >>> RigidBody((1e300, 1e300, 1e300)).energy([1e10, 0.0, 0.0])
        Traceback (most recent call last):
        ...
        ga_rotors.errors.InputError: w: the kinetic energy overflows float64 ...
        """
        _, w = self.to_principal(None, as_float_array(w, "w", last=3))
        with np.errstate(over="ignore", under="ignore"):
            e = 0.5 * np.einsum("...i,i,...i->...", w, np.asarray(self.moments), w)
        _representable(e, "w", "the kinetic energy")
        return float(e) if e.ndim == 0 else e

    def momentum(self, w) -> np.ndarray:
        """Body-frame angular momentum L = I ω, shape (..., 3), in the frame of ``w``.

        Examples
        --------
        >>> RigidBody((1.0, 2.0, 3.0)).momentum([1.0, 1.0, 1.0]).tolist()
        [1.0, 2.0, 3.0]
        """
        _, w_p = self.to_principal(None, as_float_array(w, "w", last=3))
        with np.errstate(over="ignore"):
            L = w_p * np.asarray(self.moments)
        _representable(L, "w", "the angular momentum")
        return self.from_principal(None, L)[1]

    def angular_acceleration(self, w, torque=None) -> np.ndarray:
        r"""ω̇ from Euler's equations,
        :math:`\mathsf{I} \dot\omega = (\mathsf{I} \omega) \times \omega + \tau`, in the frame of
        ``w``.

        Parameters
        ----------
        w : array_like, shape (..., 3)
            Body angular velocity (rad/s) in the user's body frame.
        torque : array_like, shape (..., 3), optional
            Body-frame torque τ (N·m), same frame; none by default.

        Returns
        -------
        ndarray, shape (..., 3)
            ω̇ (rad/s²); InputError when it is beyond float64.

        Examples
        --------
        >>> body = RigidBody((1.0, 2.0, 3.0))
        >>> body.angular_acceleration([1.0, 1.0, 1.0])  # ((2-3)/1, (3-1)/2, (1-2)/3)
        array([-1.        ,  1.        , -0.33333333])
        >>> body.angular_acceleration([1.0, 1.0, 1.0], [1.0, 2.0, 3.0])
        array([0.        , 2.        , 0.66666667])
        """
        _, w = self.to_principal(None, as_float_array(w, "w", last=3))
        inertia = np.asarray(self.moments)
        with np.errstate(over="ignore", invalid="ignore"):
            a = np.cross(w * inertia, w) / inertia
            if torque is not None:
                _, tau = self.to_principal(None, as_float_array(torque, "torque", last=3))
                try:
                    a = a + tau / inertia
                except ValueError:
                    raise InputError(
                        f"shapes {w.shape} and {tau.shape} do not broadcast", key="w and torque"
                    ) from None
        _representable(a, "w", "the angular acceleration")
        return self.from_principal(None, a)[1]

    def space_momentum(self, q, w) -> np.ndarray:
        r"""Space-frame angular momentum :math:`L = q\, (\mathsf{I} \omega)\, q^*`: constant in
        torque-free motion.

        ``q`` and ``w`` are the user's body frame's orientation and angular velocity.

        Examples
        --------
        >>> RigidBody((1.0, 2.0, 3.0)).space_momentum([0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
        array([-1.,  0.,  0.])
        """
        from .quaternion import rotate

        return rotate(q, self.momentum(w))
