"""A trajectory as an xarray Dataset that follows the CF conventions.

The samples run along the dimension ``time``, whose index coordinate holds their times in
seconds (``standard_name = "time"``, ``axis = "T"``): ``ds.sel(time=30.0)`` is the sample
at t = 30 s. Multi-column arrays get a component dimension with the labels as
coordinates (``quaternion_component`` = w, x, y, z, ...). Every variable carries
``units`` and ``long_name`` (:mod:`~ga_rotors.results.variables`); the Dataset's
attributes say how the data were made (:func:`~ga_rotors.results.provenance.provenance`:
``Conventions``, the body frame, integrator, step, the resolved scene, package versions)
and, for a scene with an exact solution, the largest rounding-error bound of that
reference over the sampled times (how far the "truth" itself may be off).

The time coordinate's units are ``s``, not CF's ``seconds since <date>``: a simulation
has no calendar date, and a reference date would make xarray decode the times into
dates. cf_xarray finds the axis by its ``axis`` and ``standard_name``; pint-xarray reads
every ``units``.

A path that stopped early (its state stopped being finite) is padded with NaN after its
last valid sample, and its ``valid_samples`` attribute says how many rows are real.
"""

from __future__ import annotations

import numpy as np

from ..optional import require
from .provenance import provenance
from .variables import STANDARD, component_dim, describe, one_unit

__all__ = [
    "EXACT_BOUND_TIMES",
    "bound_rows",
    "run_attributes",
    "time_rows",
    "to_dataset",
    "variable_attrs",
]

#: At most this many sample times (evenly spread, the last included) are evaluated to find
#: the exact reference's largest error bound; the bounds grow smoothly with time.
EXACT_BOUND_TIMES = 1000


def variable_attrs(name: str) -> dict:
    """The CF attributes of the trajectory array ``name``: units, long name and, where
    CF's standard-name table has one, its standard name (and axis).

    Examples
    --------
    >>> variable_attrs("t")
    {'units': 's', 'long_name': 'simulation time', 'standard_name': 'time', 'axis': 'T'}
    >>> variable_attrs("L")
    {'units': 'kg m^2/s', 'long_name': 'body-frame angular momentum Iw'}
    """
    unit, long_name = describe(name)
    return {"units": unit, "long_name": long_name, **STANDARD.get(name, {})}


def bound_rows(count: int) -> np.ndarray:
    """The rows of a run of ``count`` samples at which its exact reference's largest
    rounding-error bound is evaluated: at most :data:`EXACT_BOUND_TIMES`, evenly spread,
    the first and the last included (the bounds grow smoothly with time).

    Examples
    --------
    >>> bound_rows(3).tolist(), bound_rows(10**6).size, int(bound_rows(10**6)[-1])
    ([0, 1, 2], 1000, 999999)
    """
    return np.unique(np.linspace(0, count - 1, min(count, EXACT_BOUND_TIMES)).astype(int))


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
    trajectory = one_unit(trajectory)  # an array of mixed units: its parts
    n, out = len(trajectory), {}
    for name in trajectory.names:
        a = trajectory[name]
        pad = [(0, n - a.shape[0])] + [(0, 0)] * (a.ndim - 1)
        out[name] = a if a.shape[0] == n else np.pad(a, pad, constant_values=np.nan)
    return out


def to_dataset(trajectory, scene=None):
    """The trajectory as a CF :class:`xarray.Dataset` with units and provenance.

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
    >>> ds["q"].dims, ds["q"].attrs["units"], ds["time"].attrs["axis"]
    (('time', 'quaternion_component'), '1', 'T')
    >>> float(ds["w"].sel(time=0.005, body_axis="3"))
    60.0
    >>> ds.attrs["Conventions"], ds.attrs["integrator"], ds.attrs["exact_error_bound"] < 1e-12
    ('CF-1.10', 'rk4', True)
    """
    xr = require("xarray", "results")
    trajectory = one_unit(trajectory)  # an array of mixed units: its parts, one unit each
    t = trajectory.t
    coords: dict = {"time": ("time", t, variable_attrs("t"))}
    variables = {}
    for name, a in time_rows(trajectory).items():
        if name == "t":
            continue
        attrs = variable_attrs(name)
        if trajectory[name].shape[0] < t.shape[0]:
            attrs["valid_samples"] = int(trajectory[name].shape[0])
        dims: tuple[str, ...] = ("time",)
        if a.ndim == 2:
            dim, labels = component_dim(trajectory, name)
            coords.setdefault(dim, (dim, list(labels)))
            dims = ("time", dim)
        variables[name] = (dims, a, attrs)
    return xr.Dataset(variables, coords=coords, attrs=run_attributes(trajectory.meta, scene, t))


def run_attributes(meta: dict, scene=None, times=()) -> dict:
    """What a run's files say about it: the :func:`~.provenance.provenance` of its ``meta``
    and, for a scene with an exact solution, that reference's largest rounding-error bound
    over the sample ``times`` (``exact_error_bound``, in rad; evaluated at those of
    :func:`bound_rows`, which a stream picks as it goes). The Dataset's global attributes,
    the CSV sidecar's properties.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene, run_scene
    >>> scene = load_scene("heavy_top").replace({"time.duration": 0.01})
    >>> tr = run_scene(scene)
    >>> attrs = run_attributes(tr.meta, scene, tr.t)
    >>> attrs["integrator"], attrs["exact_error_bound"] < 1e-12, attrs["exact_error_bound_units"]
    ('rk4', True, 'rad')
    >>> "exact_error_bound" in run_attributes({}, load_scene("damped_top"), [0.0])  # none
    False
    """
    attrs = provenance(meta, scene)
    times = np.asarray(times)
    exact = scene.exact_solution if scene is not None and scene.exact and times.size else None
    bound = None if exact is None else exact.bound(times[bound_rows(times.size)])
    if bound is not None:
        attrs["exact_error_bound"], attrs["exact_error_bound_units"] = bound, "rad"
    return attrs
