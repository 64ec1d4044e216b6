"""CSV as every reader opens it, described by a W3C "CSV on the Web" metadata sidecar.

A results CSV file is plain: the header row, one header per column with its unit, then
one row per sample::

    t [s],w_1 [rad/s],w_2 [rad/s],w_3 [rad/s],q_w [1],...
    0,0.3,0.1,15.7,1,...

so ``pandas.read_csv(path)``, ``polars.read_csv(path)``, ``numpy.loadtxt(path,
delimiter=",", skiprows=1)`` and a spreadsheet read it with no options. Headers read
``name_component [unit]``. Each value is the shortest text that reads back as the same
float64 (``0.1``, not ``0.10000000000000001``; ``nan``, ``inf`` and ``-0`` included),
written by a CSV library: polars when it is installed, else numpy (:data:`ENGINES`;
each spells a NaN its own way, ``NaN`` or ``nan``, and both read back bit for bit). A
path that stopped early leaves its cells empty after its last sample, never NaN
(``numpy.genfromtxt`` reads them as nan).

What the columns are and how the run was made go beside it, in ``<file>.csv-metadata.json``
(:func:`csv_metadata`), the name under which the W3C's *Metadata Vocabulary for Tabular
Data* (CSVW) looks for a CSV file's description: JSON-LD with the CSVW context, the CSV
named by a relative ``url``, each column's ``name``, ``titles`` (its header), ``datatype``,
unit (``schema:unitText``) and long name (``dc:description``), and the run's attributes,
the ones its netCDF file carries (:func:`~ga_rotors.results.dataset.run_attributes`: the
body frame, integrator, step, scene, versions), as ``schema:additionalProperty`` entries
named as in the netCDF file. The two files are written together, or neither.
"""

from __future__ import annotations

import csv
import importlib.util
import io
import json
import math
import os
import re
import urllib.parse
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..files import output_file
from .variables import COMPONENT_DIMS, describe, one_unit

__all__ = [
    "CSVW_CONTEXT",
    "ENGINES",
    "METADATA_SUFFIX",
    "CsvRows",
    "csv_engine",
    "csv_header",
    "csv_metadata",
    "metadata_path",
    "metadata_text",
    "write_csv",
    "write_csv_files",
]

#: The JSON-LD context of a CSVW metadata document (names a vocabulary; nothing loads it).
CSVW_CONTEXT = "http://www.w3.org/ns/csvw"

#: What a CSV file's name gets to name its metadata sidecar (``run.csv-metadata.json``).
METADATA_SUFFIX = "-metadata.json"

# A CSVW column name must be a URI-template variable name, and may not start with "_".
_COLUMN_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_]*")

#: CSV writers, in the order they are chosen: polars when it is installed, else numpy.
ENGINES = ("polars", "numpy")


#: True in a process made by ``os.fork`` (a ``multiprocessing`` pool's workers on Linux):
#: polars' thread pool does not survive a fork, and a child writing with it waits forever
#: once the parent has used it, so the default writer there is numpy.
_FORKED = False


def _forked() -> None:
    global _FORKED
    _FORKED = True


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forked)


def csv_engine(engine: str | None = None) -> str:
    """The CSV writer to use: ``engine`` if given, else the first of :data:`ENGINES` that
    is installed (numpy always is), polars left out in a forked process.

    Examples
    --------
    >>> csv_engine("numpy")
    'numpy'
    >>> csv_engine() in ENGINES
    True
    >>> csv_engine("pandas")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: engine: expected one of polars, numpy, got 'pandas'
    """
    if engine is not None:
        if engine not in ENGINES:
            raise InputError(f"expected one of {', '.join(ENGINES)}, got {engine!r}", key="engine")
        return engine
    return "polars" if not _FORKED and importlib.util.find_spec("polars") else "numpy"


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
    for header, name, _ in one_unit(trajectory).columns():
        try:
            out.append(f"{header} [{describe(name)[0]}]")
        except InputError:
            out.append(header)
    return out


def _header_line(trajectory) -> bytes:
    line = io.StringIO()
    csv.writer(line, lineterminator="\n").writerow(csv_header(trajectory))
    return line.getvalue().encode("utf-8")


class CsvRows:
    """The rows of a trajectory's consecutive pieces, written to an open binary file.

    The first :meth:`write` writes the header line first; the rows of all the pieces are
    the rows of the whole trajectory (a path that stopped part-way through a
    piece leaves its remaining cells empty).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> out = io.BytesIO()
    >>> rows = CsvRows(out, "numpy")
    >>> rows.write(Trajectory({"t": np.array([0.0, 0.1]), "energy": np.array([0.5, 1 / 3])}))
    >>> rows.write(Trajectory({"t": np.array([0.2]), "energy": np.array([])}))
    >>> print(out.getvalue().decode(), end="")
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
        """Append the rows of ``piece`` (the header line first, once)."""
        piece = one_unit(piece)  # an array of mixed units: its parts, one unit each
        if not self._started:
            self.fh.write(_header_line(piece))
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


def _numpy(fh, columns, n) -> None:
    # numpy's float-to-text conversion is Python's repr: the shortest round-trip text
    cells = np.full((n, len(columns)), "", dtype=object)
    for j, (values, rows) in enumerate(columns):
        cells[:rows, j] = np.asarray(values, dtype=np.float64).astype(str)
    fh.write("".join(",".join(row) + "\n" for row in cells.tolist()).encode())


_WRITERS = {"polars": _polars, "numpy": _numpy}


def metadata_path(path) -> Path:
    """Where the CSVW metadata of the CSV file ``path`` goes: beside it, its name plus
    :data:`METADATA_SUFFIX` (where a CSVW processor looks for it).

    Examples
    --------
    >>> metadata_path("out/heavy_top.csv")
    PosixPath('out/heavy_top.csv-metadata.json')
    """
    path = Path(path)
    return path.with_name(path.name + METADATA_SUFFIX)


def _json_value(value):
    """An attribute as JSON holds it: a numpy number as Python's, a float that is not
    finite (which JSON has no number for) as its text."""
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, list | tuple):
        return [_json_value(v) for v in value]
    return value


def _column(plain: str, header: str, name: str, component: str | None, dim: str | None):
    """One column's description: ``plain``, its name (``w_1``); ``header``, its header
    (``w_1 [rad/s]``); ``name``, its array; ``component``, its label along ``dim``."""
    column: dict = {}
    if _COLUMN_NAME.fullmatch(plain):  # else (a user's array) its titles name it
        column["name"] = plain
    column["titles"] = header
    column["datatype"] = "double"
    try:
        unit, long_name = describe(name)
    except InputError:  # an array a user added: no unit is known
        return column
    column["schema:unitText"] = unit
    column["dc:description"] = long_name if dim is None else f"{long_name}; {dim} {component}"
    return column


def csv_metadata(trajectory, url: str, attributes: dict) -> dict:
    """The CSVW metadata document (JSON-LD) of ``trajectory``'s CSV file named ``url``
    (relative to the sidecar: the CSV's own file name), carrying the run's ``attributes``
    (:func:`~ga_rotors.results.dataset.run_attributes`).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> from ga_rotors.results.dataset import run_attributes
    >>> tr = Trajectory({"t": np.zeros(2), "w": np.zeros((2, 3))}, {"w": ("1", "2", "3")},
    ...                 meta={"integrator": "rk4"})
    >>> doc = csv_metadata(tr, "run.csv", run_attributes(tr.meta))
    >>> doc["url"], doc["tableSchema"]["columns"][1]
    ('run.csv', {'name': 'w_1', 'titles': 'w_1 [rad/s]', 'datatype': 'double', \
'schema:unitText': 'rad/s', 'dc:description': 'body angular velocity of the primary path; \
body_axis 1'})
    >>> [(p["schema:name"], p["schema:value"]) for p in doc["schema:additionalProperty"]][3]
    ('body_frame', 'the body axes the inertia was given in')
    """
    columns = []
    trajectory = one_unit(trajectory)
    headers = csv_header(trajectory)
    for header, (plain, name, index) in zip(headers, trajectory.columns(), strict=True):
        if index is None:
            columns.append(_column(plain, header, name, None, None))
            continue
        labels = trajectory.components.get(name) or ()  # the Dataset's component dimension
        dim = COMPONENT_DIMS.get(tuple(labels), f"{name}_component")
        component = labels[index] if labels else str(index)
        columns.append(_column(plain, header, name, component, dim))
    return {
        "@context": CSVW_CONTEXT,
        "url": urllib.parse.quote(url),
        "dc:title": attributes.get("title", "ga_rotors results"),
        "dc:description": attributes.get("comment", ""),
        "schema:additionalProperty": [
            {"@type": "schema:PropertyValue", "schema:name": key, "schema:value": _json_value(v)}
            for key, v in attributes.items()
        ],
        "tableSchema": {"columns": columns},
    }


def metadata_text(trajectory, csv_name: str, attributes: dict) -> str:
    """The sidecar's JSON text: :func:`csv_metadata`, indented, no NaN or Infinity.

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.array([0.0, 0.5])}, meta={"integrator": "rk4"})
    >>> doc = json.loads(metadata_text(tr, "run.csv", {"body_frame": "body axes"}))
    >>> doc["url"], [c["titles"] for c in doc["tableSchema"]["columns"]]
    ('run.csv', ['t [s]'])
    """
    document = csv_metadata(trajectory, csv_name, attributes)
    return json.dumps(document, indent=1, allow_nan=False) + "\n"


def write_csv_files(trajectory, path, *, scene=None, engine: str | None = None) -> list[Path]:
    """Write the CSV file ``path`` and its metadata sidecar (:func:`metadata_path`) where
    they are, not atomically, for a folder whose files move into place together
    (:func:`ga_rotors.files.output_set`): the files of a
    :class:`~ga_rotors.results.streams.CsvStream` given the whole trajectory as one piece.
    Returns both paths.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> stage = pathlib.Path(tempfile.mkdtemp())
    >>> tr = Trajectory({"t": np.array([0.0, 0.5])}, meta={"integrator": "rk4"})
    >>> [p.name for p in write_csv_files(tr, stage / "run.csv")]
    ['run.csv', 'run.csv-metadata.json']
    """
    from .streams import CsvStream

    out = CsvStream(path, scene, engine=engine)
    try:
        out.append(trajectory)
        out.close(trajectory.meta)
    finally:
        out.abort()
    return [Path(path), metadata_path(path)]


def write_csv(trajectory, path=None, *, scene=None, engine: str | None = None) -> str | Path:
    """Write the trajectory as CSV with units in the headers, and its CSVW metadata beside
    it (``<path>-metadata.json``): both files, or (on any failure) neither changed.

    Without ``path``, return the CSV text. ``scene``: the scene that made the run (its
    resolved TOML and exact-solution bound join the metadata). ``engine``: the CSV writer
    (default: the first installed of :data:`ENGINES`). Returns the CSV file's path.

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.array([0.0, 0.5]), "energy": np.array([1.0, 1.0 / 3])},
    ...                 meta={"integrator": "rk4"})
    >>> print(write_csv(tr, engine="polars"), end="")
    t [s],energy [J]
    0.0,1.0
    0.5,0.3333333333333333
    """
    if path is None:
        out = io.BytesIO()
        CsvRows(out, engine).write(trajectory)
        return out.getvalue().decode("utf-8")
    csv_engine(engine)  # an unknown engine: refused before any folder is touched
    with output_file(path) as staged:
        write_csv_files(trajectory, staged, scene=scene, engine=engine)
    return Path(path)
