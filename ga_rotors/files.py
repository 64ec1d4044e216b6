"""Files written atomically: through a temporary file in the target's directory and
``os.replace``, so a failed or interrupted run leaves the previous file (or none), never a
half-written one. Every output of the package (CSV, NPZ, PNG, reports, generated code) goes
through :func:`atomic_write`.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable, Sequence
from pathlib import Path

from .errors import InputError

__all__ = ["atomic_write", "write_text", "write_together"]


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def atomic_write(path, write) -> Path:
    """Call ``write(file_object)`` on a temporary file, then move it onto ``path``.

    A failure anywhere leaves ``path`` as it was (absent, or the previous version).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> atomic_write(d / "x.txt", lambda f: f.write(b"hello")).read_bytes()
    b'hello'
    """
    path = Path(path)
    if path.is_dir():
        raise InputError(f"path: {path} is a directory; expected a file name")
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"path: directory {parent} does not exist")
    fd, tmp = tempfile.mkstemp(dir=parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; give what open() would
        with os.fdopen(fd, "wb") as fh:
            write(fh)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def write_text(path, text: str) -> Path:
    """Write ``text`` as UTF-8 to ``path`` atomically (see :func:`atomic_write`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> write_text(pathlib.Path(tempfile.mkdtemp()) / "a.md", "θ").read_text(encoding="utf-8")
    'θ'
    """
    return atomic_write(path, lambda fh: fh.write(text.encode("utf-8")))


def write_together(
    out_dir, plan: Sequence[tuple[str, Callable[[Path], object]]], argument: str = "out_dir"
) -> list[Path]:
    """Write several files into ``out_dir`` as one step: all of them, or none.

    Each ``write(path)`` of ``plan`` writes one file into a staging directory next to
    ``out_dir``; only when every one has succeeded are they moved in (a new directory is
    renamed into place whole). A failure removes the staging directory and leaves
    ``out_dir`` as it was.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "run"
    >>> [p.name for p in write_together(out, [("a.txt", lambda p: p.write_text("a"))])]
    ['a.txt']
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise InputError(f"{argument}: {out} exists and is not a directory")
    exists = out.is_dir()
    parent = out if exists else out.parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(dir=parent, prefix=f".{out.name}.staging-"))
    except OSError as exc:
        raise InputError(f"{argument}: cannot write into {parent}: {exc.strerror}") from None
    try:
        for name, write in plan:
            write(staging / name)
        if exists:
            for name, _ in plan:
                os.replace(staging / name, out / name)
            staging.rmdir()
        else:
            os.chmod(staging, 0o777 & ~_umask())  # mkdtemp makes 0700; give what mkdir would
            os.rename(staging, out)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return [out / name for name, _ in plan]
