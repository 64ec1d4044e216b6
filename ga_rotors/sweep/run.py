"""Running a sweep on Dask into a chunked zarr store, resumably.

The store is created whole first (in a staging directory, then renamed into place): every
variable at its full size, chunked along ``sample`` as the sweep's ``chunk``, plus a
``chunk_done`` flag per chunk (:mod:`ga_rotors.sweep.store`). Each Dask task draws one
chunk's values, integrates them and reduces them (the angle from the nominal), writes its
blocks (raw chunk files: nothing to encode), and only then sets the chunk's flag. Where
the varied keys are a body's moments and rates on the quaternion path, one compiled pass
(:func:`ga_rotors.ensemble.run_columns`) makes each sample's inputs from its values,
integrates it and records its states and angle in the store's layout; otherwise the
chunk's inputs are built (:func:`ga_rotors.ensemble.scene_samples`, a Scene per sample
where a key needs it), integrated on the serial batched loop
(:func:`ga_rotors.ensemble.run_samples`) and reduced. Both give the same numbers.
Running the same sweep into the same store again skips the flagged chunks: an
interrupted sweep resumes from its finished chunks, and a chunk cut off halfway is done
again. A store holds one sweep (its digest is an attribute); another sweep is refused.

Where the tasks run:

* by default, on Dask's threaded scheduler in this process, one thread per core: the
  compiled loops, numpy and the writes release the GIL, so the threads integrate side by
  side with no scheduler, serialisation or worker processes in between (a local
  ``distributed`` cluster of two processes cost 30-45 % of a 100-step sweep's kernel time
  on two cores; see benchmarks/bench_ensemble.py). Each thread integrates a chunk,
  reduces it and hands it to this process's writer thread, which writes it (the chunk
  files go straight to the disk, so the writer mostly waits) while the thread
  integrates the next. The last chunks are cut into pieces that several threads
  integrate, so that no thread idles at the end;
* on a Dask cluster, through a ``distributed.Client`` (of a ``--scheduler`` address, or
  one given): one worker process per core with one thread each is the layout to start.
  A worker integrates one chunk while its writer thread writes the previous one;
* ``client="sync"``: in this process, one chunk after the other, with a second thread
  drawing the next chunk's inputs and a writer thread writing the previous one.
"""

from __future__ import annotations

import collections
import functools
import itertools
import os
import shutil
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import _kernels as K
from .._jit import jit
from ..errors import InputError, first_line
from ..optional import require
from . import budget as sweep_budget
from . import store as zstore
from .percentiles import percentiles
from .spec import DRAWS_VERSION, Sweep, load_sweep

__all__ = [
    "LOCAL_CLUSTER_CONFIG",
    "flush_writes",
    "histogram",
    "keep_freed_memory",
    "local_cluster",
    "open_sweep",
    "run_chunk",
    "run_sweep",
    "summary",
]


@dataclass(frozen=True)
class _Task:
    """What a worker needs: the sweep's text and base directory, the store, the nominal.

    ``layouts`` is :func:`ga_rotors.sweep.store.write_chunk`'s memory of the store's
    variables, shared by the threads of this process (a worker process fills its copy).
    """

    text: str
    file: str
    store: str
    nominal: np.ndarray
    layouts: dict = field(default_factory=dict, compare=False)


_SWEEPS: dict[tuple[str, str], Sweep] = {}


def _sweep(task: _Task) -> Sweep:
    key = (task.text, task.file)
    if key not in _SWEEPS:
        _SWEEPS[key] = load_sweep(Path(task.file) if task.file != "<string>" else task.text)
    return _SWEEPS[key]


def _bounds(sweep: Sweep, c: int) -> tuple[int, int]:
    return c * sweep.chunk, min(sweep.size, (c + 1) * sweep.chunk)


def _integrate(task: _Task, sweep: Sweep, lo: int, hi: int, columns=None):
    """(values, q, w, angle) of samples ``lo`` to ``hi - 1``, in the store's layout.

    ``columns`` is :meth:`Sweep.columns` of those samples when made beforehand. In one
    compiled pass from the values (:func:`ga_rotors.ensemble.run_columns`) where it
    applies; otherwise each sample's inputs are built (:func:`~ga_rotors.ensemble.
    scene_samples`, which names a bad value), integrated and reduced in turn. Both give
    the same numbers.
    """
    from ..ensemble import run_columns, run_samples, scene_samples

    cols, values = sweep.columns(lo, hi) if columns is None else columns
    done = run_columns(sweep.scene, sweep.rows, cols, sweep.times, task.nominal)
    if done is not None:
        return (values, *done)
    run = run_samples(scene_samples(sweep.scene, values, n=hi - lo), sweep.times, parallel=False)
    return values, run.q.transpose(1, 0, 2), run.w.transpose(1, 0, 2), _angle(task, run)


def _nominal(sweep: Sweep) -> np.ndarray:
    """The base scene's own orientations at the output times (k, 4)."""
    from ..ensemble import run_samples, scene_samples

    # one sample: no threads to start, and the serial loop the chunks load as well
    return run_samples(scene_samples(sweep.scene, n=1), sweep.times, parallel=False).q[:, 0]


def run_chunk(task: _Task, c: int, wait: bool = True, columns=None) -> int:
    """Integrate chunk ``c`` of the sweep and write it into the store; return ``c``.

    ``wait=False`` returns once the chunk is integrated and leaves its reduction and
    writing to this process's writer thread, which does them while the next chunk is
    integrated (the write is mostly waiting on the disk, the integration on the CPU); it
    first waits for the previous chunk's write, so at most one chunk is pending.
    :func:`flush_writes` waits for the last one. ``columns`` are the chunk's values
    (:meth:`Sweep.columns`) when they were drawn beforehand (by :func:`run_sweep` in
    this process).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "s.zarr"
    >>> text = '[sweep]\\nscene = "intermediate_axis_flip"\\nchunk = 1\\nsamples = 2\\n'
    >>> text += '[set]\\n"time.duration" = 0.01\\n[grid]\\n"body.mass" = [0.3, 0.4]\\n'
    >>> open_sweep(run_sweep(text, out, client="sync")).sizes["sample"]
    4
    """
    sweep = _sweep(task)
    job = functools.partial(_finish, task, c, *_integrate(task, sweep, *_bounds(sweep, c), columns))
    if wait:
        job()
    else:
        _write_behind(job)
    return c


def _angle(task: _Task, run) -> np.ndarray:
    """The angle from the nominal of each sample of ``run`` at each time: (sample, time)."""
    angle = np.empty(run.q.shape[1::-1])
    _angles(run.q, task.nominal, angle)
    return angle


def _finish(task: _Task, c: int, values: dict, q, w, angle, first=None, pieces=None) -> None:
    """Write chunk ``c``'s blocks (each with the sample first), then its flag.

    Each block covers one whole chunk of its variable, or with ``first`` (a piece of the
    chunk, ``pieces`` its :class:`_Pieces`) the piece's own rows of it, so writes never
    share rows; the flag goes last, written after the chunk's last piece: the chunk
    counts as done only once all of it is written.
    """
    blocks = {
        "q": q,  # (sample, time, 4)
        "w": w,
        "angle_from_nominal": angle,
        **{f"value_{j}": v for j, v in enumerate(values.values())},
    }
    for name, block in blocks.items():
        _write_block(task, name, block, c, first)
    if pieces is None or pieces.written():
        _write_block(task, "chunk_done", np.ones(1, dtype=np.int8), c, None)


def _write_block(task: _Task, name: str, block, c: int, first) -> None:
    try:
        zstore.write_chunk(task.store, name, block, c, task.layouts, first)
    except OSError as exc:  # a full disk, a store removed under the sweep...
        raise _write_error(task.store, exc, f"chunk {c} of {name}") from None


def _write_error(store, exc: OSError, what: str) -> InputError:
    # One line naming the store. An InputError pickles as its message, so a Dask
    # worker's reaches the command as it is.
    return InputError(f"cannot write {store} ({what}): {exc.strerror or exc}", key="--out")


@jit
def _angles(q, nominal, out):
    """out[i, j] = the angle of sample i (q[j, i], times first) from nominal[j].

    :func:`ga_rotors._kernels.angle_any_norm`: it does not depend on the norms, so an
    integrator that lets the norm drift (RK4 over a long or fast run) still has its
    angle, where :func:`ga_rotors.quaternion.distance` would refuse the whole chunk. A
    sample that is zero or stopped being finite gets NaN.
    """
    for j in range(q.shape[0]):
        b = (nominal[j, 0], nominal[j, 1], nominal[j, 2], nominal[j, 3])
        for i in range(q.shape[1]):
            out[i, j] = K.angle_any_norm((q[j, i, 0], q[j, i, 1], q[j, i, 2], q[j, i, 3]), b)


#: This process's writer thread and the writes it has pending, oldest first.
_WRITER: dict = {"executor": None, "pending": collections.deque()}
_WRITER_LOCK = threading.Lock()


def _write_behind(job, depth: int = 1) -> None:
    """Hand ``job`` to the writer thread, once fewer than ``depth`` writes are pending.

    A threaded run's threads finish their chunks at about the same time (equal chunks,
    started together): with room for one chunk each, neither waits for the other's write.
    """
    with _WRITER_LOCK:
        pending = _WRITER["pending"]
        while len(pending) >= depth:
            pending.popleft().result()  # a failed write raises here, in the task that waits
        if _WRITER["executor"] is None:
            _WRITER["executor"] = ThreadPoolExecutor(1, thread_name_prefix="ga_rotors-writer")
        pending.append(_WRITER["executor"].submit(job))


def _wait_pending() -> None:
    """Wait for every pending write; raise the first one's error, if any."""
    pending, error = _WRITER["pending"], None
    while pending:
        try:
            pending.popleft().result()
        except BaseException as exc:  # raised below, once all are done
            error = error or exc
    if error is not None:
        raise error


def flush_writes() -> None:
    """Wait until the chunks this process is writing in the background are written.

    Raises what the write raised. :func:`run_sweep` calls it here and on every Dask
    worker before it returns.

    Examples
    --------
    >>> flush_writes()  # nothing pending
    """
    with _WRITER_LOCK:
        _wait_pending()


def _output_times(sweep: Sweep) -> np.ndarray:
    scene = sweep.scene
    start, h = scene.data["time"]["start"], scene.step
    k = np.array([scene.steps]) if sweep.times is None else np.rint((sweep.times - start) / h)
    return start + h * k


#: Variables filled in chunk by chunk; everything else is written when the store is made.
_CHUNKED = ("q", "w", "angle_from_nominal", "chunk_done")


def _template(sweep: Sweep, nominal: np.ndarray, t: np.ndarray):
    """The whole store as a Dataset: what every chunk fills in, as fill values."""
    from ..results import provenance

    xr = require("xarray", "results")
    n, k = sweep.size, t.size

    def empty(*shape):
        return np.broadcast_to(np.nan, shape)

    data = {
        "q": (("sample", "time", "quaternion_component"), empty(n, k, 4), {
            "units": "1", "description": "orientation (w, x, y, z) of each sample"}),
        "w": (("sample", "time", "body_axis"), empty(n, k, 3), {
            "units": "rad/s", "description": "body angular velocity of each sample"}),
        "angle_from_nominal": (("sample", "time"), empty(n, k), {
            "units": "rad", "description": "geodesic angle from the base scene's orientation"}),
        "q_nominal": (("time", "quaternion_component"), nominal, {
            "units": "1", "description": "orientation of the base scene (no changes)"}),
        "chunk_done": (("chunk",), np.broadcast_to(np.int8(0), (sweep.chunks,)), {
            "description": "1 once the chunk's samples are written"}),
    }  # fmt: skip
    values = sweep.values(0, min(1, n))
    for j, (key, v) in enumerate(values.items()):
        dims = ("sample", *(f"value_{j}_component",) * (v.ndim - 1))
        data[f"value_{j}"] = (dims, empty(n, *v.shape[1:]), {"scene_key": key})
    # No coordinate on sample: sample s is at position s (an index of 10⁶ integers would be
    # written with the store and read back at every open, for nothing).
    coords = {
        "t": ("time", t, {"units": "s", "description": "output time"}),
        "quaternion_component": ["w", "x", "y", "z"],
        "body_axis": ["1", "2", "3"],
    }
    scene = sweep.scene
    meta = {
        "integrator": scene.data["integrator"]["method"],
        "step": scene.step,
        "steps": scene.steps,
        "torques": [term.name for term in scene.torques()],
    }
    attrs = provenance(meta, sweep.scene)
    attrs.update(
        title="ga_rotors sweep",
        sweep_toml=sweep.text,
        sweep_digest=sweep.digest,
        seed=-1 if sweep.seed is None else sweep.seed,
        draws_version=DRAWS_VERSION,
        samples_per_grid_point=sweep.samples,
        varied_keys=", ".join(sweep.keys),
    )
    ds = xr.Dataset(data, coords=coords, attrs=attrs)
    ds["chunk_done"].encoding["_FillValue"] = 0  # unwritten flags read as 0
    return ds


def _chunked(template) -> set[str]:
    return set(_CHUNKED) | {name for name in template.data_vars if name.startswith("value_")}


def _create(sweep: Sweep, store: Path, nominal: np.ndarray) -> None:
    """Create the store (all of it, or nothing) for the nominal orientations (k, 4).

    Metadata only for the chunked variables: unwritten chunks read as the fill value (NaN,
    and 0 for the flags). No compression: orientations and rates are full-precision noise
    to a compressor, which would only spend the workers' time.
    """
    template = _template(sweep, nominal, _output_times(sweep))
    try:
        staging = Path(tempfile.mkdtemp(dir=store.parent, prefix=f".{store.name}.staging-"))
    except OSError as exc:
        raise _write_error(store, exc, "creating it") from None
    try:
        zstore.create(
            staging / "new", template, {"sample": sweep.chunk, "chunk": 1}, _chunked(template)
        )
        os.rename(staging / "new", store)
    except OSError as exc:
        raise _write_error(store, exc, "creating it") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


#: Seconds to wait for a ``--scheduler`` to answer before saying it cannot be reached.
SCHEDULER_TIMEOUT = 10


def _client(client, scheduler: str | None):
    """(client, owned): an explicit ``distributed.Client``, or one of ``scheduler``."""
    if client is not None:
        return client, False
    distributed = require("distributed", "dask")
    try:
        # not the process's default scheduler: the sweep hands its client the tasks, and a
        # client that failed to connect must not stay behind as every later compute's
        # (a malformed address left it there, and the next .values hung)
        client = distributed.Client(scheduler, timeout=SCHEDULER_TIMEOUT, set_as_default=False)
        return client, True
    except (OSError, TimeoutError) as exc:
        raise InputError(f"--scheduler: cannot reach {scheduler}: {first_line(exc)}") from None
    except ValueError as exc:  # no port, an unknown scheme: distributed parses it first
        raise InputError(
            f"--scheduler: {scheduler!r} is not a scheduler address (tcp://host:port): {exc}"
        ) from None


#: Fewest samples in a piece of a chunk split between threads (see :func:`_parts`): a
#: task's fixed cost (Dask's, the inputs', the loop's call, its writes) is about 0.5 ms,
#: against 0.6 µs a sample for the loop at 100 steps.
MIN_PIECE = 4096

#: Pieces start at a multiple of this many samples where they can: 512 rows of float64
#: are a whole number of pages, so each piece's part of a chunk file goes straight to the
#: disk from its own first row (:func:`ga_rotors.files.write_direct`).
PIECE_ALIGN = 512


def _parts(sweep: Sweep, todo: list[int], threads: int) -> list[tuple[int, int, int, int]]:
    """The tasks of a run on ``threads`` threads: (chunk, first, end, pieces) each.

    One task per chunk, except the last ``threads`` chunks, cut into pieces of samples
    ``first`` to ``end - 1`` of the chunk that get smaller towards the end (each a
    ``2·threads``-th of the samples left, at least :data:`MIN_PIECE`, starting at a
    multiple of :data:`PIECE_ALIGN`): whole chunks alone leave threads idle at the end
    (16 chunks of a 10⁶-sample sweep, the last a quarter full, on two threads: one
    thread integrates 8 chunks while the other does 7¼, 5 % longer than an even split),
    and so do equal pieces when a thread has lost time to the writer: the last pieces
    are short, so the threads run out of work within a few milliseconds of each other.
    """
    out = []
    tail = todo[len(todo) - threads :] if threads > 1 else []
    left = sum(hi - lo for lo, hi in map(functools.partial(_bounds, sweep), tail))
    for c in todo[: len(todo) - len(tail)]:
        lo, hi = _bounds(sweep, c)
        out.append((c, 0, hi - lo, 1))
    for c in tail:
        lo, hi = _bounds(sweep, c)
        n, cuts = hi - lo, [0]
        while cuts[-1] < n:
            size = max(MIN_PIECE, left // (2 * threads))
            end = -(-(cuts[-1] + size) // PIECE_ALIGN) * PIECE_ALIGN
            if n - end < MIN_PIECE:  # no piece shorter than MIN_PIECE at the chunk's end
                end = n
            left -= end - cuts[-1]
            cuts.append(end)
        out += [(c, a, b, len(cuts) - 1) for a, b in itertools.pairwise(cuts)]
    return out


class _Pieces:
    """The pieces of one chunk, integrated and written by several threads: the last to be
    integrated counts the chunk as handed over, the last to be written flags it."""

    def __init__(self, count: int):
        self.integrating = self.writing = count
        self.lock = threading.Lock()

    def integrated(self) -> bool:
        """One piece integrated: True if it was the last."""
        with self.lock:
            self.integrating -= 1
            return not self.integrating

    def written(self) -> bool:
        """One piece written: True if it was the last."""
        with self.lock:
            self.writing -= 1
            return not self.writing


class _Started:
    """How many of a run's tasks have started, of ``total``."""

    def __init__(self, total: int):
        self.count, self.total = 0, total
        self.lock = threading.Lock()

    def one(self) -> None:
        with self.lock:
            self.count += 1

    def all(self) -> bool:
        with self.lock:
            return self.count == self.total


def _run_part(
    task: _Task,
    c: int,
    first: int,
    end: int,
    pieces: _Pieces | None,
    ready,
    started=None,
    depth: int = 1,
) -> bool:
    """Integrate samples ``first`` to ``end - 1`` of chunk ``c``; True if that handed over
    the whole chunk (its last piece).

    A whole chunk (``pieces`` None) is written by its task, then flagged. A piece writes
    its own rows of the chunk's files; the last piece written flags the chunk, so a chunk
    counts as done only once all of it is written, whatever the split. A sample's
    numbers depend on its index only (its draws, its own integration): a chunk made of
    pieces is the chunk made at once, bit for bit. ``ready()``, called before a write,
    makes the store if it is not made yet (once: see :class:`_Once`) and raises what
    making it raised. ``depth``: writes pending at most (see :func:`_write_behind`).
    Once every task has started (``started``, a :class:`_Started`), a task writes in this
    thread, which has nothing left to integrate, beside the writer thread's pending write
    rather than after it: the end of the sweep waits for both.
    """
    if started is not None:
        started.one()
    sweep = _sweep(task)
    start = c * sweep.chunk
    # reduced here, so that the pieces of the last chunks reduce side by side and the
    # writer thread, which the end of the sweep waits for, only writes
    done = _integrate(task, sweep, start + first, start + end)
    write = functools.partial(_ready_then_finish, ready, task, c, *done)
    if pieces is not None:
        write = functools.partial(write, first=first, pieces=pieces)
    if started is not None and started.all():
        write()
    else:  # written on this process's writer thread while this one integrates on
        _write_behind(write, depth)
    return pieces is None or pieces.integrated()


def _ready_then_finish(ready, task: _Task, c: int, *done, first=None, pieces=None) -> None:
    ready()
    _finish(task, c, *done, first=first, pieces=pieces)


class _Once:
    """``f()`` run by the first call, under a lock; every call raises what it raised."""

    def __init__(self, f):
        self.f, self.lock, self.done, self.error = f, threading.Lock(), False, None

    def __call__(self) -> None:
        with self.lock:
            if not self.done:
                try:
                    self.f()
                except BaseException as exc:  # raised to every caller
                    self.error = exc
                self.done = True
        if self.error is not None:
            raise self.error


def _run_threads(task: _Task, sweep: Sweep, todo: list[int], threads: int, done, ready) -> None:
    """Run chunks ``todo`` on Dask's threaded scheduler, ``threads`` at a time.

    Each task integrates a chunk (or a piece of one, see :func:`_parts`) on the serial
    loop and hands it to the writer thread (:func:`_write_behind`: at most one chunk
    pending), so the writes overlap the integration; the tasks that end the run write
    their chunks themselves, beside the writer. ``done()`` is called in this thread
    as each chunk is handed over; every handed chunk is written and flagged before this
    returns or raises.
    The pool is this call's own and is shut down before it returns or raises: an
    interrupted sweep (Ctrl-C reaches this thread, waiting for the next task) first lets
    the running tasks finish (Dask starts no more than ``threads`` tasks at a time, so
    nothing else is queued), and so leaves no write behind it; a chunk whose pieces did
    not all run is not flagged, and runs again next time.
    """
    threaded = require("dask.threaded", "dask")
    parts = _parts(sweep, todo, threads)
    shared = {c: _Pieces(n) for c, _, _, n in parts if n > 1}
    ready = ready or (lambda: None)
    # Keys that Dask's ordering (reverse order of the names, for tasks that depend on
    # nothing) starts in the order of ``parts``: chunks then fill the store from its
    # start, and the pieces run last. Only a preference: any order writes the same store.
    width = len(str(len(parts)))
    keys = [f"ga_rotors-chunk-{len(parts) - 1 - i:0{width}d}" for i in range(len(parts))]
    started = _Started(len(parts))
    graph = {
        key: (_run_part, task, c, first, end, shared.get(c), ready, started, threads)
        for key, (c, first, end, _) in zip(keys, parts, strict=True)
    }

    def posttask(key, wrote, dsk, state, worker_id):
        if wrote:
            done()

    pool = ThreadPoolExecutor(threads, thread_name_prefix="ga_rotors-sweep")
    try:
        # the callback as Dask's 5-tuple (start, start_state, pretask, posttask, finish),
        # given to this computation only, not registered for every Dask call in the process
        threaded.get(graph, list(graph), pool=pool, callbacks=[(None, None, None, posttask, None)])
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
        flush_writes()  # the last chunk handed to the writer


#: Dask settings of the local cluster a sweep starts. Its workers' sampling profiler off,
#: and the event-loop tick, system monitor and memory monitor at 0.5-1 s instead of
#: 20-500 ms: they feed the dashboard, which nobody watches here; with Dask's defaults an
#: idle two-worker cluster took 80 ms of CPU a second (4 % of two cores), with these 20.
#: And glibc's own heap trimming in the workers, as in any other process: Dask sets
#: MALLOC_TRIM_THRESHOLD_=65536, which hands every freed chunk-sized array back to the
#: system, so the next chunk's arrays fault their pages in again (a chunk's inputs took
#: 10 ms in a worker against 6 ms in this process, measured).
LOCAL_CLUSTER_CONFIG = {
    "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None,
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "500ms",
    "distributed.admin.system-monitor.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
}


def local_cluster(workers: int | None = None):
    """A local Dask cluster of worker processes, started, for ``run_sweep(client=...)``.

    ``workers`` processes (default: one per core) of one thread each, with
    :data:`LOCAL_CLUSTER_CONFIG`; the caller closes it. A sweep does not need it on one
    machine (it runs on Dask's threaded scheduler by default, at less cost); it is for
    watching a sweep on Dask's dashboard, or trying a cluster's layout before renting one.

    Examples
    --------
    >>> import dask, distributed
    >>> with local_cluster(1) as cluster, distributed.Client(cluster) as client:
    ...     total = client.submit(sum, [1, 2]).result()
    ...     profiling = client.run(lambda: dask.config.get("distributed.worker.profile.enabled"))
    >>> total, list(profiling.values())  # the worker process got the settings
    (3, [False])
    """
    import logging

    distributed = require("distributed", "dask")
    dask = require("dask", "dask")
    with dask.config.set(LOCAL_CLUSTER_CONFIG):  # the nannies hand it to their workers
        return distributed.LocalCluster(
            n_workers=workers or os.cpu_count() or 1,
            threads_per_worker=1,
            processes=True,
            silence_logs=logging.ERROR,  # Dask's own start/stop chatter is not the user's news
            # The scheduler serves HTTP whatever the dashboard setting, on 8787 unless told
            # otherwise: a free port, so a second cluster on the machine prints no warning.
            dashboard_address=":0",
        )


# glibc's mallopt settings of keep_freed_memory: arrays up to 32 MiB (glibc's largest)
# from the heap rather than mapped afresh, and up to 512 MiB of freed heap kept.
_KEPT_MEMORY = {"M_MMAP_THRESHOLD": 32 << 20, "M_TRIM_THRESHOLD": 512 << 20}
_MALLOPT = {"M_TRIM_THRESHOLD": -1, "M_MMAP_THRESHOLD": -3}  # glibc's malloc.h


def keep_freed_memory() -> bool:
    """Have this process's allocator keep the memory it frees, for the next chunk's arrays.

    Every chunk of a sweep makes its arrays afresh (draws, inputs, states: about 19 MB for
    65,536 samples), and glibc hands freed blocks of that size back to the system, so each
    chunk's arrays fault their pages in again, 4 KiB at a time: 0.06-0.08 s of CPU per 10⁶
    samples at 100 steps, a tenth of the integration (measured with these settings against
    glibc's defaults, threads, under load). ``ga-rotors sweep`` calls it (its process
    ends with the sweep); from Python, call it before :func:`run_sweep` to have the same,
    for the rest of the process, whose memory then stays with it once freed (arrays up to
    32 MiB come from the heap, and up to 512 MiB of it is kept). Returns False where the C
    library has no ``mallopt`` (not glibc): nothing changes there.

    Examples
    --------
    In a process of its own (it changes the allocator for the rest of the process):

    >>> import platform, subprocess, sys
    >>> code = "from ga_rotors.sweep import keep_freed_memory; print(keep_freed_memory())"
    >>> done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    >>> done.stdout.strip() == str(platform.libc_ver()[0] == "glibc")
    True
    """
    import ctypes

    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return all(mallopt(_MALLOPT[name], value) == 1 for name, value in _KEPT_MEMORY.items())


def run_sweep(
    source, out, *, client=None, scheduler=None, workers=None, progress=None, budget=None
) -> Path:
    """Run (or resume) the sweep ``source`` into the zarr store ``out``.

    Parameters
    ----------
    source : path or str
        The sweep file, or its text (see :mod:`ga_rotors.sweep.spec`).
    out : path
        The store, a ``.zarr`` directory; created if absent, resumed if it holds this sweep.
    client : distributed.Client or "sync", optional
        Where the chunks run: an existing client (a cluster's); ``"sync"`` runs them here,
        one by one. Default: a client of ``scheduler`` if given (closed at the end; the
        cluster stays up), else Dask's threaded scheduler in this process.
    scheduler : str, optional
        A Dask scheduler's address (``tcp://host:8786``), given
        :data:`SCHEDULER_TIMEOUT` seconds to answer.
    workers : int, optional
        Threads of the default run in this process (default: one per core).
    progress : callable, optional
        ``progress(done, total)`` in chunks.
    budget : ga_rotors.scene.budget.Budget, optional
        The most the sweep may take (default :data:`ga_rotors.sweep.budget.DEFAULT`):
        beyond it, refused before anything is written (:mod:`ga_rotors.sweep.budget`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> text = '[sweep]\\nscene = "intermediate_axis_flip"\\nsamples = 3\\nseed = 7\\n'
    >>> text += '[set]\\n"time.duration" = 0.01\\n[[draw]]\\nkey = "body.mass"\\n'
    >>> text += 'uniform = [0.2, 0.4]\\n'
    >>> out = run_sweep(text, pathlib.Path(tempfile.mkdtemp()) / "s.zarr", client="sync")
    >>> ds = open_sweep(out)
    >>> ds["q"].shape, ds["value_0"].attrs["scene_key"]
    ((3, 1, 4), 'body.mass')
    """
    require("zarr", "results")
    require("dask.threaded", "dask")
    if client is None and scheduler:
        require("distributed", "dask")  # before anything is written
    if workers is not None and workers < 1:
        raise InputError(f"--workers: expected a positive number, got {workers}")
    sweep = load_sweep(source)
    threads = 1 if client == "sync" else workers
    sweep_budget.check(sweep, sweep_budget.DEFAULT if budget is None else budget, threads)
    store = Path(out)
    if store.suffix != ".zarr":
        raise InputError(f"--out: {store}: expected a .zarr store name")
    if not store.parent.is_dir():
        raise InputError(f"--out: directory {store.parent} does not exist")
    created = store.exists()
    if created:
        ds = _open(store)
        if ds.attrs.get("sweep_digest") != sweep.digest:
            raise InputError(
                f"--out: {store} holds another sweep (digest {ds.attrs.get('sweep_digest')}, "
                f"this one {sweep.digest}); choose another store or delete it"
            )
        done = ds["chunk_done"].values == 1  # unwritten flags read as the fill value
        _same_draws(store, ds, sweep, done)
        nominal = ds["q_nominal"].values
    else:
        nominal = _nominal(sweep)
        done = np.zeros(sweep.chunks, dtype=bool)
    text = sweep.text
    file = str(Path(sweep.file).resolve()) if sweep.file != "<string>" else "<string>"
    # chunks run here use this one: a scene file the sweep names may have changed since
    # an earlier run of the same sweep text in this process
    _SWEEPS[(text, file)] = sweep
    task = _Task(text, file, str(store.resolve()), nominal)
    todo = [int(c) for c in np.flatnonzero(~done)]
    total, finished = sweep.chunks, int(done.sum())
    if todo and client == "sync":
        # The next chunk's draws and inputs are made on a second thread while this one
        # creates the store, then integrates (numpy, scipy and the compiled loops release
        # the GIL).
        prepare = ThreadPoolExecutor(1, thread_name_prefix="ga_rotors-inputs")
        try:
            ahead = prepare.submit(sweep.columns, *_bounds(sweep, todo[0]))
            if not created:
                _create(sweep, store, nominal)
            if progress is not None:
                progress(finished, total)
            for i, c in enumerate(todo):
                columns = ahead.result()
                if i + 1 < len(todo):
                    ahead = prepare.submit(sweep.columns, *_bounds(sweep, todo[i + 1]))
                run_chunk(task, c, wait=False, columns=columns)
                finished += 1
                if progress is not None:
                    progress(finished, total)
        finally:  # an interrupted sweep keeps what it integrated
            prepare.shutdown(wait=True, cancel_futures=True)
            flush_writes()
        return store
    if not todo:
        if progress is not None:
            progress(finished, total)
        return store
    if client is None and not scheduler:
        # The store is made by the first chunk's write, on the writer thread, once the
        # threads integrate (about 4 ms of Python and files: made on a thread of its own
        # from the start, it held the GIL while the threads drew their first chunks, and
        # they began integrating 5-10 ms later).
        made = _Once(functools.partial(_create, sweep, store, nominal)) if not created else None
        if progress is not None:
            progress(finished, total)

        def flagged():
            nonlocal finished
            finished += 1
            if progress is not None:
                progress(finished, total)

        threads = workers or os.cpu_count() or 1
        _run_threads(task, sweep, todo, threads, flagged, made)
        return store
    distributed = require("distributed", "dask")
    # connected before anything is written: an unreachable scheduler leaves no store
    dask_client, owned = _client(client, scheduler)
    try:
        if not created:
            _create(sweep, store, nominal)
        if progress is not None:
            progress(finished, total)
        futures = dask_client.map(run_chunk, [task] * len(todo), todo, wait=False, pure=False)
        # results come with the completions (a failed chunk raises here), rather than
        # one round trip to the client's event loop per future
        completed = distributed.as_completed(futures, loop=dask_client.loop, with_results=True)
        for _ in completed:
            finished += 1
            if progress is not None:
                progress(finished, total)
        dask_client.run(flush_writes)  # every worker's last chunk
    finally:
        if owned:
            dask_client.close()
    return store


def _same_draws(store: Path, ds, sweep: Sweep, done) -> None:
    """Refuse to resume a store whose chunks drew their normal values another way."""
    version = int(ds.attrs.get("draws_version", 1))  # stores before it was recorded: 1
    normal = any(dist == "normal" for _, dist, _ in sweep.draws)
    if normal and version != DRAWS_VERSION and not done.all():
        raise InputError(
            f"--out: {store} was begun by an earlier ga_rotors, whose normal draws (version "
            f"{version}) differ in the last bits from this one's (version {DRAWS_VERSION}): "
            f"its {int((~done).sum())} unwritten chunks would not match its written ones; "
            "finish it with that version, or choose another store or delete it"
        )


def _open(store: Path):
    xr = require("xarray", "results")
    try:
        ds = xr.open_zarr(store, consolidated=True)
    except (OSError, ValueError, KeyError) as exc:
        first = first_line(exc)
        raise InputError(f"{store}: not a sweep store ({first})") from None
    # a zarr store of something else: what a sweep's reading relies on, named
    lacking = [v for v in ("chunk_done", "angle_from_nominal", "q_nominal") if v not in ds]
    if lacking or "sweep_digest" not in ds.attrs:
        what = ", ".join(lacking + ([] if "sweep_digest" in ds.attrs else ["sweep_digest"]))
        raise InputError(f"{store}: not a sweep store (no {what})")
    return ds


def open_sweep(store):
    """The finished sweep at ``store`` as a Dataset (lazy, chunked along ``sample``).

    Refuses a store whose chunks are not all written, saying how many are missing.

    Examples
    --------
    >>> open_sweep("no_such.zarr")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: no_such.zarr: no such sweep store
    """
    store = Path(store)
    if not store.exists():
        raise InputError(f"{store}: no such sweep store")
    ds = _open(store)
    missing = int((ds["chunk_done"].values != 1).sum())
    if missing:
        raise InputError(
            f"{store}: {missing} of {ds.sizes['chunk']} chunks are not written yet; "
            "run the sweep again to finish it"
        )
    return ds


#: Bytes of angles :func:`summary` reads at once; a larger store is read a chunk at a time.
SUMMARY_IN_MEMORY = 2**28


def _by_chunk(a):
    """A callable giving the blocks of ``a`` along ``sample``, a stored chunk at a time
    (each call starts again: the reductions below read them in several passes)."""
    step = (a.chunks[0][0] if a.chunks else a.shape[0]) or 1
    return lambda: (a[lo : lo + step] for lo in range(0, a.shape[0], step))


def summary(ds) -> str:
    """Spread of the samples from the base scene at each output time, as text lines.

    Exact medians and 95th percentiles (:func:`~ga_rotors.sweep.percentiles.percentiles`)
    in bounded memory: a store of more than :data:`SUMMARY_IN_MEMORY` bytes of angles is
    read a chunk of samples at a time.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset({"angle_from_nominal": (("sample", "time"), [[0.0], [0.01]])},
    ...                 coords={"t": ("time", [1.0])})
    >>> print(summary(ds))
    t [s]  median [deg]  95% [deg]  max [deg]  (2 samples)
    1  0.2865  0.5443  0.573
    """
    a = ds["angle_from_nominal"]
    n = a.shape[0]
    if a.size * 8 <= SUMMARY_IN_MEMORY:
        whole = np.degrees(a.values)

        def column(j):
            return lambda: (whole[:, j],)
    else:  # read a block of samples at a time, a few passes per output time
        blocks = _by_chunk(a)

        def column(j):
            return lambda: (np.degrees(b[:, j].values) for b in blocks())

    lines = [f"t [s]  median [deg]  95% [deg]  max [deg]  ({n} samples)"]
    for j, t in enumerate(ds["t"].values):
        # samples that blew up have no angle (NaN, skipped); none left: nan
        m, (p95,), top, _ = percentiles(column(j), [95])
        lines.append(f"{t:.6g}  {m:.4g}  {p95:.4g}  {top:.4g}")
    return "\n".join(lines)


def histogram(ds, name: str = "angle_from_nominal", bins: int = 50):
    """Counts of a per-sample variable in ``bins`` equal bins, at each output time.

    Read chunk by chunk along ``sample`` (memory bounded by one chunk, whatever the
    number of samples). Returns a Dataset: ``count`` (time, bin) and the bin ``edges``
    (bin_edge), in the variable's units.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset({"angle_from_nominal": (("sample", "time"), [[0.0], [0.5], [1.0]])},
    ...                 coords={"t": ("time", [1.0])})
    >>> h = histogram(ds, bins=2)
    >>> h["count"].values.tolist(), h["edges"].values.tolist()
    ([[1, 2]], [0.0, 0.5, 1.0])
    """
    xr = require("xarray", "results")
    a = ds[name]
    blocks = _by_chunk(a)
    top = 0.0
    for b in blocks():
        top = max(top, float(np.nanmax(b.values, initial=0.0)))
    edges = np.linspace(0.0, top if top > 0 else 1.0, bins + 1)
    counts = np.zeros((a.shape[1], bins), dtype=np.int64)
    for b in blocks():
        block = b.values
        for j in range(a.shape[1]):
            counts[j] += np.histogram(block[:, j], bins=edges)[0]
    units = a.attrs.get("units", "")
    return xr.Dataset(
        {"count": (("time", "bin"), counts), "edges": (("bin_edge",), edges, {"units": units})},
        coords={"t": ds["t"]},
        attrs={"variable": name},
    )
