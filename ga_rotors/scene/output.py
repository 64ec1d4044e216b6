"""A scene run's files: data, the figure, the summary and the resolved scene.

:func:`stream_scene` runs a scene and writes, into one directory, exactly what ``output``
declares, as the run goes on:

* ``<name>.csv`` / ``.npz`` / ``.nc`` / ``.zarr`` (any registered format) for
  ``output.data``, each appended piece by piece (:mod:`ga_rotors.results.streams`);
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
from .budget import CHUNK_STEPS, SUMMARY_DELAY, SUMMARY_LAG
from .formats import FORMATS
from .loading import load_scene
from .model import Scene

__all__ = ["stream_scene", "write_outputs"]

#: Bytes of a finished data file whose writeback is started at a time (about 15 ms of
#: this machine's disk queue): the run stops asking between slices once it is done.
WRITEBACK_SLICE = 32 * 2**20


def _declared(scene: Scene) -> bool:
    out = scene.data["output"]
    return bool(out["data"] or out["plots"])


def _names(scene: Scene, summary: bool) -> list[str]:
    out, name = scene.data["output"], scene.name
    names = [f"{name}{FORMATS[fmt].suffix}" for fmt in out["data"]]
    if out["plots"]:
        names.append(f"{name}.{out['figure_format']}")
    if summary:
        names.append(f"{name}.summary.txt")
    return [*names, f"{name}.scene.toml"]


def _write(scene: Scene, pieces, stage: Path | None, summarise: bool):
    """Feed ``pieces`` to the writers in ``stage`` (None: no files), the thinned copy and
    (``summarise``) the summary; write the figure, summary and scene files; return the
    Report (with ``summarise`` off, only whether the run completed).

    A piece is consumed in two more threads while the next one is integrated: one writes
    it to the data files and thins it (figure), the other measures it (summary; with
    ``summarise`` off there is nothing to measure and no such thread). The compiled
    loops, the CSV formatting and numpy's array loops release the GIL, so on two cores
    they overlap. Each consumer takes the pieces one at a time, in order; the files'
    thread has finished with a piece before the next is handed over, the summary's may
    fall :data:`~ga_rotors.scene.budget.SUMMARY_LAG` pieces behind, and the figure is
    drawn (here) while it catches up. Every consumer has finished before this returns or
    raises: nothing writes into the staging folder after a failure or an interrupt.
    """
    import threading
    from collections import deque
    from concurrent.futures import ThreadPoolExecutor

    out = scene.data["output"]
    sink = _Sink(scene, stage, summarise)
    try:
        with (
            ThreadPoolExecutor(max_workers=1, thread_name_prefix="ga_rotors-writer") as files,
            ThreadPoolExecutor(max_workers=1, thread_name_prefix="ga_rotors-summary") as measures,
        ):
            writing, measuring, held, done = None, deque(), deque(), threading.Event()
            delay = SUMMARY_DELAY if sink.figure and sink.summary is not None else 0
            try:
                for piece in pieces:  # integrated here, consumed there
                    if writing is not None:
                        writing.result()  # the previous piece is written (or its error raised)
                    while len(measuring) >= SUMMARY_LAG:
                        measuring.popleft().result()
                    sink.meta = piece.meta
                    writing = files.submit(sink.write, piece)
                    if sink.summary is not None:
                        held.append(piece)
                        if len(held) > delay:
                            measuring.append(measures.submit(sink.measure, held.popleft()))
                if writing is not None:
                    writing.result()
                # the data files are finished there, the last pieces measured there, while
                # the figure is drawn here
                writing = files.submit(sink.close, done)
                measuring.extend(measures.submit(sink.measure, p) for p in held)
                held.clear()
                if stage is not None and sink.thin is not None:
                    from . import figures

                    figure = figures.render(scene, sink.thin.trajectory(sink.meta))
                    (stage / f"{scene.name}.{out['figure_format']}").write_bytes(figure)
                while measuring:
                    measuring.popleft().result()
                done.set()
                writing.result()
            except BaseException:
                done.set()
                for future in (writing, *measuring):
                    if future is not None:  # not started: dropped; started: its pool waits
                        future.cancel()
                raise
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


class _Sink:
    """Where the pieces of a run go: its data files, its summary, its figure's copy."""

    def __init__(self, scene: Scene, stage: Path | None, summarise: bool):
        from .summary import RunSummary

        out, name = scene.data["output"], scene.name
        self.scene, self.meta = scene, None
        self.writers, self.paths = [], []
        if stage is not None:
            for fmt in out["data"]:
                path = stage / f"{name}{FORMATS[fmt].suffix}"
                self.writers.append(FORMATS[fmt].open(path, scene))
                self.paths.append(path)
        self.summary = RunSummary(scene) if summarise else None
        self.figure = stage is not None and bool(out["plots"])
        self.thin = self.balance = None

    def write(self, piece: Trajectory) -> None:
        """Append ``piece`` to the data files and the figure's thinned copy (the summary,
        a long run's largest cost, has a thread to itself)."""
        for writer in self.writers:
            writer.append(piece)
        self._thin(piece)

    def measure(self, piece: Trajectory) -> None:
        """Add ``piece`` to the summary."""
        if self.summary is not None:
            self.summary.add(piece)

    def _thin(self, piece: Trajectory) -> None:
        from .figures import energy_balance_drawn
        from .thinning import ThinnedCopy

        if self.thin is None and self.figure:
            meta = piece.meta
            every = meta["sample_every"]
            count = meta["steps"] // every + 1 + (1 if meta["steps"] % every else 0)
            t_end = float(piece.t[0]) + meta["steps"] * meta["step"]
            self.thin = ThinnedCopy(float(piece.t[0]), t_end, count)
            if not self.thin.keep_all and energy_balance_drawn(self.scene):
                self.balance = _Balance(self.scene)
        if self.thin is not None:
            self.thin.add(piece if self.balance is None else self.balance.add(piece))

    def close(self, done=None) -> None:
        """Finish the data files, then start writing those that went through the page
        cache to disk, a slice at a time until ``done`` (a ``threading.Event``) is set,
        when the run has nothing else to do: on ext4 the moves into place would otherwise
        start it and wait (:func:`ga_rotors.files.start_writeback`); what is left then is
        left to them (or, on other file systems, to the system). A file written straight
        to the disk (its writer's ``direct``: the CSV, where the file system allows it)
        is already there."""
        from ..files import start_writeback

        for writer in self.writers:
            writer.close(self.meta)
        for writer, path in zip(self.writers, self.paths, strict=True):
            if getattr(writer, "direct", False) or not path.is_file():
                continue  # on the disk already; a store (a folder) is many small files
            for start in range(0, path.stat().st_size, WRITEBACK_SLICE):
                if done is not None and done.is_set():
                    return
                start_writeback(path, start, WRITEBACK_SLICE)

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
    ['heavy_top.csv', 'heavy_top.png', 'heavy_top.summary.txt', 'heavy_top.scene.toml']
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
    ['spinning_disk.csv', 'spinning_disk.scene.toml']
    """
    from ..files import output_set

    if not _declared(scene):
        return []
    with output_set(out_dir, "--out") as stage:
        _write(scene, [trajectory], stage, False)
        if summary is not None:
            (stage / f"{scene.name}.summary.txt").write_text(summary + "\n", "utf-8")
    return [Path(out_dir) / n for n in _names(scene, summary is not None)]
