"""Broadcasting arrays into the flat form the compiled loops take, and reporting failures.

A public vectorised function validates shapes and types here, hands the loop one 2-D (or
1-D) C-contiguous array per argument, and reshapes the loop's output back. An argument
whose leading shape already is the broadcast shape, or that holds a single item, is passed
without a copy: the loop reads row ``i * step`` with ``step`` 1 or 0. Only genuinely
mixed broadcasting (say (5, 1, 4) with (1, 7, 4)) materialises a copy.

Loops check finiteness (and unit norm, where required) inside the loop and return the
first flat index that failed, or -1. :meth:`Batch.fail` then finds out which argument was
wrong on the slow path, so the fast path makes no second pass over memory.
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit
from ._validate import UNIT_TOLERANCE, as_float_array, check_finite, require_unit
from .errors import InputError


class Batch:
    """Arguments of one vectorised call, broadcast against each other.

    Parameters
    ----------
    *specs : (value, name, trailing)
        ``trailing`` is the required length of the last axis (4 for quaternions, 3 for
        vectors, (3, 3) for matrices) or ``None`` for a scalar per item (angles, t).

    Examples
    --------
    >>> b = Batch(([[1.0, 0, 0, 0]] * 2, "p", 4), ([0.0, 1, 0, 0], "q", 4))
    >>> b.shape, b.steps, [f.shape for f in b.flat]
    ((2,), (1, 0), [(2, 4), (1, 4)])
    >>> Batch(([1.0, 2.0], "p", 4))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: p: expected an array of shape (..., 4), got shape (2,)
    """

    def __init__(self, *specs):
        self.names = [name for _, name, _ in specs]
        self.arrays = []
        self.trailing = []
        for value, name, trailing in specs:
            trail = (
                ()
                if trailing is None
                else (trailing if isinstance(trailing, tuple) else (trailing,))
            )
            a = as_float_array(value, name, last=trail[-1] if trail else None, finite=False)
            if a.shape[a.ndim - len(trail) :] != trail or a.ndim < len(trail):
                expected = ", ".join(["..."] + [str(t) for t in trail])
                raise InputError(
                    f"{name}: expected an array of shape ({expected}), got shape {a.shape}"
                )
            self.arrays.append(a)
            self.trailing.append(trail)
        leading = [
            a.shape[: a.ndim - len(t)] for a, t in zip(self.arrays, self.trailing, strict=True)
        ]
        try:
            self.shape = np.broadcast_shapes(*leading)
        except ValueError:
            described = ", ".join(f"{n} {s}" for n, s in zip(self.names, leading, strict=True))
            raise InputError(f"leading shapes do not broadcast: {described}") from None
        self.n = math.prod(self.shape)
        self.flat = []
        steps = []
        for a, lead, trail in zip(self.arrays, leading, self.trailing, strict=True):
            size = math.prod(lead)
            if lead == self.shape or size == 1:
                f = np.ascontiguousarray(a.reshape((size, *trail)))
                steps.append(1 if size == self.n else 0)
            else:
                f = np.ascontiguousarray(
                    np.broadcast_to(a, self.shape + trail).reshape((self.n, *trail))
                )
                steps.append(1)
            self.flat.append(f)
        self.steps = tuple(steps)

    def empty(self, *trailing: int) -> np.ndarray:
        """A flat output array with ``trailing`` item shape."""
        return np.empty((self.n, *trailing))

    def shaped(self, out: np.ndarray) -> np.ndarray:
        """The flat output reshaped to the broadcast leading shape."""
        return out.reshape(self.shape + out.shape[1:])

    def fail(self, index: int, *, unit=(), nonzero=(), what: str = "result") -> None:
        """Raise the error behind a loop's failure at flat ``index`` (no-op when -1).

        Checks, in order: finiteness of every argument, unit norm of the arguments named in
        ``unit``, nonzero norm of those in ``nonzero``; otherwise the result overflowed.
        """
        if index < 0:
            return
        for a, name in zip(self.arrays, self.names, strict=True):
            check_finite(a, name)
        for a, name in zip(self.arrays, self.names, strict=True):
            if name in unit:
                require_unit(a, name, UNIT_TOLERANCE)
            if name in nonzero:
                axes = tuple(range(-len(self.trailing[self.names.index(name)]), 0))
                zero = ~np.any(a != 0, axis=axes) if axes else a == 0
                if np.any(zero):
                    where = tuple(int(i) for i in np.argwhere(zero)[0]) if zero.ndim else ()
                    raise InputError(f"{name}: expected nonzero values, got zero at index {where}")
        where = tuple(int(i) for i in np.unravel_index(index, self.shape))
        raise InputError(
            f"{', '.join(self.names)}: {what} is not finite at index {where} "
            "(overflow of float64); rescale the input"
        )


# Row access for the compiled loops: tuples in and out, so the scalar kernels inline.


@jit
def row4(a, i):
    return (a[i, 0], a[i, 1], a[i, 2], a[i, 3])


@jit
def row3(a, i):
    return (a[i, 0], a[i, 1], a[i, 2])


@jit
def put(out, i, r):
    for k in range(len(r)):
        out[i, k] = r[k]


@jit
def finite(r):
    """All entries of tuple r finite: x - x is 0 for finite x and NaN for ±inf and NaN."""
    s = 0.0
    for k in range(len(r)):
        s += r[k] - r[k]
    return s == 0.0
