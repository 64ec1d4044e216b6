"""The sweep's zarr store: created from a description, its chunks written as raw bytes.

A sweep store is zarr format 2 with every variable uncompressed, unfiltered and in C
order, so its metadata and its chunk files follow from the Zarr v2 storage specification
alone: a ``.zarray`` and a ``.zattrs`` (holding xarray's ``_ARRAY_DIMENSIONS``) per
variable, the group's ``.zgroup`` and ``.zattrs``, the consolidated ``.zmetadata``; a
chunk file is the bytes of the chunk's C-ordered array (an edge chunk extended to the full
chunk shape). :func:`create` writes the metadata of a template Dataset in a few
milliseconds (xarray's ``to_zarr(compute=False)`` took 60-180 ms for the same store, a
tenth of a 10⁶-sample sweep's integration at 100 steps per sample); the tests check that
xarray reads it back identical to the store xarray itself writes from that template.
:func:`write_chunk` writes one chunk of one variable, falling back on zarr's own write
for any other layout (a store made by another tool). Chunk files go straight to the disk
(``O_DIRECT``) where the system allows it, not through the page cache: see
:func:`ga_rotors.files.write_direct`.
"""

from __future__ import annotations

import json
import math
import os
import threading
from pathlib import Path

import numpy as np

from ..files import write_direct
from ..optional import require

__all__ = ["create", "write_chunk"]

_ZARR_FORMAT = 2

_ZARR_WRITES = threading.Lock()


def _fill(dtype: np.dtype, encoding: dict):
    """The ``fill_value`` xarray gives a variable: its ``_FillValue``, NaN for floats."""
    if "_FillValue" in encoding:
        return encoding["_FillValue"]
    return "NaN" if dtype.kind == "f" else None


def _json(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"attribute value {value!r} is not JSON")


def _write(path: Path, data: bytes) -> None:
    with open(path, "wb") as f:
        f.write(data)


def create(path, template, chunks: dict, empty) -> None:
    """Write the store ``path`` (a new directory) for the Dataset ``template``.

    Parameters
    ----------
    template : xarray.Dataset
        Every variable and coordinate with its dims, dtype, attributes and (for those
        written now) data; ``encoding["_FillValue"]`` where it is not NaN / none.
    chunks : dict of dim -> int
        Chunk length along those dimensions (whole length along any other).
    empty : set of str
        Variables written later chunk by chunk: only their metadata is written (an
        unwritten chunk reads as the fill value).

    Examples
    --------
    >>> import tempfile, pathlib, xarray as xr
    >>> ds = xr.Dataset({"a": (("s",), np.broadcast_to(np.nan, (5,)))},
    ...                 coords={"s": np.arange(5)})
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "x.zarr"
    >>> create(out, ds, {"s": 2}, {"a"})
    >>> write_chunk(out, "a", np.array([1.0, 2.0]), 0)
    >>> xr.open_zarr(out)["a"].values.tolist()
    [1.0, 2.0, nan, nan, nan]
    """
    path = Path(path)
    path.mkdir()
    meta: dict = {".zgroup": {"zarr_format": _ZARR_FORMAT}, ".zattrs": dict(template.attrs)}
    # xarray names a variable's non-index coordinates in its "coordinates" attribute
    extra = [n for n in template.coords if n not in template.dims]
    for name, var in template.variables.items():
        dtype = var.dtype
        shape = var.shape
        chunk = [min(chunks.get(d, n), n) or 1 for d, n in zip(var.dims, shape, strict=True)]
        if name not in empty:
            chunk = [n or 1 for n in shape]  # written now, one chunk
        attrs = dict(var.attrs)
        if name in template.data_vars:
            own = [c for c in extra if set(template[c].dims) <= set(var.dims)]
            if own:
                attrs["coordinates"] = " ".join(own)
        attrs["_ARRAY_DIMENSIONS"] = list(var.dims)
        meta[f"{name}/.zarray"] = {
            "shape": list(shape),
            "chunks": chunk,
            "dtype": dtype.str,
            "fill_value": _fill(dtype, var.encoding),
            "order": "C",
            "filters": None,
            "dimension_separator": ".",
            "compressor": None,
            "zarr_format": _ZARR_FORMAT,
        }
        meta[f"{name}/.zattrs"] = attrs
        (path / name).mkdir()
        if name not in empty and var.size:
            key = ".".join(["0"] * max(1, var.ndim))
            _write(path / name / key, np.ascontiguousarray(var.values, dtype=dtype).tobytes())
    # compact JSON: json's C encoder (with indent=, the pure-Python one: 1.5 of the
    # 2.5 ms a store's creation took, holding the GIL while the sweep's threads integrate)
    for key, value in meta.items():
        _write(path / key, json.dumps(value, default=_json).encode())
    consolidated = {"metadata": meta, "zarr_consolidated_format": 1}
    _write(path / ".zmetadata", json.dumps(consolidated, default=_json).encode())


def _layout(store, name: str):
    """(chunk shape, dtype, fill, separator) of a variable stored as raw chunks, or None."""
    try:
        meta = json.loads((Path(store) / name / ".zarray").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    raw = (
        meta.get("zarr_format") == 2 and meta.get("compressor") is None
        and not meta.get("filters") and meta.get("order") == "C"
    )  # fmt: skip
    if not raw:
        return None
    sep = meta.get("dimension_separator", ".")
    return tuple(meta["chunks"]), np.dtype(meta["dtype"]), meta["fill_value"], sep


def write_chunk(
    store, name: str, block: np.ndarray, c: int, layouts: dict | None = None, first=None
) -> None:
    """Write ``block`` as chunk ``c`` along the first dimension of variable ``name``; or,
    given ``first``, as the part of that chunk from its row ``first`` on (a piece: the
    chunk's other rows are left as they are, for the other pieces to write).

    Raw bytes straight into the chunk's file (nothing to encode; zarr's own write path
    cost about a quarter of a 10⁶-sample sweep's time); zarr's write when the variable's
    layout is not the raw one. ``layouts``, a dict the caller keeps for this store (and
    drops if the store is made again), remembers each variable's layout after its first
    chunk: reading and parsing six metadata files a chunk was 3-4 ms of CPU per 10⁶
    samples.

    Examples
    --------
    >>> import tempfile, pathlib, xarray as xr
    >>> ds = xr.Dataset({"a": (("s", "k"), np.broadcast_to(np.nan, (3, 2)))})
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "x.zarr"
    >>> create(out, ds, {"s": 2}, {"a"})
    >>> write_chunk(out, "a", np.array([[5.0, 6.0]]), 1)  # the edge chunk: one row of two
    >>> xr.open_zarr(out)["a"].values.tolist()
    [[nan, nan], [nan, nan], [5.0, 6.0]]
    >>> write_chunk(out, "a", np.array([[3.0, 4.0]]), 0, first=1)  # chunk 0 in two pieces
    >>> write_chunk(out, "a", np.array([[1.0, 2.0]]), 0, first=0)
    >>> xr.open_zarr(out)["a"].values.tolist()
    [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]
    """
    if layouts is None:
        layout = _layout(store, name)
    else:
        if name not in layouts:
            layouts[name] = _layout(store, name)
        layout = layouts[name]
    if layout is None:
        zarr = require("zarr", "results")
        array = zarr.open_group(store, mode="r+", zarr_format=2)[name]
        lo = c * array.chunks[0] + (first or 0)
        with _ZARR_WRITES:  # zarr reads, changes and rewrites a chunk a piece is part of
            array[lo : lo + block.shape[0]] = block
        return
    chunks, dtype, _, sep = layout
    data = np.ascontiguousarray(block, dtype=dtype)
    start = first or 0
    if data.shape[1:] != chunks[1:] or start + data.shape[0] > chunks[0]:
        raise ValueError(f"{name}: block of shape {data.shape} for chunks of {chunks}")
    path = Path(store, name, sep.join([str(c)] + ["0"] * (len(chunks) - 1)))
    size = math.prod(chunks) * dtype.itemsize
    if first is None:
        write_direct(path, data)
    else:  # its own bytes of the file: a piece's first row is a page boundary where it can be
        write_direct(path, data, at=start * (size // chunks[0]))
    if start + data.shape[0] < chunks[0]:
        # The edge chunk is stored at the full chunk shape, but what lies past the array's
        # end is never read: the file is extended to that size (a hole, nothing written)
        # rather than padded with the fill value (a 10⁶-sample sweep's last chunk, a
        # quarter full, wrote 5 MB for 1.3 MB of samples, at the very end of the sweep).
        # A piece extends it too (a file only grows to it, whichever piece comes first).
        os.truncate(path, size)
