"""The compiled batch loops behind :mod:`ga_rotors.motor`: one per operation.

Each loop is a thin shell around one scalar kernel (:mod:`ga_rotors._motor_kernels`,
:mod:`ga_rotors.motor._screw`) run over the rows of flat arrays with strides (a stride of
0 broadcasts one row), as :mod:`ga_rotors._quaternion_loops` does for quaternions, and
returns True when every result is finite (:func:`ga_rotors._batch.residue`). Motors that
must be unit go through :func:`~ga_rotors.motor._screw.munit`, which turns one that is not
(or a non-finite one) into NaN, so the same finiteness check catches it; the caller then
names the bad argument.
"""

from __future__ import annotations

from .. import _kernels as K
from .. import _motor_kernels as MK
from .._batch import put, residue, row3, row4
from .._jit import jit
from . import _screw as S

__all__ = [
    "apply_loop",
    "exp_loop",
    "from_pose_loop",
    "log_loop",
    "multiply_loop",
    "normalize_loop",
    "sandwich_line_loop",
    "sandwich_plane_loop",
    "sandwich_point_loop",
    "to_pose_loop",
    "unit_loop",
]


@jit
def row8(a, i):
    return (a[i, 0], a[i, 1], a[i, 2], a[i, 3], a[i, 4], a[i, 5], a[i, 6], a[i, 7])


@jit
def row6(a, i):
    return (a[i, 0], a[i, 1], a[i, 2], a[i, 3], a[i, 4], a[i, 5])


@jit
def multiply_loop(a, sa, b, sb, out):
    # Every coefficient of a multiplies the scalar part of b and vice versa (or zeros: inf
    # * 0 = nan), so a non-finite input always reaches the result.
    bad = 0.0
    for n in range(out.shape[0]):
        r = MK.mmul(row8(a, n * sa), row8(b, n * sb))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def normalize_loop(a, out):
    bad = 0.0
    for n in range(out.shape[0]):
        r = S.mnormalize(row8(a, n))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def unit_loop(a, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = S.munit(row8(a, n), tol)
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def exp_loop(b, out):
    # a non-finite input reaches the result (the ideal part is linear in it).
    bad = 0.0
    for n in range(out.shape[0]):
        r = S.mexp(row6(b, n))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def log_loop(m, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = S.mlog(S.munit(row8(m, n), tol))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def sandwich_plane_loop(m, sm, x, sx, out, tol):
    # munit flags the motor; a non-finite x reaches every output through m0² x.
    bad = 0.0
    for n in range(out.shape[0]):
        r = MK.sandwich_plane(S.munit(row8(m, n * sm), tol), row4(x, n * sx))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def sandwich_line_loop(m, sm, x, sx, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = MK.sandwich_line(S.munit(row8(m, n * sm), tol), row6(x, n * sx))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def sandwich_point_loop(m, sm, x, sx, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = MK.sandwich_point(S.munit(row8(m, n * sm), tol), row4(x, n * sx))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def apply_loop(m, sm, x, sx, out, tol):
    bad = 0.0
    for n in range(out.shape[0]):
        r = S.apply_point(S.munit(row8(m, n * sm), tol), row3(x, n * sx))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def from_pose_loop(q, sq, t, st, out, tol):
    # qunit flags the quaternion; t reaches the result through q0 t (|q| = 1).
    bad = 0.0
    for n in range(out.shape[0]):
        r = MK.motor_from_pose(K.qunit(row4(q, n * sq), tol), row3(t, n * st))
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0


@jit
def to_pose_loop(m, out, tol):
    """Rows (w, x, y, z, t₁, t₂, t₃): the quaternion and translation of each unit motor."""
    bad = 0.0
    for n in range(out.shape[0]):
        u = S.munit(row8(m, n), tol)
        q, _ = MK.dual_parts(u)
        t = MK.translation(u)
        r = (q[0], q[1], q[2], q[3], t[0], t[1], t[2])
        put(out, n, r)
        bad += residue(r)
    return bad == 0.0
