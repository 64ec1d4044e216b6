"""ga_rotors: rotations in geometric (Clifford) algebra.

Modules, each with one job:

* :mod:`ga_rotors.quaternion`: Hamilton quaternions as float arrays of shape (..., 4)
* :mod:`ga_rotors.rotor`: rotors in Cl(3,0) as ``clifford`` multivectors
* :mod:`ga_rotors.errors`: the exceptions and warnings raised on purpose
* :mod:`ga_rotors.simulate`: integrate a rigid body along the rotor, quaternion and
  Euler-angle paths (:mod:`ga_rotors.integrators`, :mod:`ga_rotors.paths`), giving a
  :class:`~ga_rotors.trajectory.Trajectory`; :mod:`ga_rotors.crosscheck` compares the paths
* :mod:`ga_rotors.kinematics`: Euler-angle, quaternion and rotor rates <-> body ω
* :mod:`ga_rotors.reference`: exact solutions (symmetric, asymmetric and heavy tops)
* :mod:`ga_rotors.paper`: ``ga-rotors paper``, the source paper's gyroscope reproduced

Conventions (scalar-first Hamilton quaternions, active rotations, scipy's Euler naming)
are fixed once in ``docs/conventions.md``.
"""

__all__ = ["__version__"]  # the subpackages and modules are imported by name

__version__ = "0.1.0"
