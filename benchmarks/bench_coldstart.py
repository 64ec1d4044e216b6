"""Cold start: the first run after install against a warm run, and the rotor API's first
product in a fresh process (issue 12: within 1.5× of warm; under 0.5 s).

Run from the repository root: ``python benchmarks/bench_coldstart.py [repeats]``.
"After install" is simulated by empty compiled-code caches: every measurement runs in a
fresh process with ``NUMBA_CACHE_DIR`` and ``GA_ROTORS_CACHE_DIR`` pointing at a new
temporary directory (cold), then again with the same directories (warm); the child times
the first use itself (after its set-up: imports, building the rotors). Prints a Markdown
table of those times (median and min–max of ``repeats`` cold/warm pairs, default 3).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: What a user does first: label -> (setup code, timed code), run in a fresh process; the
#: child reports the timed part's wall time (the process's own start-up is not in it).
TASKS = {
    "import ga_rotors": ("", "import ga_rotors\n"),
    "rotor API: first product (rotors built)": (
        "from ga_rotors import rotor\nR = rotor.from_axis_angle([0, 0, 1], 0.5)\n",
        "S = rotor.compose(R, R)\n",
    ),
    "simulate (rk4, rotor path, 1000 steps)": (
        "import ga_rotors as gr\n",
        "gr.simulate([1, 2, 3], [1, 0, 0, 0], [1, 0.5, 0.2], duration=1.0, step=1e-3)\n",
    ),
    "ga-rotors run spinning_disk": (
        "import tempfile\nfrom ga_rotors.cli import main\nout = tempfile.mkdtemp()\n",
        "assert main(['run', 'spinning_disk', '--out', out, '--no-progress']) == 0\n",
    ),
}


def _time(task: tuple[str, str], caches: Path) -> float:
    setup, timed = task
    code = (
        "import time\n" + setup + "_start = time.perf_counter()\n" + timed
        + "print(time.perf_counter() - _start)\n"
    )  # fmt: skip
    env = {**os.environ, "NUMBA_CACHE_DIR": str(caches / "numba"),
           "GA_ROTORS_CACHE_DIR": str(caches / "ga_rotors"), "PYTHONPATH": str(ROOT)}  # fmt: skip
    proc = subprocess.run(
        [sys.executable, "-c", code], env=env, check=True, capture_output=True, text=True
    )
    return float(proc.stdout.strip().splitlines()[-1])


def main(repeats: int = 3) -> None:
    print(f"`python benchmarks/bench_coldstart.py {repeats}`; seconds, median (min–max)\n")
    print("| first use | cold (empty caches) | warm | cold / warm |")
    print("|---|---|---|---|")
    for label, task in TASKS.items():
        cold, warm = [], []
        for _ in range(repeats):
            with tempfile.TemporaryDirectory() as tmp:
                cold.append(_time(task, Path(tmp)))
                warm.append(_time(task, Path(tmp)))

        def cell(t):
            return f"{statistics.median(t):.2f} ({min(t):.2f}–{max(t):.2f})"

        ratio = statistics.median(cold) / statistics.median(warm)
        print(f"| {label} | {cell(cold)} | {cell(warm)} | {ratio:.2f} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
