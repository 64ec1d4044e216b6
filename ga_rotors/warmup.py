"""Compile ahead: the loops a command needs, in parallel processes, once per installed version.

The first run of a loop compiles it (numba, seconds of CPU per loop) and stores the machine
code (see docs/cache.md); every later process loads it. :func:`warm` moves that first
compilation out of the command a user is waiting for: each :class:`Task` is a tiny run of
the real work (one scene on one orientation path, 2 output steps, run in pieces and its
data written as ``ga-rotors run`` does; the paper's computations and CSV files on 10
steps) that leaves the compiled code in the cache, run here or in
forked worker processes. A task that succeeded is remembered by a marker file under the
cache directory, named by the package version and the task, so a warm cache costs a few
file checks.

``ga-rotors cache --warm`` warms everything the bundled commands use (the paper and
every bundled scene) in forked worker processes, one per CPU, each task in a fresh worker
that ends with it: Ctrl-C, SIGTERM or an error in the parent kills and reaps the running
workers (and on Linux a worker dies with its parent however that ends), and numba writes
each cache file whole before renaming it into place, so an interrupted warm-up leaves a
usable cache that the next run completes. ``ga-rotors paper`` and ``ga-rotors run`` warm
what they need in their own process, one progress line per task, when their tasks have
not been done yet: that keeps the compiled code in memory for the run that follows, and
costs the least CPU: parallel workers each compile again the kernels every loop shares,
and shorten the wall time only where cores are idle (``benchmarks/bench_first_run.py
--only workers``; docs/cache.md).
"""

from __future__ import annotations

import hashlib
import os
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
    matplotlib) and the CSV files, whose compiled number formatting is cached too."""
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
    """The paper's tasks and every bundled scene's.

    Tasks whose loop (integrator, path, kinds of effect) an earlier task compiles come
    last, so that parallel workers do not compile the same loop at once; they still run,
    for what else their scene computes (its exact reference, its outputs).

    Examples
    --------
    >>> tasks = all_tasks()
    >>> len(tasks) == len({t.key() for t in tasks})
    True
    """
    from .scene import bundled

    first, later, seen, keys = [], [], set(), set()
    for task in [*paper_tasks(), *(t for name in bundled() for t in scene_tasks(name))]:
        if task.key() in keys:  # the paper's scene is also bundled
            continue
        keys.add(task.key())
        if task.scene is not None:
            d = task.scene.data
            what = (d["integrator"]["method"], tuple(task.scene.paths),
                    tuple(sorted(e["type"] for e in d["effects"])))  # fmt: skip
            if what in seen:
                later.append(task)
                continue
            seen.add(what)
        first.append(task)
    return first + later


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
    except Exception as exc:  # reported by the parent, which goes on with the others
        return time.perf_counter() - start, f"{type(exc).__name__}: {exc}"
    return time.perf_counter() - start, None


def _become_worker(parent: int, unblock) -> None:
    """In a forked worker: die at once on SIGTERM or Ctrl-C, and with the parent.

    The parent's handlers (SIGTERM raised as an exception, SIGINT as KeyboardInterrupt)
    would be caught around the task, and the worker would go on compiling, orphaned once
    the parent had gone. A worker stopped mid-compilation leaves numba's cache usable: its
    files are written whole under a temporary name, then renamed into place.
    """
    import signal

    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    _block(False, unblock)
    if sys.platform.startswith("linux"):  # the kernel ends the worker if the parent dies
        try:
            import ctypes

            ctypes.CDLL(None).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent:  # the parent died before the line above
        os._exit(1)


def _block(block: bool, previous=None):
    """Hold back (or let through again) Ctrl-C and SIGTERM; returns the mask to restore."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        return None
    if block:
        return signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
    if previous is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)
    return None


def _start(task: Task, unblock=None) -> tuple[int, int]:
    """Fork a worker for ``task``; return its pid and the pipe its result comes through.
    ``unblock``: the signal mask the worker restores once its handlers are the defaults."""
    parent = os.getpid()
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - runs in the worker, which reports through the pipe
        status = 1
        try:
            os.close(read)
            _become_worker(parent, unblock)
            took, error = _run_one(task)
            # small enough for the pipe's buffer: the write never waits for the parent
            os.write(write, repr((took, None if error is None else error[:500])).encode())
            status = 0
        finally:
            os._exit(status)
    os.close(write)
    return pid, read


def _result(text: bytes, status: int) -> tuple[float, str | None]:
    """The result a finished worker sent, or why it sent none."""
    import ast

    if text:
        try:
            return ast.literal_eval(text.decode())
        except (ValueError, SyntaxError, UnicodeDecodeError):  # killed while writing it
            return 0.0, "the worker ended while reporting its result"
    if os.WIFSIGNALED(status):
        return 0.0, f"the worker was killed (signal {os.WTERMSIG(status)})"
    return 0.0, f"the worker ended without a result (exit status {os.WEXITSTATUS(status)})"


def _in_workers(todo: list[Task], n: int, done) -> None:
    """Run each task in its own forked worker, at most ``n`` at once, calling ``done`` as
    each ends. A worker forked after another ended loads what that one compiled from the
    disk cache instead of compiling it again. Whatever stops the parent (Ctrl-C, SIGTERM,
    an error) kills and reaps every running worker first: none is left behind."""
    import select
    import signal

    running: dict[int, tuple[int, Task]] = {}  # the result pipe -> (pid, task)
    waiting = list(todo)
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        while waiting or running:
            # the first task alone: it compiles what every task shares (the kernels, the
            # references, the conversions), which the workers after it then load from the
            # disk instead of each compiling it again (measured once under load: the whole
            # warm-up 12.5 s CPU instead of 16.4 s with all at once; 9.7 s in one process)
            while waiting and len(running) < (1 if len(waiting) == len(todo) - 1 else n):
                task = waiting.pop(0)
                # Ctrl-C or SIGTERM between the fork and this record would leave the new
                # worker out of the clean-up below: they wait until it is recorded
                blocked = _block(True)
                try:
                    pid, read = _start(task, blocked)
                    running[read] = (pid, task)
                finally:
                    _block(False, blocked)
            # a pipe is ready when its worker wrote its result and ended (or just ended)
            ready, _, _ = select.select(list(running), [], [])
            for read in ready:
                pid, task = running.pop(read)
                with os.fdopen(read, "rb") as fh:
                    text = fh.read()
                _, status = os.waitpid(pid, 0)
                done(task, *_result(text, status))
    finally:
        for pid, _ in running.values():
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        for read, (pid, _) in running.items():
            try:
                os.waitpid(pid, 0)
            except ChildProcessError:
                pass
            os.close(read)


def warm(
    tasks, processes: int | None = None, stream=None, show: bool = True
) -> list[tuple[Task, str]]:
    """Run the tasks not done yet for this version, in parallel forked processes.

    Parameters
    ----------
    tasks : list of Task
    processes : int, optional
        At most this many at once (default: the number of CPUs).
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
    n = max(1, min(processes or os.cpu_count() or 1, len(todo)))
    start = time.perf_counter()
    print(
        f"ga-rotors: compiling {len(todo)} loop set(s) in {n} process(es), once per installed "
        "version (`ga-rotors cache --warm` does this ahead)",
        file=stream,
        flush=True,
    )
    failed = []
    count = 0

    def done(task: Task, took: float, error: str | None) -> None:
        nonlocal count
        count += 1
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

    if n == 1 or not hasattr(os, "fork"):
        for task in todo:
            done(task, *_run_one(task))
    else:
        _in_workers(todo, n, done)
    print(f"ga-rotors: compiled in {time.perf_counter() - start:.1f} s", file=stream, flush=True)
    return failed
