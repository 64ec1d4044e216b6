"""Trajectory: named arrays, CSV/NPZ export, atomic writes."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

from ga_rotors.errors import InputError
from ga_rotors.trajectory import Trajectory


def sample():
    t = np.linspace(0.0, 1.0, 5)
    return Trajectory(
        {"t": t, "w": np.arange(15.0).reshape(5, 3) / 7, "euler": np.ones((3, 3)) / 3},
        {"w": ("1", "2", "3"), "euler": ("psi", "theta", "phi")},
        {"integrator": "rk4"},
    )


def test_csv_round_trips_at_full_precision_and_leaves_missing_cells_empty(tmp_path):
    tr = sample()
    path = tr.to_csv(tmp_path / "run.csv")
    rows = list(csv.reader(io.StringIO(path.read_text())))
    assert rows[0] == ["t", "w_1", "w_2", "w_3", "euler_psi", "euler_theta", "euler_phi"]
    data = rows[1:]
    assert len(data) == 5
    assert [float(x) for x in data[4][1:4]] == tr.w[4].tolist()  # repr: exact round trip
    assert data[3][4:] == ["", "", ""] and data[2][4] != ""
    assert "nan" not in path.read_text().lower()


def test_npz_holds_every_array_and_labels(tmp_path):
    tr = sample()
    with np.load(tr.to_npz(tmp_path / "run.npz")) as z:
        assert np.array_equal(z["w"], tr.w) and z["euler"].shape == (3, 3)
        assert z["euler__components"].tolist() == ["psi", "theta", "phi"]


def test_missing_array_names_what_exists():
    with pytest.raises(AttributeError, match="no array 'q'; it has t, w, euler"):
        _ = sample().q
    assert "q" not in sample()


def test_bad_construction_is_refused(tmp_path):
    with pytest.raises(InputError, match="needs the sample times 't'"):
        Trajectory({"w": np.zeros((2, 3))})
    with pytest.raises(InputError, match="w: expected at most 2 rows"):
        Trajectory({"t": np.zeros(2), "w": np.zeros((3, 3))})
    with pytest.raises(InputError, match="does not exist"):
        sample().to_csv(tmp_path / "nowhere" / "x.csv")
