"""scipy's adaptive DOP853 (Dormand–Prince 8(5,3)) through the integrator interface.

Not a compiled loop: scipy drives the steps in Python and calls the right-hand side once
per evaluation. The right-hand side itself is the same compiled, specialised vector field
the fixed-step methods use (ẋ from the path's kinematics, ω̇ from Euler's equations with
exactly the declared torques), :func:`ga_rotors.integrators._runner.vector_field`, so
a comparison with the compiled methods measures the method and scipy's driver, not a
slower formula. Order 8, adaptive: a tolerance, not a step, sets the accuracy; the ``h``
and ``every`` of its ``run`` only fix the sample times. Conserves nothing.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from .base import FREE, KINEMATIC, MOTION, TORQUED, Integrator, LoopResult, register

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
    paths = frozenset({"rotor", "quaternion", "euler", "motor"})
    evaluations = 12  # per accepted step; the run's own count is in ``stats[0]``
    adaptive = True
    continues = True

    def __init__(self, rtol: float = 1e-10, atol: float | None = None):
        if not (0.0 < rtol < 1.0):
            raise InputError(f"rtol: expected a number in (0, 1), got {rtol!r}")
        self.rtol = float(rtol)
        self.atol = float(atol) if atol is not None else 1e-3 * self.rtol
        self._validate_declaration()

    @property
    def problems(self) -> frozenset[str]:
        return frozenset({FREE, TORQUED, KINEMATIC, MOTION})

    def _whole(self, problem, path, x0, w0, t0, h, nsteps, every, progress=None):
        from scipy.integrate import solve_ivp

        from ._runner import vector_field

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

    def _pieces(self, problem, path, x0, w0, t0, h, nsteps, every, chunk, progress=None):
        """See :meth:`Integrator.run`'s ``chunk``: scipy's DOP853 stepper kept alive
        between pieces (its step size, error history and dense output carry over), each
        piece the samples of about ``chunk`` steps read off its dense output exactly as
        ``solve_ivp(t_eval=...)`` reads them, so the pieces joined are the whole run's
        samples bit for bit.

        Examples
        --------
        >>> from ga_rotors.integrators import Problem
        >>> args = (Problem((1.0, 2.0, 3.0)), "quaternion", (1.0, 0, 0, 0), (0.1, 0, 2.0),
        ...         0.0, 0.01, 100, 10)
        >>> pieces = list(DOP853.run(*args, chunk=40))
        >>> [len(p.t) for p in pieces]
        [5, 4, 2]
        >>> bool((np.concatenate([p.x for p in pieces]) == DOP853.run(*args).x).all())
        True
        """
        from scipy.integrate import DOP853 as Stepper

        from ._runner import vector_field

        rhs = vector_field(problem, path)
        x0 = np.asarray(x0, dtype=np.float64)
        dim = x0.shape[0]
        kinematic = problem.kind == KINEMATIC
        y0 = x0 if kinematic else np.concatenate([x0, np.asarray(w0, dtype=np.float64)])
        per_piece = max(1, int(chunk) // every)
        t0, h, nsteps, every = float(t0), float(h), int(nsteps), int(every)
        count = nsteps // every + 1 + (1 if nsteps % every else 0)  # samples in the run

        def times(i, j):  # samples i..j-1 at the times solve_ivp(t_eval=...) is given
            return t0 + h * np.minimum(np.arange(i, j) * every, nsteps).astype(np.float64)

        with np.errstate(invalid="ignore", over="ignore"):
            solver = Stepper(rhs, t0, y0, float(times(count - 1, count)[0]), rtol=self.rtol,
                             atol=self.atol)  # fmt: skip
        params = np.asarray(problem.params()) if kinematic else None
        ts: list = []  # samples read off the dense output, not yet handed out
        ys: list = []
        read = 0  # samples read off so far
        handed = 0  # samples handed out so far
        while handed < count:
            size = per_piece + (0 if handed else 1)  # sample 0, then ``chunk`` steps' worth
            while read < min(count, handed + size) and solver.status == "running":
                with np.errstate(invalid="ignore", over="ignore"):
                    solver.step()
                if solver.status == "failed":
                    break
                # every sample this step covers, in one evaluation, as solve_ivp reads them
                ahead = min(count, int((solver.t - t0) / (h * every)) + 2)
                window = times(read, max(ahead, read))
                new = read + int(np.searchsorted(window, solver.t, side="right"))
                if new > read:
                    ts.append(window[: new - read])
                    ys.append(solver.dense_output()(window[: new - read]).T)
                    read = new
            t = np.concatenate(ts) if ts else times(0, 0)
            y = np.concatenate(ys) if ys else np.empty((0, y0.shape[0]))
            if handed == 0 and read == 0:  # failed before the first output time: y0 alone
                t, y = times(0, 1), y0[None, :]
            take = min(size, t.shape[0])
            ts, ys = [t[take:]], [y[take:]]
            t, y = t[:take], y[:take]
            handed += take
            complete = take == size or handed == count
            if progress is not None:
                progress(min(nsteps, (handed - 1) * every) if handed else 0)
            if kinematic:
                w = np.array([problem.omega.kernel(v, params) for v in t]).reshape(-1, 3)
            else:
                w = y[:, dim:]
            yield LoopResult(
                t=t, x=y[:, :dim], w=w, complete=complete, stats=np.array([float(solver.nfev)])
            )
            if not complete:
                return


DOP853 = register(Dop853())
