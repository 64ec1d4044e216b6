"""A short tour: rotors and quaternions agree, and the hard points stay exact.

Builds random rotations both as Hamilton quaternions (compiled, vectorised) and as rotors
in Cl(3,0) (clifford multivectors), composes and applies them both ways, and prints how
far apart the two paths land; then shows exp/log, matrix conversion and Euler angles at
the points where textbook formulas break (angle 0, tiny angles, half-turns, gimbal lock).
"""

from __future__ import annotations

import argparse

__all__ = ["add_arguments", "run"]

#: Most random pairs ``--count`` takes: each goes through clifford, a few ms apiece.
MAX_COUNT = 100_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--count", type=int, default=200, help="random rotations to compare (default 200)"
    )
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")


def run(args: argparse.Namespace) -> int:
    import math
    import warnings

    import numpy as np

    from .. import euler, rotor
    from .. import quaternion as Q
    from ..errors import GimbalLockWarning, InputError

    if args.count < 1:
        raise InputError(f"--count: expected a positive number of rotations, got {args.count}")
    if args.count > MAX_COUNT:  # each pair goes through clifford in Python, one at a time
        raise InputError(f"--count: at most {MAX_COUNT} rotations (a tour), got {args.count}")
    if args.seed < 0:
        raise InputError(f"--seed: expected an integer ≥ 0, got {args.seed}")
    rng = np.random.default_rng(args.seed)
    p = Q.normalize(rng.normal(size=(args.count, 4)))
    q = Q.normalize(rng.normal(size=(args.count, 4)))
    v = rng.normal(size=(args.count, 3))

    print("ga_rotors demo: rotors in Cl(3,0) and Hamilton quaternions\n")
    print("convention: q = (w, x, y, z) ↦ R = w − x e23 − y e31 − z e12, v ↦ q v q* = R v R̃")
    R = rotor.from_axis_angle([0.0, 0.0, 1.0], math.pi / 2)
    print(f"  quarter-turn about z:  q = {np.round(rotor.to_quaternion(R), 6)},  R = {R}")
    print(f"  R e1 R̃ = {(R * rotor.layout().blades['e1'] * ~R).clean(1e-15)}\n")

    pq = Q.multiply(p, q)
    rotated = Q.rotate(pq, v)
    compose_gap = sandwich_gap = 0.0
    for k in range(args.count):
        Rk = rotor.compose(rotor.from_quaternion(p[k]), rotor.from_quaternion(q[k]))
        compose_gap = max(compose_gap, Q.distance(rotor.to_quaternion(Rk), pq[k]))
        sandwich_gap = max(sandwich_gap, float(np.abs(rotor.apply(Rk, v[k]) - rotated[k]).max()))
    print(f"{args.count} random pairs, composed and applied both ways:")
    print(f"  largest angle between R1 R2 and q1 q2:        {compose_gap:.2e} rad")
    print(f"  largest difference of R v R̃ and q v q*:       {sandwich_gap:.2e}\n")

    print("exp/log of rotors at the hard points (rotation angle in, angle out):")
    e12 = rotor.layout().blades["e12"]
    for angle in (0.0, 1e-300, 1e-9, math.pi - 1e-12, math.pi):
        back = float(-2.0 * rotor.log(rotor.exp(-0.5 * angle * e12)).value[4])
        print(f"  {angle!r:>22} -> {back!r}")
    print(f"  log(−1) = {rotor.log(-1.0 + 0.0 * e12)}  (z axis: a documented choice)\n")

    print("matrix → quaternion at a half-turn (trace −1, where dividing by 4 q0 fails):")
    half = Q.from_axis_angle([1.0, 2.0, 2.0], math.pi)
    back = Q.from_matrix(Q.to_matrix(half))
    print(
        f"  {np.round(half, 15)} -> {np.round(back, 15)}, error {Q.distance(half, back):.1e} rad\n"
    )

    print("Euler angles at gimbal lock (paper's ZYZ with nutation 0; aerospace ZYX, pitch 90°):")
    for seq, angles in (("ZYZ", [0.3, 0.0, 0.5]), ("ZYX", [0.4, math.pi / 2, 0.3])):
        locked_q = euler.to_quaternion(seq, angles)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", GimbalLockWarning)
            got, locked = euler.from_quaternion(locked_q, seq, return_gimbal=True)
        error = Q.distance(euler.to_quaternion(seq, got), locked_q)
        print(f"  {seq} {np.round(angles, 6)} -> {np.round(got, 6)}, locked={locked}, "
              f"rotation error {error:.1e} rad")  # fmt: skip
    print("\nmore: docs/rotations.md (API tour), docs/conventions.md (every convention)")
    return 0
