"""A scene run's files: data (CSV, NPZ), the figure, the summary and the resolved scene.

:func:`write_outputs` writes, into one directory, exactly what ``output`` declares:

* ``<name>.csv`` / ``<name>.npz`` (or any registered format) for ``output.data``;
* ``<name>.png`` (or ``.svg``, ``.pdf``: ``output.figure_format``), one panel per entry
  of ``output.plots`` (drawn with matplotlib, carrying a digest of the data it shows);
* ``<name>.summary.txt`` when ``output.summary`` is on, and ``<name>.scene.toml``, the
  resolved scene, whenever anything is written (what made these files).

Atomicity: everything is first written into a staging directory on the same file system;
only when every file is complete are they moved into place (one ``rename`` of the whole
directory when it did not exist, otherwise one ``os.replace`` per file). A failure at any
point removes the staging directory, so a failed run leaves no half-written files and
changes nothing it had not finished.
"""

from __future__ import annotations

from ..trajectory import Trajectory
from .figures import render
from .formats import FORMATS
from .model import Scene

__all__ = ["write_outputs"]


def _plan(scene: Scene, tr: Trajectory, summary: str | None) -> list[tuple[str, object]]:
    name = scene.name
    out = scene.data["output"]
    plan: list[tuple[str, object]] = []
    for fmt in out["data"]:
        write = FORMATS[fmt].write
        plan.append((f"{name}{FORMATS[fmt].suffix}", lambda p, write=write: write(tr, p)))
    if out["plots"]:
        figure = f"{name}.{out['figure_format']}"
        plan.append((figure, lambda p: p.write_bytes(render(scene, tr))))
    if not plan:
        return []
    if summary is not None:
        plan.append((f"{name}.summary.txt", lambda p: p.write_text(summary + "\n", "utf-8")))
    plan.append((f"{name}.scene.toml", lambda p: p.write_text(scene.to_toml(), "utf-8")))
    return plan


def write_outputs(scene: Scene, trajectory: Trajectory, out_dir, summary: str | None = None):
    """Write the declared files into ``out_dir`` atomically; return their paths.

    Nothing is written (and no directory created) when the scene declares no data and
    no plots.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> s = load_scene("spinning_disk").replace({"time.duration": 0.1, "output.plots": []})
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "run"
    >>> [p.name for p in write_outputs(s, run_scene(s), out)]
    ['spinning_disk.csv', 'spinning_disk.scene.toml']
    """
    from ..files import write_together

    plan = _plan(scene, trajectory, summary)
    if not plan:
        return []
    return write_together(out_dir, plan, argument="--out")
