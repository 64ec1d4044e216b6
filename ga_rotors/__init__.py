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
* :mod:`ga_rotors.paper`: the source paper's gyroscope reproduced (``ga-rotors paper``)
* :mod:`ga_rotors.cli`: the ``ga-rotors`` command, one module per sub-command

Conventions (scalar-first Hamilton quaternions, active rotations, scipy's Euler naming)
are fixed once in ``docs/conventions.md``.
"""

__all__ = ["__version__"]  # the subpackages and modules are imported by name


def __getattr__(name: str):
    # The version is set once, in pyproject.toml, and read from the installed metadata on
    # first use: importlib.metadata costs ~15 ms, which `import ga_rotors` need not pay.
    if name == "__version__":
        from importlib.metadata import PackageNotFoundError, version

        try:
            value = version("ga-rotors")
        except PackageNotFoundError:  # a source tree that was never installed
            value = "unknown (not installed)"
        globals()["__version__"] = value
        return value
    raise AttributeError(f"module 'ga_rotors' has no attribute {name!r}")
