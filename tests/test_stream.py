"""Streamed runs: a run in pieces equals the one-shot run bit for bit (every integrator,
every path, free, torqued by a torque of time, kinematic, stopped paths)."""

import os
import warnings

import numpy as np
import pytest
from _direct_io import PATHS
from _torques_for_tests import turning_torque, wobble

from ga_rotors import quaternion as Q
from ga_rotors import shapes
from ga_rotors.integrators import PrescribedOmega, TorqueTerm, catalogue, get
from ga_rotors.simulation import simulate, simulate_chunks

BODY = (1.0, 2.0, 3.0)
Q0 = Q.from_axis_angle([0.3, 1.0, 0.2], 0.7)
W0 = (0.4, -0.2, 2.0)
# 60 steps sampled every 7 (the last sample is off the pattern), pieces of 14 steps
RUN = dict(duration=0.6, step=0.01, sample_every=7)


def _same(one, pieces):
    """The pieces joined are the one-shot trajectory, every array bit for bit."""
    assert set(pieces[0].names) == set(one.names)
    for name in one.names:
        joined = np.concatenate([p[name] for p in pieces])
        assert joined.shape == one[name].shape, name
        assert (joined == one[name]).all() or np.array_equal(joined, one[name], equal_nan=True), (
            name,
            np.abs(joined - one[name]).max(),
        )
    assert pieces[-1].meta == one.meta


def _both(*args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        one = simulate(*args, **RUN, **kwargs)
        pieces = list(simulate_chunks(*args, **RUN, chunk_steps=14, **kwargs))
    return one, pieces, caught


def _methods(problem):
    return [row["name"] for row in catalogue() if problem in get(row["name"]).problems]


@pytest.mark.parametrize("method", _methods("free"))
def test_pieces_equal_one_run_free(method):
    paths = sorted(get(method).paths & {"rotor", "quaternion", "euler"})
    one, pieces, _ = _both(BODY, Q0, W0, paths=paths, integrator=method,
                           outputs=("energy", "L", "L_space", "angles"))  # fmt: skip
    assert len(pieces) == 5  # 60 steps in pieces of 14
    _same(one, pieces)


@pytest.mark.parametrize("method", _methods("torqued"))
def test_pieces_equal_one_run_with_a_torque_of_time(method):
    """The torque reads t: a piece sees exactly the times the one-shot run sees."""
    paths = sorted(get(method).paths & {"rotor", "quaternion", "euler"})
    torque = TorqueTerm(turning_torque, (0.5, 3.0), depends_on_omega=False)
    one, pieces, _ = _both(BODY, Q0, W0, paths=paths, integrator=method, torques=(torque,),
                           t0=0.3)  # fmt: skip
    _same(one, pieces)


@pytest.mark.parametrize("method", _methods("kinematic"))
def test_pieces_equal_one_run_kinematic(method):
    paths = sorted(get(method).paths & {"rotor", "quaternion", "euler"})
    omega = PrescribedOmega(wobble, (0.3, 2.0, 1.5))
    one, pieces, _ = _both(None, Q0, omega, paths=paths, integrator=method, t0=0.1)
    _same(one, pieces)


@pytest.mark.parametrize("method", ["rk4", "dop853"])
def test_pieces_of_a_path_that_stops_early(method):
    """The Euler-angle path started at its singularity stops; the others go on."""
    q0 = Q.from_axis_angle([0.0, 1.0, 0.0], 0.0)
    one, pieces, caught = _both(shapes.disk(2.0, 0.075), q0, (0.02, 0.03, 15.7),
                                paths=("rotor", "euler"), integrator=method,
                                euler_angles=(0.0, 0.0, 0.0))  # fmt: skip
    assert not one.meta["paths"]["euler"]["complete"]
    assert len(caught) == 2  # one warning each: one run, one run in pieces
    _same(one, pieces)


def test_pieces_report_progress_to_the_end():
    seen = []
    list(simulate_chunks(BODY, Q0, W0, **RUN, chunk_steps=14, paths=("rotor", "quaternion"),
                         progress=lambda done, total: seen.append((done, total))))  # fmt: skip
    assert seen[-1] == (120, 120) and seen == sorted(seen)


def test_chunk_steps_is_checked():
    from ga_rotors.errors import InputError

    with pytest.raises(InputError, match="chunk_steps"):
        simulate_chunks(BODY, Q0, W0, **RUN, chunk_steps=0)
    with pytest.raises(InputError, match="not an argument"):
        simulate_chunks(BODY, Q0, W0, **RUN, colour="red")


# ------------------------------------------------------------------ streamed scene runs

from ga_rotors.scene import (  # noqa: E402
    bundled,
    load_scene,
    report,
    run_scene,
    stream_scene,
    write_outputs,
)

ALL_FORMATS = ["csv", "npz", "netcdf", "zarr"]


def _pieces_of(scene):
    """A piece length that splits the run into about seven uneven pieces."""
    return max(1, scene.steps // 7 + 3)


def _compare_files(scene, streamed, whole):
    import xarray as xr

    from ga_rotors.results import read

    name = scene.name
    assert (streamed / f"{name}.csv").read_bytes() == (whole / f"{name}.csv").read_bytes()
    a, b = np.load(streamed / f"{name}.npz"), np.load(whole / f"{name}.npz")
    assert a.files == b.files
    for key in a.files:
        assert np.array_equal(a[key], b[key], equal_nan=a[key].dtype.kind == "f"), key
    for suffix in (".nc", ".zarr"):
        xr.testing.assert_identical(read(streamed / f"{name}{suffix}"),
                                    read(whole / f"{name}{suffix}"))  # fmt: skip


@pytest.mark.parametrize("how", PATHS)
def test_a_streamed_npz_holds_the_arrays_however_it_was_written(tmp_path, monkeypatch, how):
    """The rows files and the archive straight to and from the disk, or through the page
    cache (no O_DIRECT; refused at the open, at the first write or read): the same arrays,
    each member's checksum right; rows files of several buffers and a ragged end."""
    import zipfile

    from _direct_io import arrange

    from ga_rotors.results import streams
    from ga_rotors.trajectory import Trajectory

    arrange(how, tmp_path, monkeypatch)
    monkeypatch.setattr(streams, "ROWS_BUFFER", 8192)
    rng = np.random.default_rng(7)
    pieces = [
        Trajectory({"t": rng.random(n), "w": rng.random((n, 3))}, {"w": ("1", "2", "3")})
        for n in (1, 700, 0, 1500, 3)
    ]
    out = streams.NpzStream(tmp_path / "run.npz")
    for piece in pieces:
        out.append(piece)
    out.close({})
    assert out.direct == (how == "direct")
    with zipfile.ZipFile(tmp_path / "run.npz") as archive:
        assert archive.testzip() is None
    data = np.load(tmp_path / "run.npz")
    assert data.files == ["t", "w", "w__components"]
    for name in ("t", "w"):
        assert np.array_equal(data[name], np.concatenate([p[name] for p in pieces]))
    assert data["w__components"].tolist() == ["1", "2", "3"]
    assert [p.name for p in tmp_path.iterdir()] == ["run.npz"]  # the rows files are gone


@pytest.mark.parametrize("chunk_rows, write_chunks", [(4, 1), (16, 2), (64, 8)])
def test_a_streamed_zarr_store_holds_the_rows_however_the_pieces_fall(
    tmp_path, monkeypatch, chunk_rows, write_chunks
):
    """Pieces shorter than a chunk, across chunks, empty, many chunks long: the store
    (written whole chunks at a time after the first piece, into arrays grown by doubling
    and cut back at the end) reads back as the rows given, chunked as declared."""
    import json

    from ga_rotors.results import read, streams
    from ga_rotors.trajectory import Trajectory

    monkeypatch.setattr(streams, "CHUNK_ROWS", chunk_rows)
    monkeypatch.setattr(streams, "ZARR_WRITE_CHUNKS", write_chunks)
    rng = np.random.default_rng(11)
    sizes = (0, 3, 1, 50, 0, 7, 130, 2, 64)
    starts = np.cumsum((0, *sizes))
    pieces = [
        Trajectory({"t": np.arange(lo, lo + n, dtype=float), "w": rng.random((n, 3))},
                   {"w": ("1", "2", "3")})
        for lo, n in zip(starts, sizes, strict=False)
    ]  # fmt: skip
    out = streams.ZarrStream(tmp_path / "run.zarr")
    for piece in pieces:
        out.append(piece)
    out.close({})
    ds = read(tmp_path / "run.zarr")
    assert ds["t"].values.tolist() == list(range(sum(sizes)))
    assert np.array_equal(ds["w"].values, np.concatenate([p.w for p in pieces]))
    meta = json.loads((tmp_path / "run.zarr" / "w" / ".zarray").read_text())
    assert meta["shape"] == [sum(sizes), 3] and meta["chunks"] == [chunk_rows, 3]


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc/self/fd (Linux)")
@pytest.mark.parametrize("finish", ["close", "abort"])
def test_a_netcdf_stream_holds_its_file_open_between_pieces_and_lets_it_go(tmp_path, finish):
    """Opened once for the pieces after the first (not once per piece), closed by
    ``close`` (the rows and the attributes read back) and by ``abort`` (a failed run)."""
    from ga_rotors.results import read, streams
    from ga_rotors.trajectory import Trajectory

    path = tmp_path / "run.nc"
    real = os.path.realpath(path)  # what /proc/self/fd shows (tmp_path may hold a link)

    def handles():
        fds = os.listdir("/proc/self/fd")
        return sum(os.path.realpath(f"/proc/self/fd/{fd}") == real for fd in fds)

    out = streams.NetcdfStream(path)
    for lo in (0, 2, 4, 6):
        out.append(Trajectory({"t": np.arange(lo, lo + 2.0), "energy": np.ones(2)}))
        assert handles() == (lo > 0)
    if finish == "close":
        out.close({"integrator": "rk4"})
    else:
        out.abort()
    assert handles() == 0
    if finish == "close":
        ds = read(path)
        assert ds["t"].values.tolist() == list(range(8)) and ds.attrs["integrator"] == "rk4"


@pytest.mark.parametrize("name", sorted(bundled()))
def test_streamed_run_writes_the_files_and_summary_of_the_whole_run(name, tmp_path):
    """Every bundled scene in full, streamed in about seven pieces: the same data files
    (CSV bytes, NPZ arrays, netCDF and zarr Datasets), the same summary, and (a short
    run: every sample kept) the same figure."""
    from ga_rotors.scene.figures import DIGEST_PREFIX

    scene = load_scene(name).replace({"output.data": ALL_FORMATS, "output.summary": True})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a scene's own warnings (gimbal lock) both ways
        files, rep = stream_scene(scene, tmp_path / "streamed", chunk_steps=_pieces_of(scene))
        tr = run_scene(scene)
        whole = report(scene, tr)
        write_outputs(scene, tr, tmp_path / "whole", str(whole))
    assert rep.lines == whole.lines and rep.values == whole.values
    assert [p.name for p in files] == sorted(
        (p.name for p in (tmp_path / "whole").iterdir()), key=[p.name for p in files].index
    )
    _compare_files(scene, tmp_path / "streamed", tmp_path / "whole")
    png = {k: (tmp_path / k / f"{name}.png").read_bytes() for k in ("streamed", "whole")}
    digest = [p[p.index(DIGEST_PREFIX.encode()) :][:60] for p in png.values()]
    assert digest[0] == digest[1]


def _scene(effects, **extra):
    from ga_rotors.scene import Scene

    data = {
        "body": {"moments": [1.0, 2.0, 3.0]},
        "initial": {"angular_velocity": {"body": [0.3, 1.0, 0.2], "units": "rad/s"}},
        "time": {"duration": 2.0, "output_step": 0.01},
        "integrator": {"step": 1e-3},
        "effects": effects,
        "output": {"data": ALL_FORMATS, "plots": ["omega", "invariants"], "summary": True},
    }
    for key, value in extra.items():
        data[key] = {**data.get(key, {}), **value}
    return Scene(data)


@pytest.mark.parametrize(
    "scene",
    [
        _scene([{"type": "space_torque", "torque": [0.0, 0.1, 0.2]}]),
        _scene([{"type": "body_torque", "torque": [0.0, 0.0, 0.5]}]),
        _scene([], integrator={"method": "dop853", "tolerance": 1e-10}),
    ],
    ids=["space-torque", "body-torque", "adaptive"],
)
def test_streamed_summary_and_files_equal_the_whole_run_beyond_the_bundled(scene, tmp_path):
    _, rep = stream_scene(scene, tmp_path / "streamed", chunk_steps=_pieces_of(scene))
    tr = run_scene(scene)
    whole = report(scene, tr)
    write_outputs(scene, tr, tmp_path / "whole", str(whole))
    assert rep.lines == whole.lines and rep.values == whole.values
    _compare_files(scene, tmp_path / "streamed", tmp_path / "whole")


def test_a_stopped_path_streams_as_it_stops(tmp_path):
    """The Euler-angle path started at its singularity: ragged columns, NaN-padded
    netCDF/zarr with valid_samples, INCOMPLETE summary, all as the whole run."""
    scene = load_scene("spinning_disk").replace(
        {"initial.orientation.euler": [0.0, 0.0, 0.0], "output.data": ALL_FORMATS,
         "output.summary": True, "time.duration": 1.0}
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, rep = stream_scene(scene, tmp_path / "streamed", chunk_steps=_pieces_of(scene))
        tr = run_scene(scene)
        whole = report(scene, tr)
        write_outputs(scene, tr, tmp_path / "whole", str(whole))
    assert "incomplete" in rep.values and rep.lines == whole.lines
    _compare_files(scene, tmp_path / "streamed", tmp_path / "whole")


def test_the_summary_evaluates_the_reference_once_for_every_path_and_omega(monkeypatch):
    """One evaluation of the exact solution per piece serves the ω error and each path's
    orientation error, a stopped path reading only its own rows: the same numbers as each
    error computed on its own from the reference."""
    scene = load_scene("spinning_disk").replace(
        {"initial.orientation.euler": [0.0, 0.0, 0.0], "time.duration": 0.5,
         "output.quantities": []}
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tr = run_scene(scene)
    exact = scene.exact_solution
    assert tr["euler"].shape[0] < len(tr)  # the Euler path stopped: fewer rows
    calls = []
    evaluate = type(exact).state
    monkeypatch.setattr(
        type(exact), "state", lambda self, t: calls.append(len(t)) or evaluate(self, t)
    )
    rep = report(scene, tr)
    assert calls.count(len(tr)) == 1
    monkeypatch.undo()
    for path in scene.paths:
        q = Q.normalize(tr.quaternions(path))
        alone = exact.orientation_error(tr.t[: q.shape[0]], q).max()
        assert rep.values[f"error_{path}"] == alone, path
    omega = np.linalg.norm(tr.w - exact.angular_velocity(tr.t[: tr.w.shape[0]]), axis=-1)
    assert rep.values["omega_error"] == omega.max()


def test_a_long_runs_figure_keeps_every_samples_extremes():
    """Beyond KEEP_ALL samples the figure's copy is thinned: bounded, and each column's
    smallest and largest value (spikes) survive."""
    from ga_rotors.scene.run import run_pieces
    from ga_rotors.scene.thinning import COLUMNS, KEEP_ALL, ThinnedCopy

    scene = load_scene("intermediate_axis_flip").replace(
        {"time.duration": 60.0, "time.output_step": 0.001}
    )
    pieces = list(run_pieces(scene, chunk_steps=7919))
    count = sum(len(p) for p in pieces)
    assert count > KEEP_ALL
    copy = ThinnedCopy(pieces[0].t[0], pieces[-1].t[-1], count)
    for piece in pieces:
        copy.add(piece)
    thin = copy.trajectory()
    columns = sum(int(np.prod(thin[n].shape[1:])) for n in thin.names if n != "t")
    assert len(thin) <= COLUMNS * (2 + 2 * columns) and len(thin) < count / 2
    for name in thin.names:
        whole = np.concatenate([p[name] for p in pieces])
        assert (thin[name].max(axis=0) == whole.max(axis=0)).all(), name
        assert (thin[name].min(axis=0) == whole.min(axis=0)).all(), name
    assert thin.t[0] == pieces[0].t[0] and thin.t[-1] == pieces[-1].t[-1]


@pytest.mark.parametrize("seed", range(24))
def test_the_thinned_rows_are_each_slices_ends_and_first_extremes(seed):
    """Per slice (the rows in one pixel column): its first and last row, and for each
    column of each array the first row holding its smallest and its largest value, or the
    slice's first row when it holds a NaN; a stopped path's array has fewer rows."""
    from ga_rotors.scene.thinning import ThinnedCopy
    from ga_rotors.trajectory import Trajectory

    rng = np.random.default_rng(seed)
    n, columns = int(rng.integers(1, 400)), int(rng.integers(1, 40))
    t = np.sort(rng.uniform(0.0, 1.0, n))
    arrays = {"t": t}
    for k, rows in enumerate((n, int(rng.integers(0, n + 1)))):
        a = rng.integers(-2, 3, (rows, 2)).astype(float)  # ties
        if rows and seed % 3 == 0:
            a[rng.integers(0, rows, 2), rng.integers(0, 2, 2)] = np.nan
        arrays[f"x{k}"] = a
    copy = ThinnedCopy(0.0, 1.0, 10**6, columns)
    copy.add(Trajectory(arrays))
    expected = set()
    slices = np.clip(np.floor(t * columns), 0, columns - 1)
    for s in np.unique(slices):
        run = np.flatnonzero(slices == s)
        expected |= {run[0], run[-1]}
        for a in (arrays["x0"], arrays["x1"]):
            inside = run[run < a.shape[0]]
            for j in range(a.shape[1] if inside.size else 0):
                v = a[inside, j]
                if np.isnan(v).any():
                    expected.add(inside[0])
                else:
                    expected |= {inside[np.argmin(v)], inside[np.argmax(v)]}
    assert copy.trajectory().t.tolist() == t[sorted(expected)].tolist()


@pytest.mark.parametrize("seed", range(12))
def test_a_lines_envelope_is_each_slices_ends_and_first_extremes(seed):
    """What a figure draws of one line beyond KEEP_ALL rows: per slice its first and last
    row and the first rows of its smallest and largest value (a NaN: the slice's first)."""
    from ga_rotors.scene.thinning import envelope

    rng = np.random.default_rng(seed)
    n, columns = int(rng.integers(1, 400)), int(rng.integers(1, 40))
    t = np.sort(rng.uniform(0.0, 1.0, n))
    y = rng.integers(-2, 3, n).astype(float)  # ties
    if seed % 3 == 0:
        y[rng.integers(0, n, 2)] = np.nan
    expected = set()
    span = t[-1] - t[0] if t[-1] > t[0] else 1.0
    slices = np.clip(np.floor((t - t[0]) / span * columns), 0, columns - 1)
    for s in np.unique(slices):
        run = np.flatnonzero(slices == s)
        expected |= {run[0], run[-1]}
        v = y[run]
        if np.isnan(v).any():
            expected.add(run[0])
        else:
            expected |= {run[np.argmin(v)], run[np.argmax(v)]}
    assert envelope(t, y, columns).tolist() == sorted(expected)


def test_a_long_runs_figure_draws_each_line_through_its_own_envelope():
    """Beyond KEEP_ALL samples each line is drawn through its envelope: at most four rows
    a slice, and its smallest and largest values, first and last samples, all there."""
    from ga_rotors.scene.figures import draw
    from ga_rotors.scene.run import run_scene
    from ga_rotors.scene.thinning import COLUMNS, KEEP_ALL

    scene = load_scene("intermediate_axis_flip").replace(
        {"time.duration": 60.0, "time.output_step": 0.001, "output.plots": ["omega"]}
    )
    tr = run_scene(scene)
    assert len(tr) > KEEP_ALL
    lines = draw(scene, tr).axes[0].get_lines()
    assert len(lines) == 3
    for k, line in enumerate(lines):
        x, y, w = line.get_xdata(), line.get_ydata(), tr.w[:, k]
        assert len(y) <= 4 * COLUMNS < len(w)
        assert (y.min(), y.max()) == (w.min(), w.max())
        assert (x[0], x[-1], y[0], y[-1]) == (tr.t[0], tr.t[-1], w[0], w[-1])
        assert np.isin(x, tr.t).all() and (np.diff(x) > 0).all()


def test_a_zarr_store_replaces_the_previous_runs(tmp_path):
    from ga_rotors.results import read

    scene = load_scene("spinning_disk").replace(
        {"time.duration": 0.5, "output.data": ["zarr"], "output.plots": []}
    )
    stream_scene(scene, tmp_path)
    first = read(tmp_path / "spinning_disk.zarr")
    stream_scene(scene.replace({"time.duration": 0.2}), tmp_path)
    second = read(tmp_path / "spinning_disk.zarr")
    assert first.sizes["time"] == 51 and second.sizes["time"] == 21
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "spinning_disk.scene.toml", "spinning_disk.summary.txt", "spinning_disk.zarr"
    ]  # fmt: skip


def test_streamed_memory_does_not_grow_with_the_run(tmp_path):
    """Ten times the steps, the same peak of traced allocations (within 2x): the samples
    are written as they come (no time is measured). Both runs are many pieces long, so
    each meets the worst moment (a piece written while the next is computed) at least
    once; a short run of three pieces could miss it and halve its peak. (The NPZ archive
    is copied from its row files through a buffer of at most 4 MiB: bounded, and the
    larger run's peak holds more of it.)"""
    import tracemalloc

    # no figure: its copy of a short run is every sample (bounded apart, above)
    scene = load_scene("heavy_top").replace({"output.data": ["csv", "npz"], "output.plots": []})
    peaks = []
    for duration in (2.0, 20.0):
        s = scene.replace({"time.duration": duration})
        stream_scene(s, tmp_path / "warm", chunk_steps=2000)  # compiled, imported
        runs = []
        for repeat in range(2):  # the lower: another thread of the process may allocate
            tracemalloc.start()
            stream_scene(s, tmp_path / f"{duration}-{repeat}", chunk_steps=2000)
            runs.append(tracemalloc.get_traced_memory()[1])
            tracemalloc.stop()
        peaks.append(min(runs))
    assert peaks[1] < 2 * peaks[0], peaks


def test_the_disk_budget_refuses_with_the_key(tmp_path, capsys):
    from ga_rotors.cli import main

    argv = ["run", "heavy_top", "--out", str(tmp_path / "o"), "--max-disk", "0.001"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "time.duration" in err and "--max-disk GIB" in err
    assert "of files" in err and not (tmp_path / "o").exists()


# ------------------------------------------------------------------ CSV text, compiled

from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from ga_rotors.results.decimal import format_rows  # noqa: E402


def _printf(values):
    return "".join(f"{v:.17g}\n" for v in values).encode()  # printf's %.17g


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1,
                max_size=50))  # fmt: skip
def test_csv_values_are_printfs_17g_and_read_back(values):
    text = format_rows(np.array(values)[:, None])
    assert text == _printf(values)
    back = np.array([float(v) for v in text.split()])
    assert np.array_equal(back, np.array(values), equal_nan=True)


def _hard_values():
    rng = np.random.default_rng(13)
    p = np.concatenate([10.0 ** np.arange(-307, 309), [float(f"1e{k}") for k in range(-308, 309)]])
    values = np.concatenate([
        p, np.nextafter(p, 0), np.nextafter(p, np.inf), -p,
        [5e-324, 2.2250738585072014e-308, 2.225073858507201e-308, 1.7976931348623157e308,
         1e-4, 9.9999999999999995e-05, 1e17, 99999999999999999.0, 0.0, -0.0],
        np.frombuffer(rng.bytes(8 * 500_000), dtype=np.float64),
        rng.standard_normal(500_000) * 10.0 ** rng.integers(-300, 300, 500_000),
        [np.nan, np.inf, -np.inf, -5e-324],
    ])  # fmt: skip
    return values


@pytest.mark.parametrize("columns", [1, 8, 11, 16])
def test_csv_values_at_the_hard_places(columns):
    """Powers of ten and their neighbours (where log10 is one off), the range's ends,
    subnormals, the %g switch points, and a million values of every magnitude; in one
    column (each value on its own) and in rows of 8, 11 and 16 (eight values of a row
    at once in vector registers, the rest one by one)."""
    values = _hard_values()
    values = values[: values.size - values.size % columns]
    expected = "".join(
        ",".join(f"{v:.17g}" for v in row) + "\n" for row in values.reshape(-1, columns).tolist()
    ).encode()
    assert format_rows(values.reshape(-1, columns)) == expected


def test_eight_values_at_once_are_one_at_a_times():
    """Every lane of the vector pass (_decimal8) gives what the one-value pass gives: the
    same digits and exponent, and the same verdict on whether the value needs the slow
    path (zeros, subnormals, inf, nan, the ends of the range, next to powers of ten)."""
    from numba import njit

    from ga_rotors.results import decimal as D

    @njit
    def both(values, bits, out_n, out_k, out_ok, one_n, one_k, one_ok):
        for i in range(0, values.shape[0], D.LANES):
            D._decimal8(values, i, D._POW10_HI, D._POW10_LO, D._ROUNDED10, out_n, out_k,
                        out_ok, i)  # fmt: skip
        for i in range(values.shape[0]):
            biased = np.int64((bits[i] >> np.uint64(52)) & np.uint64(0x7FF))
            one_n[i], one_k[i], one_ok[i] = D._decimal_fast(values[i], biased, D._POW10,
                                                            D._ROUNDED10)  # fmt: skip

    values = _hard_values()
    values = np.concatenate([values, -values])
    values = values[: values.size - values.size % D.LANES]
    arrays = [np.empty(values.size, dtype=t) for t in (np.int64, np.int64, np.bool_) * 2]
    both(values, values.view(np.uint64), *arrays)
    n, k, ok, one_n, one_k, one_ok = arrays
    assert np.array_equal(ok, one_ok) and 0.2 < ok.mean() < 1.0
    assert np.array_equal(n[ok], one_n[ok]) and np.array_equal(k[ok], one_k[ok])


def test_the_stream_benchmark_runs_in_its_quick_mode(tmp_path):
    """benchmarks/bench_stream.py end to end, tiny (no number is judged here)."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    out = tmp_path / "bench.json"
    proc = subprocess.run(
        [sys.executable, str(root / "benchmarks" / "bench_stream.py"), "--quick", "--json",
         str(out), "--no-summary"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert "stream / bare wall time" in proc.stdout and "summary: off" in proc.stdout
    results = json.loads(out.read_text())["results"]
    assert set(results) == {"bare", "stream"}
    assert all(r["peak_mb"] > 0 and r["seconds"] > 0 for rows in results.values() for r in rows)


def test_a_long_torqued_runs_figure_balances_energy_over_every_sample(tmp_path):
    """Thinned, the energy-balance panel still integrates τ·ω over every sample: its work
    is the whole run's (the trapezoid sums, carried from piece to piece)."""
    from ga_rotors.scene.figures import energy_balance
    from ga_rotors.scene.output import _Balance
    from ga_rotors.scene.run import run_pieces

    scene = _scene([{"type": "body_torque", "torque": [0.0, 0.2, 0.5]}],
                   time={"duration": 30.0, "output_step": 0.001})  # fmt: skip
    balance, kept = _Balance(scene), []
    for piece in run_pieces(scene, chunk_steps=4999):
        kept.append(balance.add(piece))
    tr = run_scene(scene)
    gain, work = energy_balance(scene, tr, tr.quaternions())
    joined = np.concatenate([p["torque_work"] for p in kept])
    assert np.allclose(joined, work, rtol=1e-12, atol=1e-15 * abs(work).max())
    assert (np.concatenate([p["energy_gain"] for p in kept]) == gain).all()
    stream_scene(scene.replace({"output.data": []}), tmp_path)  # the figure draws from it
    assert (tmp_path / f"{scene.name}.png").stat().st_size > 0


def test_a_run_with_its_summary_off_measures_nothing_but_still_says_incomplete(
    tmp_path, monkeypatch
):
    """``output.summary = false``: the run pays for no summary (RunSummary never built;
    its exact reference at every sample is the streamed run's largest cost), writes no
    summary file, and the report still carries the INCOMPLETE line of a stopped path
    (what ``ga-rotors run`` prints and turns into exit status 3)."""
    import ga_rotors.scene.summary as summary

    monkeypatch.setattr(summary, "RunSummary", lambda *a, **k: pytest.fail("measured"))
    scene = load_scene("spinning_disk").replace(
        {"output.data": ["csv"], "output.summary": False, "time.duration": 0.5}
    )
    files, rep = stream_scene(scene, tmp_path / "ok", chunk_steps=128)
    assert [p.name for p in files] == [
        "spinning_disk.csv", "spinning_disk.png", "spinning_disk.scene.toml"
    ]  # fmt: skip
    assert rep.lines == [] and rep.values == {}
    stopped = scene.replace({"initial.orientation.euler": [0.0, 0.0, 0.0]})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, rep = stream_scene(stopped, tmp_path / "stopped", chunk_steps=128)
    assert rep.values == {"incomplete": 1.0}
    assert rep.lines[0].startswith("INCOMPLETE: the run stopped before t = 0.5 s (euler at")


def test_csv_rows_of_mixed_columns_are_printfs_17g():
    """Rows of several columns, each value as %.17g between commas: every magnitude and
    sign next to every other (the text of one value is stored in 8-byte words that may
    run past its end, into where the next one goes), and a column that stopped early."""
    rng = np.random.default_rng(7)
    n, m = 3000, 9
    scale = 10.0 ** rng.integers(-8, 20, (n, m))
    block = rng.standard_normal((n, m)) * scale
    block[rng.random((n, m)) < 0.05] = 0.0
    block[::97, 3] = np.nan
    block[::89, 5] = -np.inf
    block[:, 6] = np.round(block[:, 6], 2)  # trailing zeros to drop
    block[:, 7] = rng.integers(-(10**6), 10**6, n)  # integers
    lengths = np.full(m, n)
    lengths[8] = n // 3
    expected = "".join(
        ",".join(f"{v:.17g}" if r < lengths[j] else "" for j, v in enumerate(row)) + "\n"
        for r, row in enumerate(block.tolist())
    ).encode()
    assert format_rows(block, lengths) == expected
    out = np.empty(n * (m * 26 + 1), dtype=np.uint8)
    assert bytes(format_rows(block, lengths, out=out)) == expected


@pytest.mark.parametrize(
    "value", [-1.2345678901234567e-100, -0.00012345678901234567, -1234567.8901234567]
)
def test_csv_text_stays_inside_its_buffer(value):
    """Values of the longest texts in every cell: nothing is stored past the buffer a
    block of rows may take (MAX_CHARS per value, one newline per row)."""
    from ga_rotors.results.decimal import MAX_CHARS

    n, m = 5, 4
    size = n * (m * MAX_CHARS + 1)
    memory = np.full(size + 64, 7, dtype=np.uint8)
    text = format_rows(np.full((n, m), value), out=memory[:size])
    assert bytes(text) == ((",".join([f"{value:.17g}"] * m) + "\n") * n).encode()
    assert (memory[size:] == 7).all()


def _ragged(n=1001):
    from ga_rotors.trajectory import Trajectory

    rng = np.random.default_rng(3)
    return Trajectory(
        {"t": np.arange(n) * 0.1, "w": rng.standard_normal((n, 3)), "q": rng.random((n // 3, 4))}
    )


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("block_rows", [1, 7, 64, 5000])
def test_csv_streamed_by_one_or_two_threads_is_the_text_written_whole(
    tmp_path, threads, block_rows
):
    """Pieces of rows (a column stopped in the middle of one), blocks formatted by one
    thread or split with a helper: the bytes of write_csv."""
    from ga_rotors.results import write_csv
    from ga_rotors.results.streams import CsvStream

    tr = _ragged()
    out = CsvStream(tmp_path / "run.csv", threads=threads, block_rows=block_rows)
    for lo, hi in [(0, 1), (1, 300), (300, 300), (300, 333), (333, 334), (334, 1001)]:
        out.append(_rows(tr, lo, hi))
    out.close({})
    assert (tmp_path / "run.csv").read_text() == write_csv(tr)


def _rows(tr, lo, hi):
    from ga_rotors.trajectory import Trajectory

    return Trajectory({n: tr[n][lo:hi] for n in tr.names})


def test_a_failure_in_the_csv_helper_is_raised_after_both_threads_stop(tmp_path, monkeypatch):
    from ga_rotors.results import streams

    real, calls = streams._csv_text, []

    def failing(piece, start, stop, buffer):
        calls.append(start)
        if start > 0:  # the helper's half of the first pair
            raise OSError("injected")
        return real(piece, start, stop, buffer)

    monkeypatch.setattr(streams, "_csv_text", failing)
    out = streams.CsvStream(tmp_path / "run.csv", threads=2, block_rows=100)
    with pytest.raises(OSError, match="injected"):
        out.append(_ragged())
    assert len(calls) == 2 and min(calls) == 0  # both halves of the first pair, no more
    out.abort()
    assert out._helper is None


def test_the_figure_is_drawn_while_the_summary_catches_up(tmp_path, monkeypatch):
    """The summary may lag behind the files by SUMMARY_LAG pieces: the figure is drawn
    while it measures the last ones (here the first piece's measuring waits until the
    figure has been drawn: without the lag the run would wait for it)."""
    import threading

    from ga_rotors.scene import figures, output
    from ga_rotors.scene.budget import SUMMARY_LAG

    drawn, render = threading.Event(), figures.render
    measure, waited = output._Sink.measure, []

    def slow_measure(self, piece):
        if not waited:
            waited.append(drawn.wait(60))  # True: the figure was drawn meanwhile
        return measure(self, piece)

    def spy_render(*args, **kwargs):
        out = render(*args, **kwargs)
        drawn.set()
        return out

    monkeypatch.setattr(output._Sink, "measure", slow_measure)
    monkeypatch.setattr(figures, "render", spy_render)
    scene = load_scene("heavy_top").replace({"time.duration": 0.5, "output.data": ["csv"]})
    pieces = -(-scene.steps // 1000)
    assert 1 < pieces <= SUMMARY_LAG
    files, rep = stream_scene(scene, tmp_path / "o", chunk_steps=1000)
    assert waited == [True] and rep.values["drift_total_energy"] < 1e-9
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == sorted(p.name for p in files)


def test_a_failure_in_the_summary_stops_the_run_and_leaves_nothing(tmp_path, monkeypatch):
    import threading

    from ga_rotors.scene import output

    measure, calls = output._Sink.measure, []

    def failing(self, piece):
        calls.append(len(piece))
        if len(calls) == 2:
            raise ValueError("injected")
        return measure(self, piece)

    monkeypatch.setattr(output._Sink, "measure", failing)
    before = threading.active_count()
    scene = load_scene("heavy_top").replace({"time.duration": 2.0, "output.data": ["csv"]})
    with pytest.raises(ValueError, match="injected"):
        stream_scene(scene, tmp_path / "o", chunk_steps=1000)
    assert not (tmp_path / "o").exists() and threading.active_count() == before


@pytest.mark.parametrize("writeback", [True, False], ids=["linux", "elsewhere"])
def test_the_data_files_are_finished_and_their_writeback_started_while_the_figure_is_drawn(
    tmp_path, monkeypatch, writeback
):
    """Each data file written through the page cache is finished, then its writeback
    started (the rename over the previous run's file would wait for it, ext4's
    auto_da_alloc), on the files' thread while the figure is drawn (here the figure waits
    for it); where the call is missing the files are the same and nothing is said. The
    CSV and the NPZ, written straight to the disk where the file system allows it, have
    none."""
    import threading

    from _direct_io import direct_writes_work_in

    from ga_rotors import files as _files
    from ga_rotors.scene import figures
    from ga_rotors.scene.figures import DIGEST_PREFIX

    written = ["heavy_top.nc"]  # not the store (.zarr)
    if not direct_writes_work_in(tmp_path):
        written[:0] = ["heavy_top.csv", "heavy_top.npz"]
    started, start, render = [], _files.start_writeback, figures.render
    all_started, waited = threading.Event(), []

    def spy(path, offset, length):
        started.append((path.name, path.read_bytes(), threading.current_thread().name))
        if len(started) % len(written) == 0:
            all_started.set()
        return start(path, offset, length)

    def slow_render(*args, **kwargs):
        waited.append(all_started.wait(60))
        all_started.clear()
        return render(*args, **kwargs)

    monkeypatch.setattr(_files, "start_writeback", spy)
    monkeypatch.setattr(figures, "render", slow_render)
    if not writeback:
        monkeypatch.setattr(_files, "_sync_file_range", lambda: None)
    scene = load_scene("heavy_top").replace({"time.duration": 0.5, "output.data": ALL_FORMATS})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for _ in range(2):  # the second run's files replace the first's
            stream_scene(scene, tmp_path / "o", chunk_steps=1000)
    assert waited == [True, True]
    assert [name for name, _, _ in started] == written * 2  # one slice each: small files
    assert all(thread.startswith("ga_rotors-writer") for _, _, thread in started)
    for name, data, _ in started[len(written) :]:  # complete when started: the files moved in
        assert data == (tmp_path / "o" / name).read_bytes()
    monkeypatch.setattr(figures, "render", render)
    tr = run_scene(scene)
    write_outputs(scene, tr, tmp_path / "whole", str(report(scene, tr)))
    _compare_files(scene, tmp_path / "o", tmp_path / "whole")
    png = [(tmp_path / k / "heavy_top.png").read_bytes() for k in ("o", "whole")]
    digest = [p[p.index(DIGEST_PREFIX.encode()) :][:60] for p in png]
    assert digest[0] == digest[1]


def test_a_failure_finishing_the_data_files_stops_the_run_and_leaves_the_previous(
    tmp_path, monkeypatch
):
    import threading

    from ga_rotors.errors import InputError
    from ga_rotors.results import streams

    scene = load_scene("heavy_top").replace({"time.duration": 0.5, "output.data": ["csv"]})
    stream_scene(scene, tmp_path / "o", chunk_steps=1000)
    before = {p.name: p.read_bytes() for p in (tmp_path / "o").iterdir()}

    close = streams.CsvStream.close

    def failing(self, meta):
        close(self, meta)
        raise OSError(28, "No space left on device (injected)")

    monkeypatch.setattr(streams.CsvStream, "close", failing)
    threads = threading.active_count()
    with pytest.raises(InputError, match=r"^--out: cannot write .*No space left on device"):
        stream_scene(scene.replace({"time.duration": 0.6}), tmp_path / "o", chunk_steps=1000)
    assert {p.name: p.read_bytes() for p in (tmp_path / "o").iterdir()} == before
    assert threading.active_count() == threads


def test_the_writeback_goes_a_slice_at_a_time_until_the_run_is_done(tmp_path, monkeypatch):
    """The writeback of a finished file is asked for a slice at a time, and no more once
    the run has nothing else to do (the call can wait on a slow disk's queue). netCDF:
    written by its library, through the page cache."""
    import threading

    from ga_rotors import files as _files
    from ga_rotors.scene import output

    scene = load_scene("heavy_top").replace({"time.duration": 0.5, "output.data": ["netcdf"]})
    tr = run_scene(scene)
    monkeypatch.setattr(output, "WRITEBACK_SLICE", 4096)
    for done_after in (None, 3, 0):  # never set, set while the third slice is asked, set
        asked, done = [], threading.Event()

        def spy(path, start, length, asked=asked, done=done, done_after=done_after):
            asked.append((start, length))
            if len(asked) == done_after:
                done.set()

        monkeypatch.setattr(_files, "start_writeback", spy)
        if done_after == 0:
            done.set()
        sink = output._Sink(scene, tmp_path, False)
        sink.meta = tr.meta  # as the run sets it before the first piece
        sink.write(tr)
        sink.close(done)
        size = (tmp_path / "heavy_top.nc").stat().st_size
        slices = [(start, 4096) for start in range(0, size, 4096)]
        assert len(slices) > 3 and asked == slices[:done_after], done_after
