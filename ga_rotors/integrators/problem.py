"""What is integrated: a body's moments with its declared torques, or a prescribed ω(t).

A :class:`Problem` is immutable, and what an integrator derives from it (its checks, its
compiled loop, the packed parameters) is remembered on it (:meth:`Problem.derived`);
:func:`problem_for` shares one problem between the calls that repeat the same moments and
torques. Torque and ω kernels are compiled functions defined at module level of an
importable module, so the generated loops can import them by name
(:mod:`ga_rotors.integrators._source`). A :class:`Batch` is many bodies with one problem's
torques, each with its own moments and torque parameters, run at once.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = [
    "FREE",
    "KINEMATIC",
    "MOTION",
    "TORQUED",
    "Batch",
    "ForceTerm",
    "PrescribedOmega",
    "Problem",
    "TorqueTerm",
    "problem_for",
]

FREE = "free"
TORQUED = "torqued"
KINEMATIC = "kinematic"
#: Whole rigid motion: rotation and translation of a body with a mass (ga_rotors.paths.motor
#: and the quaternion path's pose variant, ga_rotors.paths.pose).
MOTION = "motion"


def _kernel_location(kernel, what: str) -> tuple[str, str]:
    """(module, name) under which ``kernel`` can be imported, or InputError."""
    func = getattr(kernel, "py_func", kernel)
    module, name = getattr(func, "__module__", None), getattr(func, "__qualname__", "")
    if not callable(kernel) or not module or not name or "." in name or "<" in name:
        raise InputError(
            f"{what}: expected a compiled kernel defined at module level of an importable "
            f"module, got {kernel!r}"
        )
    try:
        found = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError):
        found = None
    if found is not kernel:
        raise InputError(f"{what}: {module}.{name} does not import as the kernel given")
    return module, name


def _check_kernel(term, what: str, arity: int, signature: str) -> None:
    """Check that ``term.kernel`` imports as itself and takes ``arity`` arguments, and
    name ``term`` after it unless it has a name (the one rule of every kernel term)."""
    location = _kernel_location(term.kernel, f"{what} {term.name}" if term.name else what)
    if not term.name:
        object.__setattr__(term, "name", location[1])
    if _arity(term.kernel) not in (None, arity):
        raise InputError(
            f"{what} {term.name}: expected signature {signature}, "
            f"got {_arity(term.kernel)} parameters"
        )


def _params(values, what: str) -> tuple[float, ...]:
    arr = np.asarray(values, dtype=np.float64).reshape(-1)
    if not np.isfinite(arr).all():
        raise InputError(f"{what}: parameters must be finite, got {tuple(arr)}")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class TorqueTerm:
    """One declared torque: ``kernel(t, q, w, p) -> body-frame torque`` and its parameters.

    ``depends_on_omega`` says whether the torque reads ``w``. The default, True, is the
    safe one for a kernel nobody has vouched for; declare False for a torque of
    orientation and time only (gravity, a constant body or space torque), which the
    splitting and variational methods integrate at their full order.

    Examples
    --------
    >>> from ga_rotors._kernels import cross
    >>> TorqueTerm(cross, (1.0, 2.0))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: ...
    """

    kernel: Callable
    params: tuple[float, ...] = ()
    name: str = ""
    depends_on_omega: bool = True

    def __post_init__(self):
        object.__setattr__(self, "params", _params(self.params, "torque params"))
        if not isinstance(self.depends_on_omega, bool):
            raise InputError(
                f"depends_on_omega: expected True or False, got {self.depends_on_omega!r}"
            )
        _check_kernel(self, "torque kernel", 4, "kernel(t, q, w, p)")

    @property
    def location(self) -> tuple[str, str]:
        return _kernel_location(self.kernel, "torque kernel")


@dataclass(frozen=True)
class ForceTerm:
    """One declared force (with its torque): ``kernel(t, q, c, w, v, p) -> (F, τ)``.

    The wrench contract, the same for every path (``docs/conventions.md`` §11): the kernel
    receives the body's orientation ``q`` (principal frame to space, unit quaternion), the
    position ``c`` and velocity ``v`` of its centre of mass in space, the body angular
    velocity ``w`` (principal frame) and ``p``, a float64 view of this term's parameters;
    it returns six numbers, the force F in space components (N) and the torque τ about the
    centre of mass in principal body components (N·m). A motor path turns them into the
    force line of the body frame; the quaternion path uses them as they are.

    ``depends_on_velocity`` says whether the kernel reads ``w`` or ``v`` (True, the safe
    default for a kernel nobody has vouched for): the splitting methods take only forces
    of pose and time at their order. ``conserves`` names what a body under this force
    alone keeps (see :data:`CONSERVED`); ``potential``, for a force that conserves energy,
    is a compiled ``potential(q, c, p) -> V`` (J) with F = −∂V/∂c (and the torque its
    rotational part), so that kinetic energy plus V is constant.

    Examples
    --------
    >>> from ga_rotors import RigidBody
    >>> from ga_rotors.forces import uniform_gravity
    >>> term = uniform_gravity(RigidBody((1.0, 2.0, 2.0), mass=2.0))
    >>> term.name, term.params, sorted(term.conserves), term.depends_on_velocity
    ('uniform_gravity', (0.0, 0.0, -19.6133), ['energy', 'spin'], False)
    >>> ForceTerm(term.kernel, (1.0,), conserves={"momentum"})
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: conserves: unknown quantity 'momentum'; expected some of angular_momentum, energy, linear_momentum, spin
    """  # noqa: E501

    kernel: Callable
    params: tuple[float, ...] = ()
    name: str = ""
    depends_on_velocity: bool = True
    conserves: frozenset[str] = frozenset()
    potential: Callable | None = None
    #: the space point about which it conserves ``angular_momentum`` (a spring's anchor)
    point: tuple[float, float, float] | None = None

    def __post_init__(self):
        object.__setattr__(self, "params", _params(self.params, "force params"))
        if not isinstance(self.depends_on_velocity, bool):
            raise InputError(
                f"expected True or False, got {self.depends_on_velocity!r}",
                key="depends_on_velocity",
            )
        conserves = frozenset(self.conserves)
        unknown = sorted(conserves - CONSERVED)
        if unknown:
            raise InputError(f"unknown quantity {unknown[0]!r}; expected some of "
                             f"{', '.join(sorted(CONSERVED))}", key="conserves")  # fmt: skip
        if "energy" in conserves and self.potential is None:
            raise InputError("a force that conserves energy declares its potential",
                             key="potential")  # fmt: skip
        if "angular_momentum" in conserves and self.point is None:
            raise InputError("angular momentum is conserved about a point: give point=",
                             key="point")  # fmt: skip
        object.__setattr__(self, "conserves", conserves)
        if self.point is not None:
            object.__setattr__(self, "point", _params(self.point, "point"))
        _check_kernel(self, "force kernel", 6, "kernel(t, q, c, w, v, p)")

    @property
    def location(self) -> tuple[str, str]:
        return _kernel_location(self.kernel, "force kernel")


#: What a force may declare it conserves (with no other force on the body): the total
#: ``energy`` (kinetic plus its potential), the ``linear_momentum`` (no net force), the
#: ``spin`` (angular momentum about the centre of mass: no torque about it) and the
#: ``angular_momentum`` about its ``point`` (the force's line passes through it).
CONSERVED = frozenset({"energy", "linear_momentum", "spin", "angular_momentum"})


@dataclass(frozen=True)
class PrescribedOmega:
    """A prescribed body angular velocity ``kernel(t, p) -> (ω1, ω2, ω3)`` and parameters.

    Examples
    --------
    >>> from ga_rotors.reference.coning import coning_rate
    >>> omega = PrescribedOmega(coning_rate, (2.0, 0.5))
    >>> omega.name, omega.params, Problem(omega=omega).kind
    ('coning_rate', (2.0, 0.5), 'kinematic')
    """

    kernel: Callable
    params: tuple[float, ...] = ()
    name: str = ""

    def __post_init__(self):
        object.__setattr__(self, "params", _params(self.params, "omega params"))
        _check_kernel(self, "omega kernel", 2, "kernel(t, p)")

    @property
    def location(self) -> tuple[str, str]:
        return _kernel_location(self.kernel, "omega kernel")


def _arity(kernel) -> int | None:
    code = getattr(getattr(kernel, "py_func", kernel), "__code__", None)
    return None if code is None else code.co_argcount


@dataclass(frozen=True)
class Problem:
    """What is integrated: a body with declared torques, a body with a mass moving
    through space under declared forces, or a prescribed ω(t).

    ``accept_lower_order=True`` lets a method that handles orientation-only torques run
    with a torque that depends on ω, knowing it is then first-order accurate. ``kind`` is
    the problem's kind (:mod:`~ga_rotors.integrators.kinds`): by default what the
    arguments say (``"kinematic"`` with an ω(t), ``"motion"`` with a ``mass``,
    ``"torqued"`` with torques, ``"free"``); name a registered kind of your own to
    integrate another state (``docs/extending.md``).

    A motion problem (rotation and translation) has the ``mass`` (kg), the moments about
    the centre of mass, ``centre_of_mass``: where the centre of mass is in the frame the
    state is integrated in (principal axes, from the body-frame origin; m), and
    ``forces`` (:class:`ForceTerm`) beside its torques (each a torque about the centre of
    mass).

    Examples
    --------
    >>> Problem((1.0, 2.0, 3.0)).kind, Problem((1.0, 2.0, 3.0), kind="free").kind
    ('free', 'free')
    >>> Problem((1.0, 2.0, 3.0), mass=2.0, centre_of_mass=(0.0, 0.1, 0.0)).kind
    'motion'
    >>> Problem((1.0, 2.0, 3.0), kind="torqued")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: kind: these arguments make a 'free' problem, not 'torqued'
    >>> from ga_rotors import RigidBody
    >>> from ga_rotors.forces import uniform_gravity
    >>> Problem((1.0, 2.0, 3.0), forces=[uniform_gravity(RigidBody((1.0, 2.0, 3.0), mass=1.0))])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: mass: forces move a body through space: give its mass
    """

    inertia: tuple[float, float, float] | None = None
    torques: tuple[TorqueTerm, ...] = ()
    omega: PrescribedOmega | None = None
    accept_lower_order: bool = False
    kind: str | None = None
    mass: float | None = None
    centre_of_mass: tuple[float, float, float] = (0.0, 0.0, 0.0)
    forces: tuple[ForceTerm, ...] = ()
    # Values derived from this (immutable) problem, computed once: see ``derived``.
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "torques", tuple(self.torques))
        for term in self.torques:
            if not isinstance(term, TorqueTerm):
                raise InputError(f"torques: expected TorqueTerm items, got {term!r}")
        object.__setattr__(self, "forces", tuple(self.forces))
        for term in self.forces:
            if not isinstance(term, ForceTerm):
                raise InputError(f"expected ForceTerm items, got {term!r}", key="forces")
        if self.mass is None:
            if self.forces:
                raise InputError("forces move a body through space: give its mass", key="mass")
            if tuple(self.centre_of_mass) != (0.0, 0.0, 0.0):
                raise InputError("a centre of mass off the origin needs the mass", key="mass")
        else:
            mass = _params((self.mass,), "mass")[0]
            if not mass > 0.0 or self.omega is not None:
                raise InputError(f"expected a positive mass (kg) of a body, got {self.mass!r}",
                                 key="mass")  # fmt: skip
            object.__setattr__(self, "mass", mass)
            offset = _params(self.centre_of_mass, "centre_of_mass")
            if len(offset) != 3:
                raise InputError(f"expected 3 numbers (m), got {len(offset)}",
                                 key="centre_of_mass")  # fmt: skip
            object.__setattr__(self, "centre_of_mass", offset)
        if self.omega is not None:
            if not isinstance(self.omega, PrescribedOmega):
                raise InputError(f"omega: expected a PrescribedOmega, got {self.omega!r}")
            if self.torques:
                raise InputError("omega: a prescribed ω(t) takes no torques (no dynamics)")
        elif self.inertia is None:
            raise InputError("inertia: a dynamics problem needs the principal moments")
        if self.inertia is not None:
            object.__setattr__(self, "inertia", tuple(float(i) for i in self.inertia))
        if not isinstance(self.accept_lower_order, bool):
            raise InputError(
                f"accept_lower_order: expected True or False, got {self.accept_lower_order!r}"
            )
        said = (
            KINEMATIC if self.omega is not None
            else MOTION if self.mass is not None
            else TORQUED if self.torques
            else FREE
        )  # fmt: skip
        if self.kind is None:
            object.__setattr__(self, "kind", said)
        elif not isinstance(self.kind, str):
            raise InputError(f"expected the name of a problem kind, got {self.kind!r}", key="kind")
        elif self.kind in (FREE, TORQUED, KINEMATIC, MOTION) and self.kind != said:
            raise InputError(f"these arguments make a {said!r} problem, not {self.kind!r}",
                             key="kind")  # fmt: skip

    @property
    def body(self) -> tuple[float, ...]:
        """What a motion problem's steps receive as ``inertia``: the principal moments, the
        mass and the centre of mass, (I₁, I₂, I₃, m, s₁, s₂, s₃).

        Examples
        --------
        >>> Problem((1.0, 2.0, 3.0), mass=4.0, centre_of_mass=(0.0, 0.5, 0.0)).body
        (1.0, 2.0, 3.0, 4.0, 0.0, 0.5, 0.0)
        """
        if self.mass is None:
            raise InputError("a body without a mass turns only; give mass=", key="mass")
        return (*self.inertia, self.mass, *self.centre_of_mass)

    def params(self) -> np.ndarray:
        """The packed parameter array the generated ``torque``/``omega``/``wrench`` slices:
        the torques' parameters, then the forces'."""
        terms = (self.omega,) if self.omega is not None else (*self.torques, *self.forces)
        flat = [p for term in terms for p in term.params]
        return np.array(flat, dtype=np.float64)

    def derived(self, key, make: Callable[[], Any]):
        """``make()``, computed on the first call with this ``key`` and remembered: what an
        integrator derives from a problem (its checks passed, its compiled loop, the
        packed parameters) is computed once per problem, not once per run.

        Examples
        --------
        >>> p = Problem((1.0, 2.0, 3.0))
        >>> p.derived("answer", lambda: 42), p.derived("answer", lambda: 0)
        (42, 42)
        """
        try:
            return self._derived[key]
        except KeyError:
            value = self._derived[key] = make()
            return value


_PROBLEMS: dict[tuple, Problem] = {}


def problem_for(inertia, torques=(), accept_lower_order: bool = False, *, mass=None,
                centre_of_mass=(0.0, 0.0, 0.0), forces=()) -> Problem:  # fmt: skip
    """The :class:`Problem` of these moments and torques, shared by the calls that repeat
    them (the last 64 kept), so what runs derive from a problem — its checks, its compiled
    loop — is derived once: :func:`ga_rotors.simulation.simulate` builds its problem here.

    Examples
    --------
    >>> problem_for((1.0, 2.0, 3.0)) is problem_for([1, 2, 3])
    True
    >>> problem_for((1.0, 2.0, 3.0), accept_lower_order=True).accept_lower_order
    True
    """
    motion = {}
    if mass is not None or forces:
        motion = {"mass": mass, "centre_of_mass": tuple(centre_of_mass), "forces": tuple(forces)}
    try:
        if not (type(inertia) is tuple and len(inertia) == 3 and type(inertia[0]) is float
                and type(inertia[1]) is float and type(inertia[2]) is float):  # fmt: skip
            inertia = tuple(float(i) for i in inertia)
        key = (inertia, torques if type(torques) is tuple else tuple(torques), accept_lower_order,
               tuple(sorted(motion.items())))  # fmt: skip
        found = _PROBLEMS.get(key)
    except TypeError:  # something unhashable: let Problem say what is wrong with it
        return Problem(inertia, tuple(torques), accept_lower_order=accept_lower_order, **motion)
    if found is None:
        if len(_PROBLEMS) >= 64:
            _PROBLEMS.clear()
        found = _PROBLEMS[key] = Problem(key[0], key[1], accept_lower_order=accept_lower_order,
                                         **motion)  # fmt: skip
    return found


@dataclass(frozen=True, eq=False)
class Batch:
    """Many bodies with ``problem``'s declared torques, each with its own moments and
    torque parameters: what :meth:`~ga_rotors.integrators.Integrator.run` integrates at
    once, each body as its own single run would, bit for bit.

    ``inertia`` (n, 3) principal moments, one row per body (for another problem kind, the
    kind's ``body_size`` numbers: :mod:`~ga_rotors.integrators.kinds`); ``params`` (n, P) each body's
    packed torque parameters (as :meth:`Problem.params` packs the problem's; default: the
    problem's for every body).

    Examples
    --------
    >>> b = Batch(Problem((1.0, 2.0, 3.0)), [[1.0, 2.0, 3.0], [1.0, 2.0, 2.5]])
    >>> len(b), b.params.shape
    (2, (2, 0))
    >>> Batch(Problem((1.0, 2.0, 3.0)), [[1.0, 2.0, 3.0]], params=[[1.0]])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: params: expected shape (1, 0) (one row of the problem's 0 parameters per body), got (1, 1)
    """  # noqa: E501

    problem: Problem
    inertia: np.ndarray
    params: np.ndarray | None = None

    def __post_init__(self):
        if not isinstance(self.problem, Problem):
            raise InputError(f"expected a Problem, got {self.problem!r}", key="problem")
        inertia = np.asarray(self.inertia, dtype=np.float64)
        if inertia.ndim != 2:
            raise InputError(f"expected one row per body, got shape {inertia.shape}",
                             key="inertia")  # fmt: skip
        size = self.problem.params().size
        if self.params is None:
            params = np.tile(self.problem.params(), (inertia.shape[0], 1))
        else:
            params = np.asarray(self.params, dtype=np.float64)
        if params.shape != (inertia.shape[0], size):
            raise InputError(
                f"expected shape {(inertia.shape[0], size)} (one row of the problem's {size} "
                f"parameters per body), got {params.shape}", key="params",
            )  # fmt: skip
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "params", params)

    def __len__(self) -> int:
        return self.inertia.shape[0]
