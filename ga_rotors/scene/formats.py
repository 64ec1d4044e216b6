"""Data formats a scene run can write (``output.data``): one registry, one entry per format.

Each :class:`DataFormat` names its file suffix, how to write a whole trajectory to a path
and how to open a writer that takes a run piece by piece (``stream``: the four built-in
formats write as the run goes on, see :mod:`ga_rotors.results.streams`); the schema
accepts exactly the names in :data:`FORMATS`, and :func:`ga_rotors.scene.stream_scene`
writes each declared one into the run's staging folder. A new format is one
:func:`register` call (``docs/extending.md``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from ..errors import InputError
from ..results.table import METADATA_SUFFIX

__all__ = ["FORMATS", "DataFormat", "default_data", "register", "require_formats"]


@dataclass(frozen=True)
class DataFormat:
    """One data format: ``write(trajectory, path)`` writes the whole file at ``path`` (and
    its ``companions`` beside it);
    ``stream(path, scene)``, if given, opens a writer taking the run piece by piece
    (``append(piece)``, then ``close(meta)``; ``abort()`` on failure).

    ``path`` is in a staging directory (the run's files move into place together), so
    the writer need not be atomic itself. A format without ``stream`` is written whole
    at the end of the run, its pieces kept in memory until then.

    Examples
    --------
    >>> FORMATS["csv"].suffix, FORMATS["csv"].companions
    ('.csv', ('-metadata.json',))
    """

    name: str
    suffix: str
    doc: str
    write: Callable = field(repr=False)
    stream: Callable | None = field(default=None, repr=False)
    #: (module, extra) pairs the format imports: checked before a run starts
    needs: tuple[tuple[str, str], ...] = ()
    #: what the data file's name gets for each other file its writers write beside it
    #: (CSV: its CSVW metadata, ``<name>.csv-metadata.json``)
    companions: tuple[str, ...] = ()

    def files(self, name: str) -> list[str]:
        """The names of the files this format writes for a run named ``name``.

        Examples
        --------
        >>> FORMATS["csv"].files("top"), FORMATS["npz"].files("top")
        (['top.csv', 'top.csv-metadata.json'], ['top.npz'])
        """
        data = f"{name}{self.suffix}"
        return [data, *(data + companion for companion in self.companions)]

    def open(self, path, scene=None):
        """A writer of this format at ``path`` for the pieces of a run.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> import numpy as np
        >>> from ga_rotors.trajectory import Trajectory
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
        >>> out = FORMATS["csv"].open(path)
        >>> out.append(Trajectory({"t": np.array([0.0, 1.0])}))
        >>> out.close({})
        >>> lines = path.read_text().splitlines()
        >>> lines[0], [float(x) for x in lines[1:]]
        ('t [s]', [0.0, 1.0])
        """
        if self.stream is not None:
            return self.stream(path, scene)
        return _Whole(self, path)


def default_data() -> list[str]:
    """The data formats of a scene whose ``output.data`` is not given: a binary format, so
    a long run writes at about the speed of its integration (CSV text costs several times
    more: ``benchmarks/bench_stream.py``). netCDF, the field's format with the run's units,
    frame and settings (CF), where the ``results`` extra is installed; NPZ, which needs
    numpy only, where it is not.

    Examples
    --------
    >>> default_data() in (["netcdf"], ["npz"])
    True
    """
    import importlib.util

    installed = all(importlib.util.find_spec(module) for module, _ in FORMATS["netcdf"].needs)
    return ["netcdf"] if installed else ["npz"]


def require_formats(scene) -> None:
    """Refuse, before anything runs, a scene whose ``output.data`` names a format whose
    optional packages are not installed: one line naming the file, the key and the
    ``pip install`` command (not a failure after the run's first piece).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> require_formats(load_scene("heavy_top"))   # CSV: nothing to install
    """
    from ..errors import SceneError
    from ..optional import MissingExtraError, require

    for i, name in enumerate(scene.data["output"]["data"]):
        for module, extra in FORMATS[name].needs:
            try:
                require(module, extra)
            except MissingExtraError as exc:
                raise SceneError(scene.file, f"output.data[{i}]", f"{name!r}: {exc}") from None


class _Whole:
    """The writer of a format that only writes whole trajectories: pieces kept, joined."""

    def __init__(self, fmt: DataFormat, path):
        self.fmt, self.path, self.pieces = fmt, path, []

    def append(self, piece) -> None:
        self.pieces.append(piece)

    def close(self, meta: dict) -> None:
        import numpy as np

        from ..trajectory import Trajectory

        first = self.pieces[0]
        arrays = {n: np.concatenate([p[n] for p in self.pieces]) for n in first.names}
        self.fmt.write(Trajectory(arrays, first.components, meta), self.path)

    def abort(self) -> None:
        self.pieces = []


def _csv(trajectory, path):
    from ..results.table import write_csv_files  # in the staging folder: both files

    return write_csv_files(trajectory, path)


def _npz(trajectory, path):
    return trajectory.to_npz(path)


def _store(trajectory, path):
    from ..results import write  # xarray and h5netcdf: the [results] extra

    return write(trajectory, path)


def _stream(name: str):
    def open_stream(path, scene):
        from ..results import streams

        return getattr(streams, name)(path, scene)

    return open_stream


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


register(
    DataFormat("csv", ".csv", "every array as CSV columns, full precision, and their CSVW "
               "metadata", _csv, _stream("CsvStream"), companions=(METADATA_SUFFIX,))
)  # fmt: skip
register(
    DataFormat("npz", ".npz", "every array in one NumPy .npz archive", _npz,
               _stream("NpzStream"))
)  # fmt: skip
register(
    DataFormat(
        "netcdf", ".nc", "every array with its unit and the run's settings (the results extra)",
        _store, _stream("NetcdfStream"), (("xarray", "results"), ("h5netcdf", "results")),
    )
)  # fmt: skip
register(
    DataFormat(
        "zarr", ".zarr", "a zarr store: the netCDF content, chunked (the results extra)",
        _store, _stream("ZarrStream"), (("xarray", "results"), ("zarr", "results")),
    )
)  # fmt: skip
