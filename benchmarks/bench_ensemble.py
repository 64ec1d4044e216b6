"""Ensembles and sweeps: the batched kernels, and what a sweep adds on top of them.

Usage (from the repository root)::

    python benchmarks/bench_ensemble.py [--bodies 100000] [--steps 200] [--repeats 5]
                                        [--sweep-samples 1000000] [--sweep-steps 100]

1. Kernel throughput in million body-steps per second, RK4, rows interleaved in each
   repeat (median, min–max): ``rk4_free`` (torque-free, one inertia shared by every body:
   the old ensemble), ``run_samples`` on a torque-free scene with per-sample inertia and
   initial rate, and ``run_samples`` on the heavy top (gravity, per-sample torque
   parameters). Threads: numba's default (every core).
2. Sweep overhead: one Monte-Carlo sweep of ``--sweep-samples`` samples run end to end
   with ``run_sweep`` on a LocalCluster (one worker process per core) into a zarr store,
   against the raw batched kernel on the same samples (``run_samples`` on every core, the
   draws made beforehand). Cluster start-up and imports (xarray, zarr, Dask: a fixed cost
   per process) are reported apart; the store's creation and every chunk's integration,
   reduction and write are in the sweep's time. The same sweep run in this process
   (``client="sync"``) against the serial kernel separates the sweep's own work from
   Dask's scheduling.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ga_rotors.ensemble import rk4_free, run_samples, scene_samples  # noqa: E402
from ga_rotors.scene import load_scene  # noqa: E402

FREE = {"integrator.paths": ["quaternion"], "body": {"moments": [900.0, 950.0, 1100.0]},
        "initial.angular_velocity": {"body": [0.002, 0.001, 0.5236], "units": "rad/s"}}  # fmt: skip


def _scene(name: str, steps: int, extra: dict | None = None):
    h = 0.01
    changes = {"time.duration": steps * h, "integrator.step": h, "time.output_step": steps * h}
    return load_scene(name).replace({**changes, **(extra or {})})


def kernels(bodies: int, steps: int, repeats: int) -> None:
    rng = np.random.default_rng(1)
    free = _scene("spinning_disk", steps, FREE)
    per_sample = {
        "body.moments": np.array(free.body.moments) * (1 + 0.01 * rng.normal(size=(bodies, 3))),
        "initial.angular_velocity.body[2]": 0.5236 + 0.005 * rng.normal(size=bodies),
    }
    free_samples = scene_samples(free, per_sample)
    heavy = _scene("heavy_top", steps, {"integrator.paths": ["quaternion"]})
    heavy_samples = scene_samples(
        heavy, {"initial.angular_velocity.body[2]": 60 + rng.normal(size=bodies)}
    )
    q0 = np.ascontiguousarray(free_samples.orientation.T)
    w0 = np.ascontiguousarray(free_samples.angular_velocity.T)

    rows = {
        "rk4_free (shared inertia, torque-free)": lambda: rk4_free(
            free.body.moments, q0.copy(), w0.copy(), free.step, steps
        ),
        "run_samples, torque-free scene, per-sample inertia and rate": lambda: run_samples(
            free_samples
        ),
        "run_samples, heavy top (gravity), per-sample parameters": lambda: run_samples(
            heavy_samples
        ),
    }
    for f in rows.values():  # compile, or load from numba's cache
        f()
    rates: dict[str, list[float]] = {k: [] for k in rows}
    for _ in range(repeats):
        for name, f in rows.items():
            t0 = time.perf_counter()
            f()
            rates[name].append(bodies * steps / (time.perf_counter() - t0) / 1e6)
    print(f"kernels: {bodies} bodies x {steps} RK4 steps, {repeats} interleaved repeats")
    for name, r in rates.items():
        print(f"  {name:62s} {statistics.median(r):7.0f} M body-steps/s "
              f"({min(r):.0f}-{max(r):.0f})")  # fmt: skip


def _warm() -> None:
    """Import what a chunk needs (a worker's first task would otherwise pay for it)."""
    import dask.array  # noqa: F401
    import xarray  # noqa: F401
    import zarr  # noqa: F401

    import ga_rotors.ensemble
    import ga_rotors.sweep.run  # noqa: F401


def sweep_overhead(samples: int, steps: int) -> None:
    import distributed

    from ga_rotors.sweep import load_sweep, run_sweep

    _warm()
    h = 0.01
    text = f"""
[sweep]
scene = "spinning_disk"
samples = {samples}
seed = 1
chunk = 65536

[set]
"time.duration" = {steps * h}
"integrator.step" = {h}
"time.output_step" = {steps * h}
"integrator.paths" = ["quaternion"]
"body" = {{moments = [900.0, 950.0, 1100.0]}}
"initial.angular_velocity" = {{body = [0.002, 0.001, 0.5236], units = "rad/s"}}

[[draw]]
key = "body.moments[0]"
normal = [900.0, 9.0]

[[draw]]
key = "initial.angular_velocity.body[2]"
normal = [0.5236, 0.005]
"""
    sweep = load_sweep(text)
    t0 = time.perf_counter()
    values = sweep.values(0, sweep.size)
    s = scene_samples(sweep.scene, values)
    t_inputs = time.perf_counter() - t0
    run_samples(scene_samples(sweep.scene, n=8))  # compiled / cached
    t0 = time.perf_counter()
    run_samples(s)
    t_kernel = time.perf_counter() - t0
    t0 = time.perf_counter()
    run_samples(s, parallel=False)
    t_serial = time.perf_counter() - t0
    del s
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run_sweep(text, Path(tmp) / "s.zarr", client="sync")
        t_here = time.perf_counter() - t0
    t0 = time.perf_counter()
    cluster = distributed.LocalCluster(
        n_workers=os.cpu_count(), threads_per_worker=1, processes=True, dashboard_address=None
    )
    client = distributed.Client(cluster)
    client.run(_warm)
    t_start = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run_sweep(text, Path(tmp) / "s.zarr", client=client)
        t_sweep = time.perf_counter() - t0
    client.close()
    cluster.close()
    print(
        f"sweep: {samples} samples x {steps} RK4 steps, chunks of 65536, {os.cpu_count()} workers"
    )
    print(f"  raw kernel (run_samples, every core):   {t_kernel:7.2f} s "
          f"(+ {t_inputs:.2f} s drawing the values and building the inputs)")  # fmt: skip
    print(f"  sweep end to end (run_sweep, Dask):     {t_sweep:7.2f} s "
          f"(+ {t_start:.2f} s starting the local cluster)")  # fmt: skip
    print(f"  overhead over the raw kernel:           {100 * (t_sweep / t_kernel - 1):6.1f} %")
    print(f"  one thread: raw kernel {t_serial:.2f} s, sweep in this process (client='sync') "
          f"{t_here:.2f} s: overhead {100 * (t_here / t_serial - 1):.1f} %")  # fmt: skip


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bodies", type=int, default=100_000)
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--sweep-samples", type=int, default=1_000_000)
    p.add_argument("--sweep-steps", type=int, default=100)
    a = p.parse_args()
    kernels(a.bodies, a.steps, a.repeats)
    sweep_overhead(a.sweep_samples, a.sweep_steps)


if __name__ == "__main__":
    main()
