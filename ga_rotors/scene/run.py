"""Run a scene: integrate exactly what it declares, add only the quantities it asks for.

:func:`run_scene` builds the scene's torques (its declared effects, nothing else), runs
:func:`ga_rotors.simulate.simulate` on the scene's paths and returns the
:class:`~ga_rotors.trajectory.Trajectory`, with ``output.quantities`` added. Quantities
that nobody listed are not computed. :func:`exact_solution` gives the exact reference
that applies to the scene (``Scene.exact``), in the scene's own time and space frame.

Examples
--------
>>> from ga_rotors.scene import load_scene
>>> scene = load_scene("heavy_top").replace({"time.duration": 0.1})
>>> scene.data["output"]["quantities"]
['angles', 'total_energy', 'error']
>>> run_scene(scene).names
('t', 'w', 'R', 'q', 'angles', 'total_energy', 'error_R', 'error_q')
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..trajectory import Trajectory
from .loading import load_scene
from .model import Scene

__all__ = ["Exact", "exact_solution", "gravity_terms", "run_scene"]


def gravity_terms(scene: Scene) -> tuple[np.ndarray, np.ndarray] | None:
    """(weight m g in space, r = pivot -> centre of mass in the integration frame), or None.

    Examples
    --------
    >>> weight, r = gravity_terms(load_scene("heavy_top"))
    >>> weight.tolist(), r.tolist()
    ([0.0, 0.0, -9.80665], [0.0, 0.0, 0.04])
    """
    if scene.gravity_index is None:
        return None
    g = scene.data["effects"][scene.gravity_index]
    weight = scene.mass * np.array(g["g"])
    return weight, np.array(scene.frame.to_principal(g["pivot_to_com"]))


@dataclass
class Exact:
    """An exact solution in the scene's terms: absolute times, the scene's space frame.

    ``model`` is the reference object (times from the initial state, and for the heavy
    top a space frame with gravity along −z); ``frame`` is G, the rotation taking the
    scene's space frame to the model's (None: the same).

    Examples
    --------
    >>> scene = load_scene("spinning_disk")
    >>> exact = exact_solution(scene)
    >>> exact.name, exact.frame, exact.has_orientation
    ('symmetric_top', None, True)
    >>> exact.orientation_error([0.0], scene.orientation)  # the initial state itself
    array([0.])
    >>> exact_solution(load_scene("heavy_top")).frame  # gravity already along −z
    array([1., 0., 0., 0.])
    """

    name: str
    model: object
    t0: float
    frame: np.ndarray | None = None
    has_orientation: bool = True

    def angular_velocity(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=np.float64) - self.t0
        if hasattr(self.model, "angular_velocity"):
            return self.model.angular_velocity(t)
        return self.model.at(t)[1]

    def orientations(self, t) -> np.ndarray:
        from .. import quaternion as Q

        q = self.model.at(np.asarray(t, dtype=np.float64) - self.t0)[0]
        return q if self.frame is None else Q.multiply(Q.conjugate(self.frame), q)

    def orientation_error(self, t, q) -> np.ndarray:
        from ..quaternion import distance

        return np.atleast_1d(distance(self.orientations(t), q))


def exact_solution(scene: Scene) -> Exact | None:
    """The exact solution of ``scene`` (see ``Scene.exact``), or None.

    Raises InputError (from the reference) when the state is outside its domain, e.g. a
    heavy top whose symmetry axis starts vertical.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> exact_solution(load_scene("spinning_disk")).name
    'symmetric_top'
    """
    q0, w0, t0 = scene.orientation, scene.angular_velocity, scene.data["time"]["start"]
    if scene.exact == "symmetric_top":
        from ..reference.symmetric_top import SymmetricTop

        return Exact("symmetric_top", SymmetricTop(scene.body, q0, w0), t0)
    if scene.exact == "asymmetric_top":
        from ..reference.asymmetric_top import AsymmetricTop

        return Exact("asymmetric_top", AsymmetricTop(scene.body, q0, w0), t0)
    if scene.exact == "heavy_top":
        from .. import quaternion as Q
        from ..reference.heavy_top import HeavyTop

        weight, r = gravity_terms(scene)
        down = np.array([0.0, 0.0, -1.0])
        frame = Q.from_two_vectors(weight, down)
        mgl = float(np.linalg.norm(weight) * r[2])
        model = HeavyTop(scene.body, mgl, Q.multiply(frame, q0), w0)
        return Exact("heavy_top", model, t0, frame)
    if scene.exact == "damped_symmetric_top":
        from ..reference.damped_top import DampedSymmetricTop

        c = scene.data["effects"][0]["coefficient"]
        model = DampedSymmetricTop(scene.body, c, q0, w0)
        return Exact("damped_symmetric_top", model, t0, has_orientation=model.spherical)
    return None


def _integrator(scene: Scene):
    """The registered method's name, or for an adaptive one an instance at the tolerance."""
    from ..integrators import base

    spec = scene.data["integrator"]
    if "tolerance" not in spec:
        return spec["method"]
    method = base.get(spec["method"])
    return method if method.rtol == spec["tolerance"] else type(method)(rtol=spec["tolerance"])


def _user_compile_error(scene: Scene, exc: Exception):
    from ..errors import SceneError

    users = [i for i, e in enumerate(scene.data["effects"]) if e["type"] == "user"]
    first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    key = f"effects[{users[0]}].function" if len(users) == 1 else "effects"
    return SceneError(
        scene.file, key, f"numba could not compile the loop with the user torque: {first}"
    )


def run_scene(scene, *, progress=None) -> Trajectory:
    """Integrate a scene (a :class:`Scene`, a file path or a bundled scene's name).

    Parameters
    ----------
    scene : Scene or str or path
    progress : callable, optional
        ``progress(done, total)`` in steps (all paths), called as the loops advance.

    Returns
    -------
    Trajectory
        ``t``, ``w``, one array per path (``R``, ``q``, ``euler``) and the scene's
        ``output.quantities`` (``error`` becomes ``error_R``, ``error_q``,
        ``error_euler``); ``meta["scene"]`` is the scene's name.

    Examples
    --------
    >>> tr = run_scene("heavy_top")
    >>> tr.meta["torques"], tr.meta["problem"]
    (['gravity'], 'torqued')
    """
    from .. import simulate as _sim
    from ..crosscheck import orientations

    scene = load_scene(scene)
    torques = scene.torques()
    wanted = scene.data["output"]["quantities"]
    try:
        tr = _sim.simulate(
            scene.body,
            scene.orientation,
            scene.angular_velocity,
            duration=scene.data["time"]["duration"],
            step=scene.step,
            paths=scene.paths,
            integrator=_integrator(scene),
            torques=torques,
            accept_lower_order=scene.data["integrator"].get("accept_lower_order", False),
            euler_angles=scene.euler_angles,
            outputs=[name for name in wanted if name in _sim.OUTPUTS],
            sample_every=scene.sample_every,
            t0=scene.data["time"]["start"],
            progress=progress,
            step_limit_key=f"{scene.file}: integrator.step",
        )
    except Exception as exc:
        from numba.core.errors import NumbaError

        if isinstance(exc, NumbaError) and any(e["type"] == "user" for e in scene.data["effects"]):
            raise _user_compile_error(scene, exc) from None
        raise
    arrays = {name: tr[name] for name in tr.names}
    components = dict(tr.components)
    extra = [name for name in wanted if name not in _sim.OUTPUTS]
    if extra:
        primary = tr.meta["primary"]
        n = tr.w.shape[0]
        q = orientations(tr, primary)[:n]
        arrays_needed = _quantities(scene, tr, q, extra)
        for name, (values, labels) in arrays_needed.items():
            arrays[name] = values
            if labels:
                components[name] = labels
    meta = dict(tr.meta)
    meta.update(
        scene=scene.name,
        principal_rotation=scene.principal_rotation,
        exact=scene.exact,
    )
    return Trajectory(arrays, components, meta)


def _quantities(scene: Scene, tr: Trajectory, q: np.ndarray, names: list[str]) -> dict:
    """The scene-level quantities in ``names`` (and nothing else)."""
    from .. import quaternion as Q

    out: dict[str, tuple[np.ndarray, tuple[str, ...] | None]] = {}
    w, t = tr.w, tr.t[: tr.w.shape[0]]
    if "potential_energy" in names or "total_energy" in names:
        grav = gravity_terms(scene)
        if grav is None:
            potential = np.zeros(w.shape[0])
        else:
            weight, r = grav
            potential = -(Q.rotate(q, r) @ weight)
        if "potential_energy" in names:
            out["potential_energy"] = (potential, None)
        if "total_energy" in names:
            out["total_energy"] = (scene.body.energy(w) + potential, None)
    if "omega_space" in names:
        out["omega_space"] = (Q.rotate(q, w), ("x", "y", "z"))
    if "error" in names or "omega_error" in names:
        exact = exact_solution(scene)
        if "omega_error" in names:
            out["omega_error"] = (np.linalg.norm(w - exact.angular_velocity(t), axis=-1), None)
        if "error" in names:
            from .. import paths as _paths
            from ..crosscheck import orientations

            for path in scene.paths:
                array = _paths.get(path).array
                qp = Q.normalize(orientations(tr, path))  # the rotation; |q| drift aside
                out[f"error_{array}"] = (exact.orientation_error(tr.t[: qp.shape[0]], qp), None)
    return out
