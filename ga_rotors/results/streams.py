"""Results files written piece by piece as a long run goes on: memory holds one piece.

Each writer takes a run's pieces in order (:class:`~ga_rotors.trajectory.Trajectory`
objects of consecutive samples, as :func:`ga_rotors.simulation.simulate_chunks` hands them
out) with ``append``; ``close`` finishes the file with the run's final ``meta`` (which
paths completed, how many samples each has), ``abort`` drops it after a failure. The file
is the one the whole trajectory gives written in one go (:class:`CsvStream`,
:class:`~.npz.NpzStream`, :class:`NetcdfStream`, :class:`ZarrStream`), chunked along
``time`` by :data:`~.store.CHUNK_ROWS` rows, or the run's rows when it has fewer. Writers
write where they are told: a scene run points them into its staging folder
(:func:`ga_rotors.files.output_set`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..optional import require
from . import store
from .dataset import bound_rows, run_attributes, time_rows, to_dataset
from .npz import NpzStream
from .variables import one_unit

__all__ = ["ZARR_WRITE_CHUNKS", "CsvStream", "NetcdfStream", "NpzStream", "ZarrStream",
           "sample_count"]  # fmt: skip

#: Chunks of rows a :class:`ZarrStream` collects before each write: each write through
#: xarray opens the store and rewrites its arrays' metadata, so it is done for many rows
#: at once (8 chunks of 16,384 rows: 4 MB per 4-column array held at most).
ZARR_WRITE_CHUNKS = 8

#: Bytes of the buffer between a :class:`CsvStream` and its file.
CSV_BUFFER = 1 << 20


def sample_count(meta: dict) -> int:
    """Samples of the run a piece's ``meta`` belongs to: every ``sample_every``-th step
    from 0, and the last step when it is off that pattern.

    Examples
    --------
    >>> sample_count({"steps": 60, "sample_every": 7}), sample_count({"steps": 60,
    ...                                                               "sample_every": 6})
    (10, 11)
    """
    steps, every = meta["steps"], meta["sample_every"]
    return steps // every + 1 + (1 if steps % every else 0)


class _RunStream:
    """What every streamed writer keeps of a run's pieces: their rows, each array's rows
    (short for a stopped path), the times the exact reference's bound is evaluated at
    (:func:`~.dataset.bound_rows` of the run's sample count, every time when the pieces
    do not say it); the rows not yet in the file (:meth:`_dataset`); the open file."""

    def __init__(self, path, scene=None):
        self.path, self.scene = Path(path), scene
        self.rows = self.written = 0  # rows taken, rows in the file
        self.valid: dict[str, int] = {}  # array -> rows taken (short for a stopped path)
        self.chunk_rows = store.CHUNK_ROWS  # rows per chunk along time, by the first piece
        self._held: list[dict] = []  # rows taken, not yet in the file (time_rows)
        self._bound_rows, self._bound_times = None, []
        self._file = self.columns = None  # the first piece's arrays with no rows

    def _take(self, piece) -> dict:
        """Count the piece's rows, pick its bound times; its arrays as the files hold them
        (:func:`~.dataset.time_rows`)."""
        from ..trajectory import Trajectory

        piece = one_unit(piece)
        if self.rows == 0:
            self.columns = Trajectory({n: piece[n][:0] for n in piece.names}, piece.components)
            meta = piece.meta
            expected = sample_count(meta) if "steps" in meta and "sample_every" in meta else 0
            self.chunk_rows = min(store.CHUNK_ROWS, expected or store.CHUNK_ROWS)
            self._bound_rows = bound_rows(expected) if expected else None  # None: all
        if self.scene is not None:
            t, pick = piece.t, self._bound_rows
            if pick is not None:
                t = t[pick[(pick >= self.rows) & (pick < self.rows + len(t))] - self.rows]
            self._bound_times.append(t)
        for name in piece.names:
            self.valid[name] = self.valid.get(name, 0) + piece[name].shape[0]
        self.rows += len(piece)
        return time_rows(piece)

    def _dataset(self, end: int):
        """The held rows up to row ``end`` of the run as a Dataset; the rest stay held."""
        from ..trajectory import Trajectory

        arrays = {name: np.concatenate([h[name] for h in self._held]) for name in self._held[0]}
        take, self.written = end - self.written, end
        self._held = [{name: a[take:] for name, a in arrays.items()}] if end < self.rows else []
        head = {name: a[:take] for name, a in arrays.items()}
        return to_dataset(Trajectory(head, self.columns.components))

    def _finish(self, attrs, variable_attrs, meta: dict) -> None:
        """Set the file's attributes ``attrs`` to those :func:`~.dataset.run_attributes`
        gives the whole run (from the final ``meta``; they overwrite every attribute the
        first rows' Dataset had), and each short array's ``valid_samples``
        (``variable_attrs(name)``; the rows written are padded, so none has one yet)."""
        times = np.concatenate(self._bound_times) if self._bound_times else ()
        attrs.update(run_attributes(meta, self.scene, times))
        for name, rows in self.valid.items():
            if name != "t" and rows < self.rows:
                variable_attrs(name)["valid_samples"] = int(rows)

    def abort(self) -> None:
        """Drop the rows held and close the file (the staging folder goes away with it)."""
        self._held = []
        f, self._file = self._file, None
        if f is not None:
            f.close()


class CsvStream(_RunStream):
    """CSV written piece by piece, and its CSVW metadata at :meth:`close`: the files of
    :func:`ga_rotors.results.table.write_csv_files`.

    Examples
    --------
    >>> import json, tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> out = CsvStream(path)
    >>> out.append(Trajectory({"t": np.array([0.0, 0.5]), "energy": np.array([1.0, 2.0])}))
    >>> out.append(Trajectory({"t": np.array([1.0]), "energy": np.array([3.0])}))
    >>> out.close({"integrator": "rk4"})
    >>> print(path.read_text().replace(".0,", ",").replace(".0\\n", "\\n"), end="")
    t [s],energy [J]
    0,1
    0.5,2
    1,3
    >>> json.loads(path.with_name("run.csv-metadata.json").read_text())["url"]
    'run.csv'
    """

    def __init__(self, path, scene=None, *, engine: str | None = None):
        from .table import csv_engine

        super().__init__(path, scene)
        self.engine = csv_engine(engine)
        self._file = open(self.path, "wb", buffering=CSV_BUFFER)

    def append(self, piece) -> None:
        """Write the rows of ``piece`` (the header line first, with the first piece)."""
        from .table import csv_rows

        csv_rows(self._file, piece, self.engine, header=self.columns is None)
        self._take(piece)

    def close(self, meta: dict) -> None:
        """Finish the file; write its metadata, with the run's attributes (the final
        ``meta``)."""
        from ..trajectory import Trajectory
        from .table import write_metadata

        self.abort()
        columns = Trajectory({"t": np.zeros(0)}) if self.columns is None else self.columns
        attrs: dict = {}
        self._finish(attrs, lambda name: {}, meta)
        write_metadata(self.path, columns, attrs)


class NetcdfStream(_RunStream):
    """netCDF (HDF5, through h5netcdf), growing along an unlimited ``time`` dimension.

    The first piece makes the file through xarray (variables, units, chunks of the run's
    rows up to :data:`~.store.CHUNK_ROWS`: a 61-row run's file is 42 kB, where a
    contiguous one is 28 kB), which stays open for the pieces after it: each
    :meth:`append` extends every ``time`` variable (the ``time`` coordinate, the
    dimension's scale, among them) through h5py, the HDF5 library under h5netcdf, whose
    own variables looked each dataset up several times per write (1 s of a 10⁷-step run's
    2.7 s of CPU, against 0.3 s).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> from ga_rotors.results import read
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.nc"
    >>> out = NetcdfStream(path)
    >>> for lo in (0, 2):
    ...     out.append(Trajectory({"t": np.arange(lo, lo + 2.0), "energy": np.ones(2)}))
    >>> out.close({"integrator": "rk4"})
    >>> ds = read(path)
    >>> ds["time"].values.tolist(), ds["energy"].attrs["units"], ds.attrs["integrator"]
    ([0.0, 1.0, 2.0, 3.0], 'J', 'rk4')
    """

    def __init__(self, path, scene=None):
        require("xarray", "results")
        super().__init__(path, scene)

    def append(self, piece) -> None:
        """Make the file of the first piece, or extend every ``time`` variable by the
        piece's rows."""
        self._held.append(self._take(piece))
        if self._file is None:
            ds = self._dataset(self.rows)
            ds.to_netcdf(self.path, engine="h5netcdf", unlimited_dims=["time"],
                         encoding=store.chunk_encoding(ds, "netcdf", self.chunk_rows))  # fmt: skip
            self._file = require("h5py", "results").File(self.path, "a")
            # looked up once: h5py finds a dataset by name anew on each lookup (60 ms of
            # a 10⁷-step run's writes, done per piece)
            self._variables = {n: self._file["time" if n == "t" else n] for n in self.valid}
            return
        for name, a in self._held.pop().items():
            variable = self._variables[name]
            variable.resize(self.rows, axis=0)
            variable[self.written : self.rows, ...] = a
        self.written = self.rows

    def close(self, meta: dict) -> None:
        """Write the run's attributes (the final ``meta``) and the short paths' counts."""
        if self._file is None:
            return
        self.abort()
        with require("h5netcdf", "results").File(self.path, "a") as f:  # netCDF's attr types
            self._finish(f.attrs, lambda name: f.variables[name].attrs, meta)


class ZarrStream(_RunStream):
    """A zarr store (format 2, as :func:`ga_rotors.results.write` writes) appended along
    ``time`` through xarray, its metadata consolidated at the end.

    Pieces are held until :data:`ZARR_WRITE_CHUNKS` whole chunks of rows are there, then
    written with ``to_zarr`` (the first block making the store, the next ones
    ``append_dim="time"``), so each chunk is written once, whole; the rows left at the end
    go with :meth:`close`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> from ga_rotors.results import read
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.zarr"
    >>> out = ZarrStream(path)
    >>> for lo in (0, 2):
    ...     out.append(Trajectory({"t": np.arange(lo, lo + 2.0), "energy": np.ones(2)},
    ...                           meta={"steps": 3, "sample_every": 1}))
    >>> out.close({})
    >>> read(path)["time"].values.tolist()
    [0.0, 1.0, 2.0, 3.0]
    """

    def __init__(self, path, scene=None):
        require("xarray", "results")
        require("zarr", "results")
        super().__init__(path, scene)

    def append(self, piece) -> None:
        """Hold the piece's rows; write the whole blocks of chunks held."""
        self._held.append(self._take(piece))
        block = self.chunk_rows * ZARR_WRITE_CHUNKS
        end = self.written + (self.rows - self.written) // block * block
        if end > self.written:
            self._write(end)

    def _write(self, end: int) -> None:
        """Write the rows held up to row ``end`` of the run (the first ones make the store);
        keep the rest."""
        first = self.written == 0
        ds = self._dataset(end)
        how = {"mode": "w", "encoding": store.chunk_encoding(ds, "zarr", self.chunk_rows)}
        ds.to_zarr(self.path, zarr_format=store.ZARR_FORMAT, consolidated=False,
                   **(how if first else {"append_dim": "time"}))  # fmt: skip

    def close(self, meta: dict) -> None:
        """Write the rows left, the run's attributes, the short paths' counts; consolidate
        the metadata."""
        if self.rows == 0:
            return
        zarr = require("zarr", "results")
        if self.rows > self.written:
            self._write(self.rows)
        group = zarr.open_group(str(self.path), mode="r+", zarr_format=store.ZARR_FORMAT)
        self._finish(group.attrs, lambda name: group[name].attrs, meta)
        zarr.consolidate_metadata(str(self.path), zarr_format=store.ZARR_FORMAT)
