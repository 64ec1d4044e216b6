"""ga_rotors: rotations in geometric (Clifford) algebra.

Everything a user needs for the everyday tasks is one import away, and nothing is
imported until it is used (``import ga_rotors`` loads neither numpy, numba nor clifford):

>>> import ga_rotors as gr
>>> tr = gr.simulate([1.0, 2.0, 3.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0],
...                  duration=1.0, step=1e-3)
>>> gr.quaternion.to_euler(tr.quaternions()[-1], "ZYX").round(9).tolist()  # 1 rad about z
[1.0, 0.0, 0.0]
>>> tr = gr.run_scene(gr.load_scene("spinning_disk").replace({"time.duration": 0.01}))
>>> tr.meta["scene"]
'spinning_disk'

Names
-----
* integrate a rigid body: :func:`simulate` -> :class:`Trajectory` (its orientation by
  name: ``quaternions(path)``, ``rotors(path)``), :class:`RigidBody`, :mod:`shapes`,
  :func:`cross_check` (the paths against each other);
* scenes (TOML files, ``docs/scenes.md``): :func:`load_scene`, :class:`Scene`,
  :func:`run_scene`, :func:`bundled_scenes`;
* rotations: :mod:`quaternion` (float arrays (..., 4), scalar first), :mod:`rotor`
  (clifford rotors of Cl(3,0)), :mod:`euler` (every sequence, scipy's naming),
  :mod:`matrix`, :mod:`kinematics`;
* rigid motions: :mod:`motor` (motors of Cl(3,0,1) as float arrays (..., 8): rotation
  with translation, and the points, lines and planes they move);
* exact references: :class:`SymmetricTop`, :class:`AsymmetricTop`, :class:`HeavyTop`,
  :class:`DampedSymmetricTop`; with translation, :class:`FreeFlight` and
  :class:`SpringAtCentreOfMass`;
* :mod:`integrators` (the registry: ``integrators.names()``, ``integrators.get(name)``,
  ``integrators.catalogue()``), :mod:`effects` (the torques a scene may declare),
  :mod:`errors` (what is raised on purpose; every user error is a ``GaRotorsError``).

Subpackages by job: :mod:`ga_rotors.scene` (scene files to results), :mod:`ga_rotors.paper`
(the source paper's gyroscope reproduced, ``ga-rotors paper``), :mod:`ga_rotors.cli` (the
``ga-rotors`` command, one module per sub-command), :mod:`ga_rotors.paths` (orientation
paths), :mod:`ga_rotors.reference` (exact solutions).

Conventions (scalar-first Hamilton quaternions, active rotations, scipy's Euler naming)
are fixed once in ``docs/conventions.md``.
"""

from __future__ import annotations

import importlib

#: public name -> (module, attribute); attribute None: the module itself.
_EXPORTS: dict[str, tuple[str, str | None]] = {
    "simulate": ("ga_rotors.simulation", "simulate"),
    "Trajectory": ("ga_rotors.trajectory", "Trajectory"),
    "RigidBody": ("ga_rotors.body", "RigidBody"),
    "cross_check": ("ga_rotors.crosscheck", "cross_check"),
    "Scene": ("ga_rotors.scene.model", "Scene"),
    "load_scene": ("ga_rotors.scene.loading", "load_scene"),
    "bundled_scenes": ("ga_rotors.scene.loading", "bundled"),
    "run_scene": ("ga_rotors.scene.run", "run_scene"),
    "SymmetricTop": ("ga_rotors.reference.symmetric_top", "SymmetricTop"),
    "AsymmetricTop": ("ga_rotors.reference.asymmetric_top", "AsymmetricTop"),
    "HeavyTop": ("ga_rotors.reference.heavy_top", "HeavyTop"),
    "DampedSymmetricTop": ("ga_rotors.reference.damped_top", "DampedSymmetricTop"),
    "FreeFlight": ("ga_rotors.reference.rigid_motion", "FreeFlight"),
    "SpringAtCentreOfMass": ("ga_rotors.reference.rigid_motion", "SpringAtCentreOfMass"),
    "quaternion": ("ga_rotors.quaternion", None),
    "rotor": ("ga_rotors.rotor", None),
    "motor": ("ga_rotors.motor", None),
    "euler": ("ga_rotors.euler", None),
    "matrix": ("ga_rotors.matrix", None),
    "kinematics": ("ga_rotors.kinematics", None),
    "shapes": ("ga_rotors.shapes", None),
    "integrators": ("ga_rotors.integrators", None),
    "effects": ("ga_rotors.effects", None),
    "errors": ("ga_rotors.errors", None),
    "GaRotorsError": ("ga_rotors.errors", "GaRotorsError"),
    "InputError": ("ga_rotors.errors", "InputError"),
    "SceneError": ("ga_rotors.errors", "SceneError"),
}

__all__ = ["__version__", *_EXPORTS]


def __getattr__(name: str):
    if name == "__version__":
        # Set once, in pyproject.toml, and read from the installed metadata on first use:
        # importlib.metadata costs ~15 ms, which `import ga_rotors` need not pay.
        from importlib.metadata import PackageNotFoundError, version

        try:
            value = version("ga-rotors")
        except PackageNotFoundError:  # a source tree that was never installed
            value = "unknown (not installed)"
        globals()["__version__"] = value
        return value
    try:
        module, attribute = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'ga_rotors' has no attribute {name!r}") from None
    value = importlib.import_module(module)
    if attribute is not None:
        value = getattr(value, attribute)
    globals()[name] = value  # looked up once
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
