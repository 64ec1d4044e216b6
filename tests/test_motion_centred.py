"""The motor path's kernels of a body frame at the centre of mass (s = 0), which a single
run binds instead of the general ones (ga_rotors.integrators._source.centred).

Oracle: the general kernels themselves at s = 0 (the lever's terms are exact zeros
there), number for number; and batches, centred or not, against each body's single run,
bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors import RigidBody, forces
from ga_rotors import quaternion as Q
from ga_rotors.integrators import Batch, Problem, get
from ga_rotors.integrators._source import BATCH, BATCH_CENTRED, LOOP, source
from ga_rotors.paths import motor as motor_path

RACKET, MASS = (0.011, 0.023, 0.031), 0.31
CENTRED_BODY = (*RACKET, MASS, 0.0, 0.0, 0.0)

finite = st.floats(-50.0, 50.0, allow_nan=False)
vec3 = st.tuples(finite, finite, finite)


def _motor(q, t):
    return motor_path.initial_state(Q.normalize(np.asarray(q)), t, (0.0,) * 3, (0.0,) * 3,
                                    (0.0,) * 3)[0]  # fmt: skip


@settings(max_examples=60, deadline=None)
@given(q=st.tuples(finite, finite, finite, finite).filter(lambda q: sum(x * x for x in q) > 1e-3),
       t=vec3, om=vec3, v=vec3, force=vec3, torque=vec3)  # fmt: skip
def test_centred_kernels_give_the_general_kernels_numbers_at_s_zero(q, t, om, v, force, torque):
    x = tuple(_motor(q, t))
    w = (*om, *v)
    f = (*force, *torque)
    assert np.array_equal(motor_path.centred_accel(x, w, CENTRED_BODY, f),
                          motor_path.accel(x, w, CENTRED_BODY, f))  # fmt: skip
    assert np.array_equal(motor_path.centred_free_accel(x, w, CENTRED_BODY),
                          motor_path.free_accel(x, w, CENTRED_BODY))  # fmt: skip
    general = motor_path.centre_of_mass(x, w, CENTRED_BODY)
    centred = motor_path.centred_centre_of_mass(x, w, CENTRED_BODY)
    for a, b in zip(centred, general, strict=True):
        assert np.array_equal(a, b)


def _problem(s):
    body = RigidBody(RACKET, mass=MASS, centre_of_mass=s)
    return Problem(RACKET, mass=MASS, centre_of_mass=s, forces=(forces.uniform_gravity(body),))


def test_the_centred_kernels_are_bound_exactly_where_the_bodies_are_centred():
    rk4 = get("rk4")
    for form in (LOOP, BATCH_CENTRED):  # a single run at the centre; a batch all centred
        text = source(rk4, _problem((0.0, 0.0, 0.0)), "motor", form)[0]
        assert "import centred_accel as " in text and "import centred_centre_of_mass as " in text
    offset = source(rk4, _problem((0.0, 0.15, 0.0)), "motor", LOOP)[0]
    assert "import accel as o_motion" in offset and "centred" not in offset
    batch = source(rk4, _problem((0.0, 0.0, 0.0)), "motor", BATCH)[0]  # own s per body
    assert "import accel as _c_o_motion" in batch and "centred" not in batch


def _starts(n, s, seed):
    rng = np.random.default_rng(seed)
    q = Q.normalize(rng.normal(size=(n, 4)))
    w, p, v = rng.normal(size=(n, 3)) * 5, rng.normal(size=(n, 3)), rng.normal(size=(n, 3))
    starts = [motor_path.initial_state(q[i], p[i], w[i], v[i], s[i]) for i in range(n)]
    return np.array([a for a, _ in starts]), np.array([b for _, b in starts])


@pytest.mark.parametrize("offset", [0.0, 0.15], ids=["all centred", "one body off centre"])
def test_a_batch_is_each_bodys_single_run_bit_for_bit_centred_or_not(offset):
    """All bodies centred: the batch binds the centred kernels, as their single runs do;
    one body off its centre: the general kernels for all, whose numbers at s = 0 are the
    centred kernels' (the first test)."""
    s = np.zeros((3, 3))
    s[2, 1] = offset
    x0, r0 = _starts(3, s, 7)
    problems = [_problem(tuple(row)) for row in s]
    batch = Batch(problems[0], np.array([p.body for p in problems]))
    run = get("rk4").run(batch, "motor", x0, r0, 0.0, 1e-3, 40, [40], parallel=False)
    for i, problem in enumerate(problems):
        one = get("rk4").run(problem, "motor", x0[i], r0[i], 0.0, 1e-3, 40, 40)
        assert np.array_equal(one.x[-1], run.x[-1, i]) and np.array_equal(one.w[-1], run.w[-1, i])
