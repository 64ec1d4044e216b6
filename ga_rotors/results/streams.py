"""Results files written piece by piece, as a long run goes on: memory holds one piece.

Each writer takes the pieces of one run in order (:class:`~ga_rotors.trajectory.Trajectory`
objects of consecutive samples, the first holding sample 0, as
:func:`ga_rotors.simulation.simulate_chunks` hands them out) with ``append``, and
finishes the file with ``close``, given the run's final ``meta`` (what the run became:
which paths completed, how many samples each has). The file is the one the whole
trajectory would give, written in one go:

* :class:`CsvStream` — CSV with units in the headers (:class:`~.table.CsvRows`), through
  one buffered file, and its CSVW metadata sidecar (:func:`~.table.csv_metadata`);
* :class:`~.npz.NpzStream` — the ``.npz`` archive of :func:`~.npz.write_npz`;
* :class:`NetcdfStream` — netCDF along an unlimited ``time`` dimension (h5netcdf),
  extended per piece;
* :class:`ZarrStream` — a zarr store (format 2) appended along ``time`` through xarray,
  whole chunks at a time.

netCDF and zarr files read back (:func:`ga_rotors.results.read`) as the Dataset
:func:`ga_rotors.results.to_dataset` makes of the whole trajectory; their chunks along
``time`` are :data:`~.store.CHUNK_ROWS` rows, or the run's rows when it has fewer.
Writers write where they are told: a scene run points them into its staging folder
(:func:`ga_rotors.files.output_set`), which moves the finished set into place.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..optional import require
from .npz import NpzStream

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
    (short for a stopped path), the exact reference's bound times; the run's attributes
    at the end."""

    def __init__(self, path, scene=None):
        self.path = Path(path)
        self.scene = scene
        self.rows = 0
        self.valid: dict[str, int] = {}  # array -> rows written (short for a stopped path)
        self.bound = None
        self.chunk_rows = 0  # rows per chunk along time, set by the first piece

    def _take(self, piece) -> None:
        """Count the piece's rows (and pick its bound times)."""
        from .store import CHUNK_ROWS
        from .variables import one_unit

        piece = one_unit(piece)  # the arrays as the files hold them

        if self.rows == 0:
            meta = piece.meta
            expected = sample_count(meta) if "steps" in meta and "sample_every" in meta else 0
            self.chunk_rows = min(CHUNK_ROWS, expected) if expected > 0 else CHUNK_ROWS
            if self.scene is not None:
                self.bound = _BoundTimes(self.scene, piece)
        if self.bound is not None:
            self.bound.take(piece.t, self.rows)
        for name in piece.names:
            self.valid[name] = self.valid.get(name, 0) + piece[name].shape[0]
        self.rows += len(piece)

    def _attrs(self, meta: dict) -> tuple[dict, dict]:
        """The run's attributes (those :func:`~.dataset.run_attributes` gives the whole
        run), and each time variable's ``valid_samples`` (or None)."""
        from .provenance import provenance

        attrs = provenance(meta, self.scene)
        if self.bound is not None:
            bound = self.bound.value()
            if bound is not None:
                attrs["exact_error_bound"] = bound
                attrs["exact_error_bound_units"] = "rad"
        valid = {
            name: (rows if rows < self.rows else None)
            for name, rows in self.valid.items()
            if name != "t"
        }
        return attrs, valid


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
        from .table import CsvRows

        super().__init__(path, scene)
        self._fh = open(self.path, "wb", buffering=CSV_BUFFER)
        self._rows = CsvRows(self._fh, engine)
        self._columns = None  # the first piece's arrays, no rows: what the columns are

    def append(self, piece) -> None:
        """Write the rows of ``piece`` (the header line first, with the first piece)."""
        from ..trajectory import Trajectory

        if self._columns is None:
            arrays = {name: piece[name][:0] for name in piece.names}
            self._columns = Trajectory(arrays, piece.components)
        self._take(piece)
        self._rows.write(piece)

    def close(self, meta: dict) -> None:
        """Finish the file; write its metadata, with the run's attributes (the final
        ``meta``)."""
        from ..trajectory import Trajectory
        from .table import metadata_path, metadata_text

        self._fh.close()
        columns = self._columns if self._columns is not None else Trajectory({"t": np.zeros(0)})
        text = metadata_text(columns, self.path.name, self._attrs(meta)[0])
        metadata_path(self.path).write_text(text, encoding="utf-8")

    def abort(self) -> None:
        """Stop writing (the run failed; the staging folder goes away with the file)."""
        self._fh.close()


class _DatasetStream(_RunStream):
    """What the netCDF and zarr writers share: xarray, per-piece Datasets."""

    def __init__(self, path, scene=None):
        require("xarray", "results")
        super().__init__(path, scene)


class _BoundTimes:
    """The sample times :func:`ga_rotors.results.to_dataset` evaluates the exact
    reference's error bound at, picked from the pieces as they pass (their indices are
    known from the run's sample count)."""

    def __init__(self, scene, first_piece):
        from .dataset import EXACT_BOUND_TIMES

        count = sample_count(first_piece.meta)
        self.scene = scene
        self.pick = np.unique(np.linspace(0, count - 1, min(count, EXACT_BOUND_TIMES)).astype(int))
        self.times: list = []

    def take(self, t, offset: int) -> None:
        inside = self.pick[(self.pick >= offset) & (self.pick < offset + t.shape[0])]
        self.times.append(t[inside - offset])

    def value(self):
        from .dataset import exact_bound_at

        return exact_bound_at(self.scene, np.concatenate(self.times))


class NetcdfStream(_DatasetStream):
    """netCDF (HDF5, through h5netcdf), growing along an unlimited ``time`` dimension.

    A run of at most :data:`~.store.CHUNK_ROWS` samples is held and written whole at
    :meth:`close`, contiguous, as :func:`ga_rotors.results.write` writes it (a chunked,
    growing file costs HDF5 a few kB more per variable). Past that many rows, the rows
    held make the file through xarray (variables, units, chunks of CHUNK_ROWS rows), which
    stays open for the pieces after them, each extending every ``time`` variable.

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
        super().__init__(path, scene)
        self._held: list = []  # the pieces, until there are more than CHUNK_ROWS rows
        self._file = None
        self._variables: dict = {}  # trajectory array -> the file's variable

    def append(self, piece) -> None:
        """Hold the piece, or extend every ``time`` variable by its rows."""
        from .dataset import time_rows
        from .store import CHUNK_ROWS

        self._take(piece)
        if self._file is None:
            self._held.append(piece)
            if self.rows > CHUNK_ROWS:  # a long run: the file grows from here on
                self._create(_joined(self._held))
                self._held = []
            return
        old = self.rows - len(piece)
        for name, rows in time_rows(piece).items():
            variable = self._variables[name]
            variable.resize(self.rows, axis=0)
            variable[old : self.rows, ...] = rows

    def _create(self, rows) -> None:
        """Make the file, along an unlimited ``time``, from the trajectory ``rows``; keep
        it open.

        The rows after these are appended through h5py, the HDF5 library under h5netcdf:
        each variable along ``time`` (the ``time`` coordinate, which is the dimension's
        scale, among them) grown by the piece's rows and filled. Through h5netcdf's
        variables each write looked its dataset up several times over: 1 s of a 10⁷-step
        run's 2.7 s of CPU, against 0.3 s this way."""
        from .dataset import to_dataset
        from .store import CHUNK_ROWS, _netcdf_engine, chunk_encoding

        h5py = require("h5py", "results")
        ds = to_dataset(rows)
        ds.to_netcdf(self.path, engine=_netcdf_engine(), unlimited_dims=["time"],
                     encoding=chunk_encoding(ds, "netcdf", CHUNK_ROWS))  # fmt: skip
        self._file = h5py.File(self.path, "a")
        self._variables = {name: self._file["time" if name == "t" else name] for name in rows.names}

    def close(self, meta: dict) -> None:
        """Write the run's attributes (the final ``meta``) and the short paths' counts (a
        short run: the whole file)."""
        from .dataset import to_dataset
        from .store import _netcdf_engine

        if self._file is None:
            if self._held:
                whole = _joined(self._held).extended({}, meta=meta)
                to_dataset(whole, self.scene).to_netcdf(self.path, engine=_netcdf_engine())
            return
        self._file.close()
        self._file = None
        attrs, valid = self._attrs(meta)
        h5netcdf = require("h5netcdf", "results")  # netCDF's attribute types
        with h5netcdf.File(self.path, "a") as f:
            for key in list(f.attrs):
                if key not in attrs:
                    del f.attrs[key]
            for key, value in attrs.items():
                f.attrs[key] = value
            for name, rows in valid.items():
                _set_valid(f.variables[name].attrs, rows)

    def abort(self) -> None:
        """Close the file (the staging folder goes away with it)."""
        self._held = []
        f, self._file = self._file, None
        if f is not None:
            f.close()


class ZarrStream(_DatasetStream):
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
        super().__init__(path, scene)
        require("zarr", "results")
        self._held: list = []  # pieces not yet written
        self._written = 0  # rows in the store

    def append(self, piece) -> None:
        """Hold the piece's rows; write the whole blocks of chunks held."""
        self._take(piece)
        self._held.append(piece)
        block = self.chunk_rows * ZARR_WRITE_CHUNKS
        end = self._written + (self.rows - self._written) // block * block
        if end > self._written:
            self._write(end)

    def _write(self, end: int) -> None:
        """Write the rows held up to row ``end`` of the run; keep the rest."""
        from .dataset import to_dataset
        from .store import ZARR_FORMAT, chunk_encoding

        rows, self._held = _joined(self._held), []
        take = end - self._written
        head, tail = _split(rows, take)
        ds = to_dataset(head)
        if self._written == 0:
            ds.to_zarr(self.path, mode="w", zarr_format=ZARR_FORMAT, consolidated=False,
                       encoding=chunk_encoding(ds, "zarr", self.chunk_rows))  # fmt: skip
        else:
            ds.to_zarr(self.path, append_dim="time", zarr_format=ZARR_FORMAT, consolidated=False)
        self._written = end
        if len(tail):
            self._held = [tail]

    def close(self, meta: dict) -> None:
        """Write the rows left, the run's attributes, the short paths' counts; consolidate
        the metadata."""
        if self.rows == 0:
            return
        zarr = require("zarr", "results")
        from .store import ZARR_FORMAT

        if self.rows > self._written:
            self._write(self.rows)
        attrs, valid = self._attrs(meta)
        group = zarr.open_group(str(self.path), mode="r+", zarr_format=ZARR_FORMAT)
        group.attrs.clear()
        group.attrs.update(attrs)
        for name, rows in valid.items():
            _set_valid(group[name].attrs, rows)
        zarr.consolidate_metadata(str(self.path), zarr_format=ZARR_FORMAT)

    def abort(self) -> None:
        """Drop what is held (the staging folder goes away with the store)."""
        self._held = []


def _joined(pieces):
    """The consecutive ``pieces`` as one trajectory (a stopped path's rows stay in front)."""
    from ..trajectory import Trajectory

    if len(pieces) == 1:
        return pieces[0]
    first = pieces[0]
    arrays = {name: np.concatenate([p[name] for p in pieces]) for name in first.names}
    return Trajectory(arrays, first.components, pieces[-1].meta)


def _split(trajectory, rows: int):
    """(the first ``rows`` samples of ``trajectory``, the rest)."""
    from ..trajectory import Trajectory

    if rows >= len(trajectory):
        return trajectory, Trajectory({"t": trajectory.t[:0]})
    parts = [
        Trajectory(
            {name: trajectory[name][part] for name in trajectory.names},
            trajectory.components,
            trajectory.meta,
        )
        for part in (slice(None, rows), slice(rows, None))
    ]
    return parts[0], parts[1]


def _set_valid(attrs, rows) -> None:
    if rows is None:
        if "valid_samples" in attrs:
            del attrs["valid_samples"]
    else:
        attrs["valid_samples"] = int(rows)
