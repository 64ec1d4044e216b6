"""Cold start: the first run after install against a warm run, and the rotor API's first
product in a fresh process (issue 12: within 1.5× of warm; under 0.5 s).

Run from the repository root: ``python benchmarks/bench_coldstart.py [repeats]``.
"After install" is simulated by empty compiled-code caches: every measurement runs in a
fresh process with ``NUMBA_CACHE_DIR`` and ``GA_ROTORS_CACHE_DIR`` pointing at a new
temporary directory (cold), then again with the same directories (warm). Prints a Markdown
table of wall times (median and min–max of ``repeats`` cold/warm pairs, default 3).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: What a user does first: (label, Python code run in a fresh process).
TASKS = {
    "import ga_rotors": "import ga_rotors",
    "rotor API: first product": (
        "import numpy as np\n"
        "from ga_rotors import rotor\n"
        "R = rotor.from_axis_angle([0, 0, 1], 0.5)\n"
        "S = rotor.compose(R, R)\n"
    ),
    "simulate (rk4, rotor path)": (
        "from ga_rotors.simulate import simulate\n"
        "simulate([1, 2, 3], [1, 0, 0, 0], [1, 0.5, 0.2], duration=1.0, step=1e-3)\n"
    ),
    "ga-rotors run spinning_disk": (
        "import sys, tempfile\n"
        "from ga_rotors.cli import main\n"
        "out = tempfile.mkdtemp()\n"
        "sys.exit(main(['run', 'spinning_disk', '--out', out, '--no-progress']))\n"
    ),
}


def _time(code: str, caches: Path) -> float:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(caches / "numba"),
           "GA_ROTORS_CACHE_DIR": str(caches / "ga_rotors"), "PYTHONPATH": str(ROOT)}  # fmt: skip
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], env=env, check=True, capture_output=True)
    return time.perf_counter() - start


def main(repeats: int = 3) -> None:
    print(f"`python benchmarks/bench_coldstart.py {repeats}`; seconds, median (min–max)\n")
    print("| first use | cold (empty caches) | warm | cold / warm |")
    print("|---|---|---|---|")
    for label, code in TASKS.items():
        cold, warm = [], []
        for _ in range(repeats):
            with tempfile.TemporaryDirectory() as tmp:
                cold.append(_time(code, Path(tmp)))
                warm.append(_time(code, Path(tmp)))

        def cell(t):
            return f"{statistics.median(t):.2f} ({min(t):.2f}–{max(t):.2f})"

        ratio = statistics.median(cold) / statistics.median(warm)
        print(f"| {label} | {cell(cold)} | {cell(warm)} | {ratio:.2f} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
