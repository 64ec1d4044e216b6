"""The compiled batch loops behind :mod:`ga_rotors.quaternion`: one per operation.

Each loop is a thin shell around one scalar kernel of :mod:`ga_rotors._kernels`, run over
rows of flat arrays with strides (a stride of 0 broadcasts one row), and returns True when
every result is finite (see :func:`ga_rotors._batch.residue`). Why checking the result
suffices is noted per loop: NaN or inf inputs always reach the result there.
:mod:`ga_rotors.quaternion` validates, broadcasts and names the bad argument.
"""

from __future__ import annotations

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
