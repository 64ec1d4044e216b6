"""The paper's runs: each body and initial nutation on the rotor, quaternion and Euler paths.

Each run integrates the rotor, quaternion and Euler-angle paths with RK4
(:mod:`ga_rotors.paper.models` holds the paper's numbers), compares rotor with quaternion
(round-off), every path with the exact symmetric-top solution
(:mod:`ga_rotors.reference.symmetric_top`), and records the Euler-angle path's trouble
near sin θ = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import euler
from ..crosscheck import PathComparison, cross_check
from ..kinematics import body_omega_from_zyz_rates, zyz_rates_from_body_omega
from ..reference.symmetric_top import SymmetricTop
from ..simulation import simulate
from ..trajectory import Trajectory
from .models import MODELS, RATES, STEP, STEPS, THETA0_DEG, Model

__all__ = ["PaperRun", "run_all", "run_case", "summary"]


@dataclass
class PaperRun:
    """One run's results.

    ``trajectory`` holds ``t``, ``w``, ``R`` (rotor path), ``q`` (quaternion path),
    ``euler`` (Euler-angle path), ``angles`` (ZYZ angles of the rotor path, ψ and φ
    unwrapped to continuous curves), ``psi_plus_phi`` (their sum, unwrapped as one angle),
    ``euler_rates`` (ψ̇, θ̇, φ̇ along the Euler-angle path)
    and ``error_R``, ``error_q``, ``error_euler`` (geodesic angle to the exact solution).

    Examples
    --------
    >>> s = run_case("paper", 0.001, steps=10)
    >>> s.key, s.trajectory.t.shape, sorted(s.max_error)
    ('paper_0.001deg', (11,), ['R', 'euler', 'q'])
    >>> s.rotor_vs_quaternion < 1e-13  # the same ODE in isomorphic algebras: round-off
    True
    """

    model: Model
    theta0_deg: float
    trajectory: Trajectory
    comparisons: list[PathComparison]
    max_error: dict[str, float]
    watch: dict
    norm_drift: float

    @property
    def key(self) -> str:
        return f"{self.model.name}_{self.theta0_deg:g}deg"

    @property
    def rotor_vs_quaternion(self) -> float:
        return next(c.max_angle for c in self.comparisons if c.paths == ("rotor", "quaternion"))


def run_case(model: str, theta0_deg: float, step: float = STEP, steps: int = STEPS) -> PaperRun:
    """Integrate one body and initial nutation on all three paths and measure it.

    Examples
    --------
    >>> s = run_case("disk", 15.0, steps=1000)
    >>> s.rotor_vs_quaternion < 1e-13, s.max_error["R"] < 1e-9
    (True, True)
    """
    body = MODELS[model]
    angles0 = np.array([0.0, np.radians(theta0_deg), 0.0])
    w0 = body_omega_from_zyz_rates(angles0, RATES)
    q0 = euler.to_quaternion("ZYZ", angles0)
    tr = simulate(
        body.moments,
        q0,
        w0,
        duration=step * steps,
        step=step,
        paths=("rotor", "quaternion", "euler"),
        euler_angles=angles0,
    )
    exact = SymmetricTop(body.moments, q0, w0)
    arrays = {name: tr[name] for name in tr.names}
    components = dict(tr.components)

    quats = {p: tr.quaternions(p) for p in ("rotor", "quaternion", "euler")}
    raw = euler.from_quaternion(quats["rotor"], "ZYZ")
    angles = raw.copy()
    angles[:, 0] = np.unwrap(raw[:, 0])
    angles[:, 2] = np.unwrap(raw[:, 2])
    arrays["angles"] = angles
    components["angles"] = ("psi", "theta", "phi")
    # ψ + φ is the one combination defined at θ = 0: unwrap the sum itself, not the terms.
    arrays["psi_plus_phi"] = np.unwrap(raw[:, 0] + raw[:, 2])
    valid = tr.euler.shape[0]
    arrays["euler_rates"] = zyz_rates_from_body_omega(tr.euler, tr.w[:valid])
    components["euler_rates"] = ("psi", "theta", "phi")

    max_error = {}
    for path, name in (("rotor", "R"), ("quaternion", "q"), ("euler", "euler")):
        n = quats[path].shape[0]
        err = exact.orientation_error(tr.t[:n], quats[path])
        arrays[f"error_{name}"] = err
        max_error[name] = float(err.max())

    euler_status = tr.meta["paths"]["euler"]
    meta = dict(tr.meta)
    meta.update(model=body.name, theta0_deg=theta0_deg, rates=RATES)
    return PaperRun(
        model=body,
        theta0_deg=theta0_deg,
        trajectory=Trajectory(arrays, components, meta),
        comparisons=cross_check(tr),
        max_error=max_error,
        watch={**euler_status["watch"], "complete": euler_status["complete"]},
        norm_drift=float(np.abs(np.linalg.norm(tr["rotor_blades"], axis=1) - 1.0).max()),
    )


def run_all(step: float = STEP, steps: int = STEPS) -> list[PaperRun]:
    """Both bodies, both initial nutations: paper θ₀ = 15°, 0.001°, then disk.

    ``ga-rotors paper`` runs them at the paper's 10,000 steps of 1 ms.

    Examples
    --------
    >>> [s.key for s in run_all(steps=10)]
    ['paper_15deg', 'paper_0.001deg', 'disk_15deg', 'disk_0.001deg']
    """
    return [run_case(m, th, step, steps) for m in MODELS for th in THETA0_DEG]


def summary(runs: list[PaperRun]) -> str:
    """The table ``ga-rotors paper`` prints.

    Examples
    --------
    >>> print(summary([run_case("paper", 15.0, steps=100)]).splitlines()[0])
    The paper's gyroscope: RK4, 100 steps of 1 ms, torque-free.
    """
    first = runs[0].trajectory.meta
    lines = [
        f"The paper's gyroscope: RK4, {first['steps']:,} steps of {first['step'] * 1e3:g} ms, "
        "torque-free.",
        "Max geodesic angle (rad): rotor vs quaternion path, and each path vs the exact "
        "symmetric-top solution.",
        "",
        f"{'scene':<16}{'rotor-quat':>12}{'rotor':>11}{'quaternion':>12}{'euler':>11}"
        f"{'| |R|-1 |':>11}   Euler-angle path near sin θ = 0",
    ]
    for s in runs:
        w = s.watch
        if w["unresolved_steps"]:
            trouble = (
                f"{w['unresolved_steps']} unresolved steps from t = {w['first_unresolved']:g} s, "
                f"min |sin θ| {w['min_abs_sin_theta']:.1e}, {w['pole_crossings']} pole crossings"
            )
        else:
            trouble = f"fine (min |sin θ| {w['min_abs_sin_theta']:.2f})"
        if not w["complete"]:
            trouble += "; stopped: state not finite"
        lines.append(
            f"{s.key:<16}{s.rotor_vs_quaternion:>12.1e}{s.max_error['R']:>11.1e}"
            f"{s.max_error['q']:>12.1e}{s.max_error['euler']:>11.1e}{s.norm_drift:>11.1e}   "
            f"{trouble}"
        )
    return "\n".join(lines)
