"""ga_rotors: rotations in geometric (Clifford) algebra.

Modules, each with one job:

* :mod:`ga_rotors.quaternion`: Hamilton quaternions as float arrays of shape (..., 4)
* :mod:`ga_rotors.rotor`: rotors in Cl(3,0) as ``clifford`` multivectors
* :mod:`ga_rotors.errors`: the exceptions and warnings raised on purpose

Conventions (scalar-first Hamilton quaternions, active rotations, scipy's Euler naming)
are fixed once in ``docs/conventions.md``.
"""

__version__ = "0.1.0"
