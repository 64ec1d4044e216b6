"""The compiled batch loops behind :mod:`ga_rotors.quaternion`: one per operation.

Each loop is a thin shell around one scalar kernel of :mod:`ga_rotors._kernels`, run over
rows of flat arrays with strides (a stride of 0 broadcasts one row), and returns True when
every result is finite (see :func:`ga_rotors._batch.residue`). Why checking the result
suffices is noted per loop: NaN or inf inputs always reach the result there.
:mod:`ga_rotors.quaternion` validates, broadcasts and names the bad argument.
"""

from __future__ import annotations

import math

import numpy as np

from . import _kernels as K
from ._batch import put, residue, row3, row4
from ._jit import jit

__all__ = [
    "axis_angle_loop",
    "distance_loop",
    "divide_loop",
    "exp_loop",
    "from_axis_angle_loop",
    "from_rotvec_loop",
    "inverse_loop",
    "largest_distance_loop",
    "log_loop",
    "multiply_loop",
    "norm_loop",
    "normalize_loop",
    "rotate_loop",
    "rotate_one",
    "slerp_loop",
    "to_rotvec_loop",
    "two_vectors_loop",
]


@jit
def multiply_loop(a, sa, b, sb, out):
    # every input component multiplies some nonzero component of the other factor, or
    # multiplies zeros (inf * 0 = nan): non-finite inputs always give a non-finite result.
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qmul(row4(a, n * sa), row4(b, n * sb))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def divide_loop(a, sa, b, sb, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qmul(row4(a, n * sa), K.qinverse(row4(b, n * sb)))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def inverse_loop(a, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qinverse(row4(a, n))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def norm_loop(a, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qnorm(row4(a, n))
        out[n] = r
        bad += r - r
    return bad == 0.0


@jit
def normalize_loop(a, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qnormalize(row4(a, n))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def rotate_loop(q, sq, v, sv, out, tol):
    # qunit turns non-unit and non-finite q into NaN; a non-finite v reaches the result
    # through its own term v + ...
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qrotate(K.qunit(row4(q, n * sq), tol), row3(v, n * sv))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def rotate_one(q, v, tol):
    return K.qrotate(K.qunit(q, tol), v)


@jit
def axis_angle_loop(q, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.axis_angle_from_quat(K.qunit(row4(q, n), tol))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def from_axis_angle_loop(u, su, t, st, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.quat_from_axis_angle(row3(u, n * su), t[n * st])
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def from_rotvec_loop(v, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.quat_from_rotvec(row3(v, n))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def to_rotvec_loop(q, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.rotvec_from_quat(K.qunit(row4(q, n), tol))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def exp_loop(a, out):
    # exp(-inf) = 0 would hide an infinite input: check the input too.
    bad = 0.0
    for n in range(out.shape[0]):
        x = row4(a, n)
        r = K.qexp(x)
        put(out, n, r)
        bad += residue(x) + residue(r)
    return bad == 0.0


@jit
def log_loop(a, out):
    bad = 0.0
    for n in range(out.shape[0]):
        x = row4(a, n)
        r = K.qlog(x)
        put(out, n, r)
        bad += residue(x) + residue(r)
    return bad == 0.0


@jit
def slerp_loop(a, sa, b, sb, t, st, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.qslerp(K.qunit(row4(a, n * sa), tol), K.qunit(row4(b, n * sb), tol), t[n * st])
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def distance_loop(a, sa, b, sb, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.geodesic_angle(K.qunit(row4(a, n * sa), tol), K.qunit(row4(b, n * sb), tol))
        out[n] = r
        bad += r - r
    return bad == 0.0


@jit
def two_vectors_loop(u, su, v, sv, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = K.quat_from_two_vectors(row3(u, n * su), row3(v, n * sv))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


#: Rows screened at a time by :func:`largest_distance_loop`.
_BLOCK = 1024


@jit
def largest_distance_loop(a, b, tol):
    """(the largest of :func:`distance_loop`'s angles from a[n] to b[n] over the rows of
    ``b`` (n, 4; ``a`` has at least as many), the first row holding it, whether every row
    was finite), without computing every angle.

    The angle is 2 asin |vec(a* ⊗ b)| for unit a, b, increasing in |vec|; |vec| without
    the normalisations is within 5e-14 + 4 tol |vec| of the normalised one (rounding, a
    few ulps of unit inputs; the inputs' allowed departure from unit, tol each), so two
    rows' |vec| and angles are in the same order unless their |vec| are within
    1e-13 + 8 tol |vec|. Only a row whose |vec| is that close to the largest |vec| seen
    so far (this block's or an earlier one's, whose
    row was then measured) can hold the largest angle: the full angle (two
    normalisations, two hypot, an atan2) is computed for those alone. Between paths that
    agree to rounding the angles grow slowly along a run, and few rows come that close.
    No rows: (−1.0, 0, True).
    """
    keys = np.empty(_BLOCK)
    best, at, ok, largest = -1.0, 0, True, 0.0
    for start in range(0, b.shape[0], _BLOCK):
        stop = min(start + _BLOCK, b.shape[0])
        top = 0.0
        for n in range(start, stop):
            d = K.qmul(K.qconj((a[n, 0], a[n, 1], a[n, 2], a[n, 3])),
                       (b[n, 0], b[n, 1], b[n, 2], b[n, 3]))  # fmt: skip
            key = d[1] * d[1] + d[2] * d[2] + d[3] * d[3]
            keys[n - start] = key
            if key > top:
                top = key
            elif not key <= top:  # nan
                ok = False
        largest = max(largest, math.sqrt(top))
        floor = max(largest - 1e-13 - 8.0 * tol * largest, 0.0)
        floor = floor * floor
        for n in range(start, stop):
            if keys[n - start] >= floor:
                r = K.geodesic_angle(
                    K.qunit((a[n, 0], a[n, 1], a[n, 2], a[n, 3]), tol),
                    K.qunit((b[n, 0], b[n, 1], b[n, 2], b[n, 3]), tol),
                )
                if r > best:
                    best, at = r, n
                elif not r <= best:
                    ok = False
    return best, at, ok
