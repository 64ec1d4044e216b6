r"""The algebra isomorphism ℍ → Cl⁺(3,0) as one coefficient table (pure NumPy, no clifford).

Coefficients follow clifford's ``Cl(3)`` blade order (1, e1, e2, e3, e12, e13, e23, e123).
With :math:`I = e_{123}` and the unit vectors' duals :math:`e_{23} = I e_1`,
:math:`e_{31} = I e_2`, :math:`e_{12} = I e_3`:

.. math::

    i \mapsto -e_{23}, \qquad j \mapsto -e_{31} = +e_{13}, \qquad k \mapsto -e_{12},

so :math:`q = (w, x, y, z) \mapsto R = w - x e_{23} - y e_{31} - z e_{12} = w - I \vec q`,
and the unit quaternion of the rotation by α about u maps to the rotor
:math:`\cos\frac{\alpha}{2} - I u \sin\frac{\alpha}{2} = \exp(-I u \alpha/2)`, which rotates
vectors by :math:`v \mapsto R v \tilde R` exactly as :math:`q v q^*` does.

Why the signs: :math:`(-e_{23})(-e_{31}) = e_2 e_3 e_3 e_1 = e_2 e_1 = -e_{12}`, the image of
k, so ij = k is kept. The "obvious" map :math:`i \mapsto e_{23}`, :math:`j \mapsto e_{31}`,
:math:`k \mapsto e_{12}` sends ij to :math:`e_{23} e_{31} = -e_{12}`, the image of −k: it
reverses every product (:math:`\varphi(pq) = \varphi(q)\, \varphi(p)`), an anti-isomorphism.
Its table is kept here too, as :data:`ANTI_ISOMORPHISM`, so the tests and docs can show it failing.

Examples
--------
>>> to_even([0.0, 1.0, 0.0, 0.0])          # i ↦ −e23
array([ 0.,  0.,  0.,  0.,  0.,  0., -1.,  0.])
>>> from_even(to_even([0.1, 0.2, 0.3, 0.4]))
array([0.1, 0.2, 0.3, 0.4])
"""

from __future__ import annotations

import numpy as np

from ._validate import UNIT_TOLERANCE, as_float_array
from .errors import InputError

__all__ = [
    "ANTI_ISOMORPHISM",
    "BLADES",
    "EVEN",
    "ISOMORPHISM",
    "ODD",
    "from_even",
    "to_even",
]

#: clifford's Cl(3) blade order.
BLADES = ("1", "e1", "e2", "e3", "e12", "e13", "e23", "e123")
#: indices of the even blades (1, e12, e13, e23) and the odd ones (e1, e2, e3, e123).
EVEN = (0, 4, 5, 6)
ODD = (1, 2, 3, 7)

#: (quaternion component, blade index, sign): 1 ↦ 1, i ↦ −e23, j ↦ +e13 (= −e31), k ↦ −e12.
ISOMORPHISM = ((0, 0, 1.0), (1, 6, -1.0), (2, 5, 1.0), (3, 4, -1.0))
#: The rejected map i ↦ +e23, j ↦ +e31 (= −e13), k ↦ +e12: it reverses products.
ANTI_ISOMORPHISM = ((0, 0, 1.0), (1, 6, 1.0), (2, 5, -1.0), (3, 4, 1.0))


def to_even(q, table=ISOMORPHISM) -> np.ndarray:
    """Cl(3) coefficients (..., 8) of quaternions (..., 4) under ``table``.

    Examples
    --------
    >>> to_even([[1.0, 0, 0, 0], [0, 0, 0, 1.0]])
    array([[ 1.,  0.,  0.,  0.,  0.,  0.,  0.,  0.],
           [ 0.,  0.,  0.,  0., -1.,  0.,  0.,  0.]])
    """
    q = as_float_array(q, "q", last=4)
    c = np.zeros((*q.shape[:-1], 8))
    for component, blade, sign in table:
        c[..., blade] = sign * q[..., component]
    return c


def from_even(c, table=ISOMORPHISM, name: str = "R") -> np.ndarray:
    """Quaternions (..., 4) of Cl(3) coefficients (..., 8) under ``table``.

    The odd part (e1, e2, e3, e123) must vanish: entries up to ``UNIT_TOLERANCE`` times the
    multivector's size are round-off and dropped; larger ones raise :class:`InputError`.

    Examples
    --------
    >>> from_even([0.5, 0, 0, 0, -0.5, 0.5, -0.5, 0])
    array([0.5, 0.5, 0.5, 0.5])
    >>> from_even([0.0, 1.0, 0, 0, 0, 0, 0, 0])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: R: expected an even multivector (grades 0 and 2), got ...
    """
    c = as_float_array(c, name, last=8)
    # Scaled by the largest coefficient so that 1e±300 multivectors neither overflow nor
    # underflow in the squares; the test is relative to the size, as documented.
    scale = np.abs(c).max(axis=-1, initial=0.0)
    s = c / np.where(scale > 0.0, scale, 1.0)[..., None]
    odd = np.sqrt(np.sum(s[..., list(ODD)] ** 2, axis=-1))
    bad = odd > UNIT_TOLERANCE * np.sqrt(np.sum(s**2, axis=-1))
    if np.any(bad):
        where = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        raise InputError(
            f"expected an even multivector (grades 0 and 2), got odd part "
            f"{odd[where] * scale[where]:.3g} (e1, e2, e3, e123) at index {where}",
            key=name,
        )
    q = np.empty((*c.shape[:-1], 4))
    for component, blade, sign in table:
        q[..., component] = sign * c[..., blade]
    return q
