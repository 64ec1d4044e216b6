"""Orientation paths: the ways one motion's orientation is integrated.

Each path is a module holding the compiled kernels that bind the template slots
``o_rate``, ``o_axpy``, ``o_rk4``, ``o_quat``, ``o_load``, ``o_store``, ``o_watch`` (and,
on the unit sphere, ``o_normalize``/``o_from_quat``); see
:mod:`ga_rotors.integrators.slots`. The same integrator template runs on every path it
supports, so the paths differ only in their kinematics.

* ``rotor`` (primary): Ṙ = ½ R Ω in Cl(3,0), kernels generated from clifford's layout;
* ``quaternion``: q̇ = ½ q ⊗ (0, ω);
* ``euler``: the paper's z–y′–z″ angles, singular at sin θ = 0 (watched and reported).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType

from ..errors import InputError

__all__ = ["PATHS", "Path", "get"]


@dataclass(frozen=True)
class Path:
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

    Examples
    --------
    >>> p = PATHS["euler"]
    >>> p.array, p.components, p.dim, p.on_unit_sphere
    ('euler', ('psi', 'theta', 'phi'), 3, False)
    >>> p.load().__name__
    'ga_rotors.paths.euler'
    """

    name: str
    module: str
    array: str
    components: tuple[str, ...]
    on_unit_sphere: bool
    description: str

    @property
    def dim(self) -> int:
        return len(self.components)

    def load(self) -> ModuleType:
        """The kernel module."""
        return importlib.import_module(self.module)


PATHS: dict[str, Path] = {
    p.name: p
    for p in (
        Path(
            "rotor",
            "ga_rotors.paths.rotor",
            "rotor_blades",
            ("1", "e12", "e13", "e23"),
            True,
            "rotor equation dR/dt = R Ω / 2 in Cl(3,0)",
        ),
        Path(
            "quaternion",
            "ga_rotors.paths.quaternion",
            "q",
            ("w", "x", "y", "z"),
            True,
            "quaternion kinematics dq/dt = q ⊗ (0, ω) / 2",
        ),
        Path(
            "euler",
            "ga_rotors.paths.euler",
            "euler",
            ("psi", "theta", "phi"),
            False,
            "the paper's ZYZ Euler-angle rates (singular at sin θ = 0)",
        ),
    )
}


def get(name: str) -> Path:
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
