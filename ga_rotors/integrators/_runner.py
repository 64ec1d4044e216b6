"""Running generated loops: one run, a run in pieces, a batch of bodies, the vector field.

What :meth:`~ga_rotors.integrators.Integrator.run` calls for a template integrator. For
one (integrator, problem, path), everything a run needs that does not depend on its
states (the generated module, the path's size and statistics, the packed parameters, the
entry to the compiled call) is derived once and kept by the problem (:func:`prepared`);
a run then only checks its counts and states, allocates its samples and calls the loop.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..paths import resolve as resolve_path
from . import _source, loops
from ._cache import specialise
from .base import Integrator, LoopResult
from .kinds import KINDS
from .problem import Batch, Problem

__all__ = [
    "BATCH_CHUNK",
    "CHUNK_STEPS",
    "bare_loop",
    "pieces",
    "prepared",
    "run_batch",
    "run_prepared",
    "sample_marks",
    "vector_field",
]

#: Steps per call of the compiled loop when progress is reported (~10 ms of RK4).
CHUNK_STEPS = 131_072
#: Bodies per chunk of a batch: a chunk's state (7 doubles a body) stays in L1 through
#: all its steps (256 bodies x 7 doubles = 14 KB).
BATCH_CHUNK = 256


@dataclass(frozen=True)
class _Prepared:
    """What every run of one (integrator, problem, path) shares, derived once."""

    owner: Integrator  # held, so that the id in the problem's key is never reused
    loop: object
    run: object  # the module's judged_run: limit, loop and watch in one compiled call
    source: Path | None
    dim: int
    shape: tuple[int]  # (dim,), the state's shape
    rate: int  # numbers in the rate part of the state
    rate_shape: tuple[int]  # (rate,)
    stats: np.ndarray  # the path's initial watch statistics (copied per run)
    inertia: tuple
    params: np.ndarray
    #: judged_run's flags for this problem: JUDGE when the limit is measured in the
    #: compiled module (and the problem has a body), REFUSE too when a run past it raises
    flags: int
    #: the integrator declares a limit the compiled module cannot judge (a plain Python
    #: function, without a ``measure``): :meth:`Integrator.check_step` judges it
    python_limit: bool


def _entry(dispatcher, sample: tuple):
    """The machine code ``dispatcher`` compiles (or loads from its cache) for the types of
    ``sample``, as a function that skips the dispatcher's typing of every argument on
    every call (a quarter of a microsecond for judged_run's thirteen): only for a caller
    that passes exactly those types, as :func:`run_prepared` makes sure it does (states
    converted and checked, counts as ints, times as floats, its own output arrays).
    Uncompiled (``NUMBA_DISABLE_JIT=1``), the function itself."""
    compile_signature = getattr(dispatcher, "compile", None)
    if compile_signature is None:
        return dispatcher
    import numba

    return compile_signature(tuple(numba.typeof(a) for a in sample))


def _prepare(integrator: Integrator, problem: Problem, path: str) -> _Prepared:
    kind = KINDS[problem.kind]
    spec = resolve_path(path, kind.moves)
    kernels = spec.load()
    compiled = specialise(integrator, problem, path)
    stats = (
        kernels.initial_stats() if hasattr(kernels, "initial_stats") else np.zeros(kernels.NSTATS)
    )
    inertia = kind.body(problem)
    limited = integrator.step_limit is not None and kind.judged and problem.inertia is not None
    measured = limited and hasattr(integrator.step_limit, "measure")
    flags = 0
    if measured:
        flags = loops.JUDGE | (loops.REFUSE if integrator.step_limit_action == "raise" else 0)
    params = problem.params()
    # the types run_prepared passes: states, t0, h, nsteps, every, inertia, params,
    # the three output arrays, the statistics, flags
    sample = (np.empty(spec.dim), np.empty(kind.rate), 0.0, 0.0, 1, 1, inertia, params,
              np.empty(1), np.empty((1, spec.dim)), np.empty((1, kind.rate)), stats, 0)  # fmt: skip
    return _Prepared(
        integrator, compiled.module.loop, _entry(compiled.module.run, sample), compiled.path,
        spec.dim, (spec.dim,), kind.rate, (kind.rate,), stats, inertia, params, flags,
        limited and not measured,
    )  # fmt: skip


def prepared(integrator: Integrator, problem: Problem, path: str, checked: bool = False):
    """The :class:`_Prepared` run of ``integrator`` on ``problem`` and ``path``, derived
    once and kept by the problem; ``checked``: :meth:`Integrator.check` passed first
    (kept under its own key, so one look-up serves a checked run)."""
    if checked:
        return problem.derived(
            ("checked run", id(integrator), path),
            lambda: integrator.check_once(problem, path) or prepared(integrator, problem, path),
        )
    return problem.derived(
        ("loop", id(integrator), path), lambda: _prepare(integrator, problem, path)
    )


def _counts(nsteps, every) -> tuple[int, int]:
    if type(nsteps) is not int or type(every) is not int or nsteps < 1 or every < 1:
        if isinstance(nsteps, bool) or not (isinstance(nsteps, int | np.integer) and nsteps >= 1):
            raise InputError(f"nsteps: expected a positive integer, got {nsteps!r}")
        if isinstance(every, bool) or not (isinstance(every, int | np.integer) and every >= 1):
            raise InputError(f"every: expected a positive integer, got {every!r}")
        nsteps, every = int(nsteps), int(every)
    return nsteps, every


def _state(value, shape: tuple[int, ...], name: str) -> np.ndarray:
    """``value`` as a contiguous float64 array of ``shape`` (the array itself if it is one)."""
    a = np.ascontiguousarray(value, dtype=np.float64)
    if a.shape != shape:
        raise InputError(f"expected shape {shape}, got {a.shape}", key=name)
    return a


def _rows(nsteps: int, every: int) -> int:
    """Samples of ``nsteps`` steps kept every ``every``: the start, each ``every``-th step,
    and the last step."""
    return nsteps // every + 1 + (1 if nsteps % every else 0)


_NO_W = {}  # rate size -> the zero rates of a kinematic run (read by no loop)
_F64 = np.float64
# module-level names: a global look-up each instead of a global and an attribute
_empty, _contiguous = np.empty, np.ascontiguousarray
_new_tuple = tuple.__new__  # a LoopResult without the named tuple's keyword-handling __new__


def run_prepared(prep: _Prepared, x0, w0, t0, h, nsteps, every, flags: int = 0, progress=None):
    """One run of a prepared loop: (LoopResult, value, bound, crossing), the last three
    ``judged_run``'s verdicts (see :mod:`~.loops`; ``flags`` as there, the prepared ones
    being the caller's to add). With ``progress``, the loop runs in pieces of about
    :data:`CHUNK_STEPS` steps and ``progress(done)`` is called after each, unjudged (the
    samples are the same, bit for bit: :func:`pieces`). A refused run (``REFUSE``, past
    the limit) returns None for the result.

    The counts and states are checked here on every run (a wrong one gets its one line,
    naming ``nsteps``, ``every``, ``x0`` or ``w0``); the rest was derived once. Every
    run pays this function's Python (about 0.6 µs), so it is written for that: locals,
    no helper calls on the common path."""
    if type(nsteps) is not int or type(every) is not int or nsteps < 1 or every < 1:
        nsteps, every = _counts(nsteps, every)
    rows = nsteps // every + 1 + (1 if nsteps % every else 0)
    stats = prep.stats
    if stats.size:  # a path's watch statistics (empty arrays need no copy)
        stats = stats.copy()
    out_t = _empty(rows)
    out_x = _empty((rows, prep.dim))
    out_w = _empty((rows, prep.rate))
    x = _contiguous(x0, dtype=_F64)
    w = _NO_W.get(prep.rate) if w0 is None else _contiguous(w0, dtype=_F64)
    if w is None:
        w = _NO_W[prep.rate] = np.zeros(prep.rate)
    if x.shape != prep.shape or w.shape != prep.rate_shape:
        _state(x, prep.shape, "x0")
        _state(w, prep.rate_shape, "w0")
    if progress is None:  # the common case: one call of the compiled loop
        written, value, bound, crossing = prep.run(
            x, w, float(t0), float(h), nsteps, every, prep.inertia, prep.params,
            out_t, out_x, out_w, stats, flags,
        )  # fmt: skip
        if written == 0:
            return None, value, bound, crossing
    else:  # into the run's arrays, each piece from the previous one's last sample
        row = written = 0

        def into(_):
            return out_t[row:], out_x[row:], out_w[row:]

        span = max(1, CHUNK_STEPS // every) * every
        for _, _, _, got, _ in _spans(prep, x, w, float(t0), float(h), nsteps, every, span,
                                      stats, into, progress):  # fmt: skip
            written = row + got
            row = written - 1
        value, bound, crossing = 0.0, 1.0, -1
    if written < rows:
        out_t, out_x, out_w = out_t[:written], out_x[:written], out_w[:written]
    result = _new_tuple(LoopResult, (out_t, out_x, out_w, written == rows, stats, prep.source))
    return result, value, bound, crossing


def _spans(prep, x, w, t0, h, nsteps, every, span, stats, out, progress):
    """The loop over consecutive spans of ``span`` steps (a multiple of ``every``): for
    each, ``out(rows)`` gives the arrays its samples go into (sample 0 the previous span's
    last), and (t, x, w, rows written, rows expected) is yielded. Each span continues
    from the exact state at its step number (a step's time is t0 + k·h, whichever span
    takes it) with the watch statistics carried over, so the samples are one call's, bit
    for bit. A span whose state stopped being finite is the last."""
    done = 0
    while done < nsteps:
        n = min(span, nsteps - done)
        rows = _rows(n, every)
        out_t, out_x, out_w = out(rows)
        got = prep.loop(
            x, w, t0, h, done, n, every, prep.inertia, prep.params, out_t, out_x, out_w, stats
        )
        done += n
        if progress is not None:
            progress(done)
        yield out_t, out_x, out_w, got, rows
        if got < rows:
            return
        x, w = out_x[got - 1].copy(), out_w[got - 1].copy()


def pieces(prep: _Prepared, x0, w0, t0, h, nsteps, every, chunk, progress=None):
    """The run of :func:`run_prepared` as consecutive pieces of about ``chunk`` steps.

    A generator of :class:`LoopResult`: the first holds sample 0 and the samples of the
    first ``chunk`` steps (rounded up to whole multiples of ``every``), each next one the
    samples after the previous piece's last. Joined, they are the samples of one call,
    bit for bit, and memory holds one piece at a time. A piece whose state stopped being
    finite is the last one (``complete`` False); ``stats`` of the last piece are the
    run's. The arguments are checked before the first piece.

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> rk4, problem = get("rk4"), Problem((1.0, 2.0, 3.0))
    >>> prep = prepared(rk4, problem, "quaternion")
    >>> args = ((1.0, 0, 0, 0), (0.1, 0.0, 2.0), 0.0, 0.01, 100, 10)
    >>> parts = list(pieces(prep, *args, chunk=30))
    >>> [len(p.t) for p in parts]
    [4, 3, 3, 1]
    >>> whole = run_prepared(prep, *args)[0]
    >>> bool((np.concatenate([p.x for p in parts]) == whole.x).all())
    True
    """
    nsteps, every = _counts(nsteps, every)
    x = _state(x0, prep.shape, "x0")
    w = np.zeros(prep.rate) if w0 is None else _state(w0, (prep.rate,), "w0")
    span = max(1, int(chunk) // every) * every
    stats = prep.stats.copy() if prep.stats.size else prep.stats

    def fresh(rows):
        return np.empty(rows), np.empty((rows, prep.dim)), np.empty((rows, prep.rate))

    def generate():
        first = 0  # a later piece's sample 0 is the previous one's last
        for t, xs, ws, got, rows in _spans(prep, x, w, float(t0), float(h), nsteps, every,
                                           span, stats, fresh, progress):  # fmt: skip
            yield LoopResult(t[first:got], xs[first:got], ws[first:got], got == rows, stats,
                             prep.source)  # fmt: skip
            first = 1

    return generate()


def _batch_state(value, shape: tuple[int, int], name: str) -> np.ndarray:
    """``value`` as float64 of ``shape``, in whatever layout it has (the caller copies)."""
    a = np.asarray(value, dtype=np.float64)
    if a.shape != shape:
        raise InputError(f"expected shape {shape}, got {a.shape}", key=name)
    return a


def sample_marks(every, nsteps: int) -> np.ndarray:
    """The step numbers a batch samples: ``every`` an int (the start, every ``every``-th
    step and the last, as a run samples), or the step numbers themselves (increasing,
    within the run).

    Examples
    --------
    >>> sample_marks(4, 10).tolist(), sample_marks([3, 10], 10).tolist()
    ([0, 4, 8, 10], [3, 10])
    >>> sample_marks([5, 5], 10)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: every: expected a positive integer, or increasing step numbers from 0 to 10, got [5, 5]
    """  # noqa: E501
    if isinstance(every, int | np.integer) and not isinstance(every, bool):
        nsteps, every = _counts(nsteps, every)
        marks = np.arange(0, nsteps + 1, every, dtype=np.int64)
        return marks if marks[-1] == nsteps else np.append(marks, nsteps)
    try:
        marks = np.asarray(every)
        ok = (marks.ndim == 1 and marks.size and marks.dtype.kind in "iu"
              and marks[0] >= 0 and marks[-1] <= nsteps and np.all(np.diff(marks) > 0))  # fmt: skip
    except (TypeError, ValueError):
        ok = False
    if not ok:
        shown = marks.tolist() if isinstance(every, list | tuple | np.ndarray) else every
        raise InputError(
            "expected a positive integer, or increasing step numbers from 0 to "
            f"{nsteps}, got {shown!r}", key="every",
        )  # fmt: skip
    return marks.astype(np.int64)


def run_batch(integrator: Integrator, batch: Batch, path: str, x0, w0, t0, h, nsteps,
              every, parallel: bool = True, chunk: int = BATCH_CHUNK) -> LoopResult:  # fmt: skip
    """Every body of ``batch`` from its state in ``x0`` (n, dim) and ``w0`` (n, rate),
    sampled at :func:`sample_marks` of ``every``: ``t`` (k,), ``x`` (k, n, dim), ``w``
    (k, n, rate); ``complete`` when every body's state is finite at the end. Each body
    follows exactly its own single run (the same step, compiled inline: bit for bit).

    ``parallel``: spread the chunks of ``chunk`` bodies over numba's threads, or run them
    in the calling thread (for several batches at once in one process, which numba's
    default threading layer does not allow for parallel loops). A batch of one chunk runs
    in the calling thread either way: there is nothing to spread, and the serial loop
    compiles in about half the time of the parallel one (10.6 against 19.2 s for a
    thrown body under gravity).

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> batch = Batch(Problem((1.0, 2.0, 3.0)), np.tile([1.0, 2.0, 3.0], (2, 1)))
    >>> r = run_batch(get("rk4"), batch, "quaternion", [[1.0, 0, 0, 0]] * 2,
    ...               [[0.0, 0.0, 2.0], [0.0, 0.0, 1.0]], 0.0, 0.01, 100, 50)
    >>> r.t.tolist(), r.x.shape
    ([0.0, 0.5, 1.0], (3, 2, 4))
    >>> bool(np.allclose(r.x[-1, 0], (np.cos(1.0), 0, 0, np.sin(1.0)), atol=1e-10))
    True
    """
    problem, n = batch.problem, len(batch)
    kind = KINDS[problem.kind]
    dim = resolve_path(path, kind.moves).dim
    nsteps = _counts(nsteps, 1)[0]
    if isinstance(chunk, bool) or not isinstance(chunk, int | np.integer) or chunk < 1:
        raise InputError(f"expected a positive number of bodies, got {chunk!r}", key="chunk")
    if batch.inertia.shape[1] != kind.body_size:
        raise InputError(f"expected {kind.body_size} numbers per body, got "
                         f"{batch.inertia.shape[1]}", key="inertia")  # fmt: skip
    marks = sample_marks(every, nsteps)
    # copies, stored one row per component: the loop integrates them in place
    x = np.array(_batch_state(x0, (n, dim), "x0").T, order="C")
    w = np.array(_batch_state(w0, (n, kind.rate), "w0").T, order="C")
    body = np.ascontiguousarray(batch.inertia.T)
    params = np.ascontiguousarray(batch.params.T)
    out_x, out_w = np.empty((marks.size, dim, n)), np.empty((marks.size, kind.rate, n))
    call = (x, w, body, params, float(t0), float(h), marks, out_x, out_w, chunk)
    # bodies all with their frames at their centres of mass (the last three numbers of a
    # motion's body, Problem.body) take the kernels their single runs take, without the
    # lever's terms
    form = _source.BATCH_CENTRED if kind.moves and not body[-3:].any() else _source.BATCH
    parallel = parallel and n > chunk
    spec = specialise(integrator, problem, path, form)
    try:
        (spec.module.loop if parallel else spec.module.serial)(*call)
    except Exception as exc:  # a step that unpacks ``inertia`` cannot take the stored values
        from numba.core.errors import TypingError

        if not isinstance(exc, TypingError) or kind.stored is None:
            raise
        spec = specialise(integrator, problem, path, _source.BATCH_MOMENTS)
        (spec.module.loop if parallel else spec.module.serial)(*call)
    complete = bool(np.isfinite(out_x[-1]).all() and np.isfinite(out_w[-1]).all())
    return LoopResult(t0 + marks * float(h), out_x.transpose(0, 2, 1), out_w.transpose(0, 2, 1),
                      complete, np.zeros(0), spec.path)  # fmt: skip


def vector_field(problem: Problem, path: str):
    """The specialised right-hand side f(t, y) -> ẏ, for scipy-style integrators.

    ``y`` is the path's state followed by the rate part (a dynamics problem) or the state
    alone (a prescribed ω(t)); the returned function evaluates one compiled call per
    evaluation and returns a new array. Only the declared torques enter it, as in the
    loops.

    Examples
    --------
    >>> f = vector_field(Problem((1.0, 2.0, 3.0)), "quaternion")
    >>> f(0.0, np.array([1.0, 0, 0, 0, 0, 0, 2.0])).tolist()
    [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    """
    kind = KINDS[problem.kind]
    compiled = specialise(None, problem, path, _source.RHS).module.rhs
    params = problem.params()
    inertia = kind.body(problem)
    dim = resolve_path(path, kind.moves).dim + (kind.rate if kind.dynamic else 0)

    def f(t, y):
        y = np.ascontiguousarray(y, dtype=np.float64)
        if y.shape != (dim,):
            raise InputError(f"y: expected shape ({dim},), got {y.shape}")
        out = np.empty(dim)
        compiled(float(t), y, inertia, params, out)
        return out

    return f


def bare_loop(integrator: Integrator, problem: Problem, path: str, x0, w0, t0, h, nsteps, every):
    """A zero-argument call of the compiled loop alone, its arrays allocated beforehand:
    the floor :meth:`Integrator.run` is measured against (its per-call overhead is its time
    minus this one's; ``benchmarks/bench_overhead.py``).

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> call = bare_loop(get("rk4"), Problem((1.0, 2.0, 3.0)), "quaternion",
    ...                  (1.0, 0, 0, 0), (0.0, 0.0, 2.0), 0.0, 0.01, 100, 100)
    >>> call()  # rows written: the start and the end
    2
    """
    prep = prepared(integrator, problem, path)
    rows = _rows(nsteps, every)
    out_t, out_x, out_w = np.empty(rows), np.empty((rows, prep.dim)), np.empty((rows, prep.rate))
    stats = prep.stats.copy()
    x = np.ascontiguousarray(x0, dtype=np.float64)
    w = np.ascontiguousarray(w0, dtype=np.float64)
    loop, inertia, params = prep.loop, prep.inertia, prep.params
    t0, h = float(t0), float(h)

    def call():
        return loop(x, w, t0, h, 0, nsteps, every, inertia, params, out_t, out_x, out_w, stats)

    return call
