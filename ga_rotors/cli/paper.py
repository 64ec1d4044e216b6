"""Reproduce the paper's gyroscope: Figures 3–10 through rotors, quaternions and Euler angles.

Integrates the paper's two torque-free scenes (θ₀ = 15° and 0.001°; RK4, 10,000 steps of
1 ms) on the paper's printed inertia and on a uniform disk spinning about its symmetry
axis, each along three orientation paths: the rotor equation dR/dt = ½RΩ in Cl(3,0), the
quaternion equation, and the paper's z–y′–z″ Euler-angle rates. Prints the rotor/quaternion
cross-check, every path's error against the exact symmetric-top solution, and what the
Euler-angle path did near sin θ = 0; writes the figures (PNG) and the data (CSV).
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

from ..paper.reproduce import DEFAULT_OUT, FORMATS

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--out",
        default=DEFAULT_OUT,
        metavar="DIR",
        help=f"output directory, created if missing (default: ./{DEFAULT_OUT})",
    )
    what = parser.add_mutually_exclusive_group()
    what.add_argument(
        "--no-figures", action="store_true", help="skip the PNG figures (data and summary only)"
    )
    what.add_argument(
        "--figures-only",
        action="store_true",
        help="write only the PNG figures (how docs/figures/ is made)",
    )
    parser.add_argument(
        "--format",
        choices=FORMATS,
        default="png",
        help="figure format: PNG at 150 dpi (default), or vector SVG or PDF for print",
    )


def run(args: argparse.Namespace) -> int:
    from ..paper.reproduce import reproduce
    from ..paper.runs import summary

    start = time.perf_counter()
    parallel = (os.cpu_count() or 1) > 1
    runs, written = reproduce(
        args.out,
        figures=not args.no_figures,
        data=not args.figures_only,
        parallel=parallel,
        fmt=args.format,
    )
    print(summary(runs))
    print()
    where = os.path.relpath(Path(args.out).resolve())
    print(f"wrote {len(written)} files to {where}/ in {time.perf_counter() - start:.1f} s")
    print('see it move: ga-rotors view paper_15deg (or paper_0.001deg)')
    return 0
