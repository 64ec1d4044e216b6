"""A trajectory as an xarray Dataset: dimension ``time``, units, and how it was made.

Every variable carries ``units`` and ``description`` attributes; multi-column arrays get
a component dimension with the labels as coordinates (``quaternion_component`` = w, x, y,
z, ...). The Dataset's attributes say how the data were made: the resolved scene as TOML
(when given), integrator, order, step, steps between samples, declared torques, package
versions, and for a scene with an exact solution the largest rounding-error bound of that
reference over the sampled times (how far the "truth" itself may be off).

A path that stopped early (its state stopped being finite) is padded with NaN after its
last valid sample, and its ``valid_samples`` attribute says how many rows are real.
"""

from __future__ import annotations

import functools
import importlib.metadata
import json

import numpy as np

from ..optional import require
from .variables import COMPONENT_DIMS, describe

__all__ = ["EXACT_BOUND_TIMES", "exact_bound_at", "provenance", "time_rows", "to_dataset"]

#: At most this many sample times (evenly spread, the last included) are evaluated to find
#: the exact reference's largest error bound; the bounds grow smoothly with time.
EXACT_BOUND_TIMES = 1000

_PACKAGES = ("ga-rotors", "numpy", "numba", "scipy", "xarray")


def provenance(meta: dict, scene=None) -> dict:
    """Dataset attributes for a run's ``meta`` and optional scene: plain str/int/float values.

    netCDF attributes hold strings and numbers only, so the scene is its TOML text, lists
    of names are joined with ", ", and the per-path status is JSON.

    Examples
    --------
    >>> a = provenance({"integrator": "rk4", "step": 0.001, "torques": ["gravity"]})
    >>> a["integrator"], a["step"], a["torques"], a["version_numpy"] == np.__version__
    ('rk4', 0.001, 'gravity', True)
    """
    attrs: dict = {"title": "ga_rotors results", "conventions_doc": "docs/conventions.md"}
    for key in ("integrator", "order", "step", "steps", "sample_every", "problem", "primary"):
        if meta.get(key) is not None:
            value = meta[key]
            attrs[key] = value if isinstance(value, int | float | str) else str(value)
    if meta.get("moments") is not None:
        attrs["principal_moments"] = [float(m) for m in meta["moments"]]
        attrs["principal_moments_units"] = "kg m2"
    if "torques" in meta:
        attrs["torques"] = ", ".join(meta["torques"])
    if "paths" in meta:
        attrs["paths_json"] = json.dumps(meta["paths"], sort_keys=True, default=str)
    if meta.get("scene") is not None:
        attrs["scene"] = str(meta["scene"])
    if meta.get("scene_toml") is not None:  # a scene run records its resolved scene
        attrs["scene_toml"] = str(meta["scene_toml"])
        attrs["exact_solution"] = meta.get("exact") or "none"
    if scene is not None:
        attrs["scene"] = scene.name
        attrs["scene_toml"] = scene.to_toml()
        attrs["exact_solution"] = scene.exact or "none"
    attrs.update(_versions())
    return attrs


@functools.cache
def _versions() -> dict:
    """version_<package> of each installed package of :data:`_PACKAGES`, read once a
    process: parsing their metadata took 3-9 ms, paid by every results file and sweep."""
    versions = {}
    for package in _PACKAGES:
        try:
            versions[f"version_{package.replace('-', '_')}"] = importlib.metadata.version(package)
        except importlib.metadata.PackageNotFoundError:
            pass
    return versions


def _exact_bound(scene, t: np.ndarray) -> float | None:
    """Largest rounding-error bound (rad) of the scene's exact reference over ``t``."""
    if t.size == 0:
        return None
    pick = np.unique(np.linspace(0, t.size - 1, min(t.size, EXACT_BOUND_TIMES)).astype(int))
    return exact_bound_at(scene, t[pick])


def exact_bound_at(scene, times: np.ndarray) -> float | None:
    """Largest rounding-error bound (rad) of the scene's exact reference at ``times``
    (None when the scene has no reference with a bound).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> exact_bound_at(load_scene("heavy_top"), np.array([0.0, 1.0])) < 1e-12
    True
    >>> exact_bound_at(load_scene("damped_top"), np.array([0.0])) is None
    True
    """
    exact = scene.exact_solution if scene.exact else None
    return None if exact is None else exact.bound(times)


def time_rows(trajectory) -> dict[str, np.ndarray]:
    """Each array of ``trajectory`` as :func:`to_dataset` holds it along ``time`` (``t``
    included): a path that stopped early padded with NaN to the trajectory's length.

    What a stream appends for each piece after the first (the variables, units and
    attributes are the first piece's Dataset's).

    Examples
    --------
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.arange(3.0), "euler": np.ones((2, 3))})
    >>> {name: a.shape for name, a in time_rows(tr).items()}
    {'t': (3,), 'euler': (3, 3)}
    """
    n = trajectory.t.shape[0]
    out = {}
    for name in trajectory.names:
        a = trajectory[name]
        if a.shape[0] < n:
            pad = np.full((n, *a.shape[1:]), np.nan)
            pad[: a.shape[0]] = a
            a = pad
        out[name] = a
    return out


def to_dataset(trajectory, scene=None):
    """The trajectory as an :class:`xarray.Dataset` with units and provenance.

    Parameters
    ----------
    trajectory : Trajectory
    scene : Scene, optional
        The scene that made it: its TOML and exact-solution bound become attributes.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene, run_scene
    >>> scene = load_scene("heavy_top").replace({"time.duration": 0.01})
    >>> ds = to_dataset(run_scene(scene), scene)
    >>> ds["q"].dims, ds["q"].attrs["units"], ds["t"].attrs["units"]
    (('time', 'quaternion_component'), '1', 's')
    >>> ds.attrs["integrator"], ds.attrs["exact_solution"], ds.attrs["exact_error_bound"] < 1e-12
    ('rk4', 'heavy_top', True)
    """
    xr = require("xarray", "results")
    t = trajectory.t
    coords = {"t": ("time", t, dict(zip(("units", "description"), describe("t"), strict=True)))}
    variables = {}
    for name, a in time_rows(trajectory).items():
        if name == "t":
            continue
        unit, description = describe(name)
        attrs = {"units": unit, "description": description}
        if trajectory[name].shape[0] < t.shape[0]:
            attrs["valid_samples"] = int(trajectory[name].shape[0])
        dims: tuple[str, ...] = ("time",)
        if a.ndim == 2:
            labels = trajectory.components.get(name) or tuple(str(i) for i in range(a.shape[1]))
            dim = COMPONENT_DIMS.get(tuple(labels), f"{name}_component")
            coords.setdefault(dim, (dim, list(labels)))
            dims = ("time", dim)
        variables[name] = (dims, a, attrs)
    attrs = provenance(trajectory.meta, scene)
    if scene is not None:
        bound = _exact_bound(scene, t)
        if bound is not None:
            attrs["exact_error_bound"] = bound
            attrs["exact_error_bound_units"] = "rad"
    return xr.Dataset(variables, coords=coords, attrs=attrs)
