"""Files written atomically, and sets of files written all or nothing.

One file goes through a temporary file in the target's directory and ``os.replace``
(:func:`atomic_write`), so a failed or interrupted run leaves the previous file (or none),
never a half-written one. A command's set of outputs goes through :func:`output_set` (or
:func:`write_together`): every file is written into a staging folder first and moved in
only when all of them exist, so ``--out`` holds the complete new set or the previous one.

Faults, and what each leaves:

* an error, Ctrl-C or SIGTERM while writing: the staging folder is removed, ``--out`` is
  untouched (the command line turns SIGTERM into an exception so clean-up runs);
* SIGKILL: the staging folder stays; the next command writing the same ``--out`` removes
  it (or, if every file had been written and the moves had begun, finishes moving them
  in), so no debris lasts and no half set stays;
* a power cut or a crash of the operating system: the same for the files' names, but
  their contents are not forced to disk (an ``fsync`` of a long run's CSV, hundreds of
  megabytes, would cost more than the run), so a file written in the seconds before the
  cut may come back short or empty, as with any unsynced write. On ext4 with its default
  ``auto_da_alloc``, a file renamed over the previous run's has its data written before
  the rename is committed, which covers re-running into the same ``--out``;
* two commands writing one ``--out``: serialised by a lock on the folder holding it
  (``fcntl.flock``, no lock file left behind); the second waits up to
  :data:`LOCK_TIMEOUT` seconds, then fails with one line;
* a full disk, a file where the folder goes, a folder where an output file goes, a file
  where an output folder goes (an output folder, such as a zarr store, replaces the
  previous run's folder of that name), a dangling symbolic link as ``--out``, a name
  that would leave ``--out`` or is too long: one line (:class:`~ga_rotors.errors.InputError`
  naming the argument), before anything moves.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

from .errors import InputError

__all__ = [
    "LOCK_TIMEOUT",
    "atomic_write",
    "output_set",
    "start_writeback",
    "write_text",
    "write_together",
]

#: Seconds a command waits for another one writing the same ``--out`` before giving up.
LOCK_TIMEOUT = 120.0

#: Longest file name most file systems take, in bytes (NAME_MAX).
NAME_MAX = 255

_COMPLETE = ".complete"  # inside a staging folder: every file is written, moves may begin


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _os_error(argument: str, where, exc: OSError) -> InputError:
    return InputError(f"cannot write {where}: {exc.strerror or exc}", key=argument)


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
        raise InputError(f"{path} is a directory; expected a file name", key="path")
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"directory {parent} does not exist", key="path")
    try:
        fd, tmp = tempfile.mkstemp(dir=parent, prefix=f".{path.name[:200]}.", suffix=".tmp")
    except OSError as exc:  # named by the file asked for, not the temporary one
        raise OSError(exc.errno, exc.strerror, str(path)) from None
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


@functools.cache
def _sync_file_range():
    """Linux's ``sync_file_range`` from the C library, or None (another system; no libc)."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        import ctypes

        call = ctypes.CDLL(None, use_errno=True).sync_file_range
    except (OSError, AttributeError):
        return None
    call.argtypes = (ctypes.c_int, ctypes.c_int64, ctypes.c_int64, ctypes.c_uint)
    call.restype = ctypes.c_int
    return call


_SYNC_FILE_RANGE_WRITE = 2  # <fcntl.h>: start writing dirty pages, do not wait for them


def start_writeback(path, start: int = 0, length: int = 0) -> bool:
    """Ask the system to start writing ``length`` bytes of a finished file's data from
    ``start`` (0: to the end) to disk now, without waiting for them to be written; return
    whether it was asked (Linux only: elsewhere, or if the call fails, nothing is done and
    nothing is said).

    This promises nothing about a power cut (it is not ``fsync``); it moves work earlier.
    ext4 (``auto_da_alloc``) starts this writeback itself when a file is renamed over an
    existing one, and the rename waits while it does: 0.24 s for a 577 MB CSV moved over
    the previous run's. Started on another thread while the run draws its figure, it is
    done before the moves. The call itself can wait while the disk's queue is full, so a
    caller with a deadline asks a slice at a time.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "data.csv"
    >>> _ = path.write_text("t [s],x [m]")
    >>> type(start_writeback(path)), path.read_text()     # True on Linux
    (<class 'bool'>, 't [s],x [m]')
    """
    call = _sync_file_range()
    if call is None:
        return False
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return False
    try:
        return call(fd, start, length, _SYNC_FILE_RANGE_WRITE) == 0
    finally:
        os.close(fd)


def _check_name(name: str, argument: str) -> None:
    """A file name from a scene or a plan: one plain path component, short enough."""
    if (
        not isinstance(name, str)
        or name in ("", ".", "..")
        or "/" in name
        or "\\" in name
        or "\0" in name
        or name.startswith(".")
    ):
        raise InputError(
            f"{name!r} is not a plain file name; it must stay in {argument}",
            key=argument,
        )
    if len(name.encode("utf-8", "surrogateescape")) > NAME_MAX:
        raise InputError(
            f"file name {name[:40]!r}... is {len(name.encode())} bytes long; "
            f"at most {NAME_MAX} (shorten the scene's name)",
            key=argument,
        )


def _staging_prefix(out: Path) -> str:
    # A fixed-length prefix: long --out names never overflow NAME_MAX here.
    tag = hashlib.sha256(os.fsencode(out.name)).hexdigest()[:12]
    return f".ga_rotors-staging-{tag}-"


@contextlib.contextmanager
def _locked(folder: Path, argument: str) -> Iterator[None]:
    """Hold an exclusive lock on ``folder`` itself (no lock file to leave behind)."""
    try:
        import fcntl
    except ImportError:  # not POSIX: no serialisation, the rest still holds
        yield
        return
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError as exc:
        raise _os_error(argument, folder, exc) from None
    try:
        deadline = time.monotonic() + LOCK_TIMEOUT
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise InputError(
                        f"another ga-rotors process has been writing into {folder} "
                        f"for {LOCK_TIMEOUT:g} s; wait for it to finish, or choose another "
                        f"{argument}",
                        key=argument,
                    ) from None
                time.sleep(0.05)
        yield
    finally:
        os.close(fd)  # releases the lock


def _finish_moves(staging: Path, out: Path) -> None:
    for f in sorted(staging.iterdir()):
        if f.name != _COMPLETE:
            target = out / f.name
            if f.is_dir() and target.is_dir() and not target.is_symlink():
                # a store (a folder) replaces the previous run's: removed, then renamed in;
                # interrupted in between, the next run's recovery finishes the moves
                shutil.rmtree(target)
            os.replace(f, target)
    (staging / _COMPLETE).unlink(missing_ok=True)
    staging.rmdir()


def _recover(out: Path) -> None:
    """Deal with the staging folders of killed runs into ``out`` (called under the lock,
    so none belongs to a live process): roll forward a complete set whose moves had begun,
    remove anything else."""
    prefix = _staging_prefix(out)
    places = [out.parent] + ([out] if out.is_dir() else [])
    for place in places:
        for staging in place.glob(prefix + "*"):
            if place == out and (staging / _COMPLETE).exists():
                try:
                    _finish_moves(staging, out)
                    continue
                except OSError:
                    pass
            shutil.rmtree(staging, ignore_errors=True)


def _remove(staging: Path) -> None:
    """Remove a staging folder a forked writer may still be adding to (the paper's figure
    workers after the parent was interrupted): once it is gone they cannot recreate it."""
    for _ in range(50):
        shutil.rmtree(staging, ignore_errors=True)
        if not os.path.lexists(staging):
            return
        time.sleep(0.02)


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """SIGINT/SIGTERM arriving while the files move in are delivered after the last move."""
    if threading.current_thread() is not threading.main_thread() or not hasattr(
        signal, "pthread_sigmask"
    ):
        yield
        return
    held = {signal.SIGINT, signal.SIGTERM}
    old = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


@contextlib.contextmanager
def output_set(out_dir, argument: str = "out_dir") -> Iterator[Path]:
    """A staging folder whose files become ``out_dir``'s together, or not at all.

    Write every file of the set into the yielded folder (any writer, forked processes
    too, by plain file names); when the block ends without an exception they are moved
    into ``out_dir`` (created if missing: a new folder is renamed into place whole), and
    files of ``out_dir`` not in the set are left alone. An exception removes the staging
    folder and leaves ``out_dir`` as it was. See the module's notes for faults.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "run"
    >>> with output_set(out) as stage:
    ...     _ = (stage / "a.txt").write_text("a")
    ...     (out / "a.txt").exists()
    False
    >>> (out / "a.txt").read_text()
    'a'
    >>> with output_set(out) as stage:
    ...     _ = (stage / "a.txt").write_text("new")
    ...     raise RuntimeError("the run failed")
    Traceback (most recent call last):
    ...
    RuntimeError: the run failed
    >>> (out / "a.txt").read_text(), sorted(p.name for p in out.parent.iterdir())
    ('a', ['run'])
    """
    out = Path(out_dir)
    try:
        if os.path.islink(out) and not out.exists():
            raise InputError(
                f"{out} is a symbolic link to {os.readlink(out)}, which does not exist",
                key=argument,
            )
        if out.exists() and not out.is_dir():
            raise InputError(f"{out} exists and is not a directory", key=argument)
    except OSError as exc:  # a name too long, a loop of links, a folder we may not read
        raise _os_error(argument, out, exc) from None
    parent = out.parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise _os_error(argument, parent, exc) from None
    with _locked(parent, argument):
        _recover(out)
        exists = out.is_dir()
        try:
            staging = Path(
                tempfile.mkdtemp(dir=out if exists else parent, prefix=_staging_prefix(out))
            )
        except OSError as exc:
            raise _os_error(argument, out if exists else parent, exc) from None
        try:
            try:
                yield staging
                names = sorted(f.name for f in staging.iterdir())
                for name in names:
                    _check_name(name, argument)
                    target, folder = out / name, (staging / name).is_dir()
                    if exists and target.is_dir() and not target.is_symlink() and not folder:
                        raise InputError(
                            f"{target} is a folder; the output file {name} "
                            "goes there (nothing was replaced)",
                            key=argument,
                        )
                    if exists and folder and os.path.lexists(target) and not target.is_dir():
                        raise InputError(
                            f"{target} is not a folder; the output folder {name} (a store) "
                            "goes there (nothing was replaced)",
                            key=argument,
                        )
                with _signals_held():
                    if not exists:
                        os.chmod(staging, 0o777 & ~_umask())  # mkdtemp makes 0700
                        os.rename(staging, out)
                    else:
                        fd = os.open(staging / _COMPLETE, os.O_CREAT | os.O_WRONLY, 0o600)
                        os.fsync(fd)
                        os.close(fd)
                        _finish_moves(staging, out)
            except OSError as exc:
                raise _os_error(argument, out, exc) from None
        except BaseException:
            if not (staging / _COMPLETE).exists():
                _remove(staging)
            raise


def write_together(
    out_dir, plan: Sequence[tuple[str, Callable[[Path], object]]], argument: str = "out_dir"
) -> list[Path]:
    """Write several files into ``out_dir`` as one step: all of them, or none.

    Each ``write(path)`` of ``plan`` writes one file into the staging folder of
    :func:`output_set`; names must be plain file names (a name from a scene can never
    leave ``out_dir``, nor exceed :data:`NAME_MAX` bytes).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "run"
    >>> [p.name for p in write_together(out, [("a.txt", lambda p: p.write_text("a"))])]
    ['a.txt']
    >>> write_together(out, [("../escape.txt", lambda p: p.write_text("x"))], "--out")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: --out: '../escape.txt' is not a plain file name; ...
    """
    for name, _ in plan:
        _check_name(name, argument)
    with output_set(out_dir, argument) as stage:
        for name, write in plan:
            write(stage / name)
    return [Path(out_dir) / name for name, _ in plan]
