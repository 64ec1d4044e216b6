"""Problem kinds: what each kind of problem brings to a compiled loop, declared as data.

A :class:`ProblemKind` says everything the code generator (:mod:`._source`) needs to turn
an integrator's step template into a loop for one kind of problem, so a new kind plugs in
by declaration (:func:`register_kind`), not by a generator of its own:

* the **state layout**: a run's state is the path's orientation state ``x`` (its size is
  the path's) and a *rate* part ``w`` of ``rate`` numbers (the body ω: 3), read and
  written by the kernels ``rate_load``/``rate_store`` and stepped by ``rate_axpy``
  (w + h·k) and ``rate_rk4`` (RK4's weighted sum); the loop templates and the Runge–Kutta
  steps are written over them (slots ``r_load``, ``r_store``, ``r_axpy``, ``r_rk4``), so
  they serve any rate size;
* the **slots it generates** (``slots``: slot name -> :class:`SlotSource`, the slot's
  source text made from the problem, and the other slots that text calls): ``accel``
  (Euler's equations, with or without ``torque``), ``torque`` (the sum of the declared
  torque kernels), ``omega`` (a prescribed ω(t)); a step that calls a slot its kind does
  not generate is refused in one line, and so is a step that never reaches the slot the
  kind ``evaluates`` (a torqued step that ignores the torque);
* its **loop templates** (:mod:`.loops`): ``loop`` for a run, ``rhs`` for the vector
  field of scipy-style integrators, ``batch`` for many bodies at once (None: no batches);
* the **body** a loop passes its step as ``inertia`` (``body(problem)``; a batch's rows
  per sample), and ``stored``: a kernel of the body whose values a batch computes once per
  body and keeps beside it (the Euler coefficients: six divisions per body instead of per
  stage), read back wherever the step's kernels would call it;
* ``judged``: whether the integrators' step limits (:mod:`.limits`) apply.

The three built-in kinds are :data:`FREE`, :data:`TORQUED` and :data:`KINEMATIC`.
``docs/extending.md`` ("A problem kind") shows a new one end to end.

Examples
--------
>>> sorted(KINDS["torqued"].slots["accel"].calls)
['o_quat', 'torque']
>>> KINDS["kinematic"].evaluates, KINDS["kinematic"].batch is None
('omega', True)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import NamedTuple

from .._kernels import euler_coefficients, euler_rates, free_euler_rates
from ..errors import InputError
from . import loops
from ._arith import axpy3, axpy6, load3, load6, rk4_sum3, rk4_sum6, store3, store6
from .problem import FREE, KINEMATIC, MOTION, TORQUED

__all__ = ["KINDS", "ProblemKind", "SlotSource", "register_kind"]


class SlotSource(NamedTuple):
    """How a kind writes one generated slot.

    ``write(problem, imports) -> str`` returns the slot's ``def`` (a module-level function
    named after the slot), binding the kernels it calls with ``imports.kernel(name,
    kernel)``; ``calls`` are the other slots that text calls.

    Examples
    --------
    >>> class Imports:  # what the generator passes: it records the kernels bound
    ...     def kernel(self, name, kernel):
    ...         print("binds", name)
    >>> from ga_rotors.integrators import Problem
    >>> print(KINDS["free"].slots["accel"].write(Problem((1.0, 2.0, 3.0)), Imports()))
    binds free_euler_rates
    def accel(t, x, w, inertia, params):
        return free_euler_rates(inertia, w)
    <BLANKLINE>
    """

    write: Callable
    calls: frozenset[str] = frozenset()


def _torque(problem, imports) -> str:
    """``torque(t, q, w, params)``: the sum of exactly the declared torque kernels, each
    on its slice of the packed parameters."""
    calls, offset = [], 0
    for n, term in enumerate(problem.torques):
        alias = f"_term_{n}"
        imports.kernel(alias, term.kernel)
        size = len(term.params)
        calls.append(f"{alias}(t, q, w, params[{offset}:{offset + size}])")
        offset += size
    if len(calls) == 1:
        body = f"    return {calls[0]}\n"
    else:
        body = "".join(f"    a{n} = {c}\n" for n, c in enumerate(calls))
        sums = [" + ".join(f"a{n}[{k}]" for n in range(len(calls))) for k in range(3)]
        body += f"    return ({sums[0]}, {sums[1]}, {sums[2]})\n"
    return "def torque(t, q, w, params):\n" + body


def _free_accel(problem, imports) -> str:
    """Euler's equations of the torque-free body: no torque term at all."""
    imports.kernel("free_euler_rates", free_euler_rates)
    return "def accel(t, x, w, inertia, params):\n    return free_euler_rates(inertia, w)\n"


def _torqued_accel(problem, imports) -> str:
    """Euler's equations with the declared torques, evaluated at the path's quaternion."""
    imports.kernel("euler_rates", euler_rates)
    return (
        "def accel(t, x, w, inertia, params):\n"
        "    return euler_rates(inertia, w, torque(t, o_quat(x), w, params))\n"
    )


def _wrench(problem, imports) -> str:
    """``wrench(t, q, c, w, v, params)``: the sum of exactly the declared forces (each a
    force in space and a torque about the centre of mass) and torques (about the centre of
    mass), each kernel on its slice of the packed parameters (torques first)."""
    calls, offset = [], 0
    for n, term in enumerate(problem.torques):
        imports.kernel(f"_term_{n}", term.kernel)
        size = len(term.params)
        calls.append((False, f"_term_{n}(t, q, w, params[{offset}:{offset + size}])"))
        offset += size
    for n, term in enumerate(problem.forces):
        imports.kernel(f"_force_{n}", term.kernel)
        size = len(term.params)
        calls.append((True, f"_force_{n}(t, q, c, w, v, params[{offset}:{offset + size}])"))
        offset += size
    if not calls:
        return "def wrench(t, q, c, w, v, params):\n    return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)\n"
    body = "".join(f"    a{n} = {call}\n" for n, (_, call) in enumerate(calls))
    sums = []
    for k in range(6):  # forces give six numbers, torques the last three
        parts = [f"a{n}[{k if force else k - 3}]" for n, (force, _) in enumerate(calls)
                 if force or k >= 3]  # fmt: skip
        sums.append(" + ".join(parts) if parts else "0.0")
    return "def wrench(t, q, c, w, v, params):\n" + body + f"    return ({', '.join(sums)})\n"


def _motion_accel(problem, imports) -> str:
    """The path's equations of motion (``o_motion``) under the declared wrench, evaluated at
    the state's centre of mass; with nothing declared, the free equations alone."""
    if not problem.forces and not problem.torques:
        return "def accel(t, x, w, inertia, params):\n    return o_free_motion(x, w, inertia)\n"
    return (
        "def accel(t, x, w, inertia, params):\n"
        "    q, c, u, v = o_centre(x, w, inertia)\n"
        "    return o_motion(x, w, inertia, wrench(t, q, c, u, v, params))\n"
    )


def _omega(problem, imports) -> str:
    """The prescribed body ω(t) on its parameters."""
    imports.kernel("_omega_0", problem.omega.kernel)
    size = len(problem.omega.params)
    return f"def omega(t, params):\n    return _omega_0(t, params[0:{size}])\n"


def _moments(problem) -> tuple[float, ...]:
    """The principal moments (a prescribed ω(t) has none: ones, which no step reads)."""
    return problem.inertia if problem.inertia is not None else (1.0, 1.0, 1.0)


def _motion_body(problem) -> tuple[float, ...]:
    """The moments, the mass and the centre of mass (:attr:`Problem.body`)."""
    return problem.body


@dataclass(frozen=True)
class ProblemKind:
    """One kind of problem, as the code generator sees it (see the module's text).

    Parameters
    ----------
    name : str
        The kind's name (``Problem.kind``, the keys of an integrator's ``steps``).
    loop, rhs : function
        Loop templates (:mod:`.loops`): a run's fixed-step loop, and the vector field.
    slots : mapping of str to SlotSource
        The slots this kind generates.
    evaluates : str or None
        The generated slot a step of this kind must reach.
    batch : function or None
        The batched chunk loop template; None: the kind has no batched runs.
    rate : int
        Numbers in the rate part of the state; ``rate_load``/``rate_store`` read and
        write that many (tuples of floats, arrays of float64), ``rate_axpy(w, h, k)`` and
        ``rate_rk4(w, h, k1, k2, k3, k4)`` step them.
    body : function
        ``body(problem)``: the tuple a loop passes its step as ``inertia``.
    body_size : int
        Numbers in it (a batch's per-sample body rows).
    stored : kernel or None
        A compiled kernel of the body, ``stored(inertia) -> tuple``, that a batch computes
        once per body (``stored_size`` numbers) and appends to the body tuple, and that
        the step's kernels then read back instead of computing (None: nothing stored).
    judged : bool
        The integrators' step limits apply to this kind (they read the first three
        numbers of the rates as ω and of the body as its moments).
    dynamic : bool
        The rate part is integrated (False: it is prescribed, and the vector field's
        state is the orientation alone).
    moves : bool
        The state carries the body's position: a problem of this kind runs on the paths
        that integrate whole rigid motion (:func:`ga_rotors.paths.resolve`).

    Examples
    --------
    >>> free = KINDS["free"]
    >>> free.loop.__name__, free.rate, free.body_size, free.stored.__name__, free.stored_size
    ('fixed_step_loop', 3, 3, 'euler_coefficients', 6)
    >>> from ga_rotors.integrators import Problem
    >>> free.body(Problem((1.0, 2.0, 3.0)))
    (1.0, 2.0, 3.0)
    """

    name: str
    loop: Callable
    rhs: Callable
    slots: Mapping[str, SlotSource]
    evaluates: str | None = None
    batch: Callable | None = None
    rate: int = 3
    rate_load: Callable = field(default=load3)
    rate_store: Callable = field(default=store3)
    rate_axpy: Callable = field(default=axpy3)
    rate_rk4: Callable = field(default=rk4_sum3)
    body: Callable = field(default=_moments)
    body_size: int = 3
    stored: Callable | None = None
    stored_size: int = 0
    judged: bool = True
    dynamic: bool = True
    moves: bool = False


#: name -> ProblemKind: every kind a problem can be and a step can be declared for.
KINDS: dict[str, ProblemKind] = {}


def register_kind(kind: ProblemKind) -> ProblemKind:
    """Add a problem kind (names are unique) and return it.

    Examples
    --------
    >>> register_kind(KINDS["free"]) is KINDS["free"]
    True
    >>> import dataclasses
    >>> register_kind(dataclasses.replace(KINDS["free"], evaluates="torque"))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: register_kind: a problem kind named 'free' already exists
    """
    if not isinstance(kind, ProblemKind):
        raise InputError(f"expected a ProblemKind, got {kind!r}", key="register_kind")
    existing = KINDS.get(kind.name)
    if existing is not None and existing is not kind:
        raise InputError(f"a problem kind named {kind.name!r} already exists", key="register_kind")
    if kind.evaluates is not None and kind.evaluates not in kind.slots:
        raise InputError(
            f"{kind.name}: evaluates {kind.evaluates!r}, which is not one of its slots",
            key="register_kind",
        )
    KINDS[kind.name] = kind
    return kind


_TORQUE = SlotSource(_torque)

register_kind(
    ProblemKind(
        FREE,
        loop=loops.fixed_step_loop,
        rhs=loops.dynamics_rhs,
        slots={"accel": SlotSource(_free_accel)},
        batch=loops.batch_chunk,
        stored=euler_coefficients,
        stored_size=6,
    )
)
register_kind(
    ProblemKind(
        TORQUED,
        loop=loops.fixed_step_loop,
        rhs=loops.dynamics_rhs,
        slots={
            "accel": SlotSource(_torqued_accel, frozenset({"torque", "o_quat"})),
            "torque": _TORQUE,
        },
        evaluates="torque",
        batch=loops.batch_chunk,
        stored=euler_coefficients,
        stored_size=6,
    )
)
register_kind(
    ProblemKind(
        KINEMATIC,
        loop=loops.kinematic_loop,
        rhs=loops.kinematic_rhs,
        slots={"omega": SlotSource(_omega)},
        evaluates="omega",
        judged=False,
        dynamic=False,
    )
)
register_kind(
    ProblemKind(
        MOTION,
        loop=loops.fixed_step_loop,
        rhs=loops.dynamics_rhs,
        slots={
            "accel": SlotSource(
                _motion_accel,
                frozenset({"wrench", "o_centre", "o_motion", "o_free_motion"}),
            ),
            "wrench": SlotSource(_wrench),
        },
        batch=loops.batch_chunk,
        rate=6,
        rate_load=load6,
        rate_store=store6,
        rate_axpy=axpy6,
        rate_rk4=rk4_sum6,
        body=_motion_body,
        body_size=7,
        stored=euler_coefficients,
        stored_size=6,
        moves=True,
    )
)
