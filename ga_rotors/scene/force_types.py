"""Forces a scene can declare (``[[forces]]``): each type, its keys, and its ForceTerm.

A scene's ``[[forces]]`` entries become :class:`ga_rotors.integrators.ForceTerm` objects
built by :mod:`ga_rotors.forces` on the scene's body (its mass, its centre of mass, its
principal axes): only the declared forces are simulated, as only the declared torques
are. Body points (``at``) are in the scene's body frame from the body-frame origin, m;
forces, anchors and centres are in space.

=============== ================================================== ====================
type            force                                              keys
=============== ================================================== ====================
uniform_gravity the weight m g at the centre of mass               g
spring          a spring from a body point to a space anchor       stiffness, anchor,
                                                                   at, rest_length
point_force     a constant force at a body point, fixed in space   force, at, fixed_in
                or turning with the body
linear_drag     F = −b v at the centre of mass                     coefficient
central_gravity a planet's field with its gravity-gradient torque  mu, centre
user            a compiled kernel(t, q, c, w, v, p) (opt-in only)  function, params,
                                                                   depends_on_velocity
=============== ================================================== ====================

Examples
--------
>>> from ga_rotors.scene.reader import Reader
>>> entry = FORCE_TYPES["spring"].resolve(Reader("x.toml"),
...     {"type": "spring", "stiffness": 8.0, "anchor": [0, 0, 1]}, "forces[0]")
>>> entry
{'type': 'spring', 'stiffness': 8.0, 'anchor': [0.0, 0.0, 1.0], 'at': [0.0, 0.0, 0.0], 'rest_length': 0.0}
>>> FORCE_TYPES["spring"].resolve(Reader("x.toml"), {"type": "spring", "anchor": [0, 0, 1]},
...                               "forces[0]")
Traceback (most recent call last):
...
ga_rotors.errors.SceneError: x.toml: forces[0].stiffness: missing; this key is required
"""  # noqa: E501

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from .. import forces as _forces
from ..effects import EffectType, Key
from ..errors import InputError
from ..integrators.problem import ForceTerm
from .reader import Reader, join

__all__ = ["FORCE_TYPES", "ForceType"]


@dataclass(frozen=True)
class ForceType:
    """A kind of force a scene may declare: its keys and how a resolved entry becomes a
    ForceTerm on the scene's body.

    Examples
    --------
    >>> [k.name for k in FORCE_TYPES["point_force"].keys]
    ['force', 'at', 'fixed_in']
    """

    name: str
    doc: str
    keys: tuple[Key, ...]
    build: Callable = field(repr=False)
    #: whether the force reads the velocity; None: the entry's own key says
    depends_on_velocity: bool | None = False

    def reads_velocity(self, entry: dict) -> bool:
        """Whether the force of a resolved ``entry`` reads the velocities (w or v).

        Examples
        --------
        >>> FORCE_TYPES["linear_drag"].reads_velocity({})
        True
        >>> FORCE_TYPES["user"].reads_velocity({"depends_on_velocity": False})
        False
        """
        if self.depends_on_velocity is None:
            return bool(entry["depends_on_velocity"])
        return self.depends_on_velocity

    def resolve(self, reader: Reader, entry: dict, key: str) -> dict:
        """Check ``entry``'s keys and fill defaults; ``type`` first (as an effect's)."""
        return EffectType.resolve(self, reader, entry, key)

    def term(self, entry: dict, body, reader: Reader, key: str) -> ForceTerm:
        """The ForceTerm of a resolved ``entry`` on ``body`` (a RigidBody with a mass);
        a refusal is a SceneError naming the entry's key."""
        try:
            return self.build(entry, body)
        except InputError as exc:
            where = join(key, exc.key) if exc.key and exc.key != "body" else key
            raise reader.error(where, exc.detail) from None


def _vector(reader, value, key):
    return list(reader.vector(value, key))


def _nonzero_vector(reader, value, key):
    v = _vector(reader, value, key)
    if not any(v):
        raise reader.error(key, "expected a nonzero vector; without it, omit the force")
    return v


def _positive(unit):
    return lambda reader, value, key: reader.number(value, key, positive=True, unit=unit)


def _nonnegative(unit):
    return lambda reader, value, key: reader.number(value, key, nonnegative=True, unit=unit)


def _fixed_in(reader, value, key):
    return reader.string(value, key, ("space", "body"))


def _function(reader, value, key):
    from ..effects import EFFECTS

    # the same rule as a user torque's name
    return next(k for k in EFFECTS["user"].keys if k.name == "function").read(reader, value, key)


def _params(reader, value, key):
    return list(reader.numbers(value, key))


def _boolean(reader, value, key):
    return reader.boolean(value, key)


def _gravity(entry, body):
    return _forces.uniform_gravity(body, entry["g"])


def _spring(entry, body):
    return _forces.spring(body, entry["stiffness"], entry["anchor"], at=entry["at"],
                          rest_length=entry["rest_length"])  # fmt: skip


def _point_force(entry, body):
    return _forces.point_force(body, entry["force"], at=entry["at"], fixed_in=entry["fixed_in"])


def _drag(entry, body):
    return _forces.linear_drag(body, entry["coefficient"])


def _central(entry, body):
    return _forces.central_gravity(body, entry["mu"], centre=entry["centre"])


def _user(entry, body):
    try:
        return _forces.user_force(entry["function"], entry["params"],
                                  depends_on_velocity=entry["depends_on_velocity"])  # fmt: skip
    except InputError as exc:  # the refusal to import is about the function key too
        raise InputError(exc.detail, key=exc.key or "function") from None


_AT = "m, body frame, from the body-frame origin: where it acts"
_DOWN = [0.0, 0.0, -_forces.STANDARD_GRAVITY]
_MU = "m³/s², the planet's G M (the Earth's by default)"
_READS = "whether the kernel reads w or v (false lets the splittings take it at their order)"

#: type name -> ForceType, in the order the docs list them.
FORCE_TYPES: dict[str, ForceType] = {
    f.name: f
    for f in (
        ForceType(
            "uniform_gravity",
            "the weight m g at the centre of mass",
            (Key("g", _nonzero_vector, _DOWN, "m/s², space frame"),),
            _gravity,
        ),
        ForceType(
            "spring",
            "a spring from a body point to a space anchor, F = k (|d| − ℓ₀) d/|d|",
            (
                Key("stiffness", _positive("N/m"), doc="N/m"),
                Key("anchor", _vector, doc="m, space frame: the spring's fixed end"),
                Key("at", _vector, [0.0, 0.0, 0.0], _AT),
                Key("rest_length", _nonnegative("m"), 0.0, "m"),
            ),
            _spring,
        ),
        ForceType(
            "point_force",
            "a constant force at a body point, fixed in space (a pull) or in the body (a thrust)",
            (
                Key("force", _vector, doc="N, space or body components (fixed_in)"),
                Key("at", _vector, [0.0, 0.0, 0.0], _AT),
                Key("fixed_in", _fixed_in, "space", '"space" or "body"'),
            ),
            _point_force,
        ),
        ForceType(
            "linear_drag",
            "linear drag F = −b v at the centre of mass",
            (Key("coefficient", _nonnegative("N·s/m"), doc="N·s/m"),),
            _drag,
            depends_on_velocity=True,
        ),
        ForceType(
            "central_gravity",
            "a planet's gravity μ/r² on the extended body, with the gravity-gradient torque",
            (
                Key("mu", _positive("m³/s²"), _forces.EARTH_MU, _MU),
                Key("centre", _vector, [0.0, 0.0, 0.0], "m, space frame: the planet's centre"),
            ),
            _central,
        ),
        ForceType(
            "user",
            "a compiled kernel(t, q, c, w, v, p) named package.module:function (runs only "
            "with --allow-user-code)",
            (
                Key("function", _function, doc='"package.module:function", compiled'),
                Key("params", _params, [], "numbers passed to the kernel as p"),
                Key("depends_on_velocity", _boolean, True, _READS),
            ),
            _user,
            depends_on_velocity=None,
        ),
    )
}
