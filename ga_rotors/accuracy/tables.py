"""Reading the sweeps: the cheapest run per target, per-method tables, and the goal table.

The goal table (:func:`goal`, :func:`goal_table`) answers issue 12's question per case and
target error: is the best ga_rotors method, called through its public API, at least
:data:`GOAL_RATIO` times faster than the fastest compiled peer? The two runs the sweeps
picked are timed again in the same process, interleaved (ours, peer, ours, peer, ...), so
both see the same machine; the medians and their min–max ranges are what the table shows.
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass

from .measuring import Point, runner
from .sweeps import REFINE_TARGETS, Study

__all__ = [
    "FAMILIES",
    "GOAL_RATIO",
    "GOAL_TARGETS",
    "TARGETS",
    "Goal",
    "cheapest",
    "goal",
    "goal_table",
    "method_table",
    "summary_table",
]

#: Target geodesic errors (rad) of the cheapest-method tables.
TARGETS = tuple(10.0**-k for k in range(3, 13))
#: Targets of the goal table (the sweeps are refined near them), and the speed-up asked
#: for from 1e-6 on (at 1e-3, ≥ 1×).
GOAL_TARGETS = REFINE_TARGETS
GOAL_RATIO = 1.5
#: Families in the tables' column order: ours, compiled peers, casual peers.
FAMILIES = ("ga_rotors", "compiled", "scipy", "numpy-quaternion", "MuJoCo")


def cheapest(points: list[Point], targets=TARGETS, families=None) -> dict:
    """For each target error, the fastest point (per family) whose error reaches it.

    Returns ``{family: {target: Point or None}}``.

    Examples
    --------
    >>> pts = [Point("a", 10, 0.01, 40, 1e-4, 0, 0), Point("b", 10, 0.002, 40, 1e-6, 0, 0)]
    >>> cheapest(pts, targets=(1e-3, 1e-5))["ga_rotors"][1e-3].method
    'b'
    """
    families = families or sorted({p.family for p in points})
    table = {}
    for fam in families:
        row = {}
        for target in targets:
            ok = [p for p in points if p.family == fam and p.error <= target]
            row[target] = min(ok, key=lambda p: p.seconds) if ok else None
        table[fam] = row
    return table


def _fmt_ms(seconds: float) -> str:
    return f"{1e3 * seconds:.3g}"


def _label(t: float) -> str:
    return f"1e-{round(-math.log10(t))}"


def method_table(st: Study, targets=TARGETS) -> str:
    """Markdown: per method (rows) the least median time (ms) that reaches each target.

    Examples
    --------
    >>> from ga_rotors.accuracy import Study, cases
    >>> st = Study(cases()["symmetric"], [Point("rk4", 8, 0.002, 32, 1e-4, 0, 0)])
    >>> print(method_table(st, targets=(1e-3, 1e-6)))
    | method | 1e-3 | 1e-6 |
    |---|---|---|
    | rk4 | **2** | — |
    """
    methods = []
    for p in st.points:
        if p.method not in methods:
            methods.append(p.method)
    best = {t: min((p.seconds for p in st.points if p.error <= t), default=None) for t in targets}
    lines = [
        "| method | " + " | ".join(_label(t) for t in targets) + " |",
        "|---|" + "---|" * len(targets),
    ]
    for m in methods:
        cells = []
        for t in targets:
            ok = [p.seconds for p in st.points if p.method == m and p.error <= t]
            if not ok:
                cells.append("—")
                continue
            cell = _fmt_ms(min(ok))
            cells.append(f"**{cell}**" if min(ok) == best[t] else cell)
        lines.append(f"| {m} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def summary_table(studies: list[Study], targets=TARGETS) -> str:
    """Markdown: per case and target, the cheapest project method, the cheapest run of each
    peer family (median ms), and how many times faster ours is than the fastest compiled
    peer and than the fastest casual one (from the sweeps; the goal table re-times the
    headline pairs interleaved).

    Examples
    --------
    >>> from ga_rotors.accuracy import Study, cases
    >>> st = Study(cases()["symmetric"], [Point("rk4", 8, 0.002, 32, 1e-4, 0, 0),
    ...     Point("njit_rk4", 8, 0.004, 32, 1e-4, 0, 0, family="compiled")])
    >>> summary_table([st], targets=(1e-3,)).splitlines()[-1]
    '| symmetric | 1e-3 | rk4 | 2 | 4 (njit_rk4) | n/a | n/a | n/a | 2× | no peer reaches it |'
    """
    lines = [
        "| problem | target (rad) | cheapest method | ms | compiled peers ms | scipy DOP853 ms | "
        "numpy-quaternion ms | MuJoCo ms | compiled / ours | casual / ours |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for st in studies:
        table = cheapest(st.points, targets, FAMILIES)
        for t in targets:
            ours = table["ga_rotors"][t]
            cells = []
            for fam in FAMILIES[1:]:
                p = table[fam][t]
                present = any(q.family == fam for q in st.points)
                if p is None:
                    cells.append("not reached" if present else "n/a")
                else:
                    cells.append(f"{_fmt_ms(p.seconds)} ({p.method})")

            name = ours.method if ours else "—"
            ms = _fmt_ms(ours.seconds) if ours else "—"
            ratios = [_ratio(table, t, ours, fams) for fams in (FAMILIES[1:2], FAMILIES[2:])]
            lines.append(f"| {st.case.name} | {_label(t)} | {name} | {ms} | " + " | ".join(cells)
                         + f" | {ratios[0]} | {ratios[1]} |")  # fmt: skip
    return "\n".join(lines)


def _ratio(table, target, ours, families) -> str:
    """The fastest of ``families`` at ``target`` over ours, as a table cell."""
    reached = [table[f][target].seconds for f in families if table[f][target] is not None]
    if ours is None:
        return "not reached"
    return f"{min(reached) / ours.seconds:.3g}×" if reached else "no peer reaches it"


@dataclass(frozen=True)
class Goal:
    """One cell of the goal table: our best run and the fastest compiled peer's at one
    target, re-timed interleaved. Times are (median, min, max) seconds.

    Examples
    --------
    >>> ours = Point("dp8", 400, 1e-4, 4800, 1e-7, 0, 0)
    >>> Goal("x", 1e-6, ours, None).met  # no compiled peer reaches 1e-6
    True
    """

    case: str
    target: float
    ours: Point | None
    peer: Point | None
    ours_times: tuple[float, float, float] | None = None
    peer_times: tuple[float, float, float] | None = None

    @property
    def ratio(self) -> float | None:
        """Peer's median over ours (> 1: ours is faster), or None if either is missing."""
        if self.ours_times is None or self.peer_times is None:
            return None
        return self.peer_times[0] / self.ours_times[0]

    @property
    def met(self) -> bool:
        """Ours at least :data:`GOAL_RATIO`× faster (at 1e-3: at least as fast); a target
        no peer reaches counts as met if ours reaches it.

        Examples
        --------
        >>> p = Point("rk4", 8, 1.0, 32, 1e-7, 0, 0)
        >>> Goal("x", 1e-6, p, p, (1.0, 1.0, 1.0), (1.4, 1.3, 1.5)).met
        False
        >>> Goal("x", 1e-3, p, p, (1.0, 1.0, 1.0), (1.0, 1.0, 1.0)).met
        True
        """
        if self.ours is None:
            return False
        if self.peer is None:
            return True
        need = 1.0 if self.target >= 1e-3 else GOAL_RATIO
        return self.ratio is not None and self.ratio >= need


def _interleaved(runs, rounds: int, budget: float) -> list[tuple[float, float, float]]:
    """(median, min, max) of each of ``runs`` timed in turn, ``rounds`` times (each warmed
    once first); stops early after ``budget`` seconds."""
    for run in runs:
        run()
    times: list[list[float]] = [[] for _ in runs]
    start_all = time.perf_counter()
    for _ in range(max(1, rounds)):
        for k, run in enumerate(runs):
            start = time.perf_counter()
            run()
            times[k].append(time.perf_counter() - start)
        if time.perf_counter() - start_all > budget:
            break
    return [(statistics.median(t), min(t), max(t)) for t in times]


def goal(st: Study, targets=GOAL_TARGETS, rounds: int = 21, budget: float = 2.0) -> list[Goal]:
    """The goal cells of one study: per target, our cheapest run and the cheapest compiled
    peer's, re-timed interleaved (``rounds`` each, within ``budget`` seconds per cell).

    Examples
    --------
    >>> from ga_rotors.accuracy import Study, cases, measure
    >>> case = cases()["asymmetric_far"]
    >>> (cell,) = goal(Study(case, [measure(case, "dp8", 400, repeats=1)]), targets=(1e-6,))
    >>> cell.ours.method, cell.peer  # no compiled peer in this study: nothing to re-time
    ('dp8', None)
    """
    import warnings

    from ..errors import StepLimitWarning
    from . import compiled_peers

    table = cheapest(st.points, targets, ("ga_rotors", "compiled"))
    out = []
    for t in targets:
        ours, peer = table["ga_rotors"][t], table["compiled"][t]
        if ours is None or peer is None:
            out.append(Goal(st.case.name, t, ours, peer))
            continue
        run_ours = runner(st.case, ours.method, int(ours.setting))[0]
        setting = int(peer.setting) if peer.method in compiled_peers.FIXED else peer.setting
        run_peer = compiled_peers.runner(st.case, peer.method, setting)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", StepLimitWarning)
            mine, theirs = _interleaved([run_ours, run_peer], rounds, budget)
        out.append(Goal(st.case.name, t, ours, peer, mine, theirs))
    return out


def _range(times) -> str:
    median, low, high = (1e3 * x for x in times)
    return f"{median:.3g} ({low:.3g}–{high:.3g})"


def goal_table(goals: list[Goal]) -> str:
    """Markdown: per case and target, our best and the fastest compiled peer, medians (ms)
    with min–max, the ratio and whether the goal is met.

    Examples
    --------
    >>> p = Point("split4", 64, 1e-4, 320, 1e-7, 0, 0)
    >>> q = Point("njit_rk4", 64, 2e-4, 256, 1e-7, 0, 0, family="compiled")
    >>> print(goal_table([Goal("x", 1e-6, p, q, (1e-4, 9e-5, 2e-4), (2e-4, 2e-4, 3e-4))]))
    | problem | target | ga_rotors (ms, median (min–max)) | fastest compiled peer (ms) | peer / ours | goal |
    |---|---|---|---|---|---|
    | x | 1e-6 | split4: 0.1 (0.09–0.2) | njit_rk4: 0.2 (0.2–0.3) | 2× | met |
    """  # noqa: E501
    lines = [
        "| problem | target | ga_rotors (ms, median (min–max)) | fastest compiled peer (ms) "
        "| peer / ours | goal |",
        "|---|---|---|---|---|---|",
    ]
    for g in goals:
        if g.ours is None:
            ours, peer, ratio, verdict = "not reached", "—", "—", "NOT MET: ours does not reach it"
            if g.peer is not None:
                peer = f"{g.peer.method}: {_fmt_ms(g.peer.seconds)}"
        elif g.peer is None:
            ours = f"{g.ours.method}: {_fmt_ms(g.ours.seconds)}"
            peer, ratio, verdict = "not reached", "—", "met (no compiled peer reaches it)"
        else:
            ours = f"{g.ours.method}: {_range(g.ours_times)}"
            peer = f"{g.peer.method}: {_range(g.peer_times)}"
            ratio = f"{g.ratio:.3g}×"
            need = "1" if g.target >= 1e-3 else f"{GOAL_RATIO:g}"
            verdict = "met" if g.met else f"NOT MET (needs ≥ {need}×)"
        lines.append(f"| {g.case} | {_label(g.target)} | {ours} | {peer} | {ratio} | {verdict} |")
    return "\n".join(lines)
