"""Sweeps: reproducible draws whatever the chunking, Dask runs, resumption, the store."""

from __future__ import annotations

import contextlib
import io
import itertools
import os
import socket
import warnings

import numpy as np
import pytest
from _direct_io import PATHS
from _sweeps import run_until_interrupted

from ga_rotors import optional
from ga_rotors.errors import InputError, SceneError

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")
distributed = pytest.importorskip("distributed")

from ga_rotors.cli import main  # noqa: E402
from ga_rotors.ensemble import run_samples, scene_samples  # noqa: E402
from ga_rotors.optional import MissingExtraError  # noqa: E402
from ga_rotors.sweep import BLOCK, histogram, load_sweep, open_sweep, run_sweep, summary  # noqa: E402

SWEEP = """
[sweep]
scene = "intermediate_axis_flip"
samples = 5
seed = 42
chunk = 4
times = [0.01, 0.02]

[set]
"time.duration" = 0.02

[grid]
"initial.angular_velocity.body[1]" = [9.0, 10.0]

[[draw]]
key = "initial.angular_velocity.body[0]"
normal = [0.0, 0.1]

[[draw]]
key = "body.mass"
uniform = [0.25, 0.35]
"""


@pytest.fixture(autouse=True)
def kept_memory(monkeypatch):
    """Calls of keep_freed_memory by the command, which would otherwise change the
    allocator of the test process itself (its doctest runs it in a process of its own)."""
    import ga_rotors.sweep

    calls = []
    monkeypatch.setattr(ga_rotors.sweep, "keep_freed_memory", lambda: calls.append(1) or True)
    return calls


def test_the_same_seed_gives_the_same_numbers_whatever_the_chunking():
    text = SWEEP.replace("samples = 5", f"samples = {BLOCK + 1000}")
    sweep = load_sweep(text)
    whole = sweep.values(0, sweep.size)
    cuts = [0, 3, BLOCK - 1, BLOCK + 7, 2 * BLOCK + 5, sweep.size]
    for key, values in whole.items():
        pieces = [sweep.values(a, b)[key] for a, b in itertools.pairwise(cuts)]
        assert np.array_equal(np.concatenate(pieces), values), key
    draws = whole["body.mass"]
    assert draws.min() >= 0.25 and draws.max() <= 0.35 and np.unique(draws).size == draws.size
    normal = whole["initial.angular_velocity.body[0]"]
    assert abs(normal.mean()) < 0.01 and abs(normal.std() - 0.1) < 0.01
    other = load_sweep(text.replace("seed = 42", "seed = 43")).values(0, 10)
    assert not np.array_equal(other["body.mass"], whole["body.mass"][:10])


def test_a_grid_varies_its_last_key_fastest_and_repeats_each_point_for_the_draws():
    sweep = load_sweep(SWEEP)
    v = sweep.values(0, sweep.size)["initial.angular_velocity.body[1]"]
    assert v.tolist() == [9.0] * 5 + [10.0] * 5


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The sweep run in this process, chunk after chunk."""
    out = tmp_path_factory.mktemp("ref") / "ref.zarr"
    return open_sweep(run_sweep(SWEEP, out, client="sync")).load()


def test_a_local_cluster_of_two_workers_writes_what_a_plain_run_writes(tmp_path, reference):
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        seen = []
        out = run_sweep(
            SWEEP, tmp_path / "s.zarr", client=client, progress=lambda d, n: seen.append((d, n))
        )
    ds = open_sweep(out).load()
    xr.testing.assert_identical(ds, reference)
    assert seen[0] == (0, 3) and seen[-1] == (3, 3)  # 10 samples in chunks of 4


def test_the_store_holds_what_the_ensemble_computes_for_those_values(reference):
    sweep = load_sweep(SWEEP)
    values = sweep.values(0, sweep.size)
    run = run_samples(scene_samples(sweep.scene, values), sweep.times)
    assert np.array_equal(reference["q"].values, run.q.transpose(1, 0, 2))
    assert np.array_equal(reference["w"].values, run.w.transpose(1, 0, 2))
    for j, key in enumerate(values):
        assert reference[f"value_{j}"].attrs["scene_key"] == key
        assert np.array_equal(reference[f"value_{j}"].values, values[key])
    assert reference["t"].values.tolist() == [0.01, 0.02]
    assert reference.attrs["seed"] == 42 and reference.attrs["sweep_toml"] == SWEEP
    assert np.all(reference["angle_from_nominal"].values[:, 1] > 0)


def test_the_histogram_counts_every_sample_at_every_time(reference):
    h = histogram(reference, bins=7)
    assert h["count"].shape == (2, 7) and h["count"].values.sum(axis=1).tolist() == [10, 10]
    a = reference["angle_from_nominal"].values
    assert np.array_equal(h["count"].values[1], np.histogram(a[:, 1], bins=h["edges"].values)[0])


def test_an_interrupted_sweep_resumes_from_its_finished_chunks(tmp_path, reference):
    out = tmp_path / "s.zarr"
    run_until_interrupted(SWEEP, out, after=2, client="sync")
    with pytest.raises(InputError, match="1 of 3 chunks are not written yet"):
        open_sweep(out)
    calls = []
    run_sweep(SWEEP, out, client="sync", progress=lambda d, n: calls.append(d))
    assert calls == [2, 3]  # only the missing chunk ran
    xr.testing.assert_identical(open_sweep(out).load(), reference)


def test_a_store_of_another_sweep_is_refused(tmp_path):
    out = run_sweep(SWEEP, tmp_path / "s.zarr", client="sync")
    with pytest.raises(InputError, match="holds another sweep"):
        run_sweep(SWEEP.replace("seed = 42", "seed = 1"), out, client="sync")


def _as_draws_version_1(store):
    # what a store begun before the draws' version was recorded holds: no attribute
    import json

    for name in (".zattrs", ".zmetadata"):
        meta = json.loads((store / name).read_text())
        read = (lambda m: m) if name == ".zattrs" else (lambda m: m["metadata"][".zattrs"])
        assert read(meta).pop("draws_version") == 2
        (store / name).write_text(json.dumps(meta))


def test_a_store_begun_with_other_normal_draws_is_not_resumed(tmp_path, reference):
    out = tmp_path / "s.zarr"
    run_until_interrupted(SWEEP, out, after=2, client="sync")
    _as_draws_version_1(out)
    refused = r"normal draws \(version 1\) differ .* its 1 unwritten chunks"
    with pytest.raises(InputError, match=refused):
        run_sweep(SWEEP, out, client="sync")
    # uniform draws only: the same numbers in both versions, so it resumes
    uniform = SWEEP.replace("normal = [0.0, 0.1]", "uniform = [0.0, 0.1]")
    out = tmp_path / "u.zarr"
    run_until_interrupted(uniform, out, after=2, client="sync")
    _as_draws_version_1(out)
    assert open_sweep(run_sweep(uniform, out, client="sync")).sizes["sample"] == 10
    # a finished store of either version opens, and has nothing left to draw
    done = run_sweep(SWEEP, tmp_path / "d.zarr", client="sync")
    _as_draws_version_1(done)
    assert run_sweep(SWEEP, done, client="sync") == done
    xr.testing.assert_identical(open_sweep(done).load().drop_attrs(), reference.drop_attrs())


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("samples = 5", "sampels = 5"), r"sweep\.sampels: unknown key \(did you mean 'samples'"),
        (
            ('"initial.angular_velocity.body[1]" =', '"integrator.step" ='),
            r"grid\.integrator\.step: .*cannot vary",
        ),
        (("seed = 42", ""), r"sweep\.seed: missing; random draws need a seed"),
        (
            ("normal = [0.0, 0.1]", "normal = [0.0, -0.1]"),
            r"draw\[0\]\.normal: expected std ≥ 0, got -0\.1",
        ),
        (("normal = [0.0, 0.1]", "poisson = [1.0]"), r"draw\[0\]\.poisson: unknown key"),
        (('"intermediate_axis_flip"', '"no_such_scene"'), r"sweep\.scene: .*no bundled scene"),
        (("chunk = 4", "chunk = 0"), r"sweep\.chunk: expected an integer ≥ 1"),
    ],
)
def test_a_bad_sweep_file_is_one_line_naming_the_key(change, message):
    with pytest.raises(SceneError, match=message):
        load_sweep(SWEEP.replace(*change))


def test_the_command_runs_resumes_and_prints_the_spread(tmp_path):
    spec = tmp_path / "dispersion.toml"
    spec.write_text(SWEEP)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["sweep", str(spec), "--out", str(tmp_path / "d.zarr"), "--here"]) == 0
    text = out.getvalue()
    assert "median [deg]" in text and "(10 samples)" in text and "d.zarr" in text
    with contextlib.redirect_stdout(io.StringIO()):  # again: everything already done
        assert main(["sweep", str(spec), "--out", str(tmp_path / "d.zarr"), "--here"]) == 0


def test_the_command_runs_on_dask_threads_by_default(tmp_path, reference, monkeypatch, kept_memory):
    """``ga-rotors sweep`` with no --here or --scheduler: Dask's threaded scheduler in this
    process, --workers threads (the store is the one a plain run writes), no cluster."""
    import dask.threaded

    spec = tmp_path / "dispersion.toml"
    spec.write_text(SWEEP)
    pools = []
    real = dask.threaded.get

    def spy(graph, keys, **kwargs):
        pools.append(kwargs["pool"]._max_workers)
        return real(graph, keys, **kwargs)

    monkeypatch.setattr(dask.threaded, "get", spy)
    monkeypatch.setattr(distributed, "LocalCluster", None)  # starting one would fail
    for argv, threads in (([], os.cpu_count()), (["--workers", "2"], 2)):
        out = tmp_path / f"d{threads}.zarr"
        with contextlib.redirect_stdout(io.StringIO()) as printed:
            status = main(["sweep", str(spec), "--out", str(out), *argv])
        assert status == 0 and "(10 samples)" in printed.getvalue()
        xr.testing.assert_identical(open_sweep(out).load(), reference)
        assert pools[-1] == threads
    assert len(kept_memory) == 2  # each command keeps its freed memory for the next chunk


@pytest.mark.parametrize(("threads", "pieces"), [(2, [1, 4, 2]), (3, [4, 4, 2])])
def test_chunks_cut_into_pieces_between_threads_are_the_chunks_made_at_once(
    tmp_path, reference, monkeypatch, threads, pieces
):
    """The last chunks of a threaded run (as many as threads) are integrated in pieces by
    several threads, each writing its own rows, the last written flagging the chunk: the
    store is the one a plain run writes."""
    import ga_rotors.sweep.run as sweep_run

    monkeypatch.setattr(sweep_run, "MIN_PIECE", 1)
    monkeypatch.setattr(sweep_run, "PIECE_ALIGN", 1)
    parts = sweep_run._parts(load_sweep(SWEEP), [0, 1, 2], threads)
    assert [len([p for p in parts if p[0] == c]) for c in range(3)] == pieces
    for c in range(3):  # the pieces of each chunk cover it once, in order
        cuts = [(a, b) for k, a, b, _ in parts if k == c]
        assert cuts[0][0] == 0 and all(x[1] == y[0] for x, y in itertools.pairwise(cuts))
        assert cuts[-1][1] == min(4, 10 - 4 * c)
    seen = []
    out = run_sweep(
        SWEEP, tmp_path / "s.zarr", workers=threads, progress=lambda d, n: seen.append(d)
    )
    xr.testing.assert_identical(open_sweep(out).load(), reference)
    assert seen == [0, 1, 2, 3]  # one step per chunk written, none per piece


def test_a_threaded_sweep_interrupted_leaves_whole_flagged_chunks_and_resumes(tmp_path, reference):
    """Ctrl-C reaches the thread waiting on Dask; the chunks running then finish and flag
    themselves before run_sweep raises, so every flagged chunk holds all its samples, no
    write goes on after it, and a second run does only the rest."""
    text = SWEEP.replace("chunk = 4", "chunk = 1")  # ten chunks, two threads
    full = open_sweep(run_sweep(text, tmp_path / "whole.zarr", workers=2)).load()
    out = tmp_path / "s.zarr"
    run_until_interrupted(text, out, workers=2)
    first = xr.open_zarr(out).load()
    flags = first["chunk_done"].values == 1  # unwritten flags read as NaN here
    assert 1 <= flags.sum() < 10  # the running chunks finished, the others never started
    for c in range(10):
        if flags[c]:
            xr.testing.assert_identical(
                first.isel(sample=[c]).drop_vars("chunk_done"),
                full.isel(sample=[c]).drop_vars("chunk_done"),
            )
        else:  # not started: nothing of it written
            assert np.isnan(first["q"].values[c]).all()
    calls = []
    run_sweep(text, out, workers=2, progress=lambda d, n: calls.append(d))
    assert calls[0] == flags.sum() and calls[-1] == 10  # only the missing chunks ran
    xr.testing.assert_identical(open_sweep(out).load(), full)
    assert np.array_equal(full["q"].values, reference["q"].values)


def test_the_command_on_an_existing_scheduler_writes_what_a_plain_run_writes(tmp_path, reference):
    """``ga-rotors sweep --scheduler ADDRESS`` (docs/ensembles.md): the sweep runs on a
    cluster someone else started, here two workers in this process, and leaves it running."""
    spec = tmp_path / "dispersion.toml"
    spec.write_text(SWEEP)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        with contextlib.redirect_stdout(io.StringIO()) as out:
            argv = ["sweep", str(spec), "--out", str(tmp_path / "d.zarr")]
            status = main([*argv, "--scheduler", cluster.scheduler_address])
        assert status == 0 and "(10 samples)" in out.getvalue()
        assert len(cluster.workers) == 2  # the user's cluster is still there
    xr.testing.assert_identical(open_sweep(tmp_path / "d.zarr").load(), reference)


def test_an_unreachable_scheduler_is_one_line(tmp_path, capsys, monkeypatch):
    """Refused within SCHEDULER_TIMEOUT (10 s; 1 s here), in one line, before the store is
    created (it used to wait 30 s, print Dask's multi-line message and leave a store)."""
    import ga_rotors.sweep.run as sweep_run

    monkeypatch.setattr(sweep_run, "SCHEDULER_TIMEOUT", 1)
    spec = tmp_path / "dispersion.toml"
    spec.write_text(SWEEP)
    with socket.socket() as free:  # a port nobody listens on
        free.bind(("127.0.0.1", 0))
        port = free.getsockname()[1]
    argv = ["sweep", str(spec), "--out", str(tmp_path / "d.zarr")]
    with contextlib.redirect_stdout(io.StringIO()):
        status = main([*argv, "--scheduler", f"tcp://127.0.0.1:{port}"])
    err = capsys.readouterr().err.strip()
    assert status == 2 and err.startswith("ga-rotors: error: --scheduler: cannot reach tcp://")
    assert "\n" not in err and not (tmp_path / "d.zarr").exists()


def test_the_command_names_the_extra_when_dask_is_missing(tmp_path, monkeypatch):
    real = optional.importlib.import_module

    def fake(name, *args):
        top = name.split(".")[0]
        if top in ("dask", "distributed"):
            raise ModuleNotFoundError(f"No module named {top!r}", name=top)
        return real(name, *args)

    monkeypatch.setattr(optional.importlib, "import_module", fake)
    spec = tmp_path / "dispersion.toml"
    spec.write_text(SWEEP)
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = main(["sweep", str(spec), "--out", str(tmp_path / "d.zarr")])
    assert status == 2
    assert err.getvalue().strip().endswith('pip install "ga-rotors[dask]"')
    assert not (tmp_path / "d.zarr").exists()  # refused before anything was written
    with pytest.raises(MissingExtraError, match="dask"):
        run_sweep(SWEEP, tmp_path / "d.zarr")


@pytest.mark.parametrize("threads", [None, 2], ids=["here", "threads, in pieces"])
def test_chunks_go_through_zarr_when_a_store_is_not_laid_out_raw(
    tmp_path, reference, monkeypatch, threads
):
    # Chunks are written as raw bytes into the store's files (the layout the sweep creates:
    # uncompressed, unfiltered, C order); any other layout is left to zarr's own writes,
    # which rewrite a whole chunk for a piece of it: pieces of one chunk written by
    # several threads still make the whole chunk.
    import ga_rotors.sweep.run as sweep_run
    from ga_rotors.sweep import store

    monkeypatch.setattr(store, "_layout", lambda store, name: None)
    monkeypatch.setattr(sweep_run, "MIN_PIECE", 1)
    monkeypatch.setattr(sweep_run, "PIECE_ALIGN", 1)
    client = "sync" if threads is None else None
    out = run_sweep(SWEEP, tmp_path / "s.zarr", client=client, workers=threads)
    xr.testing.assert_identical(open_sweep(out).load(), reference)


@pytest.mark.parametrize("samples", [1, 4095, 4096, 8192 + 7, 65536, 100_000, 1_000_000])
@pytest.mark.parametrize("threads", [1, 2, 3, 8])
def test_the_last_chunks_are_cut_into_aligned_pieces_that_shrink_towards_the_end(samples, threads):
    # Each chunk covered once, in order; a piece starts on a whole number of pages of its
    # chunk file (PIECE_ALIGN rows of float64) and holds MIN_PIECE samples or more, unless
    # its chunk is shorter; the run ends on a short piece, so that threads run out of
    # work together.
    import ga_rotors.sweep.run as sweep_run

    text = f'[sweep]\nscene = "heavy_top"\nsamples = {samples}\nchunk = 65536\nseed = 1\n'
    sweep = load_sweep(text + '[[draw]]\nkey = "body.mass"\nnormal = [1.0, 0.1]\n')
    todo = list(range(sweep.chunks))
    parts = sweep_run._parts(sweep, todo, threads)
    assert [c for c, *_ in parts] == sorted(c for c, *_ in parts)
    for c in todo:
        cuts = [(a, b, n) for k, a, b, n in parts if k == c]
        n = min(65536, samples - 65536 * c)
        assert cuts[0][0] == 0 and cuts[-1][1] == n and all(len(cuts) == x[2] for x in cuts)
        assert all(x[1] == y[0] for x, y in itertools.pairwise(cuts))
        assert all(a % sweep_run.PIECE_ALIGN == 0 for a, _, _ in cuts)
        assert all(b - a >= min(n, sweep_run.MIN_PIECE) for a, b, _ in cuts)
        if len(cuts) > 1:
            assert c >= len(todo) - threads  # only the run's last chunks
    tail = sum(min(65536, samples - 65536 * c) for c in todo[-threads:])
    if threads > 1 and tail >= 4 * sweep_run.MIN_PIECE:
        last = parts[-1][2] - parts[-1][1]
        assert last <= 2 * sweep_run.MIN_PIECE + sweep_run.PIECE_ALIGN
        assert len(parts) > len(todo)


def test_a_chunk_whose_piece_failed_to_write_is_not_flagged_and_is_done_again(
    tmp_path, reference, monkeypatch
):
    # The pieces of a chunk write their own rows; the flag follows the last piece
    # written. A piece's failed write leaves its chunk unflagged (whatever the other
    # pieces wrote), and the next run does that chunk again, whole.
    import ga_rotors.sweep.run as sweep_run
    from ga_rotors.sweep import store

    monkeypatch.setattr(sweep_run, "MIN_PIECE", 1)
    monkeypatch.setattr(sweep_run, "PIECE_ALIGN", 1)
    real = store.write_chunk
    failed = []

    def disk_full(path, variable, block, c, layouts=None, first=None):
        if variable == "w" and c == 2 and first == 1 and not failed:
            failed.append(first)
            raise OSError(28, "No space left on device")
        return real(path, variable, block, c, layouts, first)

    monkeypatch.setattr(store, "write_chunk", disk_full)
    out = tmp_path / "s.zarr"
    with pytest.raises(InputError, match=r"\(chunk 2 of w\): No space"):
        run_sweep(SWEEP, out, workers=2)
    assert failed == [1]
    flags = xr.open_zarr(out)["chunk_done"].values
    assert flags[2] != 1  # its other piece was written, the chunk is not done
    run_sweep(SWEEP, out, workers=2)
    xr.testing.assert_identical(open_sweep(out).load(), reference)


def _disk_full_at(monkeypatch, name: str, chunk: int):
    from ga_rotors.sweep import store

    def disk_full(path, variable, block, c, *rest):
        if variable == name and c == chunk:
            raise OSError(28, "No space left on device")
        return real(path, variable, block, c, *rest)

    real = store.write_chunk
    monkeypatch.setattr(store, "write_chunk", disk_full)


def test_a_failed_background_write_is_raised_not_lost(tmp_path, monkeypatch):
    _disk_full_at(monkeypatch, "w", 1)
    out = tmp_path / "s.zarr"
    with pytest.raises(
        InputError, match=r"--out: cannot write .*s\.zarr \(chunk 1 of w\): No space"
    ):
        run_sweep(SWEEP, out, client="sync")
    with pytest.raises(InputError, match="2 of 3 chunks are not written yet"):
        open_sweep(out)  # chunk 1 lost its flag; chunk 2 stopped on chunk 1's failed write


def test_a_full_disk_is_one_line_naming_the_store(tmp_path, monkeypatch):
    # On the command line, run here, on Dask's threads (the default) or on a cluster (of
    # threads, so the fault reaches the workers too: the error crosses Dask as it would
    # from a worker process).
    _disk_full_at(monkeypatch, "q", 2)
    spec = tmp_path / "dispersion.toml"
    spec.write_text(SWEEP)
    for where, store in ((["--here"], "here.zarr"), ([], "threads.zarr"), (None, "dask.zarr")):
        err = io.StringIO()
        argv = ["sweep", str(spec), "--out", str(tmp_path / store), "--no-progress"]
        with contextlib.ExitStack() as stack:
            stack.enter_context(contextlib.redirect_stderr(err))
            stack.enter_context(contextlib.redirect_stdout(io.StringIO()))
            if where is None:
                cluster = stack.enter_context(distributed.LocalCluster(
                    n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
                ))  # fmt: skip
                address = cluster.scheduler_address
                argv += ["--scheduler", address]
            else:
                argv += where
            status = main(argv)
        lines = err.getvalue().strip().splitlines()
        assert status == 2 and len(lines) == 1, (where, err.getvalue())
        assert lines[0].startswith("ga-rotors: error: --out: cannot write ")
        assert f"{store} (chunk 2 of q): No space left on device" in lines[0]


@pytest.mark.parametrize("client", ["sync", None])
def test_a_full_disk_while_creating_the_store_is_one_line(tmp_path, monkeypatch, client):
    # On threads (None) the store is made while the first chunks integrate: the first
    # chunk to write raises what making it raised.
    from ga_rotors.sweep import store

    def disk_full(path, data):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(store, "_write", disk_full)
    with pytest.raises(InputError, match=r"cannot write .*s\.zarr \(creating it\): No space"):
        run_sweep(SWEEP, tmp_path / "s.zarr", client=client)
    assert list(tmp_path.iterdir()) == []  # no store, no staging left


def test_a_sample_that_blows_up_is_nan_and_the_others_are_kept(tmp_path):
    # 900 rad per RK4 step overflows within the run; 0.3 rad per step keeps a finite state
    # whose norm has drifted past the unit tolerance of quaternion.distance.
    text = SWEEP.replace("samples = 5", "samples = 1").replace(
        '"initial.angular_velocity.body[1]" = [9.0, 10.0]',
        '"initial.angular_velocity.body[1]" = [9.0, 900000.0, 300.0]',
    )
    text = text.replace('"time.duration" = 0.02', '"time.duration" = 0.1')
    text = text.replace("times = [0.01, 0.02]", "times = [0.05, 0.1]")
    ds = open_sweep(run_sweep(text, tmp_path / "s.zarr", client="sync")).load()
    angle = ds["angle_from_nominal"].values
    assert np.all(np.isnan(ds["q"].values[1, -1])) and np.isnan(angle[1, -1])
    drifted = np.linalg.norm(ds["q"].values[2, -1])
    assert abs(drifted - 1) > 1e-6 and 0 < angle[2, -1] <= np.pi
    assert np.all(np.isfinite(angle[0])) and np.all(np.isfinite(angle[2]))
    assert histogram(ds, bins=4)["count"].values.sum(axis=1).tolist() == [2, 2]  # NaN skipped
    assert "(3 samples)" in summary(ds) and "nan" not in summary(ds)


def test_a_store_made_again_by_another_sweep_gets_its_own_chunks(tmp_path, reference):
    # Same samples in chunks of 3 instead of 4, into the path of a deleted store: what a
    # process remembered of the first store's layout must not shape the second's chunks.
    import shutil

    out = tmp_path / "s.zarr"
    run_sweep(SWEEP, out, client="sync")
    shutil.rmtree(out)
    again = open_sweep(run_sweep(SWEEP.replace("chunk = 4", "chunk = 3"), out, client="sync"))
    assert again["q"].encoding["chunks"][0] == 3
    for name in ("q", "w", "angle_from_nominal", "value_0", "value_1", "value_2"):
        assert np.array_equal(again[name].values, reference[name].values, equal_nan=True), name


def test_the_summary_of_a_time_where_every_sample_blew_up_is_nan_without_a_warning():
    ds = xr.Dataset(
        {"angle_from_nominal": (("sample", "time"), [[0.01, np.nan], [0.02, np.nan]])},
        coords={"t": ("time", [1.0, 2.0])},
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's "All-NaN slice encountered" among them
        lines = summary(ds).splitlines()
    assert lines[2].split() == ["2", "nan", "nan", "nan"]
    assert lines[1].split()[0] == "1" and "nan" not in lines[1]


def test_the_store_reads_back_as_the_store_xarray_writes_from_the_same_template(tmp_path):
    # The sweep writes its store's zarr metadata itself (fast); xarray writing the same
    # template is the oracle: both read back identical, chunking and fill values alike.
    from ga_rotors.sweep import run as sweep_run
    from ga_rotors.sweep import store

    sweep = load_sweep(SWEEP)
    template = sweep_run._template(sweep, np.eye(4)[:2], np.array([0.01, 0.02]))
    ours, theirs = tmp_path / "ours.zarr", tmp_path / "theirs.zarr"
    chunked = sweep_run._chunked(template)
    store.create(ours, template, {"sample": 4, "chunk": 1}, chunked)
    encoding = {n: {"compressors": None, **v.encoding} for n, v in template.variables.items()}
    lazy = template.copy()
    for name in chunked:
        dims = {"sample": 4, "chunk": 1}
        lazy[name] = lazy[name].chunk({d: dims[d] for d in lazy[name].dims if d in dims})
    lazy.to_zarr(theirs, compute=False, zarr_format=2, consolidated=True, encoding=encoding)
    a, b = xr.open_zarr(ours, consolidated=True), xr.open_zarr(theirs, consolidated=True)
    xr.testing.assert_identical(a.load(), b.load())
    for name in template.variables:
        assert a[name].encoding["chunks"] == b[name].encoding["chunks"] or name not in chunked
        assert a[name].encoding.get("_FillValue") == b[name].encoding.get("_FillValue") or (
            np.isnan(a[name].encoding["_FillValue"]) and np.isnan(b[name].encoding["_FillValue"])
        ), name
    assert a["q"].encoding["chunks"] == (4, 2, 4)
    # and a chunk written raw reads back through zarr
    store.write_chunk(ours, "q", np.arange(24.0).reshape(3, 2, 4), 2)
    q = xr.open_zarr(ours)["q"].values
    assert np.array_equal(q[8:], np.arange(16.0).reshape(2, 2, 4)) and np.isnan(q[:8]).all()


def test_the_angle_from_the_nominal_is_the_geodesic_distance_whatever_the_norm():
    from ga_rotors import quaternion as Q
    from ga_rotors.sweep import run as sweep_run

    rng = np.random.default_rng(5)
    nominal = Q.normalize(rng.normal(size=(2, 4)))
    q = Q.normalize(rng.normal(size=(2, 6, 4)))
    q[:, 0] = nominal  # the nominal itself: 0
    q[:, 1] = Q.multiply(nominal, Q.from_axis_angle([0.0, 1.0, 0.0], 1e-12))  # resolved
    q[:, 2] = -nominal  # the same rotation
    q[1, 3] *= 1.01  # a drifted norm: the same angle
    q[0, 4] = 0.0  # not a rotation
    q[0, 5, 1], q[1, 5, 2] = np.inf, np.nan  # stopped being finite
    out = np.empty((6, 2))
    sweep_run._angles(q, nominal, out)
    expected = np.full((6, 2), np.nan)
    for j in range(2):
        for i in range(6):
            norm = np.linalg.norm(q[j, i])
            if np.isfinite(norm) and norm > 0:
                expected[i, j] = Q.distance(q[j, i] / norm, nominal[j])
    assert np.array_equal(np.isnan(out), np.isnan(expected))
    assert np.isnan(out[4, 0]) and np.isnan(out[5]).all()
    assert np.all(out[[0, 2]] < 4e-16)  # the product's round-off: ~1e-16 rad at most
    assert np.allclose(out[1], 1e-12, rtol=1e-3, atol=0)
    ok = ~np.isnan(expected)
    assert np.allclose(out[ok], expected[ok], rtol=4e-16, atol=4e-16)


def test_threads_loading_the_same_loop_at_once_wait_for_one_another(monkeypatch):
    """The threads of a sweep in a new process all start by loading the same generated
    modules; a module is in sys.modules before it has run, and a second thread finding
    it there half made failed ("has no attribute 'step'", seen on a resumed sweep)."""
    from _loading_race import race_first_load

    from ga_rotors import ensemble

    samples = scene_samples(load_sweep(SWEEP).scene, n=2)
    expected = run_samples(samples, parallel=False)  # compiled, cached; then unloaded
    monkeypatch.setattr(ensemble, "_SCENE_LOOPS", {})
    slowed, errors, results = race_first_load(
        monkeypatch, lambda: run_samples(samples, parallel=False)
    )
    assert slowed and errors == []
    for run in results:  # the same samples run three times: the same numbers each time
        assert (run.q == expected.q).all()


@pytest.mark.parametrize("doubles", [100, 512, 1000, 1536, 4096])
@pytest.mark.parametrize("how", PATHS)
def test_a_chunk_file_holds_its_bytes_however_it_is_written(tmp_path, monkeypatch, doubles, how):
    # Direct writes from a page-aligned copy, the end past the last whole 4 KiB through
    # the page cache; the plain write where the system has no O_DIRECT, or the file
    # system refuses it at open (tmpfs) or at the write. Sizes: under a page, one page,
    # a page and a ragged end, whole pages. An older, longer file is replaced.
    from _direct_io import arrange

    from ga_rotors import files
    from ga_rotors.sweep import store

    opened = arrange(how, tmp_path, monkeypatch)
    out = tmp_path / "x.zarr"
    ds = xr.Dataset({"a": (("s",), np.broadcast_to(np.nan, (2 * doubles,)))})
    store.create(out, ds, {"s": doubles}, {"a"})
    (out / "a" / "1").write_bytes(b"\1" * (8 * doubles + 9000))  # an older, longer file
    data = np.random.default_rng(doubles).normal(size=doubles)
    store.write_chunk(out, "a", data, 1)
    assert (out / "a" / "1").read_bytes() == data.tobytes()
    read = xr.open_zarr(out)["a"].values
    assert np.array_equal(read[doubles:], data) and np.isnan(read[:doubles]).all()
    direct = doubles * 8 >= files.DIRECT_ALIGN and how != "no O_DIRECT"
    assert any(opened) == direct  # tried direct only where a whole page is written


def test_a_sweep_written_direct_is_the_sweep_written_through_the_page_cache(tmp_path, monkeypatch):
    # Chunks of 200 samples at two times: q and w files of 12,800 and 9,600 bytes (whole
    # pages and a ragged end), the angle's 3,200 (under a page): the same store bytes.
    from _direct_io import direct_writes_work_in

    from ga_rotors import files as _files

    if not direct_writes_work_in(tmp_path):
        pytest.skip("no direct writes on this file system")
    text = SWEEP.replace("samples = 5", "samples = 300").replace("chunk = 4", "chunk = 200")
    direct = run_sweep(text, tmp_path / "direct.zarr")
    monkeypatch.setattr(_files, "_O_DIRECT", 0)
    cached = run_sweep(text, tmp_path / "cached.zarr")
    for name in ("q", "w", "angle_from_nominal", "value_0", "chunk_done"):
        files = sorted(p.name for p in (direct / name).iterdir())
        assert files == sorted(p.name for p in (cached / name).iterdir()), name
        for f in files:
            assert (direct / name / f).read_bytes() == (cached / name / f).read_bytes(), f
    assert (direct / "q" / "0.0.0").stat().st_size == 12800
    xr.testing.assert_identical(open_sweep(direct).load(), open_sweep(cached).load())


def test_the_draws_are_the_documented_function_of_the_seed_and_the_sample():
    # What fixes the numbers of every store written: sample s, draw j is the
    # ((s mod BLOCK)·draws + j)-th of its block's Generator.integers(0, 2**53) (the oracle:
    # numpy's own Generator on SeedSequence(seed, spawn_key=(block,))), as u = (k + ½)·2⁻⁵³,
    # then the normal's quantile (ga_rotors' own, draws version 2: within a few units in
    # the last place of scipy's ndtri) or the uniform's affine map.
    from scipy.special import ndtri

    from ga_rotors.sweep import _normal

    sweep = load_sweep(SWEEP.replace("samples = 5", f"samples = {BLOCK + 300}"))
    lo, hi = BLOCK - 200, BLOCK + 500  # across a block's end
    got = sweep.values(lo, hi)
    expected = {key: np.empty(hi - lo) for key in ("normal", "uniform", "scipy")}
    for s in range(lo, hi):
        block, at = divmod(s, BLOCK)
        if s == lo or at == 0:
            gen = np.random.Generator(
                np.random.PCG64(np.random.SeedSequence(42, spawn_key=(block,)))
            )
            k = gen.integers(0, 2**53, size=2 * BLOCK, dtype=np.uint64)
        u = (k[2 * at : 2 * at + 2].astype(np.float64) + 0.5) * 2.0**-53
        expected["normal"][s - lo] = _normal.inverse_normal(u[0]) * 0.1 + 0.0
        expected["scipy"][s - lo] = ndtri(u[0]) * 0.1
        expected["uniform"][s - lo] = u[1] * (0.35 - 0.25) + 0.25
    normal = got["initial.angular_velocity.body[0]"]
    assert np.array_equal(normal, expected["normal"])
    np.testing.assert_allclose(normal, expected["scipy"], rtol=2e-15, atol=1e-17)
    assert np.array_equal(got["body.mass"], expected["uniform"])
