"""Results files written piece by piece, as a long run goes on: memory holds one piece.

Each writer takes the pieces of one run in order (:class:`~ga_rotors.trajectory.Trajectory`
objects of consecutive samples, the first holding sample 0, as
:func:`ga_rotors.simulation.simulate_chunks` hands them out) with :meth:`append`, and
finishes the file with :meth:`close`, given the run's final ``meta`` (what the run
became: which paths completed, how many samples each has). The file is the one the whole
trajectory would give, written in one go:

* :class:`CsvStream` — CSV with units in the headers (:mod:`ga_rotors.results.table`), a
  block of rows at a time;
* :class:`NpzStream` — the ``.npz`` of :meth:`Trajectory.to_npz`: each array's rows go
  to a file of their own as they come, and :meth:`close` copies them into the archive
  (no compression, as ``numpy.savez``), one buffer at a time;
* :class:`NetcdfStream` — netCDF along an unlimited ``time`` dimension, extended per piece;
* :class:`ZarrStream` — a zarr store (format 2) appended along ``time``.

netCDF and zarr files read back (:func:`ga_rotors.results.read`) as the Dataset
:func:`ga_rotors.results.to_dataset` makes of the whole trajectory. Writers write where
they are told: a scene run points them into its staging folder
(:func:`ga_rotors.files.output_set`), which moves the finished set into place.
"""

from __future__ import annotations

import os
import shutil
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from ..files import DirectWriter, read_direct
from ..optional import require

__all__ = ["CHUNK_ROWS", "CsvStream", "NetcdfStream", "NpzStream", "ZarrStream"]

#: Rows per chunk of the netCDF and zarr variables along ``time``.
CHUNK_ROWS = 16_384

#: Chunks of rows (:data:`CHUNK_ROWS` each) a :class:`ZarrStream` collects before writing
#: them: each call into zarr costs about a millisecond beyond its data. Writing the
#: 10⁷-step heavy top's store alone took 1.3-1.4 s here from 2 to 8 chunks at a time
#: (1.2-1.4 s over repeats, no trend); 4 keeps what is held to 4 chunks and a piece.
ZARR_WRITE_CHUNKS = 4

#: Bytes each array of an :class:`NpzStream` collects before writing them to its rows
#: file (one buffer per array: a run's NPZ has up to a dozen).
ROWS_BUFFER = 2 << 20


class CsvStream:
    """CSV written piece by piece (:func:`ga_rotors.results.write_csv`'s text), straight
    to the disk where the system allows it (:class:`ga_rotors.files.DirectWriter`).

    Where the machine has a second core, the rows of each piece are formatted by two
    threads, half the blocks each (the text of a CSV is most of a long run's output
    work): the caller's, which formats its blocks in place in the file's buffer
    (:meth:`~ga_rotors.files.DirectWriter.reserve`) and writes every block in order, and
    a helper that only formats into a buffer of its own. The helper has finished with a piece before
    :meth:`append` returns or raises.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> out = CsvStream(path)
    >>> out.append(Trajectory({"t": np.array([0.0, 0.5]), "energy": np.array([1.0, 2.0])}))
    >>> out.append(Trajectory({"t": np.array([1.0]), "energy": np.array([3.0])}))
    >>> out.close({})
    >>> print(path.read_text(), end="")
    t [s],energy [J]
    0,1
    0.5,2
    1,3
    """

    def __init__(self, path, *, threads: int | None = None, block_rows: int | None = None):
        from .table import BLOCK_ROWS

        self.path = Path(path)
        self._fh = None
        self._direct = False
        self._buffers = []
        self._helper = None
        self._threads = min(2, os.cpu_count() or 1) if threads is None else threads
        self._block_rows = BLOCK_ROWS if block_rows is None else block_rows

    def append(self, piece) -> None:
        """Write the rows of ``piece`` (the header first, with the first piece)."""
        from concurrent.futures import ThreadPoolExecutor, wait

        from .table import csv_buffer_size, csv_header

        if self._fh is None:
            self._fh = DirectWriter(self.path)
            self._fh.write((",".join(csv_header(piece)) + "\n").encode())
            # one buffer a thread for every block of the run: each written before the next
            size = csv_buffer_size(piece, self._block_rows)
            self._buffers = [np.empty(size, dtype=np.uint8) for _ in range(self._threads)]
            if self._threads > 1:
                self._helper = ThreadPoolExecutor(1, thread_name_prefix="ga_rotors-csv")
        n = len(piece)
        if n == 0:
            return
        step = self._block_rows
        if self._helper is None:
            for lo in range(0, n, step):
                self._format(piece, lo, min(n, lo + step))
            return
        # blocks of equal size in pairs, no more rows than a buffer holds: this thread
        # formats and writes the first of each pair while the helper formats the second
        pairs = -(-n // (2 * step))
        rows = -(-n // (2 * pairs))
        for lo in range(0, n, 2 * rows):
            mid, hi = min(n, lo + rows), min(n, lo + 2 * rows)
            later = self._helper.submit(_csv_text, piece, mid, hi, self._buffers[1])
            try:
                self._format(piece, lo, mid)
            finally:
                wait([later])  # the helper is done with its buffer, even after an error
            self._fh.write(later.result())

    def _format(self, piece, start: int, stop: int) -> None:
        """Append rows ``start:stop``, formatted in place in the file's buffer."""
        from .table import csv_buffer_size

        room = self._fh.reserve(csv_buffer_size(piece, stop - start))
        if room is None:  # more than the writer's buffer holds: through our own
            self._fh.write(_csv_text(piece, start, stop, self._buffers[0]))
        else:
            self._fh.commit(len(_csv_text(piece, start, stop, room)))

    @property
    def direct(self) -> bool:
        """Whether the file went straight to the disk (no writeback left to start)."""
        return self._direct

    def close(self, meta: dict) -> None:
        """Finish the file."""
        self._stop(finish=True)

    def abort(self) -> None:
        """Stop writing (the run failed; the staging folder goes away with the file)."""
        self._stop(finish=False)

    def _stop(self, finish: bool) -> None:
        if self._helper is not None:
            self._helper.shutdown()
            self._helper = None
        if self._fh is not None:
            fh, self._fh = self._fh, None
            if finish:
                fh.close()
                self._direct = fh.direct
            else:
                fh.abort()


def _csv_text(piece, start: int, stop: int, buffer):
    """The CSV text of rows ``start:stop`` of ``piece`` (at most a buffer's rows), in
    ``buffer``."""
    from .table import csv_rows

    if stop <= start:
        return b""
    (text,) = csv_rows(piece, stop - start, buffer=buffer, start=start, stop=stop)
    return text


class NpzStream:
    """The ``.npz`` archive of :meth:`Trajectory.to_npz`, its arrays' rows collected on disk.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.npz"
    >>> out = NpzStream(path)
    >>> for lo in (0, 2):
    ...     out.append(Trajectory({"t": np.arange(lo, lo + 2.0), "w": np.ones((2, 3))},
    ...                           {"w": ("1", "2", "3")}))
    >>> out.close({})
    >>> data = np.load(path)
    >>> data["t"].tolist(), data["w"].shape, data["w__components"].tolist()
    ([0.0, 1.0, 2.0, 3.0], (4, 3), ['1', '2', '3'])
    """

    def __init__(self, path):
        self.path = Path(path)
        self._dir = Path(tempfile.mkdtemp(dir=self.path.parent, prefix=".npz-rows-"))
        self._files: dict = {}  # name -> (open file, trailing shape, rows)
        self._components: dict = {}
        self._direct = False

    def append(self, piece) -> None:
        """Add the rows of ``piece`` to each array's file."""
        for name in piece.names:
            a = np.ascontiguousarray(piece[name], dtype=np.float64)
            if name not in self._files:
                fh = DirectWriter(self._dir / f"{len(self._files)}.rows", ROWS_BUFFER)
                self._files[name] = [fh, a.shape[1:], 0]
            entry = self._files[name]
            entry[0].write(a)
            entry[2] += a.shape[0]
        for name, labels in piece.components.items():
            if name in self._files:
                self._components[name] = labels

    @property
    def direct(self) -> bool:
        """Whether the archive went straight to the disk (no writeback left to start)."""
        return self._direct

    def close(self, meta: dict) -> None:
        """Write the archive: each array's header, then its rows copied from disk.

        The rows are read and the archive written straight from and to the disk where
        the file system allows it (:func:`ga_rotors.files.read_direct`,
        :class:`~ga_rotors.files.DirectWriter`): the archive is then written in one
        pass, each member's sizes and checksum after its data (a zip "data descriptor",
        which every zip reader, numpy's ``load`` included, reads)."""
        with DirectWriter(self.path) as out:
            with zipfile.ZipFile(_Appended(out), "w", zipfile.ZIP_STORED, allowZip64=True) as zf:
                for name, (fh, trailing, rows) in self._files.items():
                    fh.close()
                    header = np.lib.format.header_data_from_array_1_0(np.empty((0, *trailing)))
                    header["shape"] = (rows, *trailing)
                    with zf.open(f"{name}.npy", "w", force_zip64=True) as member:
                        np.lib.format.write_array_header_1_0(member, header)
                        for block in read_direct(fh.path, ROWS_BUFFER):
                            member.write(block)
                for name, labels in self._components.items():
                    with zf.open(f"{name}__components.npy", "w", force_zip64=True) as member:
                        np.lib.format.write_array(member, np.array(labels))
        self._direct = out.direct
        self.abort()

    def abort(self) -> None:
        """Remove the rows collected so far."""
        for fh, _, _ in self._files.values():
            fh.abort()
        self._files = {}
        shutil.rmtree(self._dir, ignore_errors=True)


class _Appended:
    """A file written in order, for :class:`zipfile.ZipFile`: no ``seek`` or ``tell``,
    so the archive is written in one pass (each member's sizes after its data)."""

    def __init__(self, out):
        self.write = out.write

    def flush(self) -> None:
        """Nothing to do: the writer's bytes go out when it is closed."""


class _DatasetStream:
    """What the netCDF and zarr writers share: per-piece Datasets, attributes at the end."""

    def __init__(self, path, scene=None):
        require("xarray", "results")
        self.path = Path(path)
        self.scene = scene
        self.rows = 0
        self.valid: dict[str, int] = {}  # array -> rows written (short for a stopped path)
        self.bound = None

    def _take(self, piece, as_dataset: bool):
        """Count the piece's rows (and pick its bound times); return it as a Dataset (for
        the piece that makes the file: variables, units) or as its arrays along ``time``
        (:func:`~ga_rotors.results.dataset.time_rows`, for the pieces after: a Dataset
        for each cost 2.8 ms, 0.2 s of a 10⁷-step run's 77 pieces)."""
        from .dataset import time_rows, to_dataset

        if self.bound is None and self.scene is not None:
            self.bound = _BoundTimes(self.scene, piece)
        if self.bound is not None:
            self.bound.take(piece.t, self.rows)
        for name in piece.names:
            self.valid[name] = self.valid.get(name, 0) + piece[name].shape[0]
        self.rows += len(piece)
        return to_dataset(piece) if as_dataset else time_rows(piece)

    def _attrs(self, meta: dict) -> tuple[dict, dict]:
        """The run's attributes, and each time variable's ``valid_samples`` (or None)."""
        from .dataset import provenance

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

    def _encoding(self, ds) -> dict:
        return {
            name: {self._chunk_key: (CHUNK_ROWS, *var.shape[1:])}
            for name, var in ds.variables.items()
            if var.dims[:1] == ("time",)
        }

    def abort(self) -> None:
        """Nothing to undo: the staging folder goes away with the file."""


class _BoundTimes:
    """The sample times :func:`ga_rotors.results.dataset` evaluates the exact reference's
    error bound at, picked from the pieces as they pass (their indices are known from the
    run's sample count)."""

    def __init__(self, scene, first_piece):
        from .dataset import EXACT_BOUND_TIMES

        meta = first_piece.meta
        steps, every = meta["steps"], meta["sample_every"]
        count = steps // every + 1 + (1 if steps % every else 0)
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
    """netCDF (HDF5, through h5netcdf) along an unlimited ``time`` dimension.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> from ga_rotors.results import read
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.nc"
    >>> out = NetcdfStream(path)
    >>> for lo in (0, 2):
    ...     out.append(Trajectory({"t": np.arange(lo, lo + 2.0), "energy": np.ones(2)},
    ...                           meta={"integrator": "rk4"}))
    >>> out.close({"integrator": "rk4"})
    >>> ds = read(path)
    >>> ds["t"].values.tolist(), ds["energy"].attrs["units"], ds.attrs["integrator"]
    ([0.0, 1.0, 2.0, 3.0], 'J', 'rk4')
    """

    _chunk_key = "chunksizes"

    def __init__(self, path, scene=None):
        super().__init__(path, scene)
        # open from the second piece to the end (reopening it for each piece cost 0.2 s
        # of CPU over the 77 pieces of a 10⁷-step heavy top), and its time variables
        self._file = None
        self._names: list[str] = []
        self._variables: dict = {}

    def append(self, piece) -> None:
        """Extend every ``time`` variable by the piece's rows."""
        first = self.rows == 0
        data = self._take(piece, as_dataset=first)
        if first:  # the first piece makes the file
            from .store import _netcdf_engine

            data.to_netcdf(self.path, engine=_netcdf_engine(), unlimited_dims=["time"],
                           encoding=self._encoding(data))  # fmt: skip
            self._names = [n for n, v in data.variables.items() if v.dims[:1] == ("time",)]
            return
        if self._file is None:
            h5netcdf = require("h5netcdf", "results")
            self._file = h5netcdf.File(self.path, "a")
            self._variables = {name: self._file.variables[name] for name in self._names}
        old = self.rows - len(piece)
        self._file.resize_dimension("time", self.rows)
        for name, variable in self._variables.items():
            variable[old : self.rows, ...] = data[name]

    def close(self, meta: dict) -> None:
        """Write the run's attributes (the final ``meta``) and the short paths' counts."""
        if self.rows == 0:
            return
        h5netcdf = require("h5netcdf", "results")
        attrs, valid = self._attrs(meta)
        f, self._file = self._file, None
        if f is None:  # a run of one piece
            f = h5netcdf.File(self.path, "a")
        with f:
            for key in list(f.attrs):
                if key not in attrs:
                    del f.attrs[key]
            for key, value in attrs.items():
                f.attrs[key] = value
            for name, rows in valid.items():
                _set_valid(f.variables[name].attrs, rows)

    def abort(self) -> None:
        """Close the file (the staging folder goes away with it)."""
        f, self._file = self._file, None
        if f is not None:
            f.close()


class ZarrStream(_DatasetStream):
    """A zarr store (format 2, as :func:`ga_rotors.results.write` writes) appended along
    ``time``, its metadata consolidated at the end.

    The first piece makes the store through xarray (variables, units, encodings); the
    rows after it are collected and written with zarr's own arrays,
    :data:`ZARR_WRITE_CHUNKS` whole chunks at a time (each chunk once, but the one the
    first piece ends in, completed once), into arrays grown by doubling and cut to the
    run's rows at :meth:`close`. Appending each piece through
    ``to_zarr(append_dim=...)`` instead reopened the store, rewrote every array's
    metadata and recompressed the chunk each piece ends in: 4.3 s for the 244 MB of a
    10⁷-step heavy top on this machine, against 1.2-1.4 s now (the same store read
    back).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> from ga_rotors.results import read
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.zarr"
    >>> out = ZarrStream(path)
    >>> for lo in (0, 2):
    ...     out.append(Trajectory({"t": np.arange(lo, lo + 2.0), "energy": np.ones(2)}))
    >>> out.close({})
    >>> read(path)["t"].values.tolist()
    [0.0, 1.0, 2.0, 3.0]
    """

    _chunk_key = "chunks"

    def __init__(self, path, scene=None):
        super().__init__(path, scene)
        self._group = None  # the store's group, once it exists
        self._arrays: dict | None = None  # name -> zarr array of the group
        self._held: dict[str, list] = {}  # name -> rows not yet written
        self._written = 0  # rows in the store

    def append(self, piece) -> None:
        """Append the piece's rows to every ``time`` variable (written whole chunks at a
        time: the last rows wait for the next piece or :meth:`close`)."""
        from .store import ZARR_FORMAT

        zarr = require("zarr", "results")
        data = self._take(piece, as_dataset=self._arrays is None)
        if self._arrays is None:
            data.to_zarr(self.path, mode="w", zarr_format=ZARR_FORMAT, consolidated=False,
                         encoding=self._encoding(data))  # fmt: skip
            self._group = zarr.open_group(str(self.path), mode="r+", zarr_format=ZARR_FORMAT)
            self._arrays = {
                name: self._group[name]
                for name, var in data.variables.items()
                if var.dims[:1] == ("time",)
            }
            self._written = self.rows
            return
        for name in self._arrays:
            self._held.setdefault(name, []).append(data[name])
        end = self.rows - self.rows % CHUNK_ROWS
        if end - self._written >= ZARR_WRITE_CHUNKS * CHUNK_ROWS:
            self._write_held(end)

    def _write_held(self, end: int) -> None:
        """Write the rows held up to row ``end`` of the run; keep the rest."""
        start = self._written
        for name, a in self._arrays.items():
            held = self._held[name]
            rows = np.concatenate(held) if len(held) > 1 else held[0]
            if a.shape[0] < end:  # doubled: a few resizes (each rewrites the metadata)
                a.resize((max(end, 2 * a.shape[0]), *a.shape[1:]))
            a[start:end] = rows[: end - start]
            self._held[name] = [rows[end - start :]]
        self._written = end

    def close(self, meta: dict) -> None:
        """Write the run's attributes, the short paths' counts; consolidate the metadata."""
        if self.rows == 0:
            return
        zarr = require("zarr", "results")
        from .store import ZARR_FORMAT

        if self.rows > self._written:
            self._write_held(self.rows)
        for a in self._arrays.values():
            if a.shape[0] != self.rows:  # grown past the run's rows: cut back
                a.resize((self.rows, *a.shape[1:]))
        attrs, valid = self._attrs(meta)
        group = self._group  # opened by the first piece: not opened again
        group.attrs.clear()
        group.attrs.update(attrs)
        for name, rows in valid.items():
            _set_valid(group[name].attrs, rows)
        zarr.consolidate_metadata(str(self.path), zarr_format=ZARR_FORMAT)


def _set_valid(attrs, rows) -> None:
    if rows is None:
        if "valid_samples" in attrs:
            del attrs["valid_samples"]
    else:
        attrs["valid_samples"] = int(rows)
