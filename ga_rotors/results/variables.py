"""What each array of a trajectory is: its unit, its long name and its component axis.

One table for every results format (xarray attributes, CSV headers), so a unit is
written once. Names are those of :class:`ga_rotors.trajectory.Trajectory`. Units are
written so that both UDUNITS (what CF files use) and pint (``pint-xarray``'s default
registry) read them: ``kg m^2/s``, not ``kg m2 s-1``, which pint does not parse.

CF's standard-name table has a name for time, and for a ship's or an aircraft's roll,
pitch and yaw rates about its own fore, starboard and down axes; it has none for a rigid
body's angular velocity vector, its quaternion, its ZYZ angles or its angular momentum,
so those carry a ``long_name`` and ``units`` only (:data:`STANDARD`).
"""

from __future__ import annotations

from ..errors import InputError

__all__ = ["COMPONENT_DIMS", "STANDARD", "VARIABLES", "describe"]

#: array name -> (unit, long name). Units follow SI; "1" is dimensionless.
VARIABLES: dict[str, tuple[str, str]] = {
    "t": ("s", "simulation time"),
    "w": ("rad/s", "body angular velocity of the primary path"),
    "q": ("1", "orientation quaternion (w, x, y, z), body to space, of the quaternion path"),
    "rotor_blades": (
        "1",
        "rotor path's raw state: coefficients on clifford's blades (1, e12, e13, e23), "
        "not a quaternion",
    ),
    "euler": ("rad", "integrated ZYZ Euler angles (psi, theta, phi), Euler-angle path"),
    "energy": ("J", "kinetic energy 1/2 w.Iw of the primary path"),
    "potential_energy": ("J", "gravitational energy -m g.r_space about the pivot"),
    "total_energy": ("J", "kinetic plus gravitational energy"),
    "L": ("kg m^2/s", "body-frame angular momentum Iw"),
    "L_space": ("kg m^2/s", "space-frame angular momentum q (Iw) q*"),
    "omega_space": ("rad/s", "space-frame angular velocity q w q*"),
    "angles": ("rad", "ZYZ Euler angles (psi, theta, phi) of the primary path's orientation"),
    "omega_error": ("rad/s", "|w - w_exact| of the primary path"),
    "position": ("m", "position of the body-frame origin in space, primary path"),
    "velocity": ("m/s", "velocity of the body-frame origin in space, primary path"),
    "motor": (
        "1",
        "motor path's raw state: the body frame's motor on the blades (1, e01, e02, e03, "
        "e12, e13, e23, e0123), the e0 blades in m",
    ),
    "q_com": (
        "1",
        "quaternion path's raw state for a moving body: q (w, x, y, z) and the centre of "
        "mass in space (cx, cy, cz) in m",
    ),
}

#: array name -> its CF attributes beyond units and long name (CF's standard-name table
#: has an entry for time; see the module's notes for the rest).
STANDARD: dict[str, dict[str, str]] = {"t": {"standard_name": "time", "axis": "T"}}

#: component labels -> name of the dimension they index.
COMPONENT_DIMS: dict[tuple[str, ...], str] = {
    ("w", "x", "y", "z"): "quaternion_component",
    ("1", "e12", "e13", "e23"): "rotor_blade",
    ("1", "2", "3"): "body_axis",
    ("x", "y", "z"): "space_axis",
    ("psi", "theta", "phi"): "zyz_angle",
    ("1", "e01", "e02", "e03", "e12", "e13", "e23", "e0123"): "motor_blade",
    ("w", "x", "y", "z", "cx", "cy", "cz"): "pose_component",
}


def describe(name: str) -> tuple[str, str]:
    """(unit, long name) of the trajectory array ``name``.

    Examples
    --------
    >>> describe("w")
    ('rad/s', 'body angular velocity of the primary path')
    >>> describe("error_quaternion")
    ('rad', 'geodesic angle from the exact orientation, quaternion path')
    >>> describe("x")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: x: no unit is known for this array
    """
    if name in VARIABLES:
        return VARIABLES[name]
    if name.startswith("error_"):
        path = name[len("error_") :]  # one per path: error_rotor, error_quaternion, ...
        return "rad", f"geodesic angle from the exact orientation, {path} path"
    raise InputError(f"{name}: no unit is known for this array")
