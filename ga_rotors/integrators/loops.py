"""Loop templates: the compiled driver every fixed-step integrator runs inside.

Templates are plain Python (see :mod:`ga_rotors.integrators.base`); the code generator
(:mod:`ga_rotors.integrators._source`) pastes them into a module next to the integrator's
step template and the path's kernels, and compiles them there. Which loop a problem runs
is its kind's declaration (:mod:`ga_rotors.integrators.kinds`). The loops share one calling
convention::

    rows = loop(x0, w0, t0, h, first, nsteps, every, inertia, params, out_t, out_x, out_w,
                stats)

* ``x0`` (dim,) path state at step ``first``, ``w0`` the rate part of the state (the
  body ω; ignored by the kinematic loop), read and written through the kind's
  ``r_load``/``r_store``; the loop takes steps ``first`` to ``first + nsteps``;
* sample 0 is the initial state; then every ``every`` steps and always the last step;
* ``t = t0 + (first + i)·h`` is computed, not accumulated, so times carry no drift, and a
  run continued from step ``first`` sees exactly the times a single run sees;
* ``rows`` is the number of samples written; it is smaller than the arrays when the state
  stopped being finite (the samples before are valid, nothing after is written).

Around the loop, :func:`judged_run` is a run's one compiled call: the step limit on the
initial state, the loop, and the stored samples' watch, with its verdicts returned as
numbers (``(rows, value, bound, crossing)``) for the Python around it to turn into words
only when a limit is past (:meth:`ga_rotors.integrators.TemplateIntegrator.run`).

The right-hand-side templates (``dynamics_rhs``, ``kinematic_rhs``) evaluate the vector
field once, for integrators that are not compiled loops (scipy's DOP853); see
:func:`ga_rotors.integrators._runner.vector_field`.

The batched templates (:func:`batch_chunk`, :func:`batch_loop`) run many bodies at once,
each with its own body and parameters, with the *same* step (compiled inline, so the
loop over bodies vectorises): struct-of-arrays states, ``x`` of shape (dim, n), ``w`` of
shape (rate, n), read and written one row per component (``x_rows``, ``x_get``,
``x_put``, ... generated for the sizes at hand), bodies in chunks small enough to stay in
the L1 cache, each chunk taking all its steps before the next, chunks spread over the
cores with ``prange``.
"""

from __future__ import annotations

from numba import prange

from ._arith import finite_row
from .limits import _watch_candidates
from .slots import (
    accel,
    body_get,
    body_rows,
    chunk_load,
    chunk_store,
    limit,
    loop,
    o_load,
    o_rate,
    o_store,
    o_watch,
    omega,
    param_get,
    param_rows,
    r_load,
    r_store,
    step,
    w_get,
    w_put,
    w_rows,
    x_get,
    x_put,
    x_rows,
)

# Templates only (consumed by ga_rotors.integrators._source, never called as Python):
# nothing here is an API of its own.
__all__: list[str] = []


def fixed_step_loop(
    x0, w0, t0, h, first, nsteps, every, inertia, params, out_t, out_x, out_w, stats
):
    """Dynamics: ``x, w = step(t, x, w, h, inertia, params)`` repeated ``nsteps`` times."""
    x = o_load(x0)
    w = r_load(w0)
    out_t[0] = t0 + first * h
    o_store(out_x, 0, x)
    r_store(out_w, 0, w)
    row = 1
    countdown = every
    for i in range(nsteps):
        t = t0 + (first + i) * h
        o_watch(t, x, w, h, stats)
        x, w = step(t, x, w, h, inertia, params)
        countdown -= 1
        if countdown == 0 or i + 1 == nsteps:
            countdown = every
            out_t[row] = t0 + (first + i + 1) * h
            o_store(out_x, row, x)
            r_store(out_w, row, w)
            if not (finite_row(out_x, row) and finite_row(out_w, row)):
                return row
            row += 1
    return row


def kinematic_loop(
    x0, w0, t0, h, first, nsteps, every, inertia, params, out_t, out_x, out_w, stats
):
    """Prescribed ω(t): ``x = step(t, x, h, params)``; ``out_w`` records ω(t)."""
    x = o_load(x0)
    out_t[0] = t0 + first * h
    o_store(out_x, 0, x)
    r_store(out_w, 0, omega(out_t[0], params))
    row = 1
    countdown = every
    for i in range(nsteps):
        t = t0 + (first + i) * h
        o_watch(t, x, omega(t, params), h, stats)
        x = step(t, x, h, params)
        countdown -= 1
        if countdown == 0 or i + 1 == nsteps:
            countdown = every
            t1 = t0 + (first + i + 1) * h
            out_t[row] = t1
            o_store(out_x, row, x)
            r_store(out_w, row, omega(t1, params))
            if not (finite_row(out_x, row) and finite_row(out_w, row)):
                return row
            row += 1
    return row


#: ``judged_run``'s ``flags``: judge the step limit on the initial state; ...
JUDGE = 1
#: ... past it, do not run (the method has no step there: lgvi); ...
REFUSE = 2
#: ... within it, find the first stored sample whose ω is past it.
WATCH = 4


def judged_run(x0, w0, t0, h, nsteps, every, inertia, params, out_t, out_x, out_w, stats, flags):
    """``loop`` with the step limit judged around it, as ``flags`` ask; returns (rows
    written, the limit's value and bound on the initial state (0, 1 when not judged), the
    first stored sample past the limit or −1). A refused run writes no rows."""
    value, bound = 0.0, 1.0
    if flags & JUDGE:
        value, bound = limit(inertia, w0, h, nsteps)
        if flags & REFUSE and not value < bound:
            return 0, value, bound, -1
    rows = loop(x0, w0, t0, h, 0, nsteps, every, inertia, params, out_t, out_x, out_w, stats)
    crossing = -1
    if flags & WATCH and value < bound:
        for k in _watch_candidates(out_w, rows, inertia):
            at, most = limit(inertia, out_w[k], h, nsteps)
            if not at < most:
                crossing = k
                break
    return rows, value, bound, crossing


def dynamics_rhs(t, y, inertia, params, out):
    """out = ẏ for y = (path state..., rates...): the state's size is the path's (the
    length of the tuple ``o_load`` reads, a constant to the compiler), the rates follow."""
    n = y.shape[0]
    x = o_load(y)
    dim = len(x)
    w = r_load(y[dim:])
    o_store(out.reshape((1, n)), 0, o_rate(x, w))
    r_store(out[dim:].reshape((1, n - dim)), 0, accel(t, x, w, inertia, params))


def kinematic_rhs(t, y, inertia, params, out):
    """out = ẋ for the path state y under the prescribed ω(t)."""
    o_store(out.reshape((1, y.shape[0])), 0, o_rate(o_load(y), omega(t, params)))


#: Bodies a batched loop integrates together: their state, body and parameters sit in one
#: block of rows this long (``chunk_load``), small enough for the L1 cache (256 bodies of
#: a whole motion: 13 state and 13 body numbers, 53 KB of L2 at worst).
BLOCK = 256


def batch_chunk(x, w, body, params, lo, hi, t0, h, marks, out_x, out_w):
    """Bodies ``lo``..``hi - 1`` of a batch (``x`` (dim, n) and ``w`` (rate, n) their
    starts) through every step, :data:`BLOCK` of them at a time, each block in one array
    of rows (``chunk_load``); their states at step ``marks[m]`` into ``out_x[m]`` and
    ``out_w[m]``. ``body`` (body size, n) and ``params`` (P, n) are per body; a state
    that stops being finite stays NaN (nothing reads it)."""
    for start in range(lo, hi, BLOCK):
        end = min(hi, start + BLOCK)
        s = chunk_load(x, w, body, params, start, end)
        xs, ws = x_rows(s), w_rows(s)
        bs, ps = body_rows(s), param_rows(s, params, start, end)
        done = 0
        for m in range(marks.shape[0]):
            for k in range(done, marks[m]):
                t = t0 + k * h
                for i in range(end - start):
                    xi, wi = step(t, x_get(xs, i), w_get(ws, i), h, body_get(bs, i),
                                  param_get(ps, i))  # fmt: skip
                    x_put(xs, i, xi)
                    w_put(ws, i, wi)
            done = marks[m]
            chunk_store(s, out_x[m], out_w[m], start, end)


def batch_loop(x, w, body, params, t0, h, marks, out_x, out_w, chunk):
    """Every body of a batch, ``chunk`` bodies at a time, the chunks spread over the
    cores (see :func:`batch_chunk`)."""
    n = x.shape[1]
    for c in prange((n + chunk - 1) // chunk):
        lo = c * chunk
        batch_chunk(x, w, body, params, lo, min(n, lo + chunk), t0, h, marks, out_x, out_w)
