r"""Orientation paths: the ways one motion's orientation is integrated.

Each path is a module holding the compiled kernels that bind the template slots
``o_rate``, ``o_axpy``, ``o_rk4``, ``o_quat``, ``o_load``, ``o_store``, ``o_watch`` (and,
on the unit sphere, ``o_normalize``/``o_from_quat``); see
:mod:`ga_rotors.integrators.slots`. The same integrator template runs on every path it
supports, so the paths differ only in their kinematics.

* ``rotor`` (primary): :math:`\dot R = \tfrac12 R \Omega` in Cl(3,0), kernels generated
  from clifford's layout;
* ``quaternion``: :math:`\dot q = \tfrac12 q \otimes (0, \omega)`;
* ``euler``: the paper's z–y′–z″ angles, singular at :math:`\sin\theta = 0` (watched and
  reported).

Whole rigid motion (a body with a mass moving through space, the ``motion`` problem kind)
runs on paths that carry the position too (``moves``):

* ``motor``: the motor M of the body frame in Cl(3,0,1), :math:`\dot M = \tfrac12 M B`,
  with the Euler–Poincaré equation for the body velocity line B
  (:mod:`ga_rotors.paths.motor`);
* ``quaternion``: for a moving body its variant ``motion`` (:mod:`ga_rotors.paths.pose`),
  the quaternion and the centre of mass, Euler's and Newton's equations.

:func:`resolve` gives the path a problem kind runs on.
"""

from __future__ import annotations

import importlib
import sys
from dataclasses import dataclass
from types import ModuleType

from ..errors import InputError

__all__ = ["PATHS", "OrientationPath", "get", "register", "resolve"]


@dataclass(frozen=True)
class OrientationPath:
    """One orientation path.

    Attributes
    ----------
    name : str
        ``"rotor"``, ``"quaternion"`` or ``"euler"``.
    module : str
        Module holding the slot kernels.
    array : str
        Name of the path's array in a :class:`~ga_rotors.trajectory.Trajectory`.
    components : tuple of str
        Column names of that array.
    on_unit_sphere : bool
        The state is a unit quaternion/rotor (``o_normalize``, ``o_from_quat`` exist).
    description : str
        One line for listings.
    sequence : str or None
        An Euler-angle path's axis sequence (scipy's naming, e.g. ``"ZYZ"``): its state
        is those angles, started from :func:`ga_rotors.euler.from_quaternion`.
    moves : bool
        The state carries the body's position too: the path integrates whole rigid motion
        (a ``motion`` problem), not the orientation alone.
    motion : OrientationPath or None
        The variant of this path that integrates whole rigid motion in the same
        coordinates (the quaternion path's: the quaternion and the centre of mass), for a
        path that is itself orientation only; None: it has none.

    Examples
    --------
    >>> p = PATHS["euler"]
    >>> p.array, p.components, p.dim, p.on_unit_sphere, p.sequence
    ('euler', ('psi', 'theta', 'phi'), 3, False, 'ZYZ')
    >>> p.load().__name__
    'ga_rotors.paths.euler'
    """

    name: str
    module: str
    array: str
    components: tuple[str, ...]
    on_unit_sphere: bool
    description: str
    sequence: str | None = None
    moves: bool = False
    motion: OrientationPath | None = None

    @property
    def dim(self) -> int:
        return len(self.components)

    def load(self) -> ModuleType:
        """The kernel module."""
        # sys.modules first: a run loads its path's module several times
        return sys.modules.get(self.module) or importlib.import_module(self.module)


#: The quaternion path's variant for whole rigid motion (see :func:`resolve`).
POSE = OrientationPath(
    "quaternion",
    "ga_rotors.paths.pose",
    "q_com",
    ("w", "x", "y", "z", "cx", "cy", "cz"),
    True,
    "quaternion and centre of mass: Euler's and Newton's equations",
    moves=True,
)

#: path name -> OrientationPath, in order of precedence for a simulation's primary path.
PATHS: dict[str, OrientationPath] = {
    p.name: p
    for p in (
        OrientationPath(
            "motor",
            "ga_rotors.paths.motor",
            "motor",
            ("1", "e01", "e02", "e03", "e12", "e13", "e23", "e0123"),
            False,
            "motor of Cl(3,0,1), dM/dt = M B / 2, Euler–Poincaré for the velocity line B",
            moves=True,
        ),
        OrientationPath(
            "rotor",
            "ga_rotors.paths.rotor",
            "rotor_blades",
            ("1", "e12", "e13", "e23"),
            True,
            "rotor equation dR/dt = R Ω / 2 in Cl(3,0)",
        ),
        OrientationPath(
            "quaternion",
            "ga_rotors.paths.quaternion",
            "q",
            ("w", "x", "y", "z"),
            True,
            "quaternion kinematics dq/dt = q ⊗ (0, ω) / 2",
            motion=POSE,
        ),
        OrientationPath(
            "euler",
            "ga_rotors.paths.euler",
            "euler",
            ("psi", "theta", "phi"),
            False,
            "the paper's ZYZ Euler-angle rates (singular at sin θ = 0)",
            sequence="ZYZ",
        ),
    )
}


def get(name: str) -> OrientationPath:
    """The path called ``name``.

    Examples
    --------
    >>> get("rotor").array
    'rotor_blades'
    >>> get("matrix")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: path: unknown path 'matrix'; expected one of euler, ...
    """
    try:
        return PATHS[name]
    except (KeyError, TypeError):
        raise InputError(
            f"path: unknown path {name!r}; expected one of {', '.join(sorted(PATHS))}"
        ) from None


def resolve(name: str, moves: bool) -> OrientationPath:
    """The path called ``name`` as a problem runs on it: for whole rigid motion
    (``moves``) the path itself if it carries the position, else its ``motion`` variant;
    for a rotation alone the path itself, if it does not carry a position.

    Examples
    --------
    >>> resolve("quaternion", moves=True).array, resolve("quaternion", moves=False).array
    ('q_com', 'q')
    >>> resolve("euler", moves=True)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: paths: the 'euler' path integrates the orientation alone; a body moving through space runs on motor, quaternion
    >>> resolve("motor", moves=False)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: paths: the 'motor' path integrates a whole rigid motion: give the body a mass and simulate it with position= and velocity=
    """  # noqa: E501
    spec = get(name)
    if moves:
        found = spec if spec.moves else spec.motion
        if found is None:
            moving = [p.name for p in PATHS.values() if p.moves or p.motion is not None]
            raise InputError(f"the {name!r} path integrates the orientation alone; a body "
                             f"moving through space runs on {', '.join(moving)}",
                             key="paths")  # fmt: skip
        return found
    if spec.moves:
        raise InputError(f"the {name!r} path integrates a whole rigid motion: give the body "
                         "a mass and simulate it with position= and velocity=",
                         key="paths")  # fmt: skip
    return spec


def register(path: OrientationPath) -> OrientationPath:
    """Add an orientation path (names and array names are unique) and return it.

    The integrators that can step it must list its name in their ``paths``. See
    ``docs/extending.md``.

    Examples
    --------
    >>> register(PATHS["euler"]) is PATHS["euler"]
    True
    >>> register(OrientationPath("euler", "my.module", "angles", ("a", "b", "c"), False, "mine"))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: register: a path named 'euler' already exists
    """
    if not isinstance(path, OrientationPath):
        raise InputError(f"expected an OrientationPath, got {path!r}", key="register")
    existing = PATHS.get(path.name)
    if existing is not None and existing is not path:
        raise InputError(f"a path named {path.name!r} already exists", key="register")
    clash = [p.name for p in PATHS.values() if p.array == path.array and p is not path]
    if clash:
        raise InputError(f"the array name {path.array!r} is {clash[0]!r}'s", key="register")
    PATHS[path.name] = path
    return path
