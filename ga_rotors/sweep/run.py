"""Running a sweep chunk by chunk into its zarr store, resumably.

Each chunk is one task: draw its samples' values (:meth:`Sweep.values`), build their
inputs (:func:`ga_rotors.ensemble.scene_samples`), integrate them on the serial batched
loop (:func:`ga_rotors.ensemble.run_samples`), measure each sample's angle from its grid
point's nominal run, and write the chunk's region of the store, then its flag
(:class:`ga_rotors.sweep.store.ChunkWriter`). Where the tasks run:

* by default, on Dask's threaded scheduler in this process, one thread per core (a
  ``concurrent.futures`` thread pool when Dask is not installed): the compiled loops,
  numpy and the writes release the GIL, so the threads integrate side by side;
* on a Dask cluster, through a ``distributed.Client`` (given, or of a scheduler's
  address; :func:`local_cluster` starts one of worker processes on this machine): the
  workers rebuild the sweep from its text and resolved scene, and write into the store,
  which must be on a file system every worker sees;
* ``client="sync"``: in this thread, one chunk after the other.

A new store is made (:func:`ga_rotors.sweep.store.create`, with each grid point's
nominal run) while the first chunks integrate: their tasks wait for it before they write
(on a cluster, for a ``distributed.Event`` set once it is made). Running the same sweep
into the same store again does only the chunks not flagged: an interrupted sweep
resumes, and a chunk cut off halfway is done again. A store records what it was begun
with (the digests of the resolved scene and of the sweep's settings, and the versions
that make its numbers): resuming it with any of them changed is refused.
"""

from __future__ import annotations

import functools
import os
import uuid
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _kernels as K
from .._jit import jit
from ..errors import InputError, SceneError, first_line
from ..optional import require
from . import budget as sweep_budget
from . import store as zstore
from .spec import Sweep, load_sweep, read_sweep

__all__ = ["LOCAL_CLUSTER_CONFIG", "SCHEDULER_TIMEOUT", "local_cluster", "open_sweep", "run_sweep"]


# ---------------------------------------------------------------------- one chunk


def _outputs(sweep: Sweep, lo: int, values: dict, run, nominal) -> dict[str, np.ndarray]:
    """What the samples from ``lo`` on, with ``values`` and ``run``, write, by variable,
    samples first.

    ``nominal``: (first grid point, q of the nominal runs of the points from it on).
    """
    out = {"q": run.q.transpose(1, 0, 2), "w": run.w.transpose(1, 0, 2)}
    if sweep.scene.moves:
        out.update(position=run.position.transpose(1, 0, 2),
                   velocity=run.velocity.transpose(1, 0, 2))  # fmt: skip
    if sweep.draws:
        first, q_nominal = nominal
        n = run.q.shape[1]
        point = np.arange(lo, lo + n, dtype=np.int64) // sweep.samples - first
        angle = np.empty((n, run.q.shape[0]))
        _angles(run.q, q_nominal, point, angle)
        out["angle_from_nominal"] = angle
        out.update((sweep.names[d.key], values[d.key]) for d in sweep.draws)
    return out


@jit
def _angles(q, nominal, point, out):
    """out[i, j]: the angle of sample i (q[j, i], times first) from its grid point's
    nominal orientation nominal[point[i], j].

    :func:`ga_rotors._kernels.angle_any_norm`: it does not depend on the norms, so an
    integrator that lets the norm drift (RK4 over a long or fast run) still has its
    angle. A sample (or nominal run) that is zero or stopped being finite gets NaN.
    """
    for i in range(q.shape[1]):
        p = point[i]
        for j in range(q.shape[0]):
            a = (q[j, i, 0], q[j, i, 1], q[j, i, 2], q[j, i, 3])
            b = (nominal[p, j, 0], nominal[p, j, 1], nominal[p, j, 2], nominal[p, j, 3])
            out[i, j] = K.angle_any_norm(a, b)


def _refused(sweep: Sweep, lo: int, values: dict, exc: InputError, what="sample") -> InputError:
    """One line naming the first sample (``what``) from ``lo`` on whose values the scene
    refuses."""
    n = next(iter(values.values())).shape[0]
    for i in range(n):
        change = {key: float(v[i]) for key, v in values.items()}
        try:
            sweep.scene.replace(change)
        except InputError as refusal:
            shown = ", ".join(f"{key} = {value!r}" for key, value in change.items())
            why = f"{refusal.key}: {refusal.detail}" if refusal.key else refusal.detail
            return SceneError(sweep.file, "", f"{what} {lo + i} ({shown}): {why}")
    return SceneError(sweep.file, "", f"{what}s {lo} to {lo + n - 1}: {exc}")


@dataclass(frozen=True)
class _Job:
    """What a chunk's task needs in this process: the sweep, the writer of its store
    (``writer()`` waits until the store is made), and the nominal runs' orientations
    (all grid points, or None to read them from the store)."""

    sweep: Sweep
    writer: Callable[[], zstore.ChunkWriter]
    nominal: np.ndarray | None


def _run_chunk(job: _Job, c: int) -> int:
    """Integrate chunk ``c`` and write it into the store; return ``c``.

    The samples are integrated before the task asks for the store: a new store is made
    while the first chunks integrate."""
    sweep = job.sweep
    lo, hi, region = sweep.chunk_region(c)
    values = sweep.values(lo, hi)
    run = _run(sweep, values, lo, "sample", parallel=False)
    writer = job.writer()
    nominal = None
    if job.nominal is not None:
        nominal = (0, job.nominal)
    elif sweep.draws:  # a worker: its grid points' nominal runs, read from the store
        points = tuple(region[d] for d in sweep.dims[:-1])
        q = writer.root["q_nominal"][points]
        nominal = (lo // sweep.samples, q.reshape(-1, *q.shape[-2:]))
    writer.write(sweep, c, _outputs(sweep, lo, values, run, nominal))
    return c


@dataclass(frozen=True)
class _Remote:
    """What a Dask worker gets to rebuild a chunk's job: text, not objects (a scene holds
    compiled functions, which do not pickle), checked against the digests it was sent;
    ``made``, the name of the ``distributed.Event`` set once a new store is made (None
    for a store that exists)."""

    text: str
    file: str
    scene_toml: str
    scene_file: str
    base_dir: str | None
    store: str
    digests: tuple
    made: str | None


#: Seconds a worker's task waits for the sweep's new store to be made before it gives up.
STORE_WAIT = 300

_REBUILT: dict = {}


def _writer_after(ready: Callable[[], object], store) -> Callable[[], zstore.ChunkWriter]:
    """A job's ``writer()``: once ``ready()`` returns (the store is made), a writer of
    ``store``, made once for all the job's chunks."""

    @functools.cache
    def writer() -> zstore.ChunkWriter:
        ready()
        return zstore.ChunkWriter(store)

    return writer


def _made(remote: _Remote) -> None:
    """On a worker: wait until the client has set the store's event (a new store)."""
    if remote.made is None:
        return
    distributed = require("distributed", "dask")
    if not distributed.Event(remote.made).wait(STORE_WAIT):
        raise InputError(
            f"{remote.file}: the store {remote.store} was not made within {STORE_WAIT} s",
            key="--out",
        )


def run_chunk(remote: _Remote, c: int) -> int:
    """A worker's task: chunk ``c`` of the sweep ``remote`` describes; returns ``c``."""
    key = (remote.digests, remote.store)
    if key not in _REBUILT:
        from ..scene import Scene

        scene = Scene.from_toml(remote.scene_toml, file=remote.scene_file, base_dir=remote.base_dir)
        sweep = read_sweep(remote.text, remote.file, scene=scene)
        if tuple(sweep.digests.items()) != remote.digests:
            raise InputError(
                f"{remote.file}: a worker rebuilt another sweep than the one it "
                f"was sent ({sweep.digests} against {dict(remote.digests)})"
            )
        _REBUILT.clear()  # one sweep at a time per process
        ready = functools.partial(_made, remote)
        _REBUILT[key] = _Job(sweep, _writer_after(ready, remote.store), None)
    return _run_chunk(_REBUILT[key], c)


# ---------------------------------------------------------------------- where they run


#: Seconds to wait for a ``--scheduler`` to answer before saying it cannot be reached.
SCHEDULER_TIMEOUT = 10


def _client(client, scheduler: str | None):
    """(client, owned): an explicit ``distributed.Client``, or one of ``scheduler``."""
    if client is not None:
        return client, False
    distributed = require("distributed", "dask")
    try:
        # not the process's default scheduler: a client that failed to connect must not
        # stay behind as every later compute's (a malformed address left it, and hung)
        client = distributed.Client(scheduler, timeout=SCHEDULER_TIMEOUT, set_as_default=False)
        return client, True
    except (OSError, TimeoutError) as exc:
        raise InputError(f"--scheduler: cannot reach {scheduler}: {first_line(exc)}") from None
    except ValueError as exc:  # no port, an unknown scheme: distributed parses it first
        raise InputError(
            f"--scheduler: {scheduler!r} is not a scheduler address (tcp://host:port): {exc}"
        ) from None


def _on_cluster(client, sweep: Sweep, todo: list[int], store: Path, make, done) -> None:
    """The chunks as tasks of ``client``'s cluster; ``make()``, when given, makes the store
    here while the workers integrate their first chunks (they wait for its event before
    they write)."""
    distributed = require("distributed", "dask")
    event = f"ga_rotors-store-{uuid.uuid4().hex}" if make is not None else None
    remote = _Remote(
        sweep.text,
        sweep.file,
        sweep.scene.to_toml(),
        sweep.scene.file,
        None if sweep.scene.base_dir is None else str(sweep.scene.base_dir),
        str(store.resolve()),
        tuple(sweep.digests.items()),
        event,
    )
    futures = client.map(run_chunk, [remote] * len(todo), todo, pure=False)
    try:
        if make is not None:
            try:
                make()
            finally:  # made or not, no task waits on: without a store they fail to open it
                distributed.Event(event, client=client).set()
        for _ in distributed.as_completed(futures, with_results=True):
            done()
    finally:  # an interrupted sweep: the running chunks finish, no others start
        client.cancel(futures)


def _on_threads(job: _Job, todo: list[int], threads: int, done) -> None:
    """The chunks on Dask's threaded scheduler, or a thread pool without Dask; either
    way on a pool of this call's, shut down (its running chunks finished, the others
    cancelled) before this returns or raises: an interrupted sweep leaves no write
    going on behind it."""
    from concurrent.futures import as_completed

    from ..optional import MissingExtraError

    pool = ThreadPoolExecutor(threads, thread_name_prefix="ga_rotors-sweep")
    try:
        try:
            threaded = require("dask.threaded", "dask")
        except MissingExtraError:
            for future in as_completed([pool.submit(_run_chunk, job, c) for c in todo]):
                future.result()
                done()
            return
        graph = {("ga_rotors-chunk", c): (_run_chunk, job, c) for c in todo}
        # Dask starts the most recently readied key first: reversed, the chunks fill the
        # store from its start (only a preference: any order writes the same store)
        keys = list(reversed(graph))
        threaded.get(
            dict(zip(keys, (graph[k] for k in keys), strict=True)),
            keys,
            pool=pool,
            callbacks=[(None, None, None, lambda *_: done(), None)],
        )
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


#: Dask settings of the local cluster a sweep starts: its workers' sampling profiler off,
#: and the event-loop tick, system monitor and memory monitor at 0.5-1 s instead of
#: 20-500 ms (they feed a dashboard nobody watches here).
LOCAL_CLUSTER_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "500ms",
    "distributed.admin.system-monitor.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
}


def local_cluster(workers: int | None = None):
    """A local Dask cluster of worker processes, started, for ``run_sweep(client=...)``.

    ``workers`` processes (default: one per core) of one thread each, with
    :data:`LOCAL_CLUSTER_CONFIG`; the caller closes it. A sweep does not need it on one
    machine (it runs on Dask's threads by default); it is for watching a sweep on Dask's
    dashboard, or trying a cluster's layout before renting one.

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
            dashboard_address=":0",  # a free port: a second cluster prints no warning
        )


# ---------------------------------------------------------------------- the sweep


def _run(sweep: Sweep, values: dict, lo: int, what: str, parallel: bool = True):
    """The runs of the samples with ``values`` (the first is sample ``lo``) on the batched
    ensemble loops (a body moving through space on the motion kind's, answering its
    position and velocity too); a refused sample is one line naming it."""
    from ..ensemble import run_samples, scene_samples

    try:
        samples = scene_samples(sweep.scene, values)
    except InputError as exc:
        raise _refused(sweep, lo, values, exc, what) from None
    return run_samples(samples, sweep.run_times(), parallel=parallel)


def _nominal(sweep: Sweep):
    """(q, w) of each grid point's nominal run, (points, time, 4) and (points, time, 3)."""
    run = _run(sweep, sweep.nominal_values(), 0, "the nominal run of grid point")
    return run.q.transpose(1, 0, 2).copy(), run.w.transpose(1, 0, 2).copy()


def _resumable(store: Path, ds, sweep: Sweep, finished: bool) -> None:
    """Refuse to resume a store begun with another scene, sweep or versions."""
    stop = "choose another store or delete it"
    if ds.attrs["sweep_format"] != zstore.FORMAT:
        raise InputError(
            f"{store} is a sweep store of another layout (format "
            f"{ds.attrs['sweep_format']}, this ga_rotors writes {zstore.FORMAT}); "
            f"{stop}",
            key="--out",
        )
    mine = sweep.digests
    if ds.attrs["sweep_digest"] != mine["sweep_digest"]:
        raise InputError(
            f"{store} holds another sweep (its grid, draws, samples, seed, chunk "
            f"or times differ from this file's); {stop}",
            key="--out",
        )
    if ds.attrs["scene_digest"] != mine["scene_digest"]:
        raise InputError(
            f"{store} was begun with another scene (the scene this sweep resolves to, its "
            "file, bundled scene or [set], has changed since); its unwritten chunks would "
            f"not match its written ones: restore the scene, or {stop}",
            key="--out",
        )
    if ds.attrs.get("made_with") != mine["made_with"] and not finished:
        raise InputError(
            f"{store} was begun with {ds.attrs.get('made_with')}; this is {mine['made_with']}: "
            f"its unwritten chunks would not match its written ones; finish it with those "
            f"versions, or {stop}",
            key="--out",
        )


def _import_first() -> None:
    """Import here what the tasks and the store's maker import: two threads importing one
    package at once can find it half made (a KeyError from the import system, seen)."""
    import scipy.special  # noqa: F401  (the normal draws)

    from .. import ensemble  # noqa: F401

    require("zarr", "results")
    require("xarray", "results")
    if zstore.have_dask():  # also imports dask.array
        require("dask.threaded", "dask")


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
        cluster stays up), else threads in this process (Dask's threaded scheduler, or a
        thread pool without Dask).
    scheduler : str, optional
        A Dask scheduler's address (``tcp://host:8786``), given
        :data:`SCHEDULER_TIMEOUT` seconds to answer.
    workers : int, optional
        Threads of the default run in this process (default: one per core).
    progress : callable, optional
        ``progress(done, total)`` in chunks.
    budget : ga_rotors.sweep.budget.SweepBudget, optional
        The most the sweep may take (default :data:`ga_rotors.sweep.budget.DEFAULT`):
        beyond it, refused before anything is written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> text = '[sweep]\\nscene = "intermediate_axis_flip"\\nsamples = 3\\nseed = 7\\n'
    >>> text += '[set]\\n"time.duration" = 0.01\\n[[draw]]\\nkey = "body.mass"\\n'
    >>> text += 'uniform = [0.2, 0.4]\\n'
    >>> out = run_sweep(text, pathlib.Path(tempfile.mkdtemp()) / "s.zarr", client="sync")
    >>> ds = open_sweep(out)
    >>> ds["q"].dims, ds["body_mass"].attrs["scene_key"]
    (('sample', 'time', 'quaternion_component'), 'body.mass')
    """
    _import_first()
    if client is None and scheduler:
        require("distributed", "dask")  # before anything is written
    if workers is not None and workers < 1:
        raise InputError(f"--workers: expected a positive number, got {workers}")
    sweep = load_sweep(source)
    threads = 1 if client == "sync" else workers or os.cpu_count() or 1
    sweep_budget.check(sweep, sweep_budget.DEFAULT if budget is None else budget, threads)
    store = Path(out)
    if store.suffix != ".zarr":
        raise InputError(f"--out: {store}: expected a .zarr store name")
    if not store.parent.is_dir():
        raise InputError(f"--out: directory {store.parent} does not exist")
    if store.exists():
        ds = zstore.open_store(store)
        root = zstore.group(store)
        finished = zstore.done(root)
        _resumable(store, ds, sweep, bool(finished.all()))
        nominal = root["q_nominal"][:] if sweep.draws else None
        if nominal is not None:
            nominal = nominal.reshape(-1, *nominal.shape[-2:])
    else:
        both = _nominal(sweep) if sweep.draws else None
        nominal = both[0] if both else None
        finished = np.zeros(sweep.chunks, dtype=bool)
    todo = [int(c) for c in np.flatnonzero(~finished)]
    count = [int(finished.sum())]

    def done() -> None:
        count[0] += 1
        if progress is not None:
            progress(count[0], sweep.chunks)

    if client not in (None, "sync") or scheduler:
        # connected before anything is written: an unreachable scheduler leaves no store
        dask_client, owned = _client(client, scheduler)
    else:
        dask_client, owned = None, False
    make = None if store.exists() else functools.partial(zstore.create, sweep, store, both)
    maker = ThreadPoolExecutor(1, thread_name_prefix="ga_rotors-store")
    try:
        if progress is not None:
            progress(count[0], sweep.chunks)
        if not todo:
            return store
        if dask_client is not None:
            _on_cluster(dask_client, sweep, todo, store, make, done)
            return store
        if make is not None and client == "sync":
            make()
            make = None
        # a new store is made while the threads integrate their first chunks; result()
        # raises in their tasks what making it raised
        ready = maker.submit(make).result if make is not None else lambda: None
        job = _Job(sweep, _writer_after(ready, store), nominal)
        if client == "sync":
            for c in todo:
                _run_chunk(job, c)
                done()
        else:
            _on_threads(job, todo, threads, done)
    finally:
        maker.shutdown(wait=True)
        if owned:
            dask_client.close()
    return store


def open_sweep(store):
    """The finished sweep at ``store`` as a Dataset (lazy, chunked as stored).

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
    ds = zstore.open_store(store)
    missing = int((~zstore.done(zstore.group(store, mode="r"))).sum())
    if missing:
        raise InputError(
            f"{store}: {missing} of {ds.sizes['chunk']} chunks are not written yet; "
            "run the sweep again to finish it"
        )
    return ds
