"""The identity catalogue: every entry proved where it holds and refuted (with an exact
counterexample) where it does not, nothing undecided, and docs/identities.md current.

The default run covers the n ≤ 4 signatures (a few seconds); GA_ROTORS_LONG=1 adds the
n = 5 signatures (about 1.5 minutes on one core).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from ga_rotors.symbolic.prover.basis import cached_basis
from ga_rotors.symbolic.prover.catalogue import (
    CATALOGUE,
    LONG_SIGNATURES,
    QUICK_SIGNATURES,
    run_catalogue,
)

PAGE = Path(__file__).resolve().parent.parent / "docs" / "identities.md"
LONG = os.environ.get("GA_ROTORS_LONG") == "1"


def test_catalogue_has_at_least_50_distinct_identities_from_the_three_books():
    assert len(CATALOGUE) >= 50
    assert len({e.key for e in CATALOGUE}) == len(CATALOGUE)
    assert len({e.identity + repr(e.kinds) for e in CATALOGUE}) == len(CATALOGUE)
    for book in ("HS", "DL", "DFM"):
        assert sum(book in e.source for e in CATALOGUE) >= 10


def test_catalogue_has_identities_that_fail_somewhere():
    failing = [
        e for e in CATALOGUE if not all(e.expected(cached_basis(*s)) for s in QUICK_SIGNATURES)
    ]
    assert len(failing) >= 6


def _check(results):
    wrong = [(r.identity.key, r.signature, r.verdict.status) for r in results if not r.as_expected]
    assert not wrong
    assert not [r for r in results if r.verdict.status == "undecided"]
    for r in results:
        if r.verdict.status == "refuted":
            ce = r.verdict.counterexample
            assert ce is not None and ce.lhs != ce.rhs


def test_every_identity_decided_as_expected_up_to_n_4():
    _check(run_catalogue(QUICK_SIGNATURES))


@pytest.mark.skipif(not LONG, reason="long mode: set GA_ROTORS_LONG=1 (n = 5, ~1.5 min)")
def test_every_identity_decided_as_expected_at_n_5():
    _check(run_catalogue(LONG_SIGNATURES))


def _table(text):
    rows = [line for line in text.splitlines() if line.startswith("| ")]
    header = [c.strip() for c in rows[0].strip("|").split(" | ")]
    body = {}
    for line in rows[1:]:
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip().strip("|"))]
        body[cells[0]] = cells
    return header, body


def test_identities_page_is_current():
    """The page lists the catalogue as it is, with the expected mark in every cell.

    (The marks were produced by a run; the test above checks that a run gives the
    expected verdicts, so together they keep the page honest without re-running n = 5.)
    """
    stale = (
        "docs/identities.md is stale: run "
        "`ga-rotors prove --catalogue --long --write docs/identities.md`"
    )
    header, body = _table(PAGE.read_text(encoding="utf-8"))
    signatures = QUICK_SIGNATURES + LONG_SIGNATURES
    assert header[5:] == [cached_basis(*s).label() for s in signatures], stale
    assert list(body) == [e.key for e in CATALOGUE], stale
    for entry in CATALOGUE:
        cells = body[entry.key]
        assert cells[1] == "`" + entry.identity.replace("|", "\\|") + "`", stale
        assert cells[3] == entry.where, stale
        for sig, cell in zip(signatures, cells[5:], strict=True):
            basis = cached_basis(*sig)
            if not entry.applies(basis):
                assert cell == "", (entry.key, basis.label(), stale)
            else:
                mark = "✓" if entry.expected(basis) else "✗"
                assert cell.startswith(mark + " ") and "unexpected" not in cell, (
                    entry.key,
                    basis.label(),
                    stale,
                )
