"""Scenes: a rigid-body simulation described as data, from the file to the run's files.

Data flows one way, one module per step:

* :mod:`~ga_rotors.scene.reader`: checks untrusted nested data, errors naming file and key;
* :mod:`~ga_rotors.scene.schema`: every table and key, resolved with its defaults;
* :mod:`~ga_rotors.scene.model`: :class:`Scene`, the resolved scene and its derived values;
* :mod:`~ga_rotors.scene.toml_io`: a resolved scene written back as TOML;
* :mod:`~ga_rotors.scene.loading`: :func:`load_scene`, files and the bundled scenes;
* :mod:`~ga_rotors.scene.exact`: the exact solution that applies, in the scene's terms
  (:mod:`~ga_rotors.scene.motion` for a body moving through space; its ``[[forces]]``
  are :mod:`~ga_rotors.scene.force_types`);
* :mod:`~ga_rotors.scene.run`: :func:`run_scene`, a scene integrated into a Trajectory
  (:func:`run_pieces`: the same run as pieces of consecutive samples);
* :mod:`~ga_rotors.scene.summary`: the closing summary (invariants, cross-check, exact),
  accumulated piece by piece; :mod:`~ga_rotors.scene.motion_summary` that of a body moving
  through space (its exact errors, balances and cross-check), both a
  :class:`~ga_rotors.scene.reports.Report`;
* :mod:`~ga_rotors.scene.thinning`: the bounded copy of a long run its figure is drawn from;
* :mod:`~ga_rotors.scene.figures`: the run's figure;
* :mod:`~ga_rotors.scene.formats`: the data formats (``output.data``), a registry;
* :mod:`~ga_rotors.scene.output`: the run's files, streamed as it goes and moved into
  place atomically (:func:`stream_scene`).

The names below are imported on first use, so ``import ga_rotors.scene.reader`` (which
:mod:`ga_rotors.effects` needs) does not import the rest.

Examples
--------
>>> from ga_rotors.scene import load_scene, run_scene
>>> scene = load_scene("spinning_disk").replace({"time.duration": 0.01})
>>> run_scene(scene).meta["scene"]
'spinning_disk'
"""

from __future__ import annotations

import importlib

#: public name -> the module of this package that defines it.
_EXPORTS = {
    "Scene": "model",
    "load_scene": "loading",
    "bundled": "loading",
    "bundled_path": "loading",
    "run_scene": "run",
    "run_pieces": "run",
    "stream_scene": "output",
    "RunSummary": "summary",
    "report": "summary",
    "Report": "summary",
    "write_outputs": "output",
    "figure_png": "figures",
    "dumps_toml": "toml_io",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_EXPORTS[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
