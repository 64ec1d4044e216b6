"""How long the symbolic audit takes, and how its building blocks compare with SymPy's own.

Usage::

    python benchmarks/bench_symbolic.py [--repeats N]

1. The whole audit (every finding and derivation), cold, in a fresh process each time
   (the audit caches its results per process, so an in-process repeat would time a
   dictionary lookup). One warm-up process first (it writes bytecode caches); the
   figure is the minimum over the repeats, because the CPU is shared and noise only ever
   adds time. Goal: under 60 s on a 2-core machine.
2. Peers, measured in the same run, reported as ratios:
   * deciding a z-y-z trigonometric identity: symbolic.trig.is_identity vs
     sympy.trigsimp(lhs - rhs) == 0;
   * the Hamilton product of two symbolic quaternions: symbolic.hamilton.mul vs
     sympy.algebras.Quaternion.__mul__;
   * rotating a symbolic vector: the Cl(3,0) rotor sandwich R v R̃ (symbolic.algebra)
     vs sympy.algebras.Quaternion.rotate_point.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

COLD = (
    "import time; t = time.perf_counter(); c = time.process_time()\n"
    "from ga_rotors.symbolic.audit import run_audit\n"
    "audit = run_audit()\n"
    "assert audit.ok and not audit.failed_checks()\n"
    "print(time.perf_counter() - t, time.process_time() - c)\n"
)


def cold_audit_seconds() -> tuple[float, float]:
    """(wall, CPU) seconds of a whole audit, imports included, in a fresh process."""
    out = subprocess.run(
        [sys.executable, "-c", COLD], cwd=ROOT, capture_output=True, text=True, check=True
    )
    wall, cpu = out.stdout.strip().splitlines()[-1].split()
    return float(wall), float(cpu)


def best(f, repeats: int) -> float:
    f()  # warm-up
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def peers(repeats: int) -> list[tuple[str, float, float]]:
    import sympy
    from sympy.algebras.quaternion import Quaternion

    sys.path.insert(0, str(ROOT))
    from ga_rotors.symbolic import hamilton, rotations, trig
    from ga_rotors.symbolic.isomorphisms import quaternion_to_rotor
    from ga_rotors.symbolic.rotors import vector

    psi, theta, phi = sympy.symbols("psi theta phi", real=True)
    m = hamilton.rotation_matrix(rotations.euler_quaternion("ZYZ", (psi, theta, phi)))
    r = rotations.euler_matrix("ZYZ", (psi, theta, phi))
    lhs, rhs = m[0, 1], r[0, 1]

    q, p = hamilton.symbols("q"), hamilton.symbols("p")
    qq, pp = Quaternion(*q), Quaternion(*p)
    v = sympy.symbols("v1:4", real=True)
    rotor = quaternion_to_rotor(q)

    def ours_trig():
        assert trig.is_identity(lhs, rhs)

    def sympy_trig():
        assert sympy.trigsimp(sympy.expand_trig(lhs - rhs)) == 0

    def ours_mul():
        hamilton.mul(q, p)

    def sympy_mul():
        (qq * pp).a.expand()

    def ours_rotate():
        (rotor * vector(v) * rotor.reverse())

    def sympy_rotate():
        [sympy.expand(c) for c in Quaternion.rotate_point(v, qq)]

    return [
        (
            "z-y-z identity: trig.is_identity vs sympy.trigsimp",
            best(ours_trig, repeats),
            best(sympy_trig, repeats),
        ),
        (
            "Hamilton product: hamilton.mul vs sympy Quaternion",
            best(ours_mul, repeats),
            best(sympy_mul, repeats),
        ),
        (
            "rotate a vector: rotor sandwich vs Quaternion.rotate_point",
            best(ours_rotate, repeats),
            best(sympy_rotate, repeats),
        ),
    ]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="timed repeats (after warm-up)")
    args = parser.parse_args()

    cold_audit_seconds()  # warm-up: bytecode caches
    runs = [cold_audit_seconds() for _ in range(args.repeats)]
    walls, cpus = [w for w, _ in runs], [c for _, c in runs]
    print(
        f"whole audit, cold, fresh process (imports included): wall min {min(walls):.2f} s, "
        f"CPU min {min(cpus):.2f} s over {args.repeats} runs "
        f"(wall: {', '.join(f'{t:.2f}' for t in walls)}); goal < 60 s. CPU time is what "
        "the audit costs; wall time adds whatever else shares the machine."
    )
    print()
    print(f"{'operation':60s} {'ours':>10s} {'peer':>10s} {'peer/ours':>10s}")
    for name, ours, peer in peers(args.repeats):
        print(f"{name:60s} {ours * 1e3:8.2f}ms {peer * 1e3:8.2f}ms {peer / ours:10.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
