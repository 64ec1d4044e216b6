r"""Energy and momenta of a body moving through space, and the balances a run must keep.

For a whole rigid motion (:func:`ga_rotors.simulate` with ``position=``) under declared
forces and torques, the laws of mechanics say how the energy and the momenta change:

.. math::

    \frac{d}{dt}\Bigl(T + \sum V\Bigr) = \sum_\text{other} (F\cdot v_c + \tau_c\cdot\omega),
    \qquad \frac{dP}{dt} = \sum F, \qquad
    \frac{dL_a}{dt} = \sum \bigl((c - a) \times F + \tau_c\bigr),

with T the kinetic energy :math:`\tfrac12 m |v_c|^2 + \tfrac12 \omega\cdot\mathsf{I}_c\omega`,
V the potentials of the forces that declare one (``ForceTerm.potential``), P = m v_c and
:math:`L_a = q\,\mathsf{I}_c\omega\,q^* + (c - a) \times P` the angular momentum about the
space point a. :func:`balances` measures each law along a trajectory: the change of the
quantity less the integral of its source, which the exact motion keeps at zero. Where the
declared terms conserve the quantity (``ForceTerm.conserves``, :func:`conserved`) the
source is zero and the row is a conservation law, exact; otherwise the source is
integrated over the samples by Simpson's rule (scipy's ``cumulative_simpson``), whose own
error, of order Δ⁴ in the sample spacing Δ, is part of the residual (sample every step for
a tight check).

The angular momentum is taken about the point the forces conserve it about (a spring's
anchor), else about the origin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .body import RigidBody
from .errors import InputError
from .integrators.problem import ForceTerm, TorqueTerm
from .trajectory import Trajectory

__all__ = ["Balance", "angular_momentum", "balances", "conserved", "energy", "linear_momentum"]


@dataclass(frozen=True)
class Balance:
    """One law along a run: ``residual`` (n,) is |change − integral of its source| (a vector
    law by its norm), ``scale`` the size it is measured against (the quantity's largest
    magnitude and its source's integral), ``conserved`` whether the source is zero.

    Examples
    --------
    >>> b = Balance("energy", "total energy", np.array([0.0, 1e-12]), 2.0, True)
    >>> print(b)
    total energy: conserved to 5e-13 (relative to 2 J)
    """

    name: str
    label: str
    residual: np.ndarray
    scale: float
    conserved: bool

    @property
    def relative(self) -> float:
        """The largest residual over the scale."""
        worst = float(np.max(self.residual)) if self.residual.size else 0.0
        return worst / self.scale if self.scale > 0 else worst

    def __str__(self) -> str:
        how = "conserved to" if self.conserved else "balanced to"
        unit = {"energy": "J", "linear_momentum": "kg m/s"}.get(self.name, "kg m^2/s")
        return f"{self.label}: {how} {self.relative:.3g} (relative to {self.scale:.3g} {unit})"


def conserved(forces=(), torques=()) -> dict:
    """What a body under these forces and torques keeps: ``{"energy": bool,
    "linear_momentum": bool, "spin": bool, "angular_momentum": point or None}``.

    A quantity is kept when every term keeps it (a torque keeps the linear momentum and
    nothing else here); the angular momentum about a point when every force keeps it about
    the same point (or, with forces through the centre of mass only and no torque, which
    keep the spin and exert no force, about any point: the origin).

    Examples
    --------
    >>> from ga_rotors import forces as F
    >>> body = RigidBody((1.0, 2.0, 2.5), mass=1.0)
    >>> conserved([F.uniform_gravity(body)])
    {'energy': True, 'linear_momentum': False, 'spin': True, 'angular_momentum': None}
    >>> conserved([F.spring(body, 2.0, [0.0, 0.0, 1.0], at=(0.1, 0.0, 0.0))])
    {'energy': True, 'linear_momentum': False, 'spin': False, 'angular_momentum': (0.0, 0.0, 1.0)}
    >>> conserved()["angular_momentum"]
    (0.0, 0.0, 0.0)
    """
    forces, torques = tuple(forces), tuple(torques)
    out = {
        "energy": not torques and all("energy" in f.conserves for f in forces),
        "linear_momentum": not forces,
        "spin": not torques and all("spin" in f.conserves for f in forces),
        "angular_momentum": None,
    }
    points = {f.point if "angular_momentum" in f.conserves else None for f in forces}
    if not forces and not torques:
        out["angular_momentum"] = (0.0, 0.0, 0.0)
    elif not torques and len(points) == 1 and None not in points:
        out["angular_momentum"] = points.pop()
    return out


class _State:
    """The centre-of-mass state of a motion trajectory's primary path, both frames."""

    def __init__(self, trajectory: Trajectory, body: RigidBody):
        if not isinstance(body, RigidBody) or body.mass is None:
            raise InputError("expected the RigidBody that moved, with its mass", key="body")
        if "velocity" not in trajectory:
            raise InputError("expected the trajectory of a body moving through space "
                             "(simulate with position=)", key="trajectory")  # fmt: skip
        from . import quaternion as Q

        n = trajectory.w.shape[0]
        self.t = trajectory.t[:n]
        self.q = Q.normalize(trajectory.quaternions()[:n])  # the user's body frame
        self.w = trajectory.w
        lever = Q.rotate(self.q, np.asarray(body.centre_of_mass))
        self.c = trajectory.positions()[:n] + lever
        self.w_space = Q.rotate(self.q, self.w)
        self.vc = trajectory.velocities()[:n] + np.cross(self.w_space, lever)
        self.spin = body.space_momentum(self.q, self.w)
        self.kinetic = 0.5 * body.mass * np.einsum("ij,ij->i", self.vc, self.vc) + np.atleast_1d(
            body.energy(self.w)
        )
        # the principal frame the kernels read
        turn = np.asarray(body.principal_rotation)
        self.q_principal = Q.multiply(self.q, turn)
        self.w_principal = Q.rotate(Q.conjugate(turn), self.w)
        self.body = body


def _state(trajectory, body) -> _State:
    return trajectory if isinstance(trajectory, _State) else _State(trajectory, body)


def energy(trajectory: Trajectory, body: RigidBody, forces=()) -> np.ndarray:
    """The total energy (n,) in J: kinetic (translation and rotation) plus the potentials
    of the ``forces`` that declare one.

    Examples
    --------
    >>> from ga_rotors import simulate, forces as F
    >>> body = RigidBody((1.0, 1.0, 1.0), mass=2.0)
    >>> weight = F.uniform_gravity(body, g=(0.0, 0.0, -10.0))
    >>> tr = simulate(body, [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=1.0, step=0.1,
    ...               velocity=[0.0, 0.0, 10.0], forces=[weight])
    >>> energy(tr, body, [weight])[[0, -1]].round(9).tolist()     # ½ m v² + ½ I ω², kept
    [100.5, 100.5]
    """
    s = _state(trajectory, body)
    out = s.kinetic.copy()
    for f in forces:
        if f.potential is not None and "energy" in f.conserves:
            p = np.asarray(f.params, dtype=np.float64)
            out += np.array([f.potential(tuple(q), tuple(c), p)
                             for q, c in zip(s.q_principal, s.c, strict=True)])  # fmt: skip
    return out


def linear_momentum(trajectory: Trajectory, body: RigidBody) -> np.ndarray:
    """P = m v_c (n, 3), kg m/s, in space.

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> body = RigidBody((1.0, 1.0, 1.0), mass=2.0, centre_of_mass=(1.0, 0.0, 0.0))
    >>> tr = simulate(body, [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=1.0, step=0.5,
    ...               velocity=[0.0, -1.0, 0.0])     # the origin circles the resting centre
    >>> linear_momentum(tr, body).round(12).tolist()[0]
    [0.0, 0.0, 0.0]
    """
    s = _state(trajectory, body)
    return body.mass * s.vc


def angular_momentum(trajectory: Trajectory, body: RigidBody, about=(0.0, 0.0, 0.0)):
    """L_a = q I_c ω q* + (c − a) × m v_c (n, 3), kg m²/s, about the space point ``about``.

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> body = RigidBody((1.0, 1.0, 1.0), mass=2.0)
    >>> tr = simulate(body, [1.0, 0, 0, 0], [0.0, 0.0, 0.0], duration=1.0, step=0.5,
    ...               position=[1.0, 0.0, 0.0], velocity=[0.0, 3.0, 0.0])
    >>> angular_momentum(tr, body)[-1].round(12).tolist()      # r × m v, constant
    [0.0, 0.0, 6.0]
    """
    s = _state(trajectory, body)
    a = np.asarray(about, dtype=np.float64)
    return s.spin + np.cross(s.c - a, body.mass * s.vc)


def _sources(s: _State, forces, torques):
    """Per sample: the total force (space), the torque about the centre of mass (space),
    and the power of the terms without a potential."""
    from . import quaternion as Q

    n = s.t.shape[0]
    force, torque, power = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n)
    for term in (*forces, *torques):
        p = np.asarray(term.params, dtype=np.float64)
        rows = np.empty((n, 6))
        for i in range(n):
            q, w = tuple(s.q_principal[i]), tuple(s.w_principal[i])
            if isinstance(term, ForceTerm):
                rows[i] = term.kernel(s.t[i], q, tuple(s.c[i]), w, tuple(s.vc[i]), p)
            else:
                rows[i, :3], rows[i, 3:] = 0.0, term.kernel(s.t[i], q, w, p)
        tau = Q.rotate(s.q_principal, rows[:, 3:])
        force += rows[:, :3]
        torque += tau
        if not (isinstance(term, ForceTerm) and "energy" in term.conserves):
            power += np.einsum("ij,ij->i", rows[:, :3], s.vc)
            power += np.einsum("ij,ij->i", tau, s.w_space)
    return force, torque, power


def _integral(t, values):
    """∫₀ᵗ values dt at every sample: Simpson's rule (scipy), exact for cubics."""
    from scipy.integrate import cumulative_simpson

    if t.shape[0] < 2:
        return np.zeros_like(values)
    return cumulative_simpson(values, x=t, axis=0, initial=0.0)


def balances(trajectory: Trajectory, body: RigidBody, forces=(), torques=()) -> list[Balance]:
    """The energy, linear momentum and angular momentum balances along ``trajectory``
    (its primary path), for the ``forces`` (:class:`~ga_rotors.integrators.ForceTerm`)
    and ``torques`` (:class:`~ga_rotors.integrators.TorqueTerm`) it was simulated with
    (see the module's text).

    Returns
    -------
    list of Balance
        ``energy``, ``linear_momentum``, ``angular_momentum`` (about the conserving point,
        or the origin), and ``spin`` (the angular momentum about the centre of mass)
        when the terms conserve it.

    Examples
    --------
    A racket thrown under gravity with its frame at the handle: energy and spin kept to
    the integrator's error, the linear momentum changed by m g t, the angular momentum
    about the origin by ∫ c × m g dt.

    >>> from ga_rotors import simulate, forces as F
    >>> body = RigidBody((0.011, 0.023, 0.031), mass=0.31, centre_of_mass=(0.0, 0.15, 0.0))
    >>> weight = F.uniform_gravity(body)
    >>> tr = simulate(body, [1.0, 0, 0, 0], [0.05, 12.0, 0.1], duration=1.0, step=1e-3,
    ...               position=[0.0, 0.0, 1.5], velocity=[3.0, 0.0, 5.0], forces=[weight])
    >>> for row in balances(tr, body, [weight]):
    ...     print(row.name, row.conserved, row.relative < 1e-9)
    energy True True
    linear_momentum False True
    angular_momentum False True
    spin True True
    """
    forces, torques = tuple(forces), tuple(torques)
    for term in forces:
        if not isinstance(term, ForceTerm):
            raise InputError(f"expected ForceTerm items, got {term!r:.60}", key="forces")
    for term in torques:
        if not isinstance(term, TorqueTerm):
            raise InputError(f"expected TorqueTerm items, got {term!r:.60}", key="torques")
    s = _state(trajectory, body)
    keeps = conserved(forces, torques)
    force, torque, power = _sources(s, forces, torques)
    rows = []

    e = energy(s, body, forces)
    work = np.zeros_like(e) if keeps["energy"] else _integral(s.t, power)
    scale = float(np.max(np.abs(e)) + np.max(np.abs(work)))
    rows.append(Balance("energy", "total energy", np.abs(e - e[0] - work), scale,
                        keeps["energy"]))  # fmt: skip

    p = linear_momentum(s, body)
    impulse = _integral(s.t, force)
    scale = float(np.max(np.linalg.norm(p, axis=1)) + np.max(np.linalg.norm(impulse, axis=1)))
    rows.append(Balance("linear_momentum", "linear momentum",
                        np.linalg.norm(p - p[0] - impulse, axis=1), scale,
                        keeps["linear_momentum"]))  # fmt: skip

    about = keeps["angular_momentum"]
    point = np.zeros(3) if about is None else np.asarray(about)
    L = angular_momentum(s, body, point)
    moment = _integral(s.t, np.cross(s.c - point, force) + torque)
    scale = float(np.max(np.linalg.norm(L, axis=1)) + np.max(np.linalg.norm(moment, axis=1)))
    where = "the origin" if about is None else f"({', '.join(f'{x:g}' for x in point)})"
    rows.append(Balance("angular_momentum", f"angular momentum about {where}",
                        np.linalg.norm(L - L[0] - moment, axis=1), scale,
                        about is not None))  # fmt: skip

    if keeps["spin"]:
        spin = s.spin
        scale = float(np.max(np.linalg.norm(spin, axis=1)))
        rows.append(Balance("spin", "angular momentum about the centre of mass",
                            np.linalg.norm(spin - spin[0], axis=1), scale, True))  # fmt: skip
    return rows
