"""Float64 values as decimal text, compiled: how the CSV writer formats its rows.

:func:`format_rows` writes a block of rows as ``%.17g`` writes each value (17
significant digits, which identify every float64; trailing zeros dropped; the exponent
form below 1e-4 and from 1e17; ``nan``, ``inf``, ``-0``), comma-separated, one line per
row, in one compiled pass over the block: no Python object per value.

The 17 digits come from the value times a power of ten carried in double-double
arithmetic (about 32 significant digits, Dekker's exact products), so they are the
correctly rounded ones unless the exact value lies within about 1e-30 (relative) of a
rounding boundary; either neighbour then still reads back as the same float64: it is
half a unit of the 17th digit away (at most 5e-17 relative), less than half a float64
ulp (at least 5.5e-17 relative). ``tests/test_results.py`` compares with Python's
``%.17g`` on values of every magnitude, and reads every value back.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .._jit import jit

__all__ = ["format_rows"]

#: 10^p as double-double (hi, lo), p in [-_HALF, _HALF]: a scale 10^s is two of them.
_HALF = 175


def _powers() -> np.ndarray:
    out = np.empty((2 * _HALF + 1, 2))
    for p in range(-_HALF, _HALF + 1):
        exact = Fraction(10) ** p
        hi = float(exact)  # correctly rounded
        out[p + _HALF] = hi, float(exact - Fraction(hi))
    return out


_POW10 = _powers()
_SPLIT = 134217729.0  # 2^27 + 1
_BIG, _TINY = 2.0**100, 2.0**-100


@jit
def _two_prod(a, b):
    """a·b = p + e exactly (Dekker; no overflow for |a|, |b| < 1e290)."""
    p = a * b
    c = _SPLIT * a
    a_hi = c - (c - a)
    a_lo = a - a_hi
    c = _SPLIT * b
    b_hi = c - (c - b)
    b_lo = b - b_hi
    e = ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo
    return p, e


@jit
def _dd_mul(a_hi, a_lo, b_hi, b_lo):
    p, e = _two_prod(a_hi, b_hi)
    e += a_hi * b_lo + a_lo * b_hi
    hi = p + e
    return hi, e - (hi - p)


@jit
def _scaled(ax, k, pow10):
    """ax·10^(16−k) as double-double (two factors from the table beyond its range)."""
    s = 16 - k
    if -_HALF <= s <= _HALF:  # one factor (values within about 1e±160)
        hi, lo = _two_prod(ax, pow10[s + _HALF, 0])
        lo += ax * pow10[s + _HALF, 1]
        h = hi + lo
        return h, lo - (h - hi)
    s1 = s // 2
    s2 = s - s1
    f_hi, f_lo = pow10[s1 + _HALF, 0], pow10[s1 + _HALF, 1]
    if ax > 1e290:  # keep Dekker's splits finite: scale by a power of two, exactly
        ax *= _TINY
        f_hi *= _BIG
        f_lo *= _BIG
    elif ax < 1e-290:  # subnormal or nearly: exact splits need normal numbers
        ax *= _BIG
        f_hi *= _TINY
        f_lo *= _TINY
    hi, lo = _two_prod(ax, f_hi)
    lo += ax * f_lo
    h = hi + lo
    lo = lo - (h - hi)
    return _dd_mul(h, lo, pow10[s2 + _HALF, 0], pow10[s2 + _HALF, 1])


@jit
def _digits(ax, pow10, out):
    """The 17 correctly rounded digits of ax > 0 into ``out``; returns the exponent k."""
    k = int(np.floor(np.log10(ax)))
    for _ in range(4):  # log10 may be one off next to a power of ten
        hi, lo = _scaled(ax, k, pow10)
        # hi + lo is within ~1e-31 (relative) of the exact product: at a boundary, a
        # lo below -1e-9 is a value below it, anything closer is the power of ten itself
        # (no other float64 lies within 1e-25 of one; if one did, 17 digits round it
        # to the power of ten anyway)
        if hi < 1e16 or (hi == 1e16 and lo < -1e-9):
            k -= 1
        elif hi > 1e17 or (hi == 1e17 and lo > -1e-8):
            k += 1
        else:
            break
    below = np.floor(lo)  # |lo| <= 8: hi is an integer (> 2^53), lo the rest
    n = np.int64(hi) + np.int64(below)
    frac = lo - below
    if frac > 0.5 or (frac == 0.5 and n % 2 == 1):
        n += 1
    if n == 100_000_000_000_000_000:  # rounded up to the next power of ten
        n = 10_000_000_000_000_000
        k += 1
    u = np.uint64(n)  # unsigned: division without Python's sign rules, 4x faster
    ten = np.uint64(10)
    for i in range(16, -1, -1):
        q = u // ten
        out[i] = u - q * ten
        u = q
    return k


@jit
def _put(buf, at, text):
    for i in range(len(text)):
        buf[at + i] = ord(text[i])
    return at + len(text)


@jit
def _value(x, pow10, digits, buf, at):
    """Write x as %.17g writes it; return the new end."""
    if x != x:
        return _put(buf, at, "nan")
    if x < 0.0 or (x == 0.0 and np.signbit(x)):
        buf[at] = 45  # "-"
        at += 1
        x = -x
    if x == np.inf:
        return _put(buf, at, "inf")
    if x == 0.0:
        buf[at] = 48
        return at + 1
    k = _digits(x, pow10, digits)
    last = 16
    while last > 0 and digits[last] == 0:
        last -= 1
    if -4 <= k < 17:
        if k >= 0:
            for i in range(k + 1):
                buf[at] = 48 + digits[i]
                at += 1
            if last > k:
                buf[at] = 46  # "."
                at += 1
                for i in range(k + 1, last + 1):
                    buf[at] = 48 + digits[i]
                    at += 1
        else:
            buf[at] = 48
            buf[at + 1] = 46
            at += 2
            for _ in range(-k - 1):
                buf[at] = 48
                at += 1
            for i in range(last + 1):
                buf[at] = 48 + digits[i]
                at += 1
        return at
    buf[at] = 48 + digits[0]
    at += 1
    if last > 0:
        buf[at] = 46
        at += 1
        for i in range(1, last + 1):
            buf[at] = 48 + digits[i]
            at += 1
    buf[at] = 101  # "e"
    buf[at + 1] = 45 if k < 0 else 43
    at += 2
    e = -k if k < 0 else k
    if e >= 100:
        buf[at] = 48 + e // 100
        at += 1
    buf[at] = 48 + (e // 10) % 10
    buf[at + 1] = 48 + e % 10
    return at + 2


@jit
def _rows(block, lengths, first, pow10, buf):
    digits = np.zeros(17, dtype=np.uint8)
    at = 0
    n, m = block.shape
    for r in range(n):
        for j in range(m):
            if j:
                buf[at] = 44  # ","
                at += 1
            if first + r < lengths[j]:
                at = _value(block[r, j], pow10, digits, buf, at)
        buf[at] = 10
        at += 1
    return at


#: Bytes a value may take: sign, 17 digits, "0." and four zeros or an exponent, a comma.
MAX_CHARS = 26


def format_rows(block, lengths=None, first: int = 0) -> bytes:
    """Rows of ``block`` (n, m) as CSV text: ``%.17g`` values, commas, newlines.

    Parameters
    ----------
    block : array_like (n, m)
    lengths : array_like (m,) of int, optional
        Rows each column has (counted from row 0 of the run); the cells of a row
        ``first + r >= lengths[j]`` are left empty (a path that stopped early).
    first : int
        The run's row number of the block's row 0.

    Examples
    --------
    >>> format_rows([[0.1, -2.5e-7, 1e17], [1 / 3, float("nan"), -0.0]])
    b'0.10000000000000001,-2.4999999999999999e-07,1e+17\\n0.33333333333333331,nan,-0\\n'
    >>> format_rows([[1.0, 2.0], [3.0, 4.0]], lengths=[2, 1])
    b'1,2\\n3,\\n'
    """
    block = np.ascontiguousarray(block, dtype=np.float64)
    if block.ndim != 2:
        block = block.reshape(block.shape[0], -1)
    n, m = block.shape
    if lengths is None:
        lengths = np.full(m, first + n, dtype=np.int64)
    lengths = np.asarray(lengths, dtype=np.int64)
    buf = np.empty(n * (m * MAX_CHARS + 1), dtype=np.uint8)
    end = _rows(block, lengths, int(first), _POW10, buf)
    return buf[:end].tobytes()
