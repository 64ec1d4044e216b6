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
from ..optional import require

__all__ = ["FORMATS", "ZARR_FORMAT", "format_of", "read", "write"]

#: file suffix -> format name.
FORMATS = {".nc": "netcdf", ".zarr": "zarr"}

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
        raise InputError(f"path: {path}: expected {choices} name")
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
        raise InputError(f"path: {target} exists and is not a zarr store (a directory)")
    old = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}.previous-"))
    os.rename(target, old / "store")
    os.rename(staging, target)
    shutil.rmtree(old, ignore_errors=True)


def write(data, path, scene=None) -> Path:
    """Write a trajectory or Dataset to ``path`` (``.nc`` or ``.zarr``), atomically.

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
    >>> read(p)["energy"].attrs["units"]
    'J'
    """
    from .dataset import to_dataset

    fmt = format_of(path)
    ds = data if hasattr(data, "data_vars") else to_dataset(data, scene)
    path = Path(path)
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"path: directory {parent} does not exist")
    if fmt == "netcdf":
        engine = _netcdf_engine()
        return _staged(path, lambda p: ds.to_netcdf(p, engine=engine))
    require("zarr", "results")
    return _staged(
        path, lambda p: ds.to_zarr(p, mode="w", zarr_format=ZARR_FORMAT, consolidated=True)
    )


def _staged(path: Path, writer) -> Path:
    """``writer(p)`` into a staging directory beside ``path``, then moved onto ``path``."""
    parent = path.parent if str(path.parent) else Path(".")
    staging = Path(tempfile.mkdtemp(dir=parent, prefix=f".{path.name}.staging-"))
    try:
        writer(staging / "new")
        if (staging / "new").is_dir():
            _replace_dir(staging / "new", path)
        else:
            if path.is_dir():
                raise InputError(f"path: {path} is a directory; expected a file name")
            os.replace(staging / "new", path)
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
    fmt = format_of(path)
    path = Path(path)
    ok = isinstance(max_memory_gib, int | float) and not isinstance(max_memory_gib, bool)
    if not (ok and max_memory_gib > 0):
        raise InputError(
            f"expected a positive number, got {max_memory_gib!r}", key="max_memory_gib"
        )
    if not path.exists():
        raise InputError(f"path: {path}: no such file or store")
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
                f"path: {path}: {ds.nbytes / 2**30:.3g} GiB of data, more than max_memory_gib = "
                f"{max_memory_gib:g} GiB at once; read(path, lazy=True) reads values as they "
                "are used"
            )
        try:
            return ds.load()
        except (OSError, ValueError, KeyError) as exc:
            raise _unreadable(path, fmt, exc) from None


def _unreadable(path: Path, fmt: str, exc: Exception) -> InputError:
    return InputError(f"path: {path}: not a readable {fmt} results file ({first_line(exc)})")
