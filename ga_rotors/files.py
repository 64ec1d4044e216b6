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
  cut may come back short or empty, as with any unsynced write. A file written straight
  to the disk (:class:`DirectWriter`: a streamed run's CSV and NPZ, a sweep's chunks)
  has handed its data to the device before it is renamed, all but its last bytes short
  of a page (the device's own cache may still hold them). On ext4 with its default
  ``auto_da_alloc``, a file renamed over the previous run's has its page-cache data
  written before the rename is committed, which covers re-running into the same
  ``--out``;
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
import errno
import functools
import hashlib
import math
import mmap
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
    "DIRECT_ALIGN",
    "KEPT_STAGING",
    "LOCK_TIMEOUT",
    "DirectWriter",
    "aligned_empty",
    "atomic_write",
    "output_set",
    "read_direct",
    "staging",
    "start_writeback",
    "write_direct",
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
    caller with a deadline asks a slice at a time. A file written straight to the disk
    (:class:`DirectWriter`) has nothing to start.

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


#: Bytes that a direct write's memory address, file offset and length are multiples of
#: (the page size: a multiple of every disk's logical block size Linux allows).
DIRECT_ALIGN = 4096

#: The ``O_DIRECT`` flag where the system has it (Linux), else 0: files are then written
#: through the page cache.
_O_DIRECT = getattr(os, "O_DIRECT", 0)

#: What a file system that does not do direct writes answers (EINVAL: tmpfs and most).
_NO_DIRECT = frozenset({errno.EINVAL, errno.EOPNOTSUPP})

#: Largest page-aligned buffer a thread keeps between calls of :func:`write_direct` (a
#: sweep's chunk file is usually a few MB; a larger file gets a buffer of its own, freed
#: after its write, so a writer thread never holds more than this once it is done).
KEPT_STAGING = 16 << 20

#: Bytes of the page-aligned buffer a :class:`DirectWriter` collects before each write.
DIRECT_BUFFER = 8 << 20

_STAGING = threading.local()


def _aligned_buffer(size: int) -> memoryview:
    """``size`` bytes (a multiple of :data:`DIRECT_ALIGN`) of fresh page-aligned memory."""
    return memoryview(mmap.mmap(-1, size))


def _pages(size: int) -> int:
    """``size`` bytes rounded up to whole pages (:data:`DIRECT_ALIGN`), at least one."""
    return max(DIRECT_ALIGN, -(-int(size) // DIRECT_ALIGN) * DIRECT_ALIGN)


def _open(path, flags: int, direct: bool) -> tuple[int, bool]:
    """(fd, whether it is direct): ``path`` opened with ``O_DIRECT`` if ``direct`` and the
    system and file system allow it, else without, silently."""
    if direct and _O_DIRECT:
        try:
            return os.open(path, flags | _O_DIRECT, 0o666), True
        except OSError as exc:
            if exc.errno not in _NO_DIRECT:
                raise
    return os.open(path, flags, 0o666), False


def staging(size: int):
    """A page-aligned writable buffer of ``size`` bytes (a numpy ``uint8`` array), for
    :func:`write_direct`: the calling thread's own, kept for its next call, unless it is
    larger than :data:`KEPT_STAGING` (then a buffer of its own, freed with it).

    Examples
    --------
    >>> buf = staging(5000)
    >>> buf.size, buf.ctypes.data % DIRECT_ALIGN, buf.flags.writeable
    (5000, 0, True)
    """
    import numpy as np

    pages = _pages(size)
    if pages > KEPT_STAGING:
        return np.frombuffer(_aligned_buffer(pages), np.uint8)[:size]
    buf = getattr(_STAGING, "buffer", None)
    if buf is None or buf.size < size:
        buf = np.frombuffer(_aligned_buffer(pages), np.uint8)
        _STAGING.buffer = buf
    return buf[:size]


def aligned_empty(shape, dtype=float):
    """An uninitialised C-ordered numpy array whose data starts on a page boundary
    (:data:`DIRECT_ALIGN`): :func:`write_direct` and :meth:`DirectWriter.write` send its
    whole pages to the disk as they are, without copying them into an aligned buffer first
    (a sweep's chunk is 9 MB at 100 steps per sample: the copy was 1 ms of CPU a chunk).

    Taken from the ordinary heap (a few bytes more than asked, the start moved to the page
    boundary), not from fresh pages: memory a process frees and asks for again is reused
    without the kernel clearing it anew.

    Examples
    --------
    >>> a = aligned_empty((3, 1000))
    >>> a.shape, a.dtype, a.ctypes.data % DIRECT_ALIGN, a.flags.c_contiguous
    ((3, 1000), dtype('float64'), 0, True)
    """
    import numpy as np

    dtype = np.dtype(dtype)
    shape = tuple(int(n) for n in np.atleast_1d(shape))
    nbytes = dtype.itemsize * math.prod(shape)
    raw = np.empty(nbytes + DIRECT_ALIGN, np.uint8)
    start = -raw.ctypes.data % DIRECT_ALIGN
    return raw[start : start + nbytes].view(dtype).reshape(shape)


def _page_aligned(view: memoryview) -> bool:
    """Whether the bytes of ``view`` start on a page boundary."""
    import numpy as np

    return np.frombuffer(view, np.uint8).__array_interface__["data"][0] % DIRECT_ALIGN == 0


def _bytes(data) -> memoryview:
    """The bytes of a C-contiguous buffer, as a flat memoryview."""
    view = memoryview(data)
    if view.format in ("B", "b", "c") and view.ndim == 1:
        return view.cast("B")
    if not view.c_contiguous:
        raise ValueError("expected a C-contiguous buffer")
    try:
        return view.cast("B")
    except TypeError:  # a format memoryview cannot cast (big-endian, structured): numpy can
        import numpy as np

        return memoryview(np.frombuffer(view, np.uint8))


def _write_all(fd: int, data) -> None:
    view = _bytes(data)
    while view:
        view = view[os.write(fd, view) :]


def _clear_direct(fd: int) -> None:
    import fcntl  # Linux, as O_DIRECT

    fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) & ~_O_DIRECT)


class DirectWriter:
    """A file written in order, straight to the disk (``O_DIRECT``) where the system and
    the file system allow it, not through the page cache.

    :meth:`write` copies the bytes it is given into a page-aligned buffer of
    ``buffer_size`` bytes (one per file, reused, freed at :meth:`close`); each time the
    buffer is full it is written whole, from an offset that is a multiple of
    :data:`DIRECT_ALIGN`. Bytes that are page-aligned in memory already
    (:func:`aligned_empty`), given while the buffer is empty, have their whole pages
    written from where they are. :meth:`close` writes what is left: its whole pages direct, the
    last bytes short of a page through the page cache. Through the page cache a write
    costs the kernel's copy and, the dearest part, allocating the cache's pages when they
    have not been used in a while: 1.5 s of CPU for 600 MB on this machine the first time,
    against 0.1 s direct (the copy into the buffer; the rest of its time is spent waiting
    on the disk, not computing).

    Where the system has no ``O_DIRECT`` (not Linux), or the file system refuses it at
    the open or at a write (EINVAL or EOPNOTSUPP: tmpfs, some network file systems), the
    same bytes are written through the page cache, a buffer at a time, silently.
    :attr:`direct` says which it was (True: no direct write has been refused; a file
    shorter than a page never has one to refuse). Use it as a context manager, or call :meth:`close`
    (after an error, :meth:`abort`: the file is left short; its caller removes it).

    Parameters
    ----------
    path : str or path
        Created, or truncated if it exists (unless ``at`` is given).
    buffer_size : int
        Bytes collected before each write (rounded up to a multiple of
        :data:`DIRECT_ALIGN`).
    direct : bool
        False: write through the page cache from the start.
    buffer : writable buffer, optional
        Page-aligned memory to collect in instead of a buffer of its own (its length a
        multiple of :data:`DIRECT_ALIGN`; not freed at :meth:`close`).
    at : int, optional
        Write from this byte offset of the file (created if absent) and leave the rest of
        it as it is, instead of replacing it: several writers fill one file, each its own
        range (ranges must not overlap). Direct only from an offset that is a multiple of
        :data:`DIRECT_ALIGN`, and then only the range's whole pages: a page that two
        ranges share always goes through the page cache.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rows.csv"
    >>> rows = [b"%d,%d\\n" % (i, i * i) for i in range(1000)]
    >>> with DirectWriter(path, buffer_size=4096) as out:  # two whole pages, then the rest
    ...     for row in rows:
    ...         _ = out.write(row)
    >>> path.read_bytes() == b"".join(rows), path.stat().st_size
    (True, 10427)
    """

    def __init__(
        self, path, buffer_size: int = DIRECT_BUFFER, *, direct: bool = True, buffer=None, at=None
    ):
        self.path = Path(path)
        if at is None:
            self._fd, self.direct = _open(self.path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, direct)
        else:
            direct = direct and at % DIRECT_ALIGN == 0
            self._fd, self.direct = _open(self.path, os.O_WRONLY | os.O_CREAT, direct)
            os.lseek(self._fd, at, os.SEEK_SET)
        # the caller's buffer (write_direct's, kept by its thread) is not released here
        self._own = buffer is None
        if self._own:
            self._buffer = _aligned_buffer(_pages(buffer_size))
        else:
            self._buffer = memoryview(buffer).cast("B")
        self._used = 0

    def write(self, data) -> int:
        """Append the bytes of ``data`` (any buffer); return their number."""
        view = _bytes(data)
        n = len(view)
        if self.direct and not self._used and n >= DIRECT_ALIGN and _page_aligned(view):
            # page-aligned memory (aligned_empty's) at a page-aligned offset of the file:
            # its whole pages go out from where they are, no copy into the buffer
            whole = n - n % DIRECT_ALIGN
            self._send(view[:whole])
            view = view[whole:]
        buffer, size = self._buffer, len(self._buffer)
        while view:
            if not self.direct and not self._used and len(view) >= size:
                _write_all(self._fd, view)  # through the page cache: no need to collect
                break
            take = min(size - self._used, len(view))
            buffer[self._used : self._used + take] = view[:take]
            self._used += take
            view = view[take:]
            if self._used == size:
                self._flush(size)
        return n

    def reserve(self, size: int):
        """Room for the next ``size`` bytes inside the buffer, to be filled in place (no
        copy): a writable numpy ``uint8`` array of ``size`` bytes, or None when ``size``
        is more than the buffer can promise (its size less a page; then :meth:`write`
        the bytes). Put the
        bytes at its start, then :meth:`commit` their number, before any other call.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "x.csv"
        >>> with DirectWriter(path, buffer_size=8192) as out:
        ...     room = out.reserve(10)
        ...     room[:3] = list(b"1,2")
        ...     out.commit(3)
        ...     out.reserve(8192) is None
        True
        >>> path.read_bytes()
        b'1,2'
        """
        import numpy as np

        size_all = len(self._buffer)
        if size > size_all - DIRECT_ALIGN:
            return None
        if size_all - self._used < size:  # out with what can go (whole pages if direct)
            self._flush_head(self._used if not self.direct else None)
        return np.frombuffer(self._buffer, np.uint8)[self._used : self._used + size]

    def commit(self, n: int) -> None:
        """Append the first ``n`` bytes put into the room :meth:`reserve` gave."""
        self._used += n
        if self._used == len(self._buffer):
            self._flush(self._used)

    def _flush_head(self, head: int | None = None) -> None:
        """Write the buffer's first ``head`` bytes (None: its whole pages) and move the rest,
        under a page, to its front."""
        used = self._used
        if head is None:
            head = used - used % DIRECT_ALIGN
        if head:
            self._flush(head)
            self._buffer[: used - head] = self._buffer[head:used]
            self._used = used - head

    def _flush(self, length: int) -> None:
        """Write the buffer's first ``length`` bytes (whole pages while direct)."""
        self._send(self._buffer[:length])
        self._used = 0

    def _send(self, data) -> None:
        """Append ``data`` to the file (page-aligned memory, whole pages, while direct)."""
        if self.direct:
            start = os.lseek(self._fd, 0, os.SEEK_CUR)
            try:
                _write_all(self._fd, data)
                return
            except OSError as exc:
                if exc.errno not in _NO_DIRECT:
                    raise
                # refused at the write (some file systems): the rest through the page
                # cache, from wherever the direct writes stopped
                self.direct = False
                _clear_direct(self._fd)
                data = data[os.lseek(self._fd, 0, os.SEEK_CUR) - start :]
        _write_all(self._fd, data)

    def close(self) -> None:
        """Write what is left and close the file (its last bytes short of a page through
        the page cache)."""
        if self._fd < 0:
            return
        try:
            if self.direct:
                self._flush_head()
            if self._used:
                if self.direct:
                    _clear_direct(self._fd)
                _write_all(self._fd, self._buffer[: self._used])
                self._used = 0
        finally:
            self.abort()

    def abort(self) -> None:
        """Close the file without writing what is left (after an error)."""
        if self._fd >= 0:
            os.close(self._fd)
            self._fd = -1
        if self._own:
            self._buffer.release()

    def __enter__(self) -> DirectWriter:
        return self

    def __exit__(self, kind, exc, tb) -> None:
        if kind is None:
            self.close()
        else:
            self.abort()


def read_direct(path, buffer_size: int = DIRECT_BUFFER) -> Iterator[memoryview]:
    """The bytes of the file ``path`` in order, a buffer of ``buffer_size`` bytes at a
    time, read straight from the disk (``O_DIRECT``) where the system and the file system
    allow it, else through the page cache (silently, as :class:`DirectWriter`).

    For a file read once, such as one a :class:`DirectWriter` wrote: through the page
    cache each page read is a page of memory the kernel must find first (as for a write;
    on this machine that cost up to 2 ms of CPU a megabyte). Each block is a view of one
    page-aligned buffer, valid until the next block is asked for.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rows"
    >>> _ = path.write_bytes(bytes(range(256)) * 40)
    >>> [len(block) for block in read_direct(path, 4096)]
    [4096, 4096, 2048]
    >>> b"".join(read_direct(path)) == path.read_bytes()
    True
    """
    fd, direct = _open(path, os.O_RDONLY, True)
    buffer = _aligned_buffer(_pages(buffer_size))
    try:
        while True:
            try:
                n = _read_into(fd, buffer)
            except OSError as exc:
                if not direct or exc.errno not in _NO_DIRECT:
                    raise
                direct = False  # refused at the read: the rest through the page cache
                _clear_direct(fd)
                continue
            if not n:
                return
            yield buffer[:n]
    finally:
        os.close(fd)
        buffer.release()


def _read_into(fd: int, buffer) -> int:
    return os.readv(fd, [buffer])


def write_direct(path, data, at: int | None = None) -> None:
    """Write the bytes of ``data`` (a C-contiguous array or any buffer) as the file
    ``path``, replacing it, straight to the disk where the system allows it; or, given
    ``at``, into the file from that byte offset on, the rest of it left as it is (see
    :class:`DirectWriter`).

    The file's whole pages are written with ``O_DIRECT``, from a page-aligned copy (this
    thread's :func:`staging` buffer) unless ``data`` is page-aligned already
    (:func:`aligned_empty`: 0.12 ms of CPU for 4 MB on this machine, against 0.55 ms
    with the copy), the end past the last whole page through the page cache; a file
    shorter than a page, a system without ``O_DIRECT`` or a file system that refuses it
    gets the plain write (see :class:`DirectWriter`, which this is). A sweep's chunk
    through the page cache cost 1-5 ms of CPU a megabyte on this machine, against about
    0.1 ms direct.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "0.0"
    >>> write_direct(path, np.arange(1000.0))
    >>> np.fromfile(path).sum(), path.stat().st_size
    (np.float64(499500.0), 8000)
    >>> write_direct(path, np.zeros(10), at=8)  # doubles 1 to 10
    >>> np.fromfile(path).sum(), path.stat().st_size
    (np.float64(499445.0), 8000)
    """
    raw = _bytes(data)
    head = len(raw) - len(raw) % DIRECT_ALIGN if _O_DIRECT else 0
    # exactly the whole pages: one direct write; none for page-aligned memory
    # (aligned_empty's), whose whole pages are written from where they are
    copied = head if head and not _page_aligned(raw) else 0
    buffer = staging(copied or DIRECT_ALIGN)
    with DirectWriter(path, direct=head > 0, buffer=buffer, at=at) as out:
        out.write(raw)


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
