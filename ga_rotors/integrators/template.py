"""The fixed-step integrator whose steps are templates: declaration and running.

How a template integrator is declared (its steps, helpers, cost per step, step limit) is
the interface documented in :mod:`ga_rotors.integrators.base`; how its templates become
a compiled loop is :mod:`ga_rotors.integrators._source` (the text),
:mod:`ga_rotors.integrators._cache` (the module) and :mod:`ga_rotors.integrators._runner`
(running it). This module joins them to the interface, so that neither imports the other.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from . import _runner, loops
from .base import ANY_TORQUE, Integrator
from .problem import Problem

__all__ = ["TemplateIntegrator"]


@dataclass(frozen=True, eq=False)
class TemplateIntegrator(Integrator):
    """A fixed-step integrator whose steps are templates (see :mod:`~.base`).

    ``evaluations`` (keyword, required) is its cost per step in vector-field evaluations.

    Examples
    --------
    >>> from ga_rotors.integrators import FREE, get
    >>> rk4 = get("rk4")
    >>> isinstance(rk4, TemplateIntegrator), sorted(rk4.problems), rk4.steps[FREE].__name__
    (True, ['free', 'kinematic', 'motion', 'torqued'], 'rk4_step')
    >>> rk4.evaluations, rk4.adaptive
    (4, False)
    >>> TemplateIntegrator(name="my euler", order=1, description="", conserves=(),
    ...                    paths=("quaternion",), steps={}, evaluations=1)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: integrator name: expected an identifier, got 'my euler'
    >>> TemplateIntegrator(name="my_euler", order=1, description="", conserves=(),
    ...                    paths=("quaternion",), steps={}, evaluations=0)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: my_euler: evaluations (its cost per step, ...) must be a positive number, got 0
    """  # noqa: E501

    name: str
    order: int
    description: str
    conserves: frozenset[str]
    paths: frozenset[str]
    steps: Mapping[str, Callable]
    helpers: tuple[Callable, ...] = field(default=())
    torques: str = ANY_TORQUE
    step_limit: Callable | None = None
    step_limit_action: str = "warn"
    evaluations: float = field(kw_only=True)
    continues = True  # not a field: every template integrator continues a run

    def __post_init__(self):
        object.__setattr__(self, "conserves", frozenset(self.conserves))
        object.__setattr__(self, "paths", frozenset(self.paths))
        object.__setattr__(self, "steps", dict(self.steps))
        object.__setattr__(self, "_problems", frozenset(self.steps))
        # (problem, path, prepared run) of the last run: a run repeating it (a sweep, a
        # benchmark, the accuracy study's repeats) skips even the problem's look-up
        object.__setattr__(self, "_last", (None, None, None))
        self._validate_declaration()

    @property
    def problems(self) -> frozenset[str]:
        return self._problems

    def run(self, problem, path, x0, w0, t0, h, nsteps, every, *, chunk=None, progress=None,
            where="h", watch=False, stacklevel=2, parallel=True):  # fmt: skip
        """See :meth:`Integrator.run`: the same checks; a run in one piece without progress
        judges the step limit inside its one compiled call
        (:func:`~ga_rotors.integrators.loops.judged_run`) when the limit is measured
        (:func:`~ga_rotors.integrators.limits.measured`, every built-in limit), and
        watches the stored samples there too; only a run past the limit comes back to
        :meth:`check_step` (or :meth:`watch_step`), which builds the words and warns, or
        raises before any step for a method that refuses (lgvi).

        Examples
        --------
        >>> from ga_rotors.integrators import Problem, get
        >>> r = get("rk4").run(Problem((1.0, 2.0, 3.0)), "quaternion", (1.0, 0, 0, 0),
        ...                    (0.0, 0.0, 2.0), 0.0, 0.01, 100, 50)
        >>> r.t.tolist(), r.x.shape
        ([0.0, 0.5, 1.0], (3, 4))
        >>> get("lgvi").run(Problem((1.0, 2.0, 3.0)), "quaternion", (1.0, 0, 0, 0),
        ...                 (0.0, 0.0, 200.0), 0.0, 0.01, 100, 50)
        Traceback (most recent call last):
        ...
        ga_rotors.errors.InputError: h: lgvi cannot step h·|ω| = 2 (limit 1): ...
        """
        if chunk is None and progress is None and where is not None and type(problem) is Problem:
            last = self._last
            if last[0] is problem and last[1] == path:
                prep = last[2]
            else:
                prep = _runner.prepared(self, problem, path, checked=True)
                object.__setattr__(self, "_last", (problem, path, prep))
            if not prep.python_limit:  # one compiled call: the limit, the loop, the watch
                flags = prep.flags | loops.WATCH if watch and prep.flags else prep.flags
                result, value, bound, crossing = _runner.run_prepared(
                    prep, x0, w0, t0, h, nsteps, every, flags
                )
                if not value < bound:  # past the limit: the words, the warning or the error
                    self.check_step(problem, w0, h, nsteps, where, stacklevel + 1)
                    if result is None:  # refused, yet check_step let it pass: run unjudged
                        result = _runner.run_prepared(prep, x0, w0, t0, h, nsteps, every)[0]
                elif crossing >= 0:
                    self.watch_step(problem, result.t, result.w, h, nsteps, where, stacklevel + 1)
                return result
        return super().run(
            problem, path, x0, w0, t0, h, nsteps, every, chunk=chunk, progress=progress,
            where=where, watch=watch, stacklevel=stacklevel + 1, parallel=parallel,
        )  # fmt: skip

    def _whole(self, problem, path, x0, w0, t0, h, nsteps, every, progress):
        prep = _runner.prepared(self, problem, path)
        return _runner.run_prepared(prep, x0, w0, t0, h, nsteps, every, 0, progress)[0]

    def _pieces(self, problem, path, x0, w0, t0, h, nsteps, every, chunk, progress):
        prep = _runner.prepared(self, problem, path)
        return _runner.pieces(prep, x0, w0, t0, h, nsteps, every, chunk, progress)

    def _batch(self, batch, path, x0, w0, t0, h, nsteps, every, parallel, chunk):
        return _runner.run_batch(self, batch, path, x0, w0, t0, h, nsteps, every, parallel,
                                 _runner.BATCH_CHUNK if chunk is None else chunk)  # fmt: skip
