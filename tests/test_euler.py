"""Euler angles in all 24 sequences against scipy, including gimbal lock in every one."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from oracles import U, half_turns, random_unit, rotation_error, to_scipy, unit_quaternions
from scipy.spatial.transform import Rotation
from uncompiled import uncompiled_twin

from ga_rotors import euler
from ga_rotors import quaternion as Q
from ga_rotors.errors import GimbalLockWarning, InputError

PROPER = [s for s in euler.SEQUENCES if s[0].lower() == s[2].lower()]
TAIT_BRYAN = [s for s in euler.SEQUENCES if s[0].lower() != s[2].lower()]


def singular_middles(seq):
    return (0.0, math.pi) if seq in PROPER else (math.pi / 2, -math.pi / 2)


def random_angles(seq, n, seed):
    rng = np.random.default_rng(seed)
    a = rng.uniform(-math.pi, math.pi, size=(n, 3))
    # keep the middle angle 0.01 rad away from the singularities, so angles are unique
    if seq in PROPER:
        a[:, 1] = rng.uniform(0.01, math.pi - 0.01, size=n)
    else:
        a[:, 1] = rng.uniform(-math.pi / 2 + 0.01, math.pi / 2 - 0.01, size=n)
    return a


def scipy_angles(r, seq):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        return r.as_euler(seq)


def same_angles(a, b, atol):
    """Equal modulo 2π."""
    d = np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))
    return np.all(np.abs(d) <= atol)


def test_there_are_24_sequences():
    assert len(euler.SEQUENCES) == 24 == len(set(euler.SEQUENCES))
    assert len(PROPER) == 12 and len(TAIT_BRYAN) == 12


@pytest.mark.parametrize("seq", euler.SEQUENCES)
def test_to_quaternion_matches_scipy_on_random_angles(seq):
    a = random_angles(seq, 50, seed=euler.SEQUENCES.index(seq))
    # three elementary quaternions (sin/cos: 1 ulp each) and two products: ~8 ulp, doubled.
    assert rotation_error(euler.to_quaternion(seq, a), Rotation.from_euler(seq, a)).max() <= 16 * U


@pytest.mark.parametrize("seq", euler.SEQUENCES)
def test_from_quaternion_matches_scipy_angles_away_from_gimbal_lock(seq):
    a = random_angles(seq, 50, seed=100 + euler.SEQUENCES.index(seq))
    q = Rotation.from_euler(seq, a).as_quat(scalar_first=True)
    ours = euler.from_quaternion(q, seq)
    # away from the singularity by >= 0.01 rad the angles are unique and have a condition
    # number <= 1/sin(0.01) ~ 100: 100 x 16 ulp.
    assert same_angles(ours, a, atol=1600 * U)
    assert same_angles(ours, scipy_angles(to_scipy(q), seq), atol=1600 * U)
    assert rotation_error(euler.to_quaternion(seq, ours), to_scipy(q)).max() <= 16 * U


@given(unit_quaternions, st.sampled_from(euler.SEQUENCES))
def test_every_sequence_round_trips_the_rotation(q, seq):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GimbalLockWarning)
        a = euler.from_quaternion(q, seq)
    assert np.all(np.abs(a) <= math.pi)
    # within GIMBAL_TOLERANCE of a lock the third angle is forced to 0, which moves the
    # rotation by at most twice that distance (a commutator bound)
    assert Q.distance(euler.to_quaternion(seq, a), q) <= 16 * U + 2 * euler.GIMBAL_TOLERANCE


@pytest.mark.parametrize("seq", ["ZYZ", "zxz", "XYZ", "zyx"])
def test_forcing_the_third_angle_near_a_lock_stays_within_its_bound(seq):
    # the hypothesis case that found it: a half-turn about y with a 1e-15 z component
    q = np.array([0.0, 0.0, 1.0, 1e-15])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GimbalLockWarning)
        a = euler.from_quaternion(q, seq)
    assert Q.distance(euler.to_quaternion(seq, a), q) <= 16 * U + 2 * euler.GIMBAL_TOLERANCE


@pytest.mark.parametrize("seq", euler.SEQUENCES)
@pytest.mark.parametrize("which", [0, 1])
def test_gimbal_lock_in_every_sequence(seq, which):
    middle = singular_middles(seq)[which]
    a = np.array([[0.3, middle, 0.5], [-2.9, middle, 2.8], [1.0, middle, 0.0]])
    q = euler.to_quaternion(seq, a)
    with pytest.warns(GimbalLockWarning, match="third angle is set to 0"):
        got, locked = euler.from_quaternion(q, seq, return_gimbal=True)
    assert np.all(locked) and np.all(got[:, 2] == 0.0) and np.all(np.isfinite(got))
    # the rotation is unchanged: within the round-off budget, not scipy's 1e-7 threshold
    assert rotation_error(euler.to_quaternion(seq, got), to_scipy(q)).max() <= 16 * U
    # and the angles are scipy's (which also zeroes the third angle)
    assert same_angles(got, scipy_angles(to_scipy(q), seq), atol=16 * U)


@pytest.mark.parametrize("seq", ["ZYZ", "zyz", "ZYX", "xyz"])
@pytest.mark.parametrize("offset", [1e-9, 1e-12])
def test_near_gimbal_lock_stays_exact_where_scipys_threshold_is_not(seq, offset):
    middle = singular_middles(seq)[0]
    a = np.array([0.3, middle + (offset if seq in PROPER else -offset), 0.5])
    q = euler.to_quaternion(seq, a)
    with warnings.catch_warnings():
        warnings.simplefilter("error", GimbalLockWarning)  # not locked: no warning
        got = euler.from_quaternion(q, seq)
    assert Q.distance(euler.to_quaternion(seq, got), q) <= 16 * U
    # scipy snaps anything within 1e-7 rad and loses the rotation by ~ the offset
    theirs = scipy_angles(to_scipy(q), seq)
    assert rotation_error(q, Rotation.from_euler(seq, theirs)) > 0.1 * offset


@pytest.mark.parametrize("seq", euler.SEQUENCES)
def test_half_turns_about_random_axes_in_every_sequence_match_scipy(seq):
    q = half_turns(60 + euler.SEQUENCES.index(seq), 20)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GimbalLockWarning)
        ours = euler.from_quaternion(q, seq)
    theirs = scipy_angles(to_scipy(q), seq)
    # compare rotations, not angles: both triples must reproduce the half-turn
    assert rotation_error(euler.to_quaternion(seq, ours), to_scipy(q)).max() <= 16 * U
    assert (Rotation.from_euler(seq, theirs).inv() * to_scipy(q)).magnitude().max() <= 16 * U


def test_identity_in_every_sequence():
    for seq in euler.SEQUENCES:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", GimbalLockWarning)
            a = euler.from_quaternion([1.0, 0, 0, 0], seq)
        assert Q.distance(euler.to_quaternion(seq, a), [1.0, 0, 0, 0]) == 0.0


def test_papers_zyz_is_precession_nutation_spin():
    psi, theta, phi = 0.4, 0.25, 15.7
    z, y = [0, 0, 1.0], [0, 1.0, 0]
    expected = Q.multiply(
        Q.multiply(Q.from_axis_angle(z, psi), Q.from_axis_angle(y, theta)),
        Q.from_axis_angle(z, phi),
    )
    assert Q.distance(euler.to_quaternion("ZYZ", [psi, theta, phi]), expected) <= 4 * U


def test_notes_aerospace_zyx_correct_form_and_the_notes_signs():
    yaw, pitch, roll = 0.7, -0.3, 1.1
    q = euler.to_quaternion("ZYX", [yaw, pitch, roll])
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    correct = [
        cy * cp * cr + sy * sp * sr,
        cy * cp * sr - sy * sp * cr,
        cy * sp * cr + sy * cp * sr,
        sy * cp * cr - cy * sp * sr,
    ]
    assert np.allclose(q, correct, rtol=0, atol=4 * U)
    # the notes print '+' in the x and z components (with their ψ = roll, φ = pitch,
    # θ = yaw): q0 and q2 agree, q1 and q3 do not.
    notes = [
        cr * cp * cy + sr * sp * sy,
        sr * cp * cy + cr * sp * sy,
        sr * cp * sy + cr * sp * cy,
        cr * cp * sy + sr * sp * cy,
    ]
    assert math.isclose(notes[0], q[0]) and math.isclose(notes[2], q[2])
    assert not math.isclose(notes[1], q[1]) and not math.isclose(notes[3], q[3])


def test_extrinsic_is_reversed_intrinsic():
    a = np.array([0.1, 0.2, 0.3])
    assert np.array_equal(euler.to_quaternion("xyz", a), euler.to_quaternion("ZYX", a[::-1]))


def test_degrees_flag_both_ways():
    q = euler.to_quaternion("ZYX", [30.0, 20.0, 10.0], degrees=True)
    assert np.allclose(q, euler.to_quaternion("ZYX", np.radians([30.0, 20.0, 10.0])), atol=U)
    assert np.allclose(
        euler.from_quaternion(q, "ZYX", degrees=True), [30.0, 20.0, 10.0], atol=1e-12
    )


def test_batched_shapes_and_gimbal_mask():
    q = random_unit(40, 6).reshape(2, 3, 4)
    assert euler.from_quaternion(q, "XYZ").shape == (2, 3, 3)
    q[1, 2] = euler.to_quaternion("XYZ", [0.2, math.pi / 2, 0.1])
    with pytest.warns(GimbalLockWarning, match="1 of 6"):
        _, mask = euler.from_quaternion(q, "XYZ", return_gimbal=True)
    assert mask.shape == (2, 3) and mask.sum() == 1 and mask[1, 2]


@pytest.mark.parametrize("seq", ["xyZ", "XXY", "abc", "XYZW", "XY", 3, None, "zyy"])
def test_unknown_sequences_list_the_valid_form(seq):
    with pytest.raises(InputError, match=r"seq: expected three axes from 'XYZ' \(intrinsic\).*ZYZ"):
        euler.to_quaternion(seq, [0.0, 0.0, 0.0])
    with pytest.raises(InputError, match="seq: "):
        euler.from_quaternion([1.0, 0, 0, 0], seq)


def test_bad_angles_and_quaternions_name_the_argument():
    with pytest.raises(InputError, match="angles: contains nan"):
        euler.to_quaternion("ZYZ", [0.0, np.nan, 0.0])
    with pytest.raises(InputError, match=r"angles: expected an array of shape \(\.\.\., 3\)"):
        euler.to_quaternion("ZYZ", [0.0, 0.0])
    with pytest.raises(InputError, match="q: expected unit"):
        euler.from_quaternion([2.0, 0, 0, 0], "ZYZ")


test_euler_agrees_uncompiled = uncompiled_twin(__file__)
