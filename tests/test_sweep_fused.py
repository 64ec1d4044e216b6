"""The sweep's compiled pass per chunk (draws, inputs, loop, angle, store layout in one go)
against the per-sample path it replaces where it applies: the same numbers, bit for bit."""

from __future__ import annotations

import numba
import numpy as np
import pytest
from _sweeps import run_until_interrupted
from hypothesis import given, settings
from hypothesis import strategies as st

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")
pytest.importorskip("distributed")

from ga_rotors import ensemble  # noqa: E402
from ga_rotors.errors import SceneError  # noqa: E402
from ga_rotors.sweep import (  # noqa: E402
    _normal,
    load_sweep,
    open_sweep,
    run_sweep,
    spec,
)
from ga_rotors.sweep import run as sweep_run  # noqa: E402

#: A sweep the compiled pass takes: moments and body rates varied, the quaternion path.
FAST = """
[sweep]
scene = "intermediate_axis_flip"
samples = 7
seed = 3
chunk = 5
times = [0.01, 0.03]

[set]
"time.duration" = 0.03
"integrator.paths" = ["quaternion"]
"body" = {moments = [1.0, 2.0, 2.5]}

[grid]
"initial.angular_velocity.body[1]" = [9.0, 10.0]

[[draw]]
key = "body.moments[0]"
normal = [1.0, 0.01]

[[draw]]
key = "initial.angular_velocity.body[2]"
uniform = [-0.5, 0.5]
"""

VARIANTS = {
    "grid and draws": FAST,
    # a whole vector per grid point, rates in deg/s (scaled in the pass)
    "vectors, deg/s": FAST.replace(
        '"initial.angular_velocity.body[1]" = [9.0, 10.0]',
        '"initial.angular_velocity.body" = [[1.0, 500.0, 2.0], [0.0, 600.0, 0.0]]\n'
        '"body.moments" = [[1.0, 2.0, 2.5], [2.0, 2.0, 3.0]]',
    )
    .replace('key = "body.moments[0]"', 'key = "initial.angular_velocity.body[0]"')
    .replace('"integrator.paths" = ["quaternion"]',
             '"integrator.paths" = ["quaternion"]\n"initial.angular_velocity.units" = "deg/s"'),
    # a declared torque: its parameters go into the loop as the batched kernel's do
    "damping": FAST.replace('scene = "intermediate_axis_flip"', 'scene = "damped_top"').replace(
        '"body" =', '"output.quantities" = ["energy"]\n"body" ='
    ),
    # one sample overflows (NaN from then on, no angle), one drifts off the unit norm
    "blow-up": FAST.replace("[9.0, 10.0]", "[9.0, 900000.0, 300.0]")
    .replace('"time.duration" = 0.03', '"time.duration" = 0.1')
    .replace("times = [0.01, 0.03]", "times = [0.05, 0.1]"),
}  # fmt: skip


@pytest.fixture
def per_sample(monkeypatch):
    """Turns the compiled pass off: every chunk takes the per-sample path."""

    def off():
        monkeypatch.setattr(ensemble, "run_columns", lambda *args: None)

    return off


@pytest.fixture
def used(monkeypatch):
    """Counts the chunks (and pieces) the compiled pass did."""
    calls = []
    real = ensemble.run_columns

    def spy(*args):
        done = real(*args)
        calls.append(done is not None)
        return done

    monkeypatch.setattr(ensemble, "run_columns", spy)
    return calls


def _files(store):
    """Each chunk file's float64 numbers, as their bits, every NaN made the same one: a
    state that overflowed holds NaN, whose sign bit the two loops' instructions may set
    differently (it is no number; xarray reads both as NaN)."""
    out = {}
    for name in ("q", "w", "angle_from_nominal", "value_0", "value_1", "value_2"):
        for p in sorted((store / name).glob("[0-9]*")):
            x = np.frombuffer(p.read_bytes(), np.float64).copy()
            x[np.isnan(x)] = np.nan
            out[f"{name}/{p.name}"] = x.view(np.uint64).tolist()
    return out


@pytest.mark.parametrize("text", list(VARIANTS.values()), ids=list(VARIANTS))
def test_the_compiled_pass_writes_the_store_the_per_sample_path_writes(
    tmp_path, text, used, per_sample
):
    fused = run_sweep(text, tmp_path / "fused.zarr", client="sync")
    assert used and all(used)  # every chunk in one pass
    per_sample()
    plain = run_sweep(text, tmp_path / "plain.zarr", client="sync")
    a, b = _files(fused), _files(plain)
    assert a.keys() == b.keys() and len(a) > 6
    assert [k for k in a if a[k] != b[k]] == []
    xr.testing.assert_identical(open_sweep(fused).load(), open_sweep(plain).load())


def test_a_sample_of_the_compiled_pass_is_its_own_single_ensemble_run():
    sweep = load_sweep(FAST)
    cols, values = sweep.columns(0, sweep.size)
    nominal = sweep_run._nominal(sweep)
    q, w, angle = ensemble.run_columns(sweep.scene, sweep.rows, cols, sweep.times, nominal)
    for i in (0, 5, sweep.size - 1):
        one = {key: v[i : i + 1] for key, v in values.items()}
        run = ensemble.run_samples(ensemble.scene_samples(sweep.scene, one), sweep.times)
        assert np.array_equal(q[i], run.q[:, 0]) and np.array_equal(w[i], run.w[:, 0])
        expected = np.empty((1, 2))
        sweep_run._angles(run.q, nominal, expected)
        assert np.array_equal(angle[i], expected[0])


def test_threads_and_pieces_write_what_one_thread_writes(tmp_path, used, monkeypatch):
    monkeypatch.setattr(sweep_run, "MIN_PIECE", 1)  # the last chunks cut between threads
    monkeypatch.setattr(sweep_run, "PIECE_ALIGN", 1)
    text = FAST.replace("samples = 7", "samples = 20")
    threads = run_sweep(text, tmp_path / "threads.zarr", workers=2)
    one = run_sweep(text, tmp_path / "one.zarr", client="sync")
    assert used and all(used)
    assert _files(threads) == _files(one)


def test_a_store_begun_by_the_per_sample_path_is_finished_by_the_compiled_pass(tmp_path, used):
    # resuming a store that the other path (an older version) began gives the store
    # either path writes whole
    whole = _files(run_sweep(FAST, tmp_path / "whole.zarr", client="sync"))
    out = tmp_path / "s.zarr"
    with pytest.MonkeyPatch.context() as m:
        m.setattr(ensemble, "run_columns", lambda *args: None)
        run_until_interrupted(FAST, out, client="sync")
    assert 0 < len(_files(out)) < len(whole)
    used.clear()
    run_sweep(FAST, out, client="sync")
    assert used and all(used)
    assert _files(out) == whole


@pytest.mark.parametrize(
    "change",
    [
        ('"integrator.paths" = ["quaternion"]', '"integrator.paths" = ["rotor"]'),
        ('key = "body.moments[0]"', 'key = "body.mass"'),  # a Scene per sample
    ],
    ids=["rotor path", "other key"],
)
def test_outside_the_compiled_pass_the_per_sample_path_runs(tmp_path, used, change):
    text = FAST.replace(*change)
    out = run_sweep(text, tmp_path / "s.zarr", client="sync")
    assert used and not any(used)
    sweep = load_sweep(text)
    values = sweep.values(0, sweep.size)
    run = ensemble.run_samples(ensemble.scene_samples(sweep.scene, values), sweep.times)
    assert np.array_equal(open_sweep(out)["q"].values, run.q.transpose(1, 0, 2))


def test_a_value_the_body_refuses_is_named_by_the_per_sample_path(tmp_path, used):
    # moments outside the triangle inequality for some samples: the pass hands the chunk
    # back, and the per-sample path names the first bad sample and key as before
    text = FAST.replace("normal = [1.0, 0.01]", "normal = [4.0, 0.5]")
    with pytest.raises(SceneError, match=r"sample \d+: .*triangle"):
        run_sweep(text, tmp_path / "s.zarr", client="sync")
    assert used and not used[0]


@numba.njit
def _values_of(raw, normal, a, b, out):
    # each draw alone, as the docs define it, from outputs given here rather than streamed
    for i in range(raw.size):
        j = i % out.shape[0]
        u = spec._uniform(raw[i])
        v = _normal.inverse_normal(min(u, spec._BELOW_ONE)) * b[j] if normal[j] else u * b[j]
        out[j, i // out.shape[0]] = v + a[j]


def test_the_rows_of_draws_are_the_draws_one_by_one_bit_for_bit():
    # _from_uniform (vectorised central piece, listed tails, then the scaling) against
    # each output drawn alone (the quantile's piece chosen per draw), on 10^6 outputs and
    # the hard cases: k = 0 (the smallest u), 2^53 - 1 (u rounds to 1), the centre, and
    # the seams of the quantile's pieces (u = 0.075 and 0.925) and their neighbours
    rng = np.random.default_rng(7)
    raw = rng.integers(0, 2**64, size=10**6, dtype=np.uint64, endpoint=False)
    ks = [0, 1, 2**53 - 1, 2**53 - 2, 2**52, 2**52 - 1]
    for seam in (0.5 - _normal.CENTRAL, 0.5 + _normal.CENTRAL):
        k = int(seam * 2**53)
        ks += [k - 2, k - 1, k, k + 1, k + 2]
    raw[: len(ks)] = np.array(ks, dtype=np.uint64) << np.uint64(11)
    normal = np.array([True, False, True])
    a, b = np.array([0.0, 1.0, -3.0]), np.array([1.0, 2.0, 2.5])
    raw = raw[: raw.size // 3 * 3]
    one_by_one = np.empty((3, raw.size // 3))
    _values_of(raw, normal, a, b, one_by_one)
    rows = (((raw >> np.uint64(11)).astype(np.float64) + 0.5) * 2.0**-53).reshape(-1, 3).T.copy()
    spec._from_uniform(normal, a, b, rows)
    assert np.all(np.isfinite(rows))
    assert np.array_equal(rows.view(np.uint64), one_by_one.view(np.uint64))
    tails = np.abs(rows[0] - 0.0) > 1.4395  # the central piece ends at x = 1.43953...
    assert 0.13 < tails.mean() < 0.17  # both pieces taken, about as often as they should


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**64 - 1),
    lo=st.integers(0, 3 * spec.BLOCK),
    n=st.integers(0, 2 * spec.BLOCK + 3),  # none: no stream, nothing drawn
    nvars=st.integers(1, 3),
)
def test_the_compiled_streams_are_numpys_pcg64_outputs(seed, lo, n, nvars):
    # Each block's stream run on in compiled code (from numpy's seeded and advanced
    # PCG64) against numpy's random_raw of the whole block, sliced: the uniform draw
    # u = (k + 1/2)·2^-53 of every output, from any first sample, across block ends.
    hi = lo + n
    out = np.empty((nvars, n))
    kinds, zeros, ones = np.zeros(nvars, dtype=bool), np.zeros(nvars), np.ones(nvars)
    spec._draw(spec._streams(seed, lo, hi, nvars), lo, kinds, zeros, ones, out)
    raw = []
    for block in range(lo // spec.BLOCK, -(-hi // spec.BLOCK)):
        bits = np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(block,)))
        raw.append(bits.random_raw(spec.BLOCK * nvars))
    first = lo - lo // spec.BLOCK * spec.BLOCK
    raw = np.concatenate([np.empty(0, np.uint64), *raw])[first * nvars : (first + n) * nvars]
    expected = ((raw >> np.uint64(11)).astype(np.float64) + 0.5) * 2.0**-53
    assert np.array_equal(out, expected.reshape(n, nvars).T)


def test_the_edge_chunk_file_is_extended_to_the_full_chunk_not_padded(tmp_path):
    # 14 samples in chunks of 5: the last chunk holds 4 samples; its file has the size of
    # a full chunk (what zarr reads), its last sample's bytes a hole, and reads back
    out = run_sweep(FAST, tmp_path / "s.zarr", client="sync")
    edge = out / "q" / "2.0.0"
    assert edge.stat().st_size == 5 * 2 * 4 * 8
    ds = open_sweep(out).load()
    assert ds.sizes["sample"] == 14 and not np.isnan(ds["q"].values[10:]).any()
    zarr = pytest.importorskip("zarr")
    direct = zarr.open_group(out, mode="r", zarr_format=2)["q"][:]
    assert np.array_equal(direct, ds["q"].values)


@pytest.mark.parametrize("client", ["sync", None])
def test_a_scene_file_changed_between_two_runs_of_one_sweep_is_read_again(tmp_path, client):
    # the chunks run in this process took the Sweep (and its scene) of the first run
    scene = tmp_path / "body.toml"
    body = "[body]\nmoments = [1.0, 2.0, 2.5]\n[initial.angular_velocity]\n"
    body += 'body = [0.1, 3.0, 0.2]\nunits = "rad/s"\n'
    body += '[time]\nduration = 0.02\n[integrator]\nstep = 0.01\npaths = ["quaternion"]\n'
    scene.write_text(body)
    sweep = tmp_path / "s.toml"
    sweep.write_text('[sweep]\nscene = "body.toml"\n[grid]\n"body.moments[0]" = [1.0, 1.1]\n')
    first = open_sweep(run_sweep(sweep, tmp_path / "a.zarr", client=client)).load()
    scene.write_text(body.replace("[0.1, 3.0, 0.2]", "[0.1, 4.0, 0.2]"))
    second = open_sweep(run_sweep(sweep, tmp_path / "b.zarr", client=client)).load()
    assert second["w"].values[0, 0, 1] != first["w"].values[0, 0, 1]
    values = {"body.moments[0]": np.array([1.0, 1.1])}
    run = ensemble.run_samples(ensemble.scene_samples(load_sweep(sweep).scene, values))
    assert np.array_equal(second["q"].values, run.q.transpose(1, 0, 2))


def test_a_local_cluster_writes_what_one_thread_writes(tmp_path, used):
    distributed = pytest.importorskip("distributed")
    one = run_sweep(FAST, tmp_path / "one.zarr", client="sync")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        out = run_sweep(FAST, tmp_path / "cluster.zarr", client=client)
    assert used and all(used)
    assert _files(out) == _files(one)


def test_a_bad_value_is_named_as_the_per_sample_path_names_it(tmp_path, monkeypatch):
    # samples 7 to 13 have a negative moment; in chunks of 10 the first chunk's last
    # sample is one of them, which the pass's check of its mapping meets first: it must
    # leave the naming to the per-sample path (the first bad sample), not name its own
    text = FAST.replace("chunk = 5", "chunk = 10").replace(
        '"initial.angular_velocity.body[1]" = [9.0, 10.0]', '"body.moments[1]" = [2.0, -2.0]'
    )
    errors = []
    for off in (False, True):
        if off:
            monkeypatch.setattr(ensemble, "run_columns", lambda *args: None)
        with pytest.raises(SceneError) as raised:
            run_sweep(text, tmp_path / f"{off}.zarr", client="sync")
        errors.append(str(raised.value))
    assert errors[0] == errors[1] and "sample 7" in errors[0]


def test_a_threaded_sweep_of_the_compiled_pass_interrupted_resumes_to_the_whole(tmp_path, used):
    # Ctrl-C reaches the thread waiting on Dask: the chunks running finish and flag
    # themselves (the last ones written by their own threads), the rest are not started
    text = FAST.replace("samples = 7", "samples = 20").replace("chunk = 5", "chunk = 2")
    whole = _files(run_sweep(text, tmp_path / "whole.zarr", workers=2))
    out = tmp_path / "s.zarr"
    run_until_interrupted(text, out, workers=2)
    flags = xr.open_zarr(out)["chunk_done"].values == 1
    assert 1 <= flags.sum() < 20
    calls = []
    run_sweep(text, out, workers=2, progress=lambda d, n: calls.append(d))
    assert calls[0] == flags.sum() and calls[-1] == 20
    assert used and all(used)
    assert _files(out) == whole
