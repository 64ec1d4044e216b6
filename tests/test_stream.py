"""Streamed runs: a run in pieces equals the one-shot run bit for bit (every integrator,
every path, free, torqued by a torque of time, kinematic, stopped paths)."""

import warnings

import numpy as np
import pytest
from _torques_for_tests import turning_torque, wobble

from ga_rotors import quaternion as Q
from ga_rotors import shapes
from ga_rotors.integrators import PrescribedOmega, TorqueTerm, catalogue, get
from ga_rotors.simulation import simulate, simulate_chunks

BODY = (1.0, 2.0, 3.0)
Q0 = Q.from_axis_angle([0.3, 1.0, 0.2], 0.7)
W0 = (0.4, -0.2, 2.0)
# 60 steps sampled every 7 (the last sample is off the pattern), pieces of 14 steps
RUN = dict(duration=0.6, step=0.01, sample_every=7)


def _same(one, pieces):
    """The pieces joined are the one-shot trajectory, every array bit for bit."""
    assert set(pieces[0].names) == set(one.names)
    for name in one.names:
        joined = np.concatenate([p[name] for p in pieces])
        assert joined.shape == one[name].shape, name
        assert (joined == one[name]).all() or np.array_equal(joined, one[name], equal_nan=True), (
            name,
            np.abs(joined - one[name]).max(),
        )
    assert pieces[-1].meta == one.meta


def _both(*args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        one = simulate(*args, **RUN, **kwargs)
        pieces = list(simulate_chunks(*args, **RUN, chunk_steps=14, **kwargs))
    return one, pieces, caught


def _methods(problem):
    return [row["name"] for row in catalogue() if problem in get(row["name"]).problems]


@pytest.mark.parametrize("method", _methods("free"))
def test_pieces_equal_one_run_free(method):
    paths = sorted(get(method).paths & {"rotor", "quaternion", "euler"})
    one, pieces, _ = _both(BODY, Q0, W0, paths=paths, integrator=method,
                           outputs=("energy", "L", "L_space", "angles"))  # fmt: skip
    assert len(pieces) == 5  # 60 steps in pieces of 14
    _same(one, pieces)


@pytest.mark.parametrize("method", _methods("torqued"))
def test_pieces_equal_one_run_with_a_torque_of_time(method):
    """The torque reads t: a piece sees exactly the times the one-shot run sees."""
    paths = sorted(get(method).paths & {"rotor", "quaternion", "euler"})
    torque = TorqueTerm(turning_torque, (0.5, 3.0), depends_on_omega=False)
    one, pieces, _ = _both(BODY, Q0, W0, paths=paths, integrator=method, torques=(torque,),
                           t0=0.3)  # fmt: skip
    _same(one, pieces)


@pytest.mark.parametrize("method", _methods("kinematic"))
def test_pieces_equal_one_run_kinematic(method):
    paths = sorted(get(method).paths & {"rotor", "quaternion", "euler"})
    omega = PrescribedOmega(wobble, (0.3, 2.0, 1.5))
    one, pieces, _ = _both(None, Q0, omega, paths=paths, integrator=method, t0=0.1)
    _same(one, pieces)


@pytest.mark.parametrize("method", ["rk4", "dop853"])
def test_pieces_of_a_path_that_stops_early(method):
    """The Euler-angle path started at its singularity stops; the others go on."""
    q0 = Q.from_axis_angle([0.0, 1.0, 0.0], 0.0)
    one, pieces, caught = _both(shapes.disk(2.0, 0.075), q0, (0.02, 0.03, 15.7),
                                paths=("rotor", "euler"), integrator=method,
                                euler_angles=(0.0, 0.0, 0.0))  # fmt: skip
    assert not one.meta["paths"]["euler"]["complete"]
    assert len(caught) == 2  # one warning each: one run, one run in pieces
    _same(one, pieces)


def test_pieces_report_progress_to_the_end():
    seen = []
    list(simulate_chunks(BODY, Q0, W0, **RUN, chunk_steps=14, paths=("rotor", "quaternion"),
                         progress=lambda done, total: seen.append((done, total))))  # fmt: skip
    assert seen[-1] == (120, 120) and seen == sorted(seen)


def test_chunk_steps_is_checked():
    from ga_rotors.errors import InputError

    with pytest.raises(InputError, match="chunk_steps"):
        simulate_chunks(BODY, Q0, W0, **RUN, chunk_steps=0)
    with pytest.raises(InputError, match="not an argument"):
        simulate_chunks(BODY, Q0, W0, **RUN, colour="red")
