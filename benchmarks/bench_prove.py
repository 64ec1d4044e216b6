"""The identity catalogue side by side with galgebra and kingdon, in one run.

Usage::

    python benchmarks/bench_prove.py [--signatures 3,0 1,3 4,1] [--timeout 20] [--repeats 3]

For every catalogue identity the peers can state (symbols of a linear kind — scalar,
vector, bivector, k-vector, even, multivector — or blades built as wedges of vectors;
no rotor, unit, null or orthogonality assumption, no definition, no exp, dual, inverse,
vee, sandwich or projective and conformal vocabulary, no basis-blade names),
in each signature, three deciders run interleaved on the same identity:

* ``ga_rotors.symbolic.prover.prove`` (numeric pre-check, exact proof or exact counterexample);
* galgebra: symbolic multivectors (``Ga.mv``), lhs − rhs, ``sympy.expand`` of the result;
* kingdon: symbolic multivectors (``Algebra.vector(name=...)`` ...), lhs − rhs,
  ``sympy.expand`` of every coefficient.

Each peer decides "zero" or "not zero", which must agree with our proved / refuted
(a disagreement is printed and the identity left out of the totals). Times are CPU
seconds of this process (``time.process_time``: the machine is shared, and CPU time is
what a decider costs); each decider runs ``--repeats`` times when a run takes under 1 s
(median, min–max shown), once otherwise. A peer that passes ``--timeout`` seconds is
stopped and counted as the timeout (a lower bound, which favours the peer).

Goal (issue 15): the total over the identities all three decide ≥ 3× faster than the
faster peer. galgebra's ``|`` is the Hestenes inner product like ours; kingdon's ``|``
is the "fat dot" (scalars included), so ours is stated for kingdon as
``(x − ⟨x⟩₀) | (y − ⟨y⟩₀)``.
"""

from __future__ import annotations

import argparse
import signal
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ga_rotors.symbolic.prover.basis import cached_basis  # noqa: E402
from ga_rotors.symbolic.prover.catalogue import CATALOGUE  # noqa: E402
from ga_rotors.symbolic.prover.grammar import (  # noqa: E402
    RESERVED_NAMES,
    Binary,
    Call,
    Name,
    Number,
    Unary,
    names_in,
    parse_identity,
)
from ga_rotors.symbolic.prover.prove import prove  # noqa: E402

PEER_KINDS = {"scalars", "vectors", "bivectors", "kvectors", "evens", "multivectors", "blades"}
PEER_FUNCTIONS = {"grade", "lc", "rc", "inner", "scalar", "comm", "rev", "involute", "conj", "even"}


class Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise Timeout


PEER_OPERATORS = {"+", "-", "*", "^", "|"}  # and "/" by a number


def statable(entry) -> bool:
    if set(entry.kinds) - PEER_KINDS or entry.define:
        return False
    lhs, rhs = parse_identity(entry.identity)
    names = names_in(lhs) | names_in(rhs)
    if any(n in RESERVED_NAMES or (n[0] == "e" and n[1:].isdigit()) for n in names):
        return False

    def ok(node):
        if isinstance(node, Call):
            return node.name in PEER_FUNCTIONS and all(ok(a) for a in node.args)
        if isinstance(node, Unary):
            return ok(node.operand)
        if isinstance(node, Binary):
            by_number = node.op == "/" and isinstance(node.right, Number)
            return (node.op in PEER_OPERATORS or by_number) and ok(node.left) and ok(node.right)
        return True

    return ok(lhs) and ok(rhs)


# -- the peers: the same tree, evaluated with their multivectors -------------------------------
class Peer:
    name = ""

    def symbols(self, kinds, sig):
        raise NotImplementedError

    def run(self, entry, sig) -> bool:
        """True when the peer finds lhs − rhs = 0."""
        import sympy

        env = self.symbols(entry.kinds, sig)
        lhs, rhs = parse_identity(entry.identity)

        def ev(node):
            if isinstance(node, Number):
                return sympy.Rational(node.value.numerator, node.value.denominator)
            if isinstance(node, Name):
                return env[node.name]
            if isinstance(node, Unary):
                x = ev(node.operand)
                return {"-": lambda: -x, "+": lambda: x, "~": lambda: self.rev(x)}[node.op]()
            if isinstance(node, Binary):
                a, b = ev(node.left), ev(node.right)
                op = node.op
                if op == "/":
                    return a / b
                if op == "|":
                    return self.inner(a, b)
                return (
                    {"+": a + b, "-": a - b}[op] if op in "+-" else (a * b if op == "*" else a ^ b)
                )
            name, args = node.name, [ev(a) for a in node.args]
            if name == "grade":
                return self.grade(args[0], int(node.args[1].value))
            if name == "comm":
                return (args[0] * args[1] - args[1] * args[0]) / 2
            return getattr(self, name)(*args)

        return self.is_zero(ev(lhs) - ev(rhs))


class Galgebra(Peer):
    name = "galgebra"

    def __init__(self):
        from galgebra.ga import Ga

        self.Ga = Ga

    def symbols(self, kinds, sig):
        p, q, r = sig
        n = p + q + r
        names = "e*" + "|".join(str(i) for i in range(1, n + 1))
        ga, *_ = self.Ga.build(names, g=[0] * r + [1] * p + [-1] * q)
        env = {}
        simple = {
            "scalars": "scalar",
            "vectors": "vector",
            "bivectors": "bivector",
            "evens": "spinor",
            "multivectors": "mv",
        }
        for kind, value in kinds.items():
            if kind in simple:
                for name in value.split(","):
                    env[name.strip()] = ga.mv(name.strip(), simple[kind])
            elif kind == "kvectors":
                for name, k in value.items():
                    env[name] = ga.mv(name, "grade", k)
            elif kind == "blades":
                for name, k in value.items():
                    blade = ga.mv(f"{name}_1", "vector")
                    for j in range(2, k + 1):
                        blade = blade ^ ga.mv(f"{name}_{j}", "vector")
                    env[name] = blade
        return env

    def inner(self, a, b):
        return a | b

    def lc(self, a, b):
        return a < b

    def rc(self, a, b):
        return a > b

    def scalar(self, a, b):
        return (a * b).get_grade(0)

    def grade(self, x, k):
        return x.get_grade(k)

    def rev(self, x):
        return x.rev()

    def involute(self, x):
        return x.g_invol()

    def conj(self, x):
        return x.ccon()

    def even(self, x):
        return x.even()

    def is_zero(self, x):
        import sympy

        return sympy.expand(getattr(x, "obj", x)) == 0


class Kingdon(Peer):
    name = "kingdon"

    def __init__(self):
        from kingdon import Algebra

        self.Algebra = Algebra

    def symbols(self, kinds, sig):
        alg = self.Algebra(*sig)
        env = {}
        for kind, value in kinds.items():
            if kind == "kvectors":
                for name, k in value.items():
                    env[name] = alg.multivector(name=name, grades=(k,))
            elif kind == "blades":
                for name, k in value.items():
                    blade = alg.vector(name=f"{name}1")
                    for j in range(2, k + 1):
                        blade = blade ^ alg.vector(name=f"{name}{j}")
                    env[name] = blade
            else:
                grades = {
                    "scalars": (0,),
                    "vectors": (1,),
                    "bivectors": (2,),
                    "evens": tuple(range(0, sum(sig) + 1, 2)),
                    "multivectors": tuple(range(sum(sig) + 1)),
                }[kind]
                for name in value.split(","):
                    env[name.strip()] = alg.multivector(name=name.strip(), grades=grades)
        return env

    def inner(self, a, b):
        # ours is Hestenes's (no scalar factors); kingdon's | keeps them
        return (a - a.grade(0)) | (b - b.grade(0))

    def lc(self, a, b):
        return a.lc(b)

    def rc(self, a, b):
        return a.rc(b)

    def scalar(self, a, b):
        return (a * b).grade(0)

    def grade(self, x, k):
        return x.grade(k)

    def rev(self, x):
        return ~x

    def involute(self, x):
        return x.involute()

    def conj(self, x):
        return x.conjugate()

    def even(self, x):
        return x.grade(*range(0, x.algebra.d + 1, 2))

    def is_zero(self, x):
        import sympy

        if not hasattr(x, "values"):
            return sympy.expand(x) == 0
        return all(sympy.expand(v) == 0 for v in x.values())


def measure(f, repeats: int, timeout: float):
    """(median, min, max) CPU seconds and f's last result; None for a timeout."""
    times, result = [], None
    for i in range(repeats):
        signal.signal(signal.SIGALRM, _alarm)
        signal.setitimer(signal.ITIMER_REAL, timeout)
        t = time.process_time()
        try:
            result = f()
        except Timeout:
            return None, None
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        times.append(time.process_time() - t)
        if i == 0 and times[0] > 1.0:
            break
    return (statistics.median(times), min(times), max(times)), result


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--signatures", nargs="+", default=["3,0", "1,3", "4,1"])
    parser.add_argument("--timeout", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only", nargs="*", default=None)
    args = parser.parse_args(argv)
    peers = []
    for cls in (Galgebra, Kingdon):
        try:
            peers.append(cls())
        except ImportError:
            print(f'{cls.name} is not installed (pip install "ga-rotors[peers]"); skipped')
    entries = [e for e in CATALOGUE if statable(e) and (not args.only or e.key in args.only)]
    print(f"{len(entries)} of {len(CATALOGUE)} catalogue identities can be stated by the peers")
    print(
        "CPU seconds, median (min–max) of up to "
        f"{args.repeats} runs; '>' marks a timeout at {args.timeout:g} s"
    )
    totals = {"ours": 0.0, **{p.name: 0.0 for p in peers}}
    bounds = dict(totals)
    header = f"{'identity':28} {'signature':9} {'ours':>24}" + "".join(
        f" {p.name:>24}" for p in peers
    )
    print(header)
    disagreements = []
    for text in args.signatures:
        sig = tuple(int(x) for x in text.split(",")) + (0,) * (3 - len(text.split(",")))
        for entry in entries:
            if not entry.applies(cached_basis(*sig)):
                continue
            ours, verdict = measure(
                lambda e=entry, s=sig: prove(e.identity, signature=s, **e.kinds), args.repeats, 1e9
            )
            cells, decided = [ours], True
            for peer in peers:
                timing, zero = measure(
                    lambda e=entry, p=peer, s=sig: p.run(e, s), args.repeats, args.timeout
                )
                if timing is not None and zero != (verdict.status == "proved"):
                    disagreements.append((entry.key, text, peer.name))
                    timing = None
                    decided = False
                cells.append(timing)
                if timing is None:
                    decided = False
            row = f"{entry.key:28} {text:9}"
            for timing in cells:
                row += (
                    f" {'>' + format(args.timeout, 'g') + ' s':>24}"
                    if timing is None
                    else (f" {timing[0]:9.4f} ({timing[1]:.4f}–{timing[2]:.4f})")
                )
            print(row, flush=True)
            names = ["ours"] + [p.name for p in peers]
            for name, timing in zip(names, cells, strict=True):
                bounds[name] += args.timeout if timing is None else timing[0]
                if decided:
                    totals[name] += timing[0]
    print()
    print(
        "totals over the identities every decider decided (CPU s):",
        ", ".join(f"{k} {v:.2f}" for k, v in totals.items()),
    )
    print(
        "totals with timeouts counted as the timeout (peers' lower bounds):",
        ", ".join(f"{k} {v:.2f}" for k, v in bounds.items()),
    )
    if peers:
        fastest = min(peers, key=lambda p: totals[p.name])
        ratio = totals[fastest.name] / totals["ours"] if totals["ours"] else float("nan")
        print(f"faster peer: {fastest.name}; ours is {ratio:.1f}x faster (goal: >= 3x)")
    for d in disagreements:
        print("disagreement (left out of the totals):", *d)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
