"""Results on disk: netCDF (``.nc``) or zarr (``.zarr``), written whole or not at all.

:func:`write` takes a :class:`~ga_rotors.trajectory.Trajectory` (converted by
:func:`ga_rotors.results.to_dataset`) or an :class:`xarray.Dataset`; :func:`read` gives
back the Dataset that was written, values, units and attributes alike.

Both are first written into a staging directory beside the target and then moved onto
it: a netCDF file by one ``os.replace``; a zarr store (a directory) by renames, an
existing store moved aside first and deleted after, so an interruption leaves the previous
store, the new one, or the previous one under ``.<name>.previous-*`` — never a mix.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

from ..errors import InputError, first_line
from ..files import checked_path, shown_path
from ..optional import require

__all__ = ["CHUNK_ROWS", "FORMATS", "ZARR_FORMAT", "chunk_encoding", "format_of", "read", "write"]

#: file suffix -> format name.
FORMATS = {".nc": "netcdf", ".zarr": "zarr"}

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


def _netcdf_engine() -> str:
    for module, engine in (("h5netcdf", "h5netcdf"), ("netCDF4", "netcdf4")):
        try:
            require(module, "results")
            return engine
        except ImportError:
            continue
    require("h5netcdf", "results")  # raises, naming the extra
    raise AssertionError("unreachable")


def _replace_dir(staging: Path, target: Path) -> None:
    """Move the finished store ``staging`` onto ``target`` (a directory or nothing)."""
    if not target.exists():
        os.rename(staging, target)
        return
    if not target.is_dir():
        raise InputError(f"path: {shown_path(target)} exists and is not a zarr store (a directory)")
    old = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}.previous-"))
    os.rename(target, old / "store")
    os.rename(staging, target)
    shutil.rmtree(old, ignore_errors=True)


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
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"path: directory {shown_path(parent)} does not exist")
    if fmt == "netcdf":
        engine = _netcdf_engine()
        return _staged(path, lambda p: ds.to_netcdf(p, engine=engine))
    require("zarr", "results")
    encoding = chunk_encoding(ds, "zarr", ds.sizes.get("time", 0))
    return _staged(
        path,
        lambda p: ds.to_zarr(
            p, mode="w", zarr_format=ZARR_FORMAT, consolidated=True, encoding=encoding
        ),
    )


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


def _staged(path: Path, writer) -> Path:
    """``writer(p)`` into a staging directory beside ``path``, then moved onto ``path``
    (what the system refuses, a name too long or a full disk, is one line naming it)."""
    parent = path.parent if str(path.parent) else Path(".")
    try:
        staging = Path(tempfile.mkdtemp(dir=parent, prefix=f".{path.name[:200]}.staging-"))
    except OSError as exc:
        raise InputError(f"path: cannot write {shown_path(path)}: {exc.strerror or exc}") from None
    try:
        writer(staging / "new")
        try:
            if (staging / "new").is_dir():
                _replace_dir(staging / "new", path)
            elif path.is_dir():
                raise InputError(f"path: {shown_path(path)} is a directory; expected a file name")
            else:
                os.replace(staging / "new", path)
        except OSError as exc:
            raise InputError(
                f"path: cannot write {shown_path(path)}: {exc.strerror or exc}"
            ) from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return path


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
        if fmt == "netcdf":
            ds = xr.open_dataset(path, engine=_netcdf_engine())
        else:
            require("zarr", "results")
            ds = xr.open_zarr(path, consolidated=None)
    except (OSError, ValueError, KeyError) as exc:
        raise _unreadable(path, fmt, exc) from None
    if lazy:
        return ds
    with ds:
        if ds.nbytes > max_memory_gib * 2**30:
            raise InputError(
                f"path: {shown_path(path)}: {ds.nbytes / 2**30:.3g} GiB of data, more than "
                f"max_memory_gib = "
                f"{max_memory_gib:g} GiB at once; read(path, lazy=True) reads values as they "
                "are used"
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
