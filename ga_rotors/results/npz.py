"""NPZ archives: every array of a trajectory as a ``.npy`` member, and what made them.

An archive holds one ``<name>.npy`` member per array (``t``, ``w``, ``q``, ...), the
component labels of each multi-column array as ``<name>__components.npy``, and
:func:`attributes_json`. ``numpy.load`` reads the arrays by name;
``json.loads(numpy.load(path)["attributes.json"])`` the attributes (numpy hands out a
member that is not ``.npy`` as its bytes). :class:`NpzStream` writes it from a run's
pieces, :func:`write_npz` from a whole trajectory (one piece).
"""

from __future__ import annotations

import json
import shutil
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..files import atomic_write
from .provenance import provenance

__all__ = ["ATTRIBUTES", "NpzStream", "attributes_json", "write_npz"]

#: The archive member holding the attributes.
ATTRIBUTES = "attributes.json"

#: Bytes copied at a time from a rows file into the archive.
COPY_BUFFER = 4 << 20


def attributes_json(trajectory, scene=None) -> str:
    """The ``attributes.json`` member of ``trajectory``'s archive: the run's attributes
    (:func:`~.provenance.provenance`: the body frame, integrator, step, scene, versions)
    and each array's units and long name (for an array whose columns carry different
    units, a raw state of a moving body, those of each part and the columns it takes:
    :data:`~ga_rotors.results.variables.PARTS`).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.zeros(2), "energy": np.ones(2)}, meta={"integrator": "rk4"})
    >>> data = json.loads(attributes_json(tr))
    >>> data["attributes"]["body_frame"], data["variables"]["energy"]["units"]
    ('the body axes the inertia was given in', 'J')
    """
    from .dataset import variable_attrs
    from .variables import PARTS

    variables = {}
    for name in trajectory.names:
        if name in PARTS:
            variables[name] = {"parts": {part: {**variable_attrs(part), "columns": list(columns)}
                                         for part, columns, _ in PARTS[name]}}  # fmt: skip
            continue
        try:
            variables[name] = variable_attrs(name)
        except InputError:  # an array a user added: no unit is known
            variables[name] = {}
    body = {"attributes": provenance(trajectory.meta, scene), "variables": variables}
    return json.dumps(body, indent=1, sort_keys=True, default=str)


def _member(name: str) -> zipfile.ZipInfo:
    """An archive member dated 1980-01-01 (zip's first date), not now: the same run
    written twice gives the same bytes."""
    info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
    info.external_attr = 0o644 << 16
    return info


def write_npz(trajectory, path, scene=None) -> Path:
    """Write every array of ``trajectory``, its component labels and its attributes to a
    ``.npz`` archive at ``path``, atomically (uncompressed, as ``numpy.savez``): the
    archive of :class:`NpzStream` given the whole trajectory as one piece.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.arange(3.0), "w": np.ones((3, 3))}, {"w": ("1", "2", "3")})
    >>> p = write_npz(tr, pathlib.Path(tempfile.mkdtemp()) / "run.npz")
    >>> data = np.load(p)
    >>> data.files, data["w__components"].tolist()
    (['t', 'w', 'w__components', 'attributes.json'], ['1', '2', '3'])
    """

    def write(fh) -> None:
        out = NpzStream(path, scene)
        try:
            out.append(trajectory)
            out.write(fh, trajectory.meta)
        finally:
            out.abort()

    return atomic_write(path, write)


class NpzStream:
    """The archive :func:`write_npz` writes, from a run's pieces: each array's rows are
    appended to a file of their own (beside ``path``) as they come, and :meth:`close`
    copies them into the archive, :data:`COPY_BUFFER` bytes at a time, each after its
    ``.npy`` header.

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

    def __init__(self, path, scene=None):
        self.path = Path(path)
        self.scene = scene
        self._dir = Path(tempfile.mkdtemp(dir=self.path.parent, prefix=".npz-rows-"))
        self._rows: dict = {}  # name -> [open rows file, trailing shape, rows]
        self._first = None  # the first piece: names, components, units

    def append(self, piece) -> None:
        """Add the rows of ``piece`` to each array's file."""
        if self._first is None:
            self._first = piece
        for name in piece.names:
            a = np.ascontiguousarray(piece[name], dtype=np.float64)
            if name not in self._rows:
                fh = open(self._dir / f"{len(self._rows)}.rows", "wb")
                self._rows[name] = [fh, a.shape[1:], 0]
            entry = self._rows[name]
            entry[0].write(a.data)
            entry[2] += a.shape[0]

    def write(self, out, meta: dict) -> None:
        """Write the archive into the binary file ``out``: each array's ``.npy`` header
        and rows, then the component labels and the attributes of the run's final
        ``meta``."""
        first = self._first.extended({}, meta=meta)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_STORED, allowZip64=True) as zf:
            for name, (fh, trailing, rows) in self._rows.items():
                fh.close()
                with zf.open(_member(f"{name}.npy"), "w", force_zip64=True) as member:
                    header = {"descr": "<f8", "fortran_order": False, "shape": (rows, *trailing)}
                    np.lib.format.write_array_header_1_0(member, header)
                    with open(fh.name, "rb") as rows_file:
                        shutil.copyfileobj(rows_file, member, COPY_BUFFER)
            for name, labels in first.components.items():
                if name in first:
                    with zf.open(_member(f"{name}__components.npy"), "w") as member:
                        np.lib.format.write_array(member, np.array(labels), allow_pickle=False)
            zf.writestr(_member(ATTRIBUTES), attributes_json(first, self.scene))

    def close(self, meta: dict) -> None:
        """Write the archive at ``path`` (nothing when no piece came), then remove the
        rows collected."""
        try:
            if self._first is not None:
                with open(self.path, "wb") as out:
                    self.write(out, meta)
        finally:
            self.abort()

    def abort(self) -> None:
        """Remove the rows collected so far."""
        for fh, _, _ in self._rows.values():
            fh.close()
        self._rows = {}
        shutil.rmtree(self._dir, ignore_errors=True)
