"""Data formats a scene run can write (``output.data``): one registry, one entry per format.

Each :class:`DataFormat` names its file suffix and how to write a trajectory to a path;
the schema accepts exactly the names in :data:`FORMATS`, and
:func:`ga_rotors.scene.output.write_outputs` writes each declared one through the atomic
writer. A new format is one :func:`register` call (``docs/extending.md``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from ..errors import InputError

__all__ = ["FORMATS", "DataFormat", "register"]


@dataclass(frozen=True)
class DataFormat:
    """One data format: ``write(trajectory, path)`` writes the whole file at ``path``.

    ``path`` is in a staging directory (the run's files move into place together), so
    the writer need not be atomic itself.

    Examples
    --------
    >>> FORMATS["csv"].suffix, FORMATS["csv"].doc
    ('.csv', 'every array as CSV columns, full precision')
    """

    name: str
    suffix: str
    doc: str
    write: Callable = field(repr=False)


def _csv(trajectory, path):
    return trajectory.to_csv(path)


def _npz(trajectory, path):
    return trajectory.to_npz(path)


def _netcdf(trajectory, path):
    from ..results import write  # xarray and h5netcdf: the [results] extra

    return write(trajectory, path)


#: format name -> DataFormat, in the order the docs list them.
FORMATS: dict[str, DataFormat] = {}


def register(fmt: DataFormat) -> DataFormat:
    """Add a data format (names are unique) and return it.

    Examples
    --------
    >>> register(FORMATS["npz"]) is FORMATS["npz"]      # the same one again: no change
    True
    >>> register(DataFormat("npz", ".npy", "another", _npz))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: register: a data format named 'npz' already exists
    """
    if not isinstance(fmt, DataFormat):
        raise InputError(f"expected a DataFormat, got {fmt!r}", key="register")
    existing = FORMATS.get(fmt.name)
    if existing is not None and existing is not fmt:
        raise InputError(f"a data format named {fmt.name!r} already exists", key="register")
    FORMATS[fmt.name] = fmt
    return fmt


register(DataFormat("csv", ".csv", "every array as CSV columns, full precision", _csv))
register(DataFormat("npz", ".npz", "every array in one NumPy .npz archive", _npz))
register(
    DataFormat(
        "netcdf", ".nc", "every array with its unit and the run's settings (ga-rotors[results])",
        _netcdf,
    )
)  # fmt: skip
