"""Whole rigid motion: the motor path against the quaternion path and a plain @njit RK4.

Run from the repository root, on a quiet machine::

    python benchmarks/bench_motion.py                 # 10**5 steps, 10**4 bodies, 9 rounds
    python benchmarks/bench_motion.py --quick         # small, 3 rounds, one thread: that it runs
    python benchmarks/bench_motion.py --cpu-time      # a shared machine: one thread, CPU time

The problem: a tennis racket thrown under gravity, spun at 12 rad/s near its middle axis,
its frame at the end of the handle, 0.15 m from the centre of mass (the coupling of
rotation and translation that motors carry). RK4 everywhere, compiled against compiled.

1. **One body, per step** (ns): ``Integrator.run``'s compiled loop (``bare_loop``: the
   loop alone, its arrays allocated before, as ``benchmarks/bench_overhead.py`` measures)
   on the motor path (the body frame's motor and velocity line, 8 + 6 numbers) and on the
   quaternion path (the quaternion and the centre of mass, 7 + 6), and a plain ``@njit``
   RK4 written as a user would write it on the same 13 states (q, c, ω, v_c: arrays,
   preallocated stages, one loop). Targets (issue 32): motor ≤ 1.5× quaternion per step;
   both ≤ 1.3× the plain RK4. The same motion once more on the motor path with its frame
   at the centre of mass (the common case: a single run binds the kernels without the
   lever's coupling terms), against the same two.
2. **Ensembles** (million body-steps per second, every core): a :class:`Batch` of bodies
   through ``Integrator.run`` (the batched loop ``ga_rotors.ensemble`` runs), each with its
   own start, on the motor path (frames at the handle, and at the centre of mass, which a
   batch of bodies all centred compiles without the lever's terms) and the quaternion
   path, against the rotational batches of the same bodies (what an ensemble ran before
   motion): turning freely, and turning under their weight about a pivot at the handle
   (a heavy top). Target: within 1.5× of the rotational body-steps/s.

Each candidate runs once per round, the rounds interleaved (other load hits all alike);
printed: median (min–max) over the rounds, and the ratios round by round, median
(min–max), each against its target (met or missed, by the median). Before timing,
every candidate's final state is checked against the motor path's (the same motion to the
integrator's error), so a fast wrong answer cannot enter the table.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ga_rotors import RigidBody  # noqa: E402
from ga_rotors import forces as F  # noqa: E402
from ga_rotors import quaternion as Q  # noqa: E402
from ga_rotors.integrators import Batch, Problem, TorqueTerm, get  # noqa: E402
from ga_rotors.integrators._runner import bare_loop  # noqa: E402
from ga_rotors.paths import resolve  # noqa: E402

RACKET, MASS, HANDLE = (0.011, 0.023, 0.031), 0.31, (0.0, 0.15, 0.0)
Q0, W0, P0, V0 = (1.0, 0.0, 0.0, 0.0), (0.05, 12.0, 0.1), (0.0, 0.0, 1.5), (3.0, 0.0, 5.0)
G = (0.0, 0.0, -F.STANDARD_GRAVITY)
H = 1e-5  # s: a long run of small steps, the loop's own cost dominating


# ----------------------------------------------------------------- the plain @njit peer


@numba.njit(cache=True)
def _field(y, out, inertia, g):
    """dy/dt of y = (q, c, ω, v_c), 13 numbers, written out plainly."""
    q0, q1, q2, q3 = y[0], y[1], y[2], y[3]
    w1, w2, w3 = y[7], y[8], y[9]
    i1, i2, i3 = inertia[0], inertia[1], inertia[2]
    out[0] = 0.5 * (-q1 * w1 - q2 * w2 - q3 * w3)
    out[1] = 0.5 * (q0 * w1 + q2 * w3 - q3 * w2)
    out[2] = 0.5 * (q0 * w2 + q3 * w1 - q1 * w3)
    out[3] = 0.5 * (q0 * w3 + q1 * w2 - q2 * w1)
    out[4], out[5], out[6] = y[10], y[11], y[12]
    out[7] = (i2 - i3) / i1 * w2 * w3
    out[8] = (i3 - i1) / i2 * w3 * w1
    out[9] = (i1 - i2) / i3 * w1 * w2
    out[10], out[11], out[12] = g[0], g[1], g[2]


@numba.njit(cache=True)
def njit_rk4(y0, h, n, inertia, g):
    """n classical RK4 steps of the thrown body from y0: the peer."""
    y = y0.copy()
    k1, k2, k3, k4, tmp = np.empty(13), np.empty(13), np.empty(13), np.empty(13), np.empty(13)
    for _ in range(n):
        _field(y, k1, inertia, g)
        for j in range(13):
            tmp[j] = y[j] + 0.5 * h * k1[j]
        _field(tmp, k2, inertia, g)
        for j in range(13):
            tmp[j] = y[j] + 0.5 * h * k2[j]
        _field(tmp, k3, inertia, g)
        for j in range(13):
            tmp[j] = y[j] + h * k3[j]
        _field(tmp, k4, inertia, g)
        for j in range(13):
            y[j] += h / 6.0 * (k1[j] + 2.0 * (k2[j] + k3[j]) + k4[j])
    return y


# ----------------------------------------------------------------- helpers


def race(candidates, rounds: int, clock=time.perf_counter) -> dict[str, list[float]]:
    """Seconds of each (name, fn) candidate: one call per round, rounds interleaved;
    ``clock``: wall time, or the process's CPU time (``time.process_time``) for loops
    in one thread on a machine other work shares."""
    for _, fn in candidates:
        fn()  # warm-up: compilation, caches
    times: dict[str, list[float]] = {name: [] for name, _ in candidates}
    for _ in range(rounds):
        for name, fn in candidates:
            t0 = clock()
            fn()
            times[name].append(clock() - t0)
    return times


def cell(values) -> str:
    return f"{statistics.median(values):8.1f} ({min(values):.1f}–{max(values):.1f})"


def ratio(times, a: str, b: str, target: float) -> str:
    """a's time over b's, round by round: the median (min–max) against the target."""
    r = [x / y for x, y in zip(times[a], times[b], strict=True)]
    met = "met" if statistics.median(r) <= target else "missed"
    return f"{statistics.median(r):.2f}× ({min(r):.2f}–{max(r):.2f})   target ≤ {target}×: {met}"


def _problem(centre_of_mass=HANDLE):
    body = RigidBody(RACKET, mass=MASS, centre_of_mass=centre_of_mass)
    return Problem(RACKET, mass=MASS, centre_of_mass=centre_of_mass,
                   forces=(F.uniform_gravity(body, G),))  # fmt: skip


def _start(path, q0=Q0, w0=W0, p0=P0, v0=V0):
    return resolve(path, moves=True).load().initial_state(np.asarray(q0), p0, w0, v0, HANDLE)


# ----------------------------------------------------------------- 1. one body

MOTOR, CENTRED, QUAT = "motor path", "motor path, frame at the centre", "quaternion path"
PEER = "plain @njit RK4, 13 states"


def one_body(steps: int, rounds: int, clock=time.perf_counter) -> None:
    rk4 = get("rk4")
    calls, finals = [], {}  # finals: the orientation and the centre of mass at the end
    x0, w0 = _start("quaternion")  # (q, c; ω, v_c): the centre of mass's own start
    module = resolve("motor", moves=True).load()
    for name, path, problem, start, s in (
        (MOTOR, "motor", _problem(), _start("motor"), HANDLE),
        (CENTRED, "motor", _problem((0.0, 0.0, 0.0)),
         module.initial_state(x0[:4], x0[4:], w0[:3], w0[3:], (0.0, 0.0, 0.0)), (0.0,) * 3),
        (QUAT, "quaternion", _problem(), (x0, w0), HANDLE),
    ):  # fmt: skip
        calls.append((name, bare_loop(rk4, problem, path, *start, 0.0, H, steps, steps)))
        end = rk4.run(problem, path, *start, 0.0, H, steps, steps).x[-1]
        turn = resolve(path, moves=True).load()
        q, origin = turn.quaternions(end), turn.positions(end, s)
        finals[name] = (q, origin + Q.rotate(Q.normalize(q), s))
    y0 = np.concatenate([x0, w0])
    inertia, g = np.array(RACKET), np.array(G)
    y = njit_rk4(y0, H, steps, inertia, g)
    finals[PEER] = (y[:4], y[4:7])
    for name, (q, c) in finals.items():  # the same motion, or not timed
        angle = Q.distance(Q.normalize(q), Q.normalize(finals[MOTOR][0]))
        gap = np.linalg.norm(c - finals[MOTOR][1])
        if not (angle < 1e-9 and gap < 1e-9):
            raise SystemExit(f"{name} disagrees with the motor path: {angle:.2g} rad, {gap:.2g} m")
    calls.append((PEER, lambda: njit_rk4(y0, H, steps, inertia, g)))
    times = race(calls, rounds, clock)
    ns = {k: [1e9 * t / steps for t in v] for k, v in times.items()}
    timed = "CPU time" if clock is time.process_time else "wall time"
    print(f"\n1. one body, RK4, {steps} steps of {H:g} s, {rounds} interleaved rounds, {timed}")
    print(f"  {'':34} {'ns/step, median (min–max)':>28}")
    for name in ns:
        print(f"  {name:34} {cell(ns[name]):>28}")
    print(f"  motor / quaternion path:       {ratio(times, MOTOR, QUAT, 1.5)}")
    print(f"  quaternion path / plain RK4:   {ratio(times, QUAT, PEER, 1.3)}")
    print(f"  motor path / plain RK4:        {ratio(times, MOTOR, PEER, 1.3)}")
    print("  the frame at the centre of mass (no lever: the common case):")
    print(f"  motor / quaternion path:       {ratio(times, CENTRED, QUAT, 1.5)}")
    print(f"  motor path / plain RK4:        {ratio(times, CENTRED, PEER, 1.3)}")


# ----------------------------------------------------------------- 2. ensembles


def ensembles(bodies: int, steps: int, rounds: int, parallel: bool = True,
              clock=time.perf_counter) -> None:  # fmt: skip
    rng = np.random.default_rng(1)
    q = Q.normalize(rng.normal(size=(bodies, 4)))
    w = np.array(W0) + 0.5 * rng.normal(size=(bodies, 3))
    p, v = np.array(P0) + rng.normal(size=(bodies, 3)), np.array(V0) + rng.normal(size=(bodies, 3))
    rk4 = get("rk4")
    calls = []
    for label, path, s in (("motion, motor path", "motor", HANDLE),
                           ("motion, motor path, at the centre", "motor", (0.0, 0.0, 0.0)),
                           ("motion, quaternion path", "quaternion", HANDLE)):  # fmt: skip
        problem, module = _problem(s), resolve(path, moves=True).load()
        starts = [module.initial_state(q[i], p[i], w[i], v[i], s) for i in range(bodies)]
        x0, r0 = np.array([a[0] for a in starts]), np.array([a[1] for a in starts])
        batch = Batch(problem, np.tile(problem.body, (bodies, 1)))
        args = (batch, path, x0, r0, 0.0, 1e-3, steps, steps)
        calls.append((label, lambda args=args: rk4.run(*args, parallel=parallel)))
    # the rotational batches of before: the same bodies turning freely, and turning under
    # the weight about a pivot at the handle (a heavy top: a torque of orientation)
    from ga_rotors.effects import gravity_kernel

    weight = (MASS * G[0], MASS * G[1], MASS * G[2], *HANDLE)
    heavy = Problem(RACKET, torques=(TorqueTerm(gravity_kernel(weight), weight,
                                                depends_on_omega=False),))  # fmt: skip
    for label, turning in (("rotation alone, free", Problem(RACKET)),
                           ("rotation alone, under gravity", heavy)):  # fmt: skip
        batch = Batch(turning, np.tile(RACKET, (bodies, 1)))
        calls.append((label, lambda b=batch: rk4.run(b, "quaternion", q, w, 0.0, 1e-3, steps,
                                                     steps, parallel=parallel)))  # fmt: skip
    times = race(calls, rounds, clock)
    rates = {k: [bodies * steps / t / 1e6 for t in v] for k, v in times.items()}
    threads = f"{numba.get_num_threads()} threads" if parallel else "one thread"
    if clock is time.process_time:
        threads += ", CPU time"
    print(f"\n2. ensembles, RK4, {bodies} bodies x {steps} steps, {rounds} interleaved rounds, "
          f"{threads}")  # fmt: skip
    print(f"  {'':34} {'M body-steps/s, median (min–max)':>34}")
    for name in rates:
        print(f"  {name:34} {cell(rates[name]):>34}")
    print("  motion's body-steps against rotation's (time ratios):")
    for label in ("motor path", "motor path, at the centre", "quaternion path"):
        for alone in ("free", "under gravity"):
            print(f"  {label} / rotation alone, {alone}:".ljust(62)
                  + ratio(times, f"motion, {label}", f"rotation alone, {alone}", 1.5))  # fmt: skip


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100_000, help="one body: steps")
    parser.add_argument("--bodies", type=int, default=10_000, help="ensembles: bodies")
    parser.add_argument("--ensemble-steps", type=int, default=1000, help="ensembles: steps")
    parser.add_argument("--rounds", type=int, default=9)
    parser.add_argument("--cpu-time", action="store_true",
                        help="every loop in one thread, timed by CPU time")  # fmt: skip
    parser.add_argument("--quick", action="store_true",
                        help="small sizes, 3 rounds, ensembles in one thread")  # fmt: skip
    a = parser.parse_args(argv)
    if a.quick:
        a.steps, a.bodies, a.ensemble_steps, a.rounds = 2000, 256, 20, 3
    for name, value, top in (("--steps", a.steps, 10**8), ("--bodies", a.bodies, 10**7),
                             ("--ensemble-steps", a.ensemble_steps, 10**6),
                             ("--rounds", a.rounds, 1000)):  # fmt: skip
        if not 1 <= value <= top:
            parser.error(f"{name} must be in 1..{top}, got {value}")
    clock = time.process_time if a.cpu_time else time.perf_counter
    one_body(a.steps, a.rounds, clock)
    # quick mode runs the batches in the calling thread: the suite compiles those loops
    # for its own tests already, and a parallel loop takes longer to compile; CPU time
    # (a machine other work shares) counts one thread's work, not the threads' waiting
    ensembles(a.bodies, a.ensemble_steps, a.rounds, not (a.quick or a.cpu_time), clock)
    return 0


if __name__ == "__main__":
    sys.exit(main())
