"""Folders private to their owner, for files the package later runs (the compiled-code cache).

Whoever can write into the cache can make ``ga-rotors`` import their module. A cache folder
is therefore created with mode 0700, and an existing one is used only when it (and the
folder holding it) belongs to the user running the process and nobody else may write into
it; otherwise the refusal is one line that says how to get out (take or remove the folder,
or point ``GA_ROTORS_CACHE_DIR`` somewhere else). There is deliberately no fallback to a
predictable name under the shared temporary directory.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from .errors import InputError

__all__ = ["private_directory", "unsafe_reason"]


def unsafe_reason(path: Path) -> str | None:
    """Why ``path`` may not hold code we run (None: it is a folder that is ours alone)."""
    try:
        st = os.stat(path)
    except OSError as exc:
        return f"cannot be used ({exc.strerror})"
    if not stat.S_ISDIR(st.st_mode):
        return "is not a folder"
    if hasattr(os, "geteuid") and st.st_uid != os.geteuid():
        return f"belongs to user id {st.st_uid}, not to you ({os.geteuid()})"
    if st.st_mode & 0o022:
        return f"can be written by others (mode {stat.S_IMODE(st.st_mode):o})"
    return None


def private_directory(path, levels: int = 2, way_out: str = "") -> Path | None:
    """``path`` created with mode 0700 if missing, checked to be private; None if impossible.

    ``levels`` is how many folders, from ``path`` upwards, must be the user's own (the
    folder and the one holding it: whoever can rename the parent can swap the folder).
    A folder that exists but is not private raises :class:`InputError` (one line, with
    ``way_out``); one that cannot be created (a read-only home) gives None.

    Examples
    --------
    >>> import os, stat, tempfile
    >>> from pathlib import Path
    >>> base = Path(tempfile.mkdtemp())
    >>> made = private_directory(base / "cache" / "generated")
    >>> oct(stat.S_IMODE(os.stat(made).st_mode)), oct(stat.S_IMODE(os.stat(made.parent).st_mode))
    ('0o700', '0o700')
    >>> os.chmod(made, 0o777)
    >>> private_directory(made, way_out="chmod 700 it")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: .../generated can be written by others (mode 777): ...
    """
    path = Path(path)
    missing = [p for p in [path, *path.parents] if not p.exists()][::-1]
    for folder in missing:  # each level 0700 (os.makedirs gives parents the umask's mode)
        try:
            os.mkdir(folder, 0o700)
        except FileExistsError:
            pass  # made meanwhile by another process: checked below like any existing one
        except OSError:
            return None
    for level, folder in enumerate([path, *path.parents]):
        if level >= levels:
            break
        reason = unsafe_reason(folder)
        if reason is not None:
            raise InputError(
                f"{folder} {reason}: code cached there would run as you; {way_out}".rstrip("; ")
            )
    if not os.access(path, os.W_OK | os.X_OK):
        return None
    return path
