"""Show or clear the cache of compiled loops (generated modules and numba's machine code).

Every integrator loop is specialised for its problem (free, torqued: which torques, which
orientation path) as a small generated Python module, compiled by numba with cache=True.
The first run of a combination compiles it (a few seconds); later runs load the machine
code from this cache (milliseconds). The directory is $GA_ROTORS_CACHE_DIR if set, else
$XDG_CACHE_HOME/ga_rotors/generated or ~/.cache/ga_rotors/generated. Modules made by other
versions of ga_rotors are deleted 14 days after they were made (a version still in use
recompiles then, once); --clear deletes everything (the next runs compile again).
"""

from __future__ import annotations

import argparse

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--clear", action="store_true", help="delete every generated module and compiled file"
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
    from ..integrators import _codegen

    directory = _codegen.cache_location()
    if directory is None:
        print("no writable cache directory: loops are compiled in memory at every start")
        return 0
    if args.clear:
        removed = _codegen.clear_cache()
        print(f"{directory}: removed {removed} files")
        return 0
    entries = _codegen.cached_modules(directory)
    mine = _codegen.version_tag()
    current = [c for c in entries if c.version == mine]
    print(f"cache: {directory}")
    print(
        f"this version ({mine}): {_modules(len(current))}, {_size(sum(c.bytes for c in current))}"
    )
    others = [c for c in entries if c.version != mine]
    print(
        f"other versions: {_modules(len(others))}, {_size(sum(c.bytes for c in others))} "
        f"(deleted {_codegen.PRUNE_AFTER_DAYS:g} days after they were made)"
    )
    return 0
