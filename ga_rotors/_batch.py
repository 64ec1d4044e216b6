"""Broadcasting arrays into the flat form the compiled loops take, and reporting failures.

A public vectorised function validates shapes and types here, hands the loop one 2-D (or
1-D) C-contiguous array per argument, and reshapes the loop's output back. An argument
whose leading shape already is the broadcast shape, or that holds a single item, is passed
without a copy: the loop reads row ``i * step`` with ``step`` 1 or 0. Only genuinely
mixed broadcasting (say (5, 1, 4) with (1, 7, 4)) materialises a copy.

Loops check finiteness (and unit norm, where required) inside the loop, summing x - x over
their results (0 when finite, NaN otherwise) and returning whether the total is 0: no
early exit, so LLVM vectorises them (measured 5.3 against 6.1 ns per product with an
early exit). :meth:`Batch.fail` then finds out which argument was wrong on the slow path,
so the fast path makes no second pass over memory.
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit
from ._validate import UNIT_TOLERANCE, as_float_array, check_finite, require_unit
from .errors import InputError

#: item shapes by the short names the public functions use.
_TRAILS = {None: (), 3: (3,), 4: (4,)}


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

    __slots__ = ("arrays", "flat", "n", "names", "shape", "steps", "trailing")

    def __init__(self, *specs):
        # Written for a small per-call cost (a single quaternion pays it in full): no
        # broadcasting machinery unless the leading shapes differ.
        names, arrays, trailing, leading = [], [], [], []
        for value, name, trail in specs:
            trail = _TRAILS.get(trail, trail)
            if type(value) is np.ndarray and value.dtype == np.float64:
                a = value
            else:
                a = as_float_array(value, name, finite=False)
            k = a.ndim - len(trail)
            if k < 0 or a.shape[k:] != trail:
                expected = ", ".join(["..."] + [str(t) for t in trail])
                raise InputError(
                    f"expected an array of shape ({expected}), got shape {a.shape}",
                    key=name,
                )
            names.append(name)
            arrays.append(a)
            trailing.append(trail)
            leading.append(a.shape[:k])
        self.names, self.arrays, self.trailing = names, arrays, trailing
        shape = leading[0]
        if any(lead != shape for lead in leading):
            try:
                shape = np.broadcast_shapes(*leading)
            except ValueError:
                described = ", ".join(f"{n} {s}" for n, s in zip(names, leading, strict=True))
                raise InputError(f"leading shapes do not broadcast: {described}") from None
        self.shape = shape
        self.n = n = math.prod(shape)
        flat, steps = [], []
        for a, lead, trail in zip(arrays, leading, trailing, strict=True):
            size = math.prod(lead)
            if lead == shape or size == 1:
                f = a.reshape((size, *trail))
                steps.append(1 if size == n else 0)
            else:
                f = np.broadcast_to(a, shape + trail).reshape((n, *trail))
                steps.append(1)
            flat.append(f if f.flags.c_contiguous else np.ascontiguousarray(f))
        self.flat, self.steps = flat, tuple(steps)

    def empty(self, *trailing: int) -> np.ndarray:
        """A flat output array with ``trailing`` item shape."""
        return np.empty((self.n, *trailing))

    def shaped(self, out: np.ndarray) -> np.ndarray:
        """The flat output reshaped to the broadcast leading shape."""
        return out.reshape(self.shape + out.shape[1:])

    def fail(self, ok: bool, out: np.ndarray, *, unit=(), nonzero=(), what: str = "result") -> None:
        """Raise the error behind a loop that reported a non-finite value (no-op when ``ok``).

        Loops only say whether anything went wrong (an early exit would keep LLVM from
        vectorising them); this slow path finds out what. Checks, in order: finiteness of
        every argument, unit norm of the arguments named in ``unit``, nonzero norm of those
        in ``nonzero``; otherwise the result overflowed at its first non-finite item.
        """
        if ok:
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
                    raise InputError(
                        f"expected nonzero values, got zero at index {where}", key=name
                    )
        rows = ~np.isfinite(out.reshape(self.n, -1)).all(axis=1)
        where = tuple(int(i) for i in np.unravel_index(int(np.argmax(rows)), self.shape))
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
def residue(r):
    """Sum of x - x over tuple r: 0.0 when every entry is finite, NaN otherwise.

    Loops add it up over all items and test the total once: no branch in the loop body.
    """
    s = 0.0
    for k in range(len(r)):
        s += r[k] - r[k]
    return s
