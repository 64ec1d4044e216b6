"""Torques a scene can declare, each a compiled kernel and its parameters (a TorqueTerm).

A scene's ``[[effects]]`` entries become :class:`ga_rotors.integrators.TorqueTerm` objects;
the code generator (:mod:`ga_rotors.integrators._source`) writes a loop whose ``torque``
is the sum of exactly those kernels. An effect that is not declared is not in the
generated source at all, and a scene without effects is the free problem, whose loop has
no torque term. Every kernel returns the torque in the *principal body frame* the
integration runs in; ``q`` is the body->space unit quaternion, ``w`` the body angular
velocity, ``p`` the term's parameters. The kernels are internal (not in ``__all__``): compiled,
unchecked, and called only from the generated loops with parameters built from a
validated scene.

=============== ======================================================== ==================
type            torque (body frame)                                      parameters
=============== ======================================================== ==================
gravity         τ = r × (q* (m g) q): weight m g (space frame) acting    m g (3), r (3)
                at the centre of mass, r from the pivot to it (body)
damping         τ = −c ω (isotropic) or τ = −C ω (C diagonal in the      c, or C (9)
                user's body axes, carried into the principal frame)
body_torque     τ = constant (body frame)                                τ (3)
space_torque    τ = q* τ_s q, a constant space-frame torque              τ_s (3)
user            ``kernel(t, q, w, p)`` named ``"package.module:function"`` the listed params
=============== ======================================================== ==================

The heavy top. A body turning about a fixed pivot obeys Euler's equations with the
inertia *about the pivot*: L = I_O ω and dL/dt = τ_O hold about a fixed point, not about
the centre of mass, which moves. When the body's inertia is given about its centre of
mass (the default, and always for a ``shape``), the parallel-axis theorem gives
I_O = I_cm + m (|r|² 1 − r rᵀ) (:func:`inertia_about_pivot`); the scene diagonalises I_O,
and the gravity torque is τ = r × m g with r = pivot→centre of mass. Energy
½ ω·I_O ω − m g·(q r q*) is then conserved (tests check it).

User torques. ``function = "package.module:function"`` names a *numba-compiled* kernel
(``@numba.njit``, ideally ``cache=True``) with the signature ``kernel(t, q, w, p)`` that
returns a 3-tuple of floats. It must be compiled (not a plain function) because the
generated loop imports it by name and calls it from compiled code; a plain function is
refused with a message saying how to compile it. The module is code: it is imported only
when the user opts in (``ga-rotors run --allow-user-code [DIR]``, see :mod:`ga_rotors.trust`),
when the validated scene is simulated (never when it is loaded or shown), and only from
the folders the user named. Before use the kernel's Python version is called once at
(t = 0, q = 1, ω = 0, p) and must return three finite numbers.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ._jit import jit
from ._kernels import cross, qconj, qrotate
from .errors import InputError
from .integrators.base import TorqueTerm
from .scene.reader import Reader, join
from .trust import import_user_module

# The torque kernels (gravity, isotropic_damping, damping, body_torque, space_torque) are
# not in __all__: they are called from generated compiled loops, which bind them by module
# and name, on values the scene has already validated; they check nothing themselves.
__all__ = [
    "EFFECTS",
    "STANDARD_GRAVITY",
    "EffectType",
    "Key",
    "gravity_kernel",
    "inertia_about_pivot",
    "listed",
    "load_user_kernel",
    "register",
    "torque_power",
]

#: m/s², the default gravity ``g = [0, 0, -STANDARD_GRAVITY]`` (space frame, z up).
STANDARD_GRAVITY = 9.80665


# ---------------------------------------------------------------------------- kernels


@jit
def gravity(t, q, w, p):
    """Torque of the weight about the pivot: r × (q* F q), F = m g (space), r = p[3:6].

    Examples
    --------
    m = 2 kg, g = 9.81 m/s² down, centre of mass 0.1 m up the body axis, tilted by
    θ = 0.5 rad about y: the torque is m g l sin θ about the body y axis.

    >>> import math
    >>> p = np.array([0.0, 0.0, -2.0 * 9.81, 0.0, 0.0, 0.1])
    >>> tilted = (math.cos(0.25), 0.0, math.sin(0.25), 0.0)
    >>> tau = gravity(0.0, tilted, (0.0, 0.0, 0.0), p)
    >>> tau[0] == tau[2] == 0.0, math.isclose(tau[1], 2.0 * 9.81 * 0.1 * math.sin(0.5))
    (True, True)
    >>> gravity(0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0), p)  # upright: balanced
    (-0.0, 0.0, 0.0)
    """
    f = qrotate(qconj(q), (p[0], p[1], p[2]))
    return cross((p[3], p[4], p[5]), f)


@jit
def vertical_gravity(t, q, w, p):
    """:func:`gravity` when the weight is along space z and the lever along body z
    (p[0] = p[1] = p[3] = p[4] = 0): the symmetric heavy top, in 8 operations a stage.

    τ = r × (q* F q) with F = f_z ẑ, r = r_z ẑ is r_z f_z ẑ × Z, Z = q* ẑ q =
    (2(xz − wy), 2(yz + wx), w² − x² − y² + z²): τ = k (−(yz + wx), xz − wy, 0) with
    k = 2 f_z r_z, instead of a rotation and a cross product (about 40 operations; the
    heavy top's dp8 step was 1.28× slower with them, 174 against 136 ns under load). The
    same torque as :func:`gravity` to rounding (``tests/test_effects.py``); a scene's
    single run and every batch of its samples run the same kernel
    (:func:`gravity_kernel`), so they agree bit for bit.

    Examples
    --------
    The tilted top of :func:`gravity`: m g l sin θ about the body y axis.

    >>> import math
    >>> p = np.array([0.0, 0.0, -2.0 * 9.81, 0.0, 0.0, 0.1])
    >>> tilted = (math.cos(0.25), 0.0, math.sin(0.25), 0.0)
    >>> tau = vertical_gravity(0.0, tilted, (0.0, 0.0, 0.0), p)
    >>> tau[0] == tau[2] == 0.0, math.isclose(tau[1], 2.0 * 9.81 * 0.1 * math.sin(0.5))
    (True, True)
    """
    w0, x, y, z = q[0], q[1], q[2], q[3]
    k = 2.0 * (p[2] * p[5])
    return (-k * (y * z + w0 * x), k * (x * z - w0 * y), 0.0)


@jit
def isotropic_damping(t, q, w, p):
    """τ = −c ω, c = p[0].

    Examples
    --------
    >>> isotropic_damping(0.0, (1.0, 0.0, 0.0, 0.0), (1.0, 2.0, 3.0), np.array([0.5]))
    (-0.5, -1.0, -1.5)
    """
    c = p[0]
    return (-c * w[0], -c * w[1], -c * w[2])


@jit
def damping(t, q, w, p):
    """τ = −C ω with C = p[0:9] row-major (principal frame).

    Examples
    --------
    >>> c = np.diag([1.0, 2.0, 3.0]).ravel()
    >>> damping(0.0, (1.0, 0.0, 0.0, 0.0), (1.0, 2.0, 3.0), c)
    (-1.0, -4.0, -9.0)
    """
    return (
        -(p[0] * w[0] + p[1] * w[1] + p[2] * w[2]),
        -(p[3] * w[0] + p[4] * w[1] + p[5] * w[2]),
        -(p[6] * w[0] + p[7] * w[1] + p[8] * w[2]),
    )


@jit
def body_torque(t, q, w, p):
    """A constant body-frame torque p[0:3].

    Examples
    --------
    Whatever the orientation and ω:

    >>> body_torque(0.0, (0.0, 1.0, 0.0, 0.0), (1.0, 2.0, 3.0), np.array([0.0, 0.0, 1e-3]))
    (0.0, 0.0, 0.001)
    """
    return (p[0], p[1], p[2])


@jit
def space_torque(t, q, w, p):
    """A constant space-frame torque p[0:3], in body components q* τ q.

    Examples
    --------
    A body turned 90° about z feels the space x axis along its own −y:

    >>> import math
    >>> q = (math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4))
    >>> tau = space_torque(0.0, q, (0.0, 0.0, 0.0), np.array([1.0, 0.0, 0.0]))
    >>> [round(c, 12) for c in tau]
    [0.0, -1.0, 0.0]
    """
    return qrotate(qconj(q), (p[0], p[1], p[2]))


# ---------------------------------------------------------------------------- power

#: The built-in kernels, by the index :func:`_built_in_power` evaluates them under.
_BUILT_IN = (gravity, vertical_gravity, isotropic_damping, damping, body_torque, space_torque)


@jit
def _built_in_power(kind, t, q, w, p, out):
    """out[n] += τ·ω of the built-in kernel ``_BUILT_IN[kind]`` at each sample: one
    compiled (and cached) loop for all of them, where a loop taking the kernel as an
    argument would compile anew in every process."""
    for n in range(t.shape[0]):
        qn = (q[n, 0], q[n, 1], q[n, 2], q[n, 3])
        wn = (w[n, 0], w[n, 1], w[n, 2])
        if kind == 0:
            tau = gravity(t[n], qn, wn, p)
        elif kind == 1:
            tau = vertical_gravity(t[n], qn, wn, p)
        elif kind == 2:
            tau = isotropic_damping(t[n], qn, wn, p)
        elif kind == 3:
            tau = damping(t[n], qn, wn, p)
        elif kind == 4:
            tau = body_torque(t[n], qn, wn, p)
        else:
            tau = space_torque(t[n], qn, wn, p)
        out[n] += tau[0] * wn[0] + tau[1] * wn[1] + tau[2] * wn[2]


def _any_power(kernel, t, q, w, p, out):
    """:func:`_built_in_power` for any compiled kernel (a user's), passed as an argument:
    compiled per kernel, not cached (built on first use: ``_power_loop``)."""
    for n in range(t.shape[0]):
        wn = (w[n, 0], w[n, 1], w[n, 2])
        tau = kernel(t[n], (q[n, 0], q[n, 1], q[n, 2], q[n, 3]), wn, p)
        out[n] += tau[0] * wn[0] + tau[1] * wn[1] + tau[2] * wn[2]


_POWER_LOOP: list = []


def torque_power(terms, t, q, w) -> np.ndarray:
    """The power Σ τ·ω of torque ``terms`` (TorqueTerms, as :meth:`Scene.torques` builds
    them) at samples of the principal frame the kernels act in: times ``t`` (n,),
    orientations ``q`` (n, 4) and body rates ``w`` (n, 3). dE/dt of the kinetic energy
    is this power, whatever the torque: the work–energy balance a run's summary states.

    Examples
    --------
    A constant torque of 0.5 N·m about body z on a body spinning at 2 rad/s about it, and
    a damping of 0.1 N·m·s: 0.5·2 − 0.1·2² = 0.6 W.

    >>> from ga_rotors.integrators import TorqueTerm
    >>> terms = [TorqueTerm(body_torque, (0.0, 0.0, 0.5)), TorqueTerm(isotropic_damping, (0.1,))]
    >>> torque_power(terms, [0.0], [[1.0, 0.0, 0.0, 0.0]], [[0.0, 0.0, 2.0]]).tolist()
    [0.6]
    """
    t = np.ascontiguousarray(t, dtype=np.float64)
    q, w = (np.ascontiguousarray(a, dtype=np.float64) for a in (q, w))
    out = np.zeros(t.shape[0])
    for term in terms:
        params = np.asarray(term.params, dtype=np.float64)
        if term.kernel in _BUILT_IN:
            _built_in_power(_BUILT_IN.index(term.kernel), t, q, w, params, out)
        else:
            if not _POWER_LOOP:
                import numba

                _POWER_LOOP.append(numba.njit(nogil=True, error_model="numpy")(_any_power))
            _POWER_LOOP[0](term.kernel, t, q, w, params, out)
    return out


# ---------------------------------------------------------------------------- physics


def inertia_about_pivot(inertia_cm, mass: float, r) -> np.ndarray:
    """Parallel-axis theorem: I_O = I_cm + m (|r|² 1 − r rᵀ), r = pivot → centre of mass.

    Examples
    --------
    A uniform disk (m = 2 kg, R = 0.075 m) on a pivot 0.1 m below its centre, on its axis:

    >>> from ga_rotors import shapes
    >>> np.diag(inertia_about_pivot(np.diag(shapes.disk(2.0, 0.075)), 2.0, [0, 0, 0.1]))
    array([0.0228125, 0.0228125, 0.005625 ])
    """
    r = np.asarray(r, dtype=np.float64)
    with np.errstate(over="ignore", invalid="ignore"):
        out = np.asarray(inertia_cm, dtype=np.float64) + mass * (
            np.dot(r, r) * np.eye(3) - np.outer(r, r)
        )
    if not np.all(np.isfinite(out)):
        raise InputError(
            "the inertia about the pivot, m |r|², overflows float64; rescale units",
            key="pivot_to_com",
        )
    return out


@dataclass(frozen=True)
class Frame:
    """What building a term needs besides its own keys.

    ``principal_rotation`` P takes the principal axes (the integration frame) to the
    user's body axes: a body-frame vector v becomes P* v P. ``mass`` is the body's mass
    (None if not given), ``base_dir`` the scene file's directory (user torques).
    """

    principal_rotation: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
    mass: float | None = None
    base_dir: Path | None = None
    file: str = "<dict>"

    def to_principal(self, v) -> tuple[float, float, float]:
        """Body-frame components in the user's axes -> principal-frame components."""
        out = qrotate(qconj(self.principal_rotation), tuple(float(x) for x in v))
        return tuple(float(x) for x in out)

    def matrix(self) -> np.ndarray:
        """M with v_user = M v_principal."""
        from .matrix import from_quaternion

        return from_quaternion(self.principal_rotation)


# ---------------------------------------------------------------------------- the schema

_REQUIRED = object()


@dataclass(frozen=True)
class Key:
    """One key of an effect table: how it is read, its default, units and meaning.

    Examples
    --------
    >>> g = {k.name: k for k in EFFECTS["gravity"].keys}
    >>> g["pivot_to_com"].required, g["g"].required, g["g"].default
    (True, False, [0.0, 0.0, -9.80665])
    >>> g["g"].doc
    'm/s², space frame'
    """

    name: str
    read: Callable
    default: object = _REQUIRED
    doc: str = ""

    @property
    def required(self) -> bool:
        return self.default is _REQUIRED


@dataclass(frozen=True)
class EffectType:
    """A kind of effect: its keys and how a resolved entry becomes a TorqueTerm.

    :data:`EFFECTS` holds one per ``type`` a scene's ``[[effects]]`` entry may name.

    Examples
    --------
    >>> damping = EFFECTS["damping"]
    >>> damping.doc, [k.name for k in damping.keys]
    ('viscous damping τ = −c ω', ['coefficient'])
    >>> list(EFFECTS)
    ['gravity', 'damping', 'body_torque', 'space_torque', 'user']
    """

    name: str
    doc: str
    keys: tuple[Key, ...]
    build: Callable = field(repr=False)
    #: Whether the torque reads ω; None: the entry's own ``depends_on_omega`` key says.
    depends_on_omega: bool | None = None
    #: ``largest_torque(entry, mass, |ω|)``: a bound on |τ| (N·m) of a resolved entry at a
    #: state turning at |ω|, which a scene checks its first step against; None: unknown
    #: (a user's kernel).
    largest_torque: Callable | None = field(default=None, repr=False)

    def reads_omega(self, entry: dict) -> bool:
        """Whether the torque of a resolved ``entry`` of this type depends on ω.

        Examples
        --------
        >>> EFFECTS["damping"].reads_omega({}), EFFECTS["gravity"].reads_omega({})
        (True, False)
        >>> EFFECTS["user"].reads_omega({"depends_on_omega": False})
        False
        """
        if self.depends_on_omega is None:
            return bool(entry["depends_on_omega"])
        return self.depends_on_omega

    def term(self, entry: dict, frame, reader: Reader, key: str) -> TorqueTerm:
        """The TorqueTerm of a resolved ``entry``, declaring whether it reads ω."""
        built = self.build(entry, frame, reader, key)
        return replace(built, depends_on_omega=self.reads_omega(entry))

    def resolve(self, reader: Reader, entry: dict, key: str) -> dict:
        """Check ``entry``'s keys and fill defaults; ``type`` first."""
        names = ["type", *(k.name for k in self.keys)]
        reader.table(entry, key, names, ["type", *(k.name for k in self.keys if k.required)])
        out = {"type": self.name}
        for k in self.keys:
            value = entry.get(k.name, k.default)
            out[k.name] = k.read(reader, value, join(key, k.name))
        return out


def _vector(reader, value, key):
    return list(reader.vector(value, key))


def _gravity_vector(reader, value, key):
    g = _vector(reader, value, key)
    if not any(g):
        raise reader.error(key, "expected a nonzero vector (m/s²); without gravity, omit it")
    return g


def _coefficient(reader, value, key):
    if isinstance(value, list | tuple):
        values = reader.vector(value, key)
        return [reader.number(v, join(key, i), nonnegative=True) for i, v in enumerate(values)]
    return reader.number(value, key, nonnegative=True, unit="N·m·s")


def _norm(v) -> float:
    """|v| of a few numbers, inf when it overflows (no floating-point warning)."""
    try:
        return math.hypot(*v)
    except OverflowError:
        return math.inf


def _gravity_bound(entry, mass, w):
    return mass * _norm(entry["g"]) * _norm(entry["pivot_to_com"])


def _damping_bound(entry, mass, w):
    c = entry["coefficient"]
    return (max(c) if isinstance(c, list) else c) * w


def _constant_bound(entry, mass, w):
    return _norm(entry["torque"])


def _inertia_about(reader, value, key):
    return reader.string(value, key, ("com", "pivot"))


_NAME = re.compile(r"^[A-Za-z_]\w*(\.[A-Za-z_]\w*)*:[A-Za-z_]\w*$")


def _function(reader, value, key):
    text = reader.string(value, key)
    if not _NAME.match(text):
        raise reader.error(
            key, f"expected 'package.module:function' (an importable name), got {text!r}"
        )
    return text


def _params(reader, value, key):
    return list(reader.numbers(value, key))


def _boolean(reader, value, key):
    return reader.boolean(value, key)


def _build_gravity(entry: dict, frame: Frame, reader: Reader, key: str) -> TorqueTerm:
    if frame.mass is None:
        raise reader.error("body.mass", f"missing; the gravity effect ({key}) needs the mass")
    weight = [frame.mass * g for g in entry["g"]]
    r = frame.to_principal(entry["pivot_to_com"])
    params = (*weight, *r)
    return TorqueTerm(gravity_kernel(params), params, name="gravity")


def gravity_kernel(params):
    """The kernel a gravity term with these parameters (m g, r) runs: :func:`vertical_gravity`
    when the weight is along space z and the lever along body z, else :func:`gravity`.

    Examples
    --------
    >>> gravity_kernel((0.0, 0.0, -9.8, 0.0, 0.0, 0.1)).__name__
    'vertical_gravity'
    >>> gravity_kernel((0.0, 0.0, -9.8, 0.01, 0.0, 0.1)).__name__
    'gravity'
    """
    f0, f1, _, r0, r1, _ = params
    return vertical_gravity if f0 == f1 == r0 == r1 == 0.0 else gravity


def _build_damping(entry: dict, frame: Frame, reader: Reader, key: str) -> TorqueTerm:
    c = entry["coefficient"]
    if not isinstance(c, list):
        return TorqueTerm(isotropic_damping, (c,), name="damping")
    m = frame.matrix()
    return TorqueTerm(damping, tuple((m.T @ np.diag(c) @ m).ravel()), name="damping")


def _build_body_torque(entry: dict, frame: Frame, reader: Reader, key: str) -> TorqueTerm:
    return TorqueTerm(body_torque, frame.to_principal(entry["torque"]), name="body_torque")


def _build_space_torque(entry: dict, frame: Frame, reader: Reader, key: str) -> TorqueTerm:
    return TorqueTerm(space_torque, tuple(entry["torque"]), name="space_torque")


def _build_user(entry: dict, frame: Frame, reader: Reader, key: str) -> TorqueTerm:
    kernel = load_user_kernel(entry["function"], reader, join(key, "function"))
    params = tuple(entry["params"])
    try:
        term = TorqueTerm(kernel, params, name=entry["function"].rpartition(":")[2])
    except InputError as exc:
        raise reader.error(join(key, "function"), str(exc)) from None
    _trial_call(kernel, params, reader, join(key, "function"))
    return term


_DEPENDS_ON_OMEGA = (
    "whether the kernel reads w; false lets splitting and variational methods (which "
    "integrate torques of orientation and time only) take it at their full order"
)

_INERTIA_ABOUT = (
    '"com": the body\'s inertia is about its centre of mass (shifted to the pivot); '
    '"pivot": already about the pivot'
)

#: type name -> EffectType, in the order the docs list them (:func:`register` adds one).
EFFECTS: dict[str, EffectType] = {
    e.name: e
    for e in (
        EffectType(
            "gravity",
            "weight acting at the centre of mass, the body turning about a fixed pivot",
            (
                Key("pivot_to_com", _vector, doc="m, body frame: pivot to centre of mass"),
                Key("g", _gravity_vector, [0.0, 0.0, -STANDARD_GRAVITY], "m/s², space frame"),
                Key("inertia_about", _inertia_about, "com", _INERTIA_ABOUT),
            ),
            _build_gravity,
            depends_on_omega=False,
            largest_torque=_gravity_bound,
        ),
        EffectType(
            "damping",
            "viscous damping τ = −c ω",
            (Key("coefficient", _coefficient, doc="N·m·s: one number or three (per axis)"),),
            _build_damping,
            depends_on_omega=True,
            largest_torque=_damping_bound,
        ),
        EffectType(
            "body_torque",
            "a constant torque fixed in the body",
            (Key("torque", _vector, doc="N·m, body frame"),),
            _build_body_torque,
            depends_on_omega=False,
            largest_torque=_constant_bound,
        ),
        EffectType(
            "space_torque",
            "a constant torque fixed in space",
            (Key("torque", _vector, doc="N·m, space frame"),),
            _build_space_torque,
            depends_on_omega=False,
            largest_torque=_constant_bound,
        ),
        EffectType(
            "user",
            "a compiled kernel(t, q, w, p) named package.module:function",
            (
                Key("function", _function, doc='"package.module:function", compiled'),
                Key("params", _params, [], "numbers passed to the kernel as p"),
                Key("depends_on_omega", _boolean, True, _DEPENDS_ON_OMEGA),
            ),
            _build_user,
        ),
    )
}


def listed(names) -> str:
    """Effect (or torque) names for a message: each once, in order, with how many times it
    appears, so a line stays short whatever the scene declares.

    Examples
    --------
    >>> listed(["gravity", "body_torque", "body_torque", "damping", "body_torque"])
    'gravity, body_torque ×3, damping'
    >>> listed([])
    ''
    """
    from collections import Counter

    counts = Counter(names)
    return ", ".join(n if counts[n] == 1 else f"{n} ×{counts[n]}" for n in counts)


def register(effect: EffectType) -> EffectType:
    """Add an effect type that scenes may declare (``type = effect.name``); return it.

    Names are unique: registering the same object again changes nothing, another under a
    taken name is refused. See ``docs/extending.md``.

    Examples
    --------
    >>> register(EFFECTS["damping"]) is EFFECTS["damping"]
    True
    >>> register(EffectType("damping", "mine", (), _build_damping))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: register: an effect named 'damping' already exists
    """
    if not isinstance(effect, EffectType):
        raise InputError(f"expected an EffectType, got {effect!r}", key="register")
    existing = EFFECTS.get(effect.name)
    if existing is not None and existing is not effect:
        raise InputError(f"an effect named {effect.name!r} already exists", key="register")
    EFFECTS[effect.name] = effect
    return effect


# ---------------------------------------------------------------------------- user torques


def load_user_kernel(spec: str, reader: Reader, key: str):
    """Import ``"package.module:function"`` and check it is a compiled 4-argument kernel.

    Only with the user's opt-in and only from the folders named there
    (:mod:`ga_rotors.trust`); ``ga_rotors`` itself counts as such a folder nowhere.

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.mkdtemp()
    >>> with open(os.path.join(folder, "my_torques_doc.py"), "w") as f:
    ...     print("import math", "from ga_rotors.effects import body_torque", sep=";", file=f)
    >>> load_user_kernel("my_torques_doc:body_torque", Reader("x.toml"), "k")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: x.toml: k: the scene asks to run code (my_torques_doc:...
    >>> from ga_rotors.trust import allow_user_code
    >>> with allow_user_code(folder):
    ...     load_user_kernel("my_torques_doc:body_torque", Reader("x.toml"), "k").__name__
    'body_torque'
    >>> with allow_user_code(folder):
    ...     load_user_kernel("my_torques_doc:math", Reader("x.toml"), "effects[0].function")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: x.toml: effects[0].function: my_torques_doc:math is module; ...
    """
    module, _, name = spec.partition(":")
    try:
        mod = import_user_module(module, spec)
    except InputError as exc:
        raise reader.error(key, str(exc)) from None
    except Exception as exc:  # any failure to import is the scene's problem, reported as such
        raise reader.error(
            key, f"cannot import module {module!r}: {type(exc).__name__}: {exc}"
        ) from None
    try:
        kernel = getattr(mod, name)
    except AttributeError:
        raise reader.error(key, f"module {module!r} has no attribute {name!r}") from None
    from numba.core.dispatcher import Dispatcher

    if not isinstance(kernel, Dispatcher):
        kind = "a plain Python function" if callable(kernel) else type(kernel).__name__
        raise reader.error(
            key,
            f"{spec} is {kind}; expected a numba-compiled kernel(t, q, w, p) returning a "
            "3-tuple: decorate it with @numba.njit(cache=True)",
        )
    args = kernel.py_func.__code__.co_argcount
    if args != 4:
        raise reader.error(key, f"{spec} takes {args} arguments; expected kernel(t, q, w, p)")
    return kernel


def _trial_call(kernel, params, reader: Reader, key: str) -> None:
    spec = f"{kernel.py_func.__module__}:{kernel.py_func.__name__}"
    try:
        out = kernel.py_func(0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0), np.array(params))
    except Exception as exc:  # the user's code: report what it raised, where
        raise reader.error(
            key, f"{spec}(t=0, q=(1,0,0,0), w=(0,0,0), p) raised {type(exc).__name__}: {exc}"
        ) from None
    try:
        values = [float(v) for v in out]
    except (TypeError, ValueError):
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise reader.error(
            key, f"{spec} must return three finite numbers (a body-frame torque), got {out!r}"
        )
