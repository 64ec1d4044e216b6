"""The audit: our own derivations hold, each verdict is pinned, the page is current, the
quoted text is verbatim, and `ga-rotors verify` behaves (exit status, errors, files).

The audit is computed once per test session (symbolic.audit.run_audit is cached).
"""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from ga_rotors.cli import main
from ga_rotors.symbolic.audit import Verdict, run_audit
from ga_rotors.symbolic.derivation import Step

ROOT = Path(__file__).resolve().parent.parent

# Pinned verdicts: a change here is a change in what the audit concludes, and must be
# argued in the commit that makes it. C = correct, V = correct under a stated convention,
# W = wrong.
EXPECTED = {
    "(1)": "C",
    "(2)": "C",
    "(3)": "C",
    "(4)": "C",
    "(5)": "C",
    "(6)": "C",
    "(7)": "C",
    "(8)": "C",
    "(9)": "C",
    "(10)": "C",
    "(11)": "C",
    "(12)": "W",
    "(13)": "V",
    "(13) axes": "W",
    "(14)": "W",
    "(15)": "C",
    "(16)": "C",
    "(17)": "C",
    "(18)": "C",
    "(19)": "C",
    "(19) singular set": "W",
    "(20)": "C",
    "(21)": "C",
    "(22)": "C",
    "(23)": "W",
    "(24)": "C",
    "(25)": "C",
    "(26)": "C",
    "(27)": "C",
    "(28)": "C",
    "(29)": "W",
    "(30)": "C",
    "(31)": "C",
    "(32)": "C",
    "(33)": "C",
    "(34)": "C",
    "(35)": "W",
    "(36)": "W",
    "(37)": "C",
    "(38)": "V",
    "(39)": "W",
    "(40)": "V",
    "Δt (§4)": "C",
    "Fig. 5 text": "V",
    "§4 other sequences": "V",
    "(41)": "V",
    "(42)": "C",
    "(43)": "V",
    "(44)": "C",
    "(45)": "W",
    "(46)": "C",
    "(47)": "C",
    "§5 ijk": "C",
    "§5 C₀,ₙ": "C",
    "N1": "C",
    "N2": "C",
    "N3": "C",
    "N4": "C",
    "N5": "C",
    "N6": "C",
    "N7": "C",
    "N8": "C",
    "N9": "W",
    "N10": "C",
    "N11": "C",
    "N12": "C",
    "N13": "C",
    "N14": "C",
    "N15": "W",
    "N16": "V",
    "N17": "W",
    "N18": "C",
    "N19": "C",
    "N20": "V",
}
CODES = {"C": Verdict.CORRECT, "V": Verdict.CONVENTION, "W": Verdict.WRONG}


@pytest.fixture(scope="module")
def audit():
    return run_audit()


def test_every_step_of_our_own_derivations_holds(audit):
    assert audit.failed_checks() == []
    assert audit.ok


def test_every_numbered_paper_equation_is_audited(audit):
    labels = {f.label for f in audit.findings if f.source == "paper"}
    assert {f"({n})" for n in range(1, 48)} <= labels


def test_verdicts_are_the_pinned_ones(audit):
    got = {f.label: f.verdict for f in audit.findings}
    assert got == {label: CODES[c] for label, c in EXPECTED.items()}


def test_wrong_and_conventional_findings_state_the_fix(audit):
    for f in audit.findings:
        if f.verdict is not Verdict.CORRECT:
            assert f.corrected, f.label
        assert f.evidence and f.reading and f.reconstruction, f.label


def test_tested_reading_is_marked_once_where_readings_are_listed(audit):
    for f in audit.findings:
        if f.readings:
            assert sum(r.tested for r in f.readings) == 1, f.label


def _seeds() -> Path | None:
    for parent in ROOT.parents:
        candidate = parent / "shared" / "seeds"
        if candidate.is_dir():
            return candidate
    return None


def test_printed_text_is_quoted_verbatim_from_the_sources(audit):
    seeds = _seeds()
    if seeds is None:
        pytest.skip("the source documents (shared/seeds beside the repository) are not here")
    paper = next(seeds.glob("000_*.txt")).read_text(encoding="utf-8")
    notes = next(seeds.glob("003_*.txt")).read_text(encoding="utf-8")
    for f in audit.findings:
        text = paper if f.source == "paper" else notes
        assert f.printed in text, f"{f.source} {f.label}: printed text not found verbatim"


def _verdict_rows(text: str) -> list[str]:
    """Summary counts and the table's source | equation | topic | verdict columns: the
    parts of the page no SymPy printing enters."""
    rows = [ln for ln in text.splitlines() if ln.startswith(("- **paper**", "- **notes**"))]
    rows += ["|".join(ln.split("|")[:5]) for ln in text.splitlines() if ln.startswith("| paper")]
    rows += ["|".join(ln.split("|")[:5]) for ln in text.splitlines() if ln.startswith("| notes")]
    return rows


@pytest.mark.parametrize("series", ["installed", "another"])
def test_docs_audit_page_is_the_generator_output(audit, series, monkeypatch):
    from ga_rotors.symbolic.audit import markdown

    if series == "another":  # what CI sees if a new SymPy series is released
        monkeypatch.setattr(markdown, "sympy_series", lambda: "0.0")
    page = (ROOT / "docs" / "audit.md").read_text(encoding="utf-8")
    fresh = audit.markdown()
    stale = "docs/audit.md is stale: run `python -m ga_rotors verify --write docs/audit.md`"
    written_with = re.search(r"with SymPy (\d+\.\d+)", page)
    assert written_with, stale
    # Another SymPy series may print the same expressions differently (term order, spacing):
    # then every verdict must still match, and only the printed forms may differ.
    if written_with.group(1) == markdown.sympy_series():
        assert page == fresh, stale
    else:
        assert _verdict_rows(page) == _verdict_rows(fresh), stale
        assert len(_verdict_rows(page)) == 2 + len(audit.findings)


def _page_formulas(page: str) -> list[str]:
    """The inline formulas of a Markdown page, outside code."""
    page = re.sub(r"```.*?```", "", page, flags=re.S)
    page = re.sub(r"`[^`]*`", "", page)
    return re.findall(r"(?<![\\$])\$(?!\$)(.+?)(?<!\\)\$", page)


def test_docs_audit_page_typesets_its_formulas(audit):
    """The page's formulas are LaTeX the site converts (the strict build would fail on one
    that does not); what the source printed stays verbatim, in code; the terminal keeps
    the plain notation."""
    mathml = _site_hook("mathml")
    page = audit.markdown()
    formulas = _page_formulas(page)
    assert len(formulas) > 1000  # every finding has some
    for latex in formulas:
        mathml.to_mathml(latex)  # raises MathError on a formula that does not convert
    f = audit.find("(36)")
    section = page.split('<a id="paper--36"></a>', 1)[1].split("<a id=", 1)[0]
    assert f"- printed (as extracted): `{f.printed}`" in section
    assert r"$\dot{q}_{0} = - \tfrac{1}{2} (q_{1} \omega_{x3} + q_{2} \omega_{y3}" in section
    assert "$" not in audit.table() and "\\" not in audit.table()
    assert "$" not in f.report()


@pytest.mark.parametrize(
    ("plain", "typeset"),
    [
        # indices, accents, powers, the conjugate's star, bars, roots and fractions
        ("q̇0 = −½ q1ωx3", r"$\dot{q}_{0} = - \tfrac{1}{2} q_{1} \omega_{x3}$"),
        ("q⁻¹ = q*/|q|²", r"$q^{-1} = q^{*}/\lvert q\rvert^{2}$"),
        (
            "θ = 2 atan2(√(q1² + q2²), q0)",
            r"$\theta = 2 \operatorname{atan2}(\sqrt{q_{1}^{2} + q_{2}^{2}}, q_{0})$",
        ),
        # the paper's shorthand, axis-indexed names, Cl's upright name, sets and spaces
        ("cψsθ in Rz(ψ)", r"$c_{\psi} s_{\theta}$ in $R_{z}(\psi)$"),
        ("Cl⁺(3,0) ≅ ℍ", r"$\mathrm{Cl}^{+}(3,0) \cong \mathbb{H}$"),
        ("e_A = e_{i1} ⋯ e_{i_k}", r"$e_{A} = e_{i_{1}} \cdots e_{i_{k}}$"),
        # formulas end at prose; numbers and quotations alone are no formula
        ("with i = e1, j = e2 (Fig. 5, 0.44 %)", r"with $i = e_{1}$, $j = e_{2}$ (Fig. 5, 0.44 %)"),
        ("the 'q 2' of (12), i.e. a unit q", r"the 'q 2' of (12), i.e. a unit $q$"),
        ("for all a, b in ℍ", r"for all $a, b$ in $\mathbb{H}$"),
        (
            "ψ in (−π, π] and 1.6E-15 per step",
            r"$\psi$ in $(- \pi, \pi]$ and $1.6 \times 10^{-15}$ per step",
        ),
    ],
)
def test_audit_formulas_are_found_and_written_as_latex(plain, typeset):
    from ga_rotors.symbolic.audit.typeset import mark

    assert mark(plain) == typeset


def _site_hook(name: str):
    """A module of docs/hooks/ (the site's math hook needs the docs extra's latex2mathml)."""
    import importlib.util

    pytest.importorskip("latex2mathml")
    spec = importlib.util.spec_from_file_location(name, ROOT / "docs" / "hooks" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_verdict_rows_ignore_printed_forms_only():
    row = "| paper | [(12)](#paper--12) | rotation matrix | wrong | Qᵀ = x + y |"
    other = "| paper | [(12)](#paper--12) | rotation matrix | wrong | Qᵀ = y + x |"
    flipped = "| paper | [(12)](#paper--12) | rotation matrix | correct | Qᵀ = x + y |"
    assert _verdict_rows(row) == _verdict_rows(other) != _verdict_rows(flipped)


def test_verify_prints_the_table_and_exits_zero(capsys):
    assert main(["verify"]) == 0
    out = capsys.readouterr().out
    assert "  (36)" in out and "WRONG" in out
    assert "wrong, with corrected forms:" in out
    assert "checked steps hold" in out and "FAILED" not in out


def test_verify_details_accepts_bare_numbers(capsys):
    assert main(["verify", "--details", "39", "n9"]) == 0
    out = capsys.readouterr().out
    assert "arcsin" in out and "q*/|q|²" in out


def test_verify_unknown_label_is_a_clean_error(capsys):
    assert main(["verify", "--details", "(99)"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ga-rotors: error: --details '(99)': no such equation")


def test_verify_write_and_check(tmp_path, capsys):
    target = tmp_path / "audit.md"
    assert main(["verify", "--write", str(target)]) == 0
    assert main(["verify", "--check", str(target)]) == 0
    target.write_text(target.read_text(encoding="utf-8") + "edited\n", encoding="utf-8")
    assert main(["verify", "--check", str(target)]) == 1
    assert "out of date" in capsys.readouterr().err
    assert [p.name for p in tmp_path.iterdir()] == ["audit.md"]  # no temp file left behind


def test_verify_write_into_missing_directory_is_a_clean_error(tmp_path, capsys):
    assert main(["verify", "--write", str(tmp_path / "nope" / "audit.md")]) == 2
    assert "expected a path in an existing directory" in capsys.readouterr().err


def test_verify_exits_nonzero_when_a_critical_derivation_fails(monkeypatch, capsys, audit):
    import ga_rotors.symbolic.audit as audit_module

    broken = replace(
        audit.findings[0], checks=(Step("broken on purpose", "", False),), critical=True
    )
    monkeypatch.setattr(audit_module, "run_audit", lambda: replace(audit, findings=(broken,)))
    assert main(["verify"]) == 1
    assert "depends on FAILED" in capsys.readouterr().err


def test_verify_only_warns_when_a_noncritical_derivation_fails(monkeypatch, capsys, audit):
    import ga_rotors.symbolic.audit as audit_module

    broken = replace(
        audit.findings[1], checks=(Step("broken on purpose", "", False),), critical=False
    )
    monkeypatch.setattr(audit_module, "run_audit", lambda: replace(audit, findings=(broken,)))
    assert main(["verify"]) == 0
    assert "warning" in capsys.readouterr().err


def test_wrong_source_equations_do_not_fail_verify(audit):
    assert audit.wrong() and audit.ok


def test_symbolic_is_independent_of_the_numeric_package():
    # ga_rotors.symbolic imports nothing of ga_rotors outside itself (its command line,
    # ga_rotors.cli.verify, is the one place that joins them), nor the numeric libraries
    # the package computes with (SymPy itself may load numpy).
    code = (
        "import sys\n"
        "import ga_rotors.symbolic.audit, ga_rotors.symbolic.isomorphisms\n"
        "import ga_rotors.symbolic.rotors\n"
        "print(sorted(m for m in sys.modules if m.startswith('ga_rotors.')\n"
        "             and not m.startswith('ga_rotors.symbolic')))\n"
        "print([m for m in ('clifford', 'numba', 'scipy') if m in sys.modules])"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout.split("\n")
    assert out[:2] == ["[]", "[]"]


def test_verify_write_that_the_system_refuses_is_a_clean_error(tmp_path, capsys, monkeypatch):
    # /proc/x.md (an existing folder no file can be made in) was a FileNotFoundError
    # traceback; a full disk is the same path
    import errno

    import ga_rotors.files

    def full(path, text):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(ga_rotors.files, "write_text", full)
    assert main(["verify", "--write", str(tmp_path / "audit.md")]) == 2
    err = capsys.readouterr().err
    assert "--write " in err and "cannot write it (No space left on device)" in err
    assert err.count("\n") == 1 and "Traceback" not in err
