"""Files written atomically, and sets of files written all or nothing.

One file goes through a temporary file in the target's directory and ``os.replace``
(:func:`atomic_write`), so a failed or interrupted run leaves the previous file (or none),
never a half-written one. A command's set of outputs goes through :func:`output_set` (or
:func:`write_together`; :func:`output_file` for one file or folder such as a zarr store):
every file is written into a staging folder first and moved in only when all of them
exist, so ``--out`` holds the complete new set or the previous one. Files are written
with ordinary buffered writes; this module adds only where they go and when they move.

Faults, and what each leaves:

* an error, Ctrl-C or SIGTERM while writing: the staging folder is removed, ``--out`` is
  untouched (the command line turns SIGTERM into an exception so clean-up runs);
* SIGKILL: the staging folder stays; the next command writing the same ``--out`` removes
  it (or, if every file had been written and the moves had begun, finishes moving them
  in), so no debris lasts and no half set stays;
* a power cut or a crash of the operating system: the same for the files' names, but
  their contents are not forced to disk (an ``fsync`` of a long run's data, hundreds of
  megabytes, would cost more than the run), so a file written in the seconds before the
  cut may come back short or empty, as with any unsynced write. On ext4 with its default
  ``auto_da_alloc``, a file renamed over the previous run's has its data written before
  the rename is committed, which covers re-running into the same ``--out``;
* two commands writing one ``--out``: serialised by a lock on the folder holding it
  (``fcntl.flock``, no lock file left behind); the second waits up to
  :data:`LOCK_TIMEOUT` seconds, then fails with one line;
* a full disk, a file where the folder goes, a folder where an output file goes, a file
  where an output folder goes (an output folder, such as a zarr store, replaces the
  previous run's folder of that name), a dangling symbolic link or an empty name as
  ``--out``, a name that would leave ``--out`` or is too long: one line
  (:class:`~ga_rotors.errors.InputError` naming the argument), before anything moves.
  Paths in these lines are shown by :func:`shown_path`: control characters escaped,
  a very long path cut.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import signal
import tempfile
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

from .errors import InputError, echoed

__all__ = [
    "LOCK_TIMEOUT",
    "NAME_MAX",
    "atomic_write",
    "checked_path",
    "output_file",
    "output_set",
    "shown_path",
    "write_text",
    "write_together",
]

#: Seconds a command waits for another one writing the same ``--out`` before giving up.
LOCK_TIMEOUT = 120.0

#: Longest file name most file systems take, in bytes (NAME_MAX).
NAME_MAX = 255

#: Characters of a path an error line shows at most (its start and its end).
SHOWN_CHARS = 80

_COMPLETE = ".complete"  # inside a staging folder: every file is written, moves may begin
_STAGING = ".ga_rotors-staging-"  # what every staging folder's name starts with


def shown_path(path) -> str:
    """``path`` as an error line shows it (:func:`ga_rotors.errors.echoed`): control
    characters (and undecodable bytes) escaped, so nothing echoed can move the cursor or
    retitle a terminal, and a path of more than :data:`SHOWN_CHARS` characters cut in its
    middle, its length said.

    Examples
    --------
    >>> shown_path("results/top")
    'results/top'
    >>> print(shown_path("out\\x1b]0;owned\\x07/top\\n"))
    out\\x1b]0;owned\\x07/top\\n
    >>> shown = shown_path("/tmp/" + "a" * 5000)
    >>> len(shown), shown[:8], shown[-20:]
    (97, '/tmp/aaa', 'aa (5005 characters)')
    """
    return echoed(os.fsdecode(path), SHOWN_CHARS)


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _os_error(argument: str, where, exc: OSError) -> InputError:
    return InputError(f"cannot write {shown_path(where)}: {exc.strerror or exc}", key=argument)


def checked_path(path, argument: str) -> Path:
    """``path`` as a Path, refusing an empty name (which ``Path`` would read as the
    current folder) in one line naming ``argument``.

    Examples
    --------
    >>> checked_path("results/top", "--out")
    PosixPath('results/top')
    >>> checked_path("", "--out")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: --out: expected a file or folder name, got an empty one
    """
    if not os.fspath(path):
        raise InputError("expected a file or folder name, got an empty one", key=argument)
    return Path(path)


def _new_file(path, argument: str) -> Path:
    """``path`` as the name of a file to write: not empty, in a folder that exists."""
    path = checked_path(path, argument)
    if not path.parent.is_dir():
        raise InputError(f"directory {shown_path(path.parent)} does not exist", key=argument)
    return path


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
    path = _new_file(path, "path")
    if path.is_dir():
        raise InputError(f"{shown_path(path)} is a directory; expected a file name", key="path")
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name[:200]}.", suffix=".tmp")
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


def _check_name(name: str, argument: str) -> None:
    """A file name from a scene, a plan or a path: one plain path component, short enough,
    not one of the names staging uses."""
    if (
        not isinstance(name, str)
        or name in ("", ".", "..", _COMPLETE)
        or any(c in name for c in "/\\\0")
        or name.startswith(_STAGING)
    ):
        raise InputError(
            f"{name!r} is not a plain file name; it must stay in {argument}",
            key=argument,
        )
    if len(name.encode("utf-8", "surrogateescape")) > NAME_MAX:
        raise InputError(
            f"file name {name[:40]!r}... is {len(name.encode())} bytes long; at most {NAME_MAX}",
            key=argument,
        )


def _staging_prefix(out: Path) -> str:
    # A fixed-length prefix: long --out names never overflow NAME_MAX here.
    tag = hashlib.sha256(os.fsencode(out.name)).hexdigest()[:12]
    return f"{_STAGING}{tag}-"


# The folders this thread holds locked: a set written inside another's staging folder (a
# format's writer calling results.write or write_csv there) takes the lock it already has.
_HELD = threading.local()


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
    info = os.fstat(fd)
    key, held = (info.st_dev, info.st_ino), _HELD.__dict__.setdefault("folders", set())
    if key in held:
        os.close(fd)
        yield
        return
    try:
        deadline = time.monotonic() + LOCK_TIMEOUT
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise InputError(
                        f"another ga-rotors process has been writing into {shown_path(folder)} "
                        f"for {LOCK_TIMEOUT:g} s; wait for it to finish, or choose another "
                        f"{argument}",
                        key=argument,
                    ) from None
                time.sleep(0.05)
        held.add(key)
        yield
    finally:
        held.discard(key)
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

    Write every file of the set into the yielded folder (any writer, other processes too,
    by plain file names); when the block ends without an exception they are moved into
    ``out_dir`` (created if missing: a new folder is renamed into place whole), and files
    of ``out_dir`` not in the set are left alone. See the module's notes for faults.

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
    out = checked_path(out_dir, argument)
    try:
        if os.path.islink(out) and not out.exists():
            raise InputError(
                f"{shown_path(out)} is a symbolic link to {shown_path(os.readlink(out))}, "
                "which does not exist",
                key=argument,
            )
        if out.exists() and not out.is_dir():
            raise InputError(f"{shown_path(out)} exists and is not a directory", key=argument)
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
                for staged in sorted(staging.iterdir()):
                    _check_name(staged.name, argument)
                    target, folder = out / staged.name, staged.is_dir()
                    # a store (a folder) replaces a folder, a file replaces a file
                    is_folder = target.is_dir() and not target.is_symlink()
                    if exists and os.path.lexists(target) and folder != is_folder:
                        kind = ("a folder", "file") if is_folder else ("not a folder", "folder")
                        raise InputError(
                            f"{shown_path(target)} is {kind[0]}; the output {kind[1]} "
                            f"{staged.name} goes there (nothing was replaced)",
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
        except BaseException:  # nothing writes there any more: a pool's drawing processes,
            # writing into a staging folder, are waited for before it ends (paper.reproduce)
            if not (staging / _COMPLETE).exists():
                shutil.rmtree(staging, ignore_errors=True)
            raise


@contextlib.contextmanager
def output_file(path, argument: str = "path") -> Iterator[Path]:
    """A staging path whose file, or folder (a zarr store), replaces ``path`` when the
    block ends without an exception: :func:`output_set` of its folder, which must exist.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.txt"
    >>> with output_file(path) as staged:
    ...     _ = staged.write_text("new")
    ...     path.exists()
    False
    >>> path.read_text()
    'new'
    >>> with output_file(path.parent / "missing" / "run.txt", "--out"):
    ...     pass
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: --out: directory ...missing does not exist
    """
    path = _new_file(path, argument)
    _check_name(path.name, argument)
    with output_set(path.parent, argument) as stage:
        yield stage / path.name


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
