"""Peers as a casual user gets them: solvers driven from Python.

* ``scipy_dop853``: scipy's ``solve_ivp(method="DOP853")`` on the same ODE with the
  project's compiled right-hand side (:class:`ga_rotors.integrators.dop853.Dop853`):
  scipy's stepping runs in Python, one compiled call per evaluation;
* ``numpy_quaternion``: numpy-quaternion's ``integrate_angular_velocity`` on the
  kinematics with the exact ω(t) supplied by a Python callback;
* ``mujoco_rk4``/``mujoco_euler``: MuJoCo stepping one body with the same inertia (its
  RK4 and its default semi-implicit Euler) through ``mujoco.rollout``, so its steps run
  in C, each paying the engine's per-step work.

These are what a user who reaches for a familiar library gets, not the fastest way to
solve the problem: the compiled peers (:mod:`ga_rotors.accuracy.compiled_peers`) are the
fair comparison. A missing peer is skipped with a notice.
"""

from __future__ import annotations

import itertools

import numpy as np

from .cases import Case
from .measuring import SAMPLES, Point, point, round_steps, sample_times, timed

__all__ = ["dop853_scipy", "mujoco_model", "mujoco_run", "numpy_quaternion"]


def dop853_scipy(case: Case, rtol: float, repeats: int, budget: float) -> Point:
    """scipy's DOP853 at ``rtol`` (atol = rtol/1000) on the case, sampled at the common times.

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> p = dop853_scipy(cases()["asymmetric_far"], 1e-10, 1, 0.1)
    >>> p.error < 1e-7, p.evaluations > 100, p.family
    (True, True, 'scipy')
    """
    from ..integrators.dop853 import Dop853

    integ = Dop853(rtol=rtol)
    problem = case.problem
    h = case.duration / SAMPLES
    x0, w0 = case.start()

    def run():
        return integ.run(problem, "quaternion", x0, w0, 0.0, h, SAMPLES, 1)

    times, result = timed(run, repeats, budget)
    return point(case, "scipy_dop853", rtol, times, result.stats[0], result.x, result.w,
                 "scipy")  # fmt: skip


def _in_child(func, args: tuple, limit: float):
    """``func(*args)`` run in a child process, or None if it has not returned after
    ``limit`` seconds (the child is then killed). The child does its own timing, so
    starting it costs nothing that is measured. ``func`` is a module-level function and
    ``args`` plain data: the child is not a fork of this process (whose threads, JAX's
    among them, a fork would copy mid-flight) but of a clean server process
    (``forkserver``; ``spawn`` where there is none)."""
    from .._children import context

    ctx = context()
    receive, send = ctx.Pipe(duplex=False)
    child = ctx.Process(target=_reply, args=(send, func, args), daemon=True)
    child.start()
    send.close()
    result = receive.recv() if receive.poll(limit) else None
    child.join(0.1)
    if child.is_alive():
        child.kill()
        child.join()
    receive.close()
    return result


def _reply(send, func, args) -> None:
    """In the child: ``func(*args)`` sent back to the parent (the child ends with the
    parent, even one killed mid-measurement)."""
    from .._children import exit_with_parent

    exit_with_parent()
    send.send(func(*args))


def numpy_quaternion(
    case: Case, tol: float, repeats: int, budget: float, limit: float = 10.0
) -> Point | None:
    """numpy-quaternion integrates dR/dt = ½ Ω R (space-frame Ω). With p = q⁻¹ the body
    kinematics q̇ = ½ q (0, ω) becomes ṗ = ½ (0, −ω) p, so it gets Ω(t) = −ω_body(t). It
    runs from sample time to sample time (one call per interval) to land on them.

    On the fast spinner at tolerances ≤ 1e-11 its scipy ``ode`` DOP853 call never returns
    (measured: still computing after minutes, inside Fortran, where no signal reaches it),
    so each measurement runs in a child process limited to ``limit`` seconds; None means
    it did not finish. The case is one of :func:`~ga_rotors.accuracy.cases`, named.

    Examples
    --------
    numpy-quaternion is an optional peer (extra ``peers``): where it is installed,

    >>> import importlib.util
    >>> from ga_rotors.accuracy import cases
    >>> if importlib.util.find_spec("quaternion"):
    ...     p = numpy_quaternion(cases()["asymmetric_far"], 1e-10, 1, 0.1)
    ...     assert p.family == "numpy-quaternion" and p.error < 1e-7
    """
    found = _in_child(_numpy_quaternion_run, (case.name, tol, repeats, budget), limit)
    if found is None:
        return None
    times, q, evaluations = found
    w_end = np.asarray(case.body_rate(case.duration))
    return point(case, "numpy_quaternion", tol, times, evaluations, q, [w_end],
                 "numpy-quaternion")  # fmt: skip


def _numpy_quaternion_run(name: str, tol: float, repeats: int, budget: float):
    """In the child: :func:`numpy_quaternion`'s measurement of case ``name``: the timings,
    the orientations (w, x, y, z) at the sample times, and the evaluations of ω."""
    import quaternion as npq

    from .cases import cases

    case = cases()[name]
    rate = case.body_rate
    q0 = case.q0
    p0 = npq.quaternion(q0[0], -q0[1], -q0[2], -q0[3])
    marks = sample_times(case)
    counter = [0]

    def counted(t):
        counter[0] += 1
        w = rate(t)
        return [-w[0], -w[1], -w[2]]

    def run():
        counter[0] = 0
        out, p = [p0], p0
        for a, b in itertools.pairwise(marks):
            p = npq.integrate_angular_velocity(counted, a, b, p, tolerance=tol)[1][-1]
            out.append(p)
        return out

    times, ps = timed(run, repeats, budget)
    return times, npq.as_float_array(ps) * np.array([1.0, -1.0, -1.0, -1.0]), counter[0]


def mujoco_model(case: Case, integrator: str, h: float):
    """One body of the case's inertia in MuJoCo (free joint; the heavy top on a ball joint
    at the fixed point, its weight as MuJoCo's gravity on the centre of mass).

    Examples
    --------
    MuJoCo is an optional peer (extra ``peers``): where it is installed,

    >>> import importlib.util
    >>> from ga_rotors.accuracy import cases
    >>> if importlib.util.find_spec("mujoco"):
    ...     model = mujoco_model(cases()["heavy_top"], "RK4", 1e-3)
    ...     assert (model.nq, model.nv, model.opt.timestep) == (4, 3, 1e-3)
    """
    import mujoco

    i1, i2, i3 = case.moments
    if case.mgl is None:
        body = (
            '<body name="b"><freejoint/>'
            f'<inertial pos="0 0 0" mass="1" diaginertia="{i1!r} {i2!r} {i3!r}"/></body>'
        )
        gravity = "0 0 0"
    else:
        # Ball joint at the fixed point, unit mass at l = mgl/g on body z; MuJoCo wants the
        # inertia about the centre of mass: I⊥ − m l² on the transverse axes.
        g = 9.81
        ell = case.mgl / g
        ip = i1 - ell * ell
        body = (
            '<body name="b"><joint type="ball"/>'
            f'<inertial pos="0 0 {ell!r}" mass="1" diaginertia="{ip!r} {ip!r} {i3!r}"/></body>'
        )
        gravity = f"0 0 {-g!r}"
    xml = (
        f'<mujoco><option timestep="{h!r}" integrator="{integrator}" gravity="{gravity}">'
        '<flag contact="disable" constraint="disable"/></option>'
        f"<worldbody>{body}</worldbody></mujoco>"
    )
    return mujoco.MjModel.from_xml_string(xml)


def mujoco_run(case: Case, integrator: str, n: int, repeats: int, budget: float) -> Point:
    """MuJoCo stepping one body n steps (a multiple of :data:`SAMPLES`); its ball/free
    joint angular velocity is in the body frame.

    Examples
    --------
    MuJoCo is an optional peer (extra ``peers``): where it is installed,

    >>> import importlib.util
    >>> from ga_rotors.accuracy import cases
    >>> if importlib.util.find_spec("mujoco"):
    ...     p = mujoco_run(cases()["asymmetric_far"], "RK4", 2000, 1, 0.1)
    ...     assert p.family == "MuJoCo" and p.error < 1e-4 and p.evaluations == 8000
    """
    import mujoco
    from mujoco import rollout

    n = round_steps(n)
    h = case.duration / n
    model = mujoco_model(case, integrator, h)
    data = mujoco.MjData(model)
    qa = 3 if case.mgl is None else 0  # quaternion address in qpos
    va = 3 if case.mgl is None else 0
    data.qpos[qa : qa + 4] = case.q0
    data.qvel[va : va + 3] = case.w0
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state0 = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, state0, spec)
    out = np.empty((1, n, state0.size))

    def run():
        rollout.rollout(model, data, state0[None, :], nstep=n, state=out)
        return out[0]

    times, states = timed(run, repeats, budget)
    rows = [n * k // SAMPLES - 1 for k in range(1, SAMPLES + 1)]
    nq = model.nq
    q = np.vstack([np.asarray(case.q0), states[rows, 1 + qa : 1 + qa + 4]])
    w_end = states[-1, 1 + nq + va : 1 + nq + va + 3]
    name = "mujoco_rk4" if integrator == "RK4" else "mujoco_euler"
    per_step = 4 if integrator == "RK4" else 1
    return point(case, name, n, times, per_step * n, q, [w_end], "MuJoCo")
