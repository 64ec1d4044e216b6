"""A sweep's zarr store: made whole by xarray, filled chunk by chunk through zarr.

:func:`create` writes the whole store's description at once with
:meth:`xarray.Dataset.to_zarr` (zarr format 2, consolidated metadata, uncompressed:
orientations and rates are full-precision noise to a compressor), in a staging directory
renamed into place, so a store is there whole or not at all. The per-sample variables
are written as placeholders of their fill value, which zarr stores as no chunk at all;
the grid's coordinates, the output times and the nominal runs are written then.
:class:`ChunkWriter` then writes one chunk's region of every per-sample variable through
zarr, and last its flag in ``chunk_done``: a chunk counts as written only once all of it
is. What the store holds (names, dimensions, attributes) is described in
docs/ensembles.md, "The store".
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from ..errors import InputError, first_line
from ..optional import require

__all__ = ["FORMAT", "ChunkWriter", "create", "done", "open_store"]

#: The layout of the stores this version writes (attribute ``sweep_format``); a store of
#: another layout is opened but never resumed. 3: the samples cut into chunks of equal
#: size as far as they go (2: full chunks and a short last one; the chunk regions
#: differ, so resuming one with the other would write samples where others belong).
FORMAT = 3

#: What the orientations and rates are expressed in (the ensemble's outputs).
BODY_FRAME = (
    "body axes as the scene gives the body; q rotates them to the space frame "
    "(v_space = q v_body q*), w is the angular velocity in them"
)

_COMPONENTS = {
    "quaternion_component": ["w", "x", "y", "z"],
    "body_axis": ["1", "2", "3"],
    "space_axis": ["x", "y", "z"],
}


def _per_sample(sweep) -> dict:
    """name -> (dims after the samples', attributes) of the variables every chunk writes
    (units from the results' one table of them)."""
    from ..results.variables import describe

    out = {
        "q": (
            ("time", "quaternion_component"),
            {
                "units": describe("q")[0],
                "long_name": "orientation quaternion (w, x, y, z), body to space",
            },
        ),
        "w": (
            ("time", "body_axis"),
            {"units": describe("w")[0], "long_name": "body angular velocity"},
        ),
    }
    if sweep.scene.moves:  # a body moving through space: where its origin is, and how fast
        for name in ("position", "velocity"):
            unit, long_name = describe(name)
            out[name] = (
                ("time", "space_axis"),
                {"units": unit, "long_name": long_name.replace(", primary path", "")},
            )
    if sweep.draws:
        out["angle_from_nominal"] = (
            ("time",),
            {
                "units": "rad",
                "long_name": "geodesic angle from the grid point's nominal orientation (q_nominal)",
            },
        )
    return out


def template(sweep, nominal=None, lazy: bool = False):
    """The whole store as a Dataset, every per-sample value at its fill value (NaN).

    ``nominal``: (q, w) of each grid point's nominal run, (points, time, 4) and
    (points, time, 3), with draws. ``lazy``: the per-sample values as Dask arrays in the
    store's chunks (which ``to_zarr(compute=False)`` describes without computing: made
    with ``dask.array.full``, since chunking a numpy array has Dask hash its values).
    """
    from ..results import provenance
    from ..results.dataset import variable_attrs

    xr = require("xarray", "results")
    dims, shape, k = sweep.dims, sweep.shape, sweep.times.size

    def empty(*extra):
        if lazy:
            full = require("dask.array", "dask").full
            return full(shape + extra, np.nan, chunks=sweep.chunk_shape + extra)
        return np.broadcast_to(np.nan, shape + extra)

    data = {
        name: (
            dims + more,
            empty(*(k if d == "time" else len(_COMPONENTS[d]) for d in more)),
            attrs,
        )
        for name, (more, attrs) in _per_sample(sweep).items()
    }
    data["chunk_done"] = (
        ("chunk",),
        np.zeros(sweep.chunks, dtype=np.int8),
        {"long_name": "1 once the chunk's samples are written", "units": "1"},
    )
    used = {d for more, _ in _per_sample(sweep).values() for d in more}
    coords = {"time": ("time", sweep.times, variable_attrs("t")),
              **{d: v for d, v in _COMPONENTS.items() if d in used}}  # fmt: skip
    for key, values in sweep.grid:
        name = sweep.names[key]
        coords[name] = (name, values, {"scene_key": key, "long_name": f"scene key {key}"})
    for d in sweep.draws:
        coords[sweep.names[d.key]] = (
            dims,
            empty(),
            {
                "scene_key": d.key,
                "long_name": f"scene key {d.key}, drawn",
                "distribution": f"{d.distribution} {d.a!r} {d.b!r}",
            },
        )
    if nominal is not None:
        grid = dims[:-1]
        points = tuple(len(v) for _, v in sweep.grid)
        described = _per_sample(sweep)
        for name, values, (more, attrs) in zip(
            ("q_nominal", "w_nominal"), nominal, (described["q"], described["w"]), strict=True
        ):
            attrs = {
                **attrs,
                "long_name": f"{attrs['long_name']} of the grid point's nominal "
                "run (the draws at their centres)",
            }
            data[name] = (grid + more, values.reshape(points + values.shape[1:]), attrs)
    scene = sweep.scene
    meta = {
        "integrator": scene.data["integrator"]["method"],
        "step": scene.step,
        "steps": scene.steps,
        "torques": [t.name for t in scene.torques()],
    }
    attrs = provenance(meta, scene)
    attrs.update(
        title=f"ga_rotors sweep of {scene.name}",
        body_frame=BODY_FRAME,
        sweep_format=FORMAT,
        sweep_toml=sweep.text,
        seed=-1 if sweep.seed is None else sweep.seed if sweep.seed < 2**63 else str(sweep.seed),
        samples_per_grid_point=sweep.samples,
        varied_keys=", ".join(sweep.keys),
        **sweep.digests,
    )
    return xr.Dataset(data, coords=coords, attrs=attrs)


#: Bytes of a chunk of the variables written when the store is made (the nominal runs).
WHOLE_CHUNK_BYTES = 2**24


def have_dask() -> bool:
    """Whether Dask is installed (it comes with the dask extra)."""
    from ..optional import MissingExtraError

    try:
        require("dask.array", "dask")
    except MissingExtraError:
        return False
    return True


def _by_chunk(sweep) -> set[str]:
    """The variables each chunk writes its region of (the others are written whole now)."""
    return {*_per_sample(sweep), *(sweep.names[d.key] for d in sweep.draws), "chunk_done"}


def _encoding(sweep, ds) -> dict:
    """No compression; chunks of the sweep's chunks for what each chunk writes, of at
    most :data:`WHOLE_CHUNK_BYTES` for what is written when the store is made."""
    from .spec import block_shape

    chunks = dict(zip(sweep.dims, sweep.chunk_shape, strict=True)) | {"chunk": 1}
    by_chunk = _by_chunk(sweep)
    out = {}
    for name, v in ds.variables.items():
        if name in by_chunk:
            shape = tuple(chunks.get(d, n) for d, n in zip(v.dims, v.shape, strict=True))
        else:
            shape = block_shape(v.shape, max(1, WHOLE_CHUNK_BYTES // v.dtype.itemsize))
        out[name] = {"compressors": None, "chunks": tuple(max(1, n) for n in shape)}
    return out


def create(sweep, path, nominal=None) -> None:
    """Write the store ``path`` for ``sweep``: all of it, or nothing.

    With Dask, the variables the chunks fill in are Dask arrays that ``to_zarr(...,
    compute=False)`` describes without computing; without it, numpy placeholders that
    zarr finds equal to the fill value and stores as no chunk (a pass over the values).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.sweep import load_sweep
    >>> text = '[sweep]\\nscene = "heavy_top"\\nchunk = 2\\n[grid]\\n"body.mass" = [1, 2, 3]'
    >>> s = load_sweep(text)
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "s.zarr"
    >>> create(s, path)
    >>> ds = open_store(path)
    >>> ds["q"].dims, ds["body_mass"].values.tolist(), done(group(path)).tolist()
    (('body_mass', 'time', 'quaternion_component'), [1.0, 2.0, 3.0], [False, False])
    """
    path = Path(path)
    lazy = have_dask()
    ds = template(sweep, nominal, lazy)
    encoding = _encoding(sweep, ds)
    try:
        staging = Path(tempfile.mkdtemp(dir=path.parent, prefix=f".{path.name}.staging-"))
    except OSError as exc:
        raise write_error(path, exc, "creating it") from None
    try:
        new = staging / "new"
        ds.to_zarr(new, zarr_format=2, consolidated=True, encoding=encoding, compute=not lazy)
        os.rename(staging / "new", path)
    except OSError as exc:
        raise write_error(path, exc, "creating it") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def write_error(store, exc: OSError, what: str) -> InputError:
    # One line naming the store. An InputError pickles as its message, so a Dask
    # worker's reaches the command as it is.
    return InputError(f"cannot write {store} ({what}): {exc.strerror or exc}", key="--out")


def group(path, mode: str = "r+"):
    """The store's zarr group (for reading its flags or nominal runs)."""
    zarr = require("zarr", "results")
    return zarr.open_group(str(path), mode=mode, zarr_format=2, use_consolidated=True)


class ChunkWriter:
    """Writes chunks into the store at ``path``: each chunk's region of every
    per-sample variable, then its flag in ``chunk_done`` (a chunk counts as written only
    once all of it is). Each array is opened once, at its first chunk: opening reads its
    metadata, which per chunk cost 30 ms of a 10⁶-sample sweep's 200 ms of writes.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.sweep import load_sweep
    >>> text = '[sweep]\\nscene = "heavy_top"\\nchunk = 2\\n[grid]\\n"body.mass" = [1, 2, 3]'
    >>> s = load_sweep(text)
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "s.zarr"
    >>> create(s, path)
    >>> q = np.tile([1.0, 0.0, 0.0, 0.0], (2, 1, 1))  # the chunk's two samples, one time
    >>> ChunkWriter(path).write(s, 0, {"q": q, "w": np.zeros((2, 1, 3))})
    >>> done(group(path)).tolist(), open_store(path)["q"][:, 0, 0].values.tolist()
    ([True, False], [1.0, 1.0, nan])
    """

    def __init__(self, path):
        self.path = path
        self.root = group(path)
        self._arrays: dict = {}

    def _array(self, name: str):
        if name not in self._arrays:
            # every chunk holds samples: zarr need not check whether it is all fill value
            self._arrays[name] = self.root[name].with_config({"write_empty_chunks": True})
        return self._arrays[name]

    def write(self, sweep, c: int, outputs: dict) -> None:
        """Write chunk ``c``'s ``outputs`` (name -> array, the chunk's samples first,
        flat), then its flag."""
        region = sweep.chunk_region(c)[2]
        extents = tuple(s.stop - s.start for s in region.values())
        where = tuple(region.values())
        try:
            for name, a in outputs.items():
                self._array(name)[where] = a.reshape(extents + a.shape[1:])
            self._array("chunk_done")[c] = 1
        except OSError as exc:  # a full disk, a store removed under the sweep...
            raise write_error(self.path, exc, f"chunk {c}") from None


def done(root) -> np.ndarray:
    """Which chunks of the store are written (its flags, unwritten ones 0).

    Examples
    --------
    >>> done({"chunk_done": np.array([1, 0, 1], dtype=np.int8)}).tolist()
    [True, False, True]
    """
    return root["chunk_done"][:] == 1


def open_store(path):
    """The store at ``path`` as a lazy Dataset, checked to be a sweep store.

    Examples
    --------
    >>> open_store("no_such.zarr")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: no_such.zarr: not a sweep store (...)
    """
    xr = require("xarray", "results")
    try:
        ds = xr.open_zarr(path, consolidated=True)
    except (OSError, ValueError, KeyError) as exc:
        raise InputError(f"{path}: not a sweep store ({first_line(exc)})") from None
    if "sweep_format" not in ds.attrs and "sweep_digest" in ds.attrs:
        raise InputError(
            f"{path}: a sweep store of an earlier ga_rotors (its inputs as value_0, value_1, "
            "...): xarray.open_zarr reads it; this version neither opens nor resumes it"
        )
    lacking = [v for v in ("chunk_done", "q", "w") if v not in ds]
    lacking += [a for a in ("sweep_format", "scene_digest", "sweep_digest") if a not in ds.attrs]
    if lacking:
        raise InputError(f"{path}: not a sweep store (no {', '.join(lacking)})")
    return ds
