"""How far a sweep's samples spread from their grid points' nominal runs, as Datasets.

:func:`summary` reduces the store's ``angle_from_nominal`` over ``sample``, one grid
point at a time, with xarray on Dask (chunk by chunk, in parallel): the median, the
95th percentile and the largest angle of each grid point at each output time (numpy's
``nanquantile`` and ``nanmax``, exact), and how many samples have no angle there
because their state stopped being finite. A task holds one grid point's angles at a
few output times (at most :data:`HELD_BYTES`, or one time's), never the whole store
(without Dask, the angles are read whole).
:func:`histogram` counts them in equal bins.
"""

from __future__ import annotations

import math

import numpy as np

from ..optional import require

__all__ = ["HELD_BYTES", "histogram", "lines", "summary"]

#: Bytes of one grid point's angles a reduction holds at once (more times than fit in it
#: are taken one at a time).
HELD_BYTES = 2**26

#: What a sample without an angle from its nominal run went through.
FAILED = "its state stopped being finite during the integration (NaN from then on)"


def _per_point(a):
    """``a`` (dims ..., sample, time) chunked whole along ``sample``, few times a chunk
    (without Dask, read whole)."""
    from .store import have_dask

    if not have_dask():
        return a.load()
    times = max(1, HELD_BYTES // (8 * a.sizes["sample"]))
    return a.chunk({"sample": -1, "time": times})


def _spread(a: np.ndarray) -> np.ndarray:
    """(median, 95th percentile, max, count of NaN) along the last axis of ``a``; NaN
    statistics where every value is NaN (without numpy's all-NaN warning)."""
    missing = np.isnan(a).sum(axis=-1)
    empty = missing == a.shape[-1]
    a = np.where(empty[..., None], 0.0, a)
    out = np.empty((*a.shape[:-1], 4))
    out[..., 0], out[..., 1] = np.nanquantile(a, [0.5, 0.95], axis=-1)
    out[..., 2] = np.nanmax(a, axis=-1)
    out[..., :3][empty] = np.nan
    out[..., 3] = missing
    return out


def summary(ds):
    """Each grid point's spread at each output time, from a sweep store's Dataset.

    Returns a Dataset over the grid's dimensions and ``time``: ``angle_median``,
    ``angle_p95``, ``angle_max`` (rad) of the samples' angles from the point's own
    nominal run; ``failed``, the samples without an angle (their state stopped being
    finite); ``nominal_failed``, whether the nominal run itself stopped being finite (then
    no sample has an angle); ``samples``, the draws per point. A sweep without draws has
    no spread: ``failed`` (0 or 1) says which grid points stopped being finite.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(
    ...     {"angle_from_nominal": (("sample", "time"), [[0.0], [0.01], [np.nan]]),
    ...      "q_nominal": (("time", "quaternion_component"), [[1.0, 0.0, 0.0, 0.0]])},
    ...     coords={"time": [1.0]})
    >>> s = summary(ds)
    >>> s["angle_median"].values.tolist(), s["failed"].values.tolist(), int(s["samples"])
    ([0.005], [1], 3)
    """
    xr = require("xarray", "results")
    if "angle_from_nominal" not in ds:
        finite = np.isfinite(ds["q"]).all("quaternion_component")
        out = xr.Dataset({"failed": (~finite).astype(np.int64), "samples": 1})
        out["failed"].attrs = {"long_name": "whether the grid point's run failed", "reason": FAILED}
        return out.compute()
    a = ds["angle_from_nominal"]
    stats = xr.apply_ufunc(
        _spread,
        _per_point(a),
        input_core_dims=[["sample"]],
        output_core_dims=[["statistic"]],
        dask="parallelized",
        output_dtypes=[float],
        dask_gufunc_kwargs={"output_sizes": {"statistic": 4}},
    )
    described = {
        "angle_median": "median",
        "angle_p95": "95th percentile",
        "angle_max": "largest",
    }
    out = xr.Dataset(
        {
            name: stats.isel(statistic=i).assign_attrs(
                units="rad",
                long_name=f"{what} of the samples' angles from their grid point's nominal run",
            )
            for i, (name, what) in enumerate(described.items())
        }
    )
    out["failed"] = (
        stats.isel(statistic=3)
        .astype(np.int64)
        .assign_attrs(long_name="samples without an angle from the nominal run", reason=FAILED)
    )
    nominal = np.isfinite(ds["q_nominal"]).all("quaternion_component")
    out["nominal_failed"] = (~nominal).assign_attrs(
        long_name="whether the grid point's nominal run stopped being finite (no angles then)"
    )
    out["samples"] = a.sizes["sample"]
    return out.drop_vars("statistic", errors="ignore").compute()


def histogram(ds, bins: int = 50):
    """Counts of each grid point's angles from its nominal run in ``bins`` equal bins
    from 0 to the largest angle, at each output time.

    Returns a Dataset: ``count`` (grid dims, time, bin) and the bin ``edges`` (rad);
    samples without an angle are not counted.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset({"angle_from_nominal": (("sample", "time"), [[0.0], [0.5], [1.0]])},
    ...                 coords={"time": [1.0]})
    >>> h = histogram(ds, bins=2)
    >>> h["count"].values.tolist(), h["edges"].values.tolist()
    ([[1, 2]], [0.0, 0.5, 1.0])
    """
    xr = require("xarray", "results")
    a = ds["angle_from_nominal"]
    top = float(a.max(skipna=True).fillna(0.0))
    edges = np.linspace(0.0, top if top > 0 else 1.0, bins + 1)

    def counts(block):
        rows = block.reshape(-1, block.shape[-1])
        out = np.array([np.histogram(row, bins=edges)[0] for row in rows])
        return out.reshape(*block.shape[:-1], bins)

    count = xr.apply_ufunc(
        counts,
        _per_point(a),
        input_core_dims=[["sample"]],
        output_core_dims=[["bin"]],
        dask="parallelized",
        output_dtypes=[np.int64],
        dask_gufunc_kwargs={"output_sizes": {"bin": bins}},
    )
    return xr.Dataset({"count": count, "edges": (("bin_edge",), edges, {"units": "rad"})}).compute()


def lines(s, most: int = 20) -> list[str]:
    """The summary ``s`` as text lines, in degrees, for the first ``most`` grid points.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(
    ...     {"angle_from_nominal": (("sample", "time"), [[0.0], [0.01], [np.nan]]),
    ...      "q_nominal": (("time", "quaternion_component"), [[1.0, 0.0, 0.0, 0.0]])},
    ...     coords={"time": [1.0]})
    >>> print("\\n".join(lines(summary(ds))))
    3 samples
      t [s]  median [deg]  95% [deg]  max [deg]  failed
      1      0.2865        0.5443     0.573      1 of 3: its state stopped being finite ...
    """
    grid = [d for d in s["failed"].dims if d != "time"]
    sizes = [s.sizes[d] for d in grid]
    n, spread = int(s["samples"]), "angle_median" in s
    out = []
    for p in range(min(math.prod(sizes), most)):
        here = s.isel(dict(zip(grid, np.unravel_index(p, sizes), strict=True)))
        where = ", ".join(f"{d} = {here[d].item():.6g}" for d in grid)
        out.append(f"{where} ({n} samples)" if where and spread else where or f"{n} samples")
        out.append(
            "  t [s]  median [deg]  95% [deg]  max [deg]  failed" if spread else "  t [s]  failed"
        )
        for j, t in enumerate(s["time"].values):
            failed = int(here["failed"].values[j])
            why = f": {FAILED}" if failed else ""
            if not spread:
                out.append(f"  {t:<6.6g} {'yes' + why if failed else 'no'}")
                continue
            if bool(here["nominal_failed"].values[j]):
                why = ": the grid point's nominal run stopped being finite"
            deg = [
                np.degrees(float(here[v].values[j]))
                for v in ("angle_median", "angle_p95", "angle_max")
            ]
            out.append(
                f"  {t:<6.6g} {deg[0]:<13.4g} {deg[1]:<10.4g} {deg[2]:<10.4g} {failed} of {n}{why}"
            )
    if math.prod(sizes) > most:
        out.append(f"... and {math.prod(sizes) - most} more grid points (summary() has them all)")
    return out
