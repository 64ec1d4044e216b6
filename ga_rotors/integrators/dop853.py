"""scipy's adaptive DOP853 (Dormand–Prince 8(5,3)) through the integrator interface.

Not a compiled loop: scipy drives the steps in Python and calls the right-hand side once
per evaluation. The right-hand side itself is the same compiled, specialised vector field
the fixed-step methods use (ẋ from the path's kinematics, ω̇ from Euler's equations with
exactly the declared torques), :func:`ga_rotors.integrators._codegen.vector_field`, so
a comparison with the compiled methods measures the method and scipy's driver, not a
slower formula. Order 8, adaptive: a tolerance, not a step, sets the accuracy; the ``h``
and ``every`` of :meth:`Dop853.run` only fix the sample times. Conserves nothing.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from .base import FREE, KINEMATIC, TORQUED, Integrator, LoopResult, register

__all__ = ["DOP853", "Dop853"]


class Dop853(Integrator):
    """scipy ``solve_ivp(method="DOP853")`` on (orientation, ω) with a compiled right-hand side.

    Parameters
    ----------
    rtol, atol : float
        scipy's tolerances (relative, absolute).

    Examples
    --------
    >>> from ga_rotors.integrators import Problem
    >>> run = Dop853(rtol=1e-10).run(Problem((1.0, 2.0, 3.0)), "quaternion",
    ...                              (1.0, 0, 0, 0), (0.0, 0.0, 2.0), 0.0, 0.5, 2, 1)
    >>> bool(np.allclose(run.x[-1], (np.cos(1.0), 0, 0, np.sin(1.0)), atol=1e-9))
    True
    >>> int(run.stats[0]) > 0  # right-hand-side evaluations
    True
    """

    name = "dop853"
    order = 8
    description = "scipy's adaptive Dormand–Prince 8(5,3), compiled right-hand side"
    conserves = frozenset()
    paths = frozenset({"rotor", "quaternion", "euler"})
    evaluations = 12  # per accepted step; the run's own count is in ``stats[0]``
    adaptive = True

    def __init__(self, rtol: float = 1e-10, atol: float | None = None):
        if not (0.0 < rtol < 1.0):
            raise InputError(f"rtol: expected a number in (0, 1), got {rtol!r}")
        self.rtol = float(rtol)
        self.atol = float(atol) if atol is not None else 1e-3 * self.rtol
        self._validate_declaration()

    @property
    def problems(self) -> frozenset[str]:
        return frozenset({FREE, TORQUED, KINEMATIC})

    def integrate(self, problem, path, x0, w0, t0, h, nsteps, every, progress=None):
        from scipy.integrate import solve_ivp

        from ._codegen import vector_field

        rhs = vector_field(problem, path)
        x0 = np.asarray(x0, dtype=np.float64)
        dim = x0.shape[0]
        kinematic = problem.kind == KINEMATIC
        y0 = x0 if kinematic else np.concatenate([x0, np.asarray(w0, dtype=np.float64)])

        marks = list(range(0, nsteps + 1, every))
        if marks[-1] != nsteps:
            marks.append(nsteps)
        times = t0 + h * np.array(marks, dtype=np.float64)
        with np.errstate(invalid="ignore", over="ignore"):  # a blow-up ends the run, below
            sol = solve_ivp(
                rhs, (times[0], times[-1]), y0, method="DOP853", t_eval=times, rtol=self.rtol,
                atol=self.atol,
            )  # fmt: skip
        if not isinstance(sol.y, np.ndarray) or sol.y.ndim != 2 or sol.y.shape[1] == 0:
            # failed before the first output time (the Euler-angle path started at its
            # singularity θ = 0: scipy returns a list here, which crashed the run)
            sol.t, sol.y = times[:1], y0[:, None]
        y = sol.y.T
        if progress is not None:
            progress(nsteps)
        if kinematic:
            w = np.array([problem.omega.kernel(t, np.asarray(problem.params())) for t in sol.t])
        else:
            w = y[:, dim:]
        return LoopResult(
            t=sol.t,
            x=y[:, :dim],
            w=w,
            complete=bool(sol.success) and sol.t.shape == times.shape,
            stats=np.array([float(sol.nfev)]),
        )


DOP853 = register(Dop853())
