"""Where clifford's Cl(3,0,1) meets the PGA names e0, e1, e2, e3: the one table of blades.

clifford's ``Cl(3, 0, 1)`` puts the null basis vector first and calls it ``e1`` (its
vectors are e1 … e4, e1² = 0). ga_rotors asks clifford for the same algebra with its
first index 0 (``Cl(3, 0, 1, firstIdx=0)``, the layout of ``clifford.pga``), so the null
vector is ``e0`` and e1, e2, e3 are Euclidean, as in the PGA literature. That call, in
:func:`layout`, is the only place the names are chosen; every array of ga_rotors.motor
stores coefficients in this layout's blade order, restricted to one kind of element:

* motors (even grades): ``(1, e01, e02, e03, e12, e13, e23, e0123)``, :data:`MOTOR`;
* planes (grade 1): ``(e0, e1, e2, e3)``, :data:`PLANE`;
* lines (grade 2): ``(e01, e02, e03, e12, e13, e23)``, :data:`LINE`;
* points (grade 3): ``(e012, e013, e023, e123)``, :data:`POINT`.

``tests/test_motor_kernels.py`` checks these tuples against clifford's layout.

Examples
--------
>>> [BLADES[i] for i in MOTOR]
['1', 'e01', 'e02', 'e03', 'e12', 'e13', 'e23', 'e0123']
"""

from __future__ import annotations

import functools

__all__ = ["BLADES", "LINE", "MOTOR", "PLANE", "POINT", "layout"]

#: clifford's blade order of Cl(3,0,1) with the null vector named e0.
BLADES = (
    "1", "e0", "e1", "e2", "e3", "e01", "e02", "e03", "e12", "e13", "e23",
    "e012", "e013", "e023", "e123", "e0123",
)  # fmt: skip
#: Indices into :data:`BLADES` of a motor's coefficients (the even grades).
MOTOR = (0, 5, 6, 7, 8, 9, 10, 15)
#: Indices of a plane's coefficients (grade 1).
PLANE = (1, 2, 3, 4)
#: Indices of a line's coefficients (grade 2).
LINE = (5, 6, 7, 8, 9, 10)
#: Indices of a point's coefficients (grade 3).
POINT = (11, 12, 13, 14)


@functools.cache
def layout():
    """clifford's Cl(3,0,1) layout with blades named as in :data:`BLADES` (created once).

    It equals ``clifford.pga.layout``, so multivectors built from ``clifford.pga``'s
    blades are accepted as they are.

    Examples
    --------
    >>> tuple(n or "1" for n in layout().names) == BLADES
    True
    """
    from clifford import Cl

    return Cl(3, 0, 1, firstIdx=0)[0]
