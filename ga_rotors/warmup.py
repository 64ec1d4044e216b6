"""Compile ahead: the loops a command needs, once per installed version.

The first run of a loop compiles it (numba, seconds of CPU per loop) and stores the machine
code (see docs/cache.md); every later process loads it. :func:`warm` moves that first
compilation out of the command a user is waiting for: each :class:`Task` is a tiny run of
the real work (one scene on one orientation path, 2 output steps, run in pieces and its
data written as ``ga-rotors run`` does; the paper's computations and CSV files on 10
steps) that leaves the compiled code in the cache. A task that succeeded is remembered by
a marker file under the cache directory, named by the package version and the task, so a
warm cache costs a few file checks.

``ga-rotors cache --warm`` warms everything the bundled commands use (the paper and every
bundled scene); ``ga-rotors paper`` and ``ga-rotors run`` warm what they need when their
tasks have not been done yet. Either way the tasks run here, in this process, one after
the other, one progress line each: numba compiles under the interpreter's lock, so
threads would not overlap, and worker processes would each compile again the kernels
every loop shares (20 % more CPU, measured) for wall time gained only on idle cores;
in this process the compiled code also stays in memory for the run that follows. Ctrl-C
stops it at the task it is in: numba writes each cache file whole before renaming it into
place, so an interrupted warm-up leaves a usable cache that the next run completes.
"""

from __future__ import annotations

import hashlib
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Task", "all_tasks", "paper_tasks", "scene_tasks", "warm"]

#: Output steps a scene task integrates: enough to run every code path of the loop.
TASK_SAMPLES = 2


@dataclass(frozen=True)
class Task:
    """A tiny run that compiles some loops: a scene, or the paper's computations (None).

    Examples
    --------
    >>> t = scene_tasks("heavy_top")[0]
    >>> t.label, t.scene.paths, t.scene.steps
    ('heavy_top: rotor path', ['rotor'], 10)
    """

    label: str
    scene: object = None

    def key(self) -> str:
        """What the task compiles, as 16 hex digits: the same work gives the same key.

        Examples
        --------
        >>> a, b = scene_tasks("heavy_top")
        >>> len(a.key()), a.key() == scene_tasks("heavy_top")[0].key(), a.key() == b.key()
        (16, True, False)
        """
        text = "paper" if self.scene is None else self.scene.to_toml()
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def run(self) -> None:
        """Do the tiny run (its results are discarded; the compiled code stays cached).

        Examples
        --------
        >>> scene_tasks("spinning_disk")[0].run()
        """
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a 2-sample run may trip checks the real one won't
            if self.scene is None:
                _paper_computations()
            else:  # the way ``ga-rotors run`` runs it: in pieces, its files written
                import tempfile

                from .scene import stream_scene

                with tempfile.TemporaryDirectory() as tmp:
                    stream_scene(self.scene, Path(tmp) / "out")
                _thin_once()


def _thin_once() -> None:
    """Thin three rows as a long run's figure is thinned: its compiled passes, which a
    warm-up run (a few samples, kept whole) never reaches."""
    import numpy as np

    from .scene.thinning import KEEP_ALL, ThinnedCopy
    from .trajectory import Trajectory

    copy = ThinnedCopy(0.0, 1.0, KEEP_ALL + 1)
    copy.add(Trajectory({"t": np.linspace(0.0, 1.0, 3), "w": np.zeros((3, 3))}))


def _paper_computations() -> None:
    """What ``ga-rotors paper`` computes and writes, on 10 steps, its files discarded: the
    summary, the figures' data and digest (not drawn: the figure processes only import
    matplotlib) and the CSV files."""
    import tempfile

    from .paper.digest import data_digest
    from .paper.figures import figure_data
    from .paper.runs import run_all, summary

    runs = run_all(steps=10)
    summary(runs)
    figure_data(runs)
    data_digest(runs)
    with tempfile.TemporaryDirectory() as tmp:
        for run in runs:
            run.trajectory.to_csv(Path(tmp) / f"{run.key}.csv")


def scene_tasks(scene) -> list[Task]:
    """One task per orientation path of ``scene`` (a Scene, a file or a bundled name).

    Examples
    --------
    >>> [t.label for t in scene_tasks("paper_15deg")]
    ['paper_15deg: rotor path', 'paper_15deg: quaternion path', 'paper_15deg: euler path']
    """
    from .scene import load_scene

    scene = load_scene(scene)
    span = TASK_SAMPLES * scene.sample_every * scene.step
    changes = {"time.duration": span, "output.plots": []}
    return [
        Task(f"{scene.name}: {path} path", scene.replace({**changes, "integrator.paths": [path]}))
        for path in scene.paths
    ]


def paper_tasks() -> list[Task]:
    """What ``ga-rotors paper`` compiles: the paper scene's three paths, then the rest of
    its computations (references, conversions, cross-checks).

    Examples
    --------
    >>> [t.label for t in paper_tasks()][-1]
    'paper: its other computations'
    """
    return [*scene_tasks("paper_15deg"), Task("paper: its other computations")]


def all_tasks() -> list[Task]:
    """The paper's tasks and every bundled scene's, each once.

    Examples
    --------
    >>> tasks = all_tasks()
    >>> len(tasks) == len({t.key() for t in tasks})
    True
    """
    from .scene import bundled

    tasks: dict[str, Task] = {}  # the paper's scene is also bundled: once
    for task in [*paper_tasks(), *(t for name in bundled() for t in scene_tasks(name))]:
        tasks.setdefault(task.key(), task)
    return list(tasks.values())


def _marker_dir() -> Path | None:
    from .integrators import _cache

    directory = _cache.cache_location()
    return None if directory is None else directory / "warm"


def _marker(directory: Path, task: Task) -> Path:
    from .integrators import _cache

    return directory / f"{_cache.version_tag()}-{task.key()}"


def clear_markers(every_version: bool = False) -> int:
    """Forget which tasks this version (or every version) did (``ga-rotors cache --clear``);
    return how many markers went.

    Examples
    --------
    >>> clear_markers() >= 0
    True
    """
    from .integrators import _cache

    directory = _marker_dir()
    removed = 0
    mine = _cache.version_tag() + "-"
    if directory is not None and directory.is_dir():
        for f in directory.iterdir():
            if not (every_version or f.name.startswith(mine)):
                continue
            try:
                f.unlink()
                removed += 1
            except OSError:
                pass
    return removed


def _run_one(task: Task) -> tuple[float, str | None]:
    start = time.perf_counter()
    try:
        task.run()
    except Exception as exc:  # reported, and the others go on ...
        stop = _interruption(exc)
        if stop is not None:  # ... unless it is Ctrl-C or SIGTERM that a library wrapped
            raise stop from None
        return time.perf_counter() - start, f"{type(exc).__name__}: {exc}"[:500]
    return time.perf_counter() - start, None


def _interruption(exc: BaseException) -> BaseException | None:
    """The interruption (Ctrl-C, SIGTERM as the command raises it: any BaseException that
    is not an Exception) that caused ``exc``, if one did: a compiler or an import that
    catches everything may hand it on wrapped in an error of its own, and a warm-up that
    took it for a failed task went on to the next one.

    Examples
    --------
    >>> try:
    ...     try:
    ...         raise KeyboardInterrupt
    ...     except BaseException as inner:
    ...         raise RuntimeError("while importing") from inner
    ... except RuntimeError as exc:
    ...     type(_interruption(exc)).__name__
    'KeyboardInterrupt'
    >>> _interruption(ValueError("a real failure")) is None
    True
    """
    seen = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        if not isinstance(exc, Exception):
            return exc
        exc = exc.__cause__ or exc.__context__
    return None


def warm(tasks, stream=None, show: bool = True) -> list[tuple[Task, str]]:
    """Run the tasks not done yet for this version, here, one after the other.

    Parameters
    ----------
    tasks : list of Task
    stream : file, optional
        Where the progress lines go (default: sys.stderr); nothing is written when every
        task was done already.
    show : bool
        Write the progress lines at all (``ga-rotors run`` shows them where it shows its
        progress bar: on a terminal, or with ``--progress``).

    Returns
    -------
    list of (Task, str)
        The tasks that failed, with the error; the command that needs them then meets
        the same error itself, with its own message.

    Examples
    --------
    >>> import io
    >>> warm(scene_tasks("spinning_disk"), stream=io.StringIO())
    []
    >>> log = io.StringIO()
    >>> warm(scene_tasks("spinning_disk"), stream=log), log.getvalue()     # done already
    ([], '')
    """
    if not show:
        import io

        stream = io.StringIO()
    stream = sys.stderr if stream is None else stream
    directory = _marker_dir()
    if directory is None:  # no cache: every process compiles in memory anyway
        return []
    todo = [t for t in tasks if not _marker(directory, t).exists()]
    if not todo:
        return []
    start = time.perf_counter()
    print(
        f"ga-rotors: compiling {len(todo)} loop set(s), once per installed version "
        "(`ga-rotors cache --warm` does this ahead)",
        file=stream,
        flush=True,
    )
    failed = []
    for count, task in enumerate(todo, 1):
        took, error = _run_one(task)
        if error is None:
            try:
                directory.mkdir(mode=0o700, parents=True, exist_ok=True)
                _marker(directory, task).touch()
            except OSError:
                pass
        else:
            failed.append((task, error))
        status = "" if error is None else f" failed: {error.splitlines()[0] if error else ''}"
        line = f"  [{count}/{len(todo)}] {task.label} ({took:.1f} s){status}"
        print(line, file=stream, flush=True)
    print(f"ga-rotors: compiled in {time.perf_counter() - start:.1f} s", file=stream, flush=True)
    return failed
