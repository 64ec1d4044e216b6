"""The fixed-step integrator whose steps are templates: declaration and running.

How a template integrator is declared (its steps, helpers, cost per step, step limit) is
the interface documented in :mod:`ga_rotors.integrators.base`; how its templates become
a compiled loop is :mod:`ga_rotors.integrators._codegen`. This module joins the two, so
that neither imports the other.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from . import _codegen
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
        self._validate_declaration()

    @property
    def problems(self) -> frozenset[str]:
        return self._problems

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
