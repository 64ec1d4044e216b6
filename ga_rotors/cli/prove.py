"""Prove or refute a geometric-algebra identity exactly, in any signature Cl(p,q,r).

Operators: * geometric, ^ outer, | Hestenes inner, & regressive (vee), >> sandwich
(R >> x is R*x*~R), ~ reverse, / division, ** integer power (a**-1 is the inverse). An
expression that Python's precedence (clifford, galgebra, kingdon) and the GA convention
(^ and | before *) read differently is refused with both readings (exit 2): add
parentheses. Every verdict prints the identity as read, fully parenthesised.

Functions: grade(x,k) lc rc inner dot scalar comm rev involute conj even dual undual
exp log inverse norm norm2 vee meet join sandwich up down. Names e1, e12, ... are basis
blades (e0 is the null vector of Cl(p,q,1), as in projective GA), I the pseudoscalar,
eo and einf the null vectors of the conformal model Cl(p,1). --define NAME=EXPR names an
expression for the identity to use (repeat it; each may use the earlier ones).

Exit status: 0 proved, 1 refuted (the counterexample is printed), 2 bad input (one
line naming what is wrong), 3 undecided (the reason is printed). With --catalogue: 0
when every identity of the catalogue comes out as expected, 1 otherwise (or when
--check finds the page out of date).

Examples:
  ga-rotors prove "(a^b)|c == a*(b|c) - b*(a|c)" --signature 3,0 --vectors a,b,c
  ga-rotors prove "R*v*~R == grade(R*v*~R, 1)" --signature 3,0,1 --rotors R --vectors v
  ga-rotors prove "B*B == grade(B*B, 0)" --signature 1,3 --bivectors B     # refuted
  ga-rotors prove "-n*a*n == a - 2*(a|n)*n" --units n --vectors a
  ga-rotors prove "a*b == -(b*a)" --vectors a,b --orthogonal a,b
  ga-rotors prove "c == 0" --signature 1,0,1 --vectors a,c --orthogonal a,c  # refuted
  ga-rotors prove "a*inverse(a) == 1" --signature 1,3 --vectors a
  ga-rotors prove "M >> (P & Q) == (M >> P) & (M >> Q)" --signature 3,0,1 --motors M --points P,Q
  ga-rotors prove "(M >> L)^(M >> L) == 0" --signature 3,0,1 --motors M --lines L
  ga-rotors prove "T >> up(x) == up(x+t)" --signature 4,1 --euclidean x,t --define T=1+einf*t/2
  ga-rotors prove "exp(log(R)) == R" --rotors R
  ga-rotors prove "B*~B == grade(B*~B, 0)" --signature 4,1 --blades B:3 --latex
  ga-rotors prove "(X*Y)**6*X == X*(Y*X)**6" --signature 4,1 --evens X,Y --timeout 1  # undecided
  ga-rotors prove --catalogue --write docs/identities.md
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

__all__ = ["add_arguments", "run"]

_NAME_OPTIONS = (
    ("scalars", "real numbers"),
    ("vectors", "vectors"),
    ("euclidean", "vectors of the base space (e1..e(p-1) of the conformal Cl(p,1))"),
    ("units", "vectors with v*v == 1"),
    ("nulls", "vectors with v*v == 0"),
    ("bivectors", "grade-2 elements"),
    ("points", "projective GA points: grade n-1 in Cl(p,q,1)"),
    ("lines", "projective GA lines: (n-2)-blades in Cl(p,q,1)"),
    ("evens", "even-grade elements"),
    ("rotors", "rotors: even versors with R*~R == 1"),
    ("motors", "motors: the rotors of Cl(p,q,1)"),
    ("multivectors", "general multivectors"),
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("identity", nargs="?", help='"lhs == rhs" (quote it for the shell)')
    parser.add_argument(
        "--signature",
        default="3,0",
        metavar="P,Q[,R]",
        help="p vectors square to +1, q to -1, r to 0 (default 3,0)",
    )
    for option, what in _NAME_OPTIONS:
        parser.add_argument(
            f"--{option}", action="append", default=[], metavar="NAMES", help=f"{what}: a,b,..."
        )
    parser.add_argument(
        "--kvectors", action="append", default=[], metavar="NAME:K", help="grade-k elements"
    )
    parser.add_argument(
        "--blades",
        action="append",
        default=[],
        metavar="NAME:K",
        help="simple k-vectors (wedges of k vectors)",
    )
    parser.add_argument(
        "--orthogonal",
        action="append",
        default=[],
        metavar="A,B",
        help="two vectors with A|B == 0 (repeat for more pairs)",
    )
    parser.add_argument(
        "--define",
        action="append",
        default=[],
        metavar="NAME=EXPR",
        help="a name for an expression the identity uses (repeat for more)",
    )
    parser.add_argument("--draws", type=int, default=16, help="random draws of the pre-check")
    parser.add_argument("--seed", type=int, default=0, help="seed of the draws")
    parser.add_argument(
        "--timeout",
        type=float,
        default=300.0,
        metavar="SECONDS",
        help="give up (undecided, exit 3) after this long (default 300; inf: no limit)",
    )
    parser.add_argument("--latex", action="store_true", help="print the verdict as LaTeX")
    catalogue = parser.add_argument_group("catalogue")
    catalogue.add_argument(
        "--catalogue",
        action="store_true",
        help="prove the identity catalogue (instead of an identity)",
    )
    catalogue.add_argument(
        "--long", action="store_true", help="also the n = 5 signatures (slow: minutes)"
    )
    catalogue.add_argument(
        "--only", action="append", default=[], metavar="KEY", help="only these catalogue keys"
    )
    catalogue.add_argument(
        "--write", type=Path, metavar="PATH", help="write the catalogue page (Markdown)"
    )
    catalogue.add_argument(
        "--check",
        type=Path,
        metavar="PATH",
        help="exit 1 if PATH differs (times aside) from the page the run generates",
    )


def _declarations(args: argparse.Namespace) -> dict:
    kinds: dict = {option: ",".join(getattr(args, option)) for option, _ in _NAME_OPTIONS}
    kinds["kvectors"] = ",".join(args.kvectors)
    kinds["blades"] = ",".join(args.blades)
    kinds["orthogonal"] = list(args.orthogonal)
    return kinds


def _catalogue(args: argparse.Namespace) -> int:
    from ..errors import InputError
    from ..files import write_text
    from ..symbolic.prover.catalogue import (
        CATALOGUE,
        LONG_SIGNATURES,
        QUICK_SIGNATURES,
        markdown,
        run_catalogue,
        strip_times,
    )
    from ..symbolic.prover.grammar import shorten

    for path in (args.write, args.check):
        if path is not None and not path.resolve().parent.is_dir():
            raise InputError(f"{shorten(str(path))}: expected a path in an existing directory")
    if args.check is not None and not args.check.is_file():
        raise InputError(f"--check {shorten(str(args.check))}: no such file")
    known = {e.key for e in CATALOGUE}
    for key in args.only:
        if key not in known:
            raise InputError(f"--only {shorten(key)!r}: no such catalogue key")
    signatures = QUICK_SIGNATURES + (LONG_SIGNATURES if args.long else ())

    def show(r):
        flag = "" if r.as_expected else "   <-- NOT AS EXPECTED"
        print(
            f"{r.identity.key:28} {r.signature:10} {r.verdict.status:9} "
            f"{r.verdict.seconds * 1000:9.1f} ms{flag}",
            flush=True,
        )

    start = time.perf_counter()
    results = run_catalogue(signatures, keys=set(args.only) or None, progress=show)
    bad = [r for r in results if not r.as_expected]
    print(
        f"{len(results)} verdicts in {time.perf_counter() - start:.1f} s; "
        f"{len(bad)} not as expected"
    )
    command = "ga-rotors prove --catalogue" + (" --long" if args.long else "")
    status = 1 if bad else 0
    if args.write is not None:
        write_text(args.write, markdown(results, command + f" --write {args.write}"))
        print(f"wrote {args.write}")
    if args.check is not None:
        page = args.check.read_text(encoding="utf-8")
        fresh = markdown(results, command + f" --write {args.check}")
        if strip_times(page) != strip_times(fresh):
            print(
                f"ga-rotors prove: {args.check} is out of date; regenerate it with "
                f"'{command} --write {args.check}'",
                file=sys.stderr,
            )
            status = 1
    return status


def run(args: argparse.Namespace) -> int:
    from ..errors import InputError

    if args.catalogue:
        if args.identity is not None:
            raise InputError("give either an identity or --catalogue, not both")
        return _catalogue(args)
    if args.identity is None:
        raise InputError('prove: give an identity "lhs == rhs" (or --catalogue)')
    if args.write is not None or args.check is not None or args.long or args.only:
        raise InputError("--write, --check, --long and --only go with --catalogue")
    from ..symbolic.prover.prove import MAX_DRAWS, prove

    if not 1 <= args.draws <= MAX_DRAWS:  # named as the option here; prove() checks it too
        raise InputError(f"--draws: expected an integer from 1 to {MAX_DRAWS}, got {args.draws}")
    if args.seed < 0:
        raise InputError(f"--seed: expected an integer ≥ 0, got {args.seed}")
    if not args.timeout > 0:  # nan too; inf is no limit
        raise InputError(f"--timeout: expected a positive number of seconds, got {args.timeout}")

    try:
        verdict = prove(
            args.identity,
            signature=args.signature,
            draws=args.draws,
            seed=args.seed,
            timeout=args.timeout,
            define=args.define or None,
            **_declarations(args),
        )
    except ValueError as exc:
        raise InputError(f"prove: {exc}") from None
    print(verdict._repr_latex_() if args.latex else verdict.report())
    return verdict.exit_code
