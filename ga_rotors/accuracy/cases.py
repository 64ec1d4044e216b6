"""The reference problems of the accuracy study: bodies, initial states, exact solutions.

Six cases span what a user meets: the paper's symmetric top, an asymmetric top far from
and next to its separatrix, a fast spinner, a heavy (Lagrange) top, and a racket thrown
through the air (rotation and translation, :class:`Flight`). Each carries its exact
reference (:mod:`ga_rotors.reference`), the range of step counts its sweep covers, and,
where the motion has one in closed form, the exact body ω(t) that kinematics-only peers
are given.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Case", "Flight", "cases"]


@dataclass(frozen=True)
class Flight:
    """What a case of a body moving through space adds: its mass, the centre of mass in
    the body frame (from the frame's origin), the origin's initial position and velocity
    in space, gravity, and the length its position errors are measured against (m).

    Examples
    --------
    >>> cases()["free_flight"].flight.length
    1.0
    """

    mass: float
    centre_of_mass: tuple[float, float, float]
    position: tuple[float, float, float]
    velocity: tuple[float, float, float]
    gravity: tuple[float, float, float]
    length: float


@dataclass(frozen=True)
class Case:
    """One reference problem.

    ``reference`` has ``at(t) -> (q, w)``; ``invariants(q, w) -> (energy, momentum)`` gives
    the energy and the conserved momentum vector (or component) for states (n, 4), (n, 3).
    ``body_rate(t)`` is the exact body ω at a scalar time (for the kinematics-only peer),
    or None; ``mgl`` is the heavy top's gravity parameter (None when torque-free): its
    torque is mgl · (Z_y, −Z_x, 0) in the body, Z = q* ẑ q (the space vertical).
    ``flight``: a body moving through space (:class:`Flight`); its runs integrate the
    whole motion on the quaternion path (the quaternion and the centre of mass), and its
    error is the larger of the angle (rad) and the body origin's distance from the exact
    one over ``flight.length`` (:meth:`errors`).

    Examples
    --------
    >>> case = cases()["asymmetric_far"]
    >>> case.problem.kind, cases()["heavy_top"].problem.kind
    ('free', 'torqued')
    >>> energy, momentum = case.invariants(case.q0, case.w0)
    >>> energy  # ½ Σ I_k ω_k² = ½ (1·1 + 2·0.25 + 3·0.04)
    array([0.81])
    """

    name: str
    title: str
    moments: tuple[float, float, float]
    q0: tuple[float, float, float, float]
    w0: tuple[float, float, float]
    duration: float
    reference: object
    mgl: float | None = None
    body_rate: Callable | None = None
    steps: tuple[int, int] = (16, 2**20)
    flight: Flight | None = None
    _final: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def problem(self):
        """The integrators' problem, built once per case (it keeps what runs derive)."""
        from ..integrators import Problem
        from ..reference.heavy_top import gravity_torque

        found = self._final.get("problem")
        if found is None and self.flight is not None:
            from ..body import RigidBody
            from ..forces import uniform_gravity

            f = self.flight
            body = RigidBody(self.moments, mass=f.mass, centre_of_mass=f.centre_of_mass)
            found = self._final["problem"] = Problem(
                self.moments, mass=f.mass, centre_of_mass=f.centre_of_mass,
                forces=(uniform_gravity(body, f.gravity),),
            )  # fmt: skip
        elif found is None:
            torques = () if self.mgl is None else (gravity_torque(self.mgl),)
            found = self._final["problem"] = Problem(self.moments, torques=torques)
        return found

    def start(self, path: str = "quaternion") -> tuple[np.ndarray, np.ndarray]:
        """The initial state and rates on ``path``: the orientation and ω, or for a flight
        the path's whole-motion state (:func:`ga_rotors.paths.resolve`).

        Examples
        --------
        >>> x0, w0 = cases()["free_flight"].start()
        >>> x0.shape, w0.shape
        ((7,), (6,))
        """
        if self.flight is None:
            return np.asarray(self.q0, dtype=np.float64), np.asarray(self.w0, dtype=np.float64)
        from ..paths import resolve

        f = self.flight
        module = resolve(path, moves=True).load()
        return module.initial_state(np.asarray(self.q0), f.position, self.w0, f.velocity,
                                    f.centre_of_mass)  # fmt: skip

    def errors(self, x, w) -> tuple[float, float, float]:
        """(error, energy drift, momentum drift) of a flight's run on the quaternion path,
        from its states x (n, 7) at the sample times and its final rates ``w[-1]``: the
        larger of the largest angle and of the largest distance over ``flight.length``;
        the drift of the total energy (kinetic plus −m g·c) and of the spin (the angular
        momentum about the centre of mass, in space), both relative to their start.

        Examples
        --------
        >>> case = cases()["free_flight"]
        >>> x0, w0 = case.start()
        >>> case.errors(np.array([x0] * 5), np.array([w0]))[1:]
        (0.0, 0.0)
        """
        from .. import quaternion as Q
        from ..paths import resolve

        f = self.flight
        module = resolve("quaternion", moves=True).load()
        x, w = np.asarray(x, dtype=np.float64), np.asarray(w, dtype=np.float64)
        times = np.linspace(0.0, self.duration, x.shape[0])
        exact = self._final.get(("flight", x.shape[0]))
        if exact is None:
            exact = self._final[("flight", x.shape[0])] = self.reference.state(times)
        q = Q.normalize(module.quaternions(x))
        angle = float(np.max(Q.distance(exact.q, q)))
        gap = np.linalg.norm(module.positions(x, f.centre_of_mass) - exact.position, axis=-1)
        error = max(angle, float(np.max(gap)) / f.length)
        x0, w0 = self.start()
        inertia = np.asarray(self.moments)

        def invariants(state, rates):
            energy = 0.5 * f.mass * rates[3:] @ rates[3:] + 0.5 * (rates[:3] ** 2) @ inertia
            energy -= f.mass * np.dot(f.gravity, state[4:])
            return energy, Q.rotate(Q.normalize(state[:4]), inertia * rates[:3])

        (e0, s0), (e1, s1) = invariants(x0, w0), invariants(x[-1], w[-1])
        drift = float(abs(e1 - e0) / abs(e0))
        return error, drift, float(np.linalg.norm(s1 - s0) / np.linalg.norm(s0))

    def exact_final(self) -> np.ndarray:
        """The exact orientation (w, x, y, z) at ``duration``, computed once per case."""
        found = self._final.get("q")
        if found is None:
            found = self._final["q"] = self.reference.at([self.duration])[0][0]
        return found

    def invariants(self, q, w):
        """(energy, conserved momentum) for states q (n, 4), w (n, 3)."""
        from .. import quaternion as Q

        inertia = np.asarray(self.moments)
        q = Q.normalize(np.atleast_2d(q))
        w = np.atleast_2d(w)
        ls = Q.rotate(q, w * inertia)
        energy = 0.5 * (w * w * inertia).sum(-1)
        if self.mgl is None:
            return energy, ls
        zz = q[:, 0] ** 2 - q[:, 1] ** 2 - q[:, 2] ** 2 + q[:, 3] ** 2
        return energy + self.mgl * zz, ls[:, 2:3]


def _asymmetric_rate(top) -> Callable:
    """Exact body ω(t) of an asymmetric top as a cheap scalar function (scipy's ellipj)."""
    from scipy.special import ellipj

    a, b, c = top._axes
    amp = top._amp
    rate, u0, m = top.rate, top._u0, top.m

    def body_rate(t):
        sn, cn, dn, _ = ellipj(rate * t + u0, m)
        w = [0.0, 0.0, 0.0]
        w[a], w[b], w[c] = amp[0] * dn, amp[1] * sn, amp[2] * cn
        return w

    return body_rate


def _symmetric_rate(moments, w0) -> Callable:
    """Body ω(t) of a torque-free symmetric top: the transverse part turns at −ν about e_k."""
    k = next(i for i in range(3) if moments[i] != moments[(i + 1) % 3] and
             moments[i] != moments[(i + 2) % 3])  # fmt: skip
    perp = moments[(k + 1) % 3]
    nu = (1.0 / moments[k] - 1.0 / perp) * moments[k] * w0[k]
    i, j = (k + 1) % 3, (k + 2) % 3

    def body_rate(t):
        c, s = math.cos(nu * t), math.sin(nu * t)
        w = [0.0, 0.0, 0.0]
        w[k] = w0[k]
        w[i] = c * w0[i] + s * w0[j]
        w[j] = -s * w0[i] + c * w0[j]
        return w

    return body_rate


def cases() -> dict[str, Case]:
    """The reference problems of the study.

    Examples
    --------
    >>> sorted(cases())
    ['asymmetric_far', 'asymmetric_near', 'fast_spinner', 'free_flight', 'heavy_top', 'symmetric']
    """
    from .. import euler, shapes
    from ..kinematics import body_omega_from_zyz_rates
    from ..reference.asymmetric_top import AsymmetricTop
    from ..reference.heavy_top import HeavyTop
    from ..reference.symmetric_top import SymmetricTop

    out = {}
    # The paper's 10 s run: uniform disk, θ₀ = 15°, rates (ψ̇, θ̇, φ̇) = (0.02, 0.02, 15.7).
    disk = shapes.disk(2.0, 0.075)
    angles = (0.0, math.radians(15.0), 0.0)
    q0 = tuple(float(x) for x in euler.to_quaternion("ZYZ", angles))
    w0 = tuple(float(x) for x in body_omega_from_zyz_rates(angles, (0.02, 0.02, 15.7)))
    out["symmetric"] = Case(
        "symmetric",
        "symmetric top: the paper's disk, 10 s",
        disk,
        q0,
        w0,
        10.0,
        SymmetricTop(disk, q0, w0),
        body_rate=_symmetric_rate(disk, w0),
    )
    tilt = (0.3, 0.1, 0.9, 0.2)
    tilt = tuple(x / math.sqrt(0.95) for x in tilt)
    far = AsymmetricTop((1.0, 2.0, 3.0), tilt, (1.0, 0.5, 0.2))
    out["asymmetric_far"] = Case(
        "asymmetric_far",
        "asymmetric top far from the separatrix (1 − m = 0.78), 20 s",
        (1.0, 2.0, 3.0), tilt, (1.0, 0.5, 0.2), 20.0, far, body_rate=_asymmetric_rate(far),
    )  # fmt: skip
    near_w = (1e-3, 2.0, 1e-3)
    near = AsymmetricTop((1.0, 2.0, 3.0), tilt, near_w)
    out["asymmetric_near"] = Case(
        "asymmetric_near",
        "asymmetric top 1e-3 off the middle axis (1 − m = 5e-7): two flips, 30 s",
        (1.0, 2.0, 3.0), tilt, near_w, 30.0, near, body_rate=_asymmetric_rate(near),
    )  # fmt: skip
    fast_i, fast_w = (1.0, 1.5, 2.0), (5.0, 3.0, 1000.0)
    fast = AsymmetricTop(fast_i, tilt, fast_w)
    out["fast_spinner"] = Case(
        "fast_spinner",
        "fast spinner: 1000 rad/s about the major axis with a wobble, 1 s",
        fast_i, tilt, fast_w, 1.0, fast, body_rate=_asymmetric_rate(fast), steps=(256, 2**21),
    )  # fmt: skip
    heavy_q = tuple(x / math.sqrt(0.81) for x in (0.6, 0.2, -0.5, 0.4))
    heavy = HeavyTop((1.0, 1.0, 0.3), 1.0, heavy_q, (1.0, -0.5, 3.0))
    out["heavy_top"] = Case(
        "heavy_top",
        "heavy top nutating past the horizontal (θ 68°–100°), 20 s",
        (1.0, 1.0, 0.3), heavy_q, (1.0, -0.5, 3.0), 20.0, heavy, mgl=1.0,
    )  # fmt: skip
    # A tennis racket thrown 5 m up and 3 m out, spun at 12 rad/s 0.5° off its middle axis
    # (it flips over once in flight), its frame at the end of the handle, 0.15 m from the
    # centre of mass: the orientation and the handle's path through the air.
    from ..forces import STANDARD_GRAVITY
    from ..reference.rigid_motion import FreeFlight

    racket, tilt_w = (0.011, 0.023, 0.031), (0.05, 12.0, 0.1)
    flight = Flight(0.31, (0.0, 0.15, 0.0), (0.0, 0.0, 1.5), (3.0, 0.0, 5.0),
                    (0.0, 0.0, -STANDARD_GRAVITY), 1.0)  # fmt: skip
    thrown = FreeFlight(racket, flight.mass, tilt, tilt_w, flight.position, flight.velocity,
                        gravity=flight.gravity, centre_of_mass=flight.centre_of_mass)  # fmt: skip
    out["free_flight"] = Case(
        "free_flight",
        "racket thrown through the air, spun near its middle axis (it turns over as it falls), "
        "frame at the handle, 1 s",
        racket, tilt, tilt_w, 1.0, thrown, body_rate=_asymmetric_rate(thrown.rotation),
        steps=(16, 2**18), flight=flight,
    )  # fmt: skip
    return out
