"""Run a sweep: a grid and/or Monte-Carlo draws of scene keys, chunk by chunk into a zarr store.

The sweep file names the scene, the keys to vary (a grid of values, random draws from
stated distributions with a seed) and the output times; see docs/ensembles.md. Chunks of
samples run on this machine by default (Dask's threaded scheduler, one thread per core),
or on an existing Dask cluster with --scheduler ADDRESS, and are written to the store as
they finish. Interrupting and running the same command again resumes from the finished
chunks; a store begun with another scene, sweep or version is not resumed.
Prints how far each grid point's samples spread from its own nominal run at each output
time, and how many failed.
A sweep needing more than --max-steps integration steps (default 1e12), --max-memory GiB
(default 2), --max-disk GiB of store (default 20) or --max-files files (default 1e5) is
refused before anything is written.
Needs the dask extra: pip install ".[dask]" in the repository.
"""

from __future__ import annotations

import argparse
import sys
import time

__all__ = ["add_arguments", "run"]

DEFAULT_OUT = "results"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("sweep", metavar="SWEEP", help="a sweep file (.toml)")
    parser.add_argument(
        "--out",
        metavar="STORE",
        default=None,
        help=f"the zarr store to write or resume (default: ./{DEFAULT_OUT}/<sweep name>.zarr)",
    )
    where = parser.add_mutually_exclusive_group()
    where.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        default=None,
        help="an existing Dask cluster's scheduler (tcp://host:8786), given 10 s to answer; "
        "default: threads on this machine",
    )
    where.add_argument(
        "--workers",
        metavar="N",
        type=int,
        default=None,
        help="threads on this machine (default: one per core)",
    )
    where.add_argument(
        "--here",
        action="store_true",
        help="run the chunks one after the other in this thread",
    )
    parser.add_argument(
        "--max-steps",
        metavar="N",
        type=float,
        default=None,
        help="refuse a sweep needing more integration steps, summed over samples (default 1e12)",
    )
    parser.add_argument(
        "--max-memory",
        metavar="GIB",
        type=float,
        default=None,
        help="refuse a sweep needing more memory (default 2 GiB)",
    )
    parser.add_argument(
        "--max-disk",
        metavar="GIB",
        type=float,
        default=None,
        help="refuse a sweep whose store needs more disk (default 20 GiB)",
    )
    parser.add_argument(
        "--max-files",
        metavar="N",
        type=float,
        default=None,
        help="refuse a sweep whose store needs more files (default 1e5)",
    )
    bar = parser.add_mutually_exclusive_group()
    bar.add_argument(
        "--progress",
        dest="progress",
        action="store_true",
        default=None,
        help="always show progress (default: only on a terminal)",
    )
    bar.add_argument(
        "--no-progress", dest="progress", action="store_false", help="never show progress"
    )


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..errors import InputError
    from ..sweep import open_sweep, run_sweep, summary
    from ..sweep.budget import DEFAULT, SweepBudget
    from ..sweep.summary import lines
    from .run import ProgressBar, budget_from_args

    start = time.perf_counter()
    files = DEFAULT.max_files if args.max_files is None else args.max_files
    if not files > 0:  # NaN too
        raise InputError(f"expected a positive number, got {args.max_files!r}", key="--max-files")
    limits = budget_from_args(args, DEFAULT)
    budget = SweepBudget(
        max_steps=limits.max_steps,
        max_memory_gib=limits.max_memory_gib,
        max_disk_gib=limits.max_disk_gib,
        max_files=files,
    )
    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers: expected a positive number, got {args.workers}")
    if args.out is None:
        out = Path(DEFAULT_OUT) / f"{Path(args.sweep).stem}.zarr"
        out.parent.mkdir(parents=True, exist_ok=True)
    else:
        out = Path(args.out)
    bar = ProgressBar(sys.stderr, args.progress, delay=0.0)
    try:
        store = run_sweep(
            Path(args.sweep),
            out,
            client="sync" if args.here else None,
            scheduler=args.scheduler,
            workers=args.workers,
            progress=bar,
            budget=budget,
        )
    finally:
        bar.close()
    print("\n".join(lines(summary(open_sweep(store)))))
    print(f"\nwrote {store} ({time.perf_counter() - start:.1f} s)")
    return 0
