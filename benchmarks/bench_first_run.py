"""Cold start: a command's first run after installation against a warm run, and the rotor
API's first product in a fresh process.

Run from the repository root::

    python benchmarks/bench_first_run.py                 # 3 repeats: rotor, paper, run
    python benchmarks/bench_first_run.py --repeats 2 --only warm-up
    python benchmarks/bench_first_run.py --repeats 1 --only rotor

Every measurement is a fresh process. "First run after install" is simulated with empty
caches: ``GA_ROTORS_CACHE_DIR`` (generated loops) and ``NUMBA_CACHE_DIR`` (numba's
machine code, also of the package's own kernels) point to new empty directories, so
everything a real first run compiles is compiled. The ``paper`` command is the README's
(``ga-rotors paper``, figures and data); ``run`` is ``ga-rotors run heavy_top``. Per
command, one repeat runs, in order, on fresh caches, interleaved with the other commands'
repeats:

* ``first run (warms itself)``: the command on empty caches, as without the install
  line's warm-up: it compiles what it needs first (ga_rotors.warmup, a progress line per
  job, in its own process), then runs;
* ``ga-rotors cache --warm``: the README's install step on empty caches (a line per
  job), timed on its own;
* ``first run after cache --warm``: then the command: the first run after the README's
  install line (the claim: within 1.5x of a warm run);
* ``warm run``: the command again, everything cached.

Wall time is what a user waits; CPU time (the process and its children, user + system)
is what the machine spends and is less disturbed by other jobs. Reported: median and
min–max over the repeats, and the ratios of the medians.

The ``warm-up`` row (``--only warm-up``) times the warm-up of every job
(``ga_rotors.warmup.all_tasks``) on fresh caches, from Python.

The rotor rows time, inside a fresh process with numba's cache warm, the first call of
``rotor.from_axis_angle`` + ``rotor.compose`` (ga_rotors' rotor API) and the first ``R * R``
on clifford MultiVectors (clifford's own product, compiled by numba without a cache at
every start: ga_rotors cannot change that cost for ``*`` on clifford objects).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
GA = str(BIN / "ga-rotors") if (BIN / "ga-rotors").exists() else None

COMMAND = {
    "paper": ["paper", "--out", "{out}"],
    "run": ["run", "heavy_top", "--out", "{out}", "--no-progress"],
}

ROTOR = """
import json, time
t0 = time.perf_counter()
import numpy as np
from ga_rotors import rotor
t1 = time.perf_counter()
R = rotor.from_axis_angle([0.0, 0.0, 1.0], 0.3)
R2 = rotor.compose(R, R)
t2 = time.perf_counter()
S = R * R
t3 = time.perf_counter()
assert np.allclose(S.value, R2.value)
print(json.dumps({"import": t1 - t0, "rotor API first product": t2 - t1,
                  "clifford R * R first": t3 - t2}))
"""


def _timed(argv, env) -> tuple[float, float]:
    """Wall and CPU seconds (process and children) of one subprocess."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    proc = subprocess.run(argv, env=env, capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def _fill(template, out):
    return [a.format(out=out) for a in template]


def one_repeat(name: str, results: dict) -> None:
    """first, cache --warm, first after it, warm: one command on fresh caches."""
    scratch = Path(tempfile.mkdtemp(prefix="bench_first_run-"))
    try:
        out = str(scratch / "out")

        def env_for(label):
            env = dict(os.environ)
            env["GA_ROTORS_CACHE_DIR"] = str(scratch / label / "ga")
            env["NUMBA_CACHE_DIR"] = str(scratch / label / "numba")
            return env

        cmd = [GA, *_fill(COMMAND[name], out)]
        rows = [
            ("first run (warms itself)", env_for("a"), cmd),
            ("ga-rotors cache --warm", env_for("b"), [GA, "cache", "--warm"]),
            ("first run after cache --warm", env_for("b"), cmd),
            ("warm run", env_for("b"), cmd),
        ]
        for label, env, argv in rows:
            wall, cpu = _timed(argv, env)
            results.setdefault((name, label), []).append((wall, cpu))
            print(f"  {name}: {label}: wall {wall:.2f} s, CPU {cpu:.2f} s", flush=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


WARM_UP = "from ga_rotors import warmup; warmup.warm(warmup.all_tasks())"


def warm_up_repeat(results: dict) -> None:
    """Every warm-up job, on fresh caches."""
    scratch = Path(tempfile.mkdtemp(prefix="bench_first_run-"))
    try:
        env = {**os.environ, "GA_ROTORS_CACHE_DIR": str(scratch / "ga"),
               "NUMBA_CACHE_DIR": str(scratch / "numba")}  # fmt: skip
        wall, cpu = _timed([sys.executable, "-c", WARM_UP], env)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    results.setdefault(("warm-up", "every job"), []).append((wall, cpu))
    print(f"  warm-up: every job: wall {wall:.2f} s, CPU {cpu:.2f} s", flush=True)


def rotor_repeat(results: dict) -> None:
    proc = subprocess.run([sys.executable, "-c", ROTOR], capture_output=True, text=True,
                          cwd=ROOT, check=True)  # fmt: skip
    for key, value in json.loads(proc.stdout.splitlines()[-1]).items():
        results.setdefault(("rotor", key), []).append((value, float("nan")))


def _fmt(values) -> str:
    med = statistics.median(values)
    return f"{med:7.2f} ({min(values):.2f}–{max(values):.2f})"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only", choices=["paper", "run", "rotor", "warm-up"], action="append")
    args = parser.parse_args(argv)
    if GA is None:
        raise SystemExit("the ga-rotors command is not installed next to this Python")
    which = args.only or ["rotor", "paper", "run"]
    results: dict = {}
    for _ in range(args.repeats):
        for name in which:  # interleaved: each repeat of each command in turn
            if name in ("rotor", "warm-up"):
                (rotor_repeat if name == "rotor" else warm_up_repeat)(results)
            else:
                one_repeat(name, results)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"{args.repeats} repeats, median (min–max), seconds; load average {load:.1f} "
          f"on {os.cpu_count()} CPUs at the end")  # fmt: skip
    print(f"{'what':<44} {'wall':>22} {'CPU':>22}")
    for (name, label), runs in results.items():
        walls = [w for w, _ in runs]
        cpus = [c for _, c in runs]
        cpu = _fmt(cpus) if all(c == c for c in cpus) else ""
        print(f"{name + ': ' + label:<44} {_fmt(walls):>22} {cpu:>22}")
    for name in which:
        if name in ("rotor", "warm-up"):
            continue

        def med(label, k, name=name):
            return statistics.median(run[k] for run in results[(name, label)])

        for k, what in ((0, "wall"), (1, "CPU")):
            warm = med("warm run", k)
            first = med("first run (warms itself)", k) / warm
            after = med("first run after cache --warm", k) / warm
            print(f"{name} ({what} medians): first run {first:.2f}x a warm run; "
                  f"first run after cache --warm {after:.2f}x")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
