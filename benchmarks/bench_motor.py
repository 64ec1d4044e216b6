"""Motor benchmark: batched products and sandwiches, ga_rotors.motor against the peers a user
would pick for the same job.

Run from the repository root, on a quiet machine::

    python benchmarks/bench_motor.py                    # n = 10**6 items, 9 rounds
    python benchmarks/bench_motor.py --n 100000 --rounds 15
    python benchmarks/bench_motor.py --quick            # n = 2000, 3 rounds: that it runs

Every operation is timed on n pairwise items (motor k with motor or element k), output
allocation included for everyone, each candidate once per round and the rounds interleaved
(load from other processes hits all alike). Printed: ns per item, median (min–max) over
the rounds, and each median's ratio to ga_rotors'. Before timing, every candidate's result
is checked against ga_rotors' (the same numbers, up to each peer's conventions, which are
converted), so a fast wrong answer cannot enter the table.

Peers (skipped with a notice when not installed):

* clifford, compiled: clifford's own way to batch, an ``@numba.njit`` loop over the
  layout's ``gmt_func`` on 16-coefficient value arrays (the sandwich as two products with
  ``adjoint_func`` for the reverse);
* kingdon: multivectors whose coefficients are NumPy arrays of n items (its generated,
  vectorised code; ``M * N``, ``M >> X``);
* scipy ``RigidTransform``: composition ``a * b`` and ``apply`` (matrices inside; it has no
  lines or planes);
* ga_rotors' own quaternion-and-position path (``quaternion.multiply`` and
  ``quaternion.rotate`` plus the translation), the representation motors replace.
"""

from __future__ import annotations

import argparse
import importlib.util
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ga_rotors import motor  # noqa: E402
from ga_rotors import quaternion as Q  # noqa: E402
from ga_rotors._pga import BLADES, LINE, MOTOR, POINT  # noqa: E402


def have(module: str) -> bool:
    found = importlib.util.find_spec(module) is not None
    if not found:
        print(f"notice: peer {module!r} is not installed; its rows are skipped")
    return found


def race(candidates, rounds: int) -> list[tuple[str, list[float]]]:
    """ns per item of each (name, fn, items) candidate: one call per round, interleaved."""
    for _, fn, _ in candidates:
        fn()  # warm-up: compilation, caches
    times: list[list[float]] = [[] for _ in candidates]
    for _ in range(rounds):
        for k, (_, fn, items) in enumerate(candidates):
            t0 = time.perf_counter()
            fn()
            times[k].append(1e9 * (time.perf_counter() - t0) / items)
    return [(name, t) for (name, _, _), t in zip(candidates, times, strict=True)]


def report(title: str, rows) -> None:
    ours = statistics.median(rows[0][1])
    print(f"\n{title}")
    print(f"  {'library':<44} {'ns/item, median (min–max)':>28} {'vs ga_rotors':>13}")
    for name, t in rows:
        med = statistics.median(t)
        cell = f"{med:9.1f} ({min(t):.1f}–{max(t):.1f})"
        print(f"  {name:<44} {cell:>28} {med / ours:12.2f}x")


def _data(n: int, seed: int = 1):
    rng = np.random.default_rng(seed)
    q = Q.normalize(rng.normal(size=(2, n, 4)))
    t = rng.normal(size=(2, n, 3))
    A, B = motor.from_pose(q[0], t[0]), motor.from_pose(q[1], t[1])
    x = rng.normal(size=(n, 3))
    L = motor.line(rng.normal(size=(n, 3)), rng.normal(size=(n, 3)))
    return q, t, A, B, x, L


def _full(a, indices) -> np.ndarray:
    out = np.zeros((a.shape[0], 16))
    out[:, list(indices)] = a
    return out


def clifford_candidates(A, B, P, L):
    """clifford's compiled path: njit loops over gmt_func on (n, 16) value arrays."""
    import numba
    from clifford import pga

    gmt, rev = pga.layout.gmt_func, pga.layout.adjoint_func

    @numba.njit(cache=False)
    def products(a, b, out):
        for i in range(a.shape[0]):
            out[i] = gmt(a[i], b[i])

    @numba.njit(cache=False)
    def sandwiches(m, x, out):
        for i in range(m.shape[0]):
            out[i] = gmt(gmt(m[i], x[i]), rev(m[i]))

    a, b, p, line = _full(A, MOTOR), _full(B, MOTOR), _full(P, POINT), _full(L, LINE)
    out = np.empty_like(a)

    def product():
        o = np.empty_like(a)
        products(a, b, o)
        return o[:, list(MOTOR)]

    def point():
        o = np.empty_like(a)
        sandwiches(a, p, o)
        return o[:, list(POINT)]

    def lines():
        o = np.empty_like(a)
        sandwiches(a, line, o)
        return o[:, list(LINE)]

    del out
    return product, point, lines


def kingdon_candidates(A, B, P, L):
    """kingdon with NumPy-array coefficients (its vectorised generated code)."""
    import kingdon

    alg = kingdon.Algebra(3, 0, 1)
    names = ["e" if b == "1" else b for b in BLADES]

    def mv(values, indices):
        return alg.multivector(**{names[i]: values[:, k] for k, i in enumerate(indices)})

    def coeffs(x, indices):
        return np.stack([np.broadcast_to(getattr(x, names[i]), (A.shape[0],)) for i in indices],
                        axis=1)  # fmt: skip

    ma, mb, mp, ml = mv(A, MOTOR), mv(B, MOTOR), mv(P, POINT), mv(L, LINE)
    return (lambda: coeffs(ma * mb, MOTOR), lambda: coeffs(ma >> mp, POINT),
            lambda: coeffs(ma >> ml, LINE))  # fmt: skip


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=10**6, help="items per call")
    parser.add_argument("--rounds", type=int, default=9, help="interleaved rounds")
    parser.add_argument("--quick", action="store_true", help="n = 2000, 3 rounds")
    args = parser.parse_args(argv)
    n, rounds = (2000, 3) if args.quick else (args.n, args.rounds)
    if not (1 <= n <= 10**8 and 1 <= rounds <= 1000):
        parser.error("--n must be in [1, 1e8] and --rounds in [1, 1000]")
    q, t, A, B, x, L = _data(n)
    P = motor.point(x)
    print(f"python benchmarks/bench_motor.py --n {n} --rounds {rounds}")

    def pose_product():
        return Q.multiply(q[0], q[1]), Q.rotate(q[0], t[1]) + t[0]

    def pose_apply():
        return Q.rotate(q[0], x) + t[0]

    product = [("ga_rotors motor.compose", lambda: motor.compose(A, B), n),
               ("ga_rotors quaternion + position", pose_product, n)]  # fmt: skip
    points = [("ga_rotors motor.apply (Euclidean points)", lambda: motor.apply(A, x), n),
              ("ga_rotors motor.sandwich_point (PGA points)",
               lambda: motor.sandwich_point(A, P), n),
              ("ga_rotors quaternion + position", pose_apply, n)]  # fmt: skip
    lines = [("ga_rotors motor.sandwich_line", lambda: motor.sandwich_line(A, L), n)]

    expected = (motor.compose(A, B), motor.sandwich_point(A, P), motor.sandwich_line(A, L))
    for name, make in (("clifford", clifford_candidates), ("kingdon", kingdon_candidates)):
        if not have(name):
            continue
        fns = make(A, B, P, L)
        for fn, want in zip(fns, expected, strict=True):
            if not np.allclose(fn(), want, rtol=0, atol=1e-10):
                raise SystemExit(f"{name} disagrees with ga_rotors: not timed")
        label = {"clifford": "clifford, njit loop over gmt_func",
                 "kingdon": "kingdon, array coefficients"}[name]  # fmt: skip
        product.append((label, fns[0], n))
        points.append((label, fns[1], n))
        lines.append((label, fns[2], n))
    if have("scipy"):
        from scipy.spatial.transform import RigidTransform, Rotation

        ra = RigidTransform.from_components(t[0], Rotation.from_quat(np.roll(q[0], -1, axis=1)))
        rb = RigidTransform.from_components(t[1], Rotation.from_quat(np.roll(q[1], -1, axis=1)))
        if not (np.allclose((ra * rb).as_matrix(), motor.to_matrix(expected[0]), atol=1e-10)
                and np.allclose(ra.apply(x), motor.apply(A, x), atol=1e-10)):  # fmt: skip
            raise SystemExit("scipy disagrees with ga_rotors: not timed")
        product.append(("scipy RigidTransform a * b", lambda: ra * rb, n))
        points.append(("scipy RigidTransform.apply", lambda: ra.apply(x), n))

    report(f"motor products, n = {n}", race(product, rounds))
    report(f"moving points, n = {n}", race(points, rounds))
    report(f"moving lines, n = {n}", race(lines, rounds))
    return 0


if __name__ == "__main__":
    sys.exit(main())
