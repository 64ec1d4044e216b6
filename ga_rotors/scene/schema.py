"""The scene schema: every table and key a scene may hold, read and checked with defaults.

:func:`resolve` turns the nested data of a scene file into the *resolved* scene: every
key checked (type, range, units, spelling, with the closest valid name suggested) and
every default filled in, so that the resolved data, written back as TOML, is a complete
scene file. Nothing here is evaluated or imported: user torques are only named. The
keys, their types, defaults and units are documented in ``docs/scenes.md``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from .. import effects as _effects
from .. import paths as _paths
from ..errors import InputError
from ..paper.figures import FIGURE_FORMATS
from ..shapes import SHAPES
from .formats import FORMATS, default_data
from .reader import Reader, join

__all__ = [
    "ANGLE_UNITS",
    "ANGULAR_VELOCITY_FORMS",
    "MAX_EFFECTS",
    "MIN_TOLERANCE",
    "MOTION_KEYS",
    "NAME",
    "ORIENTATION_FORMS",
    "PLOTS",
    "QUANTITIES",
    "RATE_UNITS",
    "ROTOR_BLADES",
    "SECTIONS",
    "adaptive",
    "compile_seconds",
    "moves",
    "resolve",
]


#: Top-level tables, in the order a resolved scene lists them.
SECTIONS = ("scene", "body", "initial", "time", "integrator", "effects", "forces", "output")

#: Angle units -> radians per unit.
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}
#: Angular-rate units -> rad/s per unit.
RATE_UNITS = {"rad/s": 1.0, "deg/s": math.pi / 180.0, "rpm": 2.0 * math.pi / 60.0}

ORIENTATION_FORMS = ("quaternion", "euler", "rotor", "axis")
ANGULAR_VELOCITY_FORMS = ("body", "space", "euler_rates")

#: Rotor blade names accepted in ``initial.orientation.rotor``: Cl(3) index and sign.
ROTOR_BLADES = {
    "1": (0, 1.0),
    "e12": (4, 1.0),
    "e21": (4, -1.0),
    "e13": (5, 1.0),
    "e31": (5, -1.0),
    "e23": (6, 1.0),
    "e32": (6, -1.0),
}

#: Arrays a scene can add to its trajectory (``output.quantities``).
QUANTITIES = {
    "energy": "kinetic energy ½ ω·Iω (J)",
    "potential_energy": "gravitational energy −m g·r_space about the pivot (J); gravity only",
    "total_energy": "kinetic plus gravitational energy (J)",
    "L": "body-frame angular momentum Iω (kg·m²/s)",
    "L_space": "space-frame angular momentum q (Iω) q* (kg·m²/s)",
    "omega_space": "space-frame angular velocity q ω q* (rad/s)",
    "angles": "ZYZ Euler angles (ψ, θ, φ) of the primary path's orientation (rad)",
    "error": "geodesic angle from the exact orientation, one array per path (rad)",
    "omega_error": "|ω − ω_exact| of the primary path (rad/s)",
}

#: Figures ``ga-rotors run`` can draw (``output.plots``).
PLOTS = {
    "omega": "body angular velocity components against time",
    "angles": "nutation θ and precession ψ (ZYZ) of the primary path against time",
    "momentum": "space-frame angular momentum components against time",
    "invariants": "drift of the scene's conserved quantities (or their exact decay)",
    "error": "geodesic error of each path against the exact solution",
    "position": "the body-frame origin's position in space against time (a moving body)",
}

#: ``initial`` keys of a body moving through space -> their unit (SI, space frame).
MOTION_KEYS = {"position": "m", "velocity": "m/s"}

#: Most ``[[effects]]`` entries a scene may declare (see :func:`compile_seconds`), and
#: most ``[[effects]]`` and ``[[forces]]`` together.
MAX_EFFECTS = 64


def compile_seconds(effects: int, evaluations: float = 4.0) -> float:
    """Rough CPU seconds numba takes to compile one path's loop with ``effects`` torque
    terms, for a method of ``evaluations`` vector-field evaluations a step, on a first run
    (the loop is cached after). Fitted on one core of this machine to rk4 (0.9, 1.7, 2.7,
    6.3, 15 s for 1, 32, 64, 128, 256 body torques) and dp8 (3.9, 4.9, 5.7 s for 1, 32,
    64): the method's own stages set the base, and the torque sum grows faster than
    linearly in its terms (LLVM optimises the whole loop at once).

    Examples
    --------
    >>> round(compile_seconds(1), 1), round(compile_seconds(64), 1), round(compile_seconds(256))
    (1.0, 3.6, 15)
    >>> round(compile_seconds(64, evaluations=12), 1)  # dp8
    5.6
    """
    return 0.25 * evaluations + 0.035 * effects + 8e-5 * effects**2


#: Smallest relative tolerance an adaptive method is given: 100 ulps, scipy's floor for
#: its own adaptive methods; a tolerance of 5e-324 made dop853 shrink its step forever.
MIN_TOLERANCE = 100 * 2.0**-52

#: What ``scene.name`` may be: a file name (the outputs are named after it).
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")
#: Longest ``scene.name``: with the longest suffix (``.summary.txt``) a file name stays
#: far below the 255 bytes file systems take.
NAME_LENGTH = 100


# ---------------------------------------------------------------------------- resolving


def _units(reader: Reader, table: dict, key: str, units: dict, what: str) -> str:
    if "units" not in table:
        raise reader.error(
            join(key, "units"),
            f"missing; {what} are ambiguous without units: expected one of "
            + ", ".join(f'"{u}"' for u in units),
        )
    return reader.string(table["units"], join(key, "units"), units)


def _resolve_scene(reader: Reader, value, default_name: str) -> dict:
    t = reader.table(value, "scene", ("name", "description"))
    name = reader.string(t.get("name", default_name), "scene.name")
    if not NAME.fullmatch(name):  # (match would take "top\n": $ matches before a newline)
        raise reader.error(
            "scene.name", f"expected letters, digits, '_', '.', '-' (a file name), got {name!r}"
        )
    if len(name) > NAME_LENGTH:
        raise reader.error(
            "scene.name", f"expected at most {NAME_LENGTH} characters, got {len(name)}"
        )
    return {"name": name, "description": reader.string(t.get("description", ""),
                                                       "scene.description")}  # fmt: skip


def _dimension_keys() -> list[str]:
    return sorted({d for _, dims in SHAPES.values() for d in dims})


def _resolve_body(reader: Reader, value) -> dict:
    dims = _dimension_keys()
    t = reader.table(value, "body", ("moments", "tensor", "shape", "mass", "centre_of_mass",
                                     *dims))  # fmt: skip
    form = reader.one_of(t, "body", ("moments", "tensor", "shape"))
    out: dict = {}
    if form == "moments":
        out["moments"] = list(reader.vector(t["moments"], "body.moments", unit="kg·m²"))
    elif form == "tensor":
        out["tensor"] = [list(r) for r in reader.matrix(t["tensor"], "body.tensor")]
    else:
        shape = reader.string(t["shape"], "body.shape", SHAPES)
        out["shape"] = shape
        needed = SHAPES[shape][1]
        for d in ("mass", *needed):
            if d not in t:
                raise reader.error(
                    join("body", d),
                    f"missing; a {shape} needs mass and {', '.join(needed)} (kg, m)",
                )
    if "mass" in t:
        out["mass"] = reader.number(t["mass"], "body.mass", positive=True, unit="kg")
    if "centre_of_mass" in t:  # stored only when given, as every motion key
        out["centre_of_mass"] = list(reader.vector(t["centre_of_mass"], "body.centre_of_mass",
                                                   unit="m"))  # fmt: skip
    for d in dims:
        if d in t:
            if form != "shape" or d not in SHAPES[out["shape"]][1]:
                takes = (
                    f"a {out['shape']} takes {', '.join(SHAPES[out['shape']][1])}"
                    if form == "shape"
                    else "dimensions go with body.shape"
                )
                raise reader.error(join("body", d), f"not used here: {takes}")
            out[d] = reader.number(t[d], join("body", d), positive=True, unit="m")
    return out


def _resolve_orientation(reader: Reader, value) -> dict:
    key = "initial.orientation"
    if value is None:
        return {"quaternion": [1.0, 0.0, 0.0, 0.0]}
    allowed = {
        "quaternion": ("quaternion",),
        "euler": ("euler", "sequence", "units"),
        "rotor": ("rotor",),
        "axis": ("axis", "angle", "units"),
    }
    every = list(dict.fromkeys(k for keys in allowed.values() for k in keys))
    t = reader.table(value, key, every)
    form = reader.one_of(t, key, ORIENTATION_FORMS)
    reader.table(t, key, allowed[form])
    if form == "quaternion":
        return {"quaternion": list(reader.vector(t["quaternion"], join(key, "quaternion"), 4))}
    if form == "rotor":
        blades = reader.table(t["rotor"], join(key, "rotor"), ROTOR_BLADES)
        out = {}
        seen: dict[int, str] = {}
        for name, v in blades.items():
            index = ROTOR_BLADES[name][0]
            if index in seen:
                raise reader.error(
                    join(join(key, "rotor"), name), f"the same blade as {seen[index]!r}; give one"
                )
            seen[index] = name
            out[name] = reader.number(v, join(join(key, "rotor"), name))
        return {"rotor": out}
    if form == "euler":
        if "sequence" not in t:
            raise reader.error(
                join(key, "sequence"),
                'missing; Euler angles need their axis sequence, e.g. "ZYZ" (the paper\'s) or '
                '"ZYX" (aerospace)',
            )
        from ..euler import SEQUENCES

        return {
            "euler": list(reader.vector(t["euler"], join(key, "euler"))),
            "sequence": reader.string(t["sequence"], join(key, "sequence"), SEQUENCES),
            "units": _units(reader, t, key, ANGLE_UNITS, "angles"),
        }
    for k in ("angle",):
        if k not in t:
            raise reader.error(join(key, k), "missing; axis-angle needs axis, angle and units")
    return {
        "axis": list(reader.vector(t["axis"], join(key, "axis"))),
        "angle": reader.number(t["angle"], join(key, "angle")),
        "units": _units(reader, t, key, ANGLE_UNITS, "angles"),
    }


def _resolve_angular_velocity(reader: Reader, value, orientation: dict) -> dict:
    key = "initial.angular_velocity"
    if value is None:
        return {"body": [0.0, 0.0, 0.0], "units": "rad/s"}
    t = reader.table(value, key, (*ANGULAR_VELOCITY_FORMS, "units"))
    form = reader.one_of(t, key, ANGULAR_VELOCITY_FORMS)
    if form == "euler_rates" and "euler" not in orientation:
        raise reader.error(
            join(key, "euler_rates"),
            "Euler-angle rates need the angles: give initial.orientation as euler (their "
            "sequence is the orientation's)",
        )
    return {
        form: list(reader.vector(t[form], join(key, form))),
        "units": _units(reader, t, key, RATE_UNITS, "angular rates"),
    }


def _resolve_initial(reader: Reader, value) -> dict:
    t = reader.table(value if value is not None else {}, "initial",
                     ("orientation", "angular_velocity", *MOTION_KEYS))  # fmt: skip
    orientation = _resolve_orientation(reader, t.get("orientation"))
    out = {
        "orientation": orientation,
        "angular_velocity": _resolve_angular_velocity(
            reader, t.get("angular_velocity"), orientation
        ),
    }
    # Stored only when given: a scene without them turns about a fixed point, and its
    # resolved data (and its figures' digests) are what they were before the keys existed.
    for name, unit in MOTION_KEYS.items():
        if name in t:
            out[name] = list(reader.vector(t[name], join("initial", name), unit=unit))
    return out


def moves(data: Mapping) -> bool:
    """Whether the scene ``data`` (given or resolved) describes a body moving through
    space: it gives ``initial.position`` or ``initial.velocity``, or declares forces.

    Examples
    --------
    >>> moves({"initial": {"velocity": [0, 0, 1]}}), moves({"body": {"moments": [1, 2, 3]}})
    (True, False)
    """
    initial = data.get("initial")
    given = isinstance(initial, Mapping) and any(k in initial for k in MOTION_KEYS)
    return bool(given or data.get("forces"))


def adaptive(method) -> bool:
    """Whether an integrator sets its accuracy by a tolerance (``rtol``), not a step: what
    it declares (:attr:`ga_rotors.integrators.Integrator.adaptive`).

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> adaptive(get("dop853")), adaptive(get("rk4"))
    (True, False)
    """
    return bool(method.adaptive)


def _resolve_integrator(reader: Reader, value, moving: bool = False) -> dict:
    from ..integrators import base

    t = reader.table(value if value is not None else {}, "integrator",
                     ("method", "step", "tolerance", "paths", "accept_lower_order"))  # fmt: skip
    name = reader.string(t.get("method", "rk4"), "integrator.method", base.names())
    method = base.get(name)
    out: dict = {"method": name, "step": None}
    if "step" in t:
        out["step"] = reader.number(t["step"], "integrator.step", positive=True, unit="s")
    if adaptive(method):
        out["tolerance"] = reader.number(t.get("tolerance", method.rtol), "integrator.tolerance",
                                         positive=True)  # fmt: skip
        if out["tolerance"] >= 1.0:
            raise reader.error("integrator.tolerance", f"expected < 1, got {out['tolerance']!r}")
        if out["tolerance"] < MIN_TOLERANCE:
            raise reader.error(
                "integrator.tolerance",
                f"expected at least {MIN_TOLERANCE:.2g}, got {out['tolerance']!r} (a relative "
                "tolerance below 100 ulps cannot be met in float64: the steps would shrink "
                "without end)",
            )
    else:
        if "tolerance" in t:
            others = [n for n in base.names() if adaptive(base.get(n))]
            raise reader.error(
                "integrator.tolerance",
                f"{name} is a fixed-step method: integrator.step sets its accuracy (a "
                f"tolerance is for adaptive methods: {', '.join(others)})",
            )
        if out["step"] is None:
            raise reader.error("integrator.step", f"missing; {name} is a fixed-step method")
    paths = reader.names(t.get("paths", ["motor" if moving else "rotor"]), "integrator.paths",
                         _paths.PATHS)  # fmt: skip
    if not paths:
        raise reader.error(
            "integrator.paths", f"expected at least one of {', '.join(_paths.PATHS)}"
        )
    for i, path in enumerate(paths):
        try:
            _paths.resolve(path, moving)
        except InputError as exc:
            why = ("" if moving else " (this scene turns about a fixed point: it gives no "
                   "initial.position, initial.velocity or forces)")  # fmt: skip
            raise reader.error(join("integrator.paths", i), exc.detail + why) from None
    out["paths"] = paths
    # Stored only when set: the resolved default scene (and its figures' digests) is the
    # same as before the key existed.
    if reader.boolean(t.get("accept_lower_order", False), "integrator.accept_lower_order"):
        out["accept_lower_order"] = True
    return out


def _resolve_time(reader: Reader, value) -> dict:
    t = reader.table(value, "time", ("start", "duration", "output_step"), ("duration",))
    out = {
        "start": reader.number(t.get("start", 0.0), "time.start", unit="s"),
        "duration": reader.number(t["duration"], "time.duration", positive=True, unit="s"),
        "output_step": None,  # default: the integrator's step, filled in by _resolve
    }
    if "output_step" in t:
        out["output_step"] = reader.number(
            t["output_step"], "time.output_step", positive=True, unit="s"
        )
    return out


def _resolve_effects(reader: Reader, value) -> list[dict]:
    entries = reader.array(value if value is not None else [], "effects")
    if len(entries) > MAX_EFFECTS:
        raise reader.error(
            "effects",
            f"{len(entries):,} entries; a scene declares at most {MAX_EFFECTS} (each is a term "
            "of every compiled loop, and compiling grows faster than their number: about "
            f"{compile_seconds(MAX_EFFECTS):.0f} s a path at {MAX_EFFECTS}); sum constant "
            "torques into one entry",
        )
    out = []
    for i, entry in enumerate(entries):
        key = join("effects", i)
        if not isinstance(entry, Mapping):
            raise reader.error(key, "expected a table ([[effects]] with a type)")
        if "type" not in entry:
            raise reader.error(
                join(key, "type"), f"missing; expected one of {', '.join(_effects.EFFECTS)}"
            )
        kind = reader.string(entry["type"], join(key, "type"), _effects.EFFECTS)
        out.append(_effects.EFFECTS[kind].resolve(reader, dict(entry), key))
    gravity = [i for i, e in enumerate(out) if e["type"] == "gravity"]
    if len(gravity) > 1:
        raise reader.error(
            join("effects", gravity[1]), "a body has one pivot: declare gravity at most once"
        )
    return out


def _resolve_forces(reader: Reader, value) -> list[dict]:
    from .force_types import FORCE_TYPES

    entries = reader.array(value if value is not None else [], "forces")
    out = []
    for i, entry in enumerate(entries):  # (more than MAX_EFFECTS: refused before)
        key = join("forces", i)
        if not isinstance(entry, Mapping):
            raise reader.error(key, "expected a table ([[forces]] with a type)")
        if "type" not in entry:
            raise reader.error(join(key, "type"),
                               f"missing; expected one of {', '.join(FORCE_TYPES)}")  # fmt: skip
        kind = reader.string(entry["type"], join(key, "type"), FORCE_TYPES)
        out.append(FORCE_TYPES[kind].resolve(reader, dict(entry), key))
    return out


def _check_terms(reader: Reader, effects: list, forces: list) -> None:
    """The cap on compiled terms holds for torques and forces together: each is a term of
    every compiled loop (see :func:`compile_seconds`)."""
    if len(effects) + len(forces) > MAX_EFFECTS:
        raise reader.error(
            "forces",
            f"{len(effects)} effects and {len(forces):,} forces; a scene declares at most "
            f"{MAX_EFFECTS} terms in all (each is a term of every compiled loop, and "
            f"compiling grows faster than their number: about "
            f"{compile_seconds(MAX_EFFECTS):.0f} s a path at {MAX_EFFECTS}); sum constant "
            "forces into one entry",
        )


def _check_motion(reader: Reader, out: dict) -> None:
    """A moving body needs its mass and cannot have a pivot; ``body.centre_of_mass`` is
    for a moving body (a pivoted one gives its lever in the gravity effect)."""
    initial, forces = out["initial"], out["forces"]
    first = next((join("initial", k) for k in MOTION_KEYS if k in initial), "forces[0]")
    if not (forces or any(k in initial for k in MOTION_KEYS)):
        if "centre_of_mass" in out["body"]:
            raise reader.error(
                "body.centre_of_mass",
                "only for a body moving through space (with initial.position, initial.velocity "
                "or forces); a body turning about a pivot gives effects.pivot_to_com",
            )
        return
    gravity = next((i for i, e in enumerate(out["effects"]) if e["type"] == "gravity"), None)
    if gravity is not None:
        raise reader.error(
            first,
            f"the scene has a pivot (effects[{gravity}], gravity about a fixed point): a "
            "pivoted body turns in place and has no position or forces; for a body moving "
            'through space declare its weight as [[forces]] type = "uniform_gravity"',
        )
    if "mass" not in out["body"]:
        raise reader.error("body.mass", f"missing; a body moving through space ({first}) "
                           "needs its mass (kg)")  # fmt: skip


def _resolve_output(reader: Reader, value) -> dict:
    t = reader.table(value if value is not None else {}, "output",
                     ("quantities", "plots", "figure_format", "data", "summary"))  # fmt: skip
    return {
        "quantities": reader.names(t.get("quantities", []), "output.quantities", QUANTITIES),
        "plots": reader.names(t.get("plots", []), "output.plots", PLOTS),
        "figure_format": reader.string(
            t.get("figure_format", "png"), "output.figure_format", FIGURE_FORMATS
        ),
        "data": reader.names(t.get("data", default_data()), "output.data", FORMATS),
        "summary": reader.boolean(t.get("summary", True), "output.summary"),
    }


def resolve(reader: Reader, data, default_name: str) -> dict:
    """The scene ``data`` checked key by key, every default filled in.

    Parameters
    ----------
    reader : Reader
        Names the file in errors.
    data : mapping
        The scene as parsed from TOML (or built in Python).
    default_name : str
        ``scene.name`` when the data give none.

    Examples
    --------
    >>> data = resolve(Reader("x.toml"), {"body": {"moments": [1, 2, 3]},
    ...                "time": {"duration": 1.0}, "integrator": {"step": 0.5}}, "x")
    >>> data["integrator"], data["time"]["output_step"]
    ({'method': 'rk4', 'step': 0.5, 'paths': ['rotor']}, 0.5)
    >>> resolve(Reader("x.toml"), {"body": {}, "time": {"duration": 1.0}}, "x")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: x.toml: body: expected exactly one of moments, tensor, ...
    """
    top = reader.table(data, "", SECTIONS, ("body", "time"))
    forces = reader.array(top.get("forces", []), "forces")
    if len(forces) > MAX_EFFECTS:  # before any entry is read
        _check_terms(reader, [], forces)
    out = {
        "scene": _resolve_scene(reader, top.get("scene", {}), default_name),
        "body": _resolve_body(reader, top["body"]),
        "initial": _resolve_initial(reader, top.get("initial")),
        "time": _resolve_time(reader, top["time"]),
        "integrator": _resolve_integrator(reader, top.get("integrator"), moves(top)),
        "effects": _resolve_effects(reader, top.get("effects")),
        "forces": _resolve_forces(reader, forces),
        "output": _resolve_output(reader, top.get("output")),
    }
    _check_terms(reader, out["effects"], out["forces"])
    _check_motion(reader, out)
    if not out["forces"]:  # stored only when declared (see _resolve_initial)
        del out["forces"]
    time, integrator = out["time"], out["integrator"]
    if integrator["step"] is None:  # an adaptive method: the step only fixes sample times
        if time["output_step"] is None:
            raise reader.error(
                "integrator.step",
                f"missing; {integrator['method']} is adaptive, but its samples need "
                "integrator.step or time.output_step",
            )
        integrator["step"] = time["output_step"]
    if time["output_step"] is None:
        time["output_step"] = integrator["step"]
    return out
