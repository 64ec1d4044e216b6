"""A scene whose body moves through space: which exact reference applies, and its errors.

A scene with ``initial.position``, ``initial.velocity`` or ``[[forces]]`` is a whole rigid
motion (:func:`ga_rotors.simulate` with ``position=``). Two of them have exact solutions
(:mod:`ga_rotors.reference.rigid_motion`):

* ``free_flight``: no torques, no force but uniform gravity (or none): the centre of mass
  on its parabola, the exact free rotation about it;
* ``spring_at_centre_of_mass``: one zero-length spring attached at the centre of mass
  (and uniform gravity, if any), no torques: a harmonic oscillator beside the free
  rotation.

Every other motion scene is measured by the balances of energy and momenta
(:mod:`ga_rotors.balances`), which its summary states instead.

Examples
--------
>>> from ga_rotors.scene import load_scene
>>> applicable(load_scene("thrown_racket"))
('free_flight', 'no torques; uniform gravity only')
>>> applicable(load_scene("satellite_orbit"))[0] is None
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["EXACT", "MotionExact", "applicable", "build", "errors"]

#: exact motion references a scene can have -> the class in ga_rotors.reference
EXACT = ("free_flight", "spring_at_centre_of_mass")


def applicable(scene) -> tuple[str | None, str]:
    """(name, why) of the exact reference of a motion ``scene``, or (None, why not).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> scene = load_scene("thrown_racket").replace(
    ...     {"forces": [{"type": "linear_drag", "coefficient": 0.01}]})
    >>> applicable(scene)
    (None, 'linear_drag has no exact solution here; the balances measure the run')
    """
    data = scene.data
    forces = data.get("forces", [])
    if data["effects"]:
        return None, "torques have no exact solution for a moving body; the balances measure it"
    kinds = [f["type"] for f in forces]
    others = sorted({k for k in kinds if k not in ("uniform_gravity", "spring")})
    if others:
        return None, f"{', '.join(others)} has no exact solution here; the balances measure the run"
    springs = [f for f in forces if f["type"] == "spring"]
    if not springs:
        return "free_flight", "no torques; " + ("uniform gravity only" if forces else "no forces")
    com = data["body"].get("centre_of_mass", [0.0, 0.0, 0.0])
    if len(springs) == 1 and springs[0]["rest_length"] == 0.0 and springs[0]["at"] == com:
        return "spring_at_centre_of_mass", "one zero-length spring at the centre of mass"
    return None, ("only one zero-length spring attached at the centre of mass has an exact "
                  "solution; the balances measure the run")  # fmt: skip


@dataclass(frozen=True)
class MotionExact:
    """The exact motion a scene is held to: ``reference`` (a FreeFlight or a
    SpringAtCentreOfMass in the scene's terms) under its ``name``
    (:attr:`ga_rotors.scene.Scene.exact_solution` of a motion scene).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> exact = load_scene("thrown_racket").exact_solution
    >>> exact.name, type(exact.reference).__name__, exact.bound([0.0, 1.0])
    ('free_flight', 'FreeFlight', None)
    """

    name: str
    reference: object

    has_orientation = True

    def bound(self, t) -> float | None:
        """No stated rounding bound: the closed forms are evaluated to rounding."""
        return None


def build(scene) -> MotionExact | None:
    """The exact reference of a motion ``scene``, or None (see :class:`MotionExact`).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> build(load_scene("thrown_racket")).name, build(load_scene("satellite_orbit"))
    ('free_flight', None)
    """
    reference = _reference(scene)
    return None if reference is None else MotionExact(scene.exact, reference)


def _reference(scene):
    from ..reference.rigid_motion import FreeFlight, SpringAtCentreOfMass

    name = scene.exact
    if name not in EXACT:
        return None
    forces = scene.data.get("forces", [])
    g = np.zeros(3)
    for f in forces:
        if f["type"] == "uniform_gravity":
            g = g + np.array(f["g"])
    common = (scene.orientation, scene.angular_velocity, scene.position, scene.velocity)
    com = scene.body.centre_of_mass
    if name == "free_flight":
        return FreeFlight(scene.body, scene.mass, *common, gravity=g, centre_of_mass=com)
    spring = next(f for f in forces if f["type"] == "spring")
    return SpringAtCentreOfMass(scene.body, scene.mass, spring["stiffness"], *common,
                                anchor=spring["anchor"], gravity=g,
                                centre_of_mass=com)  # fmt: skip


def errors(reference, t0: float, t, orientations: dict, positions: dict) -> dict:
    """Each path's largest errors against ``reference`` at the times ``t`` (from ``t0``):
    ``{path: (angle in rad, distance in m)}`` from the paths' unit ``orientations`` and
    body-origin ``positions`` (rows beyond a path's own are not compared).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene, run_scene
    >>> from ga_rotors import quaternion as Q
    >>> scene = load_scene("thrown_racket").replace({"time.duration": 0.1})
    >>> tr = run_scene(scene)
    >>> found = errors(build(scene).reference, 0.0, tr.t, {p: Q.normalize(tr.quaternions(p))
    ...                for p in tr.paths}, {p: tr.positions(p) for p in tr.paths})
    >>> all(a < 1e-9 and d < 1e-9 for a, d in found.values())
    True
    """
    from .. import quaternion as Q

    t = np.asarray(t, dtype=np.float64)
    if t.size == 0:
        return {}
    exact = reference.state(t - t0)
    out = {}
    for path, q in orientations.items():
        n = min(q.shape[0], positions[path].shape[0])
        if n == 0:
            continue
        angle = np.atleast_1d(Q.distance(q[:n], exact.q[:n]))
        miss = np.linalg.norm(positions[path][:n] - exact.position[:n], axis=1)
        out[path] = (float(angle.max()), float(miss.max()))
    return out
