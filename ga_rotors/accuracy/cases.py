"""The reference problems of the accuracy study: bodies, initial states, exact solutions.

Five cases span what a user meets: the paper's symmetric top, an asymmetric top far from
and next to its separatrix, a fast spinner, and a heavy (Lagrange) top. Each carries its
exact reference (:mod:`ga_rotors.reference`), the range of step counts its sweep covers,
and, where the motion has one in closed form, the exact body ω(t) that kinematics-only
peers are given.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Case", "cases"]


@dataclass(frozen=True)
class Case:
    """One reference problem.

    ``reference`` has ``at(t) -> (q, w)``; ``invariants(q, w) -> (energy, momentum)`` gives
    the energy and the conserved momentum vector (or component) for states (n, 4), (n, 3).
    ``body_rate(t)`` is the exact body ω at a scalar time (for the kinematics-only peer),
    or None; ``mgl`` is the heavy top's gravity parameter (None when torque-free): its
    torque is mgl · (Z_y, −Z_x, 0) in the body, Z = q* ẑ q (the space vertical).

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
    _final: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def problem(self):
        """The integrators' problem, built once per case (it keeps what runs derive)."""
        from ..integrators import Problem
        from ..reference.heavy_top import gravity_torque

        found = self._final.get("problem")
        if found is None:
            torques = () if self.mgl is None else (gravity_torque(self.mgl),)
            found = self._final["problem"] = Problem(self.moments, torques=torques)
        return found

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
    ['asymmetric_far', 'asymmetric_near', 'fast_spinner', 'heavy_top', 'symmetric']
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
    return out
