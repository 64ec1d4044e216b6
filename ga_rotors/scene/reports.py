"""A run's summary as lines and values: what every summary of a scene's run fills in.

:class:`Report` is what :mod:`ga_rotors.scene.summary` (a rotation about a fixed point)
and :mod:`ga_rotors.scene.motion_summary` (a body moving through space) both hand out;
:func:`mark_incomplete` is the line both put first when a run stopped early.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Report", "mark_incomplete"]


@dataclass
class Report:
    """A run's summary: ``lines`` to print and ``values`` (name -> number) to test.

    :func:`ga_rotors.scene.report` fills one from a simulated scene; ``str`` joins the lines.

    Examples
    --------
    >>> rep = Report("demo", ["scene demo: rk4", "  energy drift 1e-15"], {"energy": 1e-15})
    >>> print(rep)
    scene demo: rk4
      energy drift 1e-15
    >>> rep.values["energy"]
    1e-15
    """

    scene: str
    lines: list[str] = field(default_factory=list)
    values: dict[str, float] = field(default_factory=dict)

    def __str__(self) -> str:
        return "\n".join(self.lines)


def mark_incomplete(rep: Report, meta: dict, t_end: float) -> None:
    """Put the INCOMPLETE line first in ``rep`` (and ``values["incomplete"]``) when a path
    stopped before ``t_end``: every figure below it covers only the steps taken.

    Examples
    --------
    >>> rep = Report("demo", ["scene demo: rk4"])
    >>> meta = {"paths": {"rotor": {"complete": False, "ended_at": 1.5}}}
    >>> mark_incomplete(rep, meta, 3.0)
    >>> rep.lines[0]
    'INCOMPLETE: the run stopped before t = 3 s (rotor at t = 1.5 s); the figures below cover only the steps taken'
    """  # noqa: E501
    stopped = {p: i for p, i in meta["paths"].items() if not i["complete"]}
    if stopped:
        where = ", ".join(f"{p} at t = {i['ended_at']:g} s" for p, i in stopped.items())
        rep.lines.insert(
            0,
            f"INCOMPLETE: the run stopped before t = {t_end:g} s ({where}); the figures "
            "below cover only the steps taken",
        )
        rep.values["incomplete"] = 1.0
