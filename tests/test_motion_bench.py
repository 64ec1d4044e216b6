"""benchmarks/bench_motion.py end to end in its quick mode (no timing is judged here: speed
is measured by the lead on a quiet machine); every candidate's final state is checked
against the motor path's inside the script before it is timed."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_bench_motion_runs_quick_and_prints_medians_with_ranges():
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "bench_motion.py"), "--quick"],
        capture_output=True, text=True, timeout=900, cwd=ROOT,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    out = done.stdout
    for row in ("motor path", "quaternion path", "plain @njit RK4, 13 states",
                "motion, motor path", "rotation alone, under gravity"):  # fmt: skip
        assert row in out, row
    assert "median (min–max)" in out and "target ≤ 1.5×" in out


def test_bench_motion_refuses_absurd_sizes_in_one_line():
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "bench_motion.py"), "--bodies", "0"],
        capture_output=True, text=True, timeout=120, cwd=ROOT,
    )  # fmt: skip
    assert done.returncode == 2 and "--bodies must be in" in done.stderr
    assert "Traceback" not in done.stderr
