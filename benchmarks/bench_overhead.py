"""Per-call overhead of a fixed-step run through the public API (issue 12, goal < 2 µs).

Run from the repository root: ``python benchmarks/bench_overhead.py [rounds]`` (about
30 s). For each (method, steps) of :data:`ga_rotors.accuracy.overhead.COMBINATIONS`, three
calls are timed interleaved, ``rounds`` times (default 5000): the compiled loop alone (its
arrays allocated beforehand), ``Integrator.run`` and ``simulate``, on the (1, 2, 3) top,
quaternion path, one sample at the end. Overhead = the call's median minus the loop's
median. Prints a Markdown table of medians (min–max), in µs.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ga_rotors.accuracy.overhead import COMBINATIONS, measure_overhead


def main(rounds: int = 5000) -> None:
    print(f"`python benchmarks/bench_overhead.py {rounds}`; µs, median (min–max)\n")
    print("| method, steps | compiled loop | Integrator.run | run overhead | simulate "
          "| simulate overhead |")  # fmt: skip
    print("|---|---|---|---|---|---|")
    for method, nsteps in COMBINATIONS:
        m = measure_overhead(method, nsteps, rounds=rounds)

        def cell(t):
            return f"{t[0]:.3g} ({t[1]:.3g}–{t[2]:.3g})"

        print(
            f"| {method}, {nsteps} | {cell(m['loop'])} | {cell(m['run'])} | "
            f"{m['run overhead']:.3g} | {cell(m['simulate'])} | {m['simulate overhead']:.3g} |"
        )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5000)
