"""Sweeps: draws that are numpy's and scipy's whatever the chunking, the store as xarray
reads it, threads and Dask clusters writing the same store, resuming (and refusing to),
and each grid point's spread with the samples that failed."""

from __future__ import annotations

import contextlib
import io
import itertools
import math
import os
import socket

import numpy as np
import pytest
from _sweeps import run_until_interrupted
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors import optional
from ga_rotors.errors import InputError, SceneError

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")
distributed = pytest.importorskip("distributed")

from ga_rotors import quaternion as Q  # noqa: E402
from ga_rotors.cli import main  # noqa: E402
from ga_rotors.ensemble import run_samples, scene_samples  # noqa: E402
from ga_rotors.results.dataset import variable_attrs  # noqa: E402
from ga_rotors.sweep import (  # noqa: E402
    BLOCK,
    histogram,
    load_sweep,
    open_sweep,
    run_sweep,
    spec,
    summary,
)

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

GRID = "initial_angular_velocity_body_1"


def _oracle_draws(seed: int, lo: int, hi: int, draws) -> dict:
    """The documented draws, one sample at a time: numpy's Generator on the block's
    SeedSequence, u = random() + 2⁻⁵⁴, then scipy's ndtri or the uniform's affine map."""
    from scipy.special import ndtri

    d = len(draws)
    out = {key: np.empty(hi - lo) for key, _, _ in draws}
    for s in range(lo, hi):
        block, at = divmod(s, BLOCK)
        gen = np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(block,))))
        u = gen.random(size=(at + 1) * d)[at * d :] + 2.0**-54
        for j, (key, kind, (a, b)) in enumerate(draws):
            out[key][s - lo] = ndtri(u[j]) * b + a if kind == "normal" else u[j] * (b - a) + a
    return out


def test_the_draws_are_numpys_generator_and_scipys_ndtri_whatever_the_chunking():
    sweep = load_sweep(SWEEP.replace("samples = 5", f"samples = {BLOCK + 300}"))
    draws = [
        ("initial.angular_velocity.body[0]", "normal", (0.0, 0.1)),
        ("body.mass", "uniform", (0.25, 0.35)),
    ]
    lo, hi = BLOCK - 200, BLOCK + 100  # across a block's end
    expected = _oracle_draws(42, lo, hi, draws)
    for cuts in ([lo, hi], [lo, lo + 1, BLOCK, BLOCK + 7, hi]):
        for key, values in expected.items():
            pieces = [sweep.values(a, b)[key] for a, b in itertools.pairwise(cuts)]
            assert np.array_equal(np.concatenate(pieces), values), key
    other = load_sweep(SWEEP.replace("seed = 42", "seed = 43")).values(0, 10)
    assert not np.array_equal(other["body.mass"], sweep.values(0, 10)["body.mass"])


def test_the_uniform_that_rounds_to_one_gives_a_finite_normal_draw():
    # random() = 1 - 2⁻⁵³ (once in 2⁵³ draws) plus 2⁻⁵⁴ rounds to exactly 1; the normal
    # quantile of 1 is inf: a normal draw takes the largest float below 1, a uniform one
    # its high end (the interval is closed)
    u = np.array([1 - 2.0**-53]) + 2.0**-54
    assert u[0] == 1.0
    normal = spec.Draw("body.mass", "normal", 2.0, 0.02).from_uniform(u.copy())
    assert np.isfinite(normal[0]) and normal[0] > 2.0 + 0.02 * 8
    assert spec.Draw("body.mass", "uniform", 1.0, 3.0).from_uniform(u)[0] == 3.0


def test_a_grid_varies_its_last_key_fastest_and_repeats_each_point_for_the_draws():
    sweep = load_sweep(SWEEP)
    assert sweep.dims == (GRID, "sample") and sweep.shape == (2, 5)
    v = sweep.values(0, sweep.size)["initial.angular_velocity.body[1]"]
    assert v.tolist() == [9.0] * 5 + [10.0] * 5
    nominal = sweep.nominal_values()
    assert nominal["body.mass"].tolist() == [0.3, 0.3]  # the draws at their centres
    assert nominal["initial.angular_velocity.body[1]"].tolist() == [9.0, 10.0]


@settings(max_examples=60, deadline=None)
@given(
    shape=st.lists(st.integers(1, 7), min_size=1, max_size=4),
    chunk=st.integers(1, 60),
)
def test_chunks_are_rectangles_of_consecutive_samples_covering_each_once(shape, chunk):
    block = spec.block_shape(tuple(shape), chunk)
    assert math.prod(block) <= chunk
    counts = [-(-n // b) for n, b in zip(shape, block, strict=True)]
    seen = np.zeros(shape, dtype=int)
    flat = np.arange(math.prod(shape)).reshape(shape)
    for c in range(math.prod(counts)):
        at = np.unravel_index(c, counts)
        region = tuple(
            slice(i * b, min((i + 1) * b, n)) for i, b, n in zip(at, block, shape, strict=True)
        )
        seen[region] += 1
        covered = flat[region].ravel()
        assert np.array_equal(covered, np.arange(covered[0], covered[0] + covered.size))
    assert (seen == 1).all()
    # the axis cut is cut evenly: as few pieces as fit, none more than one shorter
    assert all(b == -(-n // k) for n, b, k in zip(shape, block, counts, strict=True))


def test_a_sweeps_chunk_regions_are_its_samples_in_order():
    sweep = load_sweep(SWEEP.replace("chunk = 4", "chunk = 3"))
    assert sweep.chunk_shape == (1, 3) and sweep.chunks == 4
    spans = [sweep.chunk_region(c)[:2] for c in range(sweep.chunks)]
    assert spans == [(0, 3), (3, 5), (5, 8), (8, 10)]
    assert sweep.chunk_region(3)[2] == {GRID: slice(1, 2), "sample": slice(3, 5)}


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    """The sweep run in this thread, chunk after chunk."""
    return run_sweep(SWEEP, tmp_path_factory.mktemp("ref") / "ref.zarr", client="sync")


@pytest.fixture(scope="module")
def reference(store):
    return open_sweep(store).load()


def test_the_store_opens_in_xarray_with_the_varied_keys_as_coordinates(store):
    ds = xr.open_zarr(store)
    assert ds["q"].dims == (GRID, "sample", "time", "quaternion_component")
    assert ds[GRID].values.tolist() == [9.0, 10.0] and GRID in ds.indexes
    assert ds[GRID].attrs["scene_key"] == "initial.angular_velocity.body[1]"
    mass = ds["body_mass"]
    assert mass.dims == (GRID, "sample") and mass.attrs["scene_key"] == "body.mass"
    assert mass.attrs["distribution"] == "uniform 0.25 0.35"
    # time is an index: sel picks t = 0.02 s, not row 2 (there is none)
    assert ds["time"].values.tolist() == [0.01, 0.02]
    xr.testing.assert_identical(ds.sel(time=0.02)["q"].load(), ds.isel(time=1)["q"].load())
    # grouping and selecting by a grid key work on the lazy store
    by_point = ds["angle_from_nominal"].groupby(GRID).max(...)
    assert isinstance(ds["angle_from_nominal"].data, type(by_point.data))  # still lazy
    angles = ds["angle_from_nominal"].values
    assert np.array_equal(by_point.values, angles.reshape(2, -1).max(axis=1))
    assert ds.sel({GRID: 10.0})["q"].shape == (5, 2, 4)


def test_the_store_holds_what_the_ensemble_computes_for_those_values(reference):
    sweep = load_sweep(SWEEP)
    values = sweep.values(0, sweep.size)
    run = run_samples(scene_samples(sweep.scene, values), sweep.times)
    assert np.array_equal(reference["q"].values.reshape(10, 2, 4), run.q.transpose(1, 0, 2))
    assert np.array_equal(reference["w"].values.reshape(10, 2, 3), run.w.transpose(1, 0, 2))
    for key in ("initial.angular_velocity.body[0]", "body.mass"):
        name = spec.coordinate_name(key)
        assert np.array_equal(reference[name].values.ravel(), values[key])
    nominal = run_samples(scene_samples(sweep.scene, sweep.nominal_values()), sweep.times)
    assert np.array_equal(reference["q_nominal"].values, nominal.q.transpose(1, 0, 2))
    # the angle from each sample's own grid point's nominal run: quaternion.distance
    q = reference["q"].values
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    expected = Q.distance(q, reference["q_nominal"].values[:, None])
    np.testing.assert_allclose(
        reference["angle_from_nominal"].values, expected, rtol=4e-15, atol=1e-17
    )
    assert np.all(reference["angle_from_nominal"].values[..., 1] > 0)


def test_the_store_follows_cf_and_quantifies_with_pint(store, tmp_path):
    pytest.importorskip("cf_xarray")
    pint_xarray = pytest.importorskip("pint_xarray")
    ds = xr.open_zarr(store)
    assert ds.attrs["Conventions"] == "CF-1.10" and "body axes" in ds.attrs["body_frame"]
    assert ds.cf.axes["T"] == ["time"] and ds.cf["time"].name == "time"
    assert ds["time"].attrs["standard_name"] == "time" and ds["time"].attrs["units"] == "s"
    assert ds["time"].attrs == variable_attrs("t")  # the results' one table, as a run's file
    quantified = ds.pint.quantify()
    assert str(quantified["w"].data.units) == "radian / second"
    assert pint_xarray  # imported for its accessor
    text = " ".join(str(v) for v in ds.attrs.values())
    assert str(store.parent) not in text and "/tmp" not in text  # no machine paths
    assert ds.attrs["integrator"] == "rk4" and "time.duration" in ds.attrs["sweep_toml"]


def test_threads_and_clusters_write_what_one_thread_writes(tmp_path, reference, monkeypatch):
    for workers in (1, 2, 3):
        out = run_sweep(SWEEP, tmp_path / f"t{workers}.zarr", workers=workers)
        xr.testing.assert_identical(open_sweep(out).load(), reference)
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        seen = []
        out = run_sweep(
            SWEEP, tmp_path / "c.zarr", client=client, progress=lambda d, n: seen.append((d, n))
        )
        xr.testing.assert_identical(open_sweep(out).load(), reference)
        assert seen[0] == (0, 4) and seen[-1] == (4, 4)
        # a store that cannot be made (made here while the workers integrate): one line,
        # and no task left waiting for it (the command below gets both workers)
        from ga_rotors.sweep import store as zstore

        def disk_full(*_):
            raise InputError("cannot write e.zarr (creating it): No space left on device")

        with monkeypatch.context() as m:
            m.setattr(zstore, "create", disk_full)
            with pytest.raises(InputError, match="No space left"):
                run_sweep(SWEEP, tmp_path / "e.zarr", client=client)
        assert not (tmp_path / "e.zarr").exists()
        # the command on this cluster's address leaves it running
        spec_file = tmp_path / "dispersion.toml"
        spec_file.write_text(SWEEP)
        with contextlib.redirect_stdout(io.StringIO()) as printed:
            argv = ["sweep", str(spec_file), "--out", str(tmp_path / "d.zarr")]
            assert main([*argv, "--scheduler", cluster.scheduler_address]) == 0
        assert "0 of 5" in printed.getvalue() and len(cluster.workers) == 2
    xr.testing.assert_identical(open_sweep(tmp_path / "d.zarr").load(), reference)


def test_without_dask_the_chunks_run_on_a_thread_pool(tmp_path, reference, monkeypatch):
    real = optional.importlib.import_module

    def fake(name, *args):
        if name.split(".")[0] in ("dask", "distributed"):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name.split(".")[0])
        return real(name, *args)

    monkeypatch.setattr(optional.importlib, "import_module", fake)
    out = run_sweep(SWEEP, tmp_path / "s.zarr", workers=2)
    xr.testing.assert_identical(open_sweep(out).load(), reference)
    xr.testing.assert_identical(summary(open_sweep(out)), summary(reference))
    with pytest.raises(optional.MissingExtraError, match="dask"):
        run_sweep(SWEEP, tmp_path / "d.zarr", scheduler="tcp://127.0.0.1:1")
    assert not (tmp_path / "d.zarr").exists()


@pytest.mark.parametrize("where", [{"client": "sync"}, {"workers": 2}], ids=["here", "threads"])
def test_an_interrupted_sweep_resumes_from_its_finished_chunks(tmp_path, reference, where):
    out = tmp_path / "s.zarr"
    run_until_interrupted(SWEEP, out, after=2, **where)
    flags = xr.open_zarr(out)["chunk_done"].values
    assert 2 <= flags.sum() < 4
    with pytest.raises(InputError, match=f"{4 - flags.sum()} of 4 chunks are not written yet"):
        open_sweep(out)
    calls = []
    run_sweep(SWEEP, out, progress=lambda d, n: calls.append(d), **where)
    assert calls[0] == flags.sum() and calls[-1] == 4  # only the missing chunks ran
    xr.testing.assert_identical(open_sweep(out).load(), reference)


def test_a_store_of_another_sweep_is_refused(tmp_path, store):
    with pytest.raises(InputError, match="holds another sweep"):
        run_sweep(SWEEP.replace("seed = 42", "seed = 1"), store, client="sync")
    # a comment or the order of the file's tables is not another sweep
    assert run_sweep("# the same\n" + SWEEP, store, client="sync") == store


SCENE = """
[body]
moments = [1.0, 2.0, 3.0]
[initial.angular_velocity]
body = [0.1, 5.0, 0.1]
units = "rad/s"
[time]
duration = 0.02
[integrator]
step = 0.001
"""


def test_a_sweep_killed_then_resumed_after_its_scene_file_changed_is_refused(tmp_path):
    """Issue 30 item 4: the store records the resolved scene's digest; a resumed sweep
    whose scene file was edited is refused with one line, and nothing is mixed."""
    (tmp_path / "body.toml").write_text(SCENE)
    sweep = tmp_path / "s.toml"
    sweep.write_text(SWEEP.replace('"intermediate_axis_flip"', '"body.toml"'))
    out = tmp_path / "s.zarr"
    run_until_interrupted(sweep, out, after=2, client="sync")
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    (tmp_path / "body.toml").write_text(SCENE.replace("[1.0, 2.0, 3.0]", "[1.0, 2.0, 2.9]"))
    spec_file = str(sweep)
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        assert main(["sweep", spec_file, "--out", str(out)]) == 2
    assert err.getvalue().count("\n") == 1
    assert "was begun with another scene" in err.getvalue()
    after = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    assert after == before  # nothing written
    # [set] is part of the resolved scene too
    (tmp_path / "body.toml").write_text(SCENE)
    changed = SWEEP.replace('"time.duration" = 0.02', '"time.duration" = 0.02\n"body.mass" = 2.0')
    sweep.write_text(changed.replace('"intermediate_axis_flip"', '"body.toml"'))
    with pytest.raises(InputError, match="was begun with another scene"):
        run_sweep(sweep, out, client="sync")
    sweep.write_text(SWEEP.replace('"intermediate_axis_flip"', '"body.toml"'))
    assert open_sweep(run_sweep(sweep, out, client="sync")).sizes["sample"] == 5


def test_a_store_begun_with_other_versions_is_finished_only_by_them(tmp_path, monkeypatch):
    out = tmp_path / "s.zarr"
    run_until_interrupted(SWEEP, out, after=2, client="sync")
    done = run_sweep(SWEEP, tmp_path / "d.zarr", client="sync")
    monkeypatch.setattr(spec, "_versions", lambda: "ga-rotors 9.9, numpy 9.9, scipy 9.9")
    with pytest.raises(InputError, match=r"was begun with ga-rotors .*; this is ga-rotors 9\.9"):
        run_sweep(SWEEP, out, client="sync")
    assert run_sweep(SWEEP, done, client="sync") == done  # finished: nothing to draw


def test_the_summary_is_each_grid_points_spread_from_its_own_nominal_run(reference):
    s = summary(reference)
    assert s["angle_median"].dims == (GRID, "time") and int(s["samples"]) == 5
    angles = reference["angle_from_nominal"].values
    for i in range(2):
        a = angles[i]
        assert np.array_equal(s["angle_median"].values[i], np.median(a, axis=0))
        assert np.array_equal(s["angle_p95"].values[i], np.percentile(a, 95, axis=0))
        assert np.array_equal(s["angle_max"].values[i], a.max(axis=0))
    assert s["failed"].values.sum() == 0 and not s["nominal_failed"].values.any()
    h = histogram(reference, bins=7)
    assert h["count"].dims == (GRID, "time", "bin")
    assert h["count"].values.sum(axis=-1).tolist() == [[5, 5], [5, 5]]
    edges = h["edges"].values
    assert np.array_equal(h["count"].values[1, 1], np.histogram(angles[1, :, 1], bins=edges)[0])


def test_samples_that_blow_up_are_counted_as_failed_with_why(tmp_path, capsys):
    """Issue 30 item 7: a summary states how many samples failed and why, rather than
    leaving them out of a count of samples. Past about 5,000 rad/s (one of the five draws
    here), RK4's 1 ms steps overflow within 0.1 s on this body; below it the state stays
    finite, its norm drifting (the angle does not depend on it). The second grid point's
    nominal run overflows."""
    text = SWEEP.replace(
        '"initial.angular_velocity.body[1]" = [9.0, 10.0]',
        '"initial.angular_velocity.body[1]" = [10.0, 900000.0]',
    )
    text = text.replace("normal = [0.0, 0.1]", "normal = [0.0, 2000.0]")
    text = text.replace('"time.duration" = 0.02', '"time.duration" = 0.1')
    text = text.replace("times = [0.01, 0.02]", "times = [0.05, 0.1]")
    spec_file = tmp_path / "s.toml"
    spec_file.write_text(text)
    assert main(["sweep", str(spec_file), "--out", str(tmp_path / "s.zarr"), "--here"]) == 0
    printed = capsys.readouterr().out
    ds = open_sweep(tmp_path / "s.zarr").load()
    angle = ds["angle_from_nominal"].values
    s = summary(ds)
    failed = np.isnan(angle).sum(axis=1)
    assert np.array_equal(s["failed"].values, failed)
    assert 0 < failed[0, -1] < 5  # some blew up among finite ones
    assert s["nominal_failed"].values.tolist() == [[False, False], [True, True]]
    q = ds["q"].values
    finite = np.isfinite(q).all(axis=-1)
    assert np.array_equal(np.isnan(angle[0]), ~finite[0])
    assert abs(np.linalg.norm(q[0][finite[0]], axis=-1) - 1).max() > 1e-9  # drifted, still angled
    assert (
        np.isfinite(s["angle_median"].values[0]).all()
        and np.isnan(s["angle_median"].values[1]).all()
    )
    assert f"{failed[0, -1]} of 5: its state stopped being finite" in printed
    assert "the grid point's nominal run stopped being finite" in printed


def test_a_refused_sample_is_named_by_its_place_in_the_sweep(tmp_path):
    """Issue 30 item 12: a sample whose values the scene refuses is named by its index
    in the sweep and its values, not as "sample 0" of its chunk."""
    text = SWEEP.replace("uniform = [0.25, 0.35]", "uniform = [-0.3, 2.0]")
    for seed in range(100):
        trial = text.replace("seed = 42", f"seed = {seed}")
        mass = load_sweep(trial).values(0, 10)["body.mass"]
        first = int(np.argmax(mass <= 0)) if (mass <= 0).any() else None
        if first is not None and first >= 4:  # past the first chunk
            break
    with pytest.raises(SceneError) as refused:
        run_sweep(trial, tmp_path / "s.zarr", client="sync")
    message = str(refused.value)
    assert f"sample {first} (" in message and f"body.mass = {float(mass[first])!r}" in message
    assert "\n" not in message and message.endswith(
        f"body.mass: expected a finite positive number (kg), got {float(mass[first])!r}"
    )


def test_a_full_disk_is_one_line_naming_the_store(tmp_path, monkeypatch, capsys):
    import zarr

    real = zarr.Array.__setitem__

    def disk_full(self, key, value):
        if self.path == "w" and (key[0].start, key[1].start) == (1, 0):  # chunk 2
            raise OSError(28, "No space left on device")
        return real(self, key, value)

    monkeypatch.setattr(zarr.Array, "__setitem__", disk_full)
    spec_file = tmp_path / "s.toml"
    spec_file.write_text(SWEEP)
    for where in (["--here"], ["--workers", "2"]):
        out = tmp_path / f"s{len(where)}.zarr"
        assert main(["sweep", str(spec_file), "--out", str(out), *where]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--out: cannot write " in err
        assert "(chunk 2): No space left on device" in err
        assert not xr.open_zarr(out)["chunk_done"].values[2]


def test_the_command_runs_resumes_and_prints_each_grid_points_spread(tmp_path, capsys):
    spec_file = tmp_path / "dispersion.toml"
    spec_file.write_text(SWEEP)
    argv = ["sweep", str(spec_file), "--out", str(tmp_path / "d.zarr"), "--here"]
    assert main(argv) == 0
    printed = capsys.readouterr().out
    assert f"{GRID} = 9 (5 samples)" in printed and "0 of 5" in printed and "d.zarr" in printed
    assert main(argv) == 0  # again: everything already done


def test_a_sweep_without_draws_has_no_sample_dimension(tmp_path):
    text = '[sweep]\nscene = "intermediate_axis_flip"\n[set]\n"time.duration" = 0.01\n'
    text += (
        '[grid]\n"body.mass" = [0.3, 0.4, 0.5]\n"initial.angular_velocity.body[1]" = [9.0, 10.0]\n'
    )
    ds = open_sweep(run_sweep(text, tmp_path / "g.zarr", workers=2))
    assert ds["q"].dims == ("body_mass", GRID, "time", "quaternion_component")
    assert "angle_from_nominal" not in ds and "q_nominal" not in ds
    s = summary(ds)
    assert s["failed"].dims == ("body_mass", GRID, "time") and int(s["failed"].sum()) == 0


def test_an_unreachable_scheduler_is_one_line_and_writes_nothing(tmp_path, capsys, monkeypatch):
    from ga_rotors.sweep import run as sweep_run

    monkeypatch.setattr(sweep_run, "SCHEDULER_TIMEOUT", 1)
    spec_file = tmp_path / "dispersion.toml"
    spec_file.write_text(SWEEP)
    with socket.socket() as free:  # a port nobody listens on
        free.bind(("127.0.0.1", 0))
        port = free.getsockname()[1]
    argv = ["sweep", str(spec_file), "--out", str(tmp_path / "d.zarr")]
    assert main([*argv, "--scheduler", f"tcp://127.0.0.1:{port}"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ga-rotors: error: --scheduler: cannot reach tcp://")
    assert "\n" not in err and not (tmp_path / "d.zarr").exists()


@pytest.mark.parametrize("where", [{"client": "sync"}, {"workers": 2}], ids=["here", "threads"])
def test_a_full_disk_while_making_the_store_is_one_line_and_leaves_nothing(
    tmp_path, monkeypatch, where
):
    # on threads the store is made while the first chunks integrate: the first chunk to
    # write raises what making it raised
    def disk_full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(xr.Dataset, "to_zarr", disk_full)
    with pytest.raises(InputError, match=r"cannot write .*s\.zarr \(creating it\): No space"):
        run_sweep(SWEEP, tmp_path / "s.zarr", **where)
    assert list(tmp_path.iterdir()) == []  # no store, no staging left


def test_a_store_of_an_earlier_layout_is_named_as_such(tmp_path, capsys):
    old = tmp_path / "old.zarr"
    xr.Dataset({"value_0": ("sample", np.arange(3.0))}, attrs={"sweep_digest": "abc"}).to_zarr(
        old, zarr_format=2, consolidated=True
    )
    with pytest.raises(InputError, match=r"a sweep store of an earlier ga_rotors .*open_zarr"):
        open_sweep(old)
    with pytest.raises(InputError, match="earlier ga_rotors"):
        run_sweep(SWEEP, old, client="sync")


LONG = os.environ.get("GA_ROTORS_LONG") == "1"


@pytest.mark.skipif(not LONG, reason="long mode: set GA_ROTORS_LONG=1 (about a minute)")
def test_long_a_large_sweep_is_the_same_store_however_it_runs(tmp_path):
    """Three blocks of draws across many chunks of a grid: in this thread, on threads and
    on a local cluster of worker processes, the same store bit for bit, and its draws the
    documented ones sample by sample."""
    text = SWEEP.replace("samples = 5", f"samples = {BLOCK + 1500}").replace(
        "chunk = 4", "chunk = 1000"
    )
    here = open_sweep(run_sweep(text, tmp_path / "here.zarr", client="sync")).load()
    threads = open_sweep(run_sweep(text, tmp_path / "threads.zarr", workers=3)).load()
    xr.testing.assert_identical(here, threads)
    from ga_rotors.sweep import local_cluster

    with local_cluster(2) as cluster, distributed.Client(cluster) as client:
        out = run_sweep(text, tmp_path / "cluster.zarr", client=client)
    xr.testing.assert_identical(here, open_sweep(out).load())
    sweep = load_sweep(text)
    draws = [("initial.angular_velocity.body[0]", "normal", (0.0, 0.1)),
             ("body.mass", "uniform", (0.25, 0.35))]  # fmt: skip
    expected = _oracle_draws(42, 0, sweep.size, draws)
    for key, values in expected.items():
        assert np.array_equal(here[spec.coordinate_name(key)].values.ravel(), values)
