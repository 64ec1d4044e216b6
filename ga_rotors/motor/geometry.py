"""Points, lines and planes of PGA, their Euclidean coordinates, and what motors do to them.

In Cl(3,0,1) planes are vectors, lines bivectors and points trivectors, and a unit motor M
moves every one of them by the same sandwich X ↦ M X M̃. Arrays hold the coefficients of
one grade in clifford's blade order (:mod:`ga_rotors._pga`):

* plane {x : n·x = δ}: n₁e1 + n₂e2 + n₃e3 − δ e0, as (e0, e1, e2, e3) = (−δ, n₁, n₂, n₃);
* point x: e123 − x₁e023 + x₂e013 − x₃e012 (= e123 + x₁e032 + x₂e013 + x₃e021, the form of
  the PGA literature), as (e012, e013, e023, e123) = (−x₃, x₂, −x₁, 1); a weight w
  multiplies all four, and w = 0 is a direction (a point at infinity);
* line through p with direction d: the join of the points p and p + d, as (e01, e02, e03,
  e12, e13, e23) = (m₁, m₂, m₃, d₃, −d₂, d₁) with the moment m = p × d (Plücker
  coordinates (d, m)); the x axis is e23, the meet of the planes y = 0 and z = 0.

Examples
--------
>>> point([1.0, 2.0, 3.0])
array([-3.,  2., -1.,  1.])
>>> line([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])          # the x axis: e23
array([0., 0., 0., 0., 0., 1.])
"""

from __future__ import annotations

import numpy as np

from .._batch import Batch
from .._validate import UNIT_TOLERANCE, as_float_array
from ..errors import InputError
from . import _loops
from ._checks import fail, leading_shape, line_parts, norm3

__all__ = [
    "apply",
    "line",
    "line_coordinates",
    "plane",
    "plane_coordinates",
    "point",
    "point_coordinates",
    "sandwich_line",
    "sandwich_plane",
    "sandwich_point",
]


def _first(bad: np.ndarray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()


def point(x) -> np.ndarray:
    """The PGA points (..., 4) of Euclidean points x (..., 3): e123 − x₁e023 + x₂e013 − x₃e012.

    Examples
    --------
    >>> point([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    array([[ 0.,  0.,  0.,  1.],
           [ 0.,  0., -1.,  1.]])
    """
    x = as_float_array(x, "x", last=3)
    # 0.0 − x, not −x: the origin's coefficients are +0, not −0.
    return np.stack([0.0 - x[..., 2], x[..., 1], 0.0 - x[..., 0], np.ones(x.shape[:-1])], axis=-1)


def point_coordinates(P) -> np.ndarray:
    """The Euclidean coordinates (..., 3) of PGA points P (..., 4) of any nonzero weight.

    Raises
    ------
    InputError
        For a point at infinity (weight, the e123 coefficient, 0): a direction.

    Examples
    --------
    >>> point_coordinates([-6.0, 4.0, -2.0, 2.0])        # weight 2
    array([1., 2., 3.])
    """
    P = as_float_array(P, "P", last=4)
    w = P[..., 3]
    if np.any(w == 0.0):
        raise InputError(
            "expected a finite point (nonzero e123 weight), got a point at infinity at index "
            f"{_first(w == 0.0)}",
            key="P",
        )
    return np.stack([0.0 - P[..., 2], P[..., 1], 0.0 - P[..., 0]], axis=-1) / w[..., None]


def plane(normal, offset) -> np.ndarray:
    """The PGA planes (..., 4) {x : n·x = δ} = n₁e1 + n₂e2 + n₃e3 − δ e0, as (e0, e1, e2, e3).

    The normal is kept as given (not normalised); its direction orients the plane.

    Examples
    --------
    >>> plane([0.0, 0.0, 1.0], 2.0)                     # z = 2
    array([-2.,  0.,  0.,  1.])
    """
    n = as_float_array(normal, "normal", last=3)
    d = as_float_array(offset, "offset")
    out = np.empty((*leading_shape((n, "normal", 1), (d, "offset", 0)), 4))
    out[..., 0] = -d
    out[..., 1:] = n
    return out


def plane_coordinates(a) -> tuple[np.ndarray, np.ndarray | float]:
    """(unit normal n (..., 3), offset δ (...)) of PGA planes a (..., 4): {x : n·x = δ}.

    Raises
    ------
    InputError
        For the plane at infinity (e0 alone: no normal).

    Examples
    --------
    >>> plane_coordinates([-4.0, 0.0, 2.0, 0.0])         # 2y = 4
    (array([0., 1., 0.]), 2.0)
    """
    a = as_float_array(a, "a", last=4)
    size = norm3(a[..., 1:])
    if np.any(size == 0.0):
        raise InputError(
            "expected a plane with a normal, got the plane at infinity at index "
            f"{_first(size == 0.0)}",
            key="a",
        )
    offset = -a[..., 0] / size
    return a[..., 1:] / size[..., None], (float(offset) if offset.ndim == 0 else offset)


def line(point, direction) -> np.ndarray:
    """The PGA lines (..., 6) through ``point`` along ``direction``: the join of p and p + d.

    (e01, e02, e03, e12, e13, e23) = (m₁, m₂, m₃, d₃, −d₂, d₁), m = p × d. The direction
    is kept as given (its length is the line's weight) and must not be zero.

    Examples
    --------
    >>> line([0.0, 1.0, 0.0], [0.0, 0.0, 1.0])          # parallel to z through y = 1
    array([1., 0., 0., 1., 0., 0.])
    """
    p = as_float_array(point, "point", last=3)
    d = as_float_array(direction, "direction", last=3)
    shape = (*leading_shape((p, "point", 1), (d, "direction", 1)), 3)
    p, d = np.broadcast_to(p, shape), np.broadcast_to(d, shape)
    zero = ~np.any(d != 0.0, axis=-1)
    if np.any(zero):
        raise InputError(f"expected nonzero directions, got zero at index {_first(zero)}",
                         key="direction")  # fmt: skip
    m = np.cross(p, d) + 0.0  # + 0.0: no −0 coefficients
    return np.stack([m[..., 0], m[..., 1], m[..., 2], d[..., 2], 0.0 - d[..., 1], d[..., 0]],
                    axis=-1)  # fmt: skip


def line_coordinates(L) -> tuple[np.ndarray, np.ndarray]:
    """(the point nearest the origin (..., 3), the unit direction (..., 3)) of PGA lines L.

    Raises
    ------
    InputError
        For an ideal line (no direction) or a bivector that is not a line (its direction
        d and moment m not perpendicular within UNIT_TOLERANCE: a screw).

    Examples
    --------
    >>> p, u = line_coordinates(line([3.0, 1.0, 0.0], [0.0, 0.0, 2.0]))
    >>> p + 0.0, u
    (array([3., 1., 0.]), array([0., 0., 1.]))
    """
    return line_parts(L, "L")


# ------------------------------------------------------------------- motors acting on them


def apply(M, x) -> np.ndarray:
    """Move Euclidean points x (..., 3) by unit motors M (..., 8): R x R̃ + t for M = T(t) R.

    The same as ``point_coordinates(sandwich_point(M, point(x)))``, in fewer operations.

    Examples
    --------
    >>> T = [1.0, -0.5, -1.0, -1.5, 0.0, 0.0, 0.0, 0.0]         # translator by (1, 2, 3)
    >>> apply(T, [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]])
    array([[1., 2., 3.],
           [2., 3., 4.]])
    """
    batch = Batch((M, "M", (8,)), (x, "x", 3))
    out = batch.empty(3)
    f, s = batch.flat, batch.steps
    ok = _loops.apply_loop(f[0], s[0], f[1], s[1], out, UNIT_TOLERANCE)
    fail(batch, ok, out, motors=("M",), what="moved point")
    return batch.shaped(out)


def _sandwich(loop, M, X, name: str, size: int) -> np.ndarray:
    batch = Batch((M, "M", (8,)), (X, name, (size,)))
    out = batch.empty(size)
    f, s = batch.flat, batch.steps
    ok = loop(f[0], s[0], f[1], s[1], out, UNIT_TOLERANCE)
    fail(batch, ok, out, motors=("M",), what="sandwich")
    return batch.shaped(out)


def sandwich_point(M, P) -> np.ndarray:
    """M P M̃ for PGA points P (..., 4) and unit motors M (..., 8): the moved points.

    Points at infinity (directions, weight 0) are turned and not shifted.

    Examples
    --------
    >>> T = [1.0, -0.5, -1.0, -1.5, 0.0, 0.0, 0.0, 0.0]         # translator by (1, 2, 3)
    >>> point_coordinates(sandwich_point(T, point([0.0, 0.0, 0.0])))
    array([1., 2., 3.])
    >>> sandwich_point(T, [0.0, 0.0, -1.0, 0.0])                # the direction x: unmoved
    array([ 0.,  0., -1.,  0.])
    """
    return _sandwich(_loops.sandwich_point_loop, M, P, "P", 4)


def sandwich_line(M, L) -> np.ndarray:
    """M L M̃ for PGA lines L (..., 6) and unit motors M (..., 8): the moved lines.

    Examples
    --------
    >>> T = [1.0, -0.5, -1.0, -1.5, 0.0, 0.0, 0.0, 0.0]         # translator by (1, 2, 3)
    >>> moved = sandwich_line(T, line([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]))
    >>> p, u = line_coordinates(moved)                          # through (0, 2, 3) along x
    >>> p, u + 0.0
    (array([0., 2., 3.]), array([1., 0., 0.]))
    """
    return _sandwich(_loops.sandwich_line_loop, M, L, "L", 6)


def sandwich_plane(M, a) -> np.ndarray:
    """M a M̃ for PGA planes a (..., 4) and unit motors M (..., 8): the moved planes.

    Examples
    --------
    >>> T = [1.0, -0.5, -1.0, -1.5, 0.0, 0.0, 0.0, 0.0]         # translator by (1, 2, 3)
    >>> plane_coordinates(sandwich_plane(T, plane([0.0, 0.0, 1.0], 0.0)))     # z = 3
    (array([0., 0., 1.]), 3.0)
    """
    return _sandwich(_loops.sandwich_plane_loop, M, a, "a", 4)
