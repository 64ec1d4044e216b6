"""A saved result of ``ga-rotors run``, read for the viewer in bounded memory.

A streamed run can hold more than memory: 10⁸ steps of the heavy top are 2·10⁷ samples, about
2.4 GB of arrays in its ``.npz``, while the page shows at most
:data:`~ga_rotors.view.page.MAX_FRAMES` frames and :data:`~ga_rotors.view.page.MAX_TRACE` points
of the axis' trace. So each array is read a block of rows at a time (:data:`BLOCK_BYTES`):
every row is checked, and only :data:`VIEW_ROWS` evenly spaced rows are kept, with each array's
last row (where a path that stopped early ends) and the rows of the largest \\|ω\\| and \\|L\\|
(the scale of the page's arrows). A result of at most :data:`VIEW_ROWS` rows is kept whole: its
page is the one the whole run gives.
"""

from __future__ import annotations

import math
import zipfile
import zlib
from pathlib import Path

import numpy as np

from ..errors import InputError, first_line

__all__ = ["BLOCK_BYTES", "VIEW_ROWS", "load_result"]

#: Rows of a saved result the viewer keeps at most (besides the few it must: see the module).
VIEW_ROWS = 200_000

#: Bytes of one array read at once.
BLOCK_BYTES = 8 << 20

#: A column-major (Fortran-order) array cannot be read by rows; it is read whole up to this.
WHOLE_BYTES = 256 << 20

#: What a damaged or foreign archive raises while it is read.
_UNREADABLE = (OSError, ValueError, EOFError, zipfile.BadZipFile, zlib.error)


def _header(fh):
    """(shape, Fortran order, dtype) of the ``.npy`` file ``fh``, left at its data."""
    version = np.lib.format.read_magic(fh)
    if version == (1, 0):
        return np.lib.format.read_array_header_1_0(fh)
    if version == (2, 0):
        return np.lib.format.read_array_header_2_0(fh)
    raise ValueError(f".npy format version {version} not supported")


class _Member:
    """One array of the archive: its name, shape and dtype (read from its header only)."""

    def __init__(self, archive: zipfile.ZipFile, info: zipfile.ZipInfo, where: Path):
        self.archive, self.info, self.where = archive, info, where
        self.name = info.filename.removesuffix(".npy")
        with archive.open(info) as fh:
            self.shape, self.fortran, self.dtype = _header(fh)
        if self.dtype.kind not in "iuf":  # objects, strings, bools, complex numbers
            raise InputError(f"{where}: {self.name}: expected finite real numbers, got "
                             f"{self.dtype.name} values")  # fmt: skip

    @property
    def rows(self) -> int:
        return self.shape[0] if self.shape else 1

    def _read(self, fh, size: int) -> bytes:
        data = fh.read(size)
        if len(data) != size:
            raise InputError(f"{self.where}: not a readable .npz result ({self.name} is cut short)")
        return data

    def blocks(self):
        """(first row, block) for each block of rows, in order; a 0-d array as one block."""
        trailing = self.shape[1:]
        row_bytes = self.dtype.itemsize * math.prod(trailing)
        with self.archive.open(self.info) as fh:
            _header(fh)
            if not self.shape:
                yield 0, np.frombuffer(self._read(fh, self.dtype.itemsize), self.dtype)[0]
                return
            if row_bytes == 0:  # rows of nothing, however many the header claims: no reads
                yield 0, np.empty(self.shape, self.dtype)
                return
            if trailing and self.fortran:
                if row_bytes * self.rows > WHOLE_BYTES:
                    raise InputError(
                        f"{self.where}: {self.name}: stored column-major and over "
                        f"{WHOLE_BYTES >> 20} MB (ga-rotors run stores rows)"
                    )
                whole = np.frombuffer(self._read(fh, row_bytes * self.rows), self.dtype)
                yield 0, whole.reshape(self.shape, order="F")
                return
            step = max(1, BLOCK_BYTES // max(row_bytes, 1))
            for lo in range(0, self.rows, step):
                n = min(step, self.rows - lo)
                block = np.frombuffer(self._read(fh, n * row_bytes), self.dtype)
                yield lo, block.reshape((n, *trailing))

    def kept(self, rows: np.ndarray) -> np.ndarray:
        """The rows ``rows`` (those below this array's length) after checking every row."""
        if not self.shape:
            ((_, value),) = self.blocks()
            self._check(value)
            return np.asarray(value)
        rows = rows[rows < self.rows]
        out = np.empty((rows.size, *self.shape[1:]), self.dtype.newbyteorder("="))
        last = -np.inf
        for lo, block in self.blocks():
            self._check(block)
            if self.name == "t":  # the slider's times: every one after the one before
                last = self._check_increasing(block, lo, last)
            a, b = np.searchsorted(rows, [lo, lo + block.shape[0]])
            out[a:b] = block[rows[a:b] - lo]
        return out

    def _check(self, block) -> None:
        if not np.isfinite(block).all():
            raise InputError(f"{self.where}: {self.name}: expected finite numbers")

    def _check_increasing(self, block, lo: int, last: float) -> float:
        joined = np.concatenate([[last], np.asarray(block, dtype=np.float64)])
        back = np.flatnonzero(np.diff(joined) <= 0)
        if back.size:
            k = lo + int(back[0])
            raise InputError(
                f"{self.where}: t: expected strictly increasing times, got "
                f"t[{k}] = {joined[back[0] + 1]:.6g} after {joined[back[0]]:.6g}"
            )
        return float(joined[-1])


def _expected_dims() -> dict[str, int]:
    from .. import paths

    return {"t": 1, "w": 3} | {p.array: p.dim for p in paths.PATHS.values()}


def _check_shapes(members: dict[str, _Member], where: Path) -> None:
    for name in ("t", "w"):
        if name not in members:
            raise InputError(f"{where}: the result has no {name!r} array")
    for name, dim in _expected_dims().items():
        m = members.get(name)
        if m is not None and (
            len(m.shape) != (1 if name == "t" else 2) or (name != "t" and m.shape[1] != dim)
        ):
            shape = "(n,)" if name == "t" else f"(n, {dim})"
            raise InputError(f"{where}: {name}: expected shape {shape}, got {m.shape}")
    if members["t"].rows == 0:  # (and no row index below 0 to keep)
        raise InputError(f"{where}: t: expected at least one sample, got none")


def _largest_rows(w: _Member, moments) -> list[int]:
    """The rows of the largest |ω| and |L| = |I ω| (one pass over ω)."""
    best = [(-1.0, 0), (-1.0, 0)]
    scale = np.asarray(moments, dtype=np.float64)
    for lo, block in w.blocks():
        w._check(block)
        for k, values in enumerate((block, block * scale)):
            norms = np.einsum("ij,ij->i", values, values)
            i = int(norms.argmax()) if norms.size else 0
            if norms.size and norms[i] > best[k][0]:
                best[k] = (float(norms[i]), lo + i)
    return [row for _, row in best]


def _rows(members: dict[str, _Member], moments) -> np.ndarray:
    """The rows to keep: every row of a small result, else evenly spaced ones and those the
    page needs exactly (each array's last, the largest |ω| and |L|)."""
    n = members["t"].rows
    if all(m.rows <= VIEW_ROWS for m in members.values()):
        return np.arange(max(n, *(m.rows for m in members.values())))
    must = [m.rows - 1 for m in members.values() if m.shape]
    must += _largest_rows(members["w"], moments)
    even = np.linspace(0, n - 1, VIEW_ROWS).round().astype(np.int64)
    return np.unique(np.concatenate([even, np.asarray(must, dtype=np.int64)]))


def load_result(path: Path):
    """(scene, trajectory) of a saved result, a run's directory or its ``.npz`` file, with
    at most about :data:`VIEW_ROWS` of its rows (every row checked).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> load_result(pathlib.Path(tempfile.mkdtemp()))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: ...: no .npz result here (ga-rotors run writes one ...)
    """
    from ..scene import load_scene
    from ..trajectory import Trajectory

    path = Path(path)
    if path.is_dir():
        found = sorted(path.glob("*.npz"))
        if len(found) != 1:
            detail = "no .npz result here" if not found else "more than one .npz result here"
            raise InputError(
                f"{path}: {detail} (ga-rotors run writes one when the scene's output.data "
                'lists "npz")'
            )
        path = found[0]
    scene_file = path.with_name(f"{path.stem}.scene.toml")
    if not scene_file.is_file():
        raise InputError(f"{path}: no {scene_file.name} beside it (the scene that made it)")
    scene = load_scene(scene_file)
    try:
        with zipfile.ZipFile(path) as archive:
            infos = [
                i for i in archive.infolist()
                if i.filename.endswith(".npy") and not i.filename.endswith("__components.npy")
            ]  # fmt: skip
            members = {m.name: m for m in (_Member(archive, i, path) for i in infos)}
            _check_shapes(members, path)
            rows = _rows(members, scene.body.moments)
            arrays = {name: m.kept(rows) for name, m in members.items()}
    except InputError:
        raise
    except _UNREADABLE as exc:
        raise InputError(f"{path}: not a readable .npz result ({first_line(exc)})") from None
    meta = {"moments": scene.body.moments, "primary": scene.paths[0]}
    if scene.moves:  # where the quaternion path's centre of mass is in the body frame
        meta.update(mass=scene.mass, centre_of_mass=scene.body.centre_of_mass)
    return scene, Trajectory(arrays, meta=meta)
