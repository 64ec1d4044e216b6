"""Loading a module from a file by its import spec, or from its source text: registered,
executed, unregistered if it fails. User torque modules (:mod:`ga_rotors.trust`) and
generated loop modules (:mod:`ga_rotors.integrators._cache`) are all imported this way;
the generated ones under :data:`GENERATED_LOCK`, their text kept in ``linecache``
(:func:`remember_source`) so tracebacks and ``inspect.getsource`` show it.
"""

from __future__ import annotations

import importlib.util
import linecache
import sys
import threading
import types
from importlib.machinery import ModuleSpec

__all__ = ["GENERATED_LOCK", "load_registered", "load_source", "remember_source"]

#: Held while a generated module is looked up, made and loaded: a module is registered in
#: ``sys.modules`` before it has run, and another thread finding it there half made used
#: it ("has no attribute 'loop'": single runs or a sweep's threads starting together in a
#: new process). Reentrant: making one generated module may load another.
GENERATED_LOCK = threading.RLock()


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
    return _run_registered(spec.name, module, lambda: spec.loader.exec_module(module))


def load_source(name: str, text: str) -> types.ModuleType:
    """The module ``name`` made from the source ``text`` (no file: compiled in memory),
    registered and removed again if it raises, as :func:`load_registered`; its text is
    remembered (:func:`remember_source`).

    Examples
    --------
    >>> import inspect
    >>> module = load_source("ga_rotors_demo_text", "def f():\\n    return 4\\n")
    >>> module.f(), module.__file__
    (4, '<ga_rotors_demo_text>')
    >>> print(inspect.getsource(module.f))
    def f():
        return 4
    <BLANKLINE>
    >>> _ = sys.modules.pop("ga_rotors_demo_text")
    """
    module = types.ModuleType(name)
    module.__file__ = f"<{name}>"
    remember_source(module.__file__, text)
    code = compile(text, module.__file__, "exec")
    return _run_registered(name, module, lambda: exec(code, module.__dict__))


def remember_source(filename: str, text: str) -> None:
    """Keep ``text`` in ``linecache`` as the lines of ``filename`` (as kingdon does
    for its generated code): a traceback through a generated module, and
    ``inspect.getsource`` of its functions, show the generated text, even for a
    module compiled in memory or a file pruned from the cache since."""
    # mtime None: linecache.checkcache keeps the entry instead of looking for the file
    linecache.cache[filename] = (len(text), None, text.splitlines(True), filename)


def _run_registered(name: str, module: types.ModuleType, run) -> types.ModuleType:
    sys.modules[name] = module
    try:
        run()
    except BaseException:
        sys.modules.pop(name, None)
        raise
    return module
