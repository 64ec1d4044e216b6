"""Folders private to their owner, for files the package later runs (the compiled-code cache).

Whoever can write into the cache can make ``ga-rotors`` import their module. A cache folder
is therefore created with mode 0700, and one is used only when nobody but the user running
the process can change what its path leads to. The path is resolved once (every symbolic
link followed, :func:`os.path.realpath`) and from then on only the resolved path is used,
so a link that someone re-points after the check changes nothing. Every component of the
resolved path is then checked with :func:`os.lstat` (never following a link): the folder
and the one holding it (``levels``) must belong to the user and be writable by nobody
else; every folder above must belong to the user or to root and be writable by nobody
else unless it is sticky (like ``/tmp``: others may add entries there but not rename or
remove the user's). A refusal is one line that says how to get out (take or remove the
folder, or point ``GA_ROTORS_CACHE_DIR`` somewhere else). There is deliberately no
fallback to a predictable name under the shared temporary directory.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from .errors import InputError

__all__ = ["private_directory", "unsafe_reason"]


def _uid() -> int | None:
    return os.geteuid() if hasattr(os, "geteuid") else None


def unsafe_reason(path: Path, own: bool = True) -> str | None:
    """Why the folder ``path`` (not followed if it is a link) may not lead to code we run:
    ``own``, it must be the user's and writable by nobody else; otherwise the user's or
    root's, and writable by others only when sticky. None: it is safe.

    Examples
    --------
    >>> import tempfile
    >>> unsafe_reason(Path(tempfile.mkdtemp())) is None
    True
    >>> unsafe_reason(Path("/"), own=False) is None
    True
    """
    try:
        st = os.lstat(path)
    except OSError as exc:
        return f"cannot be used ({exc.strerror})"
    if stat.S_ISLNK(st.st_mode):
        return "is a symbolic link (it was replaced after its path was resolved)"
    if not stat.S_ISDIR(st.st_mode):
        return "is not a folder"
    uid = _uid()
    if uid is not None and st.st_uid != uid and (own or st.st_uid != 0):
        return f"belongs to user id {st.st_uid}, not to you ({uid})"
    if st.st_mode & 0o022 and (own or not st.st_mode & stat.S_ISVTX):
        return f"can be written by others (mode {stat.S_IMODE(st.st_mode):o})"
    return None


def private_directory(path, levels: int = 2, way_out: str = "") -> Path | None:
    """``path`` resolved, created with mode 0700 where missing, checked to be private;
    the resolved path, or None if impossible.

    ``levels`` is how many folders, from the resolved path upwards, must be the user's own
    (the folder and the one holding it: whoever can rename the parent can swap the
    folder); the folders above may be root's, or sticky. A folder that exists but is not
    safe raises :class:`InputError` (one line, with ``way_out``); one that cannot be
    created (a read-only home) gives None. Use the path returned, never ``path`` again:
    a link on the way is followed once, here.

    Examples
    --------
    >>> import os, stat, tempfile
    >>> from pathlib import Path
    >>> base = Path(tempfile.mkdtemp())
    >>> made = private_directory(base / "cache" / "generated")
    >>> oct(stat.S_IMODE(os.stat(made).st_mode)), oct(stat.S_IMODE(os.stat(made.parent).st_mode))
    ('0o700', '0o700')
    >>> os.symlink(base / "cache", base / "link")
    >>> private_directory(base / "link" / "generated") == made   # the link's target, resolved
    True
    >>> os.chmod(made, 0o777)
    >>> private_directory(made, way_out="chmod 700 it")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: .../generated can be written by others (mode 777): ...
    """
    try:
        real = Path(os.path.realpath(Path(path).expanduser()))
    except (OSError, ValueError):  # a loop of links, a NUL in the name
        return None
    for folder in [p for p in [real, *real.parents] if not os.path.lexists(p)][::-1]:
        try:  # each level 0700 (os.makedirs gives parents the umask's mode)
            os.mkdir(folder, 0o700)
        except FileExistsError:
            pass  # made meanwhile (by another process, or a link): checked below
        except OSError:
            return None
    chain = [real, *real.parents]
    for level, folder in enumerate(chain):
        reason = unsafe_reason(folder, own=level < levels)
        if reason is not None:
            raise InputError(
                f"{folder} {reason}: code cached there would run as you; {way_out}".rstrip("; ")
            )
    if not os.access(real, os.W_OK | os.X_OK):
        return None
    return real
