"""Bad input to a sweep is one line: the sweep file's guards (the scene reader's: regular
file, size, nesting), values that overflow or are not numbers, vector keys, budgets that
count chunks and files, long echoes cut; and a fuzz of sweep files."""

from __future__ import annotations

import os
import threading

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

pytest.importorskip("zarr")
pytest.importorskip("xarray")

from ga_rotors.cli import main
from ga_rotors.errors import GaRotorsError, InputError
from ga_rotors.sweep import load_sweep, open_sweep, run_sweep
from ga_rotors.sweep.budget import BLOCK_BYTES, DEFAULT, SweepBudget, check, estimate

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


def _in_time(f, seconds: float = 20.0):
    """f() in a thread: its result, or a failure if it has not returned in time (a hang)."""
    out = []
    thread = threading.Thread(target=lambda: out.append(f()), daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), "it hangs"
    return out[0]


# ---------------------------------------------------------------- the file (issue 30 item 5)


def test_a_sweep_file_linked_to_dev_zero_is_one_line_without_reading(tmp_path, capsys):
    os.symlink("/dev/zero", tmp_path / "s.toml")
    argv = ["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "s.zarr")]
    err = _in_time(lambda: _one_line_error(capsys, argv))
    assert "s.toml: not a regular file (a character device)" in err


def test_a_fifo_for_a_sweep_file_is_one_line_and_does_not_hang(tmp_path, capsys):
    os.mkfifo(tmp_path / "s.toml")
    argv = ["sweep", str(tmp_path / "s.toml"), "--out", str(tmp_path / "s.zarr")]
    err = _in_time(lambda: _one_line_error(capsys, argv))
    assert "s.toml: not a regular file (a FIFO)" in err


def test_a_gigabyte_sweep_file_is_refused_unread(tmp_path, capsys):
    path = tmp_path / "s.toml"
    with open(path, "wb") as f:
        f.truncate(2**30)  # sparse: nothing is written, nothing must be read
    err = _one_line_error(capsys, ["sweep", str(path), "--out", str(tmp_path / "s.zarr")])
    assert "1,073,741,824 bytes; a sweep file is at most 10,000,000" in err


@pytest.mark.parametrize("depth", [40, 3000])
def test_deep_nesting_in_a_sweep_file_is_one_line(tmp_path, capsys, depth):
    text = SMALL + '[grid]\n"body.moments[0]" = ' + "[" * depth + "1.0" + "]" * depth + "\n"
    err = _one_line_error(capsys, ["sweep", str(_write(tmp_path, text)), "--out", "x.zarr"])
    assert err.strip().endswith("s.toml: arrays or tables nested too deeply")


@pytest.mark.parametrize(
    ("table", "says"),
    [
        ("set", "s.toml: set: "),
        ("grid", "'body.x.1' is varied twice (or two keys differ only in punctuation)"),
    ],
)
def test_a_hundred_thousand_keys_are_one_line_in_seconds(tmp_path, capsys, table, says):
    # a 2 MB file: each key was once looked up in a list of all of them (a minute, or
    # three for the grid's names when the last two differ only in punctuation)
    keys = f"[{table}]\n" + "".join(f'"body.k{i}" = [1.0]\n' for i in range(100_000))
    keys += '"body.x_1" = [1.0]\n"body.x.1" = [1.0]\n'
    text = SMALL.replace("[set]\n", keys) if table == "set" else SMALL + keys
    argv = ["sweep", str(_write(tmp_path, text)), "--out", str(tmp_path / "s.zarr")]
    err = _in_time(lambda: _one_line_error(capsys, argv))
    assert says in err


# ---------------------------------------------------------------- values (items 6, 11, 12)


@pytest.mark.parametrize(
    ("value", "says"),
    [
        (
            "1" + "0" * 400,
            "grid.body.moments[0][1]: expected a finite number, got an integer of 401 digits",
        ),
        ("1e400", "grid.body.moments[0][1]: expected a finite number, got inf"),
        ('"900"', "grid.body.moments[0][1]: expected a finite number, got string '900'"),
        ("true", "grid.body.moments[0][1]: expected a finite number, got boolean true"),
        ("9" * 5000, "not valid TOML: Exceeds the limit (4300 digits)"),
    ],
    ids=["10^400", "1e400", "a string", "a boolean", "5000 digits"],
)
def test_a_grid_value_that_is_not_a_float64_is_one_short_line(tmp_path, capsys, value, says):
    text = SMALL + f'[grid]\n"body.moments[0]" = [0.001, {value}]\n'
    err = _one_line_error(capsys, ["sweep", str(_write(tmp_path, text)), "--out", "x.zarr"])
    assert says in err and len(err) < 400


@pytest.mark.parametrize("where", ["draw", "grid"])
def test_a_vector_key_is_one_line_naming_its_components(where):
    # issue 30 item 6: a [[draw]] on a vector was numpy's "cannot reshape" traceback
    key = "initial.angular_velocity.body"
    text = SMALL.replace('"spinning_disk"', '"intermediate_axis_flip"')
    text = (
        text.replace('key = "body.mass"', f'key = "{key}"')
        if where == "draw"
        else (text + f'[grid]\n"{key}" = [1.0, 2.0]\n')
    )
    with pytest.raises(InputError) as refused:
        load_sweep(text)
    message = str(refused.value)
    assert f"'{key}' is 3 numbers; vary one number at a time" in message
    assert f"{key}[0], {key}[1]" in message and "\n" not in message
    # a scene whose rates are given another way: the scene's own refusal, one line
    with pytest.raises(InputError, match="the scene refuses the first grid point") as refused:
        load_sweep(text.replace('"intermediate_axis_flip"', '"spinning_disk"'))
    assert "\n" not in str(refused.value)


def test_an_error_about_a_hundred_thousand_sweep_times_is_one_short_line(tmp_path, capsys):
    times = [0.005 + 1e-7] + [0.01] * 99_999
    text = SMALL.replace("times = [0.005, 0.01]", f"times = {times}")
    err = _one_line_error(capsys, ["sweep", str(_write(tmp_path, text)), "--out", "x.zarr"])
    assert "sweep.times[0]: 0.0050001 s is not a whole number of steps" in err and len(err) < 300
    times = [0.005] * 100_000
    text = SMALL.replace("times = [0.005, 0.01]", f"times = {times}")
    err = _one_line_error(capsys, ["sweep", str(_write(tmp_path, text)), "--out", "x.zarr"])
    assert "sweep.times[1]: expected increasing times, got 0.005 s after 0.005 s" in err


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("samples = 6", "sampels = 6"), r"sweep\.sampels: unknown key \(did you mean 'samples'"),
        (('key = "body.mass"', 'key = "integrator.step"'), r"draw\[0\]\.key: .*cannot vary"),
        (("seed = 3", ""), r"sweep\.seed: missing; random draws need a seed"),
        (
            ("seed = 3", "seed = true"),
            r"sweep\.seed: expected an integer ≥ 0 and ≤ 3\.4e\+38, got True",
        ),
        (("seed = 3", f"seed = {2**200}"), r"sweep\.seed: expected .*, got a larger one"),
        (("normal = [2.0, 0.02]", "normal = [2.0, -0.1]"), r"draw\[0\]\.normal: expected std ≥ 0"),
        (
            ("normal = [2.0, 0.02]", "normal = [2.0, 1e307]"),
            r"draw\[0\]\.normal: the draws would overflow",
        ),
        (("normal = [2.0, 0.02]", "uniform = [2.0, 1.0]"), r"expected low ≤ high, got \[2, 1"),
        (("normal = [2.0, 0.02]", "poisson = [1.0]"), r"draw\[0\]\.poisson: unknown key"),
        (
            ("normal = [2.0, 0.02]", "normal = [2.0]"),
            r"draw\[0\]\.normal: expected an array of 2 numbers",
        ),
        (('"spinning_disk"', '"no_such_scene"'), r"sweep\.scene: .*no bundled scene"),
        (("chunk = 2", "chunk = 0"), r"sweep\.chunk: expected an integer ≥ 1"),
        (("times = [0.005, 0.01]", "times = []"), r"sweep\.times: expected at least one output"),
        (
            ("times = [0.005, 0.01]", "times = [0.0, 0.01]"),
            r"sweep\.times\[0\]: 0\.0 s is outside the run",
        ),
        (
            ("times = [0.005, 0.01]", "times = [0.02]"),
            r"sweep\.times\[0\]: 0\.02 s is outside the run",
        ),
        (('[[draw]]\nkey = "body.mass"\nnormal = [2.0, 0.02]\n', ""), r"grid: nothing varies"),
        (
            ("normal = [2.0, 0.02]\n", 'normal = [2.0, 0.02]\n[grid]\n"body.mass" = [1.0]\n'),
            r"'body\.mass' is varied twice",
        ),
    ],
)
def test_a_bad_sweep_file_is_one_line_naming_the_key(change, message):
    with pytest.raises(InputError, match=message) as refused:
        load_sweep(SMALL.replace(*change))
    assert "\n" not in str(refused.value)


def test_samples_without_draws_are_refused_as_the_same_run():
    text = '[sweep]\nscene = "spinning_disk"\nsamples = 3\n[grid]\n"body.mass" = [1.0, 2.0]\n'
    with pytest.raises(InputError, match=r"sweep\.samples: 3 samples of each grid point"):
        load_sweep(text)


# ---------------------------------------------------------------- budgets (item 8)


def test_a_hundred_thousand_samples_in_chunks_of_two_are_refused_before_anything(tmp_path, capsys):
    text = SMALL.replace("samples = 6", "samples = 100000")
    path = _write(tmp_path, text)
    err = _one_line_error(capsys, ["sweep", str(path), "--out", str(tmp_path / "s.zarr")])
    assert "sweep.chunk: 1e+05 samples in chunks of 2 make 50,000 chunks and" in err
    assert "ga-rotors sweep --max-files N" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]
    e = estimate(load_sweep(path))
    assert e.chunks == 50_000 and e.files > DEFAULT.max_files


def test_a_trillion_samples_is_one_line_before_anything_is_written(tmp_path, capsys):
    path = _write(tmp_path, SMALL.replace("samples = 6", "samples = 1000000000000"))
    err = _one_line_error(capsys, ["sweep", str(path), "--out", str(tmp_path / "s.zarr")])
    assert "s.toml: sweep.samples: 1e+12 samples need" in err
    assert "--max-steps N --max-disk GIB" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_a_grid_too_large_for_int64_is_counted_exactly_and_refused():
    keys = "\n".join(
        f'"initial.angular_velocity.body[{i}]" = [{", ".join(["1.0"] * 2000)}]' for i in range(3)
    )
    text = SMALL.replace("samples = 6", "samples = 2000000") + "[grid]\n" + keys + "\n"
    text += '"body.a" = [' + ", ".join(["0.1"] * 2000) + "]\n"
    text = text.replace('scene = "spinning_disk"', 'scene = "intermediate_axis_flip"')
    sweep = load_sweep(text)
    assert sweep.size == 2000**4 * 2_000_000 > 2**63
    with pytest.raises(InputError, match=r"sweep\.samples: 3\.2e\+19 samples need"):
        check(sweep)


def test_one_huge_chunk_is_refused_for_its_memory_naming_the_chunk(tmp_path, capsys):
    text = SMALL.replace("samples = 6", "samples = 100000000").replace(
        "chunk = 2", "chunk = 100000000"
    )
    argv = ["sweep", str(_write(tmp_path, text)), "--out", str(tmp_path / "s.zarr")]
    err = _one_line_error(capsys, [*argv, "--max-disk", "1e4"])
    assert "sweep.chunk: 1e+08 samples a chunk need about" in err
    assert "ga-rotors sweep --max-memory GIB" in err


@pytest.mark.parametrize(
    ("option", "value", "says"),
    [
        ("--max-steps", "50", "70 integration steps (budget 50)"),
        ("--max-disk", "1e-5", "GiB of files (budget 1e-05 GiB"),
        ("--max-memory", "1e-6", "GiB of memory on the threads integrating at once (budget 1e-06"),
        ("--max-files", "10", "make 3 chunks and 43 files (budget 10 files)"),
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
        "--max-files": e.files,
    }[option]
    argv = ["sweep", str(path), "--out", str(out), "--here", option, repr(float(enough))]
    assert main(argv) == 0
    assert open_sweep(out).sizes["sample"] == 6


@pytest.mark.parametrize("option", ["--max-disk", "--max-files"])
def test_a_nan_budget_is_one_line(tmp_path, capsys, option):
    argv = ["sweep", str(_write(tmp_path, SMALL)), "--out", str(tmp_path / "s.zarr")]
    err = _one_line_error(capsys, [*argv, option, "nan"])
    assert "expected" in err and ("--max-disk" in err or "--max-files" in err)


def test_the_estimated_disk_and_files_bound_the_store_written(tmp_path):
    text = SMALL.replace("samples = 6", "samples = 3000").replace("chunk = 2", "chunk = 1024")
    store = run_sweep(text, tmp_path / "s.zarr", client="sync")
    data, files = 0, 0
    for folder, _, names in os.walk(store):
        for f in names:
            files += 1
            if not f.startswith(".") and f != "zarr.json":
                size = os.stat(os.path.join(folder, f)).st_size  # in whole blocks, as
                data += -(-size // BLOCK_BYTES) * BLOCK_BYTES  # most file systems store it
    e = estimate(load_sweep(text))
    assert 0.5 * e.disk <= data <= e.disk + 16 * BLOCK_BYTES, (data, e.disk)
    assert 0.5 * e.files <= files <= e.files, (files, e.files)


def test_the_python_budget_argument_refuses_too(tmp_path):
    with pytest.raises(InputError, match=r"sweep\.samples: 6 samples need 70 integration steps"):
        run_sweep(SMALL, tmp_path / "s.zarr", client="sync", budget=SweepBudget(max_steps=10))
    assert not (tmp_path / "s.zarr").exists()


# ---------------------------------------------------------------- stores and addresses


@pytest.mark.parametrize("address", ["notanaddress", "foo://127.0.0.1:1"])
def test_a_malformed_scheduler_address_is_one_line_and_writes_nothing(tmp_path, capsys, address):
    dask = pytest.importorskip("dask")
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
        open_sweep(foreign)
    argv = ["sweep", str(_write(tmp_path, SMALL)), "--out", str(foreign), "--here"]
    assert "not a sweep store (no chunk_done" in _one_line_error(capsys, argv)
    assert sorted(p.name for p in foreign.iterdir()) == [".zattrs", ".zgroup", ".zmetadata", "a"]


# ---------------------------------------------------------------- fuzz


_VALUES = st.one_of(
    st.integers(-(10**400), 10**400),
    st.floats(allow_nan=True),
    st.booleans(),
    st.text(max_size=8),
    st.lists(st.floats(-10, 10), max_size=4),
    st.just([[[1.0]]]),
    st.just({"a": 1}),
)
_KEYS = st.sampled_from(
    [
        "body.mass",
        "body.moments[0]",
        "body.moments",
        "initial.angular_velocity.body[1]",
        "initial.angular_velocity.body",
        "time.duration",
        "effects[0].pivot_to_com[2]",
        "body.nope",
        "x\x1b]0;title\x07",
        "",
    ]
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    sweep=st.dictionaries(
        st.sampled_from(["samples", "seed", "chunk", "times", "scene", "other"]),
        _VALUES,
        max_size=5,
    ),
    grid=st.dictionaries(_KEYS, st.one_of(_VALUES, st.lists(_VALUES, max_size=3)), max_size=2),
    draws=st.lists(
        st.dictionaries(
            st.sampled_from(["key", "normal", "uniform", "x"]),
            st.one_of(_KEYS, _VALUES),
            max_size=3,
        ),
        max_size=2,
    ),
)
def test_any_sweep_file_loads_or_is_one_line(sweep, grid, draws):
    """Sweep files made of valid and invalid parts: load_sweep and the budget either
    accept them or raise one line, without a control character echoed raw."""
    from ga_rotors.scene.toml_io import dumps_toml

    data = {"sweep": {"scene": "heavy_top", **sweep}, "grid": grid, "draw": draws}
    try:
        text = dumps_toml({k: v for k, v in data.items() if v})
    except (TypeError, ValueError, OverflowError):
        return  # not expressible in TOML by the writer: nothing to read
    try:
        check(load_sweep(text))
    except GaRotorsError as exc:
        message = str(exc)
        assert "\n" not in message and "\x1b" not in message and len(message) < 2000, message
