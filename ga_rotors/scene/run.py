"""Run a scene: integrate exactly what it declares, add only the quantities it asks for.

:func:`run_scene` builds the scene's torques (its declared effects, nothing else), runs
:func:`ga_rotors.simulation.simulate` on the scene's paths and returns the
:class:`~ga_rotors.trajectory.Trajectory`, with ``output.quantities`` added. Quantities
that nobody listed are not computed. Everything the scene implies (the integrator at its
tolerance, the gravity terms, the exact solution) comes from the :class:`Scene`, which
computed it once; the orientation comes from the trajectory, which converts it once.

Every array is in the scene's body frame (:attr:`Scene.body_frame`, recorded as
``meta["body_frame"]``): the scene's body, which carries its principal rotation, goes to
:func:`ga_rotors.simulation.simulate` with the initial state as the scene writes it, and
simulate integrates in the principal frame and answers in the body's.

Examples
--------
>>> from ga_rotors.scene import load_scene
>>> scene = load_scene("heavy_top").replace({"time.duration": 0.1})
>>> scene.data["output"]["quantities"]
['angles', 'total_energy', 'error']
>>> run_scene(scene).names
('t', 'w', 'rotor_blades', 'q', 'angles', 'total_energy', 'error_rotor', 'error_quaternion')
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from .._kernels import gravity_potential, kinetic_energy, qnormalize, qunit
from ..body import RigidBody
from ..trajectory import Trajectory
from .loading import load_scene
from .model import Scene

__all__ = ["run_pieces", "run_scene"]


def _user_compile_error(scene: Scene, exc: Exception):
    from ..errors import SceneError, first_line

    users = [
        f"{section}[{i}].function"
        for section in ("effects", "forces")
        for i, e in enumerate(scene.data.get(section, []))
        if e["type"] == "user"
    ]
    first = first_line(exc)
    key = users[0] if len(users) == 1 else "effects"
    return SceneError(
        scene.file, key, f"numba could not compile the loop with the user term: {first}"
    )


def run_scene(scene, *, progress=None, budget=None) -> Trajectory:
    """Integrate a scene (a :class:`Scene`, a file path or a bundled scene's name).

    Every sample stays in memory (the returned arrays); for a long run, stream it to
    files instead (:func:`ga_rotors.scene.stream_scene`, what ``ga-rotors run`` does).

    Parameters
    ----------
    scene : Scene or str or path
    progress : callable, optional
        ``progress(done, total)`` in steps (all paths), called as the loops advance.
    budget : ga_rotors.scene.budget.Budget, optional
        The most steps and memory the run may take (default
        :data:`ga_rotors.scene.budget.DEFAULT`); a scene beyond it is refused before it
        runs, with one line naming the key.

    Returns
    -------
    Trajectory
        ``t``, ``w``, one array per path (``rotor_blades``, ``q``, ``euler``; the
        orientation of any of them is ``quaternions(path)``) and the scene's
        ``output.quantities`` (``error`` becomes ``error_rotor``, ``error_quaternion``,
        ``error_euler``); ``meta["scene"]`` is the scene's name, ``meta["body_frame"]``
        the frame of every array (:attr:`Scene.body_frame`).

    Examples
    --------
    >>> tr = run_scene("heavy_top")
    >>> tr.meta["torques"], tr.meta["problem"]
    (['gravity'], 'torqued')
    """
    from . import budget as _budget

    scene = load_scene(scene)
    _budget.check(scene, _budget.DEFAULT if budget is None else budget)
    return next(_pieces(scene, None, progress))


def run_pieces(scene, *, chunk_steps: int | None = None, progress=None):
    """:func:`run_scene` as Trajectories of consecutive samples, about ``chunk_steps``
    steps each (default :data:`~ga_rotors.scene.budget.CHUNK_STEPS`;
    :func:`ga_rotors.simulation.simulate_chunks`), the scene's quantities computed per
    piece: joined, they are :func:`run_scene`'s arrays bit for bit, and memory holds one
    piece at a time. No budget is checked here (the caller's, who decides what is kept:
    :func:`ga_rotors.scene.stream_scene`).

    Examples
    --------
    >>> scene = load_scene("heavy_top").replace({"time.duration": 0.1})
    >>> pieces = list(run_pieces(scene, chunk_steps=400))    # 1000 steps, sampled every 5
    >>> [len(p) for p in pieces], pieces[-1].names == run_scene(scene).names
    ([81, 80, 40], True)
    """
    from .budget import CHUNK_STEPS

    return _pieces(load_scene(scene), chunk_steps or CHUNK_STEPS, progress)


def _pieces(scene: Scene, chunk_steps, progress):
    from .. import simulation as _sim

    torques = scene.torques()
    wanted = scene.data["output"]["quantities"]
    args = (scene.body, scene.orientation, scene.angular_velocity)
    options = dict(
        duration=scene.data["time"]["duration"],
        step=scene.step,
        paths=scene.paths,
        integrator=scene.method,
        torques=torques,
        accept_lower_order=scene.data["integrator"].get("accept_lower_order", False),
        euler_angles=scene.euler_angles,
        outputs=[name for name in wanted if name in _sim.OUTPUTS],
        sample_every=scene.sample_every,
        t0=scene.data["time"]["start"],
        progress=progress,
        step_limit_key=f"{scene.file}: integrator.step",
    )
    if scene.moves:  # a whole rigid motion: its start in space and its declared forces
        options.update(position=scene.position, velocity=scene.velocity,
                       forces=scene.forces())  # fmt: skip
    extra = [name for name in wanted if name not in _sim.OUTPUTS]
    meta = {"scene": scene.name, "principal_rotation": scene.principal_rotation,
            "body_frame": scene.body_frame, "exact": scene.exact,
            "scene_toml": scene.to_toml()}  # fmt: skip
    try:
        if chunk_steps is None:
            source = iter([_sim.simulate(*args, **options)])
        else:
            source = _sim.simulate_chunks(*args, chunk_steps=chunk_steps, **options)
        for tr in source:
            arrays, components = {}, {}
            if extra:
                for name, (values, labels) in _quantities(scene, tr, extra).items():
                    arrays[name] = values
                    if labels:
                        components[name] = labels
            yield tr.extended(arrays, components, meta)
    except Exception as exc:
        from numba.core.errors import NumbaError

        users = [*scene.data["effects"], *scene.data.get("forces", [])]
        if isinstance(exc, NumbaError) and any(e["type"] == "user" for e in users):
            raise _user_compile_error(scene, exc) from None
        raise


def _quantities(scene: Scene, tr: Trajectory, names: list[str]) -> dict:
    """The scene-level quantities in ``names`` (and nothing else)."""
    from .. import quaternion as Q

    out: dict[str, tuple[np.ndarray, tuple[str, ...] | None]] = {}
    w = tr.w
    if "potential_energy" in names or "total_energy" in names:
        if scene.gravity is None:
            potential, total = np.zeros(w.shape[0]), scene.body.energy(w)
        else:  # the rotation of each sample (its |q| drift is reported), in one pass
            potential, total = _gravity_energies(scene.body, tr.quaternions(), w, scene.gravity)
        if "potential_energy" in names:
            out["potential_energy"] = (potential, None)
        if "total_energy" in names:
            out["total_energy"] = (total, None)
    if "omega_space" in names:
        q = Q.normalize(tr.quaternions()[: w.shape[0]])  # the rotation; |q| drift is reported
        out["omega_space"] = (Q.rotate(q, w), ("x", "y", "z"))
    if "error" in names or "omega_error" in names:
        # the rotation; |q| drift aside. One evaluation of the reference serves all.
        unit = {p: Q.normalize(tr.quaternions(p)) for p in scene.paths} if "error" in names else {}
        dw, dq = scene.exact_solution.errors(tr.t, w if "omega_error" in names else None, unit)
        if dw is not None:
            out["omega_error"] = (dw, None)
        for path, error in dq.items():
            out[f"error_{path}"] = (error, None)
    return out


@jit
def _energies_loop(q, w, moments, r, weight, tol, potential_out, total_out):
    """Per row: q normalised (as ``quaternion.normalize`` does, then ``rotate``), its
    potential and the total energy. Returns whether every value is finite."""
    bad = 0.0
    m = (moments[0], moments[1], moments[2])
    lever = (r[0], r[1], r[2])
    mg = (weight[0], weight[1], weight[2])
    for n in range(w.shape[0]):
        unit = qunit(qnormalize((q[n, 0], q[n, 1], q[n, 2], q[n, 3])), tol)
        v = gravity_potential(unit, lever, mg)
        total = kinetic_energy((w[n, 0], w[n, 1], w[n, 2]), m) + v
        potential_out[n] = v
        total_out[n] = total
        bad += total * 0.0
    return bad == 0.0


def _gravity_energies(body, q, w, gravity) -> tuple[np.ndarray, np.ndarray]:
    """(potential, total) energies (each (n,)) of samples with orientations ``q`` (n, 4)
    (their norms the path's own: each is normalised) and body rates ``w`` (n, 3) of the
    scene's body frame, under ``gravity`` = (weight, lever) (:attr:`Scene.gravity`, its
    lever in the principal frame, where the samples are taken by ``body.to_principal``).

    The operations and their order are those of ``-(quaternion.rotate(
    quaternion.normalize(q), r) @ weight)`` and ``body.energy(w)`` on the principal
    frame's samples, the same numbers, in one compiled pass instead of five array passes
    (a streamed heavy top computes its total energy in every piece, on the thread that
    integrates: 0.06 s less CPU over 10⁷ steps). A zero, non-finite or overflowing sample
    raises what those functions raise for it.
    """
    from .. import quaternion as Q
    from .._validate import UNIT_TOLERANCE

    weight, lever = gravity
    if not body.is_principal:
        q, w = body.to_principal(q[: w.shape[0]], w)
        body = RigidBody(body.moments)
    q, w = (np.ascontiguousarray(a, dtype=np.float64) for a in (q, w))
    n = w.shape[0]
    v, total = np.empty(n), np.empty(n)
    args = (np.asarray(a, dtype=np.float64) for a in (body.moments, lever, weight))
    if not _energies_loop(q[:n], w, *args, UNIT_TOLERANCE, v, total):
        # what the array functions say of these samples (the same values otherwise)
        v = -(Q.rotate(Q.normalize(q[:n]), lever) @ weight)
        total = body.energy(w) + v
    return v, total
