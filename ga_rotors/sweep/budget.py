"""What a sweep will cost, estimated before anything is written, and the budget it must fit.

A sweep file may ask for anything: 10¹² samples, a chunk of one sample (a file per sample
and variable), a chunk of 10⁹ samples (its arrays held at once). Before the store is made,
:func:`check` estimates the integration steps (every sample integrates every step), the
memory of the chunks integrating at once and the disk of the store, and refuses a sweep
beyond the budget with one line naming the key and how to raise the budget
(``ga-rotors sweep --max-steps N --max-memory GIB --max-disk GIB``, or ``budget=`` of
:func:`~ga_rotors.sweep.run_sweep`). Like :mod:`ga_rotors.scene.budget`, these are
estimates meant to refuse the absurd, not to bill the exact.
"""

from __future__ import annotations

import os

from ..scene.budget import Budget, Estimate

__all__ = ["DEFAULT", "check", "estimate"]

#: The budget ``ga-rotors sweep`` and :func:`~ga_rotors.sweep.run_sweep` use by default:
#: 10¹² steps is about 40 minutes of RK4 on two cores; memory and disk as for a run.
DEFAULT = Budget(max_steps=10**12, max_memory_gib=2.0, max_disk_gib=20.0)

#: Bytes a stored chunk file takes at least (a file system block).
BLOCK_BYTES = 4096

#: Float64 values per sample held for its inputs: orientation, ω, inertia and the effects'
#: parameters, drawn (with two values a sample of the normal draws' scratch) and then laid
#: out for the loop (generous: an estimate).
_INPUT_VALUES = 32


def _stored_values(sweep) -> tuple[list[int], int]:
    """Values per sample of each chunked variable, and the output times."""
    k = 1 if sweep.times is None else sweep.times.size
    per_key = [1 if v.ndim == 1 else v[0].size for v in sweep.values(0, 1).values()]
    return [4 * k, 3 * k, k, *per_key], k  # q, w, angle_from_nominal, each varied key


def estimate(sweep, threads: int | None = None) -> Estimate:
    """The steps, the memory and the disk ``sweep`` will take on ``threads`` threads
    (default: one per core), each integrating a chunk at a time.

    Examples
    --------
    >>> from ga_rotors.sweep import load_sweep
    >>> s = load_sweep('''
    ... [sweep]
    ... scene = "heavy_top"
    ... samples = 1000000
    ... chunk = 65536
    ... seed = 1
    ... [[draw]]
    ... key = "body.mass"
    ... normal = [2.0, 0.02]
    ... ''')
    >>> e = estimate(s, threads=2)
    >>> print(e)
    3e+10 steps, 1e+06 samples: about 68 MiB of memory, 72.1 MiB of files
    """
    threads = threads or os.cpu_count() or 1
    values, k = _stored_values(sweep)
    chunk = min(sweep.chunk, sweep.size)
    files = sum(max(8 * v * chunk, BLOCK_BYTES) for v in values) + BLOCK_BYTES  # + its flag
    per_sample = 8 * (_INPUT_VALUES + 2 * 8 * k + sum(values))
    # and while they integrate, the writer thread holds the chunks before theirs (one a
    # thread, their outputs) and a copy of its largest file (the page-aligned buffer of
    # direct writes)
    held = min(threads, sweep.chunks - 1)
    writing = 8 * chunk * (held * sum(values) + max(values)) if held else 0
    return Estimate(
        steps=sweep.size * sweep.scene.steps,
        samples=sweep.size,
        bytes=min(threads, sweep.chunks) * chunk * per_sample + writing,
        disk=sweep.chunks * files,
    )


def check(sweep, budget: Budget = DEFAULT, threads: int | None = None) -> Estimate:
    """Refuse ``sweep`` (SceneError naming its file and key) when it is beyond ``budget``.

    Examples
    --------
    >>> from ga_rotors.sweep import load_sweep
    >>> s = load_sweep('[sweep]\\nscene = "heavy_top"\\nsamples = 100000000\\nchunk = 2')
    >>> check(s)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: <string>: sweep.samples: 1e+08 samples need ... GiB of files ...
    >>> check(s, Budget(max_steps=10**13, max_disk_gib=1e4)).samples
    100000000
    """
    from ..scene.reader import Reader

    e = estimate(sweep, threads)
    over, raise_with = [], []
    if e.steps > budget.max_steps:
        over.append(f"{e.steps:.3g} integration steps (budget {budget.max_steps:.3g})")
        raise_with.append("--max-steps N")
    if e.disk / 2**30 > budget.max_disk_gib:
        over.append(
            f"about {e.disk / 2**30:.3g} GiB of files in {sweep.chunks:.3g} chunks (budget "
            f"{budget.max_disk_gib:g} GiB; each chunk's file takes at least "
            f"{BLOCK_BYTES // 1024} KiB)"
        )
        raise_with.append("--max-disk GIB")
    if over:
        raise Reader(sweep.file).error(
            "sweep.samples",
            f"{e.samples:.3g} samples need {' and '.join(over)}; to run it anyway raise the "
            f"budget: ga-rotors sweep {' '.join(raise_with)}",
        )
    if e.bytes / 2**30 > budget.max_memory_gib:
        raise Reader(sweep.file).error(
            "sweep.chunk",
            f"{sweep.chunk:.3g} samples a chunk need about {e.bytes / 2**30:.3g} GiB of memory "
            f"on the threads integrating at once (budget {budget.max_memory_gib:g} GiB); "
            "choose a smaller chunk, or raise the budget: ga-rotors sweep --max-memory GIB",
        )
    return e
