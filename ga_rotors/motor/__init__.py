"""Motors of projective geometric algebra Cl(3,0,1): rigid motions, rotation with translation.

A motor M is an even element of Cl(3,0,1) (e0² = 0, e1² = e2² = e3² = 1) with M M̃ = 1.
It moves planes (vectors), lines (bivectors) and points (trivectors) by the same
sandwich X ↦ M X M̃ that a rotor uses for vectors; it is the product T R of a translator
T = 1 − ½ e0 t (moving points by +t) and a rotor R = w − x e23 − y e31 − z e12 (the
quaternion (w, x, y, z) of :mod:`ga_rotors.rotor`), and the exponential of a bivector
(a screw: a rotation about a line and a slide along it, Chasles' theorem).

Arrays, compiled and broadcast like :mod:`ga_rotors.quaternion`:

* motors (..., 8): (1, e01, e02, e03, e12, e13, e23, e0123);
* bivectors and lines (..., 6): (e01, e02, e03, e12, e13, e23);
* planes and points (..., 4): (e0, e1, e2, e3) and (e012, e013, e023, e123).

The functions, by module (all of them importable from here):

* :mod:`ga_rotors.motor.motors`: build and convert (``from_pose``/``to_pose``,
  ``from_translation``, ``from_quaternion``, ``from_matrix``, ``from_screw``,
  ``from_dual_quaternion`` and their ``to_`` pairs), ``compose``, ``reverse``,
  ``inverse``, ``normalize``, ``exp``, ``log``, ``velocity_line`` (the bivector of a
  body's angular and linear velocity) and ``velocities``;
* :mod:`ga_rotors.motor.geometry`: ``point``, ``plane``, ``line`` from Euclidean
  coordinates and back, ``apply`` (Euclidean points), ``sandwich_point``,
  ``sandwich_line``, ``sandwich_plane``;
* :mod:`ga_rotors.motor.multivector`: clifford MultiVectors both ways.

Conventions in ``docs/conventions.md`` ("Motors"), a guide in ``docs/motors.md``.

Examples
--------
>>> import numpy as np
>>> from ga_rotors import motor
>>> M = motor.from_pose([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)], [0.0, 0.0, 1.0])
>>> motor.apply(M, [1.0, 0.0, 0.0]).round(15) + 0.0     # x turned to y, then lifted by z
array([0., 1., 1.])
"""

from __future__ import annotations

from .geometry import apply as apply
from .geometry import line as line
from .geometry import line_coordinates as line_coordinates
from .geometry import plane as plane
from .geometry import plane_coordinates as plane_coordinates
from .geometry import point as point
from .geometry import point_coordinates as point_coordinates
from .geometry import sandwich_line as sandwich_line
from .geometry import sandwich_plane as sandwich_plane
from .geometry import sandwich_point as sandwich_point
from .motors import compose as compose
from .motors import exp as exp
from .motors import from_dual_quaternion as from_dual_quaternion
from .motors import from_matrix as from_matrix
from .motors import from_pose as from_pose
from .motors import from_quaternion as from_quaternion
from .motors import from_screw as from_screw
from .motors import from_translation as from_translation
from .motors import inverse as inverse
from .motors import log as log
from .motors import normalize as normalize
from .motors import reverse as reverse
from .motors import to_dual_quaternion as to_dual_quaternion
from .motors import to_matrix as to_matrix
from .motors import to_pose as to_pose
from .motors import to_quaternion as to_quaternion
from .motors import to_screw as to_screw
from .motors import to_translation as to_translation
from .motors import velocities as velocities
from .motors import velocity_line as velocity_line
from .multivector import from_multivector as from_multivector
from .multivector import layout as layout
from .multivector import to_multivector as to_multivector

__all__ = [
    "apply",
    "compose",
    "exp",
    "from_dual_quaternion",
    "from_matrix",
    "from_multivector",
    "from_pose",
    "from_quaternion",
    "from_screw",
    "from_translation",
    "inverse",
    "layout",
    "line",
    "line_coordinates",
    "log",
    "normalize",
    "plane",
    "plane_coordinates",
    "point",
    "point_coordinates",
    "reverse",
    "sandwich_line",
    "sandwich_plane",
    "sandwich_point",
    "to_dual_quaternion",
    "to_matrix",
    "to_multivector",
    "to_pose",
    "to_quaternion",
    "to_screw",
    "to_translation",
    "velocities",
    "velocity_line",
]
