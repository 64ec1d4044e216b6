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
    assert rows[0] == [
        "t [s]", "w_1 [rad/s]", "w_2 [rad/s]", "w_3 [rad/s]",
        "euler_psi [rad]", "euler_theta [rad]", "euler_phi [rad]",
    ]  # fmt: skip
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


def test_orientation_by_name_for_every_path_and_primary_first():
    # Three paths holding one rotation, a quarter turn about z: q = (c, 0, 0, s); on the
    # rotor's blades (c, −s, 0, 0), since k ↦ −e12; as ZYZ angles, ψ + φ = π/2 at θ = 0.
    c = s = np.sqrt(0.5)
    tr = Trajectory(
        {
            "t": np.array([0.0]),
            "rotor_blades": np.array([[c, -s, 0.0, 0.0]]),
            "q": np.array([[c, 0.0, 0.0, s]]),
            "euler": np.array([[np.pi / 4, 0.0, np.pi / 4]]),
        },
        meta={"primary": "quaternion"},
    )
    assert tr.paths == ("quaternion", "rotor", "euler")
    for path in (None, "rotor", "quaternion", "euler"):
        assert np.allclose(tr.quaternions(path), [[c, 0.0, 0.0, s]], rtol=0, atol=4e-16), path
    [R] = tr.rotors("rotor")
    assert np.allclose(R.value, [c, 0, 0, 0, -s, 0, 0, 0], rtol=0, atol=1e-16)
    assert tr.extended({"energy": np.ones(1)}).quaternions() is tr.quaternions()


def test_orientation_of_a_missing_or_unknown_path_is_refused():
    with pytest.raises(InputError, match="no 'rotor' path"):
        sample().quaternions("rotor")
    with pytest.raises(InputError, match="unknown path 'matrix'"):
        sample().quaternions("matrix")
    with pytest.raises(InputError, match="holds no orientation path"):
        Trajectory({"t": np.zeros(2)}).quaternions()
