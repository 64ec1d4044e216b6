"""Compiled peers: what a user who writes or picks fast code would run instead.

Each solves the same ODE — y = (q, ω), q̇ = ½ q ⊗ (0, ω), I ω̇ = (I ω) × ω + τ, with the
heavy top's τ = mgl · (2(yz + wx), −2(xz − wy), 0) — from a right-hand side written
plainly here (:func:`field`, one ``@njit`` function, not the project's kernels), sampled
at the same times (:func:`~ga_rotors.accuracy.measuring.sample_times`), scored by the same
error (largest geodesic angle over the samples), and timed warm (compiled before timing;
median with min–max of repeats):

* ``njit_rk4``: thirty lines of ``@njit`` classical RK4, fixed step;
* ``njit_dop853``: a fixed-step ``@njit`` Dormand–Prince 8 of DOP853's tableau (the same
  coefficients as the project's ``dp8``), written straightforwardly with stage arrays;
* ``scipy_njit``: scipy's ``solve_ivp`` DOP853 calling the ``@njit`` right-hand side;
* ``numbalsoda_dop853``, ``numbalsoda_lsoda``: Hairer's DOP853 and LSODA compiled, with
  a numba ``cfunc`` right-hand side (``pip install numbalsoda``; it builds with a C++ and
  a Fortran compiler);
* ``diffrax_dopri8``: diffrax's Dopri8 with a PID step controller under ``jax.jit`` on
  the CPU, in double precision (``pip install diffrax``).

Adaptive peers take one tolerance ``tol`` as rtol = tol, atol = tol/1000 — scipy's
convention in :class:`ga_rotors.integrators.dop853.Dop853` too — so a tolerance means the
same for every adaptive method. A peer whose package is missing is skipped with a notice
(:func:`available`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import njit

from .cases import Case
from .measuring import SAMPLES, Point, point, round_steps, sample_times, timed

__all__ = ["ADAPTIVE", "FIXED", "available", "run_peer", "runner"]

#: Fixed-step compiled peers (setting: the number of steps) and their evaluations per step.
FIXED = {"njit_rk4": 4, "njit_dop853": 12}
#: Adaptive compiled peers (setting: the tolerance) and the package each needs.
ADAPTIVE = {
    "scipy_njit": "scipy",
    "numbalsoda_dop853": "numbalsoda",
    "numbalsoda_lsoda": "numbalsoda",
    "diffrax_dopri8": "diffrax",
}


@njit(cache=True)
def field(t, y, p, dy):
    """dy = ẏ for y = (q0, q1, q2, q3, ω1, ω2, ω3), p = (I1, I2, I3, mgl).

    Examples
    --------
    >>> dy = np.empty(7)
    >>> field(0.0, np.array([1.0, 0, 0, 0, 0, 0, 2.0]), np.array([1.0, 2.0, 3.0, 0.0]), dy)
    >>> dy.tolist()
    [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    """
    w, x, yy, z = y[0], y[1], y[2], y[3]
    w1, w2, w3 = y[4], y[5], y[6]
    i1, i2, i3, mgl = p[0], p[1], p[2], p[3]
    dy[0] = -0.5 * (x * w1 + yy * w2 + z * w3)
    dy[1] = 0.5 * (w * w1 + yy * w3 - z * w2)
    dy[2] = 0.5 * (w * w2 + z * w1 - x * w3)
    dy[3] = 0.5 * (w * w3 + x * w2 - yy * w1)
    t1 = 2.0 * mgl * (yy * z + w * x)
    t2 = -2.0 * mgl * (x * z - w * yy)
    dy[4] = ((i2 - i3) * w2 * w3 + t1) / i1
    dy[5] = ((i3 - i1) * w3 * w1 + t2) / i2
    dy[6] = (i1 - i2) * w1 * w2 / i3


@njit(cache=True)
def _rk4(y0, h, n, every, p):
    out = np.empty((n // every + 1, 7))
    y = y0.copy()
    k1, k2, k3, k4, tmp = np.empty(7), np.empty(7), np.empty(7), np.empty(7), np.empty(7)
    out[0] = y
    for i in range(n):
        t = i * h
        field(t, y, p, k1)
        for j in range(7):
            tmp[j] = y[j] + 0.5 * h * k1[j]
        field(t + 0.5 * h, tmp, p, k2)
        for j in range(7):
            tmp[j] = y[j] + 0.5 * h * k2[j]
        field(t + 0.5 * h, tmp, p, k3)
        for j in range(7):
            tmp[j] = y[j] + h * k3[j]
        field(t + h, tmp, p, k4)
        for j in range(7):
            y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
        if (i + 1) % every == 0:
            out[(i + 1) // every] = y
    return out


@njit(cache=True)
def _dop853_fixed(y0, h, n, every, p, a, b, c):
    stages = b.shape[0]
    out = np.empty((n // every + 1, 7))
    y = y0.copy()
    k = np.empty((stages, 7))
    tmp = np.empty(7)
    out[0] = y
    for i in range(n):
        t = i * h
        for s in range(stages):
            for j in range(7):
                acc = y[j]
                for r in range(s):
                    acc += h * a[s, r] * k[r, j]
                tmp[j] = acc
            field(t + c[s] * h, tmp, p, k[s])
        for j in range(7):
            acc = 0.0
            for s in range(stages):
                acc += b[s] * k[s, j]
            y[j] += h * acc
        if (i + 1) % every == 0:
            out[(i + 1) // every] = y
    return out


@njit(cache=True)
def _rhs_call(t, y, p):
    dy = np.empty(7)
    field(t, y, p, dy)
    return dy


def _params(case: Case) -> np.ndarray:
    return np.array([*case.moments, 0.0 if case.mgl is None else case.mgl])


def available(peer: str) -> str | None:
    """None if ``peer`` can run here, else the notice that says why it is skipped.

    Examples
    --------
    >>> available("njit_rk4") is None
    True
    """
    package = ADAPTIVE.get(peer)
    if package is None:
        return None
    try:
        __import__(package)
    except ImportError:
        return f"{peer}: {package} not installed (pip install {package}): skipped"
    return None


_CFUNCS: dict = {}


def _lsoda_rhs():
    """The numba ``cfunc`` numbalsoda calls: the same :func:`field` through raw pointers."""
    if "rhs" not in _CFUNCS:
        from numba import carray, cfunc, types

        sig = types.void(
            types.double, types.CPointer(types.double), types.CPointer(types.double),
            types.CPointer(types.double),
        )  # fmt: skip

        @cfunc(sig)
        def rhs(t, u, du, data):
            field(t, carray(u, 7), carray(data, 4), carray(du, 7))

        _CFUNCS["rhs"] = rhs
    return _CFUNCS["rhs"]


def _diffrax_solver():
    """A ``jax.jit``-compiled diffrax solve, the tolerance an argument (compiled once)."""
    if "diffrax" not in _CFUNCS:
        import diffrax
        import jax

        jax.config.update("jax_enable_x64", True)
        import jax.numpy as jnp

        def f(t, y, p):
            w, x, yy, z, w1, w2, w3 = (y[i] for i in range(7))
            i1, i2, i3, mgl = p[0], p[1], p[2], p[3]
            return jnp.stack([
                -0.5 * (x * w1 + yy * w2 + z * w3),
                0.5 * (w * w1 + yy * w3 - z * w2),
                0.5 * (w * w2 + z * w1 - x * w3),
                0.5 * (w * w3 + x * w2 - yy * w1),
                ((i2 - i3) * w2 * w3 + 2.0 * mgl * (yy * z + w * x)) / i1,
                ((i3 - i1) * w3 * w1 - 2.0 * mgl * (x * z - w * yy)) / i2,
                (i1 - i2) * w1 * w2 / i3,
            ])  # fmt: skip

        term = diffrax.ODETerm(f)
        solver = diffrax.Dopri8()

        @jax.jit
        def solve(y0, p, ts, tol):
            control = diffrax.PIDController(rtol=tol, atol=1e-3 * tol)
            sol = diffrax.diffeqsolve(
                term, solver, ts[0], ts[-1], None, y0, args=p,
                saveat=diffrax.SaveAt(ts=ts), stepsize_controller=control, max_steps=2**20,
            )  # fmt: skip
            return sol.ys, sol.stats["num_steps"]

        _CFUNCS["diffrax"] = solve
    return _CFUNCS["diffrax"]


def runner(case: Case, peer: str, setting) -> Callable:
    """``run()``: one warm-able call of a compiled peer, returning (samples (5, 7),
    evaluations); ``setting`` is a step count for :data:`FIXED` peers (a multiple of the
    samples), a tolerance for :data:`ADAPTIVE` ones.

    Examples
    --------
    >>> from ga_rotors.accuracy import cases
    >>> samples, evaluations = runner(cases()["symmetric"], "njit_rk4", 400)()
    >>> samples.shape, evaluations
    ((5, 7), 1600)
    """
    y0 = np.array([*case.q0, *case.w0])
    p = _params(case)
    marks = sample_times(case)
    if peer in FIXED:
        n = int(setting)
        h = case.duration / n
        if peer == "njit_rk4":
            return lambda: (_rk4(y0, h, n, n // SAMPLES, p), FIXED[peer] * n)
        from ..integrators import dp8

        stages = dp8.STAGES
        a = np.array(dp8.A).reshape(stages, stages)
        b, c = np.array(dp8.B), np.array(dp8.C)
        return lambda: (_dop853_fixed(y0, h, n, n // SAMPLES, p, a, b, c), FIXED[peer] * n)
    tol = float(setting)
    if peer == "scipy_njit":
        from scipy.integrate import solve_ivp

        def run():
            sol = solve_ivp(_rhs_call, (0.0, case.duration), y0, method="DOP853", t_eval=marks,
                            rtol=tol, atol=1e-3 * tol, args=(p,))  # fmt: skip
            return sol.y.T, sol.nfev

        return run
    if peer in ("numbalsoda_dop853", "numbalsoda_lsoda"):
        import numbalsoda

        solver = numbalsoda.dop853 if peer.endswith("dop853") else numbalsoda.lsoda
        address = _lsoda_rhs().address

        def run():
            ys, ok = solver(address, y0, marks, data=p, rtol=tol, atol=1e-3 * tol)
            return (ys if ok else np.full_like(ys, math.nan)), math.nan

        return run
    if peer == "diffrax_dopri8":
        import jax.numpy as jnp

        solve = _diffrax_solver()
        jy0, jp, jts, jtol = jnp.asarray(y0), jnp.asarray(p), jnp.asarray(marks), jnp.asarray(tol)

        def run():
            ys, steps = solve(jy0, jp, jts, jtol)
            ys.block_until_ready()
            return np.asarray(ys), 12 * int(steps)

        return run
    raise ValueError(f"unknown compiled peer {peer!r}")


def run_peer(case: Case, peer: str, setting, repeats: int, budget: float) -> Point:
    """One warm, timed run of a compiled peer (:func:`runner`): ``setting`` is a step count
    for :data:`FIXED` peers (rounded up to a multiple of the samples), a tolerance for
    :data:`ADAPTIVE` ones.

    Examples
    --------
    RK4 written plainly agrees with the project's RK4 to rounding (same method, same steps):

    >>> from ga_rotors.accuracy import cases, measure
    >>> case = cases()["heavy_top"]
    >>> ours, peer = measure(case, "rk4", 800, repeats=1), run_peer(case, "njit_rk4", 800, 1, 0.1)
    >>> peer.family, abs(peer.error - ours.error) < 1e-6 * ours.error
    ('compiled', True)
    """
    setting = round_steps(setting) if peer in FIXED else float(setting)
    times, (ys, evaluations) = timed(runner(case, peer, setting), repeats, budget)
    return _finish(case, peer, setting, times, evaluations, ys)


def _finish(case, peer, setting, times, evaluations, ys) -> Point:
    ys = np.asarray(ys)
    if ys.shape[0] != SAMPLES + 1 or not np.isfinite(ys).all():
        inf = math.inf
        return Point(peer, float(setting), times[0], float(evaluations), inf, inf, inf,
                     "compiled", times[1], times[2], note="failed")  # fmt: skip
    return point(case, peer, setting, times, evaluations, ys[:, :4], ys[:, 4:], "compiled")
