"""What accuracy costs in time: a work-precision study of the integrator catalogue.

For each reference problem (:func:`cases`) every method runs over a sweep of step counts
(adaptive peers: of tolerances); each run's error against the exact solution, its wall
time and its vector-field evaluations are recorded as a :class:`Point`. From the points,
:func:`cheapest` picks, for each target error, the cheapest run that reaches it, and
:func:`goal` re-times our best against the fastest compiled peer, interleaved.

Modules, one job each:

* :mod:`~ga_rotors.accuracy.cases` — the reference problems;
* :mod:`~ga_rotors.accuracy.measuring` — one run: time, cost, error (:func:`measure`);
* :mod:`~ga_rotors.accuracy.peers` — peers as a casual user gets them (scipy, numpy-quaternion,
  MuJoCo);
* :mod:`~ga_rotors.accuracy.compiled_peers` — peers a user who wants speed writes or picks
  (``@njit`` RK4 and DOP853, scipy with an ``@njit`` right-hand side, numbalsoda, diffrax);
* :mod:`~ga_rotors.accuracy.sweeps` — the sweeps (:func:`study`), refined near the goal's
  targets (:func:`refine`);
* :mod:`~ga_rotors.accuracy.tables` — the cheapest-method, per-method and goal tables;
* :mod:`~ga_rotors.accuracy.plots` — the work-precision figures;
* :mod:`~ga_rotors.accuracy.report` — ``ga-rotors bench accuracy``: the whole study as text,
  and the generated block of ``docs/accuracy.md``.

Measurement rules. Every project method runs compiled, called through its public API
(:meth:`ga_rotors.integrators.Integrator.run`); each time is the median of warm repeats
(a warm-up call first pays any JIT compilation), with its min–max range. The error is the
largest geodesic angle 2·atan2(|vec(q_ref* q)|, |scalar(q_ref* q)|) over the same sample
times for every method and peer.

Examples
--------
>>> from ga_rotors import accuracy
>>> p = accuracy.measure(accuracy.cases()["asymmetric_far"], "dp8", 400, repeats=1)
>>> p.error < 1e-9, p.evaluations
(True, 4800.0)
"""

from .cases import Case, cases
from .measuring import SAMPLES, Point, measure
from .plots import plot
from .sweeps import Study, methods_for, refine, study
from .tables import (
    GOAL_RATIO,
    GOAL_TARGETS,
    TARGETS,
    Goal,
    cheapest,
    goal,
    goal_table,
    method_table,
    summary_table,
)

__all__ = [
    "GOAL_RATIO",
    "GOAL_TARGETS",
    "SAMPLES",
    "TARGETS",
    "Case",
    "Goal",
    "Point",
    "Study",
    "cases",
    "cheapest",
    "goal",
    "goal_table",
    "measure",
    "method_table",
    "methods_for",
    "plot",
    "refine",
    "study",
    "summary_table",
]
