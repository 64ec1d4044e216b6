"""Atomic file writes: a failure leaves the previous file, or nothing, never half a file."""

from __future__ import annotations

import itertools

import pytest
from _direct_io import PATHS

from ga_rotors import files
from ga_rotors.errors import InputError
from ga_rotors.files import atomic_write, write_text, write_together


def test_failed_write_leaves_nothing(tmp_path):
    target = tmp_path / "out.csv"

    def boom(fh):
        fh.write(b"partial")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError):
        atomic_write(target, boom)
    assert list(tmp_path.iterdir()) == []


def test_failed_write_keeps_the_previous_file(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("old")
    with pytest.raises(RuntimeError):
        atomic_write(target, lambda fh: (_ for _ in ()).throw(RuntimeError("x")))
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]


def test_a_directory_or_a_missing_parent_is_refused_by_name(tmp_path):
    with pytest.raises(InputError, match="is a directory"):
        write_text(tmp_path, "x")
    with pytest.raises(InputError, match="does not exist"):
        write_text(tmp_path / "no" / "such.txt", "x")
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------- sets of files


def _plan(**files):
    return [(name, lambda p, t=text: p.write_text(t)) for name, text in files.items()]


def _listing(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_a_failed_set_leaves_the_previous_set_and_no_staging(tmp_path):
    out = tmp_path / "out"
    write_together(out, _plan(**{"a.csv": "old a", "b.png": "old b"}))

    def boom(path):
        path.write_text("partial")
        raise RuntimeError("the figure failed")

    with pytest.raises(RuntimeError):
        write_together(out, [*_plan(**{"a.csv": "new a"}), ("b.png", boom)])
    assert (out / "a.csv").read_text() == "old a" and (out / "b.png").read_text() == "old b"
    assert _listing(tmp_path) == ["out", "out/a.csv", "out/b.png"]


@pytest.mark.parametrize("exists", [False, True], ids=["new out", "existing out"])
def test_staging_debris_of_a_killed_run_is_removed_by_the_next(tmp_path, exists):
    out = tmp_path / "out"
    if exists:
        write_together(out, _plan(**{"a.csv": "old"}))
    # What SIGKILL leaves mid-write: a staging folder with a partial file.
    place = out if exists else tmp_path
    debris = place / (files._staging_prefix(out) + "killed")
    debris.mkdir()
    (debris / "a.csv").write_text("parti")
    write_together(out, _plan(**{"a.csv": "new"}))
    assert _listing(tmp_path) == ["out", "out/a.csv"]
    assert (out / "a.csv").read_text() == "new"


def test_a_complete_set_killed_while_moving_in_is_finished_by_the_next_run(tmp_path):
    out = tmp_path / "out"
    write_together(out, _plan(**{"a.csv": "old a", "b.csv": "old b"}))
    # Killed after a.csv moved in, before b.csv: the staging folder is marked complete.
    staging = out / (files._staging_prefix(out) + "killed")
    staging.mkdir()
    (staging / "b.csv").write_text("new b")
    (staging / ".complete").touch()
    (out / "a.csv").write_text("new a")
    write_together(tmp_path / "other", _plan(**{"x": "x"}))  # another --out: not touched
    assert staging.exists()
    with files.output_set(out):
        pass  # the next run into out (even one writing nothing) finishes the set first
    assert (out / "b.csv").read_text() == "new b" and _listing(out) == ["a.csv", "b.csv"]


def test_a_folder_where_an_output_file_goes_replaces_nothing(tmp_path):
    out = tmp_path / "out"
    write_together(out, _plan(**{"a.csv": "old a"}))
    (out / "b.png").mkdir()
    with pytest.raises(InputError, match=r"--out: .*b\.png is a folder; the output file b\.png"):
        write_together(out, _plan(**{"a.csv": "new a", "b.png": "new b"}), "--out")
    assert (out / "a.csv").read_text() == "old a" and _listing(out) == ["a.csv", "b.png"]


def test_a_file_or_a_dangling_link_as_out_is_one_line(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match=r"--out: .* exists and is not a directory"):
        write_together(tmp_path / "file", _plan(a="a"), "--out")
    (tmp_path / "link").symlink_to(tmp_path / "nowhere")
    with pytest.raises(InputError, match=r"--out: .*link is a symbolic link to .*nowhere"):
        write_together(tmp_path / "link", _plan(a="a"), "--out")
    assert _listing(tmp_path) == ["file", "link"]


@pytest.mark.parametrize(
    "name", ["../up.csv", "/abs.csv", "a/b.csv", "..", ".hidden", "x" * 256 + ".csv"]
)
def test_names_can_never_leave_or_overflow_out(tmp_path, name):
    with pytest.raises(InputError, match="--out: "):
        write_together(tmp_path / "out", _plan(**{name: "x"}), "--out")
    assert _listing(tmp_path) == []


def test_a_long_out_name_is_one_line(tmp_path):
    with pytest.raises(InputError, match=r"--out: cannot write .*: File name too long"):
        write_together(tmp_path / ("o" * 300), _plan(a="a"), "--out")
    assert _listing(tmp_path) == []


def test_a_full_disk_is_one_line_and_leaves_the_previous_set(tmp_path):
    import errno

    out = tmp_path / "out"
    write_together(out, _plan(**{"a.csv": "old"}))

    def full(path):
        raise OSError(errno.ENOSPC, "No space left on device", str(path))

    with pytest.raises(InputError, match=r"--out: cannot write .*: No space left on device"):
        write_together(out, [*_plan(**{"b.csv": "b"}), ("a.csv", full)], "--out")
    assert _listing(tmp_path) == ["out", "out/a.csv"] and (out / "a.csv").read_text() == "old"


def test_concurrent_writers_into_one_out_are_serialised(tmp_path, monkeypatch):
    # Two processes write the same new --out at once: both succeed, one after the other,
    # and the folder holds one complete set (the later one), nothing else.
    import subprocess
    import sys
    import textwrap

    code = textwrap.dedent(
        f"""
        import sys, time
        from ga_rotors.files import write_together
        tag = sys.argv[1]
        def slow(p, tag=tag):
            time.sleep(0.5)
            p.write_text(tag)
        write_together({str(tmp_path / "out")!r}, [("a.csv", slow), ("b.csv", slow)], "--out")
        """
    )
    procs = [
        subprocess.Popen([sys.executable, "-c", code, tag], stderr=subprocess.PIPE, text=True)
        for tag in ("one", "two")
    ]
    for p in procs:
        assert p.wait(timeout=120) == 0, p.stderr.read()
    a, b = ((tmp_path / "out" / n).read_text() for n in ("a.csv", "b.csv"))
    assert a == b and a in ("one", "two")
    assert _listing(tmp_path) == ["out", "out/a.csv", "out/b.csv"]


def test_a_writer_that_waits_too_long_fails_with_one_line(tmp_path, monkeypatch):
    import fcntl
    import os

    monkeypatch.setattr(files, "LOCK_TIMEOUT", 0.2)
    fd = os.open(tmp_path, os.O_RDONLY)
    fcntl.flock(fd, fcntl.LOCK_EX)  # another process writing into tmp_path
    try:
        with pytest.raises(InputError, match="--out: another ga-rotors process"):
            write_together(tmp_path / "out", _plan(a="a"), "--out")
    finally:
        os.close(fd)
    assert _listing(tmp_path) == []


def test_writeback_is_started_on_linux_and_changes_nothing(tmp_path):
    import sys

    path = tmp_path / "data.csv"
    path.write_bytes(b"t [s]\n" + b"0.5\n" * 100_000)
    before = path.read_bytes()
    assert files.start_writeback(path) is sys.platform.startswith("linux")
    assert path.read_bytes() == before
    assert files.start_writeback(tmp_path / "missing.csv") is False  # nothing said either


def test_writeback_elsewhere_or_refused_is_silently_nothing(tmp_path, monkeypatch):
    import warnings

    path = tmp_path / "data.csv"
    path.write_bytes(b"x\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        monkeypatch.setattr(files, "_sync_file_range", lambda: None)  # not Linux
        assert files.start_writeback(path) is False
        monkeypatch.setattr(files, "_sync_file_range", lambda: lambda fd, lo, n, flags: -1)
        assert files.start_writeback(path) is False  # the call failed: nothing raised
    assert path.read_bytes() == b"x\n"


@pytest.mark.parametrize(
    "argv",
    [
        ["prove", "--catalogue", "--only", "jacobi", "--write", "{out}/identities.md"],
        ["view", "spinning_disk", "--duration", "0.01", "--out", "{out}/disk.html"],
    ],
)
def test_a_file_the_system_refuses_is_one_line_naming_it(tmp_path, capsys, monkeypatch, argv):
    # prove --write /proc/x.md and view --out /proc/x.html ended in a FileNotFoundError
    # traceback naming the temporary file; a full disk takes the same path
    import errno
    import tempfile

    from ga_rotors.cli import main

    if argv[0] == "view":
        pytest.importorskip("plotly")

    def refused(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device", "/somewhere/.tmp")

    monkeypatch.setattr(tempfile, "mkstemp", refused)
    argv = [a.format(out=tmp_path) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err == f"ga-rotors: error: {argv[-1]}: No space left on device\n"
    assert list(tmp_path.iterdir()) == []


# Direct writes (O_DIRECT): the same bytes whichever way the file system lets them go.


@pytest.fixture
def how_written(request, tmp_path, monkeypatch):
    """Files in tmp_path written one way (one of PATHS); yields (how, opened): whether
    each open asked for O_DIRECT."""
    from _direct_io import arrange

    return request.param, arrange(request.param, tmp_path, monkeypatch)


def _data(n: int) -> bytes:
    import numpy as np

    return np.random.default_rng(n).integers(0, 256, n, dtype=np.uint8).tobytes()


ALIGN = files.DIRECT_ALIGN
SIZES = [0, 1, ALIGN - 1, ALIGN, ALIGN + 1, 3 * ALIGN, 5 * ALIGN + 17]


@pytest.mark.parametrize("how_written", PATHS, indirect=True)
@pytest.mark.parametrize("size", SIZES)
def test_a_file_written_direct_holds_its_bytes_however_it_went(tmp_path, how_written, size):
    # Whole pages direct, the ragged end through the page cache; an older longer file
    # is replaced; direct is tried only where there is a whole page to write.
    how, opened = how_written
    path = tmp_path / "chunk"
    path.write_bytes(b"\1" * (size + 9000))
    data = _data(size)
    files.write_direct(path, data)
    assert path.read_bytes() == data
    assert any(opened) == (size >= ALIGN and how != "no O_DIRECT")


@pytest.mark.parametrize("how_written", PATHS, indirect=True)
@pytest.mark.parametrize(
    "pieces",
    [
        [1] * 3000,  # many tiny appends across several buffers
        [ALIGN - 1, 1, ALIGN + 1, ALIGN - 1],  # around a page
        [3 * 8192 + 5],  # one append larger than the buffer, ragged
        [2 * 8192],  # exactly the buffer twice
        [0, 8191, 0, 1, 8192, 8193, 3],
        [],
    ],
    ids=["tiny", "around-a-page", "large-single", "two-buffers", "mixed", "empty"],
)
def test_a_streamed_file_is_the_bytes_appended_however_it_went(tmp_path, how_written, pieces):
    how, opened = how_written
    data = _data(sum(pieces))
    path = tmp_path / "stream.csv"
    path.write_bytes(b"\2" * (len(data) + 50_000))  # an older, longer file: truncated
    at = 0
    with files.DirectWriter(path, buffer_size=8192) as out:
        for n in pieces:
            assert out.write(memoryview(data)[at : at + n]) == n
            at += n
    assert path.read_bytes() == data
    assert opened[0] == (how != "no O_DIRECT")  # asked for at the open
    # refused at a write: known only once a whole page was written
    refused = how == "write refused" and len(data) >= ALIGN
    assert out.direct == (how in ("direct", "write refused") and not refused)


@pytest.mark.parametrize("how_written", PATHS, indirect=True)
@pytest.mark.parametrize("size", SIZES)
def test_a_file_read_direct_is_its_bytes_however_it_went(tmp_path, how_written, size):
    # The tail of a file written direct is in the page cache, not yet on the disk: a
    # direct read still sees it (the kernel writes it first).
    how, opened = how_written
    data = _data(size)
    with files.DirectWriter(tmp_path / "rows", buffer_size=8192) as out:
        out.write(data)
    del opened[:]
    blocks = [bytes(block) for block in files.read_direct(tmp_path / "rows", 8192)]
    assert b"".join(blocks) == data
    assert all(len(b) == 8192 for b in blocks[:-1]) and len(blocks) == -(-size // 8192)
    assert opened[0] == (how != "no O_DIRECT")  # asked for at the open


@pytest.mark.parametrize("how_written", PATHS, indirect=True)
def test_bytes_put_in_place_and_appended_make_one_file_however_it_went(tmp_path, how_written):
    # reserve/commit (formatting straight into the buffer) mixed with write, across the
    # buffer's end and page boundaries: the file is every committed and written byte in
    # order; a reservation larger than the buffer can promise is refused.
    import numpy as np

    rng = np.random.default_rng(3)
    expected = bytearray()
    with files.DirectWriter(tmp_path / "x", buffer_size=8192) as out:
        assert out.reserve(8192 - ALIGN + 1) is None
        for k in range(300):
            n = int(rng.integers(0, 3000))
            data = _data(n + k)[:n]
            if k % 3:
                room = out.reserve(n + int(rng.integers(0, 500)))  # more than is used
                room[:n] = np.frombuffer(data, np.uint8)
                out.commit(n)
            else:
                out.write(data)
            expected += data
    assert (tmp_path / "x").read_bytes() == bytes(expected)


def test_a_streamed_file_takes_arrays_and_text_of_any_layout(tmp_path):
    import numpy as np

    a = np.arange(5000.0).reshape(1000, 5)
    big = np.arange(3000, dtype=">i8")  # a format memoryview cannot cast
    with files.DirectWriter(tmp_path / "x", buffer_size=4096) as out:
        out.write(a)
        out.write(b"text")
        out.write(big)
    assert (tmp_path / "x").read_bytes() == a.tobytes() + b"text" + big.tobytes()
    with pytest.raises(ValueError, match="C-contiguous"), files.DirectWriter(tmp_path / "y") as out:
        out.write(a[:, ::2])


def test_a_failed_direct_write_is_raised_and_the_file_closed(tmp_path, monkeypatch):
    import errno

    def full(fd, data):
        raise OSError(errno.ENOSPC, "No space left on device")

    out = files.DirectWriter(tmp_path / "x", buffer_size=4096)
    monkeypatch.setattr(files, "_write_all", full)
    with pytest.raises(OSError, match="No space left"):
        out.write(b"x" * 5000)  # the first full buffer goes out
    out.abort()
    monkeypatch.undo()
    with pytest.raises(OSError, match="No space left"):
        with files.DirectWriter(tmp_path / "y", buffer_size=4096) as out:
            out.write(b"y" * 100)
            monkeypatch.setattr(files, "_write_all", full)
            out.close()  # the tail fails: still closed, once
    out.close()  # nothing left to do


def test_the_buffer_of_direct_writes_is_page_aligned_and_kept_only_when_small(monkeypatch):
    # Kept for the next file up to KEPT_STAGING; a larger file gets a buffer of its own,
    # so a writer thread holds at most KEPT_STAGING once it is done.
    import threading

    import numpy as np

    monkeypatch.setattr(files, "KEPT_STAGING", 8 * ALIGN)
    monkeypatch.setattr(files, "_STAGING", threading.local())
    small = files.staging(3 * ALIGN + 5)
    again = files.staging(2 * ALIGN)
    large = files.staging(9 * ALIGN)
    for buf in (small, again, large):
        assert buf.ctypes.data % ALIGN == 0
    assert small.size == 3 * ALIGN + 5 and large.size == 9 * ALIGN
    assert np.shares_memory(small, again)  # kept and reused
    assert not np.shares_memory(large, files.staging(ALIGN))  # not kept
    assert files._STAGING.buffer.size < 9 * ALIGN


@pytest.mark.parametrize("how_written", PATHS, indirect=True)
@pytest.mark.parametrize("size", [ALIGN, 3 * ALIGN, 5 * ALIGN + 17])
def test_page_aligned_memory_goes_out_from_where_it_is_however_it_went(
    tmp_path, how_written, size, monkeypatch
):
    # aligned_empty's memory: its whole pages are handed to the system as they are (no
    # copy into the buffer) where the file is direct; the file is its bytes every way,
    # alone (write_direct) or after and before other bytes (DirectWriter).
    import numpy as np

    how, _ = how_written
    data = files.aligned_empty(size, np.uint8)
    data[:] = np.frombuffer(_data(size), np.uint8)
    assert data.ctypes.data % ALIGN == 0
    sent = []
    real = files._write_all

    def spy(fd, chunk):
        sent.append(np.shares_memory(np.frombuffer(chunk, np.uint8), data))
        real(fd, chunk)

    monkeypatch.setattr(files, "_write_all", spy)
    files.write_direct(tmp_path / "one", data)
    assert (tmp_path / "one").read_bytes() == data.tobytes()
    if how == "direct":
        assert sent[0]  # its whole pages from the array itself, not from a copy
    with files.DirectWriter(tmp_path / "two", buffer_size=2 * ALIGN) as out:
        out.write(b"head")  # the buffer is not empty: copied after it
        out.write(data)
        out.close()
    assert (tmp_path / "two").read_bytes() == b"head" + data.tobytes()


@pytest.mark.parametrize("how_written", PATHS, indirect=True)
def test_writers_at_offsets_fill_one_file_however_it_went(tmp_path, how_written):
    # Ranges of one file written by several writers (write_direct's at=), in any order,
    # at page boundaries and between them: the file is every range, the bytes no range
    # covers are left as they were.
    import numpy as np

    path = tmp_path / "chunk"
    old = _data(9 * ALIGN + 100)
    path.write_bytes(old)
    new = _data(8 * ALIGN + 50)
    cuts = [0, 2 * ALIGN, 2 * ALIGN + 7, 5 * ALIGN, 8 * ALIGN + 50]
    ranges = list(itertools.pairwise(cuts))
    for a, b in reversed(ranges):
        piece = files.aligned_empty(b - a, np.uint8)  # aligned memory, aligned or not in the file
        piece[:] = np.frombuffer(new[a:b], np.uint8)
        files.write_direct(path, piece, at=a)
    assert path.read_bytes() == new + old[len(new) :]


def test_aligned_empty_is_page_aligned_whatever_the_shape_and_type():
    import numpy as np

    for shape, dtype in [((0,), float), (5, np.int8), ((3, 1000), float), ((7, 2, 4), ">f8")]:
        a = files.aligned_empty(shape, dtype)
        assert a.flags.c_contiguous and a.flags.writeable
        assert a.ctypes.data % ALIGN == 0 or a.size == 0  # an empty array has no bytes
        assert a.shape == (shape if isinstance(shape, tuple) else (shape,))
        assert a.dtype == np.dtype(dtype)
