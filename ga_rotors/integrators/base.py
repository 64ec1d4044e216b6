"""The integrator interface and the registry (the problem description is :mod:`.problem`).

How an integrator plugs in
--------------------------
An integrator is a :class:`~ga_rotors.integrators.template.TemplateIntegrator` registered
under a name. It declares everything a caller and the accuracy study need to know about it:

* ``name``, ``order``, ``description``;
* ``evaluations``: its cost per step, in vector-field evaluations (Runge–Kutta stages;
  for a splitting, its Strang stages, each a handful of exact axis rotations, about the
  cost of one evaluation; for an implicit method, one per step, its solver sweeps not
  counted): the study's "evaluations" axis is this times the number of steps;
* ``conserves``: a subset of :data:`PROPERTIES` (``unit_norm``, ``energy``,
  ``momentum_norm`` = |L|, ``space_momentum`` = space-frame L, ``symplectic``,
  ``time_reversible``), what it preserves *by construction* (tests hold it to that);
* ``paths``: the orientation paths it can step (``rotor``, ``quaternion``, ``euler``;
  see :mod:`ga_rotors.paths`); a method that needs unit-sphere operations
  (``o_normalize``, ``o_from_quat``) supports only ``rotor`` and ``quaternion``;
* ``steps``: problem kind -> step template, for the kinds it supports among
  :data:`FREE` (torque-free), :data:`TORQUED`, :data:`KINEMATIC` (prescribed ω(t));
* ``helpers``: other templates its steps call (pasted only when reachable);
* ``torques``: which torques it integrates at its declared order, :data:`ANY_TORQUE`
  (the default: Runge–Kutta-type methods evaluate the full vector field) or
  :data:`ORIENTATION_TORQUES`, torques that depend on orientation and time only (a
  kick–drift–kick splitting or a variational method, whose kick is the exact flow of
  such a torque; with a torque that reads ω the kick is not exact and the method falls
  to order 1, measured for split2/4/6 and lgvi under damping).

A :class:`TorqueTerm` says whether it reads ω (``depends_on_omega``, default True: an
unknown kernel may). :meth:`Integrator.check` refuses a problem that gives an
:data:`ORIENTATION_TORQUES` method a torque that depends on ω, naming both, unless the
problem accepts the lower order (``Problem(..., accept_lower_order=True)``).

A *template* is a plain, undecorated, module-level Python function. It calls other
templates, compiled kernels (``ga_rotors._kernels``, ``ga_rotors.body``,
``ga_rotors._rotor_kernels``, ``ga_rotors.integrators._arith``, ...) and the *slots* of
:mod:`ga_rotors.integrators.slots`, which it imports from there, so it reads and lints as
ordinary code. Step templates have fixed signatures::

    free / torqued:  x, w = step(t, x, w, h, inertia, params)
    kinematic:       x    = step(t, x, h, params)

``x`` is the path's state tuple (rotor coefficients, quaternion, or ZYZ angles), ``w`` the
body angular velocity 3-tuple, ``inertia`` the principal moments 3-tuple, ``params`` the
float64 array of the declared effects' parameters (pass it through untouched). Inside a
step, use

* ``accel(t, x, w, inertia, params)`` for ω̇ from Euler's equations, torque included when
  the problem is torqued (a torque-free module's ``accel`` has no torque term at all);
* ``torque(t, q, w, params)`` directly (e.g. a kick of kick–drift–kick), with
  ``q = o_quat(x)``; only torqued problems define it: a template that calls it cannot be
  instantiated for a free problem, so keep such a step out of ``steps[FREE]``;
* ``omega(t, params)`` for the prescribed body ω(t) (kinematic problems only);
* ``o_rate``, ``o_axpy``, ``o_rk4``, ``o_normalize``, ``o_quat``, ``o_from_quat`` for the
  path (a Lie-group method on the quaternion/rotor paths, for example, does
  ``o_from_quat(qmul(o_quat(x), quat_from_rotvec(...)))``: both maps are signed
  permutations, free after compilation).

Module-level constants a template reads (numbers or tuples of numbers, e.g. composition
coefficients) are copied into the generated module. Example, a Lie–Euler step::

    from .._kernels import qmul, quat_from_rotvec
    from ._arith import axpy3
    from .slots import accel, o_from_quat, o_quat

    def lie_euler_step(t, x, w, h, inertia, params):
        dw = accel(t, x, w, inertia, params)
        q = qmul(o_quat(x), quat_from_rotvec((h * w[0], h * w[1], h * w[2])))
        return o_from_quat(q), axpy3(w, h, dw)

    LIE_EULER = register(TemplateIntegrator(
        name="lie_euler", order=1, description="...", conserves=frozenset({"unit_norm"}),
        paths=frozenset({"rotor", "quaternion"}), steps={FREE: lie_euler_step,
        TORQUED: lie_euler_step}, evaluations=1))

and add the module's name to :data:`BUILTIN_MODULES` so the registry loads it: that one
line is the only place outside the method's own module (``docs/extending.md``, "An
integrator").

Specialisation (why code generation)
------------------------------------
numba does not cache a function that receives compiled functions as arguments, nor a
closure, so "one loop, any torque" would recompile in every process (~1 s). Instead,
:mod:`ga_rotors.integrators._source` writes, for one (integrator, problem kind, path,
declared torque kernels), a small source module: imports of the kernels the templates
use, the slots the problem's kind generates (:mod:`ga_rotors.integrators.kinds`: for a
torqued body ``torque`` as the sum of exactly the declared torque kernels, and
``accel``), the templates and the kind's loop (:mod:`ga_rotors.integrators.loops`), each
under ``@jit`` (cache=True). :mod:`ga_rotors.integrators._cache` writes it atomically into
a per-user cache directory, named by a hash of its text and of the sources it depends on,
and imports it from there, so numba's on-disk cache applies; the text is kept in
``linecache``, so tracebacks and ``inspect.getsource`` show it. Undeclared torques are
not in the source at all; free problems have no ``torque``. The same route gives a batch
of bodies its loop (the same step, compiled inline in a batched loop template) and
scipy-style integrators their vector field. A template that calls a plain Python function
missing from ``helpers=`` is refused in one line naming it.

Effects (issue 5's torques)
---------------------------
A torque is a :class:`TorqueTerm`: a compiled kernel ``kernel(t, q, w, p) -> (τ1, τ2, τ3)``
(body frame; ``q`` the body->space unit quaternion, ``w`` body ω, ``p`` a float64 array
view of this term's parameters) defined at module level in an importable module, and
its parameters. A prescribed angular velocity is a :class:`PrescribedOmega`:
``kernel(t, p) -> (ω1, ω2, ω3)``, same rules.

Running
-------
:meth:`Integrator.run` is the one way to run: it takes a :class:`Problem` (or a
:class:`~.problem.Batch` of bodies) and a path name and returns a :class:`LoopResult`
(or, with ``chunk``, the run as consecutive pieces); :func:`ga_rotors.simulation.simulate`
is the user-facing entry point. ``run`` checks the combination once per (problem, path)
(:meth:`Integrator.check`, remembered by the problem), judges the step limit on the
initial state (:meth:`Integrator.check_step`, closed form, its message built only past
the limit) and, asked to, watches the stored samples (:meth:`Integrator.watch_step`). A
template integrator does all of it in one compiled call of its generated module
(:func:`~ga_rotors.integrators.loops.judged_run`: the limit, measured by a compiled kernel,
then the loop), and comes back to :meth:`Integrator.check_step` for the words only past
the limit; what a run costs around its loop is measured by ``benchmarks/bench_overhead.py``.
A non-template integrator (e.g. scipy's DOP853) subclasses :class:`Integrator` and
implements ``_whole`` (and, if it can continue a run, ``_pieces``) itself;
:func:`ga_rotors.integrators._runner.vector_field` gives it the same compiled, specialised
right-hand side.
"""

from __future__ import annotations

import importlib
import warnings
from abc import ABC, abstractmethod
from collections.abc import Callable
from pathlib import Path as FilePath
from typing import NamedTuple

import numpy as np

from ..errors import InputError
from .kinds import KINDS
from .limits import WATCH_GROWTH, watch_candidates
from .problem import (
    FREE,
    KINEMATIC,
    MOTION,
    TORQUED,
    Batch,
    ForceTerm,
    PrescribedOmega,
    Problem,
    TorqueTerm,
    problem_for,
)

__all__ = [
    "ANY_TORQUE",
    "BUILTIN_MODULES",
    "FREE",
    "KINDS",
    "KINEMATIC",
    "MOTION",
    "ORIENTATION_TORQUES",
    "PROPERTIES",
    "TORQUED",
    "TORQUE_SUPPORT",
    "WATCH_GROWTH",
    "Batch",
    "ForceTerm",
    "Integrator",
    "LoopResult",
    "PrescribedOmega",
    "Problem",
    "TorqueTerm",
    "any_torque_methods",
    "catalogue",
    "get",
    "names",
    "problem_for",
    "register",
    "torque_conflict",
]

#: What an integrator may declare it preserves by construction.
PROPERTIES = frozenset(
    {"unit_norm", "energy", "momentum_norm", "space_momentum", "symplectic", "time_reversible"}
)

#: An integrator's ``torques``: it handles any torque τ(t, q, ω) at its declared order ...
ANY_TORQUE = "any"
#: ... or only torques τ(t, q) that do not read ω (its order falls to 1 otherwise).
ORIENTATION_TORQUES = "orientation-only"
TORQUE_SUPPORT = (ANY_TORQUE, ORIENTATION_TORQUES)

#: Modules that register integrators on import, loaded on first registry access.
BUILTIN_MODULES = (
    "ga_rotors.integrators.rk4",
    "ga_rotors.integrators.lie_group",
    "ga_rotors.integrators.splitting",
    "ga_rotors.integrators.variational",
    "ga_rotors.integrators.implicit",
    "ga_rotors.integrators.dop853",
    "ga_rotors.integrators.dp8",
)


class LoopResult(NamedTuple):
    """The samples of one run of one path.

    ``t`` (n,), ``x`` (n, dim) path states, ``w`` (n, 3) body ω; ``complete`` is False
    when the state stopped being finite and the run ended early (``t[-1]`` is then the
    last finite sample). ``stats`` holds the path's watch statistics; ``source`` the
    generated module's file (None when compiled in memory). A named tuple: built on every
    run, it costs a fraction of a frozen dataclass's 1.7 µs.

    Examples
    --------
    A spin of 2 rad/s about z for 1 s, 100 steps, a sample every 50:

    >>> r = get("rk4").run(Problem((1.0, 2.0, 3.0)), "quaternion", (1.0, 0.0, 0.0, 0.0),
    ...                    (0.0, 0.0, 2.0), 0.0, 0.01, 100, 50)
    >>> r.t, r.complete, r.x.shape, r.w.shape
    (array([0. , 0.5, 1. ]), True, (3, 4), (3, 3))

    RK4's error per step on this rotation is (h|ω|/2)⁵/5! ≈ 8e-13, about 8e-11 over 100:

    >>> bool(np.allclose(r.x[-1], (np.cos(1.0), 0, 0, np.sin(1.0)), rtol=0, atol=1e-10))
    True
    """

    t: np.ndarray
    x: np.ndarray
    w: np.ndarray
    complete: bool
    stats: np.ndarray
    source: FilePath | None = None


class Integrator(ABC):
    """What every integrator declares; :meth:`run` integrates one path.

    Examples
    --------
    >>> rk4 = get("rk4")
    >>> isinstance(rk4, Integrator), rk4.order, sorted(rk4.paths)
    (True, 4, ['euler', 'motor', 'quaternion', 'rotor'])
    >>> rk4.check(Problem((1.0, 2.0, 3.0)), "matrix")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: paths: rk4 cannot step the 'matrix' path (supports ...)
    """

    name: str
    order: int
    description: str
    conserves: frozenset[str]
    paths: frozenset[str]
    #: Cost per step in vector-field evaluations (splittings: Strang stages).
    evaluations: float
    torques: str = ANY_TORQUE
    #: ``step_limit(inertia, w0, h, nsteps) -> limits.StepLimit``, or None (no limit).
    step_limit: Callable | None = None
    #: What a run past the limit does: ``"warn"`` (StepLimitWarning) or ``"raise"``.
    step_limit_action: str = "warn"
    #: A tolerance, not the step, sets its accuracy (``h`` then only fixes sample times).
    adaptive: bool = False
    #: It can continue a run where a piece ended (``run(chunk=...)`` then hands the run
    #: out in pieces of that size; otherwise in one piece, the whole run).
    continues: bool = False

    @property
    @abstractmethod
    def problems(self) -> frozenset[str]:
        """Problem kinds supported."""

    def run(
        self, problem: Problem | Batch, path: str, x0, w0, t0: float, h: float, nsteps: int,
        every, *, chunk: int | None = None, progress: Callable[[int], None] | None = None,
        where: str | None = "h", watch: bool = False, stacklevel: int = 2,
        parallel: bool = True,
    ):  # fmt: skip
        """Integrate ``nsteps`` steps of size ``h`` from (x0, w0) at ``t0`` on ``path``,
        keeping every ``every``-th sample (and the last): the one way to run a loop.

        :meth:`check` (once per problem and path), then the step limit judged on the
        initial state (past it, a :class:`~ga_rotors.errors.StepLimitWarning`, or for a
        method that has no step there an InputError, the message starting with ``where``;
        ``where=None``: not judged, for a caller that judged it already).

        Parameters
        ----------
        problem : Problem or Batch
            What is integrated; a :class:`Batch` integrates many bodies at once (``x0``
            (n, dim), ``w0`` (n, 3); ``every`` may then be the step numbers to sample;
            not judged; ``parallel``: over numba's threads, or in the calling thread).
        chunk : int, optional
            Hand the run out as consecutive pieces of about ``chunk`` steps (an iterator
            of :class:`LoopResult`: the first holds sample 0, each next one the samples
            after the previous piece's last), so a long run holds one piece at a time.
            Joined, they are the whole run's samples bit for bit. For a batch: the
            bodies per chunk of its loop (default 256, a chunk's states stay in L1).
        progress : callable, optional
            ``progress(steps_done)``, called as the loop advances (at least at the end).
        watch : bool
            Also judge the limit at the stored samples whose ω sets a new high
            (:meth:`watch_step`): a torque may carry a run past the limit it started within.
        stacklevel : int
            The warnings' as seen from here (2: this method's caller).

        Returns
        -------
        LoopResult, or an iterator of them with ``chunk``

        Examples
        --------
        >>> r = get("rk4").run(Problem((1.0, 2.0, 3.0)), "quaternion", (1.0, 0, 0, 0),
        ...                    (0.0, 0.0, 2.0), 0.0, 0.01, 100, 100)
        >>> r.t.tolist(), r.complete
        ([0.0, 1.0], True)
        >>> pieces = get("rk4").run(Problem((1.0, 2.0, 3.0)), "rotor", (1.0, 0, 0, 0),
        ...                         (0.0, 0.0, 2.0), 0.0, 0.01, 100, 10, chunk=50)
        >>> [piece.t.tolist()[-1] for piece in pieces]
        [0.5, 1.0]

        A torque spins the body up past rk4's limit during the run:

        >>> import warnings
        >>> from ga_rotors.effects import body_torque
        >>> spin = TorqueTerm(body_torque, (0.0, 0.0, 30.0), depends_on_omega=False)
        >>> with warnings.catch_warnings(record=True) as caught:
        ...     warnings.simplefilter("always")
        ...     r = get("rk4").run(Problem((1.0, 1.5, 2.0), (spin,)), "quaternion",
        ...                        (1.0, 0, 0, 0), (0.0, 0.0, 10.0), 0.0, 0.01, 2000, 10,
        ...                        where="mine", watch=True)
        >>> str(caught[0].message).startswith("mine: rk4 crosses its step limit at t = ")
        True
        """
        if isinstance(problem, Batch):
            self.check_once(problem.problem, path)
            return self._batch(problem, path, x0, w0, t0, h, nsteps, every, parallel, chunk)
        self.check_once(problem, path)
        if chunk is not None and (
            isinstance(chunk, bool) or not isinstance(chunk, int | np.integer) or chunk < 1
        ):
            raise InputError(f"expected a positive integer, got {chunk!r}", key="chunk")
        limit = None
        if where is not None:
            limit = self.check_step(problem, w0, h, nsteps, where, stacklevel + 1)
        watching = watch and limit is not None and not limit.exceeded
        if chunk is not None:
            found = self._pieces(problem, path, x0, w0, t0, h, nsteps, every, chunk, progress)
            return self._watched(found, problem, h, nsteps, where) if watching else found
        result = self._whole(problem, path, x0, w0, t0, h, nsteps, every, progress)
        if watching:
            self.watch_step(problem, result.t, result.w, h, nsteps, where, stacklevel + 1)
        return result

    def _watched(self, pieces, problem: Problem, h: float, nsteps: int, where: str):
        """``pieces``, each watched (:meth:`watch_step`) until a sample past the limit."""
        for piece in pieces:
            if problem is not None:
                found = self.watch_step(problem, piece.t, piece.w, h, nsteps, where, 4)
                problem = None if found is not None else problem
            yield piece

    @abstractmethod
    def _whole(self, problem: Problem, path: str, x0, w0, t0: float, h: float, nsteps: int,
               every: int, progress) -> LoopResult:  # fmt: skip
        """The run in one piece, unchecked (:meth:`run` checked it)."""

    def _pieces(self, problem: Problem, path: str, x0, w0, t0: float, h: float, nsteps: int,
                every: int, chunk: int, progress):  # fmt: skip
        """The run as pieces of about ``chunk`` steps (see :meth:`run`), unchecked. This
        default, for an integrator that cannot continue a run (``continues`` False),
        yields one piece holding the whole run."""
        yield self._whole(problem, path, x0, w0, t0, h, nsteps, every, progress)

    def _batch(self, batch: Batch, path: str, x0, w0, t0, h, nsteps, every, parallel, chunk):
        """A batch's run (see :meth:`run`); this default refuses it."""
        raise InputError(
            f"{self.name} integrates one body at a time; batches run on the fixed-step "
            "template methods", key="integrator",
        )  # fmt: skip

    def check_once(self, problem: Problem, path: str) -> None:
        """:meth:`check`, remembered by the problem: a problem and path that passed are
        not checked again (the problem is immutable).

        Examples
        --------
        >>> problem = Problem((1.0, 2.0, 3.0))
        >>> get("rk4").check_once(problem, "rotor")  # checked; the next call looks it up
        >>> get("split_sym").check_once(Problem((1.0, 1.0, 2.0)), "euler")
        Traceback (most recent call last):
        ...
        ga_rotors.errors.InputError: paths: split_sym cannot step the 'euler' path ...
        """
        # The value holds self, so the id in the key is never reused while it is kept.
        problem.derived(("checked", id(self), path), lambda: self.check(problem, path) or self)

    def check(self, problem: Problem, path: str) -> None:
        """InputError naming what is unsupported, if anything."""
        if problem.kind not in KINDS:
            raise InputError(
                f"unknown problem kind {problem.kind!r}; expected one of "
                f"{', '.join(sorted(KINDS))} (register_kind adds one)", key="kind",
            )  # fmt: skip
        if problem.kind not in self.problems:
            raise InputError(
                f"{self.name} does not support {problem.kind} problems "
                f"(supports {', '.join(sorted(self.problems))})",
                key="integrator",
            )
        if path not in self.paths:
            raise InputError(
                f"{self.name} cannot step the {path!r} path "
                f"(supports {', '.join(sorted(self.paths))})",
                key="paths",
            )
        if not getattr(problem, "accept_lower_order", False):
            terms = (*getattr(problem, "torques", ()), *getattr(problem, "forces", ()))
            term = torque_conflict(self, terms)
            if term is not None:
                force = hasattr(term, "depends_on_velocity")
                what, reads, flag = (
                    ("force", "the velocity", "depends_on_velocity") if force
                    else ("torque", "ω", "depends_on_omega")
                )  # fmt: skip
                raise InputError(
                    f"{self.name} (order {self.order}) integrates {what}s of "
                    f"{'pose' if force else 'orientation'} and time only at its order, but "
                    f"{what} {term.name!r} reads {reads} ({flag}=True, which user kernels "
                    f"default to), and with it {self.name} is first-order accurate. Use a "
                    f"method that handles any {what} ({', '.join(any_torque_methods())}), "
                    f"declare {flag}=False if the {what} does not read {reads}, or accept "
                    "first order explicitly (accept_lower_order=True)",
                    key="integrator",
                )

    def check_step(
        self, problem: Problem, w0, h: float, nsteps: int, where: str = "step",
        stacklevel: int = 3,
    ):  # fmt: skip
        """Evaluate the declared step limit on the initial state; past it, warn
        (:class:`~ga_rotors.errors.StepLimitWarning`, ``stacklevel`` as seen from here:
        3, this method's caller's caller) or raise InputError, the message starting with
        ``where``. Returns the evaluated limit (None: no limit, or a prescribed-ω problem).
        A torqued problem is judged by its torque-free ν.

        Examples
        --------
        >>> import warnings
        >>> lim = get("rk4").check_step(Problem((1.0, 1.5, 2.0)), (0.0, 0.0, 1.0), 0.01, 100)
        >>> lim.quantity, lim.exceeded
        ('2N·|arg R(iy)e^(−iy)|', False)
        >>> get("lgvi").check_step(Problem((1.0, 1.5, 2.0)), (0.0, 0.0, 200.0), 0.01, 100)
        Traceback (most recent call last):
        ...
        ga_rotors.errors.InputError: step: lgvi cannot step h·|ω| = 2 (limit 1): ...
        """
        if self.step_limit is None or problem.inertia is None or w0 is None:
            return None
        if not KINDS[problem.kind].judged:  # the limits are of ω and its wobble
            return None
        w = np.asarray(w0, dtype=np.float64)
        rate = KINDS[problem.kind].rate
        if w.shape != (rate,):  # as a run says it
            raise InputError(f"expected shape ({rate},), got {w.shape}", key="w0")
        w = w[:3]  # the limits are of ω, which every kind's rates begin with
        # The verdicts of the last few (ω₀, h, N) are kept by the problem: a repeated run
        # (repeats of a sweep, a benchmark, one start over many spans) looks it up.
        key = (id(self), w.tobytes(), h, nsteps)
        seen = problem.derived("step limits", dict)
        found = seen.get(key)  # (self, limit): holding self, its id is never reused
        if found is None:
            if len(seen) >= 16:
                seen.clear()
            found = seen[key] = (self, self.step_limit(problem.inertia, w, h, nsteps))
        limit = found[1]
        if not limit.exceeded:
            return limit
        # Only now, past the limit, is the text built (it costs more than the check).
        detail = (
            f"{self.name} cannot step {limit.quantity} = {limit.value:.3g} "
            f"(limit {limit.limit:g}): {limit.effect}; take a smaller step"
        )
        if self.step_limit_action == "raise":
            raise InputError(detail, key=where)
        from ..errors import StepLimitWarning

        warnings.warn(f"{where}: {detail}", StepLimitWarning, stacklevel=stacklevel)
        return limit

    def watch_step(
        self, problem: Problem, t, w, h: float, nsteps: int, where: str = "step",
        stacklevel: int = 3,
    ):  # fmt: skip
        """After a run: the first stored sample whose ω is past the declared step limit,
        warned about (:class:`~ga_rotors.errors.StepLimitWarning`, naming its time), or None.

        A torque or damping changes ω, so a run that started within its limit may leave
        it. The limit is evaluated at each stored sample's ω (``t``, ``w``: the samples,
        principal frame) where |ω| or |L| first exceeds every earlier sample's by
        :data:`WATCH_GROWTH` (the limits' quantities grow with them; other samples are not
        evaluated, which keeps the watch cheap on long runs): with ``sample_every = 1``
        that is every step that sets such a high. ``where`` starts the message and
        ``stacklevel`` places it, as in :meth:`check_step`. Runs past the limit from the
        start are :meth:`check_step`'s.

        Examples
        --------
        A body spun up by a torque, |ω| = 10 + 10 t about its axis 3: rk4 at h = 0.01
        starts far within its limit (a lag of 5e-6 rad over 1000 steps) and crosses it at
        t = 7 s, where |ω| = 80 rad/s would lag the orientation 0.16 rad.

        >>> import warnings
        >>> t = np.linspace(0.0, 10.0, 11)
        >>> w = np.outer(10.0 + 10.0 * t, [0.0, 0.0, 1.0])
        >>> with warnings.catch_warnings(record=True) as caught:
        ...     warnings.simplefilter("always")
        ...     found = get("rk4").watch_step(Problem((1.0, 1.5, 2.0)), t, w, 0.01, 1000)
        >>> found[0], round(found[1].value, 2), "at t = 7 s" in str(caught[0].message)
        (7.0, 0.16, True)
        """
        if self.step_limit is None or problem.inertia is None or len(w) == 0:
            return None
        if not KINDS[problem.kind].judged:
            return None
        w = np.ascontiguousarray(np.asarray(w, dtype=np.float64)[:, :3])  # ω: see check_step
        candidates = watch_candidates(w, problem.inertia)
        for k in candidates:
            limit = self.step_limit(problem.inertia, w[k], h, nsteps)
            if limit.exceeded:
                from ..errors import StepLimitWarning

                warnings.warn(
                    f"{where}: {self.name} crosses its step limit at t = {float(t[k]):g} s: "
                    f"{limit.quantity} = {limit.value:.3g} (limit {limit.limit:g}) at that "
                    f"sample's ω: {limit.effect}; take a smaller step",
                    StepLimitWarning,
                    stacklevel=stacklevel,
                )
                return float(t[k]), limit
        return None

    def _validate_declaration(self) -> None:
        if not self.name or not self.name.replace("_", "").isalnum():
            raise InputError(f"integrator name: expected an identifier, got {self.name!r}")
        unknown = set(self.conserves) - PROPERTIES
        if unknown:
            raise InputError(f"{self.name}: unknown conserved properties {sorted(unknown)}")
        if not set(self.problems) <= set(KINDS):
            raise InputError(f"{self.name}: unknown problem kinds {sorted(self.problems)}")
        if self.step_limit_action not in ("warn", "raise"):
            raise InputError(
                f"{self.name}: step_limit_action must be 'warn' or 'raise', "
                f"got {self.step_limit_action!r}"
            )
        if self.torques not in TORQUE_SUPPORT:
            raise InputError(
                f"{self.name}: torques must be one of {TORQUE_SUPPORT}, got {self.torques!r}"
            )
        cost = getattr(self, "evaluations", None)
        if isinstance(cost, bool) or not isinstance(cost, int | float) or not cost > 0:
            raise InputError(
                f"{self.name}: evaluations (its cost per step, in vector-field evaluations) "
                f"must be a positive number, got {cost!r}"
            )
        if not isinstance(self.adaptive, bool):
            raise InputError(f"{self.name}: adaptive must be True or False, got {self.adaptive!r}")


def torque_conflict(integrator: Integrator, torques):
    """The first of ``torques`` that ``integrator`` cannot take at its order, or None.

    ``torques`` are :class:`TorqueTerm` objects (or anything with ``name`` and
    ``depends_on_omega``, as a scene describes its effects before building them).

    Examples
    --------
    >>> from ga_rotors.effects import gravity, isotropic_damping
    >>> drag = TorqueTerm(isotropic_damping, (0.1,))
    >>> torque_conflict(get("split2"), [drag]).name, torque_conflict(get("rk4"), [drag])
    ('isotropic_damping', None)
    >>> torque_conflict(get("split2"), [TorqueTerm(gravity, (0,) * 6, depends_on_omega=False)])
    """
    if integrator.torques == ANY_TORQUE or not ({TORQUED, MOTION} & integrator.problems):
        return None
    return next((t for t in torques if getattr(t, "depends_on_omega", None)
                 or getattr(t, "depends_on_velocity", False)), None)  # fmt: skip


def any_torque_methods() -> list[str]:
    """Registered methods that integrate any torque (ω-dependent ones too) at their order.

    Examples
    --------
    >>> "rk4" in any_torque_methods() and "split2" not in any_torque_methods()
    True
    """
    _load_builtins()
    return [
        n for n in sorted(_REGISTRY)
        if TORQUED in _REGISTRY[n].problems and _REGISTRY[n].torques == ANY_TORQUE
    ]  # fmt: skip


_REGISTRY: dict[str, Integrator] = {}
_loaded = False


def register(integrator: Integrator) -> Integrator:
    """Add ``integrator`` to the registry (names are unique) and return it.

    Examples
    --------
    Registering the same object again changes nothing; another under a taken name is refused:

    >>> import dataclasses
    >>> rk4 = get("rk4")
    >>> register(rk4) is rk4
    True
    >>> register(dataclasses.replace(rk4, description="my RK4"))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: register: an integrator named 'rk4' already exists
    """
    if not isinstance(integrator, Integrator):
        raise InputError(f"register: expected an Integrator, got {integrator!r}")
    existing = _REGISTRY.get(integrator.name)
    if existing is not None and existing is not integrator:
        raise InputError(f"register: an integrator named {integrator.name!r} already exists")
    _REGISTRY[integrator.name] = integrator
    return integrator


def _load_builtins() -> None:
    global _loaded
    if not _loaded:
        for module in BUILTIN_MODULES:
            importlib.import_module(module)
        _loaded = True


def get(name: str) -> Integrator:
    """The registered integrator called ``name``.

    Examples
    --------
    >>> get("rk4").order
    4
    >>> get("euler_forward")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: integrator: unknown integrator 'euler_forward'; expected one of ...
    """
    _load_builtins()
    try:
        return _REGISTRY[name]
    except (KeyError, TypeError):
        raise InputError(
            f"integrator: unknown integrator {name!r}; expected one of {', '.join(names())}"
        ) from None


def names() -> list[str]:
    """Names of all registered integrators, sorted.

    Examples
    --------
    >>> "rk4" in names()
    True
    """
    _load_builtins()
    return sorted(_REGISTRY)


def _limit_row(integrator: Integrator) -> str:
    """``"quantity < limit (action)"``, or ``"none"``."""
    if integrator.step_limit is None:
        return "none"
    lim = integrator.step_limit((1.0, 2.0, 3.0), (0.0, 0.0, 0.0), 0.0, 0)
    return f"{lim.quantity} < {lim.limit:g} ({integrator.step_limit_action})"


def catalogue() -> list[dict]:
    """One row per integrator: name, order, evaluations per step, conserves, problems,
    torques, paths, step limit, description.

    ``torques`` is ``"any"``, ``"orientation-only"`` (see :data:`ORIENTATION_TORQUES`),
    or ``"none"`` for a method without a torqued step.

    Examples
    --------
    >>> row = [r for r in catalogue() if r["name"] == "rk4_renorm"][0]
    >>> row["conserves"], row["paths"]
    (['unit_norm'], ['motor', 'quaternion', 'rotor'])
    """
    _load_builtins()
    return [
        {
            "name": i.name,
            "order": i.order,
            "evaluations": i.evaluations,
            "conserves": sorted(i.conserves),
            "problems": sorted(i.problems),
            "torques": i.torques if TORQUED in i.problems else "none",
            "paths": sorted(i.paths),
            "step_limit": _limit_row(i),
            "description": i.description,
        }
        for i in (_REGISTRY[n] for n in sorted(_REGISTRY))
    ]
