"""Bad input to a sweep is one line: a sweep's budget (an absurd sweep file is refused
before anything is written, and the three options that raise the budget do), and what a
probe of bad sweep files and arguments found (an empty list of times, a seed that is a
boolean, the message of a negative standard deviation, a scheduler address without a
port)."""

from __future__ import annotations

import os

import pytest

pytest.importorskip("zarr")
dask = pytest.importorskip("dask")

from ga_rotors.cli import main  # noqa: E402
from ga_rotors.errors import InputError  # noqa: E402
from ga_rotors.scene.budget import Budget  # noqa: E402
from ga_rotors.sweep import load_sweep, open_sweep, run_sweep  # noqa: E402
from ga_rotors.sweep.budget import BLOCK_BYTES, DEFAULT, check, estimate  # noqa: E402

SMALL = """
[sweep]
scene = "spinning_disk"
samples = 6
chunk = 2
seed = 3
times = [0.005, 0.01]

[set]
"time.duration" = 0.01

[[draw]]
key = "body.mass"
normal = [2.0, 0.02]
"""


def _write(tmp_path, text, name="s.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _one_line_error(capsys, argv) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    return err


def test_a_trillion_samples_is_one_line_before_anything_is_written(tmp_path, capsys):
    # found by a probe: it died allocating 466 GiB for the chunks' flags
    path = _write(tmp_path, SMALL.replace("samples = 6", "samples = 1000000000000"))
    out = tmp_path / "s.zarr"
    err = _one_line_error(capsys, ["sweep", str(path), "--out", str(out), "--no-progress"])
    assert "s.toml: sweep.samples: 1e+12 samples need" in err
    assert "--max-steps N --max-disk GIB" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_a_grid_too_large_for_int64_is_counted_exactly_and_refused():
    # numpy's product of the grid's lengths wrapped around past 2**63
    keys = "\n".join(
        f'"initial.angular_velocity.body[{i}]" = [{", ".join(["1.0"] * 2000)}]' for i in range(3)
    )
    text = SMALL.replace("samples = 6", "samples = 2000000") + "[grid]\n" + keys + "\n"
    text += '"body.moments[0]" = [' + ", ".join(["1.0"] * 2000) + "]\n"
    text = text.replace('scene = "spinning_disk"', 'scene = "intermediate_axis_flip"')
    sweep = load_sweep(text)
    assert sweep.size == 2000**4 * 2_000_000 > 2**63
    with pytest.raises(InputError, match=r"sweep\.samples: 3\.2e\+19 samples need"):
        check(sweep)


def test_tiny_chunks_are_refused_for_their_files_not_their_values(tmp_path, capsys):
    # 10⁷ samples of one time: 360 MB of values, but a chunk of one sample is five files
    # of at least a block each
    text = SMALL.replace("samples = 6", "samples = 10000000").replace("chunk = 2", "chunk = 1")
    text = text.replace("times = [0.005, 0.01]", "times = [0.01]")
    sweep = load_sweep(text)
    assert sweep.size * 9 * 8 < DEFAULT.max_disk_gib * 2**30 < estimate(sweep).disk
    err = _one_line_error(
        capsys, ["sweep", str(_write(tmp_path, text)), "--out", str(tmp_path / "s.zarr")]
    )
    assert "GiB of files in 1e+07 chunks" in err and "at least 4 KiB" in err


def test_one_huge_chunk_is_refused_for_its_memory_naming_the_chunk(tmp_path, capsys):
    text = SMALL.replace("samples = 6", "samples = 100000000").replace(
        "chunk = 2", "chunk = 100000000"
    )
    err = _one_line_error(
        capsys,
        [
            "sweep",
            str(_write(tmp_path, text)),
            "--out",
            str(tmp_path / "s.zarr"),
            "--max-disk",
            "1e4",
        ],
    )
    assert "sweep.chunk: 1e+08 samples a chunk need about" in err
    assert "ga-rotors sweep --max-memory GIB" in err


@pytest.mark.parametrize(
    ("option", "value", "says"),
    [
        ("--max-steps", "50", "60 integration steps (budget 50)"),
        ("--max-disk", "1e-5", "GiB of files in 3 chunks (budget 1e-05 GiB"),
        ("--max-memory", "1e-6", "GiB of memory on the threads integrating at once (budget 1e-06"),
    ],
)
def test_each_budget_option_refuses_below_and_runs_at_the_sweeps_estimate(
    tmp_path, capsys, option, value, says
):
    path = _write(tmp_path, SMALL)
    out = tmp_path / "s.zarr"
    err = _one_line_error(capsys, ["sweep", str(path), "--out", str(out), option, value])
    assert says in err and not out.exists()
    e = estimate(load_sweep(path), threads=1)
    enough = {
        "--max-steps": e.steps,
        "--max-disk": e.disk / 2**30,
        "--max-memory": e.bytes / 2**30,
    }[option]
    argv = ["sweep", str(path), "--out", str(out), "--here", option, repr(float(enough))]
    assert main(argv) == 0
    assert open_sweep(out).sizes["sample"] == 6


def test_a_nan_budget_is_one_line(tmp_path, capsys):
    argv = ["sweep", str(_write(tmp_path, SMALL)), "--out", str(tmp_path / "s.zarr")]
    err = _one_line_error(capsys, [*argv, "--max-disk", "nan"])
    assert "--max-steps, --max-memory, --max-disk: expected numbers" in err


def test_the_estimated_disk_bounds_the_store_written(tmp_path):
    # chunks large enough that a file is more than a block: the estimate is the store's
    # size up to the last chunk's slack and the metadata it leaves out
    text = SMALL.replace("samples = 6", "samples = 3000").replace("chunk = 2", "chunk = 1024")
    store = run_sweep(text, tmp_path / "s.zarr", client="sync")
    data = 0
    for folder, _, files in os.walk(store):
        for f in files:
            if not f.startswith(".") and f != "zarr.json":
                size = os.stat(os.path.join(folder, f)).st_size  # in whole blocks, as
                data += -(-size // BLOCK_BYTES) * BLOCK_BYTES  # most file systems store it
    e = estimate(load_sweep(text))
    assert 0.5 * e.disk <= data <= e.disk + 16 * BLOCK_BYTES, (data, e.disk)


def test_the_python_budget_argument_refuses_too(tmp_path):
    with pytest.raises(InputError, match=r"sweep\.samples: 6 samples need 60 integration steps"):
        run_sweep(SMALL, tmp_path / "s.zarr", client="sync", budget=Budget(max_steps=10))
    assert not (tmp_path / "s.zarr").exists()


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("times = [0.005, 0.01]", "times = []"), r"sweep\.times: expected at least one output"),
        (("normal = [2.0, 0.02]", "uniform = [2.0, 1.0]"), r"expected low ≤ high, got \[2, 1"),
        (("seed = 3", "seed = true"), r"sweep\.seed: expected an integer ≥ 0, got True"),
    ],
)  # fmt: skip
def test_what_a_probe_of_bad_sweep_files_found_is_one_line(change, message):
    with pytest.raises(InputError, match=message):
        load_sweep(SMALL.replace(*change))


def test_a_seed_without_draws_is_still_checked():
    text = SMALL.replace('[[draw]]\nkey = "body.mass"\nnormal = [2.0, 0.02]\n', "")
    assert load_sweep(text).seed is None  # unused: the store says -1, as before
    with pytest.raises(InputError, match=r"sweep\.seed: expected an integer ≥ 0, got 'x'"):
        load_sweep(text.replace("seed = 3", 'seed = "x"'))


@pytest.mark.parametrize("address", ["notanaddress", "foo://127.0.0.1:1"])
def test_a_malformed_scheduler_address_is_one_line_and_writes_nothing(tmp_path, capsys, address):
    pytest.importorskip("distributed")
    out = tmp_path / "s.zarr"
    argv = ["sweep", str(_write(tmp_path, SMALL)), "--out", str(out), "--scheduler", address]
    err = _one_line_error(capsys, argv)
    assert f"--scheduler: {address!r} is not a scheduler address (tcp://host:port)" in err
    assert not out.exists()
    # the failed client is not left as the process's scheduler (later computes hung on it)
    assert dask.config.get("scheduler", None) is None


def test_a_zarr_store_of_something_else_is_not_a_sweep_store(tmp_path, capsys):
    import numpy as np
    import xarray as xr

    foreign = tmp_path / "other.zarr"
    xr.Dataset({"a": ("x", np.arange(3.0))}).to_zarr(foreign, zarr_format=2, consolidated=True)
    with pytest.raises(InputError, match=r"other\.zarr: not a sweep store \(no chunk_done, "):
        open_sweep(foreign)  # was a KeyError from xarray
    argv = ["sweep", str(_write(tmp_path, SMALL)), "--out", str(foreign), "--here"]
    assert "not a sweep store (no chunk_done" in _one_line_error(capsys, argv)
    assert sorted(p.name for p in foreign.iterdir()) == sorted(
        [".zattrs", ".zgroup", ".zmetadata", "a"]
    )


def test_the_one_uniform_that_rounds_to_one_gives_a_finite_normal_draw():
    # k = 2^53 - 1 (once in 2^53 draws): (k + 1/2)·2^-53 rounds to exactly 1 in float64,
    # and the normal quantile of 1 is inf; a normal draw takes the largest float below 1, and
    # a uniform one keeps its high end (the interval is closed)
    import numpy as np

    from ga_rotors.sweep import spec

    k = np.array([[2.0**53 - 1]])
    assert ((k + 0.5) * 2.0**-53)[0, 0] == 1.0
    top = np.uint64(2**64 - 1)  # the 64-bit output all ones: k = x >> 11 = 2^53 - 1
    assert spec._uniform(top) == 1.0
    rows = np.full((2, 1), spec._uniform(top))  # a normal draw, then a uniform one
    spec._from_uniform(np.array([True, False]), np.array([2.0, 1.0]), np.array([0.02, 2.0]), rows)
    normal, uniform = rows[:, 0]
    assert np.isfinite(normal) and normal > 2.0 + 0.02 * 8
    assert uniform == 3.0
