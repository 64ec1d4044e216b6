"""Benchmarks: ``ga-rotors bench accuracy`` (work-precision study) and ``bench ensemble``.

``accuracy``: every integrator and peer on every reference problem over step/tolerance
sweeps; prints the cheapest method per problem and target error, writes one log–log PNG
per problem, and (with ``--doc``) rewrites the generated block of docs/accuracy.md.
``ensemble``: batched RK4 over many bodies on all cores, in body-steps per second.
Timings are medians (with min–max) of warm repeats; run them on a quiet machine.
"""

from __future__ import annotations

import argparse
import sys

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("which", choices=("accuracy", "ensemble"), help="which benchmark")
    parser.add_argument("--quick", action="store_true", help="coarse sweep, one repeat")
    parser.add_argument("--cases", default="", help="comma-separated problems (default: all)")
    parser.add_argument("--methods", default="", help="comma-separated methods (default: all)")
    parser.add_argument(
        "--no-peers", action="store_true", help="skip every peer (compiled and casual)"
    )
    parser.add_argument("--figures", default="", help="directory for the PNG figures")
    parser.add_argument("--doc", default="", help="markdown file whose generated block to rewrite")
    parser.add_argument("--bodies", type=int, default=10_000, help="ensemble: number of bodies")
    parser.add_argument("--steps", type=int, default=1000, help="ensemble: steps per body")


def run(args) -> int:
    if args.which == "ensemble":
        from ..ensemble import benchmark

        print(benchmark(args.bodies, args.steps))
        return 0
    return _accuracy(args)


def _accuracy(args) -> int:
    from ..accuracy import report

    text = report.run_study(
        [c for c in args.cases.split(",") if c],
        [m for m in args.methods.split(",") if m],
        quick=args.quick,
        peers=not args.no_peers,
        figures=args.figures or None,
        doc=args.doc or None,
        log=lambda m: print(m, file=sys.stderr),
    )
    print(text)
    if args.doc:
        report.write_block(args.doc, text)
    return 0
