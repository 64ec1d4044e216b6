"""Who may run code: a scene's user torques run only when the user opts in, from named folders.

Scene files may come from anyone. Loading, showing and validating a scene reads data and
never imports or executes anything. A scene's ``user`` effect (``function =
"module:kernel"``) is code; it is imported only

* when the user has opted in, for this run: ``ga-rotors run SCENE --allow-user-code [DIR]``,
  the environment setting ``GA_ROTORS_ALLOW_USER_CODE=DIR[:DIR...]``, or in Python
  ``with allow_user_code(DIR): simulate(scene)``;
* after the whole scene has been read and validated (when it is simulated);
* from a folder the user named (``--allow-user-code`` alone names the scene file's own
  folder), never from the rest of ``sys.path``: ``"os:system"`` or any other installed
  module is refused, and so is a module of that name already imported from elsewhere.

The folders are searched without being added to ``sys.path``; a module found there is
registered in ``sys.modules`` under its own name so the generated loop can import it.
"""

from __future__ import annotations

import contextlib
import contextvars
import importlib
import importlib.machinery
import importlib.util
import os
import sys
import types
from collections.abc import Iterator
from pathlib import Path

from ._modules import load_registered
from .errors import InputError

__all__ = ["ENV", "FLAG", "allow_user_code", "allowed_folders", "import_user_module"]

#: The environment setting that opts in: folders separated by ``os.pathsep``.
ENV = "GA_ROTORS_ALLOW_USER_CODE"
#: The ``ga-rotors run`` option that opts in (optionally followed by a folder).
FLAG = "--allow-user-code"

_ALLOWED: contextvars.ContextVar[tuple[Path, ...]] = contextvars.ContextVar(
    "ga_rotors_allowed_user_code", default=()
)


def _folder(value, source: str) -> Path:
    path = Path(value).expanduser()
    if not path.is_dir():
        raise InputError(f"{value}: not a folder; name the folder holding your code", key=source)
    return path.resolve()


@contextlib.contextmanager
def allow_user_code(*folders) -> Iterator[tuple[Path, ...]]:
    """Allow user torques to be imported from ``folders`` inside the ``with`` block.

    Examples
    --------
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> with allow_user_code(folder) as allowed:
    ...     allowed == allowed_folders()
    True
    >>> allowed_folders()
    ()
    """
    if not folders:
        raise InputError("name at least one folder holding your code", key="allow_user_code")
    added = tuple(_folder(f, "allow_user_code") for f in folders)
    token = _ALLOWED.set(_ALLOWED.get() + added)
    try:
        yield _ALLOWED.get()
    finally:
        _ALLOWED.reset(token)


def allowed_folders() -> tuple[Path, ...]:
    """The folders user code may come from now: :func:`allow_user_code` blocks, then ``ENV``.

    Examples
    --------
    >>> import os
    >>> os.environ.pop(ENV, None) and None
    >>> allowed_folders()
    ()
    """
    env = tuple(
        _folder(part, ENV) for part in os.environ.get(ENV, "").split(os.pathsep) if part.strip()
    )
    return _ALLOWED.get() + env


def _refusal(spec: str) -> str:
    return (
        f"the scene asks to run code ({spec}); scenes are data and run nothing unless you "
        f"allow it: pass {FLAG} (the scene's folder) or {FLAG} DIR to ga-rotors run, or set "
        f"{ENV}=DIR - only for code you trust"
    )


def _inside(file, folders: tuple[Path, ...]) -> bool:
    if not file:
        return False
    where = Path(file).resolve()
    return any(where.is_relative_to(folder) for folder in folders)


def import_user_module(module: str, spec: str | None = None) -> types.ModuleType:
    """Import ``module`` from the allowed folders only; InputError (one line) otherwise.

    ``spec`` is what the scene wrote (``"module:kernel"``), for the messages.

    Examples
    --------
    >>> import_user_module("os", "os:system")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: the scene asks to run code (os:system); scenes are data ...
    """
    spec = spec or module
    folders = allowed_folders()
    if not folders:
        raise InputError(_refusal(spec))
    top = module.partition(".")[0]
    loaded = sys.modules.get(top)
    if loaded is None:
        found = importlib.machinery.PathFinder.find_spec(top, [str(f) for f in folders])
        if found is None:
            raise InputError(
                f"no module {top!r} in the allowed folders ({', '.join(map(str, folders))})"
            )
        loaded = load_registered(found)
    if not _inside(getattr(loaded, "__file__", None), folders):
        raise InputError(
            f"module {top!r} ({spec}) is already imported from "
            f"{getattr(loaded, '__file__', None) or 'the interpreter'}, outside the allowed "
            "folders; user code must come from a folder you named: rename your module"
        )
    mod = importlib.import_module(module)  # submodules come from the package's own folder
    if not _inside(getattr(mod, "__file__", None), folders):
        raise InputError(f"module {module!r} ({spec}) is outside the allowed folders")
    return mod
