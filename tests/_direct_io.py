"""Whether a folder's file system takes direct writes: probed with the system call itself,
independently of ga_rotors.files (a test of the direct path skips where there is none)."""

from __future__ import annotations

import os


def direct_writes_work_in(folder) -> bool:
    """True where a file in ``folder`` opens with ``O_DIRECT`` and takes an aligned page."""
    import mmap

    flag = getattr(os, "O_DIRECT", 0)
    if not flag:
        return False
    probe = os.path.join(folder, ".direct-probe")
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | flag, 0o666)
    except OSError:
        return False
    try:
        os.write(fd, mmap.mmap(-1, 4096))
        return True
    except OSError:
        return False
    finally:
        os.close(fd)
        os.unlink(probe)


#: The ways a file can be written (or read): direct; no O_DIRECT on the system; the file
#: system refusing it at the open (tmpfs) or at the first write (or read).
PATHS = ["direct", "no O_DIRECT", "open refused", "write refused"]


def arrange(how: str, folder, monkeypatch) -> list:
    """Make ga_rotors.files write files in ``folder`` the way ``how`` (one of
    :data:`PATHS`) says (skipping the test where "direct" cannot happen); return a list
    that records, per open, whether O_DIRECT was asked."""
    import errno
    import fcntl

    import pytest

    from ga_rotors import files

    if how == "direct" and not direct_writes_work_in(folder):
        pytest.skip("no direct writes on this file system")
    real_open, real_write_all, real_read = os.open, files._write_all, files._read_into
    opened = []
    flag = getattr(os, "O_DIRECT", 0)

    def spied_open(path, flags, *mode, **where):  # where: dir_fd (shutil.rmtree's)
        opened.append(bool(flags & flag))
        if flags & flag and how == "open refused":
            raise OSError(errno.EINVAL, "Invalid argument")
        return real_open(path, flags, *mode, **where)

    def refusing_write_all(fd, data):
        if fcntl.fcntl(fd, fcntl.F_GETFL) & flag:
            raise OSError(errno.EINVAL, "Invalid argument")
        real_write_all(fd, data)

    def refusing_read(fd, buffer):
        if fcntl.fcntl(fd, fcntl.F_GETFL) & flag:
            raise OSError(errno.EINVAL, "Invalid argument")
        return real_read(fd, buffer)

    monkeypatch.setattr(files.os, "open", spied_open)
    if how == "no O_DIRECT":
        monkeypatch.setattr(files, "_O_DIRECT", 0)
    if how == "write refused":
        monkeypatch.setattr(files, "_write_all", refusing_write_all)
        monkeypatch.setattr(files, "_read_into", refusing_read)
    return opened
