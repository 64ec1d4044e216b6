"""What one audited equation looks like, and how its verdict is reached.

A :class:`Finding` records, for one numbered equation (or one claim in the text) of a
source document: the text exactly as extracted, the reading we test (with every lost
minus sign, dot, root or fraction bar restored and the reason recorded), the other
readings considered and what each gives, our independent derivation (a list of checked
:class:`~symbolic.derivation.Step` s), the verdict, the corrected form, and the evidence.

Verdicts (:class:`Verdict`):

* **correct**: the tested reading holds in the source's own definitions;
* **correct under a stated convention**: it holds once a convention the source leaves
  open is fixed (which way a matrix acts, the quadrant of an arctan, a sign or branch,
  a rounding), and the convention is stated;
* **wrong**: it contradicts the source's own definitions, or fails under every reasonable
  convention; the corrected form and a counterexample are given.

The verdict is computed by :func:`verdict_of` from two checks each entry performs (does
the reading hold as printed? does it hold under the stated convention?), never typed in.
A failed step of *our own* derivation is not a verdict on the source: it means our
derivation is broken, and ``ga-rotors verify`` exits non-zero.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from ..derivation import Step

__all__ = ["Finding", "Reading", "Verdict", "verdict_of"]


class Verdict(StrEnum):
    """The three verdicts; :attr:`short` is the table's column.

    Examples
    --------
    >>> Verdict("wrong") is Verdict.WRONG, Verdict.CONVENTION.short
    (True, 'convention')
    """

    CORRECT = "correct"
    CONVENTION = "correct under a stated convention"
    WRONG = "wrong"

    @property
    def short(self) -> str:
        return {
            "correct": "correct",
            "correct under a stated convention": "convention",
            "wrong": "WRONG",
        }[self.value]


def verdict_of(holds_as_printed: bool, holds_under_convention: bool = False) -> Verdict:
    """The verdict from the two checks an entry makes.

    Examples
    --------
    A reading that fails as printed but holds once a convention is fixed: (q v q*)
    rotates v actively; the printed matrix is its transpose (the passive reading).

    >>> import sympy
    >>> from ga_rotors.symbolic import hamilton
    >>> q, v = hamilton.symbols("q"), sympy.symbols("v1:4")
    >>> active = sympy.Matrix(hamilton.rotate(q, v))
    >>> m = hamilton.rotation_matrix(q)
    >>> as_printed = sympy.expand(m.T * sympy.Matrix(v) - active) == sympy.zeros(3, 1)
    >>> transposed = sympy.expand(m * sympy.Matrix(v) - active) == sympy.zeros(3, 1)
    >>> as_printed, transposed
    (False, True)
    >>> verdict_of(as_printed, transposed)
    <Verdict.CONVENTION: 'correct under a stated convention'>
    """
    if holds_as_printed:
        return Verdict.CORRECT
    if holds_under_convention:
        return Verdict.CONVENTION
    return Verdict.WRONG


@dataclass(frozen=True)
class Reading:
    """One way of reading damaged text, and what the check found under it.

    Examples
    --------
    >>> r = Reading("q⁻¹ = q*/|q|²", "holds exactly", tested=True)
    >>> r.tested, r.outcome
    (True, 'holds exactly')
    """

    text: str
    outcome: str
    tested: bool = False


@dataclass(frozen=True)
class Finding:
    """The audit of one equation or claim.

    Examples
    --------
    The conjugate has the same norm, checked exactly:

    >>> import sympy
    >>> from ga_rotors.symbolic import hamilton
    >>> from ga_rotors.symbolic.derivation import step
    >>> q = hamilton.symbols("q")
    >>> holds = sympy.expand(hamilton.norm2(hamilton.conj(q)) - hamilton.norm2(q)) == 0
    >>> f = Finding(
    ...     "notes", "N0", "norm of the conjugate", printed="|q^*| = |q|",
    ...     reading="|q*| = |q|", reconstruction="nothing lost.", verdict=verdict_of(holds),
    ...     evidence="both sides expand to q0² + q1² + q2² + q3²",
    ...     checks=(step("|q*|² = |q|²", "expanded exactly", holds),),
    ... )
    >>> f.verdict.value, f.checks_ok
    ('correct', True)
    >>> print(f.report())
    notes N0: norm of the conjugate
      printed (as extracted): |q^*| = |q|
      read as: |q*| = |q|
      reconstruction: nothing lost.
      verdict: correct
      evidence: both sides expand to q0² + q1² + q2² + q3²
      [ok] |q*|² = |q|²
           expanded exactly
    """

    source: str  # "paper" or "notes"
    label: str  # "(12)", "(19) singular set", "N9"
    topic: str
    printed: str  # verbatim from the source document
    reading: str  # the reading tested, in plain notation
    reconstruction: str  # what was restored, and why
    verdict: Verdict
    evidence: str
    corrected: str = ""  # corrected form (wrong) or the convention (correct under convention)
    readings: tuple[Reading, ...] = ()
    checks: tuple[Step, ...] = ()
    critical: bool = False  # the numeric package depends on these checks
    notes: str = ""

    @property
    def checks_ok(self) -> bool:
        return all(s.holds for s in self.checks)

    def failed_checks(self) -> list[Step]:
        return [s for s in self.checks if not s.holds]

    def report(self) -> str:
        """Plain-text account of this finding."""
        lines = [
            f"{self.source} {self.label}: {self.topic}",
            f"  printed (as extracted): {self.printed}",
            f"  read as: {self.reading}",
            f"  reconstruction: {self.reconstruction}",
        ]
        for r in self.readings:
            mark = "tested" if r.tested else "considered"
            lines.append(f"  reading ({mark}): {r.text}\n      -> {r.outcome}")
        lines.append(f"  verdict: {self.verdict.value}")
        if self.corrected:
            lines.append(
                f"  {'corrected form' if self.verdict is Verdict.WRONG else 'convention'}: "
                f"{self.corrected}"
            )
        lines.append(f"  evidence: {self.evidence}")
        if self.notes:
            lines.append(f"  note: {self.notes}")
        for s in self.checks:
            lines.append(f"  [{'ok' if s.holds else 'FAILED'}] {s.claim}")
            lines.extend(f"       {line}" for line in s.shown.splitlines())
        return "\n".join(lines)
