"""The paper's gyroscope: its two scenes, on its printed inertia and on a consistent disk.

The paper (../shared/seeds/000_…, RBEF 2016) integrates a torque-free "gyroscope" with RK4,
10,000 steps of Δt = 1 ms (printed "1.0×10³ s": the minus sign was lost), from
ψ = 0, ψ̇ = 0.02 rad/s, θ = 15° (Figs. 3–5) or 0.001° (Figs. 6–10), θ̇ = 0.02 rad/s, φ = 0,
φ̇ = 15.7 rad/s, with intrinsic z–y′–z″ angles (ψ precession, θ nutation, φ spin about z3).

Two bodies:

* ``paper``: the inertia of eq. (13) as printed, (0.0056, 0.0028, 0.0028) kg·m² on
  (x3, y3, z3). Its symmetry axis is x3, but the spin φ̇ = 15.7 rad/s is about z3: this
  body spins about a *diameter* of the disk, not about its symmetry axis.
* ``disk``: :func:`ga_rotors.shapes.disk` (m = 2 kg, R = 0.075 m), symmetry axis z3 with
  ½mR² = 0.005625 kg·m², so the spin φ is about the symmetry axis, as section 3 says.

Each scene integrates the rotor, quaternion and Euler-angle paths with RK4, compares rotor
with quaternion (round-off), every path with the exact symmetric-top solution
(:mod:`ga_rotors.reference.symmetric_top`), and records the Euler-angle path's trouble
near sin θ = 0.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np

from . import euler, shapes
from .crosscheck import PathComparison, cross_check
from .kinematics import body_omega_from_zyz_rates, zyz_rates_from_body_omega
from .reference.symmetric_top import SymmetricTop
from .simulate import simulate
from .trajectory import Trajectory

__all__ = [
    "DISK_MASS",
    "DISK_RADIUS",
    "MODELS",
    "RATES",
    "STEP",
    "STEPS",
    "THETA0_DEG",
    "Model",
    "Scene",
    "data_digest",
    "run_all",
    "run_scene",
    "summary",
]


@dataclass(frozen=True)
class Model:
    """A body for the paper's scenes.

    Examples
    --------
    >>> MODELS["disk"].moments  # ¼mR², ¼mR², ½mR² for m = 2 kg, R = 0.075 m
    (0.0028125, 0.0028125, 0.005625)
    >>> MODELS["paper"].label
    "paper's inertia: symmetry axis x3, spin about z3"
    """

    name: str
    moments: tuple[float, float, float]
    label: str


#: The paper's gyroscope disk: mass (kg) and radius (m).
DISK_MASS = 2.0
DISK_RADIUS = 0.075

MODELS = {
    "paper": Model(
        "paper",
        (0.0056, 0.0028, 0.0028),
        "paper's inertia: symmetry axis x3, spin about z3",
    ),
    "disk": Model(
        "disk",
        shapes.disk(DISK_MASS, DISK_RADIUS),
        "uniform disk: symmetry axis z3 = spin axis",
    ),
}

#: The paper's initial nutation angles (degrees): Figs. 3–5 and Figs. 6–10.
THETA0_DEG = (15.0, 0.001)
#: (ψ̇, θ̇, φ̇) at t = 0, rad/s.
RATES = (0.02, 0.02, 15.7)
STEP = 1e-3
STEPS = 10_000


@dataclass
class Scene:
    """One scene's results.

    ``trajectory`` holds ``t``, ``w``, ``R`` (rotor path), ``q`` (quaternion path),
    ``euler`` (Euler-angle path), ``angles`` (ZYZ angles of the rotor path, ψ and φ
    unwrapped to continuous curves), ``psi_plus_phi`` (their sum, unwrapped as one angle),
    ``euler_rates`` (ψ̇, θ̇, φ̇ along the Euler-angle path)
    and ``error_R``, ``error_q``, ``error_euler`` (geodesic angle to the exact solution).

    Examples
    --------
    >>> s = run_scene("paper", 0.001, steps=10)
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


def run_scene(model: str, theta0_deg: float, step: float = STEP, steps: int = STEPS) -> Scene:
    """Integrate one scene on all three paths and measure it.

    Examples
    --------
    >>> s = run_scene("disk", 15.0, steps=1000)
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
    return Scene(
        model=body,
        theta0_deg=theta0_deg,
        trajectory=Trajectory(arrays, components, meta),
        comparisons=cross_check(tr),
        max_error=max_error,
        watch={**euler_status["watch"], "complete": euler_status["complete"]},
        norm_drift=float(np.abs(np.linalg.norm(tr["rotor_blades"], axis=1) - 1.0).max()),
    )


def run_all(step: float = STEP, steps: int = STEPS) -> list[Scene]:
    """Both bodies, both initial nutations: paper θ₀ = 15°, 0.001°, then disk.

    ``ga-rotors paper`` runs them at the paper's 10,000 steps of 1 ms.

    Examples
    --------
    >>> [s.key for s in run_all(steps=10)]
    ['paper_15deg', 'paper_0.001deg', 'disk_15deg', 'disk_0.001deg']
    """
    return [run_scene(m, th, step, steps) for m in MODELS for th in THETA0_DEG]


def summary(scenes: list[Scene]) -> str:
    """The table ``ga-rotors paper`` prints.

    Examples
    --------
    >>> print(summary([run_scene("paper", 15.0, steps=100)]).splitlines()[0])
    The paper's gyroscope: RK4, 100 steps of 1 ms, torque-free.
    """
    first = scenes[0].trajectory.meta
    lines = [
        f"The paper's gyroscope: RK4, {first['steps']:,} steps of {first['step'] * 1e3:g} ms, "
        "torque-free.",
        "Max geodesic angle (rad): rotor vs quaternion path, and each path vs the exact "
        "symmetric-top solution.",
        "",
        f"{'scene':<16}{'rotor-quat':>12}{'rotor':>11}{'quaternion':>12}{'euler':>11}"
        f"{'| |R|-1 |':>11}   Euler-angle path near sin θ = 0",
    ]
    for s in scenes:
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


def _significant(a: np.ndarray, digits: int = 9) -> np.ndarray:
    """``a`` as integer mantissas of ``digits`` significant digits, with their exponents."""
    a = np.asarray(a, dtype=np.float64).ravel()
    with np.errstate(divide="ignore"):
        exponent = np.floor(np.log10(np.abs(a)))
    exponent = np.where(np.isfinite(exponent), exponent, 0.0)
    mantissa = np.round(a * 10.0 ** (digits - 1 - exponent))
    return np.concatenate([mantissa, exponent]).astype(np.int64)


def data_digest(scenes: list[Scene]) -> str:
    """A digest of the plotted data, rounded to 9 significant digits.

    Stored in each PNG's metadata, so a test can tell whether committed figures still
    show what the code computes, without comparing pixels across matplotlib versions.
    Rounding keeps the digest independent of last-bit differences between machines.

    Examples
    --------
    >>> s = [run_scene("disk", 15.0, steps=10)]
    >>> data_digest(s) == data_digest([run_scene("disk", 15.0, steps=10)])
    True
    """
    h = hashlib.sha256()
    for s in scenes:
        h.update(s.key.encode())
        for name in s.trajectory.names:
            h.update(name.encode())
            h.update(_significant(s.trajectory[name]).tobytes())
    return h.hexdigest()[:16]
