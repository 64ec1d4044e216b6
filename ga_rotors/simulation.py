"""Simulate a rigid body (or a prescribed rotation) along the orientation paths asked for.

:func:`simulate` is the Python entry point: a body, its initial orientation and angular
velocity, a time span and step, the paths wanted. Each path is a separate compiled
integration of (orientation, ω) with the same integrator, so paths not asked for are
never integrated and outputs not asked for are never computed.

The primary path (whose ω goes into the trajectory's ``w``) is the first of
``motor``, ``rotor``, ``quaternion``, ``euler`` (the order of :data:`ga_rotors.paths.PATHS`)
among those requested. The function is also ``ga_rotors.simulate``.

Given a ``position`` (or a ``velocity``, or ``forces``), the body moves through space as
well as turning: a whole rigid motion, integrated on the ``motor`` path (the motor of the
body frame and its velocity line) and the ``quaternion`` path (the quaternion and the
centre of mass), :mod:`ga_rotors.paths`.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator, Sequence
from typing import NamedTuple

import numpy as np

from . import paths as _paths
from . import quaternion as _q
from ._validate import as_float_array, require_unit
from .body import RigidBody
from .errors import InputError, IntegrationStoppedWarning
from .integrators import base
from .trajectory import Trajectory

__all__ = ["OUTPUTS", "simulate", "simulate_chunks", "whole_steps"]

#: Derived outputs :func:`simulate` computes on request, from the primary path.
OUTPUTS = ("energy", "L", "L_space", "angles")

#: |duration / step - round(duration / step)| allowed, relative: the step must divide the
#: span; a few ulps of the quotient are representation error (0.3 / 0.1 = 2.9999999999999996).
_DIVIDE_TOLERANCE = 1e-9


#: Bodies given by their principal moments, built once per moments (RigidBody is frozen;
#: building one validates it, 40% of a short run's call before this cache).
_BODIES: dict[tuple, RigidBody] = {}


def _body(body) -> RigidBody:
    if isinstance(body, RigidBody):
        return body
    if type(body) is tuple:  # moments seen before (the key equals only valid moments)
        found = _BODIES.get(body)
        if found is not None:
            return found
    if body is None:
        raise InputError("body: a dynamics simulation needs a RigidBody or principal moments")
    moments = tuple(as_float_array(body, "body", last=3).tolist())
    found = _BODIES.get(moments)
    if found is None:
        if len(_BODIES) >= 64:
            _BODIES.clear()
        found = _BODIES[moments] = RigidBody(moments)
    return found


def whole_steps(duration, step) -> int:
    """How many steps of ``step`` seconds make ``duration``; the step must divide it.

    A few ulps of the quotient are representation error and are forgiven
    (0.3 / 0.1 = 2.9999999999999996 is 3 steps).

    Examples
    --------
    >>> whole_steps(0.3, 0.1), whole_steps(10.0, 1e-3)
    (3, 10000)
    >>> whole_steps(1.0, 0.3)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: step: 0.3 s does not divide duration 1.0 s into whole steps ...
    """
    for name, value in (("duration", duration), ("step", step)):
        if isinstance(value, bool) or not isinstance(value, int | float | np.floating):
            raise InputError(f"{name}: expected a number of seconds, got {value!r}")
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"{name}: expected a finite positive number of seconds, got {value!r}")
    ratio = duration / step
    if not math.isfinite(ratio):
        raise InputError(f"step: {step!r} s divides duration {duration!r} s into more "
                         "steps than float64 can count")  # fmt: skip
    n = round(ratio)
    if n < 1 or abs(ratio - n) > _DIVIDE_TOLERANCE * max(1.0, ratio):
        raise InputError(
            f"step: {step!r} s does not divide duration {duration!r} s into whole steps "
            f"(ratio {ratio!r}); choose a step that does"
        )
    return int(n)


#: (duration, step) -> steps, and paths -> the requested paths in order, for arguments
#: seen before (a sweep, repeats): their checks cost more than a short run's loop.
_STEPS: dict[tuple, int] = {}
_REQUESTED: dict = {}


def _steps(duration, step) -> int:
    """:func:`whole_steps`, remembered for the (type, value) pairs it accepted."""
    key = (type(duration), duration, type(step), step)
    try:
        return _STEPS[key]
    except (KeyError, TypeError):  # new, or unhashable: whole_steps says what is wrong
        n = whole_steps(duration, step)
        if len(_STEPS) >= 64:
            _STEPS.clear()
        try:
            _STEPS[key] = n
        except TypeError:
            pass
        return n


def _requested(paths) -> list[str]:
    try:
        return list(_REQUESTED[paths])
    except (KeyError, TypeError):  # new, or unhashable (a list)
        found = _requested_now(paths)
        if type(paths) is str or type(paths) is tuple:
            if len(_REQUESTED) >= 64:
                _REQUESTED.clear()
            _REQUESTED[paths] = tuple(found)
        return found


def _requested_now(paths) -> list[str]:
    if isinstance(paths, str):
        paths = (paths,)
    out = []
    for p in paths:
        _paths.get(p)
        if p not in out:
            out.append(p)
    if not out:
        raise InputError(f"expected at least one of {', '.join(_paths.PATHS)}", key="paths")
    order = list(_paths.PATHS)  # the registry's order is the order of precedence
    return sorted(out, key=order.index)


def simulate(
    body,
    orientation,
    angular_velocity,
    *,
    duration: float,
    step: float,
    paths: Sequence[str] | str | None = None,
    integrator: str = "rk4",
    torques: Sequence[base.TorqueTerm] = (),
    accept_lower_order: bool = False,
    euler_angles=None,
    outputs: Sequence[str] = (),
    sample_every: int = 1,
    t0: float = 0.0,
    progress=None,
    step_limit_key: str = "step",
    position=None,
    velocity=None,
    forces: Sequence[base.ForceTerm] = (),
) -> Trajectory:
    """Integrate the motion and return the requested paths and outputs.

    Parameters
    ----------
    body : RigidBody or array_like (3,) or None
        Principal moments, or a :class:`RigidBody` (for one built from a full tensor,
        ``orientation``, ``angular_velocity`` and the results refer to the tensor's frame;
        the integration runs in the principal frame, where torque kernels act).
        ``None`` with a prescribed ω(t).
    orientation : array_like (4,)
        Initial body->space unit quaternion (w, x, y, z).
    angular_velocity : array_like (3,) or PrescribedOmega
        Initial body-frame ω (rad/s), or a prescribed ω(t) (kinematics only).
    duration, step : float
        Time span and fixed step (s); ``step`` must divide ``duration``.
    paths : sequence of {"rotor", "quaternion", "euler", "motor"}
        Paths to integrate (each a separate integration); default ``("rotor",)``, and
        for a body moving through space ``("motor",)`` (there ``quaternion`` is the
        quaternion and the centre of mass; ``rotor`` and ``euler`` turn only).
    integrator : str or Integrator
        A registered integrator's name (:func:`ga_rotors.integrators.names`), or an
        integrator object (e.g. ``Dop853(rtol=1e-12)`` for another tolerance).
    torques : sequence of TorqueTerm
        Declared torques; none means torque-free. A method that integrates torques of
        orientation and time only (``catalogue()`` column ``torques``: the splittings,
        ``lgvi``) refuses a torque that depends on ω (``TorqueTerm.depends_on_omega``,
        True by default), with which it would be first-order accurate.
    accept_lower_order : bool
        Run such a combination anyway, accepting first order.
    euler_angles : array_like (3,), optional
        Initial ZYZ angles (ψ, θ, φ) for the (ZYZ) Euler-angle path; they must describe
        ``orientation``. Default: extracted from ``orientation`` with :mod:`ga_rotors.euler`.
    outputs : sequence of {"energy", "L", "L_space", "angles"}
        Derived quantities of the primary path: kinetic energy, body and space angular
        momentum, and the ZYZ Euler angles of its orientation (:mod:`ga_rotors.euler`;
        a GimbalLockWarning if a sample sits at θ = 0 or π).
    sample_every : int
        Keep every k-th step (the last step is always kept).
    t0 : float
        Initial time.
    progress : callable, optional
        ``progress(done, total)``, steps over all paths, called as the compiled loops
        advance in chunks (integrators whose ``run`` takes no ``progress`` report once
        per path).
    step_limit_key : str
        What a run past the integrator's step limit names first (scenes pass
        ``"<file>: integrator.step"``). Past the limit (``catalogue()`` column
        ``step_limit``, judged on the initial state; a torqued problem by its torque-free
        rate) the run warns with :class:`~ga_rotors.errors.StepLimitWarning`, or, for
        ``lgvi``, which has no step there, raises InputError.
    position, velocity : array_like (3,), optional
        Where the body-frame origin is in space (m) and its velocity there (m/s): given
        either, the body moves through space, a whole rigid motion (its ``body`` needs a
        ``mass``; the origin need not be the centre of mass: ``RigidBody(...,
        centre_of_mass=)``). The other defaults to zero.
    forces : sequence of ForceTerm
        Forces on a moving body (:mod:`ga_rotors.forces`), beside its ``torques`` (which
        act about the centre of mass).

    Returns
    -------
    Trajectory
        ``t``, ``w`` and one array per path (``rotor_blades``, ``q``, ``euler``; for a
        moving body ``motor``, ``q_com``, and the primary path's ``position`` and
        ``velocity``), plus ``outputs``; ``meta`` records the integrator, step and each
        path's status. Whatever the path, ``quaternions(path)`` gives its orientation as
        (w, x, y, z) and ``rotors(path)`` as clifford rotors (the rotor path's raw state
        is on clifford's blades (1, e12, e13, e23), where k is −e12: not a quaternion);
        for a moving body ``positions(path)``, ``velocities()`` and ``motors(path)``.

    Warns
    -----
    IntegrationStoppedWarning
        When a path's state stopped being finite before the end (its arrays then end at
        ``meta["paths"][path]["ended_at"]``).

    Examples
    --------
    A disk spinning about its symmetry axis, one second, rotor and quaternion paths:

    >>> from ga_rotors import shapes
    >>> tr = simulate(shapes.disk(2.0, 0.075), [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 2.0],
    ...               duration=1.0, step=1e-3, paths=("rotor", "quaternion"))
    >>> tr.names
    ('t', 'w', 'rotor_blades', 'q')
    >>> tr.q[-1].round(12).tolist()          # a 2 rad turn about z: (cos 1, 0, 0, sin 1)
    [0.540302305868, 0.0, 0.0, 0.841470984808]
    >>> tr.meta["paths"]["rotor"]["complete"]
    True

    A body thrown up at 5 m/s under gravity for one second, on the motor and quaternion
    paths: its origin is at ½ g t² below the straight line, and the paths agree.

    >>> from ga_rotors import RigidBody, forces
    >>> ball = RigidBody((1.0, 1.0, 1.0), mass=2.0)
    >>> tr = simulate(ball, [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0], duration=1.0, step=1e-2,
    ...               position=[0.0, 0.0, 0.0], velocity=[0.0, 0.0, 5.0],
    ...               forces=[forces.uniform_gravity(ball)], paths=("motor", "quaternion"))
    >>> tr.positions()[-1].round(12).tolist()        # 5 t − ½ g t²
    [0.0, 0.0, 0.096675]
    >>> tr.names
    ('t', 'w', 'position', 'velocity', 'motor', 'q_com')
    """
    plan = _plan(body, orientation, angular_velocity, duration, step, paths, integrator,
                 torques, accept_lower_order, euler_angles, outputs, sample_every, t0,
                 step_limit_key, position, velocity, forces)  # fmt: skip
    return next(_pieces(plan, None, progress))


def simulate_chunks(
    body,
    orientation,
    angular_velocity,
    *,
    duration: float,
    step: float,
    chunk_steps: int = 2**17,
    progress=None,
    **options,
) -> Iterator[Trajectory]:
    """:func:`simulate`, handed out as Trajectories of consecutive samples, each about
    ``chunk_steps`` steps long, so memory holds one piece whatever the number of steps.

    The arguments are :func:`simulate`'s. The first piece holds sample 0, each next one
    the samples after the previous piece's last; joined, they are :func:`simulate`'s
    samples and outputs bit for bit: every path continues from its exact state at its
    step number, with what its integrator carries (the watch statistics, an adaptive
    method's step size). Each piece's ``meta`` is the run's so far (``meta["paths"]``:
    complete, samples, ended_at up to that piece). A path that stopped has no rows in the
    pieces after it stopped. Arguments are checked before the first piece.

    Examples
    --------
    >>> from ga_rotors import shapes
    >>> args = (shapes.disk(2.0, 0.075), [1.0, 0.0, 0.0, 0.0], [0.1, 0.0, 2.0])
    >>> pieces = list(simulate_chunks(*args, duration=1.0, step=1e-3, chunk_steps=400,
    ...                               paths=("rotor", "quaternion"), sample_every=100))
    >>> [len(piece) for piece in pieces]
    [5, 4, 2]
    >>> whole = simulate(*args, duration=1.0, step=1e-3, paths=("rotor", "quaternion"),
    ...                  sample_every=100)
    >>> bool((np.concatenate([piece.q for piece in pieces]) == whole.q).all())
    True
    """
    if isinstance(chunk_steps, bool) or not isinstance(chunk_steps, int) or chunk_steps < 1:
        raise InputError(f"chunk_steps: expected a positive integer, got {chunk_steps!r}")
    defaults = dict(paths=None, integrator="rk4", torques=(), accept_lower_order=False,
                    euler_angles=None, outputs=(), sample_every=1, t0=0.0,
                    step_limit_key="step", position=None, velocity=None,
                    forces=())  # fmt: skip
    unknown = sorted(set(options) - set(defaults))
    if unknown:
        raise InputError(f"{unknown[0]}: not an argument of simulate")
    o = {**defaults, **options}
    plan = _plan(body, orientation, angular_velocity, duration, step, o["paths"],
                 o["integrator"], o["torques"], o["accept_lower_order"], o["euler_angles"],
                 o["outputs"], o["sample_every"], o["t0"], o["step_limit_key"],
                 o["position"], o["velocity"], o["forces"])  # fmt: skip
    return _pieces(plan, chunk_steps, progress)


class _Plan(NamedTuple):
    """What :func:`simulate` validated and derived before integrating."""

    method: base.Integrator
    problem: base.Problem
    requested: list
    starts: dict  # path -> (its initial state, its initial rates)
    rigid: RigidBody | None
    principal: np.ndarray | None
    t0: float
    h: float
    nsteps: int
    sample_every: int
    outputs: tuple
    step_limit_key: str
    specs: dict  # path -> the OrientationPath it runs on (a motion's variant)


def _plan(body, orientation, angular_velocity, duration, step, paths, integrator, torques,
          accept_lower_order, euler_angles, outputs, sample_every, t0,
          step_limit_key, position=None, velocity=None, forces=()) -> _Plan:  # fmt: skip
    method = integrator if isinstance(integrator, base.Integrator) else base.get(integrator)
    forces = forces if type(forces) is tuple else tuple(forces)
    moving = position is not None or velocity is not None or bool(forces)
    requested = _requested(paths if paths is not None else ("motor",) if moving else "rotor")
    specs = {p: _paths.resolve(p, moving) for p in requested}
    nsteps = _steps(duration, step)
    if type(sample_every) is not int or sample_every < 1:
        if isinstance(sample_every, bool) or not isinstance(sample_every, int) or sample_every < 1:
            raise InputError(f"sample_every: expected a positive integer, got {sample_every!r}")
    if type(t0) is not float or not math.isfinite(t0):
        if isinstance(t0, bool) or not isinstance(t0, int | float) or not math.isfinite(t0):
            raise InputError(f"t0: expected a finite number of seconds, got {t0!r}")
    for name in outputs:
        if name not in OUTPUTS:
            raise InputError(f"outputs: unknown output {name!r}; expected one of {OUTPUTS}")

    q0 = _orientation(orientation)

    if isinstance(angular_velocity, base.PrescribedOmega):
        if body is not None:
            raise InputError("body: a prescribed ω(t) is kinematics only; pass body=None")
        if moving:
            raise InputError("position: a prescribed ω(t) turns a frame; it does not move "
                             "a body through space")  # fmt: skip
        problem = base.Problem(omega=angular_velocity)
        rigid, w0 = None, None
        if outputs:
            raise InputError("outputs: energy and momentum need a body, not a prescribed ω(t)")
    else:
        rigid = _body(body)
        w0 = _angular_velocity(angular_velocity)
        torques = torques if type(torques) is tuple else tuple(torques)
        if moving:
            if rigid.mass is None:
                raise InputError("a body moving through space needs its mass: "
                                 "RigidBody(moments, mass=...)", key="body.mass")  # fmt: skip
            problem = base.problem_for(
                rigid.moments, torques, accept_lower_order, mass=rigid.mass,
                centre_of_mass=rigid.to_principal_axes(rigid.centre_of_mass), forces=forces,
            )  # fmt: skip
        else:
            problem = base.problem_for(rigid.moments, torques, accept_lower_order)
    for p in requested:
        method.check_once(problem, p)

    # A body given by a full tensor integrates in its principal frame: q_P = q ⊗ P and
    # ω_P = P* ω P going in, q = q_P ⊗ P* and ω = P ω_P P* coming out.
    principal = None
    if rigid is not None and rigid.principal_rotation != (1.0, 0.0, 0.0, 0.0):
        principal = np.array(rigid.principal_rotation)
        if any(_paths.get(p).sequence for p in requested):
            raise InputError(
                "an Euler-angle path integrates the angles of the principal frame, "
                "which differ from those of this body's frame; give the body by its "
                "principal moments to use it",
                key="paths",
            )
        q0 = _q.multiply(q0, principal)
        w0 = _q.rotate(_q.conjugate(principal), w0)

    starts = {}
    if moving:
        p0, v0 = _vector(position, "position"), _vector(velocity, "velocity")
        for p in requested:
            starts[p] = specs[p].load().initial_state(q0, p0, w0, v0,
                                                      problem.centre_of_mass)  # fmt: skip
    for p in () if moving else requested:
        spec = specs[p]
        module = spec.load()
        if spec.sequence == "ZYZ":
            starts[p] = module.initial_state(_euler_start(q0, euler_angles)), w0
        elif spec.sequence is not None:
            from . import euler

            starts[p] = module.initial_state(euler.from_quaternion(q0, spec.sequence)), w0
        else:
            starts[p] = module.initial_state(q0), w0

    return _Plan(method, problem, requested, starts, rigid, principal, float(t0),
                 float(step), nsteps, sample_every, tuple(outputs), step_limit_key,
                 specs)  # fmt: skip


def _pieces(plan: _Plan, chunk: int | None, progress):
    """The run of ``plan`` as Trajectories of consecutive samples (see
    :func:`simulate_chunks`); ``chunk=None``: one piece, each path's loop called once.

    Every path is one :meth:`~ga_rotors.integrators.Integrator.run`; the primary path's
    judges the step limit on the initial state (past it, a warning naming the caller of
    simulate, or lgvi's refusal before any step) and watches the samples it stores (a
    torque may carry ω past the limit the start was within); the others' are not judged
    again."""
    method, problem, requested, nsteps = plan.method, plan.problem, plan.requested, plan.nsteps
    every, h, t0 = plan.sample_every, plan.h, plan.t0
    if not method.continues:
        chunk = None  # an integrator that cannot continue a run: one piece, the whole run
    total = nsteps * len(requested)
    done = dict.fromkeys(requested, 0)
    sources = {}
    for p in requested:
        report = None
        if progress is not None:

            def report(steps, p=p):
                done[p] = steps
                progress(sum(done.values()), total)

        primary = p == requested[0]
        found = method.run(
            problem, p, *plan.starts[p], t0, h, nsteps, every, chunk=chunk,
            progress=report, where=plan.step_limit_key if primary else None, watch=primary,
            stacklevel=4,
        )  # fmt: skip
        sources[p] = iter([found]) if chunk is None else found
    span = nsteps if chunk is None else max(1, int(chunk) // every) * every
    status = {p: {"complete": True, "samples": 0, "ended_at": t0} for p in requested}
    live = dict(sources)
    for lo in range(0, nsteps, span):
        hi = min(nsteps, lo + span)
        results = {}
        for p in requested:
            result = next(live[p], None) if p in live else None
            if result is None:  # stopped earlier: no samples in this piece
                live.pop(p, None)
                continue
            results[p] = result
            info = status[p]
            info["samples"] += int(result.t.shape[0])
            if result.t.shape[0]:
                info["ended_at"] = float(result.t[-1])
            info["generated_module"] = str(result.source) if result.source else None
            module = plan.specs[p].load()
            if hasattr(module, "report") and len(result.stats) == module.NSTATS:
                info["watch"] = module.report(result.stats)  # (scipy's dop853 keeps no watch)
            if not result.complete:
                info["complete"] = False
                live.pop(p)
                warnings.warn(
                    f"paths: the {p} path of {method.name} stopped at t = "
                    f"{info['ended_at']:g} s of {t0 + nsteps * h:g} s: its state stopped being "
                    "finite (a singular path, a blow-up, or an implicit step with no solution "
                    "at this step size); the trajectory holds the samples up to then",
                    IntegrationStoppedWarning,
                    stacklevel=3,
                )
        primary = results.get(requested[0])
        if chunk is None and primary is not None and primary.complete:
            grid = primary.t  # one call's times are t0 + k·h: the grid itself, bit for bit
        else:
            marks = np.arange(lo if lo == 0 else lo + every, hi + 1, every)
            if hi == nsteps and nsteps % every:
                marks = np.concatenate([marks, [nsteps]])
            grid = t0 + h * marks
        yield _derive(plan, grid, results, status)


def _derive(plan: _Plan, grid, results: dict, status: dict) -> Trajectory:
    """One piece's Trajectory: the paths' samples, the outputs asked for, in the user's frame."""
    requested, outputs, principal, rigid = plan.requested, plan.outputs, plan.principal, plan.rigid
    arrays: dict[str, np.ndarray] = {"t": grid}
    components: dict[str, tuple[str, ...]] = {"w": ("1", "2", "3")}
    primary_w = None
    moving = plan.problem.kind == base.MOTION
    for p in requested:
        spec = plan.specs[p]
        result = results.get(p)
        rates = 6 if moving else 3
        x = result.x if result is not None else np.empty((0, spec.dim))
        w = result.w if result is not None else np.empty((0, rates))
        if primary_w is None:
            primary_w = w[:, :3]
            arrays["w"] = primary_w
            if moving:  # the body origin's, in space: the same in either frame of axes
                module, s = spec.load(), plan.problem.centre_of_mass
                arrays["position"] = module.positions(x, s)
                arrays["velocity"] = module.velocities(x, w, s)
                components["position"] = components["velocity"] = ("x", "y", "z")
        arrays[spec.array] = x
        components[spec.array] = spec.components

    # The loops return principal-frame states: the outputs are read from them on the
    # principal body (L is carried back to the user's frame below).
    principal_body = rigid if principal is None or rigid is None else RigidBody(rigid.moments)
    if "energy" in outputs:
        arrays["energy"] = np.atleast_1d(principal_body.energy(primary_w))
    if "L" in outputs:
        arrays["L"] = principal_body.momentum(primary_w)
        components["L"] = ("1", "2", "3")
    if "L_space" in outputs or "angles" in outputs:
        primary = plan.specs[requested[0]]
        n = primary_w.shape[0]
        # the rotation the state stands for: a long run's |q| drift (RK4 lets it reach
        # 0.998 over 10⁵ steps) is reported by the paths' norm drift, not fatal here
        q = _q.normalize(primary.load().quaternions(arrays[primary.array][:n]))
        if "L_space" in outputs:
            arrays["L_space"] = principal_body.space_momentum(q, primary_w)
            components["L_space"] = ("x", "y", "z")
        if "angles" in outputs:
            from . import euler

            q_user = q if principal is None else _q.multiply(q, _q.conjugate(principal))
            arrays["angles"] = euler.from_quaternion(q_user, "ZYZ") if n else np.empty((0, 3))
            components["angles"] = ("psi", "theta", "phi")
    if principal is not None:
        back = _q.conjugate(principal)
        arrays["w"] = _q.rotate(principal, arrays["w"])
        if "L" in arrays:
            arrays["L"] = _q.rotate(principal, arrays["L"])
        for p in requested:
            spec = plan.specs[p]
            module = spec.load()
            if moving:
                arrays[spec.array] = module.to_user_frame(arrays[spec.array], principal)
                continue
            q_user = _q.multiply(module.quaternions(arrays[spec.array]), back)
            arrays[spec.array] = module.initial_state(q_user)

    meta = {
        "integrator": plan.method.name,
        "order": plan.method.order,
        "step": plan.h,
        "steps": plan.nsteps,
        "sample_every": plan.sample_every,
        "problem": plan.problem.kind,
        "moments": None if rigid is None else rigid.moments,
        "torques": [t.name for t in plan.problem.torques],
        "paths": {p: dict(info) for p, info in status.items()},
        "primary": requested[0],
    }
    if moving:
        meta["mass"] = rigid.mass
        meta["centre_of_mass"] = rigid.centre_of_mass
        meta["forces"] = [f.name for f in plan.problem.forces]
        meta["force_params"] = [list(f.params) for f in plan.problem.forces]
    return Trajectory(arrays, components, meta)


_F64 = np.dtype(np.float64)


def _orientation(orientation) -> np.ndarray:
    """The initial orientation, checked and renormalised (one quaternion, unit within
    :data:`ga_rotors._validate.UNIT_TOLERANCE`)."""
    if type(orientation) is np.ndarray and orientation.dtype == _F64 and orientation.shape == (4,):
        # an array of the right kind: only its values are left to check, and a finite
        # sum of squares says they are finite (a NaN or an infinity takes the long way,
        # which names it)
        a, b, c, d = orientation.tolist()
        if math.isfinite(a * a + b * b + c * c + d * d):
            return require_unit(orientation, "orientation")
    q0 = as_float_array(orientation, "orientation", last=4)
    if q0.shape != (4,):
        raise InputError(f"orientation: expected one quaternion of shape (4,), got {q0.shape}")
    return require_unit(q0, "orientation")


def _vector(value, name: str) -> np.ndarray:
    """A position or velocity: three finite numbers (zero when not given)."""
    if value is None:
        return np.zeros(3)
    v = as_float_array(value, name, last=3)
    if v.shape != (3,):
        raise InputError(f"expected one vector of shape (3,), got shape {v.shape}", key=name)
    return v


def _angular_velocity(angular_velocity) -> np.ndarray:
    """The initial body ω, checked: three finite numbers."""
    w = angular_velocity
    if type(w) is np.ndarray and w.dtype == _F64 and w.shape == (3,):
        a, b, c = w.tolist()
        if math.isfinite(a) and math.isfinite(b) and math.isfinite(c):
            return w
    w = as_float_array(angular_velocity, "angular_velocity", last=3)
    if w.shape != (3,):
        raise InputError(f"angular_velocity: expected shape (3,), got {w.shape}")
    return w


#: Largest geodesic angle (rad) allowed between ``euler_angles`` and ``orientation``: both
#: describe one rotation, so only round-off separates them (a few 1e-16).
_SAME_ROTATION = 1e-12


def _euler_start(q0: np.ndarray, angles) -> np.ndarray:
    from ._kernels import geodesic_angle
    from .paths.euler import to_quat

    if angles is None:
        from . import euler

        return euler.from_quaternion(q0, "ZYZ")
    a = as_float_array(angles, "euler_angles", last=3)
    if a.shape != (3,):
        raise InputError(f"euler_angles: expected (ψ, θ, φ) of shape (3,), got {a.shape}")
    gap = geodesic_angle(to_quat(tuple(a)), tuple(q0))
    if gap > _SAME_ROTATION:
        raise InputError(
            f"euler_angles: {tuple(float(v) for v in a)} is {gap:.3g} rad away from "
            "orientation; they must describe the same rotation"
        )
    return a
