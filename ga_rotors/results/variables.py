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

__all__ = ["COMPONENT_DIMS", "PARTS", "STANDARD", "VARIABLES", "component_dim", "describe",
           "one_unit"]  # fmt: skip

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
    # the raw states of a moving body's paths, each split into parts of one unit (PARTS)
    "motor_rotor": (
        "1",
        "motor path's raw state, its rotor part: the body frame's motor on the blades "
        "(1, e12, e13, e23)",
    ),
    "motor_dual": (
        "m",
        "motor path's raw state, its e0 part: the body frame's motor on the blades "
        "(e01, e02, e03, e0123)",
    ),
    "com_position": ("m", "position of the centre of mass in space, quaternion path"),
}

#: A trajectory array whose components carry different units -> its parts, each of one
#: unit, as every results file holds it: (part's name, columns, component labels). The
#: motor's rotor blades are numbers and its e0 blades metres; the quaternion path of a
#: moving body holds q and the centre of mass in space (m). Neither part is derivable from
#: the other variables (``position`` is the primary path's, which may be the other path),
#: so the parts are kept, not dropped.
PARTS: dict[str, tuple[tuple[str, tuple[int, ...], tuple[str, ...]], ...]] = {
    "motor": (
        ("motor_rotor", (0, 4, 5, 6), ("1", "e12", "e13", "e23")),
        ("motor_dual", (1, 2, 3, 7), ("e01", "e02", "e03", "e0123")),
    ),
    "q_com": (
        ("q", (0, 1, 2, 3), ("w", "x", "y", "z")),
        ("com_position", (4, 5, 6), ("x", "y", "z")),
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
    ("e01", "e02", "e03", "e0123"): "motor_dual_blade",
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


def component_dim(trajectory, name: str) -> tuple[str, tuple[str, ...]]:
    """The dimension the columns of ``trajectory``'s array ``name`` run along, and their
    labels (``0``, ``1``, ... when it has none).

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.zeros(1), "w": np.zeros((1, 3)), "x": np.zeros((1, 2))},
    ...                 {"w": ("1", "2", "3")})
    >>> component_dim(tr, "w"), component_dim(tr, "x")
    (('body_axis', ('1', '2', '3')), ('x_component', ('0', '1')))
    """
    labels = trajectory.components.get(name)
    labels = tuple(labels) if labels else tuple(str(i) for i in range(trajectory[name].shape[1]))
    return COMPONENT_DIMS.get(labels, f"{name}_component"), labels


def one_unit(trajectory):
    """``trajectory`` with each array of :data:`PARTS` replaced by its parts, so every
    array has one unit (the same Trajectory when it has none of them).

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.zeros(1), "q_com": np.arange(7.0)[None]},
    ...                 {"q_com": ("w", "x", "y", "z", "cx", "cy", "cz")})
    >>> split = one_unit(tr)
    >>> split.names, split["com_position"].tolist(), describe("com_position")[0]
    (('t', 'q', 'com_position'), [[4.0, 5.0, 6.0]], 'm')
    """
    if not any(name in PARTS for name in trajectory.names):
        return trajectory
    arrays, components = {}, {}
    for name in trajectory.names:
        labels = trajectory.components.get(name)
        if name not in PARTS:
            arrays[name] = trajectory[name]
            if labels:
                components[name] = labels
            continue
        for part, columns, part_labels in PARTS[name]:
            arrays[part] = trajectory[name][:, list(columns)]
            components[part] = part_labels
    # its own class, not an import of ga_rotors.trajectory (which imports this module)
    return type(trajectory)(arrays, components, trajectory.meta)
