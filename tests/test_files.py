"""Atomic file writes: a failure leaves the previous file, or nothing, never half a file."""

from __future__ import annotations

from pathlib import Path

import pytest

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


def test_a_folder_where_an_output_file_goes_replaces_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a relative --out: a long one would be shortened when shown
    out = Path("out")
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
    "name", ["../up.csv", "/abs.csv", "a/b.csv", "..", ".complete", "x" * 256 + ".csv"]
)
def test_names_can_never_leave_or_overflow_out(tmp_path, name):
    with pytest.raises(InputError, match="--out: "):
        write_together(tmp_path / "out", _plan(**{name: "x"}), "--out")
    assert _listing(tmp_path) == []


def test_a_long_out_name_is_one_short_line(tmp_path):
    # 5,000 characters of --out: the line says what and where, not the whole name
    for out in (tmp_path / ("o" * 5000), tmp_path / "/".join(["d" * 200] * 25)):
        with pytest.raises(InputError, match=r"--out: cannot write .*: File name too long") as e:
            write_together(out, _plan(a="a"), "--out")
        assert len(str(e.value)) < 200 and f"({len(str(out))} characters)" in str(e.value)
    assert _listing(tmp_path) == []


def test_an_empty_out_is_refused_not_the_current_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for call in (lambda: write_together("", _plan(a="a"), "--out"),
                 lambda: write_text("", "x")):  # fmt: skip
        with pytest.raises(InputError, match="expected a file or folder name, got an empty one"):
            call()
    assert _listing(tmp_path) == []


def test_control_characters_in_a_path_are_echoed_escaped(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a relative --out: a long one would be shortened when shown
    Path("f\x1b]0;title\x07").write_text("x")  # a file where the folder goes
    with pytest.raises(InputError) as e:
        write_together("f\x1b]0;title\x07", _plan(a="a"), "--out")
    message = str(e.value)
    assert "\\x1b]0;title\\x07 exists and is not a directory" in message
    assert not any(ord(c) < 32 or ord(c) == 127 for c in message)


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

    def refused(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device", "/somewhere/.tmp")

    monkeypatch.setattr(tempfile, "mkstemp", refused)
    argv = [a.format(out=tmp_path) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err == f"ga-rotors: error: {argv[-1]}: No space left on device\n"
    assert list(tmp_path.iterdir()) == []


def test_run_with_an_empty_out_is_one_line_before_anything_runs(tmp_path, capsys, monkeypatch):
    from ga_rotors.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["run", "spinning_disk", "--out", "", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err == "ga-rotors: error: --out: expected a file or folder name, got an empty one\n"
    assert _listing(tmp_path) == []


def test_a_set_written_inside_another_does_not_wait_for_itself(tmp_path, monkeypatch):
    """A format's writer may call results.write or write_csv (each a set of its own) in a
    run's staging folder: a new --out's staging folder is beside it, so both sets lock the
    same folder, which this thread already holds. Another process still waits."""
    monkeypatch.setattr(files, "LOCK_TIMEOUT", 0.2)
    out = tmp_path / "run"
    with files.output_set(out, "--out") as stage:
        with files.output_file(stage / "a.txt") as staged:
            staged.write_text("a")
        (stage / "b.txt").write_text("b")
    assert _listing(out) == ["a.txt", "b.txt"] and [p.name for p in tmp_path.iterdir()] == ["run"]
