"""Foundation benchmark: quaternion products and vector rotations, ga_rotors against peers.

Run from the repository root::

    python benchmarks/bench_foundation.py            # n = 10**6 batched items
    python benchmarks/bench_foundation.py --n 100000 --repeats 5

Measured side by side in one process, after a warm-up, taking the minimum of repeats (the
machine is shared; the minimum is the least disturbed run): ns per operation, and each
peer's time as a ratio to ga_rotors'. Peers that are not installed are skipped with a
notice: numpy-quaternion, quaternionic, scipy's Rotation, clifford (object level).

* single: one product / one vector rotation through each library's Python-level API;
* batched: n pairwise products (p[k] ⊗ q[k]) and n pairwise rotations (q[k] v[k] q[k]*),
  with allocation of the output included for everyone. numpy-quaternion and quaternionic
  rotate pairwise through the sandwich q v q̄ (their ``rotate`` methods form all
  quaternion × vector pairs); clifford has no batched API, so its object-level loop is
  timed on min(n, 10**4) items and reported per item.

Also measured in fresh subprocesses: ``import ga_rotors.quaternion``, the first call of
``multiply`` with numba's on-disk cache present (cold start of a user's process), and the
same with an empty cache (the one-off compile after installation).
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ga_rotors import quaternion as Q  # noqa: E402


def race(candidates, repeats: int, number: int = 1) -> list[tuple[str, float, str]]:
    """Time every candidate once per round, ``repeats`` rounds, after one warm-up call each.

    Rounds interleave the libraries, so load from other processes on this shared machine
    hits them alike; each candidate's minimum over rounds is kept. ``candidates`` holds
    (name, fn, items per call, note); the result is ns per item.
    """
    for _, fn, _, _ in candidates:
        fn()
    times = [[] for _ in candidates]
    for _ in range(repeats):
        for k, (_, fn, _, _) in enumerate(candidates):
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            times[k].append((time.perf_counter() - t0) / number)
    return [
        (name, 1e9 * min(t) / items, note)
        for (name, _, items, note), t in zip(candidates, times, strict=True)
    ]


def have(module: str) -> bool:
    found = importlib.util.find_spec(module) is not None
    if not found:
        print(f"notice: peer {module!r} is not installed; its rows are skipped")
    return found


def report(title: str, rows: list[tuple[str, float, str]]) -> None:
    ours = rows[0][1]
    print(f"\n{title}")
    print(f"  {'library':<36} {'ns/op':>10} {'vs ga_rotors':>13}")
    for name, ns, note in rows:
        print(f"  {name:<36} {ns:10.1f} {ns / ours:12.2f}x  {note}")


def single(repeats: int, peers: dict[str, bool]) -> None:
    rng = np.random.default_rng(1)
    p, q = Q.normalize(rng.normal(size=4)), Q.normalize(rng.normal(size=4))
    v = rng.normal(size=3)
    prod = [("ga_rotors quaternion.multiply", lambda: Q.multiply(p, q), 1, "")]
    rot = [("ga_rotors quaternion.rotate", lambda: Q.rotate(q, v), 1, "")]
    if peers["quaternion"]:
        import quaternion as npq

        a, b = npq.quaternion(*p), npq.quaternion(*q)
        prod.append(("numpy-quaternion a * b", lambda: a * b, 1, ""))
        rot.append(("numpy-quaternion rotate_vectors", lambda: npq.rotate_vectors(b, v), 1, ""))
    if peers["quaternionic"]:
        import quaternionic

        qa, qb = quaternionic.array(p), quaternionic.array(q)
        prod.append(("quaternionic a * b", lambda: qa * qb, 1, ""))
        rot.append(("quaternionic q.rotate(v)", lambda: qb.rotate(v), 1, ""))
    if peers["scipy"]:
        from scipy.spatial.transform import Rotation

        ra, rb = Rotation.from_quat(np.roll(p, -1)), Rotation.from_quat(np.roll(q, -1))
        prod.append(("scipy Rotation ra * rb", lambda: ra * rb, 1, ""))
        rot.append(("scipy Rotation.apply", lambda: rb.apply(v), 1, ""))
    if peers["clifford"]:
        from ga_rotors import rotor

        e = rotor.layout().blades
        Ra, Rb = rotor.from_quaternion(p), rotor.from_quaternion(q)
        V = e["e1"] * v[0] + e["e2"] * v[1] + e["e3"] * v[2]
        prod.append(("clifford MultiVector Ra * Rb", lambda: Ra * Rb, 1, ""))
        prod.append(("ga_rotors rotor.compose (validated)", lambda: rotor.compose(Ra, Rb), 1, ""))
        rot.append(("clifford Rb * V * ~Rb", lambda: Rb * V * ~Rb, 1, ""))
        rot.append(("ga_rotors rotor.apply (validated)", lambda: rotor.apply(Rb, v), 1, ""))
    report("single product, Python level", race(prod, repeats, number=1000))
    report("single vector rotation, Python level", race(rot, repeats, number=1000))


def batched(n: int, repeats: int, peers: dict[str, bool]) -> None:
    rng = np.random.default_rng(2)
    p = Q.normalize(rng.normal(size=(n, 4)))
    q = Q.normalize(rng.normal(size=(n, 4)))
    v = rng.normal(size=(n, 3))
    prod = [("ga_rotors quaternion.multiply", lambda: Q.multiply(p, q), n, "")]
    rot = [("ga_rotors quaternion.rotate", lambda: Q.rotate(q, v), n, "")]
    if peers["quaternion"]:
        import quaternion as npq

        a, b = npq.as_quat_array(p), npq.as_quat_array(q)
        vq = npq.from_vector_part(v)
        assert np.allclose(npq.as_vector_part(b * vq * np.conjugate(b)), Q.rotate(q, v))
        prod.append(("numpy-quaternion a * b", lambda: a * b, n, ""))
        rot.append((
            "numpy-quaternion b * v * b.conj()",
            lambda: npq.as_vector_part(b * vq * np.conjugate(b)),
            n,
            "pairwise sandwich",
        ))  # fmt: skip
    if peers["quaternionic"]:
        import quaternionic

        qa, qb = quaternionic.array(p), quaternionic.array(q)
        qv = quaternionic.array.from_vector_part(v)
        prod.append(("quaternionic a * b", lambda: qa * qb, n, ""))
        rot.append(("quaternionic b * v * b.conj()", lambda: (qb * qv * qb.conj()).vector, n,
                    "pairwise sandwich"))  # fmt: skip
    if peers["scipy"]:
        from scipy.spatial.transform import Rotation

        ra = Rotation.from_quat(np.roll(p, -1, axis=1))
        rb = Rotation.from_quat(np.roll(q, -1, axis=1))
        prod.append(("scipy Rotation ra * rb", lambda: ra * rb, n, ""))
        rot.append(("scipy Rotation.apply", lambda: rb.apply(v), n, ""))
    if peers["clifford"]:
        from ga_rotors import rotor

        m = min(n, 10**4)
        e = rotor.layout().blades
        Ra = [rotor.from_quaternion(x) for x in p[:m]]
        Rb = [rotor.from_quaternion(x) for x in q[:m]]
        V = [e["e1"] * x[0] + e["e2"] * x[1] + e["e3"] * x[2] for x in v[:m]]
        note = f"Python loop over {m} items"
        pairs = list(zip(Ra, Rb, strict=True))
        sandwiches = list(zip(Rb, V, strict=True))
        prod.append(("clifford MultiVector objects", lambda: [x * y for x, y in pairs], m, note))
        rot.append(
            ("clifford MultiVector objects", lambda: [y * w * ~y for y, w in sandwiches], m, note)
        )
    report(f"batched: {n} pairwise products", race(prod, repeats))
    report(f"batched: {n} pairwise vector rotations", race(rot, repeats))


COLD = """
import time
t0 = time.perf_counter()
import numpy as np
import ga_rotors.quaternion as Q
t1 = time.perf_counter()
p, q = np.array([1.0, 0, 0, 0]), np.array([0, 1.0, 0, 0])
Q.multiply(p, q)
t2 = time.perf_counter()
Q.multiply(p, q)
t3 = time.perf_counter()
Q.multiply(p[None], q)
t4 = time.perf_counter()
Q.multiply(p[None], q)
t5 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4)
"""


def cold(repeats: int) -> None:
    def run(env):
        out = subprocess.run(
            [sys.executable, "-c", COLD],
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
        return [float(x) for x in out.stdout.split()]

    base = dict(os.environ)
    warm = [run(base) for _ in range(repeats)]  # numba's cache next to the sources is filled
    import_s = min(w[0] for w in warm)
    first_s = min(w[1] for w in warm)
    second_s = min(w[2] for w in warm)
    batch_first_s = min(w[3] for w in warm)
    batch_second_s = min(w[4] for w in warm)
    with tempfile.TemporaryDirectory() as empty:
        fresh = run({**base, "NUMBA_CACHE_DIR": empty})
    print("\nstart-up (fresh processes, minimum of", repeats, "runs)")
    print(f"  import numpy + ga_rotors.quaternion               {import_s * 1e3:8.1f} ms")
    print(f"  first multiply, numba cache on disk (cold start)  {first_s * 1e3:8.1f} ms")
    print(f"  second multiply (warm)                            {second_s * 1e6:8.1f} µs")
    print(f"  first batched multiply (its loop from the cache)  {batch_first_s * 1e3:8.1f} ms")
    print(f"  second batched multiply (warm)                    {batch_second_s * 1e6:8.1f} µs")
    print(f"  first multiply, empty cache (one-off compile)     {fresh[1] * 1e3:8.1f} ms")
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import ga_rotors"], cwd=ROOT, check=True)
    whole = (time.perf_counter() - t0) * 1e3
    print(f"  python -c 'import ga_rotors' (whole process)      {whole:8.1f} ms")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=10**6, help="batched items (default 10**6)")
    parser.add_argument("--repeats", type=int, default=7, help="repeats; the minimum is reported")
    args = parser.parse_args(argv)
    print(f"numpy {np.__version__}, python {sys.version.split()[0]}, {os.cpu_count()} CPUs")
    peers = {name: have(name) for name in ("quaternion", "quaternionic", "scipy", "clifford")}
    single(args.repeats, peers)
    batched(args.n, args.repeats, peers)
    cold(max(3, args.repeats // 2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
