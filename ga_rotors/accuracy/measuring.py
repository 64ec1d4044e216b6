"""Measuring one run: its time (median with min–max of warm repeats), cost and errors.

A :class:`Point` is one run of one method at one setting (a step count, or a tolerance):
its wall time, its vector-field evaluations (the integrator's declared
``evaluations`` per step times the steps), its orientation error against the exact
solution and the drift of its invariants. A method that refuses a step (``lgvi`` from
h·|ω| = 1) is a point with ``note`` saying so: not run there, never a crash.

Errors: the largest geodesic angle 2·atan2(|vec(q_ref* q)|, |q_ref* q|₀) (rad) over the
run's samples (:data:`SAMPLES` of them, the same times for every method and peer); the
relative drift of the energy and of the conserved momentum (the space-frame L for a free
body; its vertical component L_Z for the heavy top) at the final time.
"""

from __future__ import annotations

import math
import statistics
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, StepLimitWarning
from .cases import Case

__all__ = [
    "SAMPLES",
    "Point",
    "measure",
    "not_run",
    "point",
    "round_steps",
    "runner",
    "sample_times",
    "timed",
]

#: Samples over a run at which the error is measured (and the largest taken): the run's
#: end points and the quarter times, common to every method and peer (a step count is
#: kept to multiples of 4 so each method lands on them).
SAMPLES = 4


@dataclass(frozen=True)
class Point:
    """One run: method, its setting (steps, or tolerance), cost and errors.

    ``seconds`` is the median of the timed repeats, ``seconds_min``/``seconds_max`` their
    range; ``note`` says why a point has no result (a refused step).

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
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
    seconds_min: float = math.nan
    seconds_max: float = math.nan
    note: str = ""


def timed(run: Callable, repeats: int, budget: float) -> tuple[tuple[float, float, float], object]:
    """((median, min, max) wall time of ``run()`` over repeats after one warm-up call, its
    result); repeats stop early once they have taken ``budget`` seconds.

    Examples
    --------
    >>> (median, low, high), value = timed(lambda: 7, repeats=3, budget=1.0)
    >>> value, low <= median <= high
    (7, True)
    """
    result = run()
    times: list[float] = []
    spent = 0.0
    for _ in range(max(1, repeats)):
        start = time.perf_counter()
        result = run()
        elapsed = time.perf_counter() - start
        times.append(elapsed)
        spent += elapsed
        if spent > budget:
            break
    return (statistics.median(times), min(times), max(times)), result


def sample_times(case: Case) -> np.ndarray:
    """The :data:`SAMPLES` + 1 times at which every run is compared with the reference.

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> sample_times(cases()["asymmetric_far"]).tolist()
    [0.0, 5.0, 10.0, 15.0, 20.0]
    """
    return np.linspace(0.0, case.duration, SAMPLES + 1)


def _exact(case: Case) -> np.ndarray:
    found = case._final.get("samples")
    if found is None:
        found = case._final["samples"] = np.asarray(case.reference.at(sample_times(case))[0])
    return found


def point(case: Case, method: str, setting, times, evaluations, q, w, family) -> Point:
    """A :class:`Point` from a run's orientations ``q`` at :func:`sample_times` (n, 4) and
    its final ω ``w[-1]`` (for a flight, its whole states and rates: :meth:`Case.errors`).

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> case = cases()["symmetric"]
    >>> exact = case.reference.at(sample_times(case))[0]
    >>> p = point(case, "exact", 1, (1e-3,) * 3, 0, exact, [case.w0], "ga_rotors")
    >>> p.error < 1e-15
    True
    """
    from .. import quaternion as Q

    seconds, low, high = times
    if case.flight is not None:  # a whole motion: q holds the states, position and all
        error, energy, momentum = case.errors(q, w)
        return Point(method, float(setting), seconds, float(evaluations), error, energy,
                     momentum, family, low, high)  # fmt: skip
    q = Q.normalize(np.asarray(q, dtype=float))
    error = float(np.max(Q.distance(_exact(case), q)))
    q_end = q[-1]
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
        low,
        high,
    )


def not_run(method: str, setting, family: str, note: str) -> Point:
    """A point where the method does not run (``note`` says why): no time, no error.

    Examples
    --------
    >>> not_run("lgvi", 16, "ga_rotors", "refused").error
    inf
    """
    inf = math.inf
    return Point(method, float(setting), math.nan, math.nan, inf, inf, inf, family, note=note)


def round_steps(n: int) -> int:
    """``n`` rounded up to a multiple of :data:`SAMPLES` (every run lands on the samples).

    Examples
    --------
    >>> round_steps(16), round_steps(23)
    (16, 24)
    """
    return -(-int(n) // SAMPLES) * SAMPLES


def runner(case: Case, method: str, n: int) -> tuple[Callable, object, str]:
    """(``run``, integrator, path): ``run()`` is one call of the public
    :meth:`~ga_rotors.integrators.Integrator.run` for ``method`` with n steps (a multiple of
    :data:`SAMPLES`), sampled at :func:`sample_times`; what :func:`measure` times, and the
    goal table re-times interleaved with a peer.

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> run, integ, path = runner(cases()["symmetric"], "rk4_euler", 400)
    >>> integ.name, path, run().x.shape
    ('rk4', 'euler', (5, 3))
    """
    from .. import euler
    from ..integrators import get

    problem = case.problem
    h = case.duration / n
    if method == "rk4_euler":
        x0 = euler.from_quaternion(np.asarray(case.q0), "ZYZ")
        integ, path = get("rk4"), "euler"
    else:
        (x0, w0), integ, path = case.start(), get(method), "quaternion"
    if method == "rk4_euler":
        w0 = np.asarray(case.w0)
    every = n // SAMPLES

    def run():
        return integ.run(problem, path, x0, w0, 0.0, h, n, every)

    return run, integ, path


def measure(case: Case, method: str, n: int, repeats: int = 5, budget: float = 0.5) -> Point:
    """One fixed-step run of ``method`` (``rk4_euler``: RK4 on the z–y′–z″ angles) with n
    steps (rounded up to a multiple of :data:`SAMPLES`), through the public
    :meth:`~ga_rotors.integrators.Integrator.run`.

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> p = measure(cases()["asymmetric_far"], "split4", 200, repeats=1)
    >>> p.error < 1e-6, p.evaluations
    (True, 1000.0)

    ``lgvi`` has no step from h·|ω| = 1: the point says so instead of failing.

    >>> measure(cases()["fast_spinner"], "lgvi", 256, repeats=1).note
    'not run: h·|ω| = 3.91 (limit 1)'
    """
    from .. import euler

    n = round_steps(n)
    run, integ, path = runner(case, method, n)
    # A step the method refuses (lgvi past h·|ω| = 1) is a point "not run there".
    if integ.step_limit is not None and integ.step_limit_action == "raise":
        limit = integ.step_limit(case.moments, case.w0, case.duration / n, n)
        if limit.exceeded:
            note = f"not run: {limit.quantity} = {limit.value:.3g} (limit {limit.limit:g})"
            return not_run(method, n, "ga_rotors", note)
    # The sweep runs coarse steps on purpose: their error is measured and plotted, so a
    # step past the method's limit is not silent here (StepLimitWarning is for runs whose
    # user does not see the error).
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StepLimitWarning)
        try:
            times, result = timed(run, repeats, budget)
        except InputError as exc:
            return not_run(method, n, "ga_rotors", f"not run: {exc}")
    cost = integ.evaluations * n
    if not result.complete:
        inf = math.inf
        return Point(method, n, times[0], cost, inf, inf, inf, "ga_rotors", times[1], times[2])
    x = result.x if path != "euler" else euler.to_quaternion("ZYZ", result.x)
    return point(case, method, n, times, cost, x, result.w, "ga_rotors")
