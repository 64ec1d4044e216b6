"""Show or clear the cache of compiled loops (generated modules and numba's machine code).

Every integrator loop is specialised for its problem (free, torqued: which torques, which
orientation path) as a small generated Python module, compiled by numba with cache=True.
The first run of a combination compiles it (a few seconds); later runs load the machine
code from this cache (milliseconds). The directory is $GA_ROTORS_CACHE_DIR if set, else
$XDG_CACHE_HOME/ga_rotors/generated or ~/.cache/ga_rotors/generated. Modules made by other
versions of ga_rotors are deleted 14 days after they were made (a version still in use
recompiles then, once); --clear says what it removes and deletes this version's modules
(the next runs compile them again), --clear --all every version's. The folder is private
(mode 0700); one writable by others or owned by someone else is refused. --warm compiles
every loop the paper and the bundled scenes use, one line per job, so that their first
run loads them (the README's install line runs it; without it ga-rotors paper and run
compile what they need themselves); Ctrl-C stops it and leaves a cache the next run
completes.
"""

from __future__ import annotations

import argparse
import sys

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--clear",
        action="store_true",
        help="delete this version's generated modules and compiled files",
    )
    parser.add_argument(
        "--all", action="store_true", help="with --clear: every version's, not only this one's"
    )
    parser.add_argument(
        "--warm",
        action="store_true",
        help="compile now every loop the paper and the bundled scenes use",
    )


def _size(n: int) -> str:
    for unit in ("B", "kB", "MB", "GB"):
        if n < 1000 or unit == "GB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1000
    raise AssertionError  # unreachable: the loop returns at GB


def _modules(n: int) -> str:
    return f"{n} module" if n == 1 else f"{n} modules"


def run(args: argparse.Namespace) -> int:
    from ..errors import InputError
    from ..integrators import _cache

    if args.all and not args.clear:
        raise InputError("--all: only with --clear (ga-rotors cache --clear --all)")
    if args.warm and args.clear:
        raise InputError("--warm: not with --clear (one, then the other)")
    directory = _cache.cache_location()
    if directory is None:
        print("no writable cache directory: loops are compiled in memory at every start")
        return 0
    entries = _cache.cached_modules(directory)
    mine = _cache.version_tag()
    current = [c for c in entries if c.version == mine]
    others = [c for c in entries if c.version != mine]
    if args.clear:
        going = entries if args.all else current
        which = "every version" if args.all else f"this version ({mine})"
        print(
            f"{directory}: removing {_modules(len(going))} of {which}, "
            f"{_size(sum(c.bytes for c in going))}"
        )
        from ..warmup import clear_markers

        removed = _cache.clear_cache(every_version=args.all)
        removed += clear_markers(every_version=args.all)
        kept = "" if args.all or not others else f"; kept {_modules(len(others))} of other versions"
        print(f"removed {removed} files{kept}")
        return 0
    if args.warm:
        from ..warmup import all_tasks, warm

        tasks = all_tasks()
        failed = warm(tasks, stream=sys.stdout)
        for task, error in failed:
            print(f"ga-rotors: {task.label}: {error}", file=sys.stderr)
        print(f"{len(tasks) - len(failed)} of {len(tasks)} loop sets compiled and cached")
        return 1 if failed else 0
    print(f"cache: {directory}")
    print(
        f"this version ({mine}): {_modules(len(current))}, {_size(sum(c.bytes for c in current))}"
    )
    print(
        f"other versions: {_modules(len(others))}, {_size(sum(c.bytes for c in others))} "
        f"(deleted {_cache.PRUNE_AFTER_DAYS:g} days after they were made)"
    )
    return 0
