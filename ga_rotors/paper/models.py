"""The paper's gyroscope: its numbers (once) and the two bodies it is run on.

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

:mod:`ga_rotors.paper.runs` integrates them; the bundled scene files ``paper_15deg``,
``paper_0.001deg`` and ``spinning_disk`` are generated from these constants.
"""

from __future__ import annotations

from dataclasses import dataclass

from .. import shapes

__all__ = ["DISK_MASS", "DISK_RADIUS", "MODELS", "RATES", "STEP", "STEPS", "THETA0_DEG", "Model"]


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
