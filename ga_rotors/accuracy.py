"""What accuracy costs in time: a work-precision study of the integrator catalogue.

For each reference problem (:func:`cases`) every method runs over a sweep of step counts
(adaptive methods: of tolerances); each run's error against the exact solution, its wall
time and its right-hand-side evaluations are recorded as a :class:`Point`. From the points,
:func:`cheapest` picks, for each target error, the cheapest run that reaches it: the table
a user reads to choose a method.

Measurement rules. Every project method runs compiled (the specialised loops of
:mod:`ga_rotors.integrators`); each timing is the minimum over repeats after one warm-up
run (the warm-up also pays any JIT compilation), so methods are compared, not
interpreters or first calls. Peers run in the same process and the same sweep: scipy's
DOP853 on the same ODE with the same compiled right-hand side, numpy-quaternion's
``integrate_angular_velocity`` on the kinematics with the exact ω(t) supplied, and MuJoCo
stepping one body with the same inertia (its RK4 and its default semi-implicit Euler),
through ``mujoco.rollout`` so its steps run in C. A missing peer is skipped with a notice.

Errors: the geodesic angle (rad) between the computed and exact orientation at the final
time; the relative drift of the energy and of the conserved momentum (the space-frame L
for a free body; its vertical component L_Z for the heavy top).

Evaluations: vector-field evaluations for Runge–Kutta-type methods (4 per RK4 step, and
scipy's count for DOP853); for splitting methods, the Strang stages (each a handful of
exact axis rotations, about the cost of one vector-field evaluation); for the implicit
LGVI and midpoint rules, one per step plus their solver sweeps, which are not counted.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .errors import StepLimitWarning

__all__ = [
    "EVALUATIONS",
    "TARGETS",
    "Case",
    "Point",
    "cases",
    "cheapest",
    "measure",
    "study",
]

#: Target geodesic errors (rad) of the cheapest-method table.
TARGETS = tuple(10.0**-k for k in range(3, 13))

#: Nominal right-hand-side evaluations (or Strang stages) per step, by method.
EVALUATIONS = {
    "rk4": 4,
    "rk4_renorm": 4,
    "rk4_euler": 4,
    "lie_euler": 1,
    "rkmk4": 4,
    "cf4": 4,
    "cg3": 3,
    "split2": 1,
    "split4": 5,
    "split4_yoshida": 3,
    "split6": 7,
    "split_sym": 1,
    "lgvi": 1,
    "midpoint": 1,
    "dp8": 12,
    "mujoco_rk4": 4,
    "mujoco_euler": 1,
}


@dataclass(frozen=True)
class Case:
    """One reference problem.

    ``reference`` has ``at(t) -> (q, w)``; ``invariants(q, w) -> (energy, momentum)`` gives
    the energy and the conserved momentum vector (or component) for states (n, 4), (n, 3).
    ``body_rate(t)`` is the exact body ω at a scalar time (for the kinematics-only peer),
    or None; ``mgl`` is the heavy top's gravity parameter (None when torque-free).

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

    @property
    def problem(self):
        from .integrators import Problem
        from .reference.heavy_top import gravity_torque

        if self.mgl is None:
            return Problem(self.moments)
        return Problem(self.moments, torques=(gravity_torque(self.mgl),))

    def exact_final(self) -> np.ndarray:
        return self.reference.at([self.duration])[0][0]

    def invariants(self, q, w):
        """(energy, conserved momentum) for states q (n, 4), w (n, 3)."""
        from . import quaternion as Q

        inertia = np.asarray(self.moments)
        q = Q.normalize(np.atleast_2d(q))
        w = np.atleast_2d(w)
        ls = Q.rotate(q, w * inertia)
        energy = 0.5 * (w * w * inertia).sum(-1)
        if self.mgl is None:
            return energy, ls
        zz = q[:, 0] ** 2 - q[:, 1] ** 2 - q[:, 2] ** 2 + q[:, 3] ** 2
        return energy + self.mgl * zz, ls[:, 2:3]


@dataclass(frozen=True)
class Point:
    """One run: method, its setting (steps, or tolerance), cost and errors.

    Examples
    --------
    >>> p = measure(cases()["asymmetric_far"], "split4", 100, repeats=1)
    >>> p.method, p.setting, p.evaluations, p.family
    ('split4', 100.0, 500.0, 'ga_rotors')
    """

    method: str
    setting: float
    seconds: float
    evaluations: float
    error: float
    energy_drift: float
    momentum_drift: float
    family: str = "ga_rotors"


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
    from . import euler, shapes
    from .kinematics import body_omega_from_zyz_rates
    from .reference.asymmetric_top import AsymmetricTop
    from .reference.heavy_top import HeavyTop
    from .reference.symmetric_top import SymmetricTop

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


# ----------------------------------------------------------------------------- timing


def _best_time(run: Callable, repeats: int, budget: float) -> tuple[float, object]:
    """Minimum wall time of ``run()`` over repeats after a warm-up call; and its result."""
    result = run()
    best = math.inf
    spent = 0.0
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        result = run()
        elapsed = time.perf_counter() - start
        best = min(best, elapsed)
        spent += elapsed
        if spent > budget:
            break
    return best, result


def _point(case: Case, method, setting, seconds, evaluations, q, w, family) -> Point:
    from . import quaternion as Q

    q_end = Q.normalize(np.asarray(q[-1], dtype=float))
    error = float(Q.distance(case.exact_final(), q_end))
    e, m = case.invariants(np.array([case.q0, q_end]), np.array([case.w0, w[-1]]))
    scale = max(float(np.linalg.norm(np.asarray(case.moments) * case.w0)), 1e-300)
    return Point(
        method,
        float(setting),
        seconds,
        float(evaluations),
        error,
        abs(float(e[1] - e[0])) / abs(float(e[0])),
        float(np.linalg.norm(m[1] - m[0])) / scale,
        family,
    )


def measure(case: Case, method: str, n: int, repeats: int = 5, budget: float = 0.5) -> Point:
    """One fixed-step run of ``method`` (``rk4_euler``: RK4 on the z–y′–z″ angles) with n steps.

    Examples
    --------
    >>> p = measure(cases()["asymmetric_far"], "split4", 200, repeats=1)
    >>> p.error < 1e-6, p.evaluations
    (True, 1000.0)
    """
    from . import euler
    from .integrators import get

    problem = case.problem
    h = case.duration / n
    if method == "rk4_euler":
        x0 = euler.from_quaternion(np.asarray(case.q0), "ZYZ")
        integ, path = get("rk4"), "euler"
    else:
        x0, integ, path = np.asarray(case.q0), get(method), "quaternion"

    def run():
        # The sweep runs coarse steps on purpose: their error is measured and plotted, so a
        # step past the method's limit is not silent here (StepLimitWarning is for runs
        # whose user does not see the error).
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", StepLimitWarning)
            return integ.run(problem, path, x0, case.w0, 0.0, h, n, n)

    seconds, result = _best_time(run, repeats, budget)
    x = result.x if path != "euler" else euler.to_quaternion("ZYZ", result.x)
    if not result.complete:
        return Point(method, n, seconds, EVALUATIONS[method] * n, math.inf, math.inf, math.inf)
    return _point(case, method, n, seconds, EVALUATIONS[method] * n, x, result.w, "ga_rotors")


def _dop853(case: Case, rtol: float, repeats: int, budget: float) -> Point:
    from .integrators.dop853 import Dop853

    integ = Dop853(rtol=rtol)
    problem = case.problem

    def run():
        return integ.run(problem, "quaternion", case.q0, case.w0, 0.0, case.duration, 1, 1)

    seconds, result = _best_time(run, repeats, budget)
    return _point(case, "scipy_dop853", rtol, seconds, result.stats[0], result.x, result.w,
                  "scipy")  # fmt: skip


def _in_child(func, limit: float):
    """``func()`` run in a forked child process, or None if it has not returned after
    ``limit`` seconds (the child is then killed). The child does its own timing, so the
    fork costs nothing that is measured."""
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)

    def target():
        send.send(func())

    child = ctx.Process(target=target, daemon=True)
    child.start()
    result = receive.recv() if receive.poll(limit) else None
    child.join(0.1)
    if child.is_alive():
        child.kill()
        child.join()
    return result


def _numpy_quaternion(
    case: Case, tol: float, repeats: int, budget: float, limit: float = 10.0
) -> Point | None:
    """numpy-quaternion integrates dR/dt = ½ Ω R (space-frame Ω). With p = q⁻¹ the body
    kinematics q̇ = ½ q (0, ω) becomes ṗ = ½ (0, −ω) p, so it gets Ω(t) = −ω_body(t).

    On the fast spinner at tolerances ≤ 1e-11 its scipy ``ode`` DOP853 call never returns
    (measured: still computing after minutes, inside Fortran, where no signal reaches it),
    so each measurement runs in a forked child limited to ``limit`` seconds; None means it
    did not finish."""
    import quaternion as npq

    rate = case.body_rate

    def omega(t):
        w = rate(t)
        return [-w[0], -w[1], -w[2]]

    q0 = case.q0
    p0 = npq.quaternion(q0[0], -q0[1], -q0[2], -q0[3])
    counter = [0]

    def counted(t):
        counter[0] += 1
        return omega(t)

    def run():
        counter[0] = 0
        return npq.integrate_angular_velocity(counted, 0.0, case.duration, p0, tolerance=tol)

    found = _in_child(lambda: (_best_time(run, repeats, budget), counter[0]), limit)
    if found is None:
        return None
    (seconds, (_, p)), evaluations = found
    pe = npq.as_float_array(p[-1])
    q_end = np.array([pe[0], -pe[1], -pe[2], -pe[3]])
    w_end = np.asarray(rate(case.duration))
    return _point(case, "numpy_quaternion", tol, seconds, evaluations, [q_end], [w_end],
                  "numpy-quaternion")  # fmt: skip


def _mujoco_model(case: Case, integrator: str, h: float):
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


def _mujoco(case: Case, integrator: str, n: int, repeats: int, budget: float) -> Point:
    """MuJoCo stepping one body; its ball/free joint angular velocity is in the body frame."""
    import mujoco
    from mujoco import rollout

    h = case.duration / n
    model = _mujoco_model(case, integrator, h)
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
        return out[0, -1]

    seconds, final = _best_time(run, repeats, budget)
    nq = model.nq
    q_end = final[1 + qa : 1 + qa + 4]
    w_end = final[1 + nq + va : 1 + nq + va + 3]
    name = "mujoco_rk4" if integrator == "RK4" else "mujoco_euler"
    return _point(case, name, n, seconds, EVALUATIONS[name] * n, [q_end], [w_end], "MuJoCo")


# ------------------------------------------------------------------------------ sweeps


def _methods(case: Case) -> list[str]:
    """The methods that integrate ``case`` at their declared order (none at order 1)."""
    from .integrators import catalogue, get, torque_conflict

    problem = case.problem
    names = [
        c["name"]
        for c in catalogue()
        if problem.kind in c["problems"] and "quaternion" in c["paths"] and c["name"] != "dop853"
        and torque_conflict(get(c["name"]), problem.torques) is None
    ]  # fmt: skip
    return [*names, "rk4_euler"]


def _counts(lo: int, hi: int, factor: float) -> list[int]:
    out, n = [], float(lo)
    while n <= hi:
        if not out or round(n) != out[-1]:
            out.append(round(n))
        n *= factor
    return out


@dataclass
class Study:
    """All points of one case, and the notices of skipped peers."""

    case: Case
    points: list[Point] = field(default_factory=list)
    notices: list[str] = field(default_factory=list)


def study(
    case: Case,
    methods: list[str] | None = None,
    *,
    factor: float = 2.0**0.5,
    floor: float = 3e-14,
    max_seconds: float = 0.3,
    repeats: int = 5,
    peers: bool = True,
    log: Callable[[str], None] | None = None,
) -> Study:
    """Sweep every method (step counts ×``factor`` from ``case.steps``) and every peer.

    A method's sweep stops once its error is below ``floor``, or grows again past 4× its
    best below 1e-9 (round-off), or one run takes longer than ``max_seconds``; a tolerance
    sweep runs from 1e-3 to 1e-14 in half decades.

    Examples
    --------
    A two-point sweep of one method, without peers: doubling the steps of a fourth-order
    method divides its error by 2⁴.

    >>> import dataclasses
    >>> case = dataclasses.replace(cases()["asymmetric_far"], steps=(100, 200))
    >>> st = study(case, ["split4"], factor=2.0, repeats=1, peers=False)
    >>> [p.setting for p in st.points]
    [100.0, 200.0]
    >>> round(st.points[0].error / st.points[1].error)
    16
    """
    out = Study(case)
    say = log or (lambda _msg: None)
    for method in methods or _methods(case):
        best = math.inf
        for n in _counts(*case.steps, factor):
            p = measure(case, method, n, repeats, budget=max(0.2, 3 * max_seconds))
            out.points.append(p)
            # Stop at round-off: below the floor, or the error growing again (×4) once
            # below 1e-9, which only accumulated rounding does.
            if p.error < floor or p.seconds > max_seconds or (best < 1e-9 and p.error > 4 * best):
                break
            best = min(best, p.error)
        say(f"  {case.name}: {method} done")
    if not peers:
        return out
    tolerances = [10.0**-k for k in np.arange(3.0, 14.5, 0.5)]
    for rtol in tolerances:
        p = _dop853(case, rtol, repeats, budget=max(0.2, 3 * max_seconds))
        out.points.append(p)
        if p.seconds > 4 * max_seconds:
            break
    say(f"  {case.name}: scipy DOP853 done")
    _numpy_quaternion_sweep(case, out, tolerances, repeats, max_seconds)
    say(f"  {case.name}: numpy-quaternion done")
    _mujoco_sweep(case, out, factor, repeats, max_seconds)
    say(f"  {case.name}: MuJoCo done")
    return out


def _numpy_quaternion_sweep(case, out, tolerances, repeats, max_seconds):
    if case.body_rate is None:
        out.notices.append(
            f"{case.name}: numpy-quaternion skipped: it integrates kinematics only and needs "
            "the exact ω(t), which this problem has only through its dynamics"
        )
        return
    try:
        import quaternion  # noqa: F401
    except ImportError:
        out.notices.append("numpy-quaternion not installed: skipped")
        return
    for tol in tolerances:
        p = _numpy_quaternion(case, tol, repeats, budget=max(0.2, 3 * max_seconds))
        if p is None:
            out.notices.append(
                f"{case.name}: numpy-quaternion at tolerance {tol:.1e} did not finish in 10 s "
                "(scipy's ode DOP853 under it never returned); its sweep ends there"
            )
            break
        out.points.append(p)
        if p.seconds > 4 * max_seconds:
            break


def _mujoco_sweep(case, out, factor, repeats, max_seconds):
    try:
        import mujoco
        from mujoco import rollout  # noqa: F401
    except ImportError:
        out.notices.append("mujoco not installed: skipped")
        return
    unstable = []
    # MuJoCo reports an unstable run (and resets it) through its warning hook; collect
    # those instead of letting them print, and mark such runs as not converged.
    mujoco.set_mju_user_warning(unstable.append)
    for integrator in ("RK4", "Euler"):
        for n in _counts(*case.steps, factor):
            if n > 2**20:  # rollout stores every state: keep memory bounded
                break
            unstable.clear()
            p = _mujoco(case, integrator, n, repeats, budget=max(0.2, 3 * max_seconds))
            if unstable:
                p = Point(p.method, p.setting, p.seconds, p.evaluations, math.inf, math.inf,
                          math.inf, p.family)  # fmt: skip
            out.points.append(p)
            if p.error < 3e-14 or p.seconds > max_seconds:
                break


def cheapest(points: list[Point], targets=TARGETS, families=None) -> dict:
    """For each target error, the fastest point (per family) whose error reaches it.

    Returns ``{family: {target: Point or None}}``.

    Examples
    --------
    >>> pts = [Point("a", 10, 0.01, 40, 1e-4, 0, 0), Point("b", 10, 0.002, 40, 1e-6, 0, 0)]
    >>> cheapest(pts, targets=(1e-3, 1e-5))["ga_rotors"][1e-3].method
    'b'
    """
    families = families or sorted({p.family for p in points})
    table = {}
    for fam in families:
        row = {}
        for target in targets:
            ok = [p for p in points if p.family == fam and p.error <= target]
            row[target] = min(ok, key=lambda p: p.seconds) if ok else None
        table[fam] = row
    return table


# ----------------------------------------------------------------------------- reports

_FAMILY_ORDER = ("ga_rotors", "scipy", "numpy-quaternion", "MuJoCo")


def _fmt_ms(seconds: float) -> str:
    ms = 1e3 * seconds
    return f"{ms:.3g}"


def _label(t: float) -> str:
    return f"1e-{round(-math.log10(t))}"


def method_table(st: Study, targets=TARGETS) -> str:
    """Markdown: per method (rows) the least time (ms) that reaches each target (columns)."""
    methods = []
    for p in st.points:
        if p.method not in methods:
            methods.append(p.method)
    best = {t: min((p.seconds for p in st.points if p.error <= t), default=None) for t in targets}
    lines = [
        "| method | " + " | ".join(_label(t) for t in targets) + " |",
        "|---|" + "---|" * len(targets),
    ]
    for m in methods:
        cells = []
        for t in targets:
            ok = [p.seconds for p in st.points if p.method == m and p.error <= t]
            if not ok:
                cells.append("—")
                continue
            cell = _fmt_ms(min(ok))
            cells.append(f"**{cell}**" if min(ok) == best[t] else cell)
        lines.append(f"| {m} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def summary_table(studies: list[Study], targets=TARGETS) -> str:
    """Markdown: per case and target, the cheapest project method, the cheapest run of each
    peer, and how many times faster the project's method is than the fastest peer."""
    lines = [
        "| problem | target (rad) | cheapest method | ms | scipy DOP853 ms | "
        "numpy-quaternion ms | MuJoCo ms | fastest peer / ours |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for st in studies:
        table = cheapest(st.points, targets, _FAMILY_ORDER)
        for t in targets:
            ours = table["ga_rotors"][t]
            peers = [table[f][t] for f in _FAMILY_ORDER[1:]]
            cells = []
            for fam, p in zip(_FAMILY_ORDER[1:], peers, strict=True):
                present = any(q.family == fam for q in st.points)
                if p is None:
                    cells.append("not reached" if present else "n/a")
                else:
                    suffix = " (Euler)" if p.method == "mujoco_euler" else ""
                    cells.append(_fmt_ms(p.seconds) + suffix)
            reached = [p.seconds for p in peers if p is not None]
            if ours is None:
                ratio = "not reached"
            elif reached:
                ratio = f"{min(reached) / ours.seconds:.3g}×"
            else:
                ratio = "no peer reaches it"
            name = ours.method if ours else "—"
            ms = _fmt_ms(ours.seconds) if ours else "—"
            lines.append(f"| {st.case.name} | {_label(t)} | {name} | {ms} | " + " | ".join(cells)
                         + f" | {ratio} |")  # fmt: skip
    return "\n".join(lines)


def plot(st: Study, path) -> None:
    """Log–log work-precision figure of one case: error, energy and momentum drift against
    wall time and against evaluations; written atomically as PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 2, figsize=(10, 10), sharex="col")
    methods = []
    for p in st.points:
        if p.method not in methods:
            methods.append(p.method)
    cmap = plt.get_cmap("tab20")
    for i, m in enumerate(methods):
        pts = sorted((p for p in st.points if p.method == m), key=lambda p: p.seconds)
        style = "-" if pts[0].family == "ga_rotors" else "--"
        for row, attr in enumerate(("error", "energy_drift", "momentum_drift")):
            y = np.array([max(getattr(p, attr), 1e-17) for p in pts])
            keep = np.isfinite(y) & (y <= 10.0)  # a drift beyond 10 only says "diverged"
            for col, xattr in enumerate(("seconds", "evaluations")):
                x = np.array([getattr(p, xattr) for p in pts])
                axes[row, col].loglog(
                    x[keep],
                    y[keep],
                    style,
                    marker=".",
                    ms=3,
                    lw=1,
                    color=cmap(i % 20),
                    label=m if row == col == 0 else None,
                )
    titles = ("orientation error (rad)", "relative energy drift", "relative momentum drift")
    for row, title in enumerate(titles):
        axes[row, 0].set_ylabel(title)
        for col in range(2):
            axes[row, col].grid(True, which="major", alpha=0.3)
    axes[2, 0].set_xlabel("wall time (s), minimum of repeats")
    axes[2, 1].set_xlabel("right-hand-side evaluations (splitting: Strang stages)")
    fig.suptitle(st.case.title, y=0.995, fontsize=10)
    fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.97), ncol=6, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    _save_atomically(fig, path)
    plt.close(fig)


def _save_atomically(fig, path) -> None:
    from pathlib import Path

    from .files import atomic_write

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, lambda fh: fig.savefig(fh, format="png", dpi=60))
