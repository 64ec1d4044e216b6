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
(:func:`metadata_text`), the name under which the W3C's *Metadata Vocabulary for Tabular
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
from .variables import component_dim, describe, one_unit

__all__ = [
    "CSVW_CONTEXT",
    "ENGINES",
    "METADATA_SUFFIX",
    "csv_engine",
    "csv_header",
    "csv_rows",
    "metadata_path",
    "metadata_text",
    "write_csv",
    "write_csv_files",
    "write_metadata",
]

#: The JSON-LD context of a CSVW metadata document (names a vocabulary; nothing loads it).
CSVW_CONTEXT = "http://www.w3.org/ns/csvw"

#: What a CSV file's name gets to name its metadata sidecar (``run.csv-metadata.json``).
METADATA_SUFFIX = "-metadata.json"

# A CSVW column name must be a URI-template variable name, and may not start with "_".
_COLUMN_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_]*")

#: CSV writers, in the order they are chosen: polars when it is installed, else numpy.
ENGINES = ("polars", "numpy")


#: The process that imported this module: in another one, made by ``os.fork`` (a
#: ``multiprocessing`` pool's workers on Linux), polars' thread pool may be the parent's,
#: which does not survive a fork (a child writing with it waits forever once the parent has
#: used it), so the default writer there is numpy.
_PROCESS = os.getpid()


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
    forked = os.getpid() != _PROCESS
    return "polars" if not forked and importlib.util.find_spec("polars") else "numpy"


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


def csv_rows(fh, piece, engine: str, header: bool = False) -> None:
    """Write the rows of ``piece`` to the open binary file ``fh`` with the writer
    ``engine`` (:func:`csv_engine`), the header line first when ``header``. The rows of a
    trajectory's consecutive pieces are those of the whole (a path that stopped part-way
    through a piece leaves its remaining cells empty).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> out = io.BytesIO()
    >>> csv_rows(out, Trajectory({"t": np.array([0.0, 0.1]), "energy": np.array([0.5, 1 / 3])}),
    ...          "numpy", header=True)
    >>> csv_rows(out, Trajectory({"t": np.array([0.2]), "energy": np.array([])}), "numpy")
    >>> print(out.getvalue().decode(), end="")
    t [s],energy [J]
    0.0,0.5
    0.1,0.3333333333333333
    0.2,
    """
    piece = one_unit(piece)  # an array of mixed units: its parts, one unit each
    if header:
        line = io.StringIO()
        csv.writer(line, lineterminator="\n").writerow(csv_header(piece))
        fh.write(line.getvalue().encode("utf-8"))
    if len(piece):
        columns = []  # (values, rows that hold a value)
        for _, name, component in piece.columns():
            a = piece[name]
            columns.append((a if component is None else a[:, component], a.shape[0]))
        _WRITERS[engine](fh, columns, len(piece))


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


def _column(plain: str, header: str, name: str, index: int | None, trajectory) -> dict:
    """The description of the column ``plain`` (``w_1``), headed ``header``
    (``w_1 [rad/s]``): the array ``name``, or its component ``index``."""
    column: dict = {"name": plain} if _COLUMN_NAME.fullmatch(plain) else {}  # else: titles
    column.update(titles=header, datatype="double")
    try:
        unit, long_name = describe(name)
    except InputError:  # an array a user added: no unit is known
        return column
    if index is not None:
        dim, labels = component_dim(trajectory, name)
        long_name = f"{long_name}; {dim} {labels[index]}"
    return {**column, "schema:unitText": unit, "dc:description": long_name}


def metadata_text(trajectory, url: str, attributes: dict) -> str:
    """The CSVW metadata document (JSON-LD, indented, no NaN or Infinity) of
    ``trajectory``'s CSV file named ``url`` (relative to the sidecar: the CSV's own file
    name), carrying the run's ``attributes``
    (:func:`~ga_rotors.results.dataset.run_attributes`).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> from ga_rotors.results.dataset import run_attributes
    >>> tr = Trajectory({"t": np.zeros(2), "w": np.zeros((2, 3))}, {"w": ("1", "2", "3")},
    ...                 meta={"integrator": "rk4"})
    >>> doc = json.loads(metadata_text(tr, "run.csv", run_attributes(tr.meta)))
    >>> doc["url"], doc["tableSchema"]["columns"][1]
    ('run.csv', {'name': 'w_1', 'titles': 'w_1 [rad/s]', 'datatype': 'double', \
'schema:unitText': 'rad/s', 'dc:description': 'body angular velocity of the primary path; \
body_axis 1'})
    >>> [(p["schema:name"], p["schema:value"]) for p in doc["schema:additionalProperty"]][3]
    ('body_frame', 'the body axes the inertia was given in')
    """
    trajectory = one_unit(trajectory)
    columns = [
        _column(plain, header, name, index, trajectory)
        for header, (plain, name, index) in zip(
            csv_header(trajectory), trajectory.columns(), strict=True
        )
    ]
    document = {
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
    return json.dumps(document, indent=1, allow_nan=False) + "\n"


def write_csv_files(trajectory, path, *, scene=None, engine: str | None = None) -> list[Path]:
    """Write the CSV file ``path`` and its metadata sidecar (:func:`metadata_path`) where
    they are, not atomically, for a folder whose files move into place together
    (:func:`ga_rotors.files.output_set`): the files a
    :class:`~ga_rotors.results.streams.CsvStream` writes of the trajectory's pieces.
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
    from .dataset import run_attributes

    path = Path(path)
    with open(path, "wb") as fh:
        csv_rows(fh, trajectory, csv_engine(engine), header=True)
    attributes = run_attributes(trajectory.meta, scene, trajectory.t)
    return [path, write_metadata(path, trajectory, attributes)]


def write_metadata(path, trajectory, attributes: dict) -> Path:
    """Write the CSVW sidecar of the CSV file ``path`` (:func:`metadata_text` of
    ``trajectory``'s columns and the run's ``attributes``) beside it; return its path.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> csv = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> sidecar = write_metadata(csv, Trajectory({"t": np.zeros(2)}), {"body_frame": "body axes"})
    >>> sidecar.name, json.loads(sidecar.read_text())["url"]
    ('run.csv-metadata.json', 'run.csv')
    """
    path = Path(path)
    sidecar = metadata_path(path)
    sidecar.write_text(metadata_text(trajectory, path.name, attributes), encoding="utf-8")
    return sidecar


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
    engine = csv_engine(engine)  # an unknown engine: refused before any folder is touched
    if path is None:
        out = io.BytesIO()
        csv_rows(out, trajectory, engine, header=True)
        return out.getvalue().decode("utf-8")
    with output_file(path) as staged:
        write_csv_files(trajectory, staged, scene=scene, engine=engine)
    return Path(path)
