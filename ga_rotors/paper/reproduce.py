"""Reproduce the paper's gyroscope into a directory: summary, CSV data and figures.

:func:`reproduce` runs :func:`ga_rotors.paper.runs.run_all` and writes ``summary.txt``,
one CSV per run and the figures of :mod:`ga_rotors.paper.figures`, drawn by a standard
process pool while this process simulates and writes the data (``ga-rotors paper`` does
this).
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from ..errors import GaRotorsError

__all__ = ["DEFAULT_OUT", "reproduce"]

DEFAULT_OUT = "results"
#: The figures each drawing process draws (two cores: two processes, while this one
#: simulates and then writes the CSV files), balanced by measured drawing cost.
_SHARES = (
    ("fig03_euler_angles_15deg", "fig05_quaternion_15deg", "fig07_rotor_angles_0.001deg",
     "fig08_euler_rates_0.001deg", "fig09_body_rates_0.001deg"),
    ("fig04_body_rates_15deg", "fig06_euler_path_0.001deg", "fig06_07_overlay_0.001deg",
     "fig10_quaternion_0.001deg", "errors"),
)  # fmt: skip


#: Figure formats ``reproduce`` writes: PNG (default), or vector SVG/PDF.
FORMATS = ("png", "svg", "pdf")  # the keys of ga_rotors.paper.figures.FIGURE_FORMATS


def _drawing_pool() -> ProcessPoolExecutor:
    """A pool of one process per share of the figures, started now, so that they import
    matplotlib (the slow import) while this process simulates.

    Building figures costs more CPU than the simulations, hence processes. They are
    forked from a clean server process that has imported the figures' modules once
    (``forkserver``; ``spawn`` where there is none), never from this process and its
    threads, and end when this process ends, even killed (:mod:`ga_rotors._children`)."""
    from .._children import context, exit_with_parent

    ctx = context()
    if ctx.get_start_method() == "forkserver":
        ctx.set_forkserver_preload(["ga_rotors.paper.figures", "matplotlib.figure"])
    pool = ProcessPoolExecutor(len(_SHARES), mp_context=ctx, initializer=exit_with_parent)
    for _ in _SHARES:
        pool.submit(_ready)
    return pool


def _ready() -> None:
    """A drawing process's first job: the imports its figures need."""
    import matplotlib.figure  # noqa: F401

    from . import figures  # noqa: F401


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
        Write ``summary.txt`` and one CSV per scene (``paper_15deg.csv``, ...), each with
        its CSVW metadata (``paper_15deg.csv-metadata.json``).
    parallel : bool
        Draw the figures in a process pool while the data are computed and written, and
        first compile the loops not cached yet with a progress line on stderr
        (:mod:`ga_rotors.warmup`); the command line does this.
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
    >>> [p.name for p in written if p.suffix != ".json"]
    ['summary.txt', 'paper_15deg.csv', 'paper_0.001deg.csv', 'disk_15deg.csv', 'disk_0.001deg.csv']
    >>> sum(p.name.endswith(".csv-metadata.json") for p in written)
    4
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
    pool = _drawing_pool() if figures and parallel else None
    try:
        if parallel:  # the first run after an install or upgrade compiles, and says so,
            # while the drawing processes import matplotlib
            from ..warmup import paper_tasks, warm

            warm(paper_tasks())
        from ..files import write_text
        from ..results.table import write_csv_files
        from . import figures as paper_figures
        from .digest import data_digest
        from .runs import run_all, summary

        runs = run_all()
        drawn = []
        if figures:
            job = (paper_figures.figure_data(runs), stage, data_digest(runs))
            if pool is not None:
                drawn = [pool.submit(paper_figures.draw_all, *job, share, fmt=fmt)
                         for share in _SHARES]  # fmt: skip
        written = []
        if data:
            text = summary(runs) + "\n"
            written.append(write_text(stage / "summary.txt", text))
            for s in runs:  # each CSV with its CSVW metadata, moved in with the set
                written += write_csv_files(s.trajectory, stage / f"{s.key}.csv")
        if figures and pool is None:
            written += paper_figures.draw_all(*job, fmt=fmt)
        by_name = {}
        for future in drawn:  # a share that failed fails the set (the data are not moved in)
            try:
                by_name.update((p.stem, p) for p in future.result())
            except Exception as exc:
                raise GaRotorsError(
                    f"drawing the figures failed: {type(exc).__name__}: {exc}"
                ) from None
    finally:
        if pool is not None:
            pool.shutdown(cancel_futures=True)
    written += [by_name[stem] for stem in paper_figures.FIGURES if stem in by_name]
    return runs, written
