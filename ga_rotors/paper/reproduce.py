"""Reproduce the paper's gyroscope into a directory: summary, CSV data and figures.

:func:`reproduce` runs :func:`ga_rotors.paper.runs.run_all` and writes ``summary.txt``,
one CSV per run and the figures of :mod:`ga_rotors.paper.figures`, drawn in forked
worker processes while the parent simulates (``ga-rotors paper`` does this).
"""

from __future__ import annotations

import os
import pickle
import sys
from pathlib import Path

from ..errors import GaRotorsError

__all__ = ["DEFAULT_OUT", "reproduce"]

DEFAULT_OUT = "results"
#: The figures each forked worker draws (two cores: two workers, while the parent
#: simulates and then writes the CSV files), balanced by measured drawing cost.
_SHARES = (
    ("fig03_euler_angles_15deg", "fig05_quaternion_15deg", "fig07_rotor_angles_0.001deg",
     "fig08_euler_rates_0.001deg", "fig09_body_rates_0.001deg"),
    ("fig04_body_rates_15deg", "fig06_euler_path_0.001deg", "fig06_07_overlay_0.001deg",
     "fig10_quaternion_0.001deg", "errors"),
)  # fmt: skip


#: Figure formats ``reproduce`` writes: PNG (default), or vector SVG/PDF.
FORMATS = ("png", "svg", "pdf")  # the keys of ga_rotors.paper.figures.FIGURE_FORMATS


class _Drawer:
    """One forked figure process: it receives the figure data through a pipe, draws its
    share of the figures and sends back the paths (or the error) through another.

    Building figures costs more CPU than the simulations, so two such processes share the
    figures while the parent simulates and then writes the CSV files. They are started by
    :func:`_start_drawers`, before the parent imports numba or starts any thread.
    """

    def __init__(self, stems: tuple[str, ...]):
        self.stems = stems
        self.pid: int | None = None  # the parent waits for the first drawer only
        self._to_child = os.pipe()
        self._to_parent = os.pipe()

    def _close_parent_ends(self) -> None:
        os.close(self._to_child[1])
        os.close(self._to_parent[0])

    def _close_child_ends(self) -> None:
        os.close(self._to_child[0])
        os.close(self._to_parent[1])

    def _serve(self, children=()) -> None:  # pragma: no cover - runs in a forked child
        try:
            from . import figures

            with os.fdopen(self._to_child[0], "rb") as fh:
                job = pickle.load(fh)
            if job is None:
                result = ("skipped", [])
            else:
                data, out, digest, fmt = job
                result = ("ok", figures.draw_all(data, out, digest, self.stems, fmt=fmt))
        except BaseException as exc:  # reported to the parent, which raises it
            result = ("error", f"{type(exc).__name__}: {exc}")
        try:
            with os.fdopen(self._to_parent[1], "wb") as fh:
                pickle.dump(result, fh)
            for pid in children:
                os.waitpid(pid, 0)
        finally:
            os._exit(0)

    def send(self, job) -> None:
        with os.fdopen(self._to_child[1], "wb") as fh:
            pickle.dump(job, fh, protocol=pickle.HIGHEST_PROTOCOL)

    def result(self) -> list[Path]:
        try:
            with os.fdopen(self._to_parent[0], "rb") as fh:
                status, value = pickle.load(fh)
        except EOFError:
            status, value = "error", "the figure process died"
        finally:
            if self.pid is not None:
                os.waitpid(self.pid, 0)
        if status == "error":
            raise GaRotorsError(f"drawing the figures failed: {value}")
        return value


def _start_drawers(shares) -> list[_Drawer]:
    """Fork the figure processes: the first imports matplotlib (the slow import, overlapped
    with the parent's simulation) and then forks the others from itself, so they share
    that import instead of each paying it (about 0.7 s of CPU per process, on two cores
    that also run the parent)."""
    drawers = [_Drawer(share) for share in shares]
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - runs in the child, which reports through the pipes
        for d in drawers:
            d._close_parent_ends()
        try:
            import matplotlib.figure  # noqa: F401

            from . import figures  # noqa: F401
        except BaseException:  # each drawer imports again, and reports the error
            pass
        children = []
        for d in drawers[1:]:
            child = os.fork()
            if child == 0:
                for other in drawers:
                    if other is not d:
                        other._close_child_ends()
                d._serve()
            children.append(child)
            d._close_child_ends()
        drawers[0]._serve(children)
    for d in drawers:
        d._close_child_ends()
    drawers[0].pid = pid
    return drawers


def reproduce(
    out_dir=DEFAULT_OUT,
    figures: bool = True,
    data: bool = True,
    parallel: bool = False,
    fmt: str = "png",
):
    """Run the paper's scenes and write summary, CSV data and figures into ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Created if missing. The files are written all together or not at all
        (:func:`ga_rotors.files.output_set`): a failed or killed run leaves the previous set.
    figures : bool
        Write the PNG figures (``fig03_…png`` to ``fig10_…png``, ``errors.png``).
    data : bool
        Write ``summary.txt`` and one CSV per scene (``paper_15deg.csv``, ...).
    parallel : bool
        Draw the figures in forked processes (POSIX), and first compile the loops not
        cached yet with a progress line on stderr (:mod:`ga_rotors.warmup`); the command
        line does this.
    fmt : {"png", "svg", "pdf"}
        The figures' format: PNG at 150 dpi (default), or vector SVG/PDF for print.

    Returns
    -------
    runs : list of ga_rotors.paper.runs.PaperRun
    written : list of pathlib.Path
        Files written, as one set (a failed run leaves the previous set, no partial one).

    Examples
    --------
    >>> import tempfile
    >>> runs, written = reproduce(tempfile.mkdtemp(), figures=False)
    >>> [p.name for p in written]
    ['summary.txt', 'paper_15deg.csv', 'paper_0.001deg.csv', 'disk_15deg.csv', 'disk_0.001deg.csv']
    >>> max(s.rotor_vs_quaternion for s in runs) < 1e-12
    True
    """
    from ..files import output_set

    if fmt not in FORMATS:
        from ..errors import InputError

        raise InputError(f"--format: expected one of {', '.join(FORMATS)}, got {fmt!r}")
    out = Path(out_dir)
    with output_set(out, "--out") as stage:  # the whole set or the previous one
        written = _write_all(stage, figures, data, parallel, fmt)
    return written[0], [out / p.name for p in written[1]]


def _write_all(stage: Path, figures: bool, data: bool, parallel: bool, fmt: str = "png"):
    drawers = []
    if figures and parallel and hasattr(os, "fork"):
        drawers = _start_drawers(_SHARES)
    sent = 0
    try:
        if parallel:  # the first run after an install or upgrade compiles, and says so,
            # while the figure processes import matplotlib
            from ..warmup import paper_tasks, warm

            warm(paper_tasks(), processes=1)
        from ..files import write_text
        from . import figures as paper_figures
        from .digest import data_digest
        from .runs import run_all, summary

        runs = run_all()
        job = None
        if figures:
            job = (paper_figures.figure_data(runs), stage, data_digest(runs), fmt)
        for drawer in drawers:
            drawer.send(job)
            sent += 1
        written = []
        if data:
            text = summary(runs) + "\n"
            written.append(write_text(stage / "summary.txt", text))
            written += [s.trajectory.to_csv(stage / f"{s.key}.csv") for s in runs]
        if figures and not drawers:
            written += paper_figures.draw_all(*job[:3], fmt=fmt)
    finally:
        for drawer in drawers[sent:]:  # failed before the figures were handed over
            try:
                drawer.send(None)
            except OSError:  # interrupted (SIGTERM) while sending: its pipe is closed
                pass
        results = []
        for drawer in drawers:  # collect every worker, then report the first failure
            try:
                results.append(drawer.result())
            except GaRotorsError as exc:
                results.append(exc)
    for r in results:
        if isinstance(r, Exception):
            raise r
    by_name = {p.stem: p for r in results for p in r}
    written += [by_name[stem] for stem in paper_figures.FIGURES if stem in by_name]
    return runs, written
