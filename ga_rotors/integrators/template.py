"""The fixed-step integrator whose steps are templates: declaration and running.

How a template integrator is declared (its steps, helpers, cost per step, step limit) is
the interface documented in :mod:`ga_rotors.integrators.base`; how its templates become
a compiled loop is :mod:`ga_rotors.integrators._codegen`. This module joins the two, so
that neither imports the other.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from . import _codegen, loops
from .base import ANY_TORQUE, Integrator

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
    (True, ['free', 'kinematic', 'torqued'], 'rk4_step')
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

    def run(self, problem, path, x0, w0, t0, h, nsteps, every, progress=None):
        """See :meth:`Integrator.run`: the same checks, with the step limit judged inside
        the run's one compiled call (:func:`~ga_rotors.integrators.loops.judged_run`) when
        the limit is measured (:func:`~ga_rotors.integrators.limits.measured`, every
        built-in limit); only a run past it comes back to :meth:`check_step`, which builds
        the words and warns, or raises before any step for a method that refuses (lgvi).

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
        last = self._last
        if last[0] is problem and last[1] == path:
            prep = last[2]
        else:
            prep = _codegen.prepared(self, problem, path, checked=True)
            object.__setattr__(self, "_last", (problem, path, prep))
        if progress is not None or prep.python_limit:
            self.check_step(problem, w0, h, nsteps, where="h")
            return _codegen.run_prepared(prep, x0, w0, t0, h, nsteps, every, 0, progress)[0]
        result, value, bound, _ = _codegen.run_prepared(
            prep, x0, w0, t0, h, nsteps, every, prep.flags
        )
        if not value < bound:  # past the limit: the words, and the warning or the error
            self.check_step(problem, w0, h, nsteps, where="h")
            if result is None:  # refused, yet check_step let it pass: run it unjudged
                result = _codegen.run_prepared(prep, x0, w0, t0, h, nsteps, every)[0]
        return result

    def run_watched(
        self, problem, path, x0, w0, t0, h, nsteps, every, progress=None, *, where="step",
        stacklevel=2,
    ):  # fmt: skip
        """See :meth:`Integrator.run_watched`: as :meth:`run`, the watch over the stored
        samples done in the same compiled call; only a limit past (at the start, or at a
        sample) comes back to :meth:`check_step` or :meth:`watch_step` for the words.

        Examples
        --------
        >>> from ga_rotors.integrators import Problem, get
        >>> r = get("rk4").run_watched(Problem((1.0, 2.0, 3.0)), "quaternion",
        ...                            (1.0, 0, 0, 0), (0.0, 0.0, 2.0), 0.0, 0.01, 100, 50)
        >>> r.t.tolist()
        [0.0, 0.5, 1.0]
        """
        prep = _codegen.prepared(self, problem, path, checked=True)
        if progress is not None or prep.python_limit:
            return super().run_watched(
                problem, path, x0, w0, t0, h, nsteps, every, progress, where=where,
                stacklevel=stacklevel + 1,
            )  # fmt: skip
        flags = prep.flags | loops.WATCH if prep.flags else 0
        result, value, bound, crossing = _codegen.run_prepared(
            prep, x0, w0, t0, h, nsteps, every, flags
        )
        if not value < bound:
            self.check_step(problem, w0, h, nsteps, where, stacklevel + 1)
            if result is None:  # refused, yet check_step let it pass: run it unjudged
                result = _codegen.run_prepared(prep, x0, w0, t0, h, nsteps, every)[0]
        elif crossing >= 0:
            self.watch_step(problem, result.t, result.w, h, nsteps, where, stacklevel + 1)
        return result

    def integrate(self, problem, path, x0, w0, t0, h, nsteps, every, progress=None):
        """See :meth:`Integrator.integrate`; the compiled loop is specialised once per
        problem and path, then each call only allocates the samples and runs it."""
        return _codegen.run_loop(self, problem, path, x0, w0, t0, h, nsteps, every, progress)

    def segments(self, problem, path, x0, w0, t0, h, nsteps, every, chunk, progress=None):
        """See :meth:`Integrator.segments`: :func:`~._codegen.run_segments`, the compiled
        loop continued piece by piece from the exact state at its step number."""
        return _codegen.run_segments(
            self, problem, path, x0, w0, t0, h, nsteps, every, chunk, progress
        )
