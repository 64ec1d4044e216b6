"""Sweeps and Monte-Carlo dispersion studies of a scene, on Dask, into a zarr store.

* :func:`load_sweep` — a sweep file: the scene, grid keys, random draws and seed;
* :func:`run_sweep` — run (or resume) it chunk by chunk on Dask into a ``.zarr`` store:
  on Dask's threaded scheduler in this process by default, or on a cluster (a
  scheduler's address, a ``distributed.Client``; :func:`local_cluster` starts one of
  worker processes on this machine);
* :func:`open_sweep` — the finished store as an xarray Dataset; :func:`summary` and
  :func:`histogram` its spread from the base scene, reduced chunk by chunk;
* :mod:`ga_rotors.sweep.budget` — the steps, memory and disk a sweep will take, checked
  before anything is written;
* :func:`keep_freed_memory` — what ``ga-rotors sweep`` does to its process's allocator
  so that each chunk's arrays do not fault their pages in afresh.

Needs ``pip install "ga-rotors[dask]"`` (Dask, xarray, zarr). ``ga-rotors sweep`` is the
command; docs/ensembles.md a worked study.
"""

from __future__ import annotations

from .run import (
    LOCAL_CLUSTER_CONFIG,
    histogram,
    keep_freed_memory,
    local_cluster,
    open_sweep,
    run_chunk,
    run_sweep,
    summary,
)
from .spec import BLOCK, Sweep, load_sweep

__all__ = [
    "BLOCK",
    "LOCAL_CLUSTER_CONFIG",
    "Sweep",
    "histogram",
    "keep_freed_memory",
    "load_sweep",
    "local_cluster",
    "open_sweep",
    "run_chunk",
    "run_sweep",
    "summary",
]
