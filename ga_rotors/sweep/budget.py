"""What a sweep will cost, estimated before anything is written, and the budget it must fit.

A sweep file may ask for anything: 10¹² samples, a chunk of two samples (10⁵ samples
would make 250,000 files and spend minutes on bookkeeping for seconds of integration), a
chunk of 10⁹ samples (its arrays held at once). :func:`check` estimates the steps, the
memory of the chunks integrating at once, the store's disk and files, and refuses a sweep
beyond the budget with one line naming the key and how to raise the budget (``ga-rotors
sweep --max-steps N --max-memory GIB --max-disk GIB --max-files N``, or
``budget=SweepBudget(...)`` of :func:`~ga_rotors.sweep.run_sweep`).
Like :mod:`ga_rotors.scene.budget`, these are estimates meant to refuse the absurd, not
to bill the exact.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from ..errors import SceneError
from ..scene.budget import Budget, Estimate
from .spec import DEFAULT_CHUNK

__all__ = ["DEFAULT", "SweepBudget", "SweepEstimate", "check", "estimate"]

#: Bytes a stored chunk file takes at least (a file system block).
BLOCK_BYTES = 4096

#: Float64 values per sample held for its inputs (its values, orientation, rate,
#: inertia, the effects' parameters, as drawn and as laid out for the loop; generous).
_INPUT_VALUES = 32

#: Copies of a sample's outputs alive at once (the loop's, the quaternions', the layout
#: written, the written chunk's buffer).
_OUTPUT_COPIES = 4


@dataclass(frozen=True)
class SweepBudget(Budget):
    """A run's :class:`~ga_rotors.scene.budget.Budget` (steps, memory, disk) and the most
    files a sweep's store may have.

    Examples
    --------
    >>> SweepBudget().max_files, SweepBudget(max_files=10).max_steps
    (100000, 1000000000000)
    >>> SweepBudget(max_files=float("nan"))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: max_files: expected a positive number, got nan
    """

    max_steps: int = 10**12  # about 40 minutes of RK4 on two cores
    max_files: int = 10**5


#: The budget ``ga-rotors sweep`` and :func:`~ga_rotors.sweep.run_sweep` use by default.
DEFAULT = SweepBudget()


@dataclass(frozen=True)
class SweepEstimate(Estimate):
    """An :class:`~ga_rotors.scene.budget.Estimate` with the store's chunks and files.

    Examples
    --------
    >>> e = SweepEstimate(steps=10**6, samples=100, bytes=2**20, disk=2**21, chunks=4, files=30)
    >>> print(e)
    1e+06 steps, 100 samples: about 1 MiB of memory, 2 MiB of files in 4 chunks (30 files)
    """

    chunks: int = 0
    files: int = 0

    def __str__(self) -> str:
        chunks = f"{self.chunks:,} chunk{'s' if self.chunks != 1 else ''}"
        return f"{super().__str__()} in {chunks} ({self.files:,} files)"


def estimate(sweep, threads: int | None = None) -> SweepEstimate:
    """The steps, memory, disk and files ``sweep`` will take on ``threads`` threads
    (default: one per core), each integrating a chunk at a time.

    Every sample and every grid point's nominal run integrate every step.

    Examples
    --------
    >>> from ga_rotors.sweep import load_sweep
    >>> s = load_sweep('''
    ... [sweep]
    ... scene = "heavy_top"
    ... samples = 1000000
    ... seed = 1
    ... [[draw]]
    ... key = "body.mass"
    ... normal = [2.0, 0.02]
    ... ''')
    >>> print(estimate(s, threads=2))
    3e+10 steps, 1e+06 samples: about 90.9 MiB of memory, 72.1 MiB of files in 16 chunks (108 files)

    A body moving through space also writes its position and velocity:

    >>> text = s.text.replace("heavy_top", "thrown_racket")
    >>> s = load_sweep(text.replace("body.mass", "initial.velocity[0]"))
    >>> print(estimate(s, threads=2))
    2e+09 steps, 1e+06 samples: about 129 MiB of memory, 120 MiB of files in 16 chunks (144 files)
    """
    threads = threads or os.cpu_count() or 1
    k, moves, draws = sweep.times.size, sweep.scene.moves, len(sweep.draws)
    # values per sample of each variable a chunk writes (one file each): q, w, a moving
    # body's position and velocity; with draws the angle and each drawn value
    values = [4 * k, 3 * k] + [3 * k, 3 * k] * moves + ([k] + [1] * draws if draws else [])
    chunk = min(sweep.chunk, sweep.size)
    per_chunk = sum(max(8 * v * chunk, BLOCK_BYTES) for v in values) + BLOCK_BYTES  # + flag
    # a sample's inputs (a moving body's state, 13 or 14 numbers where a rotation's is 7,
    # twice more: as drawn and as laid out for the loop) and its outputs' copies
    inputs = _INPUT_VALUES
    if moves:
        from ..paths import resolve

        inputs += 2 * (resolve(sweep.scene.paths[0], moves=True).dim - 1)
    per_sample = 8 * (inputs + _OUTPUT_COPIES * sum(values))
    points = sweep.grid_points if draws else 0  # the nominal runs
    summary = 3 * 8 * sweep.samples * k if draws else 0  # a point's angles, sorted
    nominal = points * 8 * 7 * k  # the nominal runs' q and w, kept
    # beside the chunks' files (a variable's and the flag's): the group's three, two of
    # metadata a variable, one of data for each variable written whole (time, the
    # component labels, the grid's values, the nominal runs)
    chunked, whole = len(values) + 1, 3 + len(sweep.grid) + (2 if draws else 0)
    return SweepEstimate(
        steps=(sweep.size + points) * sweep.scene.steps,
        samples=sweep.size,
        bytes=min(threads, sweep.chunks) * chunk * per_sample + nominal * 3 + summary,
        disk=sweep.chunks * per_chunk + nominal,
        chunks=sweep.chunks,
        files=sweep.chunks * chunked + 3 + 2 * (chunked + whole) + whole,
    )


def check(sweep, budget: Budget = DEFAULT, threads: int | None = None) -> SweepEstimate:
    """Refuse ``sweep`` (SceneError naming its file and key) when it is beyond ``budget``
    (a :class:`SweepBudget`, or a run's ``Budget`` and the default file count).

    Examples
    --------
    >>> from ga_rotors.sweep import load_sweep
    >>> s = load_sweep('[sweep]\\nscene = "heavy_top"\\nsamples = 100000\\nchunk = 2\\nseed = 1\\n'
    ...                '[[draw]]\\nkey = "body.mass"\\nuniform = [1.0, 2.0]')
    >>> check(s)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: <string>: sweep.chunk: 1e+05 samples in chunks of 2 make 50,000 ...
    >>> check(s, SweepBudget(max_files=10**6)).chunks
    50000
    """
    e, file = estimate(sweep, threads), sweep.file
    over = []  # (what it needs, the option that raises the budget)
    if e.steps > budget.max_steps:
        over.append((f"{e.steps:.3g} integration steps (budget {budget.max_steps:.3g})",
                     "--max-steps N"))  # fmt: skip
    if e.disk / 2**30 > budget.max_disk_gib:
        over.append((f"about {e.disk / 2**30:.3g} GiB of files (budget {budget.max_disk_gib:g} "
                     f"GiB; each chunk's file takes at least {BLOCK_BYTES // 1024} KiB)",
                     "--max-disk GIB"))  # fmt: skip
    if over:
        needs, options = zip(*over, strict=True)
        raise SceneError(file, "sweep.samples", f"{e.samples:.3g} samples need "
                         f"{' and '.join(needs)}; to run it anyway raise the budget: "
                         f"ga-rotors sweep {' '.join(options)}")  # fmt: skip
    max_files = getattr(budget, "max_files", DEFAULT.max_files)
    if e.files > max_files:
        raise SceneError(file, "sweep.chunk", f"{e.samples:.3g} samples in chunks of "
                         f"{sweep.chunk:,} make {e.chunks:,} chunks and {e.files:,} files "
                         f"(budget {max_files:,.0f} files); choose a larger chunk "
                         f"({DEFAULT_CHUNK} is the default), or raise the budget: "
                         "ga-rotors sweep --max-files N")  # fmt: skip
    if e.bytes / 2**30 > budget.max_memory_gib:
        raise SceneError(file, "sweep.chunk", f"{sweep.chunk:.3g} samples a chunk need about "
                         f"{e.bytes / 2**30:.3g} GiB of memory on the threads integrating at "
                         f"once (budget {budget.max_memory_gib:g} GiB); choose a smaller chunk, "
                         "or raise the budget: ga-rotors sweep --max-memory GIB")  # fmt: skip
    return e
