"""Streamed scene runs: wall time against the bare integration, and peak memory.

Run from the repository root::

    python benchmarks/bench_stream.py                        # 1e7 steps per path, 3 repeats
    python benchmarks/bench_stream.py --steps 1e8 --repeats 1 --only stream
    python benchmarks/bench_stream.py --quick                # the suite's smoke run

The scene is the bundled heavy top (RK4 at 0.1 ms on the rotor and quaternion paths, a
sample every 5 steps: t, ω, both orientations, the ZYZ angles and the total energy),
integrated for ``--steps`` steps per path with its figure (angles, ω, invariants) and
summary (``--quantities`` for other quantities, ``--no-summary`` for
``output.summary = false``). The bundled scene's ``error`` quantity and panel are left
out: the summary already evaluates the exact Lagrange top at every sample (its largest
cost), and the error columns would evaluate it a second time. Each measurement is a fresh
child process, the compiled loops warm (a short run of the same scene first, in the same
child), the modes interleaved over the repeats:

* ``bare``: :func:`ga_rotors.simulate` of the same paths and sampling, the samples kept in
  memory, nothing derived or written: the integration alone (its loops, its arrays);
* ``stream``: ``ga-rotors run`` as a user runs it (:func:`ga_rotors.scene.stream_scene`)
  writing the binary format of long runs (``--data``, default netCDF): the run in pieces,
  quantities per piece, the file appended as it goes, summary and figure, moved into
  place at the end. The target: within 2x of ``bare``, peak RSS under 500 MB;
* ``csv``: the same streamed run writing CSV instead (``--csv-data``), whose cost is the
  CSV library's (reported, not a target);
* ``whole`` (``--only whole``): :func:`run_scene` then :func:`write_outputs` of the
  binary format, every sample in memory.

Times are measured inside the child around the call (interpreter start-up and imports
excluded, the same for every mode): wall time, and the CPU time of all the child's
threads (on a loaded machine the wall times stretch, the CPU times much less); peak
memory is the child's maximum resident set (``os.wait4``'s ``ru_maxrss``), start-up
included. Reported: median and min–max over the repeats, and each mode over ``bare``
(wall and CPU, pairs of the same repeat). No number here is a test: the suite only runs
``--quick``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CHILD = r"""
import json, sys, time, warnings
from ga_rotors.scene import load_scene
mode, steps, out, data = sys.argv[1], int(float(sys.argv[2])), sys.argv[3], sys.argv[4]
scene = load_scene("heavy_top").replace({"output.data": data.split(",") if data else [],
                                         "output.summary": sys.argv[6] == "on",
                                         "output.plots": ["angles", "omega", "invariants"],
                                         "output.quantities": sys.argv[5].split(",")})
scene = scene.replace({"time.duration": steps * scene.step})
warm = scene.replace({"time.duration": 200 * scene.step})
if mode == "bare":
    from ga_rotors import simulate
    def once(s):
        return simulate(s.body, s.orientation, s.angular_velocity,
                        duration=s.data["time"]["duration"], step=s.step, paths=s.paths,
                        integrator=s.method, torques=s.torques(), sample_every=s.sample_every)
elif mode == "stream":
    from ga_rotors.scene import stream_scene
    from ga_rotors.scene.budget import Budget
    budget = Budget(max_steps=10**10, max_disk_gib=1000)
    def once(s):
        return stream_scene(s, out, budget=budget)
else:
    from ga_rotors.scene import report, run_scene, write_outputs
    from ga_rotors.scene.budget import Budget
    budget = Budget(max_steps=10**10, max_memory_gib=1000)
    def once(s):
        tr = run_scene(s, budget=budget)
        return write_outputs(s, tr, out, str(report(s, tr)))
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    once(warm)  # compiled, imported
    start, cpu = time.perf_counter(), time.process_time()
    once(scene)
    took, cpu = time.perf_counter() - start, time.process_time() - cpu
print(json.dumps({"seconds": took, "cpu": cpu}))
"""


def _child(mode: str, steps: float, data: str, quantities: str, summary: str = "on") -> dict:
    """One measurement in a fresh process: seconds (inside) and peak RSS (MB)."""
    with tempfile.TemporaryDirectory(prefix="bench_stream-") as tmp:
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        log = Path(tmp) / "log"
        child_mode = "stream" if mode == "csv" else mode
        # cwd: `python -c` puts its working folder first on sys.path, so a checkout there
        # would be measured instead of this one
        with open(log, "w") as sink:  # a file, not a pipe: a chatty child never blocks
            proc = subprocess.Popen(
                [sys.executable, "-c", CHILD, child_mode, str(steps), str(Path(tmp) / "out"),
                 data, quantities, summary],
                stdout=sink, stderr=subprocess.STDOUT, env=env, cwd=ROOT,
            )  # fmt: skip
            _, status, usage = os.wait4(proc.pid, 0)  # this child's own peak memory
        proc.returncode = os.waitstatus_to_exitcode(status)
        out = log.read_text()
        if proc.returncode != 0:
            raise SystemExit(f"bench_stream: the {mode} child failed:\n{out}")
        folder = Path(tmp) / "out"
        files = sum(f.stat().st_size for f in folder.rglob("*") if f.is_file())
    result = json.loads(out.strip().splitlines()[-1])
    result["peak_mb"] = usage.ru_maxrss / 1024  # KiB on Linux
    result["files_mb"] = files / 2**20
    return result


def _summary(values: list[float]) -> str:
    return f"{statistics.median(values):9.2f}  ({min(values):.2f}–{max(values):.2f})"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=float, default=1e7, help="steps per path (default 1e7)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only", choices=["bare", "stream", "csv", "whole"], action="append",
                        help="modes to run (default: bare, stream and csv)")  # fmt: skip
    parser.add_argument(
        "--data", default="netcdf", help="output.data of the stream mode (default: netcdf)"
    )
    parser.add_argument(
        "--csv-data", default="csv", help="output.data of the csv mode (default: csv)"
    )
    parser.add_argument(
        "--quantities",
        default="angles,total_energy",
        help="output.quantities, comma-separated (default: angles,total_energy)",
    )
    parser.add_argument(
        "--no-summary",
        action="store_true",
        help="output.summary = false: the streamed run measures nothing (its report says only "
        "whether the run completed)",
    )
    parser.add_argument("--quick", action="store_true", help="a tiny run of every mode but whole")
    parser.add_argument("--json", metavar="FILE", help="also write the results as JSON")
    args = parser.parse_args(argv)
    modes = args.only or ["bare", "stream", "csv"]
    if args.quick:
        args.steps, args.repeats, modes = 2000, 1, ["bare", "stream", "csv"]
    summary = "off" if args.no_summary else "on"
    data = {"bare": "", "stream": args.data, "csv": args.csv_data, "whole": args.data}
    results: dict[str, list[dict]] = {m: [] for m in modes}
    for _ in range(args.repeats):
        for mode in modes:  # interleaved: the machine's load falls on every mode alike
            results[mode].append(_child(mode, args.steps, data[mode], args.quantities, summary))
    print(
        f"heavy top, {args.steps:.3g} steps per path (rotor + quaternion), a sample every 5 "
        f"steps, quantities: {args.quantities}, data: stream {args.data}, csv "
        f"{args.csv_data}, summary: {summary}; {args.repeats} repeat(s), fresh processes"
    )
    print(f"{'mode':<8} {'seconds: median (min–max)':<28} {'CPU seconds':<28} "
          f"{'peak RSS MB':<28} files MB")  # fmt: skip
    for mode, rows in results.items():
        seconds, cpu, peak = (_summary([r[k] for r in rows]) for k in ("seconds", "cpu", "peak_mb"))
        print(f"{mode:<8} {seconds:<28} {cpu:<28} {peak:<28} {rows[0]['files_mb']:.2f}")
    if "bare" in results:
        for mode in (m for m in results if m != "bare"):
            pairs = list(zip(results[mode], results["bare"], strict=True))
            for key, what in (("seconds", "wall"), ("cpu", "CPU")):
                ratios = [s[key] / b[key] for s, b in pairs]
                print(f"{mode} / bare {what} time: {_summary(ratios)}")
    if args.json:
        Path(args.json).write_text(json.dumps({"steps": args.steps, "results": results}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
