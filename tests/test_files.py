"""Atomic file writes: a failure leaves the previous file, or nothing, never half a file."""

from __future__ import annotations

import pytest

from ga_rotors.errors import InputError
from ga_rotors.files import atomic_write, write_text


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
