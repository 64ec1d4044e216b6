"""A scene run's files: data, the figure, the summary and the resolved scene.

:func:`stream_scene` runs a scene and writes, into one directory, exactly what ``output``
declares, as the run goes on:

* ``<name>.csv`` (with its CSVW metadata ``<name>.csv-metadata.json``) / ``.npz`` /
  ``.nc`` / ``.zarr`` (any registered format) for ``output.data``, each appended piece by
  piece (:mod:`ga_rotors.results.streams`);
* ``<name>.png`` (or ``.svg``, ``.pdf``: ``output.figure_format``), one panel per entry
  of ``output.plots`` (drawn with matplotlib, carrying a digest of the data it shows),
  drawn from a bounded thinned copy of the run
  (:class:`~ga_rotors.scene.thinning.ThinnedCopy`: every sample's extremes per pixel
  column);
* ``<name>.summary.txt`` when ``output.summary`` is on (accumulated piece by piece,
  :class:`~ga_rotors.scene.summary.RunSummary`), and ``<name>.scene.toml``, the resolved
  scene, whenever anything is written (what made these files).

The run is integrated in pieces of :data:`~ga_rotors.scene.budget.CHUNK_STEPS` steps
(:func:`ga_rotors.scene.run.run_pieces`, bit for bit the run whole), so memory holds one
piece, the thinned copy and a few numbers per piece, whatever the number of steps.
:func:`write_outputs` writes the same files from a trajectory already in memory.

Atomicity: everything is written into a staging directory on the same file system
(:func:`ga_rotors.files.output_set`); only when the run has finished and every file is
complete are they moved into place. A failure or an interruption at any point removes
the staging directory, so the previous output stays as it was.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..trajectory import Trajectory
from .budget import CHUNK_STEPS
from .formats import FORMATS
from .loading import load_scene
from .model import Scene

__all__ = ["stream_scene", "write_outputs"]


def _declared(scene: Scene) -> bool:
    out = scene.data["output"]
    return bool(out["data"] or out["plots"])


def _names(scene: Scene, summary: bool) -> list[str]:
    out, name = scene.data["output"], scene.name
    names = [file for fmt in out["data"] for file in FORMATS[fmt].files(name)]
    if out["plots"]:
        names.append(f"{name}.{out['figure_format']}")
    if summary:
        names.append(f"{name}.summary.txt")
    return [*names, f"{name}.scene.toml"]


def _write(scene: Scene, pieces, stage: Path | None, summarise: bool):
    """Feed ``pieces`` to the writers in ``stage`` (None: no files), the thinned copy and
    (``summarise``) the summary, one piece at a time as it is integrated; write the
    figure, summary and scene files; return the Report (with ``summarise`` off, only
    whether the run completed). A failure or an interrupt stops the writers (their files
    go away with the staging folder).
    """
    out = scene.data["output"]
    sink = _Sink(scene, stage, summarise)
    try:
        _consume(pieces, sink.take)
        sink.close()
        if stage is not None and sink.thin is not None:
            from . import figures

            figure = figures.render(scene, sink.thin.trajectory(sink.meta))
            (stage / f"{scene.name}.{out['figure_format']}").write_bytes(figure)
    except BaseException:
        sink.abort()
        raise
    if sink.summary is not None:
        rep = sink.summary.report()
    else:
        from .summary import status_report

        rep = status_report(scene, sink.meta)
    if stage is not None:
        name = scene.name
        if rep is not None and out["summary"]:
            (stage / f"{name}.summary.txt").write_text(str(rep) + "\n", "utf-8")
        (stage / f"{name}.scene.toml").write_text(scene.to_toml(), "utf-8")
    return rep


def _consume(pieces, take) -> None:
    """``take(piece)`` for each piece in order, on a thread of its own: each piece is
    written, thinned and measured there while the next one is integrated here (the
    compiled loops release the GIL, so on two cores the two overlap). At most the piece
    being taken and the one being integrated are alive; ``take`` has finished with every
    piece when this returns or raises.

    Why a thread: the 10⁷-step heavy top of ``benchmarks/bench_stream.py`` (netCDF,
    figure and summary) took 2.38 s of CPU in one thread, 1.0 s of it integrating and
    1.0 s writing, thinning and measuring (the summary's exact Lagrange top at every
    sample is most of it), and 0.3 s drawing: one after the other, about 2.3x the bare
    integration. Taken on a second core, the wall time is the larger of the two halves
    plus the figure."""
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=1, thread_name_prefix="ga_rotors-run") as pool:
        taking = None
        for piece in pieces:
            if taking is not None:
                taking.result()  # the previous piece is taken (or its error raised here)
            taking = pool.submit(take, piece)
        if taking is not None:
            taking.result()


class _Sink:
    """Where the pieces of a run go: its data files, its summary, its figure's copy."""

    def __init__(self, scene: Scene, stage: Path | None, summarise: bool):
        from .summary import summary_for

        out, name = scene.data["output"], scene.name
        self.scene, self.meta = scene, None
        self.writers = []
        if stage is not None:
            for fmt in out["data"]:
                self.writers.append(
                    FORMATS[fmt].open(stage / f"{name}{FORMATS[fmt].suffix}", scene)
                )
        self.summary = summary_for(scene) if summarise else None
        self.figure = stage is not None and bool(out["plots"])
        self.thin = self.balance = None

    def take(self, piece: Trajectory) -> None:
        """Append ``piece`` to the data files and the figure's thinned copy, and add it to
        the summary."""
        self.meta = piece.meta
        for writer in self.writers:
            writer.append(piece)
        self._thin(piece)
        if self.summary is not None:
            self.summary.add(piece)

    def _thin(self, piece: Trajectory) -> None:
        from ..results.streams import sample_count
        from .figures import energy_balance_drawn
        from .thinning import ThinnedCopy

        if self.thin is None and self.figure:
            meta = piece.meta
            t_end = float(piece.t[0]) + meta["steps"] * meta["step"]
            self.thin = ThinnedCopy(float(piece.t[0]), t_end, sample_count(meta))
            if not self.thin.keep_all and energy_balance_drawn(self.scene):
                self.balance = _Balance(self.scene)
        if self.thin is not None:
            self.thin.add(piece if self.balance is None else self.balance.add(piece))

    def close(self) -> None:
        """Finish the data files (with the run's final ``meta``)."""
        for writer in self.writers:
            writer.close(self.meta)

    def abort(self) -> None:
        for writer in self.writers:
            writer.abort()


class _Balance:
    """The energy balance of a thinned run's figure (:func:`~.figures.energy_balance`),
    accumulated over every sample: each piece gets ``energy_gain`` and ``torque_work``."""

    def __init__(self, scene: Scene):
        self.scene, self.first_energy, self.last, self.work = scene, None, None, 0.0

    def add(self, piece: Trajectory) -> Trajectory:
        from .. import quaternion as Q
        from .figures import energy_balance

        n = piece.w.shape[0]
        if n == 0:
            return piece
        t, w, q = piece.t[:n], piece.w, Q.normalize(piece.quaternions())[:n]
        if self.last is not None:  # the previous piece's last sample in front
            t, w, q = (np.concatenate([a, b]) for a, b in zip(self.last, (t, w, q), strict=True))
        _, work = energy_balance(self.scene, Trajectory({"t": t, "w": w}), q)
        work = self.work + (work[1:] if self.last is not None else work)
        energy = self.scene.body.energy(piece.w)
        if self.first_energy is None:
            self.first_energy = energy[0]
        self.last, self.work = (t[-1:], w[-1:], q[-1:]), float(work[-1])
        return piece.extended({"energy_gain": energy - self.first_energy, "torque_work": work})


def stream_scene(scene, out_dir, *, progress=None, budget=None, chunk_steps: int = CHUNK_STEPS):
    """Run ``scene`` and write its declared files into ``out_dir`` as the run goes on.

    Parameters
    ----------
    scene : Scene or str or path
    out_dir : str or path
        Created if missing; the new files replace the previous ones only when the run
        has finished and every file is complete.
    progress : callable, optional
        ``progress(done, total)`` in steps (all paths).
    budget : ga_rotors.scene.budget.Budget, optional
        Steps and disk the run may take (default :data:`ga_rotors.scene.budget.DEFAULT`),
        checked before it starts, the key named (:func:`ga_rotors.scene.budget.check`).
    chunk_steps : int
        Steps per piece (each path).

    Returns
    -------
    (list of Path, Report)
        The files written (none when the scene declares no data and no plots: then
        nothing is created) and the run's summary (with ``output.summary`` off, nothing
        is measured and the report says only whether the run completed:
        :func:`ga_rotors.scene.summary.status_report`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> s = load_scene("heavy_top").replace({"time.duration": 0.5, "output.data": ["csv"]})
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "run"
    >>> files, rep = stream_scene(s, out, chunk_steps=1000)
    >>> [p.name for p in files]
    ['heavy_top.csv', 'heavy_top.csv-metadata.json', 'heavy_top.png', 'heavy_top.summary.txt',
     'heavy_top.scene.toml']
    >>> rep.values["drift_total_energy"] < 1e-9
    True
    """
    from ..files import output_set
    from . import budget as _budget
    from .formats import require_formats
    from .run import run_pieces

    scene = load_scene(scene)
    _budget.check(scene, _budget.DEFAULT if budget is None else budget, streamed=True)
    require_formats(scene)
    pieces = run_pieces(scene, chunk_steps=chunk_steps, progress=progress)
    # with output.summary off nothing is measured: the report says only whether the run
    # completed (the summary's exact reference at every sample is its largest cost)
    summarise = scene.data["output"]["summary"]
    if not _declared(scene):
        return [], _write(scene, pieces, None, summarise)
    with output_set(out_dir, "--out") as stage:
        rep = _write(scene, pieces, stage, summarise)
    return [Path(out_dir) / n for n in _names(scene, scene.data["output"]["summary"])], rep


def write_outputs(scene: Scene, trajectory: Trajectory, out_dir, summary: str | None = None):
    """Write the declared files of a run already in memory into ``out_dir`` atomically;
    return their paths (the files :func:`stream_scene` writes, ``summary`` as the
    summary's text).

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
    ['spinning_disk.csv', 'spinning_disk.csv-metadata.json', 'spinning_disk.scene.toml']
    """
    from ..files import output_set

    if not _declared(scene):
        return []
    with output_set(out_dir, "--out") as stage:
        _write(scene, [trajectory], stage, False)
        if summary is not None:
            (stage / f"{scene.name}.summary.txt").write_text(summary + "\n", "utf-8")
    return [Path(out_dir) / n for n in _names(scene, summary is not None)]
