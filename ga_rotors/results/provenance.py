"""What a run integrated, as the attributes every results file carries.

One dictionary for every format: the netCDF and zarr files hold it as global attributes
(:func:`ga_rotors.results.to_dataset`), an NPZ archive as its ``attributes.json`` member,
and a CSV file names the body frame on its first line. Values are plain strings and
numbers (what netCDF attributes hold); nothing names the machine that wrote the file.
"""

from __future__ import annotations

import functools
import importlib.metadata
import json

import numpy as np

__all__ = ["BODY_FRAME_PRINCIPAL", "BODY_FRAME_USER", "CONVENTIONS", "body_frame", "provenance"]

#: The CF conventions the Datasets follow.
CONVENTIONS = "CF-1.10"

#: The body frame of a run whose ``meta`` does not name one, and whose body is integrated
#: in the axes its inertia was given in (``simulate``; a scene whose inertia is diagonal
#: in its own axes).
BODY_FRAME_USER = "the body axes the inertia was given in"

#: The body frame of a scene run whose inertia is not diagonal in the scene's axes (a full
#: tensor, an off-axis pivot) and whose ``meta`` names no frame: its data are in the
#: principal frame.
BODY_FRAME_PRINCIPAL = (
    "the principal axes of inertia; the scene's body axes are these turned by "
    "principal_rotation P (the scene body's orientation is q P*)"
)

_IDENTITY = (1.0, 0.0, 0.0, 0.0)

_PACKAGES = ("ga-rotors", "numpy", "numba", "scipy", "xarray")

#: meta key -> (attribute, its units) of the numbers a run records of its body.
_QUANTITIES = {
    "moments": ("principal_moments", "kg m^2"),
    "principal_rotation": ("principal_rotation", None),
    "mass": ("body_mass", "kg"),
    "centre_of_mass": ("body_centre_of_mass", "m"),
}

#: Entries of ``meta["paths"][path]`` kept in the ``paths_json`` attribute (the others,
#: such as the generated loop's file in the cache, name this machine).
_PATH_KEYS = ("complete", "samples", "ended_at", "reason")


def body_frame(meta: dict) -> str:
    """The frame the body-frame data of a run with ``meta`` are expressed in: a sentence.

    ``meta["body_frame"]`` when the run names it; otherwise what holds for the runs that
    do not: a scene whose ``principal_rotation`` is not the identity was integrated and
    written in its principal frame, any other run in the axes the body's inertia was given
    in; a trajectory with no run settings at all says so.

    Examples
    --------
    >>> body_frame({"integrator": "rk4"})
    'the body axes the inertia was given in'
    >>> body_frame({"principal_rotation": (0.0, 0.0, 0.0, 1.0)})[:32]
    'the principal axes of inertia; t'
    >>> body_frame({"body_frame": "axes of the disk"}), body_frame({})
    ('axes of the disk', 'not recorded')
    """
    named = meta.get("body_frame")
    if isinstance(named, str) and named.strip():
        return named
    rotation = meta.get("principal_rotation")
    if rotation is not None and tuple(float(x) for x in rotation) != _IDENTITY:
        return BODY_FRAME_PRINCIPAL
    if rotation is not None or "integrator" in meta:
        return BODY_FRAME_USER
    return "not recorded"


def provenance(meta: dict, scene=None) -> dict:
    """Attributes for a run's ``meta`` and optional scene: plain str/int/float values.

    CF's global attributes (``Conventions``, ``title``, ``source``, ``comment``), the
    frame of the body-frame data (``body_frame``), how the run was integrated (integrator,
    order, step, steps, sample_every, declared torques, each path's status as JSON), a
    moving body's mass and centre of mass (from the body-frame origin, in the body frame)
    and declared forces (each one's type and parameters as JSON, as the force's kernel
    takes them: SI units, space frame, :mod:`ga_rotors.forces`), the scene (its name, its
    resolved TOML, its exact solution) and package versions. netCDF attributes hold
    strings and numbers only, so the scene is its TOML text and lists of names are joined
    with ", ".

    Examples
    --------
    >>> import numpy as np
    >>> a = provenance({"integrator": "rk4", "step": 0.001, "torques": ["gravity"]})
    >>> a["Conventions"], a["integrator"], a["step"], a["torques"]
    ('CF-1.10', 'rk4', 0.001, 'gravity')
    >>> a["body_frame"], a["version_numpy"] == np.__version__
    ('the body axes the inertia was given in', True)
    >>> a = provenance({"mass": 0.32, "centre_of_mass": (0.0, 0.33, 0.0),
    ...                 "forces": ["uniform_gravity"], "force_params": [[0.0, 0.0, -3.1]]})
    >>> a["body_mass"], a["body_mass_units"], a["body_centre_of_mass_units"], a["forces"]
    (0.32, 'kg', 'm', 'uniform_gravity')
    >>> a["forces_json"]
    '[{"parameters": [0.0, 0.0, -3.1], "type": "uniform_gravity"}]'
    """
    if scene is not None:  # what a scene run's meta records of its scene
        meta = {**meta, "scene": scene.name, "scene_toml": scene.to_toml(), "exact": scene.exact}
    attrs: dict = {
        "Conventions": CONVENTIONS,
        "title": "ga_rotors results",
        "comment": "quaternions are (w, x, y, z), Hamilton product, rotating body to space "
        "(ga_rotors docs/conventions.md)",
        "body_frame": body_frame(meta),
    }
    for key in ("integrator", "order", "step", "steps", "sample_every", "problem", "primary"):
        if meta.get(key) is not None:
            value = meta[key]
            attrs[key] = value if isinstance(value, int | float | str) else str(value)
    if meta.get("integrator") is not None:
        order = f" (order {meta['order']})" if meta.get("order") is not None else ""
        step = f", step {meta['step']:g} s" if isinstance(meta.get("step"), int | float) else ""
        attrs["source"] = f"ga_rotors: {meta['integrator']} integrator{order}{step}"
    for key, (name, units) in _QUANTITIES.items():
        if meta.get(key) is not None:
            value = meta[key]
            attrs[name] = float(value) if np.ndim(value) == 0 else [float(x) for x in value]
            if units is not None:
                attrs[f"{name}_units"] = units
    for key in ("torques", "forces"):
        if key in meta:
            attrs[key] = ", ".join(meta[key])
    if "forces" in meta:
        params = meta.get("force_params") or [None] * len(meta["forces"])
        declared = [
            {"type": name, **({} if p is None else {"parameters": [float(x) for x in p]})}
            for name, p in zip(meta["forces"], params, strict=True)
        ]
        attrs["forces_json"] = json.dumps(declared, sort_keys=True)
    if "paths" in meta:
        paths = {
            name: {k: v for k, v in status.items() if k in _PATH_KEYS}
            for name, status in meta["paths"].items()
        }
        attrs["paths_json"] = json.dumps(paths, sort_keys=True, default=str)
    if meta.get("scene") is not None:
        attrs["scene"] = str(meta["scene"])
        attrs["title"] = f"ga_rotors run of the scene {attrs['scene']}"
    if meta.get("scene_toml") is not None:  # a scene run records its resolved scene
        attrs["scene_toml"] = str(meta["scene_toml"])
        attrs["exact_solution"] = meta.get("exact") or "none"
    attrs.update(_versions())
    return attrs


@functools.cache
def _versions() -> dict:
    """version_<package> of each installed package of :data:`_PACKAGES`, read once a
    process (parsing their metadata takes milliseconds, paid by every results file)."""
    versions = {}
    for package in _PACKAGES:
        try:
            versions[f"version_{package.replace('-', '_')}"] = importlib.metadata.version(package)
        except importlib.metadata.PackageNotFoundError:
            pass
    return versions
