"""Notebook display: a scene or a trajectory as an HTML summary table.

:class:`~ga_rotors.scene.Scene` and :class:`~ga_rotors.trajectory.Trajectory` call these
from ``_repr_html_``, so Jupyter shows what a scene resolves to and what a run holds
instead of a one-line repr. Standard library only; every value is escaped (scene names and
descriptions come from files anyone may write).
"""

from __future__ import annotations

import html

__all__ = ["scene_html", "trajectory_html"]

_STYLE = "border-collapse: collapse; text-align: left; font-size: 0.9em"


def _table(caption: str, rows) -> str:
    body = "".join(
        f'<tr><th style="text-align: left; padding-right: 1em">{html.escape(str(k))}</th>'
        f"<td>{html.escape(str(v))}</td></tr>"
        for k, v in rows
    )
    head = f'<caption style="text-align: left">{caption}</caption>'
    return f'<table style="{_STYLE}">{head}{body}</table>'


def scene_html(scene) -> str:
    """A scene's summary: its name, description and what it resolves to (``ga-rotors show``).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> text = scene_html(load_scene("heavy_top"))
    >>> "<b>heavy_top</b>" in text, "exact solution" in text
    (True, True)
    """
    rows = []
    for line in scene.describe().splitlines():
        key, _, value = line.removeprefix("# ").partition(": ")
        rows.append((key, value))
    rows.append(("duration", f"{scene.data['time']['duration']:g} s from t = "
                             f"{scene.data['time']['start']:g} s"))  # fmt: skip
    caption = f"<b>{html.escape(scene.name)}</b>"
    if scene.description:
        caption += f": {html.escape(scene.description)}"
    return _table(caption, rows)


def trajectory_html(trajectory) -> str:
    """A trajectory's summary: samples, time span, arrays, paths and how it was made.

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.5,
    ...               step=0.1, paths=("rotor", "quaternion"))
    >>> text = trajectory_html(tr)
    >>> "6 samples" in text, "rotor_blades" in text
    (True, True)
    """
    t, meta = trajectory.t, trajectory.meta
    rows = [("samples", f"{len(t)} samples, t = {t[0]:g} … {t[-1]:g} s")]
    if "integrator" in meta:
        rows.append(("integrator", f"{meta['integrator']} (order {meta.get('order')}), "
                                   f"step {meta.get('step'):g} s"))  # fmt: skip
    for name, status in meta.get("paths", {}).items():
        done = "complete" if status.get("complete") else f"ended at t = {status.get('ended_at')}"
        rows.append((f"path {name}", f"{status.get('samples')} samples, {done}"))
    for name in trajectory.names:
        if name == "t":
            continue
        a = trajectory[name]
        labels = trajectory.components.get(name)
        rows.append((name, f"{a.shape}" + (f" ({', '.join(labels)})" if labels else "")))
    title = meta.get("scene", "Trajectory")
    return _table(f"<b>{html.escape(str(title))}</b>: a trajectory (.view() plays it)", rows)
