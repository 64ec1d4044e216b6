"""Results on disk: netCDF (``.nc``, through h5netcdf) or zarr (``.zarr``), written whole
or not at all.

:func:`write` takes a :class:`~ga_rotors.trajectory.Trajectory` (converted by
:func:`ga_rotors.results.to_dataset`) or an :class:`xarray.Dataset`; :func:`read` gives
back the Dataset that was written, values, units and attributes alike. Both formats are
written into a staging folder and moved onto the target (:func:`ga_rotors.files.output_file`:
an interruption leaves the previous file or store, or the new one, never a mix).
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError, first_line
from ..files import checked_path, output_file, shown_path
from ..optional import require

__all__ = ["CHUNK_ROWS", "FORMATS", "ZARR_FORMAT", "chunk_encoding", "format_of", "read", "write"]

#: file suffix -> format name.
FORMATS = {".nc": "netcdf", ".zarr": "zarr"}

_ENGINES = {"netcdf": "h5netcdf", "zarr": "zarr"}  # format -> xarray's engine, its module

#: Rows per chunk along ``time`` of a zarr store, and of a streamed netCDF file, at most:
#: 16,384 rows of a 4-component array are 512 kB, what a streamed run holds per array.
CHUNK_ROWS = 16_384

#: Zarr stores are written in format 2: its string coordinates (component labels) have a
#: specification every zarr reader knows, which format 3's do not have yet.
ZARR_FORMAT = 2


def format_of(path) -> str:
    """The results format a path's suffix names.

    Examples
    --------
    >>> format_of("run.nc"), format_of("sweep.zarr")
    ('netcdf', 'zarr')
    >>> format_of("run.txt")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: path: run.txt: expected a .nc (netcdf) or a .zarr (zarr) name
    """
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        choices = " or ".join(f"a {s} ({f})" for s, f in FORMATS.items())
        raise InputError(f"path: {shown_path(path)}: expected {choices} name")
    return FORMATS[suffix]


def write(data, path, scene=None) -> Path:
    """Write a trajectory or Dataset to ``path`` (``.nc`` or ``.zarr``), atomically.

    A netCDF file is written contiguous (no chunks: a 61-row run takes a few kB); a zarr
    store in chunks of at most :data:`CHUNK_ROWS` rows (:func:`chunk_encoding`). The
    Dataset's own encodings (those of a file it was read from) are not carried over.

    Parameters
    ----------
    data : Trajectory or xarray.Dataset
    path : str or Path
    scene : Scene, optional
        Passed to :func:`ga_rotors.results.to_dataset` for a trajectory.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.array([0.0, 1.0]), "energy": np.array([2.0, 2.0])})
    >>> p = write(tr, pathlib.Path(tempfile.mkdtemp()) / "run.nc")
    >>> read(p)["energy"].attrs["units"], p.stat().st_size < 20_000
    ('J', True)
    """
    from .dataset import to_dataset

    path = checked_path(path, "path")
    fmt = format_of(path)
    ds = data if hasattr(data, "data_vars") else to_dataset(data, scene)
    ds = ds.drop_encoding()
    require(_ENGINES[fmt], "results")
    encoding = chunk_encoding(ds, "zarr", ds.sizes.get("time", 0))
    with output_file(path) as staged:
        if fmt == "netcdf":
            ds.to_netcdf(staged, engine="h5netcdf")
        else:
            ds.to_zarr(staged, zarr_format=ZARR_FORMAT, consolidated=True, encoding=encoding)
    return path


def chunk_encoding(ds, fmt: str, rows: int) -> dict:
    """The encoding that chunks each ``time`` variable of ``ds`` along ``time`` in pieces of
    ``rows`` rows, at most :data:`CHUNK_ROWS` (and at least one): for ``fmt`` "netcdf"
    (``chunksizes``) or "zarr" (``chunks``).

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> ds = xr.Dataset({"w": (("time", "axis"), np.zeros((61, 3)))})
    >>> chunk_encoding(ds, "zarr", 61), chunk_encoding(ds, "netcdf", 10**7)
    ({'w': {'chunks': (61, 3)}}, {'w': {'chunksizes': (16384, 3)}})
    """
    key = "chunksizes" if fmt == "netcdf" else "chunks"
    rows = min(max(int(rows), 1), CHUNK_ROWS)
    return {
        name: {key: (rows, *var.shape[1:])}
        for name, var in ds.variables.items()
        if var.dims[:1] == ("time",)
    }


#: Gibibytes :func:`read` loads at most unless told otherwise (as a run's memory budget).
READ_MEMORY_GIB = 2.0


def read(path, lazy: bool = False, max_memory_gib: float = READ_MEMORY_GIB):
    """The Dataset stored at ``path`` (``.nc`` or ``.zarr``): loaded into memory, or
    ``lazy``, its values read from the file as they are used.

    A streamed run's file can hold more than memory (10⁸ steps of the heavy top are
    gigabytes): a file whose data is over ``max_memory_gib`` is refused with one line,
    before anything is loaded, rather than filling the memory. Read it ``lazy`` then,
    and use a slice, a reduction or ``.chunk()`` for Dask; a lazy netCDF file stays
    open until the Dataset is closed (``with read(p, lazy=True) as ds:``).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np, xarray as xr
    >>> ds = xr.Dataset({"t": ("time", np.arange(3.0))}, attrs={"integrator": "rk4"})
    >>> p = write(ds, pathlib.Path(tempfile.mkdtemp()) / "run.zarr")
    >>> read(p).identical(ds)
    True
    >>> read(p, max_memory_gib=1e-9)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: path: ...run.zarr: 2.24e-08 GiB of data, more than ...
    >>> with read(p, lazy=True) as lazy:
    ...     float(lazy["t"][-1])
    2.0
    """
    xr = require("xarray", "results")
    path = checked_path(path, "path")
    fmt = format_of(path)
    ok = isinstance(max_memory_gib, int | float) and not isinstance(max_memory_gib, bool)
    if not (ok and max_memory_gib > 0):
        raise InputError(
            f"expected a positive number, got {max_memory_gib!r}", key="max_memory_gib"
        )
    try:
        found = path.exists()
    except OSError as exc:  # a name too long, a loop of links
        raise _unreadable(path, fmt, exc) from None
    if not found:
        raise InputError(f"path: {shown_path(path)}: no such file or store")
    try:
        require(_ENGINES[fmt], "results")
        ds = xr.open_dataset(path, engine=_ENGINES[fmt])
    except (OSError, ValueError, KeyError) as exc:
        raise _unreadable(path, fmt, exc) from None
    if lazy:
        return ds
    with ds:
        if ds.nbytes > max_memory_gib * 2**30:
            raise InputError(
                f"path: {shown_path(path)}: {ds.nbytes / 2**30:.3g} GiB of data, more than "
                f"max_memory_gib = {max_memory_gib:g} GiB at once; read(path, lazy=True) "
                "reads values as they are used"
            )
        try:
            return ds.load()
        except (OSError, ValueError, KeyError) as exc:
            raise _unreadable(path, fmt, exc) from None


def _unreadable(path: Path, fmt: str, exc: Exception) -> InputError:
    # the system's reason without the path it repeats; a library's first line, cut short
    detail = exc.strerror if isinstance(exc, OSError) and exc.strerror else first_line(exc)
    return InputError(
        f"path: {shown_path(path)}: not a readable {fmt} results file ({detail[:200]})"
    )
