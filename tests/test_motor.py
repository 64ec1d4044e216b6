"""ga_rotors.motor against independent oracles: scipy's RigidTransform (matrices, composition,
application, exp coordinates, dual quaternions), clifford's Cl(3,0,1) multiplication tables
(sandwiches, joins, meets, normalisation), mpmath's 40-digit matrix exponential (exp and log
at hard angles), and the closed forms of the hard cases (identity, translations, half-turns,
screws of zero and infinite pitch, non-unit input, tiny angles).

The products of the oracle are NumPy contractions with clifford's own tables (``layout.gmt``
and ``layout.omt``, dense), not clifford's MultiVector operators: those are compiled by
numba, without a cache, on first use in every process (about 15 s of CPU for the product,
the outer and regressive products and exp of this layout), which a test run should not pay
for the same numbers. tests/test_motor_kernels.py checks the kernels against the
MultiVector product itself.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import RigidTransform, Rotation
from uncompiled import uncompiled_twin

from ga_rotors import motor, rotor
from ga_rotors import quaternion as Q
from ga_rotors._pga import LINE, MOTOR, PLANE, POINT
from ga_rotors.errors import InputError

clifford = pytest.importorskip("clifford")
from clifford import pga  # noqa: E402

finite = st.floats(-10, 10, allow_nan=False)
vec3 = st.tuples(finite, finite, finite).map(np.array)
quat = (
    st.tuples(finite, finite, finite, finite)
    .filter(lambda q: sum(c * c for c in q) > 1e-2)
    .map(lambda q: np.array(q) / np.linalg.norm(q))
)
IDENTITY = np.array([1.0, 0, 0, 0, 0, 0, 0, 0])
KIND = {"motor": MOTOR, "plane": PLANE, "line": LINE, "point": POINT}

# ---------------------------------------------------------- clifford's tables, by NumPy

GMT = pga.layout.gmt.todense()  # GMT[i, j, k]: blade j of e_i e_k
OMT = pga.layout.omt.todense()
GRADES = np.array([len(b) for b in pga.layout.bladeTupList])
REV = (-1.0) ** (GRADES * (GRADES - 1) // 2)
PSEUDO = 15  # e0123


def full(x, kind="motor") -> np.ndarray:
    x = np.asarray(x, dtype=float)
    out = np.zeros((*x.shape[:-1], 16))
    out[..., list(KIND[kind])] = x
    return out


def part(X, kind="motor") -> np.ndarray:
    return X[..., list(KIND[kind])]


def gp(*factors) -> np.ndarray:
    out = factors[0]
    for f in factors[1:]:
        out = np.einsum("...i,ijk,...k->...j", out, GMT, f)
    return out


def wedge(a, b) -> np.ndarray:
    return np.einsum("...i,ijk,...k->...j", a, OMT, b)


def _complements():
    right, left = np.zeros((16, 16)), np.zeros((16, 16))
    for i in range(16):
        for j in range(16):
            right[j, i] += OMT[i, PSEUDO, j]  # e_i ∧ rc(e_i) = e0123
            left[j, i] += OMT[j, PSEUDO, i]  # lc(e_i) ∧ e_i = e0123
    return right, left


RIGHT, LEFT = _complements()


def vee(a, b) -> np.ndarray:
    """The regressive (join) product as clifford defines it (``Layout.vee_func``):
    lc(rc(a) ∧ rc(b)), with the complements read off the outer-product table."""
    return LEFT @ wedge(RIGHT @ a, RIGHT @ b)


def test_the_numpy_oracle_is_cliffords_product():
    rng = np.random.default_rng(7)
    a, b = rng.normal(size=16), rng.normal(size=16)
    A, B = (pga.layout.MultiVector(x) for x in (a, b))
    assert np.allclose(gp(a, b), (A * B).value, rtol=0, atol=1e-13)
    assert np.allclose(REV * a, (~A).value)


def rigid(q, t) -> RigidTransform:
    """scipy's rigid transform of the pose (q scalar first, t)."""
    return RigidTransform.from_components(t, Rotation.from_quat(np.roll(q, -1)))


def twist(w, v) -> np.ndarray:
    """The bivector B with exp(B) = scipy's from_exp_coords((w, v)): ½ velocity_line(w, v)."""
    return 0.5 * motor.velocity_line(w, v)


# ------------------------------------------------------------------------ the conventions


def test_the_translator_moves_points_by_plus_t():
    t = np.array([1.0, -2.0, 0.5])
    T = motor.from_translation(t)
    assert np.array_equal(T, [1.0, -0.5, 1.0, -0.25, 0.0, 0.0, 0.0, 0.0])  # 1 − ½ e0 t
    x = np.array([[0.0, 0.0, 0.0], [3.0, 1.0, -4.0]])
    assert np.array_equal(motor.apply(T, x), x + t)
    moved = motor.sandwich_point(T, motor.point(x))
    assert np.allclose(motor.point_coordinates(moved), x + t, rtol=0, atol=1e-15)


def test_the_pose_motor_rotates_then_translates_and_its_rotor_is_the_rotor_modules():
    q = Q.from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
    t = np.array([0.0, 0.0, 5.0])
    M = motor.from_pose(q, t)
    assert np.allclose(M, motor.compose(motor.from_translation(t), motor.from_quaternion(q)))
    assert np.allclose(motor.apply(M, [1.0, 0.0, 0.0]), [0.0, 1.0, 5.0], rtol=0, atol=1e-15)
    R = rotor.from_quaternion(q)  # Cl(3): w − x e23 − y e31 − z e12, the same coefficients
    for name in ("", "e12", "e13", "e23"):
        cl3 = R.value[rotor.layout().names.index(name)]
        assert motor.from_quaternion(q)[MOTOR.index(motor.layout().names.index(name))] == cl3


@given(quat, vec3, quat, vec3)
def test_compose_applies_the_right_factor_first(q1, t1, q2, t2):
    M1, M2 = motor.from_pose(q1, t1), motor.from_pose(q2, t2)
    x = np.array([0.3, -1.0, 2.0])
    both = motor.apply(motor.compose(M1, M2), x)
    assert np.allclose(both, motor.apply(M1, motor.apply(M2, x)), rtol=0, atol=1e-12)


def test_velocity_line_is_the_body_velocity_of_the_rate_equation():
    # M(t) = M0 exp(t B / 2): Ṁ = ½ M B, the body origin moves at R v R̃, turns at ω.
    q0, p0 = Q.from_rotation_vector([0.2, -0.4, 0.7]), np.array([1.0, 2.0, -1.0])
    w, v = np.array([0.3, -1.2, 2.0]), np.array([0.5, 0.1, -0.7])
    M0, B = motor.from_pose(q0, p0), motor.velocity_line(w, v)
    path = lambda t: motor.compose(M0, motor.exp(0.5 * t * B))  # noqa: E731
    h = 1e-6
    rate = (path(h) - path(-h)) / (2 * h)  # central difference, error ~1e-11
    assert np.allclose(rate, 0.5 * motor.compose(M0, np.r_[0.0, B, 0.0]), rtol=0, atol=1e-9)
    q, p = motor.to_pose(np.stack([path(-h), path(h)]))
    assert np.allclose((p[1] - p[0]) / (2 * h), Q.rotate(q0, v), rtol=0, atol=1e-9)
    qdot = (q[1] - q[0]) / (2 * h)
    assert np.allclose(qdot, 0.5 * Q.multiply(q0, np.r_[0.0, w]), rtol=0, atol=1e-9)
    assert all(np.array_equal(a, b) for a, b in zip(motor.velocities(B), (w, v), strict=True))


# ------------------------------------------------------------------ scipy's RigidTransform


@given(quat, vec3)
def test_matrices_are_scipys(q, t):
    M = motor.from_pose(q, t)
    H = rigid(q, t).as_matrix()
    assert np.allclose(motor.to_matrix(M), H, rtol=0, atol=1e-14)
    back_q, back_t = motor.to_pose(motor.from_matrix(H))
    assert Q.distance(back_q, q) < 1e-7 and np.allclose(back_t, t, rtol=0, atol=1e-14)
    assert np.allclose(motor.to_translation(M), t, rtol=0, atol=1e-13)
    assert Q.distance(motor.to_quaternion(M), q) < 2e-8


@given(quat, vec3, quat, vec3, vec3)
def test_composition_and_application_are_scipys(q1, t1, q2, t2, x):
    M = motor.compose(motor.from_pose(q1, t1), motor.from_pose(q2, t2))
    oracle = rigid(q1, t1) * rigid(q2, t2)
    assert np.allclose(motor.to_matrix(M), oracle.as_matrix(), rtol=0, atol=1e-12)
    assert np.allclose(motor.apply(M, x), oracle.apply(x), rtol=0, atol=1e-12)


@given(vec3, vec3)
def test_exp_and_log_are_scipys_exp_coordinates(w, v):
    w = w * (3.0 / max(1.0, np.linalg.norm(w)))  # |ω| < π: scipy's principal range
    M = motor.exp(twist(w, v))
    oracle = RigidTransform.from_exp_coords(np.r_[w, v])
    assert np.allclose(motor.to_matrix(M), oracle.as_matrix(), rtol=0, atol=1e-12)
    coords = oracle.as_exp_coords()
    assert np.allclose(motor.log(M), twist(coords[:3], coords[3:]), rtol=0, atol=1e-12)


@given(quat, vec3)
def test_dual_quaternions_are_scipys(q, t):
    dq = rigid(q, t).as_dual_quat(scalar_first=True)
    mine = motor.to_dual_quaternion(motor.from_pose(q, t))
    k = np.argmax(np.abs(q))
    sign = np.sign(q[k] * dq[k])  # scipy's q may be the other of ±q
    assert np.allclose(mine * sign, dq, rtol=0, atol=1e-13)
    assert np.allclose(motor.from_dual_quaternion(dq) * sign, motor.from_pose(q, t), rtol=0,
                       atol=1e-13)  # fmt: skip


# ------------------------------------------------------------------- clifford's products


@pytest.mark.parametrize("kind", ["plane", "line", "point"])
@settings(max_examples=40)
@given(q=quat, t=vec3, x=st.tuples(*[finite] * 6))
def test_the_sandwiches_are_cliffords(kind, q, t, x):
    x = np.array(x[: len(KIND[kind])])
    M = full(motor.from_pose(q, t))
    expected = gp(M, full(x, kind), REV * M)
    got = getattr(motor, f"sandwich_{kind}")(part(M), x)
    assert np.allclose(got, part(expected, kind), rtol=0, atol=1e-10)
    assert np.abs(np.delete(expected, list(KIND[kind]))).max() < 1e-10  # the grade is kept


@given(quat, vec3, quat, vec3)
def test_compose_is_the_geometric_product(q1, t1, q2, t2):
    a, b = motor.from_pose(q1, t1), motor.from_pose(q2, t2)
    assert np.allclose(motor.compose(a, b), part(gp(full(a), full(b))), rtol=0, atol=1e-12)


@given(st.tuples(*[finite] * 8).filter(lambda m: sum(m[i] ** 2 for i in (0, 4, 5, 6)) > 1e-2))
def test_normalize_gives_m_mtilde_one_by_a_central_factor(m):
    N, M = full(motor.normalize(m)), full(m)
    assert np.allclose(gp(N, REV * N), full(IDENTITY), rtol=0, atol=1e-12)
    # N = M f with f = a + b e0123 central: N M̃ has no other blades.
    f = gp(N, REV * M)
    assert np.abs(np.delete(f, [0, PSEUDO])).max() < 1e-10 * np.abs(f).max()


def test_points_lines_and_planes_are_the_pga_literatures():
    p, d = np.array([1.0, 2.0, 3.0]), np.array([0.5, -1.0, 2.0])
    e = np.eye(16)
    e0, e1, e2, e3 = e[1:5]
    # e123 + x e032 + y e013 + z e021, as the PGA literature writes a point
    literature = gp(e1, e2, e3) + p[0] * gp(e0, e3, e2) + p[1] * gp(e0, e1, e3) + p[2] * gp(
        e0, e2, e1)  # fmt: skip
    assert np.allclose(full(motor.point(p), "point"), literature)
    join = vee(full(motor.point(p), "point"), full(motor.point(p + d), "point"))
    assert np.allclose(motor.line(p, d), part(join, "line"), rtol=0, atol=1e-15)
    # The same line as the meet of two planes through p with normals n1 × n2 = d/|d|.
    n1 = np.cross(d, [1.0, 0.0, 0.0])
    n1 /= np.linalg.norm(n1)
    n2 = np.cross(d, n1) / np.linalg.norm(d)
    meet = wedge(full(motor.plane(n1, n1 @ p), "plane"), full(motor.plane(n2, n2 @ p), "plane"))
    assert np.allclose(motor.line(p, d) / np.linalg.norm(d), part(meet, "line"), atol=1e-15)
    n, delta = np.array([0.0, 3.0, 4.0]), 2.0
    for x in ([1.0, 0.4, 0.2], [0.0, 0.0, 0.0]):
        incidence = wedge(full(motor.plane(n, delta), "plane"), full(motor.point(x), "point"))
        assert math.isclose(incidence[PSEUDO], n @ x - delta, abs_tol=1e-15)  # (n·x − δ) e0123
    meet = wedge(full(motor.plane([1.0, 0, 0], 1.0), "plane"),
                 full(motor.plane([0, 1.0, 0], 2.0), "plane"))  # fmt: skip
    point, u = motor.line_coordinates(part(meet, "line"))
    assert np.allclose(point, [1.0, 2.0, 0.0]) and np.allclose(u, [0.0, 0.0, 1.0])


@given(vec3, vec3.filter(lambda d: np.linalg.norm(d) > 1e-3), vec3, finite)
def test_coordinates_round_trip(p, d, n, delta):
    assert np.allclose(motor.point_coordinates(3.0 * motor.point(p)), p, rtol=0, atol=1e-14)
    q, u = motor.line_coordinates(motor.line(p, d))
    assert np.allclose(u, d / np.linalg.norm(d)) and np.allclose(np.cross(q, u), np.cross(p, u),
                                                                 rtol=0, atol=1e-12)  # fmt: skip
    assert abs(q @ u) < 1e-12  # the nearest point to the origin
    if np.linalg.norm(n) > 1e-3:
        unit, offset = motor.plane_coordinates(motor.plane(n, delta))
        assert np.allclose(unit * offset * np.linalg.norm(n), n / np.linalg.norm(n) * delta)


def test_multivectors_both_ways_single_and_batched():
    M = motor.from_pose(Q.from_axis_angle([1.0, 2.0, 3.0], 0.4), [1.0, 0.0, -2.0])
    X = motor.to_multivector(M)
    assert isinstance(X, clifford.MultiVector) and np.array_equal(motor.from_multivector(X), M)
    batch = np.stack([M, motor.inverse(M)]).reshape(2, 1, 8)
    arr = motor.to_multivector(batch)
    assert arr.shape == (2, 1) and np.array_equal(motor.from_multivector(arr), batch)
    assert arr[1, 0] == motor.to_multivector(motor.inverse(M))
    with pytest.raises(InputError, match="X: expected a line"):
        motor.from_multivector(X, "line")
    with pytest.raises(InputError, match=r"X: expected MultiVectors of Cl.3,0,1."):
        motor.from_multivector(rotor.from_quaternion([1.0, 0, 0, 0]))
    with pytest.raises(InputError, match="kind: expected one of"):
        motor.to_multivector(M, "screw")


# ------------------------------------------------------------------------ hard cases


def test_zero_motion_is_exact_everywhere():
    assert np.array_equal(motor.exp(np.zeros(6)), IDENTITY)
    assert not np.any(motor.log(IDENTITY))
    assert np.array_equal(motor.to_matrix(IDENTITY), np.eye(4))
    axis, angle, pitch = motor.to_screw(IDENTITY)
    assert (
        angle == 0.0 and pitch == 0.0 and np.array_equal(axis, motor.line([0, 0, 0], [0, 0, 1.0]))
    )
    assert np.array_equal(motor.from_screw(axis, 0.0, 3.0), IDENTITY)


@pytest.mark.parametrize("t", [[1e-300, 0.0, 0.0], [0.0, -2.5, 0.0], [1e8, -3e7, 2.0]])
def test_pure_translations_are_exact(t):
    T = motor.from_translation(t)
    assert np.array_equal(motor.to_translation(T), t)
    B = motor.log(T)
    assert np.array_equal(B, np.r_[-0.5 * np.array(t), 0.0, 0.0, 0.0])
    assert np.array_equal(motor.exp(B), T)
    axis, angle, pitch = motor.to_screw(T)
    assert angle == math.hypot(*t) and pitch == np.inf
    assert np.allclose(motor.from_screw(axis, angle, pitch), T, rtol=1e-15, atol=0)


@pytest.mark.parametrize("axis", [[1.0, 0, 0], [0, 0, 1.0], [1.0, 1.0, 0.0], [0.3, -0.5, 0.8]])
def test_half_turns_about_lines_off_the_origin(axis):
    u = np.array(axis) / np.linalg.norm(axis)
    p = np.array([1.0, -2.0, 0.5])
    M = motor.from_screw(motor.line(p, u), np.pi)  # zero pitch: a rotation about the line
    oracle = (RigidTransform.from_translation(p) * RigidTransform.from_rotation(
        Rotation.from_rotvec(np.pi * u)) * RigidTransform.from_translation(-p))  # fmt: skip
    H = motor.to_matrix(M)
    assert np.allclose(H, oracle.as_matrix(), rtol=0, atol=1e-14)
    assert np.allclose(motor.to_matrix(motor.from_matrix(H)), H, rtol=0, atol=1e-15)  # tr = −1
    assert np.allclose(motor.exp(motor.log(M)), M, rtol=0, atol=1e-15)
    back, angle, pitch = motor.to_screw(M)
    assert angle == pytest.approx(np.pi, abs=1e-15) and abs(pitch) < 1e-15
    point, direction = motor.line_coordinates(back)
    assert abs(abs(direction @ u) - 1.0) < 1e-15  # the same axis, either way round
    assert np.linalg.norm(np.cross(point - p, u)) < 1e-14


@given(vec3, vec3.filter(lambda d: np.linalg.norm(d) > 1e-2),
       st.floats(-3.1, 3.1), st.floats(-2.0, 2.0))  # fmt: skip
def test_screws_are_scipys_and_round_trip(p, d, angle, pitch):
    u = d / np.linalg.norm(d)
    M = motor.from_screw(motor.line(p, d), angle, pitch)
    oracle = (RigidTransform.from_translation(p + pitch * angle * u)
              * RigidTransform.from_rotation(Rotation.from_rotvec(angle * u))
              * RigidTransform.from_translation(-p))  # fmt: skip
    assert np.allclose(motor.to_matrix(M), oracle.as_matrix(), rtol=0, atol=1e-12)
    if abs(angle) > 1e-6:
        axis, a, h = motor.to_screw(M)
        assert a == pytest.approx(abs(angle), abs=1e-12)
        assert h == pytest.approx(pitch, abs=1e-9 * (1 + np.linalg.norm(p)))
        assert np.allclose(motor.to_matrix(motor.from_screw(axis, a, h)), oracle.as_matrix(),
                           rtol=0, atol=1e-11)  # fmt: skip


def test_screw_of_zero_pitch_fixes_its_axis_and_of_infinite_pitch_only_slides():
    p, u = np.array([2.0, 0.0, -1.0]), np.array([0.0, 0.6, 0.8])
    axis = motor.line(p, u)
    on_axis = p + np.outer([-1.0, 0.0, 2.5], u)
    spin = motor.from_screw(axis, 1.3, 0.0)
    assert np.allclose(motor.apply(spin, on_axis), on_axis, rtol=0, atol=1e-15)
    assert np.allclose(motor.sandwich_line(spin, axis), axis, rtol=0, atol=1e-15)
    for sign in (1.0, -1.0):
        slide = motor.from_screw(axis, 2.0, sign * np.inf)
        assert np.allclose(motor.to_translation(slide), sign * 2.0 * u, rtol=0, atol=1e-15)
        assert motor.to_quaternion(slide).tolist() == [1.0, 0.0, 0.0, 0.0]


def test_rotor_part_minus_one_logs_along_the_translation():
    for t in ([0.0, 0.0, 0.0], [0.0, 3.0, 4.0]):
        M = -motor.from_translation(t)
        B = motor.log(M)
        assert np.allclose(motor.exp(B), M, rtol=0, atol=1e-15)
        a = -np.array([B[5], -B[4], B[3]])  # the rotor bivector's vector, 2θ = 2π turn
        assert np.linalg.norm(a) == pytest.approx(np.pi)
    assert np.allclose(np.cross(a, [0.0, 3.0, 4.0]), 0.0, atol=1e-15)


def _mp_matrix(B) -> np.ndarray:
    """to_matrix(exp(B)) to 40 digits: the 4×4 matrix exponential of the twist 2B."""
    mpmath.mp.dps = 40
    w, v = motor.velocities(2.0 * np.asarray(B, dtype=float))
    wx = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
    S = mpmath.matrix([[*map(mpmath.mpf, wx[i]), mpmath.mpf(v[i])] for i in range(3)] + [[0] * 4])
    return np.array(mpmath.expm(S).tolist(), dtype=float)


@pytest.mark.parametrize("theta", [1e-300, 1e-150, 1e-12, 1e-8, 1e-4, 0.25, 0.999999, 1.0,
                                   1.000001, 1.5, np.pi / 2, 3.0, np.pi - 1e-9])  # fmt: skip
def test_exp_and_log_near_zero_and_at_the_series_seam_are_exact(theta):
    # θ is the rotor angle (half the rotation); the closed form's T(θ) switches to its
    # series below θ = 1 (ga_rotors.motor._screw.SERIES_BELOW).
    u = np.array([0.36, -0.48, 0.8])
    for v in ([0.0, 0.0, 0.0], [1.0, 2.0, -0.5], [3e3, 0.0, 1e-3]):
        B = motor.velocity_line(theta * u, v)  # a = θ u: exp(B) turns by 2θ
        exact = _mp_matrix(B)  # measured: within 1.5 ulp of its largest entry
        assert np.allclose(motor.to_matrix(motor.exp(B)), exact, rtol=0,
                           atol=4 * 2.2e-16 * (1 + np.abs(exact).max()))  # fmt: skip
        if theta < np.pi - 1e-6:  # near θ = π the log is ill-conditioned (its cut):
            back = motor.log(motor.exp(B))  # it divides by sin θ / θ (1/21 at θ = 3)
            condition = theta / np.sin(theta) if theta > 0.0 else 1.0
            assert np.allclose(back, B, rtol=1e-14, atol=4e-16 * condition * np.abs(B).max())


def test_non_unit_motors_within_tolerance_are_renormalised_and_beyond_it_refused():
    M = motor.from_pose(Q.from_axis_angle([0, 1.0, 0], 0.3), [1.0, 2.0, 3.0])
    assert np.allclose(motor.apply(M * (1 + 5e-7), [1.0, 0, 0]), motor.apply(M, [1.0, 0, 0]),
                       rtol=0, atol=1e-15)  # fmt: skip
    with pytest.raises(InputError, match=r"M: expected unit motors .* at index \(1,\)"):
        motor.apply(np.stack([M, 1.01 * M]), [1.0, 0, 0])
    study = M + 1e-3 * np.r_[np.zeros(7), 1.0]  # M M̃ gains an e0123 part
    with pytest.raises(InputError, match="e0123 at index"):
        motor.log(study)
    fixed = motor.normalize(study)
    assert np.allclose(motor.log(fixed), motor.log(motor.normalize(fixed)), rtol=0, atol=1e-15)
    with pytest.raises(InputError, match="M: expected a nonzero rotor part"):
        motor.normalize([0.0, 1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 4.0])


def test_bad_input_gets_one_line_naming_the_argument():
    M = motor.from_translation([1.0, 0, 0])
    cases = [
        (lambda: motor.compose(M, [1.0, 0, 0]),
         r"motors\[1\]: expected an array of shape \(\.\.\., 8\)"),
        (lambda: motor.compose(), "motors: expected at least one motor"),
        (lambda: motor.apply(M, [np.nan, 0, 0]), "x: contains nan"),
        (lambda: motor.apply(np.zeros((2, 8)) + IDENTITY, np.zeros((3, 3))), "do not broadcast"),
        (lambda: motor.from_pose([2.0, 0, 0, 0], [0, 0, 0]), "q: expected unit quaternions"),
        (lambda: motor.from_matrix(np.diag([1.0, 1, -1, 1])),
         r"H\[\.\.\., :3, :3\]: expected a rotation"),
        (lambda: motor.from_matrix(np.eye(4) + np.eye(4)[::-1] * 0.5), "H: expected the last row"),
        (lambda: motor.from_screw([1.0, 0, 0, 0, 0, 0], 1.0),
         "axis: expected a line with a direction"),
        (lambda: motor.from_screw([0, 0, 1.0, 1.0, 0, 0], 1.0),
         "axis: expected a line .*got a screw"),
        (lambda: motor.from_screw(motor.line([0, 0, 0], [1.0, 0, 0]), 1.0, np.nan),
         "pitch: expected"),
        (lambda: motor.point_coordinates([1.0, 0, 0, 0]), "P: expected a finite point"),
        (lambda: motor.plane_coordinates([1.0, 0, 0, 0]), "a: expected a plane with a normal"),
        (lambda: motor.line([0, 0, 0], [0, 0, 0]), "direction: expected nonzero"),
        (lambda: motor.compose(np.full(8, 1e200), np.full(8, 1e200)), "product is not finite"),
        (lambda: motor.log([[1.0, 0, 0, 0, 0, 0, 0, 0], [1.0, np.inf, 0, 0, 0, 0, 0, 0]]),
         "M: contains inf at index"),
    ]  # fmt: skip
    for call, message in cases:
        with pytest.raises(InputError, match=message) as info:
            call()
        assert "\n" not in str(info.value)


def test_batches_broadcast_like_numpy():
    rng = np.random.default_rng(3)
    M = motor.from_pose(Q.normalize(rng.normal(size=(5, 1, 4))), rng.normal(size=(5, 1, 3)))
    N = motor.from_pose(Q.normalize(rng.normal(size=(1, 7, 4))), rng.normal(size=(1, 7, 3)))
    MN = motor.compose(M, N)
    assert MN.shape == (5, 7, 8)
    assert np.allclose(MN[2, 3], motor.compose(M[2, 0], N[0, 3]), rtol=0, atol=1e-15)
    x = rng.normal(size=(7, 3))
    assert motor.apply(MN, x).shape == (5, 7, 3)
    assert motor.sandwich_line(M, motor.line(x, x + 1.0)).shape == (5, 7, 6)
    assert motor.log(MN).shape == (5, 7, 6) and motor.to_matrix(MN).shape == (5, 7, 4, 4)
    assert motor.to_screw(MN)[1].shape == (5, 7)
    one = motor.apply(MN[0, 0], x[0])
    assert one.shape == (3,) and np.allclose(one, motor.apply(MN, x)[0, 0], rtol=0, atol=0)


test_motor_agrees_uncompiled = uncompiled_twin(__file__)
