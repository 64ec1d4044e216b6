"""Verify the algebra symbolically and audit the source documents equation by equation.

Derives, exactly in SymPy, what the numeric package relies on (Hamilton's product from
Cl(0,2) and Cl⁺(3,0), the rotor sandwich and its matrix, the kinematics, Euler angles)
and checks every numbered equation of the paper and every formula of the notes against
it. Prints one verdict per equation: correct / convention (correct under a stated
convention) / WRONG, then the wrong ones with corrected forms.

Exit status: 0 when every derivation the numeric package depends on holds (wrong
equations in the sources are findings, not failures); 1 when one of them fails, or when
--check finds the Markdown page out of date.

Examples:
  ga-rotors verify                       # the table
  ga-rotors verify --details 12 N9       # full accounts of eq. (12) and notes N9
  ga-rotors verify --derivations         # every derivation's report
  ga-rotors verify --write docs/audit.md # regenerate the documentation page
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--details",
        nargs="+",
        metavar="LABEL",
        default=[],
        help="print the full account of these equations: 12 or '(12)', N9, '(19) singular set'",
    )
    parser.add_argument(
        "--derivations", action="store_true", help="print the report of every derivation"
    )
    parser.add_argument(
        "--write",
        metavar="PATH",
        type=Path,
        help="write the audit as Markdown (the project's docs/audit.md)",
    )
    parser.add_argument(
        "--check",
        metavar="PATH",
        type=Path,
        help="exit 1 if PATH differs from the Markdown the audit generates",
    )


def run(args: argparse.Namespace) -> int:
    from ..errors import InputError
    from ..files import write_text

    for path in (args.write, args.check):
        if path is not None and not path.resolve().parent.is_dir():
            raise InputError(f"{path}: expected a path in an existing directory")
    if args.check is not None and not args.check.is_file():
        raise InputError(f"--check {args.check}: no such file")

    from ..symbolic.audit import run_audit

    start = time.perf_counter()
    audit = run_audit()
    elapsed = time.perf_counter() - start

    for label in args.details:
        try:
            finding = audit.find(label)
        except KeyError:
            known = ", ".join(f.label for f in audit.findings)
            raise InputError(
                f"--details {label!r}: no such equation; known labels: {known}"
            ) from None
        print(finding.report())
        print()
    if args.derivations:
        for d in audit.derivations:
            print(d.report())
            print()
    if not args.details and not args.derivations:
        print(audit.table())
        print(f"\naudit computed in {elapsed:.1f} s")

    status = 0
    if not audit.ok:
        print(
            "ga-rotors verify: a derivation the numeric package depends on FAILED", file=sys.stderr
        )
        status = 1
    elif audit.failed_checks():
        print(
            "ga-rotors verify: warning: a derivation failed (not one the numeric package uses)",
            file=sys.stderr,
        )
    if args.write is not None:
        try:
            write_text(args.write, audit.markdown())
        except OSError as exc:  # a folder we may not write in (/proc, read-only), a full disk
            raise InputError(f"--write {args.write}: cannot write it ({exc.strerror})") from None
        print(f"wrote {args.write}")
    if args.check is not None:
        if args.check.read_text(encoding="utf-8") != audit.markdown():
            print(
                f"ga-rotors verify: {args.check} is out of date; regenerate it with "
                f"'ga-rotors verify --write {args.check}'",
                file=sys.stderr,
            )
            status = 1
    return status
