"""clifford MultiVectors of Cl(3,0,1) to and from the arrays of ga_rotors.motor.

For users who work in clifford: :func:`layout` is clifford's PGA layout (equal to
``clifford.pga.layout``, blades e0, e1, e2, e3 with e0² = 0), :func:`to_multivector`
turns a motor, plane, line or point array into MultiVectors and :func:`from_multivector`
takes them back, checking that nothing of another grade is dropped. clifford is imported
on first use (about a second).

Examples
--------
>>> M = to_multivector([1.0, -0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])     # translator by x
>>> M
1.0 - (0.5^e01)
>>> P = M * to_multivector([0.0, 0.0, 0.0, 1.0], "point") * ~M       # the origin, moved
>>> from_multivector(P, "point")
array([ 0.,  0., -1.,  1.])
"""

from __future__ import annotations

import numpy as np

from .._pga import BLADES, LINE, MOTOR, PLANE, POINT
from .._pga import layout as _layout
from .._validate import UNIT_TOLERANCE, as_float_array
from ..errors import InputError

__all__ = ["KINDS", "from_multivector", "layout", "to_multivector"]

#: The kinds of arrays, with the indices of their blades in :func:`layout`'s order.
KINDS = {"motor": MOTOR, "plane": PLANE, "line": LINE, "point": POINT}


def layout():
    """clifford's Cl(3,0,1) layout with the null vector named e0 (created once).

    Examples
    --------
    >>> layout().names[:5]
    ['', 'e0', 'e1', 'e2', 'e3']
    """
    return _layout()


def _indices(kind: str):
    try:
        return KINDS[kind]
    except (KeyError, TypeError):
        raise InputError(f"expected one of {sorted(KINDS)}, got {kind!r:.40}", key="kind") from None


def to_multivector(x, kind: str = "motor"):
    """The MultiVector of one array (k,), or a ``clifford.MVArray`` of a batch (..., k).

    Parameters
    ----------
    x : array_like, shape (..., k)
        Coefficients of a ``kind``: 8 for a motor, 4 for a plane or a point, 6 for a line.
    kind : {"motor", "plane", "line", "point"}

    Examples
    --------
    >>> to_multivector([0.0, 0.0, 1.0, 0.0, 0.0, 0.0], "line")       # the moment e03
    (1.0^e03)
    >>> to_multivector(np.zeros((2, 3, 4)), "plane").shape
    (2, 3)
    """
    from clifford import MultiVector, MVArray

    indices = _indices(kind)
    a = as_float_array(x, "x", last=len(indices))
    full = np.zeros((*a.shape[:-1], len(BLADES)))
    full[..., list(indices)] = a
    if a.ndim == 1:
        return MultiVector(layout(), full)
    items = np.empty(a.shape[:-1], dtype=object)
    for where in np.ndindex(items.shape):
        items[where] = MultiVector(layout(), full[where])
    return MVArray(items)


def from_multivector(X, kind: str = "motor") -> np.ndarray:
    """The coefficient array of a MultiVector (k,) or of an array of them (..., k).

    Coefficients outside ``kind``'s blades must vanish: up to UNIT_TOLERANCE times the
    multivector's largest coefficient they are round-off and dropped; larger ones raise
    :class:`InputError`.

    Examples
    --------
    >>> from clifford.pga import e1, e2, e3
    >>> from_multivector(2.0 * e1 + e3, "plane")                   # the plane 2x + z = 0
    array([0., 2., 0., 1.])
    >>> from_multivector(e1 * e2 * e3 + e1, "point")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: X: expected a point (blades e012, e013, e023, e123), got ...
    """
    from clifford import MultiVector

    indices = _indices(kind)
    if isinstance(X, MultiVector):
        values = [X]
        shape: tuple[int, ...] = ()
    else:
        items = np.asarray(X, dtype=object)
        values, shape = list(items.ravel()), items.shape
    for n, v in enumerate(values):
        if not isinstance(v, MultiVector) or v.layout != layout():
            got = type(v).__name__ if not isinstance(v, MultiVector) else f"layout {v.layout}"
            raise InputError(
                f"expected MultiVectors of Cl(3,0,1) (ga_rotors.motor.layout()), got {got:.80} "
                f"at index {np.unravel_index(n, shape) if shape else ()}",
                key="X",
            )
    full = as_float_array(np.array([v.value for v in values]).reshape((*shape, len(BLADES))), "X")
    other = np.delete(full, list(indices), axis=-1)
    scale = np.abs(full).max(axis=-1, initial=0.0)
    bad = np.abs(other).max(axis=-1, initial=0.0) > UNIT_TOLERANCE * scale
    if np.any(bad):
        where = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        names = ", ".join(BLADES[i] for i in indices)
        raise InputError(
            f"expected a {kind} (blades {names}), got other blades at index {where}", key="X"
        )
    return full[..., list(indices)]
