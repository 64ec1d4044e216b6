"""benchmarks/bench_motor.py end to end in its quick mode (no timing is judged here: speed
is measured by the lead on a quiet machine); every peer's numbers are checked against
ga_rotors' inside the script before they are timed."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_bench_motor_runs_quick_and_prints_medians_with_ranges():
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "bench_motor.py"), "--quick"],
        capture_output=True, text=True, timeout=600, cwd=ROOT,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    out = done.stdout
    for title in ("motor products", "moving points", "moving lines"):
        assert title in out
    assert "ga_rotors motor.compose" in out and "median (min–max)" in out


def test_bench_motor_refuses_absurd_sizes_in_one_line():
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "bench_motor.py"), "--n", "0"],
        capture_output=True, text=True, timeout=120, cwd=ROOT,
    )  # fmt: skip
    assert done.returncode == 2 and "--n must be in" in done.stderr
    assert "Traceback" not in done.stderr
