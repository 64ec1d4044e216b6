"""Sweeps and Monte-Carlo dispersion studies of a scene, chunk by chunk into a zarr store.

* :func:`load_sweep` — a sweep file: the scene, grid keys, random draws and seed
  (:mod:`ga_rotors.sweep.spec`);
* :func:`run_sweep` — run (or resume) it chunk by chunk into a ``.zarr`` store: on Dask's
  threaded scheduler in this process by default (a thread pool without Dask), or on a
  Dask cluster (a scheduler's address, a ``distributed.Client``; :func:`local_cluster`
  starts one of worker processes on this machine);
* :func:`open_sweep` — the finished store as an xarray Dataset (``xr.open_zarr`` reads it
  too); :func:`summary` each grid point's spread from its own nominal run, with the
  samples that failed, and :func:`histogram` its counts;
* :mod:`ga_rotors.sweep.budget` — the steps, memory, disk and files a sweep will take,
  checked before anything is written.

Needs the dask extra: Dask, xarray, zarr (``pip install ".[dask]"`` in the repository).
``ga-rotors sweep`` is the command; docs/ensembles.md the guide.
"""

from __future__ import annotations

from .budget import SweepBudget
from .run import LOCAL_CLUSTER_CONFIG, local_cluster, open_sweep, run_chunk, run_sweep
from .spec import BLOCK, Sweep, coordinate_name, load_sweep, read_sweep
from .summary import histogram, summary

__all__ = [
    "BLOCK",
    "LOCAL_CLUSTER_CONFIG",
    "Sweep",
    "SweepBudget",
    "coordinate_name",
    "histogram",
    "load_sweep",
    "local_cluster",
    "open_sweep",
    "read_sweep",
    "run_chunk",
    "run_sweep",
    "summary",
]
