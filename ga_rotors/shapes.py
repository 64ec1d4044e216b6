"""Principal moments of inertia of uniform solids, about their centre of mass.

Every shape puts its symmetry axis (or its longest/first dimension, for the box) on the
body z axis, so ``moments[2]`` is the moment about the symmetry axis. Units are whatever
the inputs use (kg and m give kg·m²).

Examples
--------
The paper's disk (m = 2 kg, R = 0.075 m) spins about its symmetry axis, body z:

>>> disk(2.0, 0.075)
(0.0028125, 0.0028125, 0.005625)
"""

from __future__ import annotations

import math

from .errors import InputError

__all__ = ["SHAPES", "box", "cylinder", "disk", "ring", "rod", "sphere"]


def _positive(**values: float) -> None:
    for name, value in values.items():
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            raise InputError(f"expected a number, got {type(value).__name__}", key=name)
        try:
            ok = math.isfinite(value) and value > 0
        except OverflowError:  # an int beyond float64
            ok = False
        if not ok:
            raise InputError(f"expected a finite positive number, got {value!r:.40}", key=name)


def _moments(compute) -> tuple[float, float, float]:
    """``compute()``'s moments, refused when they leave float64 (1e200 m squared
    overflows, 1e-200 m squared is 0): a shape must give a rigid body's moments."""
    try:
        moments = tuple(float(m) for m in compute())
    except OverflowError:
        moments = (math.inf,)
    if not all(math.isfinite(m) and m > 0 for m in moments):
        raise InputError(
            "the moments of inertia of these dimensions are beyond float64 (overflow or "
            "underflow); rescale the units"
        )
    return moments


def disk(mass: float, radius: float) -> tuple[float, float, float]:
    r"""Thin uniform disk, symmetry axis z:
    :math:`(\tfrac14 m R^2, \tfrac14 m R^2, \tfrac12 m R^2)`.

    Examples
    --------
    >>> disk(1.0, 2.0)
    (1.0, 1.0, 2.0)
    """
    _positive(mass=mass, radius=radius)
    return _moments(lambda: (0.25 * mass * radius**2,) * 2 + (0.5 * mass * radius**2,))


def ring(mass: float, radius: float) -> tuple[float, float, float]:
    r"""Thin circular hoop, symmetry axis z: :math:`(\tfrac12 m R^2, \tfrac12 m R^2, m R^2)`.

    Examples
    --------
    >>> ring(1.0, 1.0)
    (0.5, 0.5, 1.0)
    """
    _positive(mass=mass, radius=radius)
    return _moments(lambda: (0.5 * mass * radius**2,) * 2 + (mass * radius**2,))


def cylinder(mass: float, radius: float, height: float) -> tuple[float, float, float]:
    r"""Solid cylinder, symmetry axis z:
    :math:`\left(\frac{m (3 R^2 + h^2)}{12}, \frac{m (3 R^2 + h^2)}{12}, \tfrac12 m R^2\right)`.

    Examples
    --------
    >>> cylinder(12.0, 1.0, 2.0)
    (7.0, 7.0, 6.0)
    """
    _positive(mass=mass, radius=radius, height=height)

    def compute():
        a = mass * (3.0 * radius**2 + height**2) / 12.0
        return (a, a, 0.5 * mass * radius**2)

    return _moments(compute)


def rod(mass: float, length: float, radius: float) -> tuple[float, float, float]:
    """Slender rod (a cylinder with length ≫ radius) along z.

    The radius is required: an ideal line has zero moment about its axis, which is not a
    rigid body that Euler's equations can integrate.

    Examples
    --------
    >>> rod(12.0, 1.0, 0.01)
    (1.0003, 1.0003, 0.0006)
    """
    _positive(mass=mass, length=length, radius=radius)
    return cylinder(mass, radius, length)


def box(mass: float, a: float, b: float, c: float) -> tuple[float, float, float]:
    r"""Solid cuboid with edges a, b, c along x, y, z:
    :math:`\tfrac{m}{12} (b^2 + c^2, a^2 + c^2, a^2 + b^2)`.

    Examples
    --------
    >>> box(12.0, 1.0, 2.0, 3.0)
    (13.0, 10.0, 5.0)
    """
    _positive(mass=mass, a=a, b=b, c=c)
    k = mass / 12.0
    return _moments(lambda: (k * (b**2 + c**2), k * (a**2 + c**2), k * (a**2 + b**2)))


def sphere(mass: float, radius: float) -> tuple[float, float, float]:
    r"""Solid sphere: :math:`\tfrac25 m R^2` about every axis.

    Examples
    --------
    >>> sphere(5.0, 1.0)
    (2.0, 2.0, 2.0)
    """
    _positive(mass=mass, radius=radius)
    a = _moments(lambda: (0.4 * mass * radius**2,))[0]
    return (a, a, a)


#: shape name -> (function, names of its dimensions after ``mass``), for scene files.
SHAPES = {
    "disk": (disk, ("radius",)),
    "ring": (ring, ("radius",)),
    "cylinder": (cylinder, ("radius", "height")),
    "rod": (rod, ("length", "radius")),
    "box": (box, ("a", "b", "c")),
    "sphere": (sphere, ("radius",)),
}
