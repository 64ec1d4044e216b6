r"""Forces on a body moving through space, each a compiled kernel and its parameters.

A :class:`~ga_rotors.integrators.ForceTerm` is what a whole rigid motion
(:func:`ga_rotors.simulate` with ``position=``) declares beside its torques; the code
generator writes a loop whose ``wrench`` is the sum of exactly the declared kernels, as
it does for torques (:mod:`ga_rotors.effects`). The wrench contract, once for every path
(``docs/conventions.md`` §11): a kernel ``kernel(t, q, c, w, v, p)`` receives the
orientation q (principal frame to space), the centre of mass c and its velocity v in
space, the body angular velocity w (principal frame) and its parameters p, and returns the
force F in space components and the torque τ about the centre of mass in principal body
components, six numbers.

=============== ================================================ ======================
builder         force F (space), torque τ about the centre        conserves
=============== ================================================ ======================
uniform_gravity F = m g at the centre of mass, τ = 0               energy (V = −m g·c),
                                                                   spin
spring          F = k (|d| − ℓ₀) d/|d|, d = a − x from the body    energy, angular
                point x to the anchor a; τ = r × q*Fq              momentum about a
point_force     a constant force at a body point, fixed in space   fixed in space: energy
                (τ = r × q*Fq) or in the body (F = q F_b q*,      (V = −F·x); spin when
                τ = r × F_b)                                       r = 0
linear_drag     F = −b v_c at the centre of mass, τ = 0            spin
central_gravity a planet's field μ/r² on the extended body (to       energy, angular
                its quadrupole: the gravity-gradient torque and     momentum about the
                the force that goes with it)                        planet's centre
=============== ================================================ ======================

Each builder takes the :class:`~ga_rotors.body.RigidBody` (its mass, its centre of mass,
its principal axes): body points are given in the body frame the user wrote the body in,
from its origin, and carried here to the principal frame about the centre of mass that
the kernels read. ``conserves`` says what a body under that force alone keeps (what an
exact check can hold a run to); ``potential`` is the energy of a conservative force,
compiled, ``potential(q, c, p) -> V``.

The kernels are internal (not in ``__all__``): compiled, unchecked, called from the
generated loops with parameters the builders made.
"""

from __future__ import annotations

import math

from ._jit import jit
from ._kernels import cross, qconj, qrotate
from ._validate import as_float_array
from .errors import InputError
from .integrators.problem import ForceTerm

__all__ = [
    "EARTH_MU",
    "STANDARD_GRAVITY",
    "central_gravity",
    "linear_drag",
    "point_force",
    "spring",
    "uniform_gravity",
    "user_force",
]

#: m/s², the default gravity (0, 0, −STANDARD_GRAVITY), space frame, z up.
STANDARD_GRAVITY = 9.80665
#: m³/s², the Earth's gravitational parameter G M (IERS 2010 conventions, with its
#: atmosphere), the default of :func:`central_gravity`.
EARTH_MU = 3.986004418e14


# ---------------------------------------------------------------------------- kernels


@jit
def weight(t, q, c, w, v, p):
    """F = m g = p[0:3] at the centre of mass; no torque about it.

    Examples
    --------
    >>> weight(0.0, (1.0, 0.0, 0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (0.0,) * 3, (0.0, 0.0, -9.8))
    (0.0, 0.0, -9.8, 0.0, 0.0, 0.0)
    """
    return (p[0], p[1], p[2], 0.0, 0.0, 0.0)


@jit
def weight_potential(q, c, p):
    """V = −m g·c."""
    return -(p[0] * c[0] + p[1] * c[1] + p[2] * c[2])


@jit
def _body_point(q, c, p, k):
    """The lever q r q* of the body point r = p[k:k+3] (from the centre of mass, principal
    frame) and the point's position c + q r q*."""
    lever = qrotate(q, (p[k], p[k + 1], p[k + 2]))
    return lever, (c[0] + lever[0], c[1] + lever[1], c[2] + lever[2])


@jit
def _at_point(q, p, k, f):
    """(F, τ) of the space force f applied at the body point r = p[k:k+3]: τ = r × q* f q."""
    tau = cross((p[k], p[k + 1], p[k + 2]), qrotate(qconj(q), f))
    return (f[0], f[1], f[2], tau[0], tau[1], tau[2])


@jit
def spring_force(t, q, c, w, v, p):
    """A spring of stiffness k = p[0] and rest length ℓ₀ = p[1] from the body point
    r = p[5:8] to the anchor a = p[2:5] (space): F = k (|d| − ℓ₀) d/|d|, d = a − x.

    With ℓ₀ = 0 no division: F = k d (a zero-length spring is linear in d, and defined
    at d = 0); with ℓ₀ > 0 a spring squeezed to a point has no direction and no force.

    Examples
    --------
    A spring of 10 N/m from the centre of mass at the origin to (0, 0, 1):

    >>> p = (10.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
    >>> spring_force(0.0, (1.0, 0.0, 0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (0.0,) * 3, p)
    (0.0, 0.0, 10.0, 0.0, 0.0, 0.0)
    """
    _, x = _body_point(q, c, p, 5)
    d = (p[2] - x[0], p[3] - x[1], p[4] - x[2])
    k = p[0]
    if p[1] != 0.0:
        n = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        k = k * (1.0 - p[1] / n) if n > 0.0 else 0.0
    return _at_point(q, p, 5, (k * d[0], k * d[1], k * d[2]))


@jit
def spring_potential(q, c, p):
    """V = ½ k (|d| − ℓ₀)²."""
    _, x = _body_point(q, c, p, 5)
    d = (p[2] - x[0], p[3] - x[1], p[4] - x[2])
    squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    if p[1] == 0.0:  # ½ k |d|², as F = k d: no square root
        return 0.5 * p[0] * squared
    stretch = math.sqrt(squared) - p[1]
    return 0.5 * p[0] * stretch * stretch


@jit
def space_force(t, q, c, w, v, p):
    """A constant force F = p[0:3] fixed in space, at the body point r = p[3:6].

    Examples
    --------
    1 N along space x at a point 1 m up the body z axis: a torque about body y.

    >>> p = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    >>> space_force(0.0, (1.0, 0.0, 0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (0.0,) * 3, p)
    (1.0, 0.0, 0.0, 0.0, 1.0, 0.0)
    """
    return _at_point(q, p, 3, (p[0], p[1], p[2]))


@jit
def space_force_potential(q, c, p):
    """V = −F·x, x = c + q r q* the point where it acts."""
    _, x = _body_point(q, c, p, 3)
    return -(p[0] * x[0] + p[1] * x[1] + p[2] * x[2])


@jit
def body_force(t, q, c, w, v, p):
    """A constant force F_b = p[0:3] fixed in the body (principal frame), at the body point
    r = p[3:6]: F = q F_b q*, τ = r × F_b (a thrust).

    Examples
    --------
    A thrust of 2 N along the body x axis of a body turned 90° about z: along space y.

    >>> import math
    >>> q = (math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4))
    >>> f = body_force(0.0, q, (0.0,) * 3, (0.0,) * 3, (0.0,) * 3, (2.0,) + (0.0,) * 5)
    >>> [round(x, 12) for x in f]
    [0.0, 2.0, 0.0, 0.0, 0.0, 0.0]
    """
    f = qrotate(q, (p[0], p[1], p[2]))
    tau = cross((p[3], p[4], p[5]), (p[0], p[1], p[2]))
    return (f[0], f[1], f[2], tau[0], tau[1], tau[2])


@jit
def drag_force(t, q, c, w, v, p):
    """Linear drag F = −b v_c at the centre of mass, b = p[0] (N·s/m).

    Examples
    --------
    >>> drag_force(0.0, (1.0, 0.0, 0.0, 0.0), (0.0,) * 3, (0.0,) * 3, (1.0, 2.0, 3.0), (0.5,))
    (-0.5, -1.0, -1.5, 0.0, 0.0, 0.0)
    """
    b = p[0]
    return (-b * v[0], -b * v[1], -b * v[2], 0.0, 0.0, 0.0)


@jit
def _field_parts(q, c, p):
    """What the central field needs, in principal body components: r_b (the centre of
    mass from the planet's centre p[5:8]), I r_b, |r|² and r_b·I r_b."""
    rb = qrotate(qconj(q), (c[0] - p[5], c[1] - p[6], c[2] - p[7]))
    irb = (p[2] * rb[0], p[3] * rb[1], p[4] * rb[2])
    d2 = rb[0] * rb[0] + rb[1] * rb[1] + rb[2] * rb[2]
    return rb, irb, d2, rb[0] * irb[0] + rb[1] * irb[1] + rb[2] * irb[2]


@jit
def central_field(t, q, c, w, v, p):
    r"""The field of a point mass (μ = p[0]) at p[5:8] on a body of mass m = p[1] and
    principal moments p[2:5], to the body's quadrupole (MacCullagh): the point-mass force
    :math:`-\mu m\, r/d^3`, the gravity-gradient torque
    :math:`\tfrac{3\mu}{d^5}\, r_b \times \mathsf I r_b` and its force
    :math:`-\tfrac{3\mu}{2 d^5}\bigl((\operatorname{tr}\mathsf I) r + 2\,\mathsf I r
    - 5\,\tfrac{r\cdot\mathsf I r}{d^2}\, r\bigr)`, r from the planet to the centre of mass.

    Examples
    --------
    A sphere (no gradient torque) 7000 km from the Earth's centre: its weight there.

    >>> p = (EARTH_MU, 100.0, 10.0, 10.0, 10.0, 0.0, 0.0, 0.0)
    >>> f = central_field(0.0, (1.0, 0.0, 0.0, 0.0), (7.0e6, 0.0, 0.0), (0.0,) * 3,
    ...                   (0.0,) * 3, p)
    >>> round(-f[0] / 100.0, 6), f[3:]
    (8.134703, (0.0, 0.0, 0.0))
    """
    rb, irb, d2, rir = _field_parts(q, c, p)
    d = math.sqrt(d2)
    mu = p[0]
    k = 3.0 * mu / (d2 * d2 * d)
    tau = cross(rb, irb)
    trace = p[2] + p[3] + p[4]
    g = -0.5 * k
    five = 5.0 * rir / d2
    f2 = qrotate(q, (g * ((trace - five) * rb[0] + 2.0 * irb[0]),
                     g * ((trace - five) * rb[1] + 2.0 * irb[1]),
                     g * ((trace - five) * rb[2] + 2.0 * irb[2])))  # fmt: skip
    point = -mu * p[1] / (d2 * d)
    r = (c[0] - p[5], c[1] - p[6], c[2] - p[7])
    return (point * r[0] + f2[0], point * r[1] + f2[1], point * r[2] + f2[2],
            k * tau[0], k * tau[1], k * tau[2])  # fmt: skip


@jit
def central_potential(q, c, p):
    """V = −μ m/d − μ/(2 d³) (tr I − 3 r̂·I r̂) (MacCullagh's formula)."""
    _, _, d2, rir = _field_parts(q, c, p)
    d = math.sqrt(d2)
    return -p[0] * p[1] / d - 0.5 * p[0] / (d2 * d) * (p[2] + p[3] + p[4] - 3.0 * rir / d2)


# ---------------------------------------------------------------------------- builders


def _moving(body, what: str):
    """``body`` as a RigidBody with a mass, or InputError naming ``what``."""
    from .body import RigidBody

    if not isinstance(body, RigidBody):
        raise InputError(f"{what}: expected the RigidBody it acts on, got {body!r:.60}",
                         key="body")  # fmt: skip
    if body.mass is None:
        raise InputError(f"{what} acts on a body with a mass: give RigidBody(mass=...)",
                         key="body.mass")  # fmt: skip
    return body


def _vector(value, key: str) -> tuple[float, float, float]:
    v = as_float_array(value, key, last=3)
    if v.shape != (3,):
        raise InputError(f"expected one vector of shape (3,), got shape {v.shape}", key=key)
    return tuple(float(x) for x in v)


def _number(value, key: str, *, positive: bool = False) -> float:
    v = as_float_array(value, key)
    if v.shape != () or not (v > 0.0 if positive else v >= 0.0):
        need = "a positive" if positive else "a non-negative"
        raise InputError(f"expected {need} number, got {value!r:.40}", key=key)
    return float(v)


def uniform_gravity(body, g=(0.0, 0.0, -STANDARD_GRAVITY)) -> ForceTerm:
    """The weight m g of ``body`` at its centre of mass, g in space (m/s²).

    Conserves the energy ½ m v_c² + ½ ω·Iω − m g·c and the spin (the angular momentum
    about the centre of mass, which the weight does not turn).

    Examples
    --------
    >>> from ga_rotors import RigidBody
    >>> term = uniform_gravity(RigidBody((1.0, 2.0, 2.5), mass=2.0), g=(0.0, 0.0, -10.0))
    >>> term.params, sorted(term.conserves)
    ((0.0, 0.0, -20.0), ['energy', 'spin'])
    """
    body = _moving(body, "uniform_gravity")
    weight_vector = tuple(body.mass * x for x in _vector(g, "g"))
    return ForceTerm(weight, weight_vector, name="uniform_gravity", depends_on_velocity=False,
                     conserves={"energy", "spin"}, potential=weight_potential)  # fmt: skip


def spring(body, stiffness, anchor, at=(0.0, 0.0, 0.0), rest_length=0.0) -> ForceTerm:
    """A spring of ``stiffness`` (N/m) and ``rest_length`` (m) from the body point ``at``
    (body frame, from the body-frame origin; m) to the space point ``anchor`` (m).

    The force's line passes through the anchor: it conserves the energy (½ k stretch²
    the potential) and the angular momentum about the anchor; attached at the centre of
    mass, the spin too. A zero-length spring at the centre of mass is the exact
    reference :class:`ga_rotors.reference.rigid_motion.SpringAtCentreOfMass`.

    Examples
    --------
    >>> from ga_rotors import RigidBody
    >>> body = RigidBody((1.0, 2.0, 2.5), mass=2.0, centre_of_mass=(0.0, 0.0, 0.5))
    >>> term = spring(body, 8.0, [0.0, 0.0, 1.0], at=(0.0, 0.0, 0.5))   # at the centre
    >>> term.params, sorted(term.conserves), term.point
    ((8.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0), ['angular_momentum', 'energy', 'spin'], (0.0, 0.0, 1.0))
    """  # noqa: E501
    body = _moving(body, "spring")
    k = _number(stiffness, "stiffness", positive=True)
    rest = _number(rest_length, "rest_length")
    a = _vector(anchor, "anchor")
    r = body.body_point(_vector(at, "at"))
    conserves = {"energy", "angular_momentum"} | ({"spin"} if r == (0.0, 0.0, 0.0) else set())
    return ForceTerm(spring_force, (k, rest, *a, *r), name="spring", depends_on_velocity=False,
                     conserves=conserves, potential=spring_potential, point=a)  # fmt: skip


def point_force(body, force, at=(0.0, 0.0, 0.0), fixed_in: str = "space") -> ForceTerm:
    """A constant ``force`` (N) at the body point ``at`` (body frame, from the body-frame
    origin; m), fixed in ``"space"`` (its components are space components: a steady
    pull) or in the ``"body"`` (body components, turning with it: a thrust).

    A force fixed in space is conservative (V = −F·x, x where it acts); either kind
    applied at the centre of mass leaves the spin alone.

    Examples
    --------
    >>> from ga_rotors import RigidBody
    >>> body = RigidBody((1.0, 2.0, 2.5), mass=2.0)
    >>> sorted(point_force(body, [1.0, 0.0, 0.0], at=(0.0, 0.0, 0.2)).conserves)
    ['energy']
    >>> point_force(body, [1.0, 0.0, 0.0], fixed_in="body").conserves
    frozenset({'spin'})
    """
    body = _moving(body, "point_force")
    f = _vector(force, "force")
    r = body.body_point(_vector(at, "at"))
    spin = {"spin"} if r == (0.0, 0.0, 0.0) else set()
    if fixed_in == "space":
        return ForceTerm(space_force, (*f, *r), name="space_force", depends_on_velocity=False,
                         conserves={"energy"} | spin, potential=space_force_potential)  # fmt: skip
    if fixed_in == "body":
        f_body = body.to_principal_axes(f)
        return ForceTerm(body_force, (*f_body, *r), name="body_force", depends_on_velocity=False,
                         conserves=spin)  # fmt: skip
    raise InputError(f"expected 'space' or 'body', got {fixed_in!r:.40}", key="fixed_in")


def linear_drag(body, coefficient) -> ForceTerm:
    """Linear drag F = −b v_c at the centre of mass, b = ``coefficient`` (N·s/m).

    It dissipates energy and leaves the spin alone; it reads the velocity, so the
    splitting methods (forces of pose and time only) refuse it unless the problem accepts
    their lower order.

    Examples
    --------
    >>> from ga_rotors import RigidBody
    >>> term = linear_drag(RigidBody((1.0, 2.0, 2.5), mass=2.0), 0.1)
    >>> term.params, term.depends_on_velocity, sorted(term.conserves)
    ((0.1,), True, ['spin'])
    """
    _moving(body, "linear_drag")
    b = _number(coefficient, "coefficient")
    return ForceTerm(drag_force, (b,), name="linear_drag", depends_on_velocity=True,
                     conserves={"spin"})  # fmt: skip


def central_gravity(body, mu=EARTH_MU, centre=(0.0, 0.0, 0.0)) -> ForceTerm:
    """The gravity of a planet of gravitational parameter ``mu`` (m³/s²) at the space point
    ``centre`` on ``body``, to the body's quadrupole: its orbit and the gravity-gradient
    torque that turns it on the orbit, together (a satellite's attitude and orbit).

    The field is central and the body's potential in it (MacCullagh's formula, the
    ``potential``) the exact one of the truncated field, so the energy and the angular
    momentum about the planet's centre (orbit and spin together) are kept.

    Examples
    --------
    >>> from ga_rotors import RigidBody
    >>> term = central_gravity(RigidBody((10.0, 12.0, 8.0), mass=100.0))
    >>> term.params[:5], sorted(term.conserves), term.point
    ((398600441800000.0, 100.0, 10.0, 12.0, 8.0), ['angular_momentum', 'energy'], (0.0, 0.0, 0.0))
    """
    body = _moving(body, "central_gravity")
    mu = _number(mu, "mu", positive=True)
    a = _vector(centre, "centre")
    return ForceTerm(central_field, (mu, body.mass, *body.moments, *a), name="central_gravity",
                     depends_on_velocity=False, conserves={"energy", "angular_momentum"},
                     potential=central_potential, point=a)  # fmt: skip


# ---------------------------------------------------------------------------- user forces


def user_force(spec: str, params=(), *, depends_on_velocity: bool = True) -> ForceTerm:
    """The ForceTerm of a user's compiled kernel named ``"package.module:function"``.

    The kernel follows the wrench contract of the built-in ones,
    ``kernel(t, q, c, w, v, p) -> (Fx, Fy, Fz, τ1, τ2, τ3)`` (see the module's text),
    compiled with ``@numba.njit`` (ideally ``cache=True``). Its module is code: it is
    imported only on the user's opt-in and only from the folders named there
    (:mod:`ga_rotors.trust`), exactly as a user torque is. Before use the kernel's Python
    version is called once at rest (t = 0, q = 1, c = v = w = 0, p) and must return six
    finite numbers. A user force declares nothing it conserves: the balances of a run
    under it integrate its work, impulse and moment.

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.mkdtemp()
    >>> with open(os.path.join(folder, "my_forces_doc.py"), "w") as f:
    ...     print("from ga_rotors.forces import drag_force as drag", file=f)
    >>> user_force("my_forces_doc:drag", (0.5,))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: the scene asks to run code (my_forces_doc:drag); scenes ...
    >>> from ga_rotors.trust import allow_user_code
    >>> with allow_user_code(folder):
    ...     term = user_force("my_forces_doc:drag", (0.5,))
    >>> term.name, term.params, term.conserves
    ('drag', (0.5,), frozenset())
    """
    from .trust import import_user_module

    module, _, name = str(spec).partition(":")
    try:
        mod = import_user_module(module, spec)
    except InputError:
        raise
    except Exception as exc:  # any failure to import is the caller's input, reported so
        raise InputError(f"cannot import module {module!r}: {type(exc).__name__}: {exc}",
                         key="function") from None  # fmt: skip
    kernel = getattr(mod, name, None)
    if kernel is None:
        raise InputError(f"module {module!r} has no attribute {name!r}", key="function")
    from numba.core.dispatcher import Dispatcher

    if not isinstance(kernel, Dispatcher):
        kind = "a plain Python function" if callable(kernel) else type(kernel).__name__
        raise InputError(f"{spec} is {kind}; expected a numba-compiled kernel(t, q, c, w, v, "
                         "p) returning six numbers: decorate it with @numba.njit(cache=True)",
                         key="function")  # fmt: skip
    args = kernel.py_func.__code__.co_argcount
    if args != 6:
        raise InputError(f"{spec} takes {args} arguments; expected kernel(t, q, c, w, v, p)",
                         key="function")  # fmt: skip
    params = tuple(float(x) for x in params)
    _trial_force(kernel, spec, params)
    return ForceTerm(kernel, params, name=name, depends_on_velocity=bool(depends_on_velocity))


def _trial_force(kernel, spec: str, params: tuple) -> None:
    import numpy as np

    zero = (0.0, 0.0, 0.0)
    try:
        out = kernel.py_func(0.0, (1.0, 0.0, 0.0, 0.0), zero, zero, zero, np.array(params))
    except Exception as exc:  # the user's code: report what it raised, where
        raise InputError(f"{spec}(t=0, q=(1,0,0,0), c=v=w=0, p) raised {type(exc).__name__}: "
                         f"{exc}", key="function") from None  # fmt: skip
    try:
        values = [float(x) for x in out]
    except (TypeError, ValueError):
        values = []
    if len(values) != 6 or not all(math.isfinite(x) for x in values):
        raise InputError(f"{spec} must return six finite numbers (a force in space, a torque "
                         f"in the body), got {out!r:.80}", key="function")  # fmt: skip
