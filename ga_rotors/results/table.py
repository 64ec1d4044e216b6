"""CSV for spreadsheets: one column per component, the unit in every header.

A results CSV file has one comment line naming the frame of the body-frame columns, the
header, then one row per sample::

    # body_frame: the body axes the inertia was given in
    t [s],w_1 [rad/s],w_2 [rad/s],w_3 [rad/s],q_w [1],...
    0,0.3,0.1,15.7,1,...

Headers read ``name_component [unit]``. Each value is the shortest text that reads back
as the same float64 (``0.1``, not ``0.10000000000000001``; ``nan``, ``inf`` and ``-0``
included), written by a CSV library: polars when it is installed, else pyarrow, else
numpy (:data:`ENGINES`; each writes its own spelling, ``1.0`` or ``1``, ``NaN`` or
``nan``, and every one reads back bit for bit). A path that stopped early leaves its
cells empty after its last sample, never NaN. Read it with::

    pandas.read_csv(path, comment="#")
    polars.read_csv(path, comment_prefix="#")
    numpy.genfromtxt(path, delimiter=",", skip_header=2)   # empty cells become nan
"""

from __future__ import annotations

import csv
import importlib
import io
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..files import atomic_write
from .provenance import body_frame
from .variables import describe

__all__ = ["ENGINES", "CsvRows", "csv_engine", "csv_header", "frame_line", "write_csv"]

#: CSV writers, in the order they are chosen: the first whose module is installed.
ENGINES = ("polars", "pyarrow", "numpy")


def csv_engine(engine: str | None = None) -> str:
    """The CSV writer to use: ``engine`` if given, else the first of :data:`ENGINES` that
    is installed (numpy always is).

    Examples
    --------
    >>> csv_engine("numpy")
    'numpy'
    >>> csv_engine() in ENGINES
    True
    >>> csv_engine("pandas")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: engine: expected one of polars, pyarrow, numpy, got 'pandas'
    """
    if engine is not None:
        if engine not in ENGINES:
            raise InputError(f"expected one of {', '.join(ENGINES)}, got {engine!r}", key="engine")
        return engine
    for name in ENGINES:
        try:
            importlib.import_module(name)
            return name
        except ImportError:
            continue
    return "numpy"


def csv_header(trajectory) -> list[str]:
    """Column headers with units, in the order :meth:`Trajectory.columns` gives.

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.zeros(2), "w": np.zeros((2, 3))}, {"w": ("1", "2", "3")})
    >>> csv_header(tr)
    ['t [s]', 'w_1 [rad/s]', 'w_2 [rad/s]', 'w_3 [rad/s]']

    An array the package does not know (one a user added) has no unit to show:

    >>> csv_header(Trajectory({"t": np.zeros(2), "x": np.zeros(2)}))
    ['t [s]', 'x']
    """
    out = []
    for header, name, _ in trajectory.columns():
        try:
            out.append(f"{header} [{describe(name)[0]}]")
        except InputError:
            out.append(header)
    return out


def frame_line(meta: dict) -> str:
    """The CSV file's first line: a comment naming the frame of the body-frame columns
    (:func:`~ga_rotors.results.provenance.body_frame`), on one line whatever it holds.

    Examples
    --------
    >>> frame_line({"integrator": "rk4"})
    '# body_frame: the body axes the inertia was given in\\n'
    """
    text = " ".join(body_frame(meta).split())  # no line break can end the comment early
    return f"# body_frame: {text}\n"


def _header_lines(trajectory) -> bytes:
    line = io.StringIO()
    csv.writer(line, lineterminator="\n").writerow(csv_header(trajectory))
    return (frame_line(trajectory.meta) + line.getvalue()).encode("utf-8")


class CsvRows:
    """The rows of a trajectory's consecutive pieces, written to an open binary file.

    The first :meth:`write` writes the comment and header lines first; the rows of all the
    pieces are the rows of the whole trajectory (a path that stopped part-way through a
    piece leaves its remaining cells empty).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> out = io.BytesIO()
    >>> rows = CsvRows(out, "numpy")
    >>> rows.write(Trajectory({"t": np.array([0.0, 0.1]), "energy": np.array([0.5, 1 / 3])}))
    >>> rows.write(Trajectory({"t": np.array([0.2]), "energy": np.array([])}))
    >>> print(out.getvalue().decode(), end="")
    # body_frame: not recorded
    t [s],energy [J]
    0.0,0.5
    0.1,0.3333333333333333
    0.2,
    """

    def __init__(self, fh, engine: str | None = None):
        self.fh = fh
        self.engine = csv_engine(engine)
        self._started = False

    def write(self, piece) -> None:
        """Append the rows of ``piece`` (the comment and header lines first, once)."""
        if not self._started:
            self.fh.write(_header_lines(piece))
            self._started = True
        n = len(piece)
        if n == 0:
            return
        columns = []  # (values, rows that hold a value)
        for _, name, component in piece.columns():
            a = piece[name]
            columns.append((a if component is None else a[:, component], a.shape[0]))
        _WRITERS[self.engine](self.fh, columns, n)


def _polars(fh, columns, n) -> None:
    import polars as pl

    series = [
        pl.Series(f"c{j}", values, dtype=pl.Float64).extend_constant(None, n - rows)
        for j, (values, rows) in enumerate(columns)
    ]
    pl.DataFrame(series).write_csv(fh, include_header=False)


def _pyarrow(fh, columns, n) -> None:
    import pyarrow as pa
    import pyarrow.csv as pacsv

    arrays = []
    for values, rows in columns:
        if rows == n:
            arrays.append(pa.array(values, pa.float64()))
        else:  # one masked array: a chunked one whose first chunk is empty wrote garbage
            padded = np.zeros(n)
            padded[:rows] = values
            arrays.append(pa.array(padded, pa.float64(), mask=np.arange(n) >= rows))
    table = pa.table(arrays, names=[f"c{j}" for j in range(len(arrays))])
    pacsv.write_csv(table, fh, pacsv.WriteOptions(include_header=False))


def _numpy(fh, columns, n) -> None:
    # numpy's float-to-text conversion is Python's repr: the shortest round-trip text
    cells = np.full((n, len(columns)), "", dtype=object)
    for j, (values, rows) in enumerate(columns):
        cells[:rows, j] = np.asarray(values, dtype=np.float64).astype(str)
    fh.write("".join(",".join(row) + "\n" for row in cells.tolist()).encode())


_WRITERS = {"polars": _polars, "pyarrow": _pyarrow, "numpy": _numpy}


def write_csv(trajectory, path=None, *, engine: str | None = None) -> str | Path:
    """Write the trajectory as CSV with units in the headers, atomically.

    Without ``path``, return the text. ``engine``: the CSV writer (default: the first
    installed of :data:`ENGINES`).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.array([0.0, 0.5]), "energy": np.array([1.0, 1.0 / 3])},
    ...                 meta={"integrator": "rk4"})
    >>> print(write_csv(tr, engine="pyarrow"), end="")
    # body_frame: the body axes the inertia was given in
    t [s],energy [J]
    0,1
    0.5,0.3333333333333333
    """
    if path is None:
        out = io.BytesIO()
        CsvRows(out, engine).write(trajectory)
        return out.getvalue().decode("utf-8")
    return atomic_write(path, lambda fh: CsvRows(fh, engine).write(trajectory))
