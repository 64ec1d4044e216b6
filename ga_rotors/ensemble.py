"""Ensembles: many variations of a scene at once, on every core.

:func:`scene_samples` and :func:`run_samples` integrate n variations of a scene (per-sample
inertia, initial state and parameters of the declared effects) with the scene's own
integrator and step, and return the states at chosen times, in the scene's body frame;
each sample equals the single run of the same body and start bit for bit. A scene whose
body moves through space (``scene.moves``: a thrown racket, a satellite) runs the same
way on the motion kind's batched loop, with per-sample mass, centre of mass, position,
velocity and force parameters, and answers the body origin's position and velocity too. The batched
loop is the integrators' own (:meth:`ga_rotors.integrators.Integrator.run` on a
:class:`~ga_rotors.integrators.Batch`: the single run's step compiled inline in a batched
loop template, struct-of-arrays, L1-sized chunks spread over the cores).

:func:`rk4_free` is the torque-free RK4 with one shared inertia that ``ga-rotors bench
ensemble`` measures, the raw kernel a scene's batch is measured against
(``benchmarks/bench_ensemble.py``): struct-of-arrays layout (``q`` of shape (4, n), ``w``
of shape (3, n)), the innermost loop over bodies so LLVM turns each RK4 stage into SIMD
arithmetic across 4 bodies at a time, chunks small enough to stay in the L1 cache
(256 bodies × 7 doubles = 14 KB), each chunk taking all its steps before the next, chunks
distributed over the cores with ``prange``. Its arithmetic is the package's kernels — q̇
from :func:`ga_rotors.paths.quaternion.rate`, ω̇ from
:func:`ga_rotors._kernels.free_euler_rates` (inertia ratios hoisted out of the loops),
and the RK4 combinations of :mod:`ga_rotors.integrators._arith` — compiled inline
(:func:`ga_rotors._jit.inline`), so a body follows exactly the trajectory of
``get("rk4")`` on the quaternion path, bit for bit.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from math import isfinite

import numba
import numpy as np
from numba import prange

from ._jit import inline, jit
from ._kernels import free_euler_rates
from .body import MIN_MOMENT_RATIO
from .errors import InputError
from .integrators._arith import axpy3, axpy4, rk4_sum3, rk4_sum4
from .integrators._runner import BATCH_CHUNK as CHUNK
from .paths.quaternion import rate

__all__ = [
    "CHUNK",
    "FAST_KEYS",
    "EnsembleRun",
    "SceneSamples",
    "benchmark",
    "rk4_free",
    "run_samples",
    "scene_samples",
]


_rate = inline(rate)
_accel = inline(free_euler_rates)
_axpy3, _axpy4 = inline(axpy3), inline(axpy4)
_sum3, _sum4 = inline(rk4_sum3), inline(rk4_sum4)


@numba.njit(inline="always", error_model="numpy")
def _rk4_body(x, v, h, inertia):
    """One RK4 step of one torque-free body: the operations of ``rk4_step`` on the
    quaternion path, in the same order, so results agree bit for bit."""
    half = 0.5 * h
    k1x = _rate(x, v)
    k1w = _accel(inertia, v)
    x2 = _axpy4(x, half, k1x)
    w2 = _axpy3(v, half, k1w)
    k2x = _rate(x2, w2)
    k2w = _accel(inertia, w2)
    x3 = _axpy4(x, half, k2x)
    w3 = _axpy3(v, half, k2w)
    k3x = _rate(x3, w3)
    k3w = _accel(inertia, w3)
    x4 = _axpy4(x, h, k3x)
    w4 = _axpy3(v, h, k3w)
    k4x = _rate(x4, w4)
    k4w = _accel(inertia, w4)
    return _sum4(x, h, k1x, k2x, k3x, k4x), _sum3(v, h, k1w, k2w, k3w, k4w)


@jit
def _rk4_chunk(q, w, lo, hi, inertia, h, nsteps):
    """Bodies lo..hi-1 through all steps; the inner loop over bodies vectorises."""
    q0, q1, q2, q3 = q[0, lo:hi], q[1, lo:hi], q[2, lo:hi], q[3, lo:hi]
    w0, w1, w2 = w[0, lo:hi], w[1, lo:hi], w[2, lo:hi]
    for _ in range(nsteps):
        for i in range(hi - lo):
            x, v = _rk4_body((q0[i], q1[i], q2[i], q3[i]), (w0[i], w1[i], w2[i]), h, inertia)
            q0[i] = x[0]
            q1[i] = x[1]
            q2[i] = x[2]
            q3[i] = x[3]
            w0[i] = v[0]
            w1[i] = v[1]
            w2[i] = v[2]


@jit(parallel=True)
def _rk4_soa(q, w, inertia, h, nsteps, chunk):
    n = q.shape[1]
    nchunks = (n + chunk - 1) // chunk
    for c in prange(nchunks):
        lo = c * chunk
        _rk4_chunk(q, w, lo, min(n, lo + chunk), inertia, h, nsteps)


def rk4_free(inertia, q, w, h: float, nsteps: int, chunk: int = CHUNK) -> None:
    """Advance n torque-free bodies ``nsteps`` RK4 steps of size ``h``, in place.

    Parameters
    ----------
    inertia : tuple of 3 floats
        Principal moments, shared by all bodies.
    q : ndarray, shape (4, n), float64, C-contiguous
        Orientations (scalar first), one column per body; overwritten.
    w : ndarray, shape (3, n), float64, C-contiguous
        Body angular velocities; overwritten.

    Examples
    --------
    >>> q = np.tile([[1.0], [0.0], [0.0], [0.0]], (1, 3))
    >>> w = np.tile([[0.0], [0.0], [2.0]], (1, 3))
    >>> rk4_free((1.0, 2.0, 3.0), q, w, 0.01, 100)
    >>> bool(np.allclose(q[:, 0], (np.cos(1.0), 0, 0, np.sin(1.0)), atol=1e-9))
    True
    """
    for name, a, rows in (("q", q, 4), ("w", w, 3)):
        if not (isinstance(a, np.ndarray) and a.dtype == np.float64 and a.ndim == 2
                and a.shape[0] == rows and a.flags.c_contiguous):  # fmt: skip
            raise InputError(f"{name}: expected a C-contiguous float64 array of shape ({rows}, n)")
    if q.shape[1] != w.shape[1]:
        raise InputError(
            f"q, w: expected the same number of bodies, got {q.shape[1]}, {w.shape[1]}"
        )
    _rk4_soa(q, w, tuple(float(i) for i in inertia), float(h), int(nsteps), int(chunk))


#: Bytes of arrays and body-steps a repeat that :func:`benchmark` takes at most: a
#: benchmark's size is a number typed on a command line, refused when absurd.
BENCHMARK_MEMORY = 2 * 2**30
BENCHMARK_BODY_STEPS = 10**10


def benchmark(bodies: int = 10_000, steps: int = 1000, repeats: int = 5) -> str:
    """Body-steps per second of :func:`rk4_free` (minimum time of repeats after a warm-up).

    ``ga-rotors bench ensemble`` prints this line (10,000 bodies × 1,000 steps by default).

    Examples
    --------
    >>> print(benchmark(bodies=64, steps=10, repeats=1))
    RK4 ensemble: 64 bodies x 10 steps in ... ms (min of 1) = ... million body-steps/s on ...
    >>> benchmark(bodies=-5)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: bodies: expected a positive integer, got -5
    """
    import time

    for name, value in (("bodies", bodies), ("steps", steps), ("repeats", repeats)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise InputError(f"expected a positive integer, got {value!r}", key=name)
    arrays = bodies * 7 * 8 * 2  # q and ω, and the copies each repeat runs on
    if arrays > BENCHMARK_MEMORY:
        raise InputError(
            f"{bodies:.3g} bodies need {arrays / 2**30:.3g} GiB of arrays "
            f"(at most {BENCHMARK_MEMORY / 2**30:g} GiB)",
            key="bodies",
        )
    if bodies * steps > BENCHMARK_BODY_STEPS:
        raise InputError(
            f"{bodies:.3g} bodies x {steps:.3g} steps is {bodies * steps:.3g} body-steps a "
            f"repeat, {repeats + 1} times (at most {BENCHMARK_BODY_STEPS:.3g}: about half a "
            "minute each on two cores)",
            key="steps",
        )
    rng = np.random.default_rng(1)
    q = rng.normal(size=(4, bodies))
    q /= np.linalg.norm(q, axis=0)
    w = rng.normal(size=(3, bodies))
    inertia = (1.0, 2.0, 3.0)
    rk4_free(inertia, q.copy(), w.copy(), 1e-3, 2)  # warm-up and JIT
    best = float("inf")
    for _ in range(repeats):
        qa, wa = q.copy(), w.copy()
        t0 = time.perf_counter()
        rk4_free(inertia, qa, wa, 1e-3, steps)
        best = min(best, time.perf_counter() - t0)
    rate_ = bodies * steps / best
    return (
        f"RK4 ensemble: {bodies} bodies x {steps} steps in {best * 1e3:.1f} ms "
        f"(min of {repeats}) = {rate_ / 1e6:.0f} million body-steps/s "
        f"on {numba.get_num_threads()} threads"
    )


@dataclass
class SceneSamples:
    """Per-sample inputs of a scene ensemble; states in the scene's body frame.

    ``inertia`` (n, 3) principal moments, ``orientation`` (n, 4) and ``angular_velocity``
    (n, 3) the initial state in the frame the scene gives the body in (body -> space
    quaternion, body-frame ω), ``params`` (n, P) the packed parameters of the declared
    torques (their vectors in the principal frame, where the kernels act), ``principal``
    (n, 4) the rotation P from principal to the scene's body axes (identity unless the
    scene gives a full inertia tensor), with which :func:`run_samples` turns the states
    into the principal frame and back. ``kernels`` (n,) says which
    of ``terms`` sample i's torques are: the samples' values may give one effect different
    kernels (a heavy top whose lever leaves the symmetry axis in some samples only runs
    the general gravity there, :func:`ga_rotors.effects.gravity_kernel`), and each sample
    runs its own single run's kernels, one batch per distinct set. By default one set,
    the scene's. For a scene whose body moves through space (``scene.moves``), ``terms``
    hold its torques then its forces (:class:`~ga_rotors.integrators.ForceTerm`, their
    parameters packed after the torques' in ``params``), ``motion`` (n, 4) the mass and
    the centre of mass (principal axes, from the body-frame origin: the rows the motion
    kind's loop reads after the moments) and ``position``, ``velocity`` (n, 3) the body
    origin's start in space; all three are None for a body turning about a fixed point.
    :func:`scene_samples` stores each array one row per component (the
    transpose of a C-contiguous (k, n) array, the layout the batched loops read), so
    :func:`run_samples` hands them over without copying.

    Examples
    --------
    >>> s = scene_samples("heavy_top", n=2)
    >>> s.inertia[0].tolist(), s.params.shape  # the gravity term's 6 parameters
    ([0.002225, 0.002225, 0.00125], (2, 6))
    """

    scene: object
    inertia: np.ndarray
    orientation: np.ndarray
    angular_velocity: np.ndarray
    params: np.ndarray
    principal: np.ndarray
    terms: tuple = None
    kernels: np.ndarray = None
    motion: np.ndarray | None = None
    position: np.ndarray | None = None
    velocity: np.ndarray | None = None

    def __post_init__(self):
        if self.terms is None:
            self.terms = (_terms(self.scene),)
        if self.kernels is None:
            self.kernels = np.zeros(len(self), dtype=np.int64)

    def __len__(self) -> int:
        return self.inertia.shape[0]


#: Keys whose per-sample values map to the kernel's inputs without building a scene per
#: sample (checked against a full Scene on the first and last samples before use).
#: ``body.moments`` on a body turning about a fixed point only: a moving body's forces may
#: read its moments (the central field's gravity-gradient torque).
FAST_KEYS = ("body.moments", "initial.angular_velocity.body", "initial.position",
             "initial.velocity")  # fmt: skip

#: (id(scene), keys) -> scene, for the scene and keys whose fast mapping was checked.
_CHECKED: dict = {}

_ELEMENT = re.compile(r"^(?P<key>.*)\[(?P<index>[0-2])\]$")

#: The fast keys' targets: the moments, the body rate, the position, the velocity.
_MOMENTS, _RATE, _POSITION, _VELOCITY = range(4)


def _fast_targets(scene, keys) -> list | None:
    """For each key, (which of the :data:`FAST_KEYS` targets, component or None for all
    three, scale): the vectorised mapping; None when a key needs a Scene per sample."""
    d = scene.data
    if scene.principal_rotation != (1.0, 0.0, 0.0, 0.0) or scene.gravity_index is not None:
        return None
    initial = d["initial"]
    av = initial["angular_velocity"]
    out = []
    for key in keys:
        m = _ELEMENT.match(key)
        base, index = (m["key"], int(m["index"])) if m else (key, None)
        if base == "body.moments" and "moments" in d["body"] and not scene.moves:
            out.append((_MOMENTS, index, 1.0))
        elif base == "initial.angular_velocity.body" and "body" in av:
            from .scene.schema import RATE_UNITS

            out.append((_RATE, index, RATE_UNITS[av["units"]]))
        elif base in ("initial.position", "initial.velocity") and scene.moves:
            if base.split(".")[1] not in initial:
                return None
            out.append((_POSITION if base == "initial.position" else _VELOCITY, index, 1.0))
        else:
            return None
    return out


def _fast(scene, changes: dict, n: int):
    """Vectorised inputs (moments, rate, position, velocity; the last two None for a body
    turning about a fixed point), or None when a key needs a Scene per sample."""
    targets = _fast_targets(scene, changes)
    if targets is None:
        return None
    arrays = [_repeat(scene.body.moments, n), _repeat(scene.angular_velocity, n), None, None]
    if scene.moves:
        arrays[_POSITION], arrays[_VELOCITY] = (
            _repeat(scene.position, n),
            _repeat(scene.velocity, n),
        )
    for values, (which, index, scale) in zip(changes.values(), targets, strict=True):
        target = arrays[which]
        if index is None:
            target[:] = values.reshape(n, 3) * scale
        else:
            target[:, index] = values.reshape(n) * scale
    if _refused(arrays[_MOMENTS], arrays[_RATE], np.finfo(float).tiny, MIN_MOMENT_RATIO):
        return None  # let the per-sample path name the bad value
    from .scene.model import MAX_TURN_PER_STEP  # the scene's limit (scene imports this module)

    w = arrays[_RATE]
    rate = np.hypot(np.hypot(w[:, 0], w[:, 1]), w[:, 2])  # no square to overflow
    with np.errstate(over="ignore"):  # an overflow is what is being tested for
        momentum = arrays[_MOMENTS].max(axis=1) * rate
        turn = rate * scene.data["integrator"]["step"]
        beyond = ~((momentum * momentum * 16.0 < np.finfo(float).max)
                   & (turn <= MAX_TURN_PER_STEP))  # fmt: skip
    if beyond.any():
        return None  # the scene's own magnitude checks, per sample, name it
    if scene.moves:
        p, v = arrays[_POSITION], arrays[_VELOCITY]
        energy = 0.5 * scene.mass * np.einsum("ij,ij->i", v, v) * 16.0  # as the scene's check
        if not (np.isfinite(p).all() and (energy < np.finfo(float).max).all()):
            return None
    return tuple(arrays)


@numba.njit(inline="always", error_model="numpy")
def _refused_one(m, v, tiny, ratio):
    """Whether the moments ``m`` and rate ``v`` of a sample are not finite, or the moments
    may be refused: not normal floats, too thin a body, outside the triangle (the body's
    own conditions). Every condition evaluated, without a branch (see :func:`_refused`)."""
    a, b, c = m
    w0, w1, w2 = v
    finite = (isfinite(a) & isfinite(b) & isfinite(c)
              & isfinite(w0) & isfinite(w1) & isfinite(w2))  # fmt: skip
    s = a + b + c
    lo, hi = min(a, min(b, c)), max(a, max(b, c))
    thin = (lo < tiny) | (hi > 1.0 / tiny) | (lo / hi < ratio)  # as the body's
    outside = (a > s - a) | (b > s - b) | (c > s - c)
    return (not finite) | thin | outside


@jit
def _refused(moments, omega, tiny, ratio):
    """Whether a sample's values are not finite, or its moments may be refused.

    Any sample the body's own checks might refuse goes to the per-sample path, which
    names it: moments not normal floats, too thin a body, outside the triangle. One pass
    over the samples: the same conditions as numpy expressions made about fifteen
    chunk-sized temporaries (1 ms of a 65,536-sample chunk's 2.5 ms of inputs, measured).
    Every condition of every sample is evaluated and counted, without a branch: the
    loop then runs on vector instructions (0.22 -> 0.10 ms a chunk, measured), where a
    return at the first refused sample kept it one sample at a time.
    """
    refused = 0
    for i in range(moments.shape[0]):
        m = (moments[i, 0], moments[i, 1], moments[i, 2])
        refused += _refused_one(m, (omega[i, 0], omega[i, 1], omega[i, 2]), tiny, ratio)
    return refused > 0


def scene_samples(scene, changes=None, n: int | None = None) -> SceneSamples:
    """Per-sample kernel inputs for ``scene`` with some keys changed per sample.

    Parameters
    ----------
    scene : Scene or str or path
    changes : mapping of dotted key -> array of n values, optional
        Key paths as :meth:`Scene.replace` takes them (``body.moments``,
        ``initial.angular_velocity.body[2]``, ``effects[0].coefficient``...), each with one
        value per sample along its first axis. Keys in :data:`FAST_KEYS` on a scene with a
        diagonal inertia and no gravity are mapped in one vectorised pass; any other key
        builds (and so validates) the scene once per sample.
    n : int, optional
        Number of samples when ``changes`` is empty (all samples are the scene itself).

    Examples
    --------
    >>> s = scene_samples("intermediate_axis_flip", {"initial.angular_velocity.body[1]":
    ...                                             [10.0, 10.5, 11.0]})
    >>> len(s), s.inertia.shape, s.params.shape, s.angular_velocity[:, 1].tolist()
    (3, (3, 3), (3, 0), [10.0, 10.5, 11.0])
    >>> g = scene_samples("heavy_top", {"body.mass": [1.0, 2.0]})  # a scene per sample
    >>> g.params[:, 2].tolist()  # the weight m g along z, in the torque's parameters
    [-9.80665, -19.6133]
    """
    from .scene import load_scene

    scene = load_scene(scene)
    changes = {k: np.asarray(v, dtype=np.float64) for k, v in (changes or {}).items()}
    sizes = {k: v.shape[0] if v.ndim else None for k, v in changes.items()}
    if any(s is None for s in sizes.values()):
        raise InputError(f"changes: expected one value per sample for every key, got {sizes}")
    counts = set(sizes.values()) | ({int(n)} if n is not None else set())
    if len(counts) != 1:
        raise InputError(f"changes: keys and n give different numbers of samples: {sizes}, {n}")
    count = counts.pop()
    base_params = _params(scene)
    fast = _fast(scene, changes, count) if changes else None
    checked = (id(scene), tuple(changes))
    if fast is not None and _CHECKED.get(checked) is not scene:
        moments, omega, position, velocity = fast
        for i in {0, count - 1}:  # the vectorised mapping must equal the scene's own
            one = _sample_scene(scene, changes, i)
            same = (tuple(moments[i]) == one.body.moments
                    and np.array_equal(omega[i], one.angular_velocity))  # fmt: skip
            if scene.moves:
                same = (same and np.array_equal(position[i], one.position)
                        and np.array_equal(velocity[i], one.velocity)
                        and np.array_equal(_params(one), base_params))  # fmt: skip
            if not same:
                fast = None
                break
        else:
            _CHECKED[checked] = scene  # once per scene and keys: chunks of a sweep reuse it
    if fast is not None or not changes:
        q_body, w_body = _body_frame(scene)
        moments, omega, position, velocity = fast or (
            _repeat(scene.body.moments, count), _repeat(w_body, count),
            *((_repeat(scene.position, count), _repeat(scene.velocity, count))
              if scene.moves else (None, None)),
        )  # fmt: skip
        return SceneSamples(
            scene,
            moments,
            np.tile(q_body, (count, 1)),  # by row: renormalised by row in run_samples
            omega,
            _repeat(base_params, count),
            _repeat(scene.principal_rotation, count),
            motion=_repeat(_motion_rows(scene), count) if scene.moves else None,
            position=position,
            velocity=velocity,
        )
    inertia, q0, w0 = _columns(count, 3), np.empty((count, 4)), _columns(count, 3)
    params, principal = _columns(count, base_params.size), _columns(count, 4)
    motion = position = velocity = None
    if scene.moves:
        motion, position, velocity = _columns(count, 4), _columns(count, 3), _columns(count, 3)
    names = [t.name for t in _terms(scene)]
    sets: dict[tuple, int] = {}  # the samples' kernels (as a tuple) -> index in terms
    terms, kernels = [], np.empty(count, dtype=np.int64)
    for i in range(count):
        one = _sample_scene(scene, changes, i)
        own = _terms(one)
        if [t.name for t in own] != names:
            raise InputError(f"sample {i}: changes the scene's declared effects {names}")
        key = tuple(t.kernel for t in own)
        if key not in sets:
            sets[key] = len(terms)
            terms.append(own)
        kernels[i] = sets[key]
        for shared in ("time", "integrator"):
            if one.data[shared] != scene.data[shared]:
                raise InputError(
                    f"sample {i}: changes {shared}.*; every sample of an ensemble shares the "
                    "scene's time grid and integrator"
                )
        inertia[i], (q0[i], w0[i]) = one.body.moments, _body_frame(one)
        params[i], principal[i] = _params(one), one.principal_rotation
        if scene.moves:
            motion[i], position[i], velocity[i] = _motion_rows(one), one.position, one.velocity
    return SceneSamples(scene, inertia, q0, w0, params, principal, tuple(terms), kernels,
                        motion, position, velocity)  # fmt: skip


def _terms(scene) -> tuple:
    """The scene's declared terms as a batch's problem takes them: its torques, then (for a
    body moving through space) its forces."""
    return (*scene.torques(), *scene.forces()) if scene.moves else tuple(scene.torques())


def _motion_rows(scene) -> tuple[float, ...]:
    """The mass and centre of mass (principal axes) of a moving scene's body, as the
    motion kind's loop reads them after the moments (``Problem.body``)."""
    return _problem(scene, _terms(scene)).body[3:]


def _body_frame(scene) -> tuple[np.ndarray, np.ndarray]:
    """The scene's initial orientation and body ω in the frame it gives the body in: as
    the Scene holds them (its ``principal_orientation`` and ``principal_angular_velocity``
    are the principal frame's, which run_samples converts to as simulate does)."""
    return scene.orientation, scene.angular_velocity


def _repeat(values, n: int) -> np.ndarray:
    """``values`` once per sample, shape (n, k), stored one row per component: the
    layout the batched loops read (run_samples then passes each row without a copy)."""
    return np.repeat(np.asarray(values, dtype=np.float64).reshape(-1, 1), n, axis=1).T


def _columns(n: int, k: int) -> np.ndarray:
    """An uninitialised (n, k) array stored as _repeat's."""
    return np.empty((k, n)).T


def _sample_scene(scene, changes: dict, i: int):
    """The scene with sample i's values; a bad value is named by its sample and key."""
    from .errors import SceneError

    try:
        return scene.replace({k: v[i].tolist() for k, v in changes.items()})
    except SceneError as exc:
        message = str(exc).removeprefix(f"{exc.file}: {exc.key}: " if exc.key else "")
        raise SceneError(exc.file, exc.key, f"sample {i}: {message}") from None


def _params(scene) -> np.ndarray:
    return _problem(scene, _terms(scene)).params()


@dataclass
class EnsembleRun:
    """States of every sample at chosen times, in the scene's body frame.

    The frame the scene gives the body in (for a full inertia ``tensor``, the tensor's
    frame), as :func:`~ga_rotors.simulation.simulate` answers: never the principal frame
    the loop integrates in (``SceneSamples.principal``).

    Examples
    --------
    >>> run = run_samples(scene_samples("heavy_top", n=4), times=[0.001, 0.002])
    >>> run.t.tolist(), run.q.shape, run.w.shape
    ([0.001, 0.002], (2, 4, 4), (2, 4, 3))

    ``t`` (k,) the times, ``q`` (k, n, 4) orientations (w, x, y, z), ``w`` (k, n, 3) body
    angular velocities; a sample whose state stopped being finite holds NaN from then on.
    For a body moving through space, ``position`` and ``velocity`` (k, n, 3): the body
    origin's, in space (as ``Trajectory.positions()`` and ``velocities()``); else None.
    """

    t: np.ndarray
    q: np.ndarray
    w: np.ndarray
    position: np.ndarray | None = None
    velocity: np.ndarray | None = None


def run_samples(
    samples: SceneSamples, times=None, *, chunk: int = CHUNK, parallel: bool = True
) -> EnsembleRun:
    """Integrate every sample with the scene's integrator, step and declared effects.

    Each batch of samples runs through :meth:`ga_rotors.integrators.Integrator.run` on a
    :class:`~ga_rotors.integrators.Batch`, whose loop takes the very step a single run
    compiles, so sample i equals the single run of the scene with sample i's values
    (``simulate`` of its body and start) at the same times, bit for bit. States go in and
    come out in the scene's body frame: for a body given by a full inertia tensor, they
    are turned into its principal frame (``samples.principal``) for the integration and
    back, as a single run turns them.

    Parameters
    ----------
    samples : SceneSamples
        From :func:`scene_samples`.
    times : sequence of float, optional
        Output times (absolute, as the scene's ``time.start``), each on the step grid;
        default: the end of the run.
    chunk : int
        Samples per chunk of the loop (each chunk takes all its steps before the next).
    parallel : bool
        Spread the chunks over numba's threads (default), or run them in the calling
        thread (for several concurrent calls in one process).

    Examples
    --------
    >>> s = scene_samples("intermediate_axis_flip", n=2)
    >>> run = run_samples(s, times=[0.5, 1.0])
    >>> run.q.shape, run.t.tolist(), bool(np.array_equal(run.q[:, 0], run.q[:, 1]))
    ((2, 2, 4), [0.5, 1.0], True)
    """
    from . import quaternion as Q
    from ._validate import require_unit
    from .integrators import Batch

    scene = samples.scene
    method, path, module = _method_and_path(scene)
    t0, h, nsteps = scene.data["time"]["start"], scene.step, scene.steps
    marks = _marks(times, t0, h, nsteps, scene.file)
    principal = samples.principal
    turned = not np.all(principal == (1.0, 0.0, 0.0, 0.0))
    # renormalised as a single run renormalises its start: by row (C-contiguous, as one
    # quaternion's is), or once when every sample starts from the same one (the usual case)
    q0 = np.ascontiguousarray(samples.orientation)
    if len(q0) and (q0 == q0[0]).all():
        q0 = np.broadcast_to(require_unit(q0[0], "orientation"), q0.shape)
    else:
        q0 = require_unit(q0, "orientation")
    w0 = samples.angular_velocity
    if turned:  # into the principal frame the loops integrate in: q ⊗ P, P* ω P
        q0, w0 = Q.multiply(q0, principal), Q.rotate(Q.conjugate(principal), w0)
    moves = samples.motion is not None
    if moves:
        x0, w0 = _motion_starts(module, q0, w0, samples)
        body = np.ascontiguousarray(np.hstack([samples.inertia, samples.motion]))
    else:
        x0, body = module.initial_state(q0), samples.inertia
    if len(samples.terms) == 1:
        batch = Batch(_problem(scene, samples.terms[0]), body, samples.params)
        run = method.run(batch, path, x0, w0, t0, h, nsteps, marks, chunk=chunk,
                         parallel=parallel)  # fmt: skip
        out_x, out_w = run.x, run.w
    else:  # one batch per set of kernels, their samples gathered and scattered back
        n = len(samples)
        out_x = np.empty((marks.size, n, x0.shape[1]))
        out_w = np.empty((marks.size, n, w0.shape[1]))
        for k, terms in enumerate(samples.terms):
            mine = np.flatnonzero(samples.kernels == k)
            batch = Batch(_problem(scene, terms), body[mine], samples.params[mine])
            run = method.run(batch, path, x0[mine], w0[mine], t0, h, nsteps, marks,
                             chunk=chunk, parallel=parallel)  # fmt: skip
            out_x[:, mine], out_w[:, mine] = run.x, run.w
    position = velocity = None
    if moves:  # the body origin's, in space, as a single run's trajectory reads them
        com = samples.motion[:, 1:]
        position, velocity = module.positions(out_x, com), module.velocities(out_x, out_w, com)
        out_w = out_w[..., :3]
        if turned:
            out_x = module.to_user_frame(out_x, principal)
    q, w = module.quaternions(out_x), out_w
    if turned:  # back to the scene's body axes: q_P ⊗ P*, P ω_P P*
        if not moves:
            q = Q.multiply(q, Q.conjugate(principal))
        w = Q.rotate(principal, w)
    return EnsembleRun(t0 + marks * h, np.ascontiguousarray(q), np.ascontiguousarray(w),
                       position, velocity)  # fmt: skip


def _motion_starts(module, q0, w0, samples):
    """The motion path's start (x, rates) of each sample: the path's ``initial_state`` on
    rows of samples (its arithmetic is elementwise, so each row is a single run's start)."""
    com = samples.motion[:, 1:]
    q0, w0 = np.broadcast_to(q0, (len(samples), 4)), np.ascontiguousarray(w0)
    x, r = module.initial_state(q0, samples.position, w0, samples.velocity, com)
    return np.ascontiguousarray(x), np.ascontiguousarray(r)


def _method_and_path(scene):
    """The scene's integrator, first path and that path's module, as an ensemble runs them."""
    from .integrators import TemplateIntegrator, base
    from .paths import get as get_path

    spec_method = scene.data["integrator"]
    method = base.get(spec_method["method"])
    if not isinstance(method, TemplateIntegrator):
        raise InputError(
            f"{scene.file}: integrator.method: ensembles run fixed-step methods; "
            f"{spec_method['method']!r} is adaptive"
        )
    path = scene.paths[0]
    if scene.moves:  # the path's whole-motion variant (the motor, or q and the centre of mass)
        from .paths import resolve

        return method, path, resolve(path, moves=True).load()
    pspec = get_path(path)
    if not pspec.on_unit_sphere:
        raise InputError(
            f"{scene.file}: integrator.paths: ensembles integrate the quaternion or rotor "
            f"path; the scene's first path is {path!r}"
        )
    return method, path, pspec.load()


def _problem(scene, terms):
    """The integrator's problem for a batch of the scene's samples with these terms (for a
    body moving through space, its torques and forces, its mass and centre of mass in the
    principal axes, as :func:`~ga_rotors.simulation.simulate` makes it)."""
    from .integrators import base

    lower = scene.data["integrator"].get("accept_lower_order", False)
    if not scene.moves:
        return base.problem_for(scene.body.moments, terms, lower)
    body = scene.body
    forces = tuple(t for t in terms if isinstance(t, base.ForceTerm))
    torques = tuple(t for t in terms if not isinstance(t, base.ForceTerm))
    return base.problem_for(body.moments, torques, lower, mass=body.mass, forces=forces,
                            centre_of_mass=body.to_principal_axes(body.centre_of_mass))  # fmt: skip


def _marks(times, t0: float, h: float, nsteps: int, file: str) -> np.ndarray:
    """Step indices of the output times (each a whole number of steps from t0)."""
    if times is None:
        return np.array([nsteps], dtype=np.int64)
    t = np.atleast_1d(np.asarray(times, dtype=np.float64))
    k = np.rint((t - t0) / h)
    bad = (np.abs(k * h + t0 - t) > 1e-9 * max(1.0, abs(t0) + nsteps * h)) | (k < 0) | (k > nsteps)
    if t.ndim != 1 or np.any(bad) or np.any(np.diff(k) <= 0):
        raise InputError(
            f"{file}: times: expected increasing times on the step grid t0 + k·{h!r} s "
            f"within the run, got {t.tolist()}"
        )
    return k.astype(np.int64)
