"""Results in the field's formats: CF xarray Datasets, netCDF and zarr files, NPZ, CSV.

* :func:`to_dataset` — a :class:`~ga_rotors.trajectory.Trajectory` as an
  :class:`xarray.Dataset` following the CF conventions (an indexed ``time`` coordinate;
  units and long names; how it was made, the body frame included, as attributes);
* :func:`write` / :func:`read` — a ``.nc`` or ``.zarr`` file, written atomically and read
  back as the same Dataset;
* :func:`write_npz` — an NPZ archive of the arrays, their labels and attributes;
* :func:`write_csv` — CSV for spreadsheets, with units in the headers, described by a
  W3C CSVW metadata sidecar (``<file>.csv-metadata.json``: units, the run's attributes).

xarray, h5netcdf and zarr come with the results extra (``pip install ".[results]"`` in the
repository); a function that needs a missing one says so in one line
(:class:`ga_rotors.optional.MissingExtraError`).
NPZ and CSV need nothing beyond numpy (CSV is written by polars when it is installed).
"""

from __future__ import annotations

from .dataset import to_dataset
from .npz import write_npz
from .provenance import body_frame, provenance
from .store import read, write
from .table import write_csv
from .variables import describe

__all__ = [
    "body_frame",
    "describe",
    "provenance",
    "read",
    "to_dataset",
    "write",
    "write_csv",
    "write_npz",
]
