"""Batched ensembles: classical RK4 for many torque-free bodies at once, on every core.

Struct-of-arrays layout (``q`` of shape (4, n), ``w`` of shape (3, n)): the innermost loop
runs over bodies, so LLVM turns each RK4 stage into SIMD arithmetic across 4 bodies at a
time; the bodies are split into chunks small enough to stay in the L1 cache (256 bodies ×
7 doubles = 14 KB) and each chunk takes all its steps before the next, so memory traffic
is one load and one store per chunk, not per step. Chunks are distributed over the cores
with ``prange``. The arithmetic is the package's kernels — q̇ from
:func:`ga_rotors.paths.quaternion.rate`, ω̇ from :func:`ga_rotors._kernels.free_euler_rates`
(inertia ratios hoisted out of the loops), and the RK4 combinations of
:mod:`ga_rotors.integrators._arith` — so a body of the ensemble follows exactly the
trajectory of ``get("rk4")`` on the quaternion path, bit for bit.
"""

from __future__ import annotations

import types

import numba
import numpy as np
from numba import prange

from ._jit import jit
from ._kernels import free_euler_rates
from .integrators._arith import axpy3, axpy4, rk4_sum3, rk4_sum4
from .paths.quaternion import rate

__all__ = ["CHUNK", "benchmark", "rk4_free"]

#: Bodies per chunk: a chunk's state (7 doubles a body) stays in L1 through all its steps.
CHUNK = 256


def inline_copy(kernel):
    """The same Python function as ``kernel``, compiled with ``inline="always"``, its calls to
    other compiled kernels rebound to their inline copies too.

    numba optimises each compiled function on its own and links callees afterwards, so a
    loop that calls kernels makes real calls and LLVM cannot vectorise across bodies; an
    inline copy puts the *same formula* (the same source, not a rewrite) into the loop.
    """
    found = _INLINE.get(kernel)
    if found is not None:
        return found
    func = kernel.py_func
    scope = dict(func.__globals__)
    for name in func.__code__.co_names:
        obj = scope.get(name)
        if isinstance(obj, numba.core.registry.CPUDispatcher):
            scope[name] = inline_copy(obj)
    copy = types.FunctionType(func.__code__, scope, func.__name__, func.__defaults__)
    found = numba.njit(inline="always", error_model="numpy")(copy)
    _INLINE[kernel] = found
    return found


_INLINE: dict = {}
_rate = inline_copy(rate)
_accel = inline_copy(free_euler_rates)
_axpy3, _axpy4 = inline_copy(axpy3), inline_copy(axpy4)
_sum3, _sum4 = inline_copy(rk4_sum3), inline_copy(rk4_sum4)


@numba.njit(inline="always", error_model="numpy")
def _rk4_body(x, v, h, inertia):
    """One RK4 step of one torque-free body: the operations of ``rk4_step`` on the
    quaternion path, in the same order, so results agree bit for bit."""
    half = 0.5 * h
    k1x = _rate(x, v)
    k1w = _accel(inertia, v)
    x2 = _axpy4(x, half, k1x)
    w2 = _axpy3(v, half, k1w)
    k2x = _rate(x2, w2)
    k2w = _accel(inertia, w2)
    x3 = _axpy4(x, half, k2x)
    w3 = _axpy3(v, half, k2w)
    k3x = _rate(x3, w3)
    k3w = _accel(inertia, w3)
    x4 = _axpy4(x, h, k3x)
    w4 = _axpy3(v, h, k3w)
    k4x = _rate(x4, w4)
    k4w = _accel(inertia, w4)
    return _sum4(x, h, k1x, k2x, k3x, k4x), _sum3(v, h, k1w, k2w, k3w, k4w)


@jit
def _rk4_chunk(q, w, lo, hi, inertia, h, nsteps):
    """Bodies lo..hi-1 through all steps; the inner loop over bodies vectorises."""
    q0, q1, q2, q3 = q[0, lo:hi], q[1, lo:hi], q[2, lo:hi], q[3, lo:hi]
    w0, w1, w2 = w[0, lo:hi], w[1, lo:hi], w[2, lo:hi]
    for _ in range(nsteps):
        for i in range(hi - lo):
            x, v = _rk4_body((q0[i], q1[i], q2[i], q3[i]), (w0[i], w1[i], w2[i]), h, inertia)
            q0[i] = x[0]
            q1[i] = x[1]
            q2[i] = x[2]
            q3[i] = x[3]
            w0[i] = v[0]
            w1[i] = v[1]
            w2[i] = v[2]


@jit(parallel=True)
def _rk4_soa(q, w, inertia, h, nsteps, chunk):
    n = q.shape[1]
    nchunks = (n + chunk - 1) // chunk
    for c in prange(nchunks):
        lo = c * chunk
        _rk4_chunk(q, w, lo, min(n, lo + chunk), inertia, h, nsteps)


def rk4_free(inertia, q, w, h: float, nsteps: int, chunk: int = CHUNK) -> None:
    """Advance n torque-free bodies ``nsteps`` RK4 steps of size ``h``, in place.

    Parameters
    ----------
    inertia : tuple of 3 floats
        Principal moments, shared by all bodies.
    q : ndarray, shape (4, n), float64, C-contiguous
        Orientations (scalar first), one column per body; overwritten.
    w : ndarray, shape (3, n), float64, C-contiguous
        Body angular velocities; overwritten.

    Examples
    --------
    >>> q = np.tile([[1.0], [0.0], [0.0], [0.0]], (1, 3))
    >>> w = np.tile([[0.0], [0.0], [2.0]], (1, 3))
    >>> rk4_free((1.0, 2.0, 3.0), q, w, 0.01, 100)
    >>> bool(np.allclose(q[:, 0], (np.cos(1.0), 0, 0, np.sin(1.0)), atol=1e-9))
    True
    """
    from .errors import InputError

    for name, a, rows in (("q", q, 4), ("w", w, 3)):
        if not (isinstance(a, np.ndarray) and a.dtype == np.float64 and a.ndim == 2
                and a.shape[0] == rows and a.flags.c_contiguous):  # fmt: skip
            raise InputError(f"{name}: expected a C-contiguous float64 array of shape ({rows}, n)")
    if q.shape[1] != w.shape[1]:
        raise InputError(
            f"q, w: expected the same number of bodies, got {q.shape[1]}, {w.shape[1]}"
        )
    _rk4_soa(q, w, tuple(float(i) for i in inertia), float(h), int(nsteps), int(chunk))


def benchmark(bodies: int = 10_000, steps: int = 1000, repeats: int = 5) -> str:
    """Body-steps per second of :func:`rk4_free` (minimum time of repeats after a warm-up).

    ``ga-rotors bench ensemble`` prints this line (10,000 bodies × 1,000 steps by default).

    Examples
    --------
    >>> print(benchmark(bodies=64, steps=10, repeats=1))
    RK4 ensemble: 64 bodies x 10 steps in ... ms (min of 1) = ... million body-steps/s on ...
    """
    import time

    rng = np.random.default_rng(1)
    q = rng.normal(size=(4, bodies))
    q /= np.linalg.norm(q, axis=0)
    w = rng.normal(size=(3, bodies))
    inertia = (1.0, 2.0, 3.0)
    rk4_free(inertia, q.copy(), w.copy(), 1e-3, 2)  # warm-up and JIT
    best = float("inf")
    for _ in range(repeats):
        qa, wa = q.copy(), w.copy()
        t0 = time.perf_counter()
        rk4_free(inertia, qa, wa, 1e-3, steps)
        best = min(best, time.perf_counter() - t0)
    rate_ = bodies * steps / best
    return (
        f"RK4 ensemble: {bodies} bodies x {steps} steps in {best * 1e3:.1f} ms "
        f"(min of {repeats}) = {rate_ / 1e6:.0f} million body-steps/s "
        f"on {numba.get_num_threads()} threads"
    )
