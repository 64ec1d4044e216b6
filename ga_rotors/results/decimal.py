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
ulp (at least 5.5e-17 relative). ``tests/test_stream.py`` compares with Python's
``%.17g`` on values of every magnitude, and reads every value back.

Speed (about 12 ns a value on a heavy top's 16 columns, one thread on an idle machine;
16.4 before the vector pass, about 100 in the first version; the CSV of a long run is
most of its output work): the decimal exponent is guessed from the float's binary
exponent instead of a log10; each row's numbers are found first, by straight-line code
(:func:`_decimal_fast`, the rare values it cannot settle passed to :func:`_decimal`),
all independent of one another, so the processor overlaps them instead of waiting for
each value's length, and eight at a time in vector registers where a row has eight
(:func:`_decimal8`: 3 ns a value instead of 8); the product's rounding error is one
fused multiply-add (where the processor has one; elsewhere a library call, the same
digits); the 17 digits are then one integer split into 1 + 8 + 8 digits, each 8 turned
into ASCII at once in a 64-bit word (SWAR) and stored in one go, the point put in by
storing the word it splits a second time, shifted, and the last nonzero digit found
by counting zero bits, so no byte is read back; nothing branches on a value's sign
(an oscillating column's signs are a coin toss for the branch predictor: 27 → 17 ns a
value with the rest of this paragraph's last three items); the helpers are inlined
into the row loop (a call passing an array costs reference counting per value).
"""

from __future__ import annotations

import sys
from fractions import Fraction

import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

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
#: The same table's two columns, each contiguous: what :func:`_decimal8` loads from.
_POW10_HI, _POW10_LO = np.ascontiguousarray(_POW10[:, 0]), np.ascontiguousarray(_POW10[:, 1])
_SPLIT = 134217729.0  # 2^27 + 1
_BIG, _TINY = 2.0**100, 2.0**-100


@jit(inline="always")
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


@jit(inline="always")
def _dd_mul(a_hi, a_lo, b_hi, b_lo):
    p, e = _two_prod(a_hi, b_hi)
    e += a_hi * b_lo + a_lo * b_hi
    hi = p + e
    return hi, e - (hi - p)


@jit(inline="always")
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


#: The decimal exponent's first guess from the binary one: floor(e₂ · log₁₀ 2).
_LOG10_2 = 0.30102999566398120

#: 10^p rounded to float64 (inf beyond the range), p in [-_TENS, _TENS]: moves the first
#: guess up by one.
_TENS = 330
_ROUNDED10 = np.array([float(f"1e{p}") for p in range(-_TENS, _TENS + 1)])

#: What :func:`_decimal` returns as the exponent of values without digits.
_NAN, _INF, _ZERO = 1000, 1001, 1002


@jit(inline="always")
def _exponent(ax, biased, tens):
    """floor(log10(ax)) for ax > 0, or one below it (:func:`_decimal` corrects either way).

    ``biased`` is the float's exponent field: ax ∈ [2^b, 2^(b+1)), b = biased − 1023, so
    log10 ax ∈ [b log10 2, (b + 1) log10 2), less than one decade wide: the guess from b
    is the exponent or one below, and one comparison with 10^(guess + 1) (rounded) settles
    it except within an ulp of a power of ten, where the digits' check does.
    """
    if biased == 0:  # subnormal: no implicit bit, the field says nothing
        return int(np.floor(np.log10(ax)))
    k = int(np.floor((biased - 1023) * _LOG10_2))
    if ax >= tens[k + 1 + _TENS]:
        k += 1
    return k


@jit(inline="always")
def _decimal(x, biased, pow10, tens):
    """(n, k): |x| rounded to 17 significant digits, n · 10^(k − 16) with
    10^16 <= n < 10^17; k is _NAN, _INF or _ZERO for values without digits.
    ``biased``: x's exponent field (:func:`_exponent`)."""
    if x != x:
        return 0, _NAN
    ax = abs(x)
    if ax == np.inf:
        return 0, _INF
    if ax == 0.0:
        return 0, _ZERO
    k = _exponent(ax, biased, tens)
    for _ in range(4):  # the guess may be one off next to a power of ten
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
    n += np.int64((frac > 0.5) | ((frac == 0.5) & (n & 1 == 1)))  # half to even
    if n == 100_000_000_000_000_000:  # rounded up to the next power of ten
        n = 10_000_000_000_000_000
        k += 1
    return n, k


@intrinsic
def _fma(typingctx, a, b, c):
    """a·b + c rounded once (LLVM's fma: one instruction where the processor has it)."""

    def codegen(context, builder, sig, args):
        return builder.fma(*args)

    return types.float64(types.float64, types.float64, types.float64), codegen


@intrinsic
def _leading_zero_bits(typingctx, word):
    """The number of leading zero bits of a nonzero uint64."""

    def codegen(context, builder, sig, args):
        return builder.ctlz(args[0], ir.Constant(ir.IntType(1), 1))

    return types.uint64(types.uint64), codegen


@jit(inline="always")
def _decimal_fast(x, biased, pow10, tens):
    """:func:`_decimal` for the common case, without a branch: (n, k, ok), ``ok`` false
    where the value needs :func:`_decimal` (zero, subnormal, inf, nan, beyond one table
    factor, or with hi at a power of ten, where the guessed exponent may be one off).

    Straight-line code over a row's values lets the compiler keep several in flight (about
    twice as fast as :func:`_decimal`'s loop, which it then runs for the few left over).
    """
    ax = abs(x)
    k = np.int64(np.floor((biased - 1023) * _LOG10_2))
    k += np.int64(ax >= tens[k + 1 + _TENS])
    s = 16 - k
    si = min(max(s, -_HALF), _HALF)
    f_hi = pow10[si + _HALF, 0]
    f_lo = pow10[si + _HALF, 1]
    p = ax * f_hi
    e = _fma(ax, f_hi, -p) + ax * f_lo  # the product's rounding error, exactly
    hi = p + e
    lo = e - (hi - p)
    ok = (s == si) & (biased != 0) & (biased != 2047) & (hi > 1e16) & (hi < 1e17)
    h = hi if ok else 1e16
    below = np.floor(lo)
    n = np.int64(h) + np.int64(below)
    frac = lo - below
    n += np.int64((frac > 0.5) | ((frac == 0.5) & (n & 1 == 1)))  # half to even
    top = n == 100_000_000_000_000_000  # rounded up to the next power of ten
    n = 10_000_000_000_000_000 if top else n
    k += np.int64(top)
    return n, k, ok


#: Values :func:`_decimal8` takes at once: one AVX-512 register of float64 (on a processor
#: with narrower vectors LLVM splits each operation, with the same results).
LANES = 8


class _Vectors:
    """LLVM IR for :func:`_decimal8`: the operations of :func:`_decimal_fast` on vectors
    of :data:`LANES` float64 or int64, one instruction each where the processor has it."""

    def __init__(self, builder):
        self.b = builder
        self.f64 = ir.VectorType(ir.DoubleType(), LANES)
        self.i64 = ir.VectorType(ir.IntType(64), LANES)

    def f(self, c):
        return ir.Constant(self.f64, [float(c)] * LANES)

    def i(self, c):
        return ir.Constant(self.i64, [int(c)] * LANES)

    def call(self, name, *args):
        """LLVM's vector form of ``name`` (llvm.floor, llvm.fma, llvm.smax...)."""
        from numba.core import cgutils

        ty = args[0].type
        suffix = f".v{LANES}{'f64' if ty == self.f64 else 'i64'}"
        fn = cgutils.get_or_insert_function(
            self.b.module, ir.FunctionType(ty, [a.type for a in args]), name + suffix
        )
        return self.b.call(fn, args)

    def load(self, base, at, ty):
        return self.b.load(self.b.bitcast(self.b.gep(base, [at]), ty.as_pointer()), align=1)

    def store(self, value, base, at):
        self.b.store(value, self.b.bitcast(self.b.gep(base, [at]), value.type.as_pointer()),
                     align=1)  # fmt: skip

    def table(self, base, index):
        """table[index] lane by lane, as scalar loads: llvmlite's IR builder has no vector
        address (a gather's operand), and numba's own vectorizer left every loop with
        such a look-up scalar."""
        out = ir.Constant(self.f64, ir.Undefined)
        for lane in range(LANES):
            at = self.b.extract_element(index, ir.Constant(ir.IntType(32), lane))
            value = self.b.load(self.b.gep(base, [at]), align=8)
            out = self.b.insert_element(out, value, ir.Constant(ir.IntType(32), lane))
        return out

    def count(self, flags):
        return self.b.zext(flags, self.i64)


@intrinsic
def _decimal8(typingctx, values, at, pow_hi, pow_lo, tens, digits, exponents, fast, to):
    """:func:`_decimal_fast` of ``values[at : at + LANES]`` at once, into
    ``digits[to:]``, ``exponents[to:]`` and ``fast[to:]`` (its n, k and ok).

    The same operations on each lane, in the same order, each rounded once (IEEE
    arithmetic is the same in a vector register): the same numbers, bit for bit
    (``tests/test_stream.py`` compares every lane with :func:`_decimal_fast`). A row
    of a heavy top's CSV (16 values) is two calls; a value then costs about 3 ns here
    instead of 8 (the text it becomes, :func:`_text`, still one value at a time).
    """
    sig = types.void(values, at, pow_hi, pow_lo, tens, digits, exponents, fast, to)

    def codegen(context, builder, signature, args):
        ptr = [context.make_array(t)(context, builder, a).data if isinstance(t, types.Array)
               else a for t, a in zip(signature.args, args, strict=True)]  # fmt: skip
        src, at, hi_table, lo_table, tens_table, n_out, k_out, ok_out, to = ptr
        v, b = _Vectors(builder), builder
        x = v.load(src, at, v.f64)
        biased = b.and_(b.lshr(b.bitcast(x, v.i64), v.i(52)), v.i(0x7FF))
        ax = v.call("llvm.fabs", x)
        k = b.fptosi(v.call("llvm.floor", b.fmul(b.sitofp(b.sub(biased, v.i(1023)), v.f64),
                                                 v.f(_LOG10_2))), v.i64)  # fmt: skip
        ten = v.table(tens_table, b.add(k, v.i(1 + _TENS)))
        k = b.add(k, v.count(b.fcmp_ordered(">=", ax, ten)))
        s = b.sub(v.i(16), k)
        si = v.call("llvm.smin", v.call("llvm.smax", s, v.i(-_HALF)), v.i(_HALF))
        f_hi = v.table(hi_table, b.add(si, v.i(_HALF)))
        f_lo = v.table(lo_table, b.add(si, v.i(_HALF)))
        p = b.fmul(ax, f_hi)
        e = b.fadd(v.call("llvm.fma", ax, f_hi, b.fneg(p)), b.fmul(ax, f_lo))
        hi = b.fadd(p, e)
        lo = b.fsub(e, b.fsub(hi, p))
        ok = b.icmp_signed("==", s, si)
        ok = b.and_(ok, b.icmp_signed("!=", biased, v.i(0)))
        ok = b.and_(ok, b.icmp_signed("!=", biased, v.i(2047)))
        ok = b.and_(ok, b.fcmp_ordered(">", hi, v.f(1e16)))
        ok = b.and_(ok, b.fcmp_ordered("<", hi, v.f(1e17)))
        h = b.select(ok, hi, v.f(1e16))
        below = v.call("llvm.floor", lo)
        n = b.add(b.fptosi(h, v.i64), b.fptosi(below, v.i64))
        frac = b.fsub(lo, below)
        odd = b.icmp_signed("==", b.and_(n, v.i(1)), v.i(1))
        half_up = b.and_(b.fcmp_ordered("==", frac, v.f(0.5)), odd)  # half to even
        n = b.add(n, v.count(b.or_(b.fcmp_ordered(">", frac, v.f(0.5)), half_up)))
        top = b.icmp_signed("==", n, v.i(100_000_000_000_000_000))  # up to a power of ten
        n = b.select(top, v.i(10_000_000_000_000_000), n)
        k = b.add(k, v.count(top))
        v.store(n, n_out, to)
        v.store(k, k_out, to)
        v.store(b.zext(ok, ir.VectorType(ir.IntType(8), LANES)), ok_out, to)
        return context.get_dummy_value()

    return sig, codegen


@intrinsic
def _store8(typingctx, buf, at, word):
    """Store the 8 bytes of ``word`` (uint64, little-endian) at ``buf[at : at + 8]``,
    unaligned: one store instead of eight."""

    def codegen(context, builder, sig, args):
        array = context.make_array(sig.args[0])(context, builder, args[0])
        target = builder.bitcast(builder.gep(array.data, [args[1]]), ir.IntType(64).as_pointer())
        # the first digit is the word's lowest byte: first in memory only on a
        # little-endian machine, so a big-endian one swaps the bytes before storing
        word = args[2] if sys.byteorder == "little" else builder.bswap(args[2])
        builder.store(word, target).align = 1
        return context.get_dummy_value()

    return types.void(buf, types.intp, types.uint64), codegen


@jit(inline="always")
def _ascii8(v):
    """The 8 decimal digits of v < 10^8 as ASCII, first digit in the lowest byte: the two
    4-digit halves in 32-bit lanes, split into 2-digit and then 1-digit lanes by
    multiplications standing in for divisions by 100 and 10 (exact below 10^4 and 10^2)."""
    x = np.uint64(v)
    hi = x // np.uint64(10_000)
    m = hi | ((x - hi * np.uint64(10_000)) << np.uint64(32))
    y = ((m * np.uint64(10486)) >> np.uint64(20)) & np.uint64(0x0000007F0000007F)
    z = y | ((m - y * np.uint64(100)) << np.uint64(16))
    t = ((z * np.uint64(103)) >> np.uint64(10)) & np.uint64(0x000F000F000F000F)
    return (t | ((z - t * np.uint64(10)) << np.uint64(8))) + np.uint64(0x3030303030303030)


@jit(inline="always")
def _put(buf, at, text):
    for i in range(len(text)):
        buf[at + i] = ord(text[i])
    return at + len(text)


_ZEROS = np.uint64(0x3030303030303030)


@jit(inline="always")
def _zeros_after(word):
    """How many of the 8 ASCII digits of ``word`` (:func:`_ascii8`, not all zeros) end it
    as zeros: its last digits are its highest bytes."""
    return np.int64(_leading_zero_bits(word ^ _ZEROS) >> np.uint64(3))


@jit(inline="always")
def _text(n, k, negative, buf, at):
    """Write the value (n, k) of :func:`_decimal` (``negative``: its sign bit) as %.17g
    writes it into ``buf`` from ``at``; return the new end.

    The 17 digits are the first one and two words of 8 ASCII digits; the point goes
    between them by storing the word it splits twice (the second time shifted past the
    point), so no byte is read back; the last nonzero digit is found from the words.
    Stores may reach 26 bytes from where the value starts (its sign included): junk
    past its end, overwritten by what comes next (:data:`MAX_CHARS` keeps room for it).
    """
    if k == _NAN:  # %g prints nan without its sign
        return _put(buf, at, "nan")
    buf[at] = 45  # "-", kept only if negative: no branch on a sign (half of them would
    at += np.int64(negative)  # be mispredicted in an oscillating column)
    if k == _INF:
        return _put(buf, at, "inf")
    if k == _ZERO:
        buf[at] = 48
        return at + 1
    u = np.uint64(n)  # unsigned: division without Python's sign rules
    top = u // np.uint64(100_000_000)
    first = top // np.uint64(100_000_000)
    low = u - top * np.uint64(100_000_000)
    mid = top - first * np.uint64(100_000_000)
    w1 = _ascii8(mid)
    w2 = _ascii8(low)
    if low != 0:
        last = 16 - _zeros_after(w2)  # the last nonzero digit
    elif mid != 0:
        last = 8 - _zeros_after(w1)
    else:
        last = 0
    if -4 <= k < 0:  # "0.000" and the digits
        _store8(buf, at, np.uint64(0x3030303030302E30))
        d = at + 1 - k
        buf[d] = 48 + np.uint8(first)
        _store8(buf, d + 1, w1)
        _store8(buf, d + 9, w2)
        return d + last + 1
    buf[at] = 48 + np.uint8(first)
    _store8(buf, at + 1, w1)
    fixed = 0 <= k < 17
    point = k if fixed else 0  # digits 0..point go before the "."
    if point < 8:  # the point splits w1: w1's digits after it again, one byte on
        _store8(buf, at + point + 2, w1 >> np.uint64(8 * point))
        _store8(buf, at + 10, w2)
    else:  # at 8: between w1 and w2; beyond, it splits w2 (at 16: nothing after it)
        _store8(buf, at + 9, w2)
        if point < 16:
            _store8(buf, at + point + 2, w2 >> np.uint64(8 * (point - 8)))
    buf[at + point + 1] = 46  # "."
    end = at + last + 2 if last > point else at + point + 1
    if fixed:
        return end
    buf[end] = 101  # "e"
    buf[end + 1] = 45 if k < 0 else 43
    end += 2
    e = -k if k < 0 else k
    if e >= 100:
        buf[end] = 48 + e // 100
        end += 1
    buf[end] = 48 + (e // 10) % 10
    buf[end + 1] = 48 + e % 10
    return end + 2


@jit
def _rows(block, bits, lengths, first, pow10, pow_hi, pow_lo, tens, buf):
    n, m = block.shape
    values = block.reshape(n * m)
    digits = np.empty(m, dtype=np.int64)
    exponents = np.empty(m, dtype=np.int64)
    fast = np.empty(m, dtype=np.bool_)
    vectors = m - m % LANES
    at = 0
    for r in range(n):
        # a row's numbers, independent of one another: LANES at a time, then the rest
        for j in range(0, vectors, LANES):
            _decimal8(values, r * m + j, pow_hi, pow_lo, tens, digits, exponents, fast, j)
        for j in range(vectors, m):
            biased = np.int64((bits[r, j] >> np.uint64(52)) & np.uint64(0x7FF))
            digits[j], exponents[j], fast[j] = _decimal_fast(block[r, j], biased, pow10, tens)
        done = True
        for j in range(m):
            done &= fast[j]
        if not done:  # the rare values the fast path leaves
            for j in range(m):
                if not fast[j]:
                    biased = np.int64((bits[r, j] >> np.uint64(52)) & np.uint64(0x7FF))
                    digits[j], exponents[j] = _decimal(block[r, j], biased, pow10, tens)
        for j in range(m):  # then their text, one after the other
            if j:
                buf[at] = 44  # ","
                at += 1
            if first + r < lengths[j]:
                negative = (bits[r, j] >> np.uint64(63)) != 0
                at = _text(digits[j], exponents[j], negative, buf, at)
        buf[at] = 10
        at += 1
    return at


#: Bytes a value may take: sign, 17 digits, "0." and four zeros or an exponent, a comma
#: (and what :func:`_text` stores past a value's end, at most 26 bytes from its start).
MAX_CHARS = 26


def format_rows(block, lengths=None, first: int = 0, out=None):
    """Rows of ``block`` (n, m) as CSV text: ``%.17g`` values, commas, newlines.

    Parameters
    ----------
    block : array_like (n, m)
    lengths : array_like (m,) of int, optional
        Rows each column has (counted from row 0 of the run); the cells of a row
        ``first + r >= lengths[j]`` are left empty (a path that stopped early).
    first : int
        The run's row number of the block's row 0.
    out : ndarray of uint8, optional
        A buffer of at least n (m MAX_CHARS + 1) bytes to write into, for a caller that
        formats block after block and writes each at once (no new buffer and no copy per
        block: a tenth of a long run's CSV work, measured); a memoryview of its first
        bytes is then returned, valid until the buffer is written again.

    Returns
    -------
    bytes, or memoryview when ``out`` is given

    Examples
    --------
    >>> format_rows([[0.1, -2.5e-7, 1e17], [1 / 3, float("nan"), -0.0]])
    b'0.10000000000000001,-2.4999999999999999e-07,1e+17\\n0.33333333333333331,nan,-0\\n'
    >>> format_rows([[1.0, 2.0], [3.0, 4.0]], lengths=[2, 1])
    b'1,2\\n3,\\n'
    >>> bytes(format_rows([[0.5]], out=np.empty(64, dtype=np.uint8)))
    b'0.5\\n'
    """
    block = np.ascontiguousarray(block, dtype=np.float64)
    if block.ndim != 2:
        block = block.reshape(block.shape[0], -1)
    n, m = block.shape
    if lengths is None:
        lengths = np.full(m, first + n, dtype=np.int64)
    lengths = np.asarray(lengths, dtype=np.int64)
    size = n * (m * MAX_CHARS + 1)
    if out is None:
        buf = np.empty(size, dtype=np.uint8)
    elif out.dtype != np.uint8 or out.ndim != 1 or out.shape[0] < size:
        raise ValueError(f"out: expected a 1-D uint8 array of at least {size} bytes")
    else:
        buf = out
    bits = block.view(np.uint64)  # each value's exponent field, for free
    end = _rows(block, bits, lengths, int(first), _POW10, _POW10_HI, _POW10_LO, _ROUNDED10, buf)
    return buf[:end].tobytes() if out is None else memoryview(buf)[:end]
