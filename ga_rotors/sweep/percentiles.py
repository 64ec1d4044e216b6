"""Exact medians and percentiles of more values than memory holds, read block by block.

A sweep's store can hold 10⁸ samples per output time; its summary's median and 95th
percentile are those ``numpy.median`` and ``numpy.percentile`` give, to the bit, without
holding a column: the values at the ranks they interpolate between are found by a
radix selection over the bits of the float64 values (mapped to unsigned integers whose
order is the floats' order), 16 bits a pass, so four passes over the blocks (each pass
one ``bincount`` of 65,536 bins per rank) find them exactly, whatever their spread.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

import numpy as np

__all__ = ["percentiles"]

_SIGN = np.uint64(1 << 63)
_DIGIT_BITS = 16
_DIGITS = 1 << _DIGIT_BITS


def _ordered(v: np.ndarray) -> np.ndarray:
    """float64 -> uint64 in the same order (negatives flipped whole, positives' sign set)."""
    bits = np.ascontiguousarray(v, dtype=np.float64).view(np.uint64)
    return np.where(bits & _SIGN, ~bits, bits | _SIGN)


def _float(key: int) -> float:
    """The float64 whose ordered key is ``key`` (the inverse of :func:`_ordered`)."""
    k = np.uint64(key)
    bits = k & ~_SIGN if k & _SIGN else ~k
    return float(np.array([bits], dtype=np.uint64).view(np.float64)[0])


def _select(blocks: Callable[[], Iterable[np.ndarray]], top: np.ndarray, ranks: list[int]):
    """The values at 0-based ``ranks`` of the sorted non-NaN values, given the counts of
    their keys' top 16 bits (``top``)."""
    prefixes, left = [], []
    cum = np.cumsum(top)
    for r in ranks:
        d = int(np.searchsorted(cum, r, side="right"))
        prefixes.append(d)
        left.append(r - (int(cum[d - 1]) if d else 0))
    for shift in range(64 - 2 * _DIGIT_BITS, -1, -_DIGIT_BITS):
        counts = np.zeros((len(ranks), _DIGITS), dtype=np.int64)
        for v in blocks():
            keys = _ordered(v[~np.isnan(v)])
            high = keys >> np.uint64(shift + _DIGIT_BITS)
            for i, p in enumerate(prefixes):
                digit = (keys[high == np.uint64(p)] >> np.uint64(shift)) & np.uint64(_DIGITS - 1)
                counts[i] += np.bincount(digit.astype(np.intp), minlength=_DIGITS)
        for i in range(len(ranks)):
            cum = np.cumsum(counts[i])
            d = int(np.searchsorted(cum, left[i], side="right"))
            left[i] -= int(cum[d - 1]) if d else 0
            prefixes[i] = (prefixes[i] << _DIGIT_BITS) | d
    return [_float(p) for p in prefixes]


def _between(a: float, b: float, g: float) -> float:
    """``a + (b - a)·g``, from the nearer end (how numpy's 'linear' percentile ends)."""
    diff = b - a
    return float(b - diff * (1.0 - g)) if g >= 0.5 else float(a + diff * g)


def percentiles(
    blocks: Callable[[], Iterable[np.ndarray]], qs: Iterable[float]
) -> tuple[float, list[float], float, int]:
    """The median, the ``qs`` percentiles and the maximum of the non-NaN values that
    ``blocks()`` yields (1-D arrays; called once per pass, five passes), and how many
    there are. NaN where there are none.

    Equal to ``numpy.median``, ``numpy.percentile`` (its default 'linear' method) and
    ``numpy.max`` of all the values at once, holding one block at a time.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.random.default_rng(1).standard_normal(10_001) ** 2
    >>> x[::7] = np.nan
    >>> blocks = lambda: (x[i : i + 1000] for i in range(0, x.size, 1000))
    >>> m, (p95,), top, n = percentiles(blocks, [95])
    >>> y = x[~np.isnan(x)]
    >>> (m, p95, top, n) == (np.median(y), np.percentile(y, 95), y.max(), y.size)
    True
    """
    top = np.zeros(_DIGITS, dtype=np.int64)
    shift = np.uint64(64 - _DIGIT_BITS)
    largest = -np.inf
    for v in blocks():
        v = v[~np.isnan(v)]
        if v.size:
            top += np.bincount((_ordered(v) >> shift).astype(np.intp), minlength=_DIGITS)
            largest = max(largest, float(v.max()))
    n = int(top.sum())
    qs = list(qs)
    if not n:
        return np.nan, [np.nan] * len(qs), np.nan, 0
    ranks = {(n - 1) // 2, n // 2}
    where = []
    for q in qs:
        virtual = (n - 1) * (q / 100)  # numpy's virtual index of the 'linear' method
        below = int(np.floor(virtual))
        where.append((below, min(below + 1, n - 1), virtual - below))
        ranks |= {below, min(below + 1, n - 1)}
    order = sorted(ranks)
    value = dict(zip(order, _select(blocks, top, order), strict=True))
    a, b = value[(n - 1) // 2], value[n // 2]
    median = a if n % 2 else float((a + b) / 2)
    return median, [_between(value[i], value[j], g) for i, j, g in where], largest, n
