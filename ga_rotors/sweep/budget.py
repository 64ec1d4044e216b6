"""What a sweep will cost, estimated before anything is written, and the budget it must fit.

A sweep file may ask for anything: 10¹² samples, a chunk of two samples (a task and a
few files for every two samples: 10⁵ samples would make 250,000 files and take minutes
of bookkeeping for seconds of integration), a chunk of 10⁹ samples (its arrays held at
once). Before the store is made, :func:`check` estimates the integration steps (every
sample and every grid point's nominal run integrate every step), the memory of the
chunks integrating at once, the disk and the number of files of the store, and refuses
a sweep beyond the budget with one line naming the key and how to raise the budget
(``ga-rotors sweep --max-steps N --max-memory GIB --max-disk GIB --max-files N``, or
``budget=SweepBudget(...)`` of :func:`~ga_rotors.sweep.run_sweep`). Like
:mod:`ga_rotors.scene.budget`, these are estimates meant to refuse the absurd, not to
bill the exact.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from ..errors import InputError
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
    """

    max_steps: int = 10**12  # about 40 minutes of RK4 on two cores
    max_files: int = 10**5

    def __post_init__(self):
        super().__post_init__()
        value = self.max_files
        if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
            raise InputError(f"expected a positive number, got {value!r}", key="max_files")


#: The budget ``ga-rotors sweep`` and :func:`~ga_rotors.sweep.run_sweep` use by default.
DEFAULT = SweepBudget()


@dataclass(frozen=True)
class SweepEstimate(Estimate):
    """An :class:`~ga_rotors.scene.budget.Estimate` with the store's chunks and files.

    Examples
    --------
    >>> e = SweepEstimate(steps=10**6, samples=100, bytes=2**20, disk=2**21, chunks=4, files=30)
    >>> e.chunks, e.files
    (4, 30)
    """

    chunks: int = 0
    files: int = 0

    def __str__(self) -> str:
        chunks = f"{self.chunks:,} chunk{'s' if self.chunks != 1 else ''}"
        return f"{super().__str__()} in {chunks} ({self.files:,} files)"


def _stored(sweep) -> list[int]:
    """Values per sample of each variable a chunk writes (one file each): q, w, and for a
    body moving through space its position and velocity."""
    k = sweep.times.size
    moving = [3 * k, 3 * k] if sweep.scene.moves else []
    return [4 * k, 3 * k, *moving] + ([k] + [1] * len(sweep.draws) if sweep.draws else [])


def _state_rows(sweep) -> int:
    """Numbers in one sample's state on the loop: 7 for a rotation (q, ω); for a body
    moving through space 13 or 14 (the path's q and centre of mass, or its motor, then
    ω and the velocity)."""
    if not sweep.scene.moves:
        return 7
    from ..paths import resolve

    return resolve(sweep.scene.paths[0], moves=True).dim + 6


def _fixed_files(sweep, chunked: int) -> int:
    """Files of a store beside its chunks': the group's three, two of metadata a
    variable, one of data for each variable written whole (time, the component labels,
    the grid's values, the nominal runs)."""
    whole = 3 + len(sweep.grid) + (2 if sweep.draws else 0)
    return 3 + 2 * (chunked + whole) + whole


def estimate(sweep, threads: int | None = None) -> SweepEstimate:
    """The steps, memory, disk and files ``sweep`` will take on ``threads`` threads
    (default: one per core), each integrating a chunk at a time.

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
    values, k = _stored(sweep), sweep.times.size
    chunk = min(sweep.chunk, sweep.size)
    per_chunk = sum(max(8 * v * chunk, BLOCK_BYTES) for v in values) + BLOCK_BYTES  # + flag
    # the inputs (a moving body's larger state and body rows twice more: as drawn, as
    # laid out for the loop) and the outputs' copies
    inputs = _INPUT_VALUES + 2 * (_state_rows(sweep) - 7)
    per_sample = 8 * (inputs + _OUTPUT_COPIES * sum(values))
    points = sweep.grid_points if sweep.draws else 0  # the nominal runs
    summary = 3 * 8 * sweep.samples * k if sweep.draws else 0  # a point's angles, sorted
    nominal = points * 8 * 7 * k  # the nominal runs' q and w, kept
    return SweepEstimate(
        steps=(sweep.size + points) * sweep.scene.steps,
        samples=sweep.size,
        bytes=min(threads, sweep.chunks) * chunk * per_sample + nominal * 3 + summary,
        disk=sweep.chunks * per_chunk + nominal,
        chunks=sweep.chunks,
        files=sweep.chunks * (len(values) + 1) + _fixed_files(sweep, len(values) + 1),
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
    from ..scene.reader import Reader

    e = estimate(sweep, threads)
    r = Reader(sweep.file)
    over, raise_with = [], []
    if e.steps > budget.max_steps:
        over.append(f"{e.steps:.3g} integration steps (budget {budget.max_steps:.3g})")
        raise_with.append("--max-steps N")
    if e.disk / 2**30 > budget.max_disk_gib:
        over.append(
            f"about {e.disk / 2**30:.3g} GiB of files (budget {budget.max_disk_gib:g} "
            f"GiB; each chunk's file takes at least {BLOCK_BYTES // 1024} KiB)"
        )
        raise_with.append("--max-disk GIB")
    if over:
        raise r.error(
            "sweep.samples",
            f"{e.samples:.3g} samples need {' and '.join(over)}; "
            f"to run it anyway raise the budget: ga-rotors sweep {' '.join(raise_with)}",
        )
    max_files = getattr(budget, "max_files", DEFAULT.max_files)
    if e.files > max_files:
        raise r.error(
            "sweep.chunk",
            f"{e.samples:.3g} samples in chunks of {sweep.chunk:,} make {e.chunks:,} chunks "
            f"and {e.files:,} files (budget {max_files:,.0f} files); choose a larger chunk "
            f"({DEFAULT_CHUNK} is the default), or raise the budget: ga-rotors sweep --max-files N",
        )
    if e.bytes / 2**30 > budget.max_memory_gib:
        raise r.error(
            "sweep.chunk",
            f"{sweep.chunk:.3g} samples a chunk need about {e.bytes / 2**30:.3g} GiB of memory "
            f"on the threads integrating at once (budget {budget.max_memory_gib:g} GiB); "
            "choose a smaller chunk, or raise the budget: ga-rotors sweep --max-memory GIB",
        )
    return e
