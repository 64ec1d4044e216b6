"""Exact rigid motions: rotation and translation together, in closed form.

A force whose line passes through the centre of mass exerts no torque about it, so the
body turns exactly as the torque-free top (:mod:`ga_rotors.reference.symmetric_top`,
:mod:`ga_rotors.reference.asymmetric_top`, the body's inertia taken about its centre of
mass) while the centre of mass c moves by Newton's law alone:

* :class:`FreeFlight`, uniform gravity g: c(t) = c₀ + ċ₀ t + ½ g t² (the parabola);
* :class:`SpringAtCentreOfMass`, a spring of stiffness k and zero rest length from the
  centre of mass to a space anchor a, with uniform gravity g too:
  c(t) = e + (c₀ − e) cos Ωt + (ċ₀ / Ω) sin Ωt, Ω = √(k/m), e = a + m g / k
  (an isotropic harmonic oscillator about the equilibrium e).

The body frame need not have its origin at the centre of mass: ``centre_of_mass`` is the
fixed body vector s from the body origin to it. The body origin is then at
p(t) = c(t) − q(t) s q(t)* and moves at ṗ = ċ − ω_s × (q s q*), ω_s = q ω q* (the coupling
that motors carry). Positions and velocities, given and returned, are the body origin's,
in space; the pose (q, p) is also returned as the motor T(p) R(q)
(:func:`ga_rotors.motor.from_pose`).

Accuracy: the rotation is the top's (a few ulps of the angle turned, or its stated bound
for the asymmetric top); the translation adds a few ulps of |c|, |ċ t| and |g t²|.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

from .. import motor as _motor
from .. import quaternion as Q
from .._validate import as_float_array
from ..body import RigidBody
from ..errors import InputError
from .asymmetric_top import AsymmetricTop
from .symmetric_top import SymmetricTop

__all__ = ["FreeFlight", "MotionState", "SpringAtCentreOfMass"]

#: Standard gravity (m/s²) along −z, the default of :class:`FreeFlight`.
STANDARD_GRAVITY = (0.0, 0.0, -9.80665)


@dataclass(frozen=True)
class MotionState:
    """The exact state of a rigid body at some times.

    Attributes
    ----------
    q : ndarray, shape (n, 4)
        Orientation, body to space (unit quaternions, scalar first).
    w : ndarray, shape (n, 3)
        Body-frame angular velocity (rad/s).
    position : ndarray, shape (n, 3)
        Where the body origin is, in space.
    velocity : ndarray, shape (n, 3)
        The body origin's velocity, in space.
    centre_of_mass : ndarray, shape (n, 3)
        Where the centre of mass is, in space.

    Examples
    --------
    >>> flight = FreeFlight((1.0, 2.0, 2.0), 1.5, [1.0, 0, 0, 0], [0.0, 0.0, 3.0],
    ...                     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], gravity=(0.0, 0.0, -10.0))
    >>> s = flight.state([0.0, 1.0])
    >>> s.position[1].tolist()                       # 1 m along x, ½ g t² = 5 m down
    [1.0, 0.0, -5.0]
    """

    q: np.ndarray
    w: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    centre_of_mass: np.ndarray


def _vector(x, name: str) -> np.ndarray:
    v = as_float_array(x, name, last=3)
    if v.shape != (3,):
        raise InputError(f"expected one vector of shape (3,), got shape {v.shape}", key=name)
    return v


def _positive(x, name: str) -> float:
    v = as_float_array(x, name)
    if v.shape != () or not v > 0.0:
        raise InputError(f"expected one positive number, got {x!r:.40}", key=name)
    return float(v)


class _AboutCentreOfMass(ABC):
    """Free rotation about the centre of mass; the centre's path is the subclass's."""

    def __init__(self, body, mass, orientation, angular_velocity, position, velocity,
                 centre_of_mass):  # fmt: skip
        self.body = body if isinstance(body, RigidBody) else RigidBody(body)
        self.mass = _positive(mass, "mass")
        top = SymmetricTop if self.body.is_symmetric else AsymmetricTop
        self.rotation = top(self.body, orientation, angular_velocity)
        self.offset = _vector(centre_of_mass, "centre_of_mass")
        p0, v0 = _vector(position, "position"), _vector(velocity, "velocity")
        q0, w0 = np.asarray(self.rotation.q0), np.asarray(self.rotation.w0)
        lever = Q.rotate(q0, self.offset)
        #: The centre of mass and its velocity at t = 0, in space.
        self.c0 = p0 + lever
        self.cdot0 = v0 + np.cross(Q.rotate(q0, w0), lever)

    @abstractmethod
    def _centre(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The centre of mass and its velocity (n, 3) at times t (n,)."""

    def state(self, t) -> MotionState:
        """The exact state at times ``t`` (s, from the initial state), as a MotionState.

        Examples
        --------
        >>> spring = SpringAtCentreOfMass((1.0, 1.0, 1.0), 2.0, 8.0, [1.0, 0, 0, 0],
        ...                               [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0])
        >>> s = spring.state([0.0, np.pi / 2])       # Ω = 2 rad/s: half a period
        >>> s.position.round(15) + 0.0
        array([[ 1.,  0.,  0.],
               [-1.,  0.,  0.]])
        """
        t = np.atleast_1d(as_float_array(t, "t")).ravel()
        q, w = self.rotation.at(t)
        c, cdot = self._centre(t)
        lever = Q.rotate(q, self.offset)
        position = c - lever
        velocity = cdot - np.cross(Q.rotate(q, w), lever)
        return MotionState(q, w, position, velocity, c)

    def at(self, t) -> tuple[np.ndarray, np.ndarray]:
        """The poses (q (n, 4), position (n, 3)) of the body frame at times ``t``.

        Examples
        --------
        >>> flight = FreeFlight((1.0, 2.0, 3.0), 1.0, [1.0, 0, 0, 0], [0.0, 2.0, 0.0],
        ...                     [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], gravity=(0.0, 0.0, 0.0))
        >>> q, p = flight.at([0.0, 1.0])
        >>> Q.angle(q).tolist(), p.tolist()           # 2 rad about y, at rest
        ([0.0, 2.0], [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
        """
        s = self.state(t)
        return s.q, s.position

    def motors(self, t) -> np.ndarray:
        """The motors T(p) R(q) (n, 8) of the poses at times ``t`` (:mod:`ga_rotors.motor`).

        Examples
        --------
        >>> flight = FreeFlight((1.0, 2.0, 3.0), 1.0, [1.0, 0, 0, 0], [0.0, 0.0, 0.0],
        ...                     [0.0, 0.0, 0.0], [2.0, 0.0, 0.0], gravity=(0.0, 0.0, 0.0))
        >>> flight.motors([1.0])                      # translated by 2 along x
        array([[ 1., -1.,  0.,  0.,  0.,  0.,  0.,  0.]])
        """
        q, p = self.at(t)
        return _motor.from_pose(q, p)

    def momentum(self) -> np.ndarray:
        """The linear momentum m ċ at t = 0 (kg m/s), in space.

        Examples
        --------
        >>> FreeFlight((1.0, 1.0, 1.0), 2.0, [1.0, 0, 0, 0], [0.0, 0.0, 1.0],
        ...            [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]).momentum().tolist()
        [2.0, 0.0, 0.0]
        """
        return self.mass * self.cdot0


class FreeFlight(_AboutCentreOfMass):
    """A rigid body thrown in uniform gravity: the parabola of its centre of mass and the
    free rotation of the exact tops about it, for any body-frame origin.

    Parameters
    ----------
    body : RigidBody or array_like (3,)
        The inertia about the centre of mass (principal moments, or a RigidBody with its
        ``principal_rotation``), kg m².
    mass : float
        kg.
    orientation : array_like (4,)
        Initial orientation, body to space (unit quaternion, scalar first).
    angular_velocity : array_like (3,)
        Initial body-frame angular velocity, rad/s.
    position, velocity : array_like (3,)
        Initial position and velocity of the body origin, in space (m, m/s).
    gravity : array_like (3,)
        Uniform gravitational acceleration in space, m/s² (standard gravity along −z).
    centre_of_mass : array_like (3,)
        The centre of mass in body coordinates (from the body origin), m; 0 by default.

    Examples
    --------
    A body thrown with its origin 0.1 m from the centre of mass: the centre follows the
    parabola; the origin circles it as the body turns.

    >>> flight = FreeFlight((0.01, 0.02, 0.03), 0.3, [1.0, 0, 0, 0], [0.0, 0.0, 6.0],
    ...                     [0.0, 0.0, 0.0], [2.0, 0.0, 3.0], centre_of_mass=[0.1, 0.0, 0.0])
    >>> s = flight.state([0.0, 0.5])
    >>> s.centre_of_mass[1].round(6).tolist()        # c₀ + ċ₀ t + ½ g t², ċ₀ = v₀ + ω × s
    [1.1, 0.3, 0.274169]
    >>> np.linalg.norm(s.position - s.centre_of_mass, axis=1).round(15).tolist()
    [0.1, 0.1]
    """

    def __init__(self, body, mass, orientation, angular_velocity, position, velocity, *,
                 gravity=STANDARD_GRAVITY, centre_of_mass=(0.0, 0.0, 0.0)):  # fmt: skip
        super().__init__(body, mass, orientation, angular_velocity, position, velocity,
                         centre_of_mass)  # fmt: skip
        self.gravity = _vector(gravity, "gravity")

    def _centre(self, t):
        tt = t[:, None]
        c = self.c0 + self.cdot0 * tt + 0.5 * self.gravity * tt * tt
        return c, self.cdot0 + self.gravity * tt

    def energy(self) -> float:
        """The conserved total energy ½ m ċ² + ½ ω·Iω − m g·c (J).

        Examples
        --------
        >>> FreeFlight((1.0, 1.0, 1.0), 2.0, [1.0, 0, 0, 0], [0.0, 0.0, 1.0],
        ...            [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], gravity=(0.0, 0.0, -10.0)).energy()
        21.5
        """
        kinetic = 0.5 * self.mass * float(self.cdot0 @ self.cdot0)
        spin = self.body.energy(self.rotation.w0)
        return kinetic + spin - self.mass * float(self.gravity @ self.c0)


class SpringAtCentreOfMass(_AboutCentreOfMass):
    """A rigid body on a zero-length spring from its centre of mass to a space anchor:
    an isotropic harmonic oscillator of the centre, beside the free rotation about it.

    Parameters
    ----------
    body, mass, orientation, angular_velocity, position, velocity, centre_of_mass
        As for :class:`FreeFlight`.
    stiffness : float
        k, N/m (the force is −k (c − anchor)).
    anchor : array_like (3,)
        The spring's fixed end in space, m; the origin by default.
    gravity : array_like (3,)
        Uniform gravity too, m/s²; none by default (it only moves the equilibrium).

    Attributes
    ----------
    frequency : float
        Ω = √(k/m), rad/s.
    equilibrium : ndarray (3,)
        e = anchor + m g / k.

    Examples
    --------
    >>> spring = SpringAtCentreOfMass((1.0, 2.0, 3.0), 2.0, 8.0, [1.0, 0, 0, 0],
    ...                               [0.1, 0.0, 0.2], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0],
    ...                               anchor=[0.0, 0.0, 1.0])
    >>> spring.frequency
    2.0
    >>> spring.state([np.pi]).centre_of_mass.round(15).tolist()   # one full period
    [[1.0, 0.0, 0.0]]
    """

    def __init__(self, body, mass, stiffness, orientation, angular_velocity, position,
                 velocity, *, anchor=(0.0, 0.0, 0.0), gravity=(0.0, 0.0, 0.0),
                 centre_of_mass=(0.0, 0.0, 0.0)):  # fmt: skip
        super().__init__(body, mass, orientation, angular_velocity, position, velocity,
                         centre_of_mass)  # fmt: skip
        self.stiffness = _positive(stiffness, "stiffness")
        self.anchor = _vector(anchor, "anchor")
        self.gravity = _vector(gravity, "gravity")
        self.frequency = math.sqrt(self.stiffness / self.mass)
        self.equilibrium = self.anchor + self.mass * self.gravity / self.stiffness

    def _centre(self, t):
        phase = self.frequency * t[:, None]
        cos, sin = np.cos(phase), np.sin(phase)
        x0 = self.c0 - self.equilibrium
        c = self.equilibrium + x0 * cos + (self.cdot0 / self.frequency) * sin
        return c, self.cdot0 * cos - x0 * self.frequency * sin

    def energy(self) -> float:
        """The conserved total energy ½ m ċ² + ½ ω·Iω + ½ k |c − a|² − m g·c (J).

        Examples
        --------
        >>> SpringAtCentreOfMass((1.0, 1.0, 1.0), 2.0, 8.0, [1.0, 0, 0, 0], [0.0, 0.0, 0.0],
        ...                      [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]).energy()     # ½ k x²
        4.0
        """
        kinetic = 0.5 * self.mass * float(self.cdot0 @ self.cdot0)
        spin = self.body.energy(self.rotation.w0)
        stretch = self.c0 - self.anchor
        elastic = 0.5 * self.stiffness * float(stretch @ stretch)
        return kinetic + spin + elastic - self.mass * float(self.gravity @ self.c0)
