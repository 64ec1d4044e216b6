"""Results in the field's formats: xarray Datasets, netCDF and zarr files, CSV with units.

* :func:`to_dataset` — a :class:`~ga_rotors.trajectory.Trajectory` as an
  :class:`xarray.Dataset` (dimension ``time``; units, descriptions and how it was made);
* :func:`write` / :func:`read` — a ``.nc`` or ``.zarr`` file, written atomically and read
  back as the same Dataset;
* :func:`write_csv` — CSV for spreadsheets, with units in the headers.

xarray, h5netcdf and zarr come with ``pip install "ga-rotors[results]"``; a function that
needs a missing one says so in one line (:class:`ga_rotors.optional.MissingExtraError`).
CSV needs nothing beyond numpy.
"""

from __future__ import annotations

from .dataset import provenance, to_dataset
from .store import read, write
from .table import write_csv
from .variables import describe

__all__ = ["describe", "provenance", "read", "to_dataset", "write", "write_csv"]
