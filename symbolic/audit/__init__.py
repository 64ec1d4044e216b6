"""The audit: every numbered equation of the paper and every formula of the notes.

:func:`run_audit` computes every finding (cached for the process) together with the
derivations of :mod:`symbolic.isomorphisms` and :mod:`symbolic.rotors`, and returns an
:class:`Audit` that renders the table (``ga-rotors verify``) and the Markdown page
(``docs/audit.md``, generated, never edited by hand).

Examples
--------
>>> from ga_rotors.symbolic.audit import find
>>> find("N9").verdict.value
'wrong'
>>> find("(36)").corrected.split(",")[0]
'q̇0 = −½(q1ωx3 + q2ωy3 + q3ωz3)'
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

from ..derivation import Derivation, Step
from . import notes, paper_clifford, paper_dynamics, paper_kinematics, paper_quaternions
from .core import Finding, Reading, Verdict, verdict_of

__all__ = ["ENTRIES", "Audit", "Finding", "Reading", "Verdict", "find", "run_audit", "verdict_of"]

#: Every entry, in the order of the documents.
ENTRIES: tuple[Callable[[], Finding], ...] = (
    *paper_quaternions.ENTRIES,
    *paper_dynamics.ENTRIES[:-1],
    *paper_kinematics.ENTRIES,
    paper_dynamics.other_sequences,
    *paper_clifford.ENTRIES,
    *notes.ENTRIES,
)

SOURCES = {
    "paper": "A Sutileza dos Quatérnions no Movimento de Rotação de Corpos Rígidos (Rev. Bras. "
    "Ensino Fís., 2016), equations (1)-(47) and claims in its text",
    "notes": "Quatérnios (Nogueira, Martins, Brenzikofer, Modelos Matemáticos nas Ciências Não "
    "Exatas, 2008), every formula",
}


@dataclass(frozen=True)
class Audit:
    """All findings, and the derivations they rest on.

    :func:`run_audit` builds it (once per process); ``ga-rotors verify`` prints
    :meth:`table`, and ``docs/audit.md`` is :meth:`markdown`.

    Examples
    --------
    >>> audit = run_audit()
    >>> audit.ok  # no derivation the numeric package depends on failed
    True
    >>> audit.find("n9").label, audit.find("n9") in audit.wrong()
    ('N9', True)
    >>> len(audit.wrong()) == audit.counts()[Verdict.WRONG]
    True
    """

    findings: tuple[Finding, ...]
    derivations: tuple[Derivation, ...]

    def counts(self, source: str | None = None) -> dict[Verdict, int]:
        chosen = [f for f in self.findings if source is None or f.source == source]
        return {v: sum(f.verdict is v for f in chosen) for v in Verdict}

    def wrong(self) -> list[Finding]:
        return [f for f in self.findings if f.verdict is Verdict.WRONG]

    def failed_checks(self) -> list[tuple[str, Step, bool]]:
        """(where, step, critical) for every step of our own derivations that failed."""
        out = [
            (f"{f.source} {f.label}", s, f.critical)
            for f in self.findings
            for s in f.failed_checks()
        ]
        out += [(d.title, s, d.critical) for d in self.derivations for s in d.failures()]
        return out

    @property
    def ok(self) -> bool:
        """True when no derivation the numeric package depends on failed."""
        return not any(critical for _, _, critical in self.failed_checks())

    def find(self, label: str) -> Finding:
        key = normalise_label(label)
        for f in self.findings:
            if f.label == key:
                return f
        raise KeyError(label)

    # -- rendering ----------------------------------------------------------------------
    def table(self) -> str:
        """The verdict table: one line per finding, then the wrong ones with corrections."""
        width = max(len(f.label) for f in self.findings)
        lines = []
        for source in SOURCES:
            lines.append(f"{source}: {SOURCES[source]}")
            for f in self.findings:
                if f.source == source:
                    lines.append(f"  {f.label:<{width}}  {f.verdict.short:<10}  {f.topic}")
            lines.append("")
        lines.append(self.summary())
        lines.append("")
        lines.append("wrong, with corrected forms:")
        for f in self.wrong():
            lines.append(f"  {f.source} {f.label}: {f.corrected}")
        lines.append("")
        lines.append("derivations (our own; 'critical' = the numeric package depends on it):")
        for d in self.derivations:
            state = "ok" if d.ok else "FAILED"
            lines.append(f"  [{state}] {d.title}{'  (critical)' if d.critical else ''}")
        failures = self.failed_checks()
        checks = sum(len(f.checks) for f in self.findings) + sum(
            len(d.steps) for d in self.derivations
        )
        lines.append(f"  {checks - len(failures)} of {checks} checked steps hold")
        for where, s, critical in failures:
            lines.append(f"  FAILED{' (critical)' if critical else ''}: {where}: {s.claim}")
        return "\n".join(lines)

    def summary(self) -> str:
        parts = []
        for source in SOURCES:
            c = self.counts(source)
            parts.append(
                f"{source}: {c[Verdict.CORRECT]} correct, {c[Verdict.CONVENTION]} correct "
                f"under a stated convention, {c[Verdict.WRONG]} wrong"
            )
        return "; ".join(parts)

    def markdown(self) -> str:
        from .markdown import render

        return render(self)


def normalise_label(label: str) -> str:
    """'12' -> '(12)', 'n9' -> 'N9'; other labels unchanged."""
    label = label.strip()
    if label.isdigit():
        return f"({int(label)})"
    if label[:1] in "nN" and label[1:].isdigit():
        return f"N{int(label[1:])}"
    return label


@lru_cache(maxsize=1)
def run_audit() -> Audit:
    """Compute every finding and derivation (once per process).

    Examples
    --------
    >>> audit = run_audit()
    >>> audit is run_audit()  # cached: the second call costs nothing
    True
    >>> len(audit.findings) == len(ENTRIES), audit.ok
    (True, True)
    """
    from ..isomorphisms import all_isomorphisms
    from ..rotors import rotor_kinematics, rotor_sandwich

    findings = tuple(entry() for entry in ENTRIES)
    derivations = (*all_isomorphisms(), rotor_sandwich(), rotor_kinematics())
    return Audit(findings, derivations)


def find(label: str) -> Finding:
    """The finding with this label ('(12)', '12', 'N9', '(19) singular set', ...).

    Examples
    --------
    >>> f = find("12")
    >>> f.label, f.source, f.verdict.value
    ('(12)', 'paper', 'wrong')
    >>> find("(99)")
    Traceback (most recent call last):
    ...
    KeyError: '(99)'
    """
    return run_audit().find(label)
