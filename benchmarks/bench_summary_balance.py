"""What the work–energy balance costs a run's summary (issue 30 item 2).

Run from the repository root: ``python benchmarks/bench_summary_balance.py [rounds]``
(about 30 s). The 10⁶ samples of a 1000 s heavy top (one sample a step) are integrated
once; then the whole summary (:class:`ga_rotors.scene.summary.RunSummary`, every piece
and the report) is measured with and without its balance, interleaved, ``rounds`` times
(default 5). Prints CPU seconds, median (min–max).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ga_rotors.scene import load_scene, run_pieces
from ga_rotors.scene.summary import RunSummary


def _summary(scene, pieces, balance: bool) -> float:
    summary = RunSummary(scene)
    if not balance:
        summary.balance = None
    start = time.process_time()
    for piece in pieces:
        summary.add(piece)
    summary.report()
    return time.process_time() - start


def main(rounds: int = 5) -> None:
    scene = load_scene("heavy_top").replace(
        {"time.duration": 1000.0, "time.output_step": 0.001, "output.quantities": []}
    )
    pieces = list(run_pieces(scene))
    _summary(scene, pieces[:2], True)  # compiled passes loaded before the clock runs
    times = {True: [], False: []}
    for _ in range(rounds):
        for balance in (True, False):
            times[balance].append(_summary(scene, pieces, balance))
    print(f"`python benchmarks/bench_summary_balance.py {rounds}`: "
          f"{sum(len(p) for p in pieces):,} samples; CPU s, median (min–max)")  # fmt: skip
    for balance, label in ((False, "summary"), (True, "summary with the balance")):
        t = sorted(times[balance])
        print(f"  {label:<26} {t[len(t) // 2]:.3f} ({t[0]:.3f}–{t[-1]:.3f})")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:]))
