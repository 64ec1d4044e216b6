"""Batched ensembles: many bodies at once, on every core.

:func:`scene_samples` and :func:`run_samples` integrate n variations of a scene (per-sample
inertia, initial state and parameters of the declared effects) with the scene's own
integrator and step, and return the states at chosen times; each sample equals the single
run of the same scene bit for bit. :func:`rk4_free` is the torque-free RK4 with one shared
inertia that ``ga-rotors bench ensemble`` measures.

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

import re
import types
from dataclasses import dataclass
from math import isfinite

import numba
import numpy as np
from numba import prange

from . import _modules
from ._jit import jit
from ._kernels import angle_any_norm, euler_coefficients, free_euler_rates
from .body import MIN_MOMENT_RATIO
from .errors import InputError
from .files import aligned_empty
from .integrators._arith import axpy3, axpy4, rk4_sum3, rk4_sum4
from .paths.quaternion import rate

__all__ = [
    "CHUNK",
    "FAST_KEYS",
    "EnsembleRun",
    "SceneSamples",
    "benchmark",
    "rk4_free",
    "run_columns",
    "run_samples",
    "scene_samples",
]

#: Bodies per chunk: a chunk's state (7 doubles a body) stays in L1 through all its steps.
CHUNK = 256


def inline_copy(kernel, replace: tuple = ()):
    """The same Python function as ``kernel``, compiled with ``inline="always"``, its calls to
    other compiled kernels rebound to their inline copies too.

    numba optimises each compiled function on its own and links callees afterwards, so a
    loop that calls kernels makes real calls and LLVM cannot vectorise across bodies; an
    inline copy puts the *same formula* (the same source, not a rewrite) into the loop.
    ``replace``: pairs (kernel, stand-in) — wherever the copies would call that kernel
    they call the stand-in (the batched loops replace :func:`~ga_rotors._kernels.
    euler_coefficients` by a look-up of the values that function computed beforehand).
    """
    key = (kernel, replace)
    found = _INLINE.get(key)
    if found is not None:
        return found
    for old, new in replace:
        if kernel is old:
            return new
    func = kernel.py_func
    scope = dict(func.__globals__)
    for name in func.__code__.co_names:
        obj = scope.get(name)
        if isinstance(obj, numba.core.registry.CPUDispatcher):
            scope[name] = inline_copy(obj, replace)
    copy = types.FunctionType(func.__code__, scope, func.__name__, func.__defaults__)
    found = numba.njit(inline="always", error_model="numpy")(copy)
    _INLINE[key] = found
    return found


@numba.njit(inline="always", error_model="numpy")
def stored_coefficients(inertia):
    """:func:`~ga_rotors._kernels.euler_coefficients` of a body, stored beside its moments
    in the batched loops' 9-tuple ``inertia`` (moments, then the six coefficients)."""
    return inertia[3:9]


#: What a batched loop's step calls instead of computing the coefficients (see
#: :func:`inline_copy`): each body's are computed once, by euler_coefficients itself.
STORED = ((euler_coefficients, stored_coefficients),)


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
    for name, a, rows in (("q", q, 4), ("w", w, 3)):
        if not (isinstance(a, np.ndarray) and a.dtype == np.float64 and a.ndim == 2
                and a.shape[0] == rows and a.flags.c_contiguous):  # fmt: skip
            raise InputError(f"{name}: expected a C-contiguous float64 array of shape ({rows}, n)")
    if q.shape[1] != w.shape[1]:
        raise InputError(
            f"q, w: expected the same number of bodies, got {q.shape[1]}, {w.shape[1]}"
        )
    _rk4_soa(q, w, tuple(float(i) for i in inertia), float(h), int(nsteps), int(chunk))


#: Bytes of arrays and body-steps a repeat that :func:`benchmark` takes at most: a
#: benchmark's size is a number typed on a command line, refused when absurd.
BENCHMARK_MEMORY = 2 * 2**30
BENCHMARK_BODY_STEPS = 10**10


def benchmark(bodies: int = 10_000, steps: int = 1000, repeats: int = 5) -> str:
    """Body-steps per second of :func:`rk4_free` (minimum time of repeats after a warm-up).

    ``ga-rotors bench ensemble`` prints this line (10,000 bodies × 1,000 steps by default).

    Examples
    --------
    >>> print(benchmark(bodies=64, steps=10, repeats=1))
    RK4 ensemble: 64 bodies x 10 steps in ... ms (min of 1) = ... million body-steps/s on ...
    >>> benchmark(bodies=-5)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: bodies: expected a positive integer, got -5
    """
    import time

    for name, value in (("bodies", bodies), ("steps", steps), ("repeats", repeats)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise InputError(f"expected a positive integer, got {value!r}", key=name)
    arrays = bodies * 7 * 8 * 2  # q and ω, and the copies each repeat runs on
    if arrays > BENCHMARK_MEMORY:
        raise InputError(
            f"{bodies:.3g} bodies need {arrays / 2**30:.3g} GiB of arrays "
            f"(at most {BENCHMARK_MEMORY / 2**30:g} GiB)",
            key="bodies",
        )
    if bodies * steps > BENCHMARK_BODY_STEPS:
        raise InputError(
            f"{bodies:.3g} bodies x {steps:.3g} steps is {bodies * steps:.3g} body-steps a "
            f"repeat, {repeats + 1} times (at most {BENCHMARK_BODY_STEPS:.3g}: about half a "
            "minute each on two cores)",
            key="steps",
        )
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


# ---------------------------------------------------------------------------- real scenes
#
# The loop below is a template: for one (integrator, problem kind, path, torques) it is
# compiled with ``step`` bound to an inline copy of the generated module's step — the very
# function a single run's loop calls (ga_rotors.integrators._codegen.specialise), so a
# sample follows the single run of the same scene bit for bit. Per-sample inertia, state
# and torque parameters are stored one row per component (structure of arrays, params
# of shape (P, n)) and read per body; the inner loop runs over the bodies of one
# L1-sized chunk, as in rk4_free above.
#
# Two things keep that inner loop vectorised (a stand-alone copy of this loop, one thread,
# heavy top with the general gravity kernel: 87 -> 104 M body-steps/s for the two):
# * each body's Euler coefficients (six divisions: euler_coefficients) are computed once
#   per call, by the same compiled function, and kept in a chunk-sized scratch array; the
#   step reads them back through ``stored_coefficients`` (see STORED) instead of dividing
#   in every stage of every step, where a single run's loop computes them once because
#   its inertia is a loop invariant. ``inertia`` is then a 9-tuple (moments first, so a
#   template reading inertia[0..2] reads the moments);
# * the parameters are read from one row slice per parameter taken per chunk
#   (``chunk_params``): indexing params[j, lo + i] made LLVM gather them one by one.


@numba.njit(inline="always", error_model="numpy")
def record_states(out, m, j, x, v):
    """The batched loop's outputs (``run_samples``): body j's state x, v at output time m
    into ``out`` = (states (time, 4, body), rates (time, 3, body))."""
    out_x, out_w = out
    for k in range(4):
        out_x[m, k, j] = x[k]
    for k in range(3):
        out_w[m, k, j] = v[k]


_angle_any_norm = inline_copy(angle_any_norm)


@numba.njit(inline="always", error_model="numpy")
def record_store(out, m, j, x, v):
    """A sweep's outputs, in its store's layout: ``out`` = (q (sample, time, 4), ω (sample,
    time, 3), angle from the nominal (sample, time), the nominal (time, 4)); x is the
    quaternion (the quaternion path's state), the angle
    :func:`~ga_rotors._kernels.angle_any_norm`'s, computed while the state is at hand."""
    out_q, out_w, angle, nominal = out
    for k in range(4):
        out_q[j, m, k] = x[k]
    for k in range(3):
        out_w[j, m, k] = v[k]
    b = (nominal[m, 0], nominal[m, 1], nominal[m, 2], nominal[m, 3])
    angle[j, m] = _angle_any_norm(x, b)


@numba.njit(inline="always", error_model="numpy")
def fill_row(dest, cols, j, scale, value, lo, hi):
    """dest[i] for samples lo + i < hi: cols[j, lo + i] · scale, or ``value`` if j < 0."""
    if j < 0:
        dest[: hi - lo] = value
    else:
        row = cols[j]
        for i in range(hi - lo):
            dest[i] = row[lo + i] * scale


_TINY = float(np.finfo(float).tiny)


@numba.njit(inline="always", error_model="numpy")
def refused_rows(inertia, w, n):
    """:func:`_refused` of the first n samples of moments and rates stored by row."""
    refused = 0
    for i in range(n):
        m = (inertia[0, i], inertia[1, i], inertia[2, i])
        refused += _refused_one(m, (w[0, i], w[1, i], w[2, i]), _TINY, MIN_MOMENT_RATIO)
    return refused > 0


def _scene_chunk(q, w, inertia, params, lo, hi, t0, h, marks, out):
    q0, q1, q2, q3 = q[0, lo:hi], q[1, lo:hi], q[2, lo:hi], q[3, lo:hi]
    w0, w1, w2 = w[0, lo:hi], w[1, lo:hi], w[2, lo:hi]
    i0, i1, i2 = inertia[0, lo:hi], inertia[1, lo:hi], inertia[2, lo:hi]
    c = np.empty((6, hi - lo))
    for i in range(hi - lo):
        e = euler_coefficients((i0[i], i1[i], i2[i]))
        for j in range(6):
            c[j, i] = e[j]
    c0, c1, c2, c3, c4, c5 = c[0], c[1], c[2], c[3], c[4], c[5]
    rows = chunk_params(params, lo, hi)  # noqa: F821 (bound when compiled)
    done = 0
    for m in range(marks.shape[0]):
        for k in range(done, marks[m]):
            t = t0 + k * h
            for i in range(hi - lo):
                x, v = step(  # noqa: F821 (step, body_params: bound when compiled)
                    t, (q0[i], q1[i], q2[i], q3[i]), (w0[i], w1[i], w2[i]), h,
                    body_inertia(i0[i], i1[i], i2[i], (c0[i], c1[i], c2[i], c3[i], c4[i], c5[i])),  # noqa: F821
                    body_params(rows, i),  # noqa: F821
                )  # fmt: skip
                q0[i] = x[0]
                q1[i] = x[1]
                q2[i] = x[2]
                q3[i] = x[3]
                w0[i] = v[0]
                w1[i] = v[1]
                w2[i] = v[2]
        done = marks[m]
        for i in range(hi - lo):
            record(out, m, lo + i, (q0[i], q1[i], q2[i], q3[i]), (w0[i], w1[i], w2[i]))  # noqa: F821


def _scene_soa(q, w, inertia, params, t0, h, marks, out, chunk):
    n = q.shape[1]
    nchunks = (n + chunk - 1) // chunk
    for c in prange(nchunks):
        lo = c * chunk
        chunk_loop(q, w, inertia, params, lo, min(n, lo + chunk), t0, h, marks, out)  # noqa: F821


def _sweep_soa(cols, src, scale, base, params, t0, h, marks, out, chunk):
    """The samples of ``cols`` (rows, n) through the chunk loop, into ``out``; False if a
    sample's inputs may be refused (see :func:`_refused`), with ``out`` then unfinished.

    Sample i's moments and rate are ``base``'s (moments, rate, orientation: 10 numbers)
    but where ``src[k] >= 0``: there cols[src[k], i] · scale[k]. They are made a chunk
    at a time in small arrays that stay in the cache, and the outputs go straight into
    ``out``'s arrays, whose first axis is the sample.
    """
    n = cols.shape[1]
    q, w = np.empty((4, chunk)), np.empty((3, chunk))
    inertia, rows = np.empty((3, chunk)), np.empty((params.size, chunk))
    for j in range(params.size):
        rows[j, :] = params[j]
    out_q, out_w, angle, nominal = out
    for lo in range(0, n, chunk):
        hi = min(n, lo + chunk)
        for k in range(6):
            fill_row(inertia[k] if k < 3 else w[k - 3], cols, src[k], scale[k], base[k], lo, hi)
        for k in range(4):
            q[k, : hi - lo] = base[6 + k]
        if refused_rows(inertia, w, hi - lo):
            return False
        part = (out_q[lo:hi], out_w[lo:hi], angle[lo:hi], nominal)
        chunk_loop(q, w, inertia, rows, 0, hi - lo, t0, h, marks, part)  # noqa: F821
    return True


_SCENE_LOOPS: dict = {}


def _compiled_scene_loop(
    integrator, problem, path: str, parallel: bool = True, stored=True, sweep=False
):
    """The batched loop for one specialisation, compiled once per installation.

    Thread-safe: made and loaded under :data:`ga_rotors._modules.GENERATED_LOCK` (the
    threads of a sweep all start on the same loop).

    Written as a module next to the generated single-run module (same cache directory,
    its name carrying that module's digest), so numba's cache keeps the machine code
    across processes — each Dask worker would otherwise compile it again.
    ``parallel=False`` runs the chunks one after the other in the calling thread: for
    callers that run several loops at once in one process (threads of a Dask worker),
    which numba's default threading layer does not allow for parallel loops.
    ``stored=False`` passes each body's moments alone as ``inertia`` (the coefficients
    divided out in every stage): for a step template that unpacks ``inertia`` into three
    names, which a 9-tuple cannot be. ``sweep=True`` gives :func:`_sweep_soa` instead,
    the chunk loop recording in a sweep store's layout (:func:`record_store`), serial.
    """
    with _modules.GENERATED_LOCK:
        return _load_scene_loop(integrator, problem, path, parallel, stored, sweep)


def _load_scene_loop(integrator, problem, path: str, parallel: bool, stored: bool, sweep: bool):
    import importlib.util
    import inspect

    from .files import write_text
    from .integrators._codegen import specialise

    spec = specialise(integrator, problem, path)
    gen = spec.module.__name__
    chunk_params, body_params = _params_source(problem)
    # gen_batch-<the single-run module's stem without gen_>: the cache's own naming
    # (version and digest last), so `ga-rotors cache` lists, prunes and clears it too.
    stem = gen.removeprefix("_ga_rotors_gen_")
    kind = ("sweep" if sweep else "par" if parallel else "") + ("" if stored else "div")
    name = f"_ga_rotors_gen_batch{kind}-{stem}"
    found = _SCENE_LOOPS.get(name)
    if found is not None:
        return found

    def text(cache: bool) -> str:
        replace = "STORED" if stored else "()"
        return (
            f'"""Generated by ga_rotors.ensemble for {gen}; do not edit."""\n\n'
            "import sys\n\nimport numpy as np\nfrom numba import prange\n\n"
            "from ga_rotors._jit import jit\n"
            "from ga_rotors._kernels import euler_coefficients\n"
            "from ga_rotors.ensemble import (\n"
            "    STORED, fill_row, inline_copy, record_states, record_store, refused_rows\n"
            ")\n\n"
            f"step = inline_copy(sys.modules[{gen!r}].step, {replace})\n"
            f"record = {'record_store' if sweep else 'record_states'}\n\n\n"
            f"@jit(cache={cache}, inline='always')\n{_body_inertia_source(stored)}\n\n"
            f"@jit(cache={cache}, inline='always')\n{chunk_params}\n\n"
            f"@jit(cache={cache}, inline='always')\n{body_params}\n\n"
            f"@jit(cache={cache})\n{inspect.getsource(_scene_chunk)}\n\n"
            "chunk_loop = _scene_chunk\n\n\n"
            + (
                f"@jit(cache={cache})\n{inspect.getsource(_sweep_soa)}\n\nloop = _sweep_soa\n"
                if sweep
                else f"@jit(cache={cache}, parallel={parallel})\n{inspect.getsource(_scene_soa)}"
                "\n\nloop = _scene_soa\n"
            )
        )

    file = None if spec.path is None else spec.path.with_name(f"{name[len('_ga_rotors_') :]}.py")
    if file is not None:
        try:
            if not file.exists() or file.read_text(encoding="utf-8") != text(True):
                write_text(file, text(True))  # only when different: numba keys on mtime
        except OSError:
            file = None
    if file is not None:
        module = _modules.load_registered(importlib.util.spec_from_file_location(name, file))
    else:  # no writable cache: compiled in memory, every process
        module = _modules.load_source(name, text(False))
    _SCENE_LOOPS[name] = module.loop
    return module.loop


#: The built-in torque kernels: each reads its parameters p[j] one by one, so it runs the
#: same on a tuple as on an array. A registered or user kernel may use array operations.
_INDEXING_KERNELS = (
    "body_torque",
    "damping",
    "gravity",
    "isotropic_damping",
    "space_torque",
    "vertical_gravity",
)


def _params_source(problem) -> tuple[str, str]:
    """``chunk_params(params, lo, hi)`` and ``body_params(rows, i)``: one chunk's torque
    parameters from params of shape (P, n), and sample lo + i's among them.

    A tuple of the P numbers when every declared torque is a built-in kernel: a tuple
    lives in registers, so the loop over bodies vectorises (an array view per body
    would be an object LLVM cannot keep in SIMD lanes: the gravity loop ran 5-7x slower
    per body-step than the free one), read from one row slice per parameter (indexing
    params[j, lo + i] made LLVM gather them). A kernel that may use array operations
    gets sample i's column as an array. Either way the values, and so the arithmetic,
    are the single run's.
    """
    size = int(problem.params().size)
    tuples = all(
        term.location[0] == "ga_rotors.effects" and term.location[1] in _INDEXING_KERNELS
        for term in problem.torques
    )
    if tuples:
        rows = "(" + "".join(f"params[{j}, lo:hi], " for j in range(size)).rstrip(" ") + ")"
        value = "(" + "".join(f"rows[{j}][i], " for j in range(size)).rstrip(" ") + ")"
    else:
        rows, value = "params[:, lo:hi]", "rows[:, i]"
    return (
        f"def chunk_params(params, lo, hi):\n    return {rows}\n",
        f"def body_params(rows, i):\n    return {value}\n",
    )


def _body_inertia_source(stored: bool) -> str:
    """``body_inertia(i1, i2, i3, c)``: what a batched loop passes its step as ``inertia``."""
    value = "(i1, i2, i3, c[0], c[1], c[2], c[3], c[4], c[5])" if stored else "(i1, i2, i3)"
    return f"def body_inertia(i1, i2, i3, c):\n    return {value}\n"


@dataclass
class SceneSamples:
    """Per-sample inputs of a scene ensemble, in the scene's integration (principal) frame.

    ``inertia`` (n, 3) principal moments, ``orientation`` (n, 4) and ``angular_velocity``
    (n, 3) the initial state, ``params`` (n, P) the packed parameters of the declared
    torques, ``principal`` (n, 4) the rotation P from principal to the scene's body axes
    (identity unless the scene gives a full inertia tensor). ``kernels`` (n,) says which
    of ``terms`` sample i's torques are: the samples' values may give one effect different
    kernels (a heavy top whose lever leaves the symmetry axis in some samples only runs
    the general gravity there, :func:`ga_rotors.effects.gravity_kernel`), and each sample
    runs its own single run's kernels, one batch per distinct set. By default one set,
    the scene's. :func:`scene_samples` stores each array one row per component (the
    transpose of a C-contiguous (k, n) array, the layout the batched loops read), so
    :func:`run_samples` hands them over without copying.

    Examples
    --------
    >>> s = scene_samples("heavy_top", n=2)
    >>> s.inertia[0].tolist(), s.params.shape  # the gravity term's 6 parameters
    ([0.002225, 0.002225, 0.00125], (2, 6))
    """

    scene: object
    inertia: np.ndarray
    orientation: np.ndarray
    angular_velocity: np.ndarray
    params: np.ndarray
    principal: np.ndarray
    terms: tuple = None
    kernels: np.ndarray = None

    def __post_init__(self):
        if self.terms is None:
            self.terms = (tuple(self.scene.torques()),)
        if self.kernels is None:
            self.kernels = np.zeros(len(self), dtype=np.int64)

    def __len__(self) -> int:
        return self.inertia.shape[0]


#: Keys whose per-sample values map to the kernel's inputs without building a scene per
#: sample (checked against a full Scene on the first and last samples before use).
FAST_KEYS = ("body.moments", "initial.angular_velocity.body")

#: (id(scene), keys) -> scene, for the scene and keys whose fast mapping was checked.
_CHECKED: dict = {}

_ELEMENT = re.compile(r"^(?P<key>.*)\[(?P<index>[0-2])\]$")


def _fast_targets(scene, keys) -> list | None:
    """For each key, (0 for the moments or 1 for the rate, component or None for all
    three, scale): the vectorised mapping of :data:`FAST_KEYS`; None when a key needs a
    Scene per sample."""
    d = scene.data
    if scene.principal_rotation != (1.0, 0.0, 0.0, 0.0) or scene.gravity_index is not None:
        return None
    av = d["initial"]["angular_velocity"]
    out = []
    for key in keys:
        m = _ELEMENT.match(key)
        base, index = (m["key"], int(m["index"])) if m else (key, None)
        if base == "body.moments" and "moments" in d["body"]:
            out.append((0, index, 1.0))
        elif base == "initial.angular_velocity.body" and "body" in av:
            from .scene.schema import RATE_UNITS

            out.append((1, index, RATE_UNITS[av["units"]]))
        else:
            return None
    return out


def _fast(scene, changes: dict, n: int):
    """Vectorised inputs, or None when a key needs a Scene per sample."""
    targets = _fast_targets(scene, changes)
    if targets is None:
        return None
    moments = _repeat(scene.body.moments, n)
    omega = _repeat(scene.angular_velocity, n)
    for values, (which, index, scale) in zip(changes.values(), targets, strict=True):
        target = (moments, omega)[which]
        if index is None:
            target[:] = values.reshape(n, 3) * scale
        else:
            target[:, index] = values.reshape(n) * scale
    if _refused(moments, omega, np.finfo(float).tiny, MIN_MOMENT_RATIO):
        return None  # let the per-sample path name the bad value
    return moments, omega


@numba.njit(inline="always", error_model="numpy")
def _refused_one(m, v, tiny, ratio):
    """Whether the moments ``m`` and rate ``v`` of a sample are not finite, or the moments
    may be refused: not normal floats, too thin a body, outside the triangle (the body's
    own conditions). Every condition evaluated, without a branch (see :func:`_refused`)."""
    a, b, c = m
    w0, w1, w2 = v
    finite = (isfinite(a) & isfinite(b) & isfinite(c)
              & isfinite(w0) & isfinite(w1) & isfinite(w2))  # fmt: skip
    s = a + b + c
    lo, hi = min(a, min(b, c)), max(a, max(b, c))
    thin = (lo < tiny) | (hi > 1.0 / tiny) | (lo / hi < ratio)  # as the body's
    outside = (a > s - a) | (b > s - b) | (c > s - c)
    return (not finite) | thin | outside


@jit
def _refused(moments, omega, tiny, ratio):
    """Whether a sample's values are not finite, or its moments may be refused.

    Any sample the body's own checks might refuse goes to the per-sample path, which
    names it: moments not normal floats, too thin a body, outside the triangle. One pass
    over the samples: the same conditions as numpy expressions made about fifteen
    chunk-sized temporaries (1 ms of a 65,536-sample chunk's 2.5 ms of inputs, measured).
    Every condition of every sample is evaluated and counted, without a branch: the
    loop then runs on vector instructions (0.22 -> 0.10 ms a chunk, measured), where a
    return at the first refused sample kept it one sample at a time.
    """
    refused = 0
    for i in range(moments.shape[0]):
        m = (moments[i, 0], moments[i, 1], moments[i, 2])
        refused += _refused_one(m, (omega[i, 0], omega[i, 1], omega[i, 2]), tiny, ratio)
    return refused > 0


def scene_samples(scene, changes=None, n: int | None = None) -> SceneSamples:
    """Per-sample kernel inputs for ``scene`` with some keys changed per sample.

    Parameters
    ----------
    scene : Scene or str or path
    changes : mapping of dotted key -> array of n values, optional
        Key paths as :meth:`Scene.replace` takes them (``body.moments``,
        ``initial.angular_velocity.body[2]``, ``effects[0].coefficient``...), each with one
        value per sample along its first axis. Keys in :data:`FAST_KEYS` on a scene with a
        diagonal inertia and no gravity are mapped in one vectorised pass; any other key
        builds (and so validates) the scene once per sample.
    n : int, optional
        Number of samples when ``changes`` is empty (all samples are the scene itself).

    Examples
    --------
    >>> s = scene_samples("intermediate_axis_flip", {"initial.angular_velocity.body[1]":
    ...                                             [10.0, 10.5, 11.0]})
    >>> len(s), s.inertia.shape, s.params.shape, s.angular_velocity[:, 1].tolist()
    (3, (3, 3), (3, 0), [10.0, 10.5, 11.0])
    >>> g = scene_samples("heavy_top", {"body.mass": [1.0, 2.0]})  # a scene per sample
    >>> g.params[:, 2].tolist()  # the weight m g along z, in the torque's parameters
    [-9.80665, -19.6133]
    """
    from .scene import load_scene

    scene = load_scene(scene)
    changes = {k: np.asarray(v, dtype=np.float64) for k, v in (changes or {}).items()}
    sizes = {k: v.shape[0] if v.ndim else None for k, v in changes.items()}
    if any(s is None for s in sizes.values()):
        raise InputError(f"changes: expected one value per sample for every key, got {sizes}")
    counts = set(sizes.values()) | ({int(n)} if n is not None else set())
    if len(counts) != 1:
        raise InputError(f"changes: keys and n give different numbers of samples: {sizes}, {n}")
    count = counts.pop()
    base_params = _params(scene)
    fast = _fast(scene, changes, count) if changes else None
    checked = (id(scene), tuple(changes))
    if fast is not None and _CHECKED.get(checked) is not scene:
        moments, omega = fast
        for i in {0, count - 1}:  # the vectorised mapping must equal the scene's own
            one = _sample_scene(scene, changes, i)
            if (tuple(moments[i]) != one.body.moments
                    or not np.array_equal(omega[i], one.angular_velocity)):  # fmt: skip
                fast = None
                break
        else:
            _CHECKED[checked] = scene  # once per scene and keys: chunks of a sweep reuse it
    if fast is not None or not changes:
        moments, omega = fast or (_repeat(scene.body.moments, count),
                                  _repeat(scene.angular_velocity, count))  # fmt: skip
        return SceneSamples(
            scene,
            moments,
            _repeat(scene.orientation, count),
            omega,
            _repeat(base_params, count),
            _repeat(scene.principal_rotation, count),
        )
    inertia, q0, w0 = _columns(count, 3), _columns(count, 4), _columns(count, 3)
    params, principal = _columns(count, base_params.size), _columns(count, 4)
    names = [t.name for t in scene.torques()]
    sets: dict[tuple, int] = {}  # the samples' kernels (as a tuple) -> index in terms
    terms, kernels = [], np.empty(count, dtype=np.int64)
    for i in range(count):
        one = _sample_scene(scene, changes, i)
        own = tuple(one.torques())
        if [t.name for t in own] != names:
            raise InputError(f"sample {i}: changes the scene's declared effects {names}")
        key = tuple(t.kernel for t in own)
        if key not in sets:
            sets[key] = len(terms)
            terms.append(own)
        kernels[i] = sets[key]
        for shared in ("time", "integrator"):
            if one.data[shared] != scene.data[shared]:
                raise InputError(
                    f"sample {i}: changes {shared}.*; every sample of an ensemble shares the "
                    "scene's time grid and integrator"
                )
        inertia[i], q0[i], w0[i] = one.body.moments, one.orientation, one.angular_velocity
        params[i], principal[i] = _params(one), one.principal_rotation
    return SceneSamples(scene, inertia, q0, w0, params, principal, tuple(terms), kernels)


def _repeat(values, n: int) -> np.ndarray:
    """``values`` once per sample, shape (n, k), stored one row per component: the
    layout the batched loops read (run_samples then passes each row without a copy)."""
    return np.repeat(np.asarray(values, dtype=np.float64).reshape(-1, 1), n, axis=1).T


def _columns(n: int, k: int) -> np.ndarray:
    """An uninitialised (n, k) array stored as _repeat's."""
    return np.empty((k, n)).T


def _sample_scene(scene, changes: dict, i: int):
    """The scene with sample i's values; a bad value is named by its sample and key."""
    from .errors import SceneError

    try:
        return scene.replace({k: v[i].tolist() for k, v in changes.items()})
    except SceneError as exc:
        message = str(exc).removeprefix(f"{exc.file}: {exc.key}: " if exc.key else "")
        raise SceneError(exc.file, exc.key, f"sample {i}: {message}") from None


def _params(scene) -> np.ndarray:
    from .integrators.base import Problem

    return Problem(scene.body.moments, scene.torques()).params()


@dataclass
class EnsembleRun:
    """States of every sample at chosen times, in the integration frame.

    That is the frame a single run of the scene reports (the principal axes; the same
    as the scene's body axes unless it gives a full inertia tensor, see
    ``SceneSamples.principal``).

    Examples
    --------
    >>> run = run_samples(scene_samples("heavy_top", n=4), times=[0.001, 0.002])
    >>> run.t.tolist(), run.q.shape, run.w.shape
    ([0.001, 0.002], (2, 4, 4), (2, 4, 3))

    ``t`` (k,) the times, ``q`` (k, n, 4) orientations (w, x, y, z), ``w`` (k, n, 3) body
    angular velocities; a sample whose state stopped being finite holds NaN from then on.
    """

    t: np.ndarray
    q: np.ndarray
    w: np.ndarray


def run_samples(
    samples: SceneSamples, times=None, *, chunk: int = CHUNK, parallel: bool = True
) -> EnsembleRun:
    """Integrate every sample with the scene's integrator, step and declared effects.

    The step function is the one a single run of the scene compiles
    (:func:`ga_rotors.integrators._codegen.specialise`), so sample i equals
    ``simulate(scene with sample i's values)`` at the same times, bit for bit.

    Parameters
    ----------
    samples : SceneSamples
        From :func:`scene_samples`.
    times : sequence of float, optional
        Output times (absolute, as the scene's ``time.start``), each on the step grid;
        default: the end of the run.
    parallel : bool
        Spread the chunks over numba's threads (default), or run them in the calling
        thread (for several concurrent calls in one process).

    Examples
    --------
    >>> s = scene_samples("intermediate_axis_flip", n=2)
    >>> run = run_samples(s, times=[0.5, 1.0])
    >>> run.q.shape, run.t.tolist(), bool(np.array_equal(run.q[:, 0], run.q[:, 1]))
    ((2, 2, 4), [0.5, 1.0], True)
    """
    scene = samples.scene
    method, path, module = _method_and_path(scene)
    t0, h, nsteps = scene.data["time"]["start"], scene.step, scene.steps
    marks = _marks(times, t0, h, nsteps, scene.file)
    n = len(samples)
    x = np.ascontiguousarray(module.initial_state(samples.orientation).T)
    # a copy: the loops integrate ω in place, and scene_samples stores it in their layout
    w = np.array(samples.angular_velocity.T, order="C")
    inertia = np.ascontiguousarray(samples.inertia.T)
    params = np.ascontiguousarray(samples.params.T)
    out_x, out_w = np.empty((marks.size, 4, n)), np.empty((marks.size, 3, n))
    for k, terms in enumerate(samples.terms):  # one batch per set of kernels (usually one)
        problem = _problem(scene, terms)
        mine = None if len(samples.terms) == 1 else np.flatnonzero(samples.kernels == k)
        ins = (x, w, inertia, params)
        outs = (out_x, out_w)
        if mine is not None:  # this set's samples gathered, their outputs scattered back
            ins = tuple(np.ascontiguousarray(a[:, mine]) for a in ins)
            outs = (np.empty((marks.size, 4, mine.size)), np.empty((marks.size, 3, mine.size)))
        call = (*ins, float(t0), float(h), marks, outs, int(chunk))
        try:
            _compiled_scene_loop(method, problem, path, parallel)(*call)
        except numba.core.errors.TypingError:  # a step that unpacks inertia: see stored=False
            _compiled_scene_loop(method, problem, path, parallel, stored=False)(*call)
        if mine is not None:
            out_x[:, :, mine], out_w[:, :, mine] = outs
    q = module.quaternions(out_x.transpose(0, 2, 1))
    w = out_w.transpose(0, 2, 1)
    return EnsembleRun(t0 + marks * h, np.ascontiguousarray(q), np.ascontiguousarray(w))


def _method_and_path(scene):
    """The scene's integrator, first path and that path's module, as an ensemble runs them."""
    from .integrators import TemplateIntegrator, base
    from .paths import get as get_path

    spec_method = scene.data["integrator"]
    method = base.get(spec_method["method"])
    if not isinstance(method, TemplateIntegrator):
        raise InputError(
            f"{scene.file}: integrator.method: ensembles run fixed-step methods; "
            f"{spec_method['method']!r} is adaptive"
        )
    path = scene.paths[0]
    pspec = get_path(path)
    if pspec.dim != 4:
        raise InputError(
            f"{scene.file}: integrator.paths: ensembles integrate the quaternion or rotor "
            f"path; the scene's first path is {path!r}"
        )
    return method, path, pspec.load()


def _problem(scene, terms):
    """The integrator's problem for a batch of the scene's samples with these torques."""
    from .integrators import base

    lower = scene.data["integrator"].get("accept_lower_order", False)
    return base.Problem(scene.body.moments, terms, accept_lower_order=lower)


@dataclass
class _SweepPlan:
    """What :func:`run_columns` hands :func:`_sweep_soa` for one scene and varied keys."""

    scene: object  # kept alive: plans are found by id(scene)
    loop: object
    compile: object  # (stored) -> the loop; stored=False if the step unpacks inertia
    src: np.ndarray
    scale: np.ndarray
    base: np.ndarray
    params: np.ndarray
    t0: float
    h: float
    marks: np.ndarray


#: (id(scene), layout, times) -> _SweepPlan, or None where the sweep's path stays.
_PLANS: dict = {}

#: Plans kept at most (a sweep run has one; each run of a sweep file loads its scene anew).
MAX_PLANS = 16


def _sweep_plan(scene, layout: tuple, times, cols) -> _SweepPlan | None:
    targets = _fast_targets(scene, [key for key, _ in layout])
    if targets is None or scene.paths[0] != "quaternion":
        return None  # record_store takes the state for the quaternion it is
    try:
        method, path, _ = _method_and_path(scene)
    except InputError:
        return None  # run_samples says it
    src, scale = np.full(6, -1, dtype=np.int64), np.ones(6)
    row = 0
    for (_, width), (which, index, factor) in zip(layout, targets, strict=True):
        if width != (3 if index is None else 1):
            return None
        for k in range(3) if index is None else (index,):
            src[3 * which + k], scale[3 * which + k] = row + (k if index is None else 0), factor
        row += width
    start = np.array([*scene.body.moments, *scene.angular_velocity, *scene.orientation])
    problem = _problem(scene, tuple(scene.torques()))

    def compile(stored: bool):
        return _compiled_scene_loop(method, problem, path, False, stored, sweep=True)

    t0, h = scene.data["time"]["start"], scene.step
    plan = _SweepPlan(
        scene, compile(True), compile, src, scale, start, np.ascontiguousarray(_params(scene)),
        float(t0), float(h), _marks(times, t0, h, scene.steps, scene.file),
    )  # fmt: skip
    # the mapping must be the scene's own: checked on the first and last samples
    changes, row = {}, 0
    for key, width in layout:
        changes[key] = cols[row] if width == 1 else cols[row : row + width].T
        row += width
    for i in {0, cols.shape[1] - 1}:
        one = _sample_scene(scene, changes, i)
        got = [plan.base[k] if src[k] < 0 else cols[src[k], i] * scale[k] for k in range(6)]
        if tuple(got[:3]) != one.body.moments or not np.array_equal(got[3:], one.angular_velocity):
            return None
    return plan


def run_columns(scene, layout, cols, times, nominal):
    """Integrate the samples whose varied values are ``cols``, outputs in a store's layout.

    The compiled pass of a sweep's chunk: each sample's inputs made from its values in
    the loop, integrated by :func:`run_samples`' loop (the same step, so the same numbers
    bit for bit), its states and its angle from ``nominal`` recorded straight into arrays
    whose first axis is the sample.

    Parameters
    ----------
    scene : Scene
    layout : tuple of (key, width)
        The varied keys in the order of the rows of ``cols``, each with its number of rows
        (1, or 3 for a whole vector).
    cols : ndarray, shape (rows, n)
    times : sequence of float or None
        As :func:`run_samples`' ``times``.
    nominal : ndarray, shape (k, 4)
        The orientation the angle is measured from, at each output time.

    Returns
    -------
    (q (n, k, 4), w (n, k, 3), angle (n, k)), or None when the pass does not apply: keys
    outside :data:`FAST_KEYS`, a scene they cannot be mapped on in one pass (see
    :func:`scene_samples`), a path other than the quaternion's, or a sample whose values
    the scene may refuse. :func:`scene_samples` and :func:`run_samples` then do it (and
    name a bad value).

    Examples
    --------
    >>> s = scene_samples("intermediate_axis_flip", n=1)
    >>> scene = s.scene.replace({"integrator.paths": ["quaternion"]})
    >>> cols = np.array([[10.0, 10.5]])
    >>> nominal = run_samples(scene_samples(scene, n=1)).q[:, 0]
    >>> q, w, angle = run_columns(scene, (("initial.angular_velocity.body[1]", 1),), cols,
    ...                           None, nominal)
    >>> q.shape, w[:, 0, 1].tolist(), angle.shape
    ((2, 1, 4), [..., ...], (2, 1))
    >>> run = run_samples(scene_samples(scene, {"initial.angular_velocity.body[1]": cols[0]}))
    >>> bool(np.array_equal(q[:, 0], run.q[0]))
    True
    """
    key = (id(scene), tuple(layout), None if times is None else tuple(np.atleast_1d(times)))
    plan = _PLANS.get(key, False)
    if plan is False or (plan is not None and plan.scene is not scene):
        if len(_PLANS) >= MAX_PLANS:  # each holds its scene: a long process keeps a few
            _PLANS.clear()
        try:
            plan = _PLANS[key] = _sweep_plan(scene, tuple(layout), times, cols)
        except InputError:  # a first or last sample the scene refuses: the per-sample
            return None  # path names the first bad one (nothing kept: checked again)
    if plan is None:
        return None
    n, k = cols.shape[1], plan.marks.size
    # page-aligned: a sweep's writer sends them to the disk without copying them first
    q, w, angle = aligned_empty((n, k, 4)), aligned_empty((n, k, 3)), aligned_empty((n, k))
    out = (q, w, angle, np.ascontiguousarray(nominal, dtype=np.float64))
    call = (cols, plan.src, plan.scale, plan.base, plan.params, plan.t0, plan.h, plan.marks)
    try:
        ok = plan.loop(*call, out, CHUNK)
    except numba.core.errors.TypingError:  # a step that unpacks inertia: see stored=False
        plan.loop = plan.compile(False)
        ok = plan.loop(*call, out, CHUNK)
    if not ok:
        return None
    return q, w, angle


def _marks(times, t0: float, h: float, nsteps: int, file: str) -> np.ndarray:
    """Step indices of the output times (each a whole number of steps from t0)."""
    if times is None:
        return np.array([nsteps], dtype=np.int64)
    t = np.atleast_1d(np.asarray(times, dtype=np.float64))
    k = np.rint((t - t0) / h)
    bad = (np.abs(k * h + t0 - t) > 1e-9 * max(1.0, abs(t0) + nsteps * h)) | (k < 0) | (k > nsteps)
    if t.ndim != 1 or np.any(bad) or np.any(np.diff(k) <= 0):
        raise InputError(
            f"{file}: times: expected increasing times on the step grid t0 + k·{h!r} s "
            f"within the run, got {t.tolist()}"
        )
    return k.astype(np.int64)
