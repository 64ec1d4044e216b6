"""The sweeps: every method and peer on one case, over step counts or tolerances.

:func:`study` runs each project method over step counts ×``factor`` (stopping at
round-off or at a time budget), then each peer: the casual ones of
:mod:`~ga_rotors.accuracy.peers` and the compiled ones of
:mod:`~ga_rotors.accuracy.compiled_peers`. Missing peers are skipped with a notice in
:attr:`Study.notices`; a method that refuses a step is a point marked "not run there".

The grids are coarse (steps ×√2, tolerances ×√10), so the cheapest run reaching a target
can cost up to √2 times what the method needs there. :func:`refine` then looks between
the run that misses each goal target and the one that reaches it, for ours and for every
compiled peer alike, so the goal table compares each side's cheapest run, not the grid's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .cases import Case
from .measuring import SAMPLES, Point, measure, round_steps

__all__ = ["REFINE_TARGETS", "Study", "methods_for", "refine", "study"]


def methods_for(case: Case) -> list[str]:
    """The fixed-step methods that integrate ``case`` at their declared order (none at
    order 1), plus ``rk4_euler`` (RK4 on the paper's angles).

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> "split4" in methods_for(cases()["heavy_top"]), "dop853" in methods_for(cases()["symmetric"])
    (True, False)
    """
    from ..integrators import get, names, torque_conflict

    problem = case.problem
    out = []
    for name in names():
        method = get(name)
        if method.adaptive or problem.kind not in method.problems:
            continue
        terms = (*problem.torques, *problem.forces)
        if "quaternion" in method.paths and torque_conflict(method, terms) is None:
            out.append(name)
    # the paper's angles carry the orientation alone
    return out if case.flight is not None else [*out, "rk4_euler"]


def _counts(lo: int, hi: int, factor: float) -> list[int]:
    out, n = [], float(lo)
    while n <= hi:
        if not out or round(n) != out[-1]:
            out.append(round(n))
        n *= factor
    return out


@dataclass
class Study:
    """All points of one case, and the notices of skipped peers.

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> st = Study(cases()["symmetric"])
    >>> st.points, st.notices
    ([], [])
    """

    case: Case
    points: list[Point] = field(default_factory=list)
    notices: list[str] = field(default_factory=list)


#: Tolerances of the adaptive sweeps: 1e-3 to 3e-14 in half decades (scipy floors rtol
#: at 2.2e-14).
TOLERANCES = tuple(10.0**-k for k in np.arange(3.0, 14.0, 0.5))


def study(
    case: Case,
    methods: list[str] | None = None,
    *,
    factor: float = 2.0**0.5,
    floor: float = 3e-14,
    max_seconds: float = 0.3,
    repeats: int = 5,
    peers: bool = True,
    between: int = 3,
    log: Callable[[str], None] | None = None,
) -> Study:
    """Sweep every method (step counts ×``factor`` from ``case.steps``) and every peer,
    then :func:`refine` near the goal targets with ``between`` runs per bracket (0: none).

    A method's sweep stops once its error is below ``floor``, or grows again past 4× its
    best below 1e-9 (round-off), or one run takes longer than ``max_seconds``; a tolerance
    sweep runs from 1e-3 to 3e-14 in half decades (by ×10 when ``factor`` ≥ 2, the quick
    mode) and stops at the same time budget.

    Examples
    --------
    A two-point sweep of one method, without peers: doubling the steps of a fourth-order
    method divides its error by 2⁴.

    >>> import dataclasses
    >>> from ga_rotors.accuracy import cases
    >>> case = dataclasses.replace(cases()["asymmetric_far"], steps=(100, 200))
    >>> st = study(case, ["split4"], factor=2.0, repeats=1, peers=False, between=0)
    >>> [p.setting for p in st.points]
    [100.0, 200.0]
    >>> round(st.points[0].error / st.points[1].error)
    16
    """
    out = Study(case)
    say = log or (lambda _msg: None)
    budget = max(0.2, 3 * max_seconds)
    for method in methods or methods_for(case):
        best = math.inf
        for n in _counts(*case.steps, factor):
            p = measure(case, method, n, repeats, budget=budget)
            out.points.append(p)
            if p.note:  # refused here: finer steps may run
                continue
            # Stop at round-off: below the floor, or the error growing again (×4) once
            # below 1e-9, which only accumulated rounding does.
            if p.error < floor or p.seconds > max_seconds or (best < 1e-9 and p.error > 4 * best):
                break
            best = min(best, p.error)
        say(f"  {case.name}: {method} done")
    if peers:
        tolerances = TOLERANCES[::2] if factor >= 2.0 else TOLERANCES
        _compiled_sweeps(case, out, factor, tolerances, repeats, max_seconds, say)
        _casual_sweeps(case, out, factor, tolerances, repeats, max_seconds, say)
    if between:
        refine(out, between=between, repeats=repeats, budget=max(0.2, 3 * max_seconds))
        say(f"  {case.name}: refined near the goal targets")
    return out


#: The targets :func:`refine` looks near: the goal table's (tables.GOAL_TARGETS is this).
REFINE_TARGETS = (1e-3, 1e-6, 1e-9, 1e-12)
#: A method is refined at a target when its cheapest run there is within this factor of
#: its family's cheapest: a finer grid saves at most the grid's factor (√2), so a method
#: further behind cannot become the cheapest.
_CONTENDER = 1.5


def _fineness(p: Point) -> float:
    """Orders one method's runs from coarse to fine: step counts up, tolerances down."""
    return p.setting if p.setting >= 1 else 1.0 / p.setting


def refine(
    st: Study, targets=REFINE_TARGETS, *, between: int = 3, repeats: int = 5, budget: float = 0.9
) -> None:
    """Add ``between`` runs, evenly spaced in log(setting), between each contending
    method's coarsest run that reaches a target and the next coarser run (which misses
    it); where the grid's coarsest run already reaches it, one coarser run first (half the
    steps, or ten times the tolerance up to 1e-2) to bracket it. Ours and the compiled
    peers alike (the casual peers are 30–5000× slower: no finer grid changes what they
    show).

    Examples
    --------
    dp8 misses 1e-6 with 16 steps and reaches it with 32; three runs between find that
    20 steps reach it too:

    >>> from ga_rotors.accuracy import cases, measure
    >>> case = cases()["asymmetric_far"]
    >>> st = Study(case, [measure(case, "dp8", n, repeats=1) for n in (16, 32)])
    >>> refine(st, targets=(1e-6,), between=3, repeats=1)
    >>> [(p.setting, p.error <= 1e-6) for p in st.points]
    [(16.0, False), (32.0, True), (20.0, True), (24.0, True), (28.0, True)]
    """
    from . import compiled_peers

    for target in targets:
        for family in ("ga_rotors", "compiled"):
            mine = [p for p in st.points if p.family == family and not p.note]
            reached = [p for p in mine if p.error <= target]
            if not reached:
                continue
            best = min(p.seconds for p in reached)
            for method in dict.fromkeys(p.method for p in reached):
                runs = sorted((p for p in mine if p.method == method), key=_fineness)
                first = next(k for k, p in enumerate(runs) if p.error <= target)
                cheapest = min(p.seconds for p in runs[first:] if p.error <= target)
                if cheapest > _CONTENDER * best:
                    continue
                fixed = family == "ga_rotors" or method in compiled_peers.FIXED
                hi = runs[first].setting
                if first > 0:
                    lo = runs[first - 1].setting
                else:  # the grid's coarsest run reaches it: one run coarser, if it exists
                    lo = float(max(SAMPLES, round_steps(hi / 2))) if fixed else min(1e-2, hi * 10)
                    if lo == hi or _run(st, method, lo, repeats, budget).error <= target:
                        continue
                done = {p.setting for p in runs} | {lo}
                for k in range(1, between + 1):
                    setting = lo * (hi / lo) ** (k / (between + 1))
                    if fixed:
                        setting = float(round_steps(setting))
                    if setting not in done and min(lo, hi) < setting < max(lo, hi):
                        done.add(setting)
                        _run(st, method, setting, repeats, budget)


def _run(st: Study, method: str, setting: float, repeats: int, budget: float) -> Point:
    """One more run of ``method`` (ours or a compiled peer) at ``setting``, added to ``st``."""
    from . import compiled_peers

    if method in compiled_peers.FIXED or method in compiled_peers.ADAPTIVE:
        p = compiled_peers.run_peer(st.case, method, setting, repeats, budget)
    else:
        p = measure(st.case, method, int(setting), repeats, budget=budget)
    st.points.append(p)
    return p


def _compiled_sweeps(case, out, factor, tolerances, repeats, max_seconds, say):
    from . import compiled_peers as C

    if case.flight is not None:
        out.notices.append(f"{case.name}: compiled peers skipped: they integrate the rotation "
                           "alone (benchmarks/bench_motion.py has a plain @njit RK4 of the "
                           "whole motion)")  # fmt: skip
        return

    budget = max(0.2, 3 * max_seconds)
    for peer in C.FIXED:
        best = math.inf
        for n in _counts(*case.steps, factor):
            p = C.run_peer(case, peer, n, repeats, budget)
            out.points.append(p)
            if p.error < 3e-14 or p.seconds > max_seconds or (best < 1e-9 and p.error > 4 * best):
                break
            best = min(best, p.error)
        say(f"  {case.name}: {peer} done")
    for peer in C.ADAPTIVE:
        notice = C.available(peer)
        if notice is not None:
            out.notices.append(notice)
            continue
        for tol in tolerances:
            p = C.run_peer(case, peer, tol, repeats, budget)
            out.points.append(p)
            if p.seconds > 4 * max_seconds:
                break
        say(f"  {case.name}: {peer} done")


def _casual_sweeps(case, out, factor, tolerances, repeats, max_seconds, say):
    from .peers import dop853_scipy

    for rtol in tolerances:
        p = dop853_scipy(case, rtol, repeats, budget=max(0.2, 3 * max_seconds))
        out.points.append(p)
        if p.seconds > 4 * max_seconds:
            break
    say(f"  {case.name}: scipy DOP853 done")
    numpy_quaternion_sweep(case, out, tolerances, repeats, max_seconds)
    say(f"  {case.name}: numpy-quaternion done")
    mujoco_sweep(case, out, factor, repeats, max_seconds)
    say(f"  {case.name}: MuJoCo done")


def numpy_quaternion_sweep(case, out, tolerances, repeats, max_seconds):
    """numpy-quaternion over ``tolerances`` (kinematics only: needs the exact ω(t))."""
    from .peers import numpy_quaternion

    if case.flight is not None:
        out.notices.append(f"{case.name}: numpy-quaternion skipped: it integrates "
                           "orientations, not a body moving through space")  # fmt: skip
        return
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
        p = numpy_quaternion(case, tol, repeats, budget=max(0.2, 3 * max_seconds))
        if p is None:
            out.notices.append(
                f"{case.name}: numpy-quaternion at tolerance {tol:.1e} did not finish in 10 s "
                "(scipy's ode DOP853 under it never returned); its sweep ends there"
            )
            break
        out.points.append(p)
        if p.seconds > 4 * max_seconds:
            break


def mujoco_sweep(case, out, factor, repeats, max_seconds):
    """MuJoCo's RK4 and Euler over step counts (rollout keeps every state: ≤ 2²⁰ steps)."""
    from .peers import mujoco_run

    if case.flight is not None:
        out.notices.append(f"{case.name}: MuJoCo skipped: its model here is a body turning "
                           "about a fixed point")  # fmt: skip
        return
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
            p = mujoco_run(case, integrator, n, repeats, budget=max(0.2, 3 * max_seconds))
            if unstable:
                inf = math.inf
                p = Point(p.method, p.setting, p.seconds, p.evaluations, inf, inf, inf,
                          p.family, p.seconds_min, p.seconds_max, "unstable")  # fmt: skip
            out.points.append(p)
            if p.error < 3e-14 or p.seconds > max_seconds:
                break
