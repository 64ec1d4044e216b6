"""Loading a module from a file by its import spec: registered, executed, unregistered
if it fails. User torque modules (:mod:`ga_rotors.trust`) and generated loop modules
(:mod:`ga_rotors.integrators._codegen`) are both imported this way.
"""

from __future__ import annotations

import importlib.util
import sys
import types
from importlib.machinery import ModuleSpec

__all__ = ["load_registered"]


def load_registered(spec: ModuleSpec) -> types.ModuleType:
    """The module of ``spec``, registered in ``sys.modules`` under ``spec.name`` before it
    runs (so that what it imports, or what numba's cache looks up, finds it) and removed
    again if running it raises, so a broken module is never left half-imported.

    Examples
    --------
    >>> import pathlib, tempfile, importlib.util
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "ga_rotors_demo_mod.py"
    >>> _ = path.write_text("VALUE = 3\\n")
    >>> load_registered(importlib.util.spec_from_file_location("ga_rotors_demo_mod", path)).VALUE
    3
    >>> _ = path.write_text("raise ValueError('broken')\\n")
    >>> sys.modules.pop("ga_rotors_demo_mod") is not None
    True
    >>> load_registered(importlib.util.spec_from_file_location("ga_rotors_demo_mod", path))
    Traceback (most recent call last):
    ...
    ValueError: broken
    >>> "ga_rotors_demo_mod" in sys.modules
    False
    """
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        sys.modules.pop(spec.name, None)
        raise
    return module
