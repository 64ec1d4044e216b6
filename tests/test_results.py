"""Results formats: Dataset with units and provenance, netCDF/zarr round trips, CSV."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

from ga_rotors import optional
from ga_rotors.errors import InputError
from ga_rotors.optional import MissingExtraError
from ga_rotors.scene import load_scene, run_scene
from ga_rotors.trajectory import Trajectory

xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")
pytest.importorskip("zarr")

from ga_rotors import results  # noqa: E402


@pytest.fixture(scope="module")
def heavy():
    scene = load_scene("heavy_top").replace({"time.duration": 0.05})
    return scene, run_scene(scene)


def ragged():
    """An Euler-angle path that stopped after 3 of 5 samples."""
    t = np.linspace(0.0, 1.0, 5)
    return Trajectory(
        {"t": t, "w": np.arange(15.0).reshape(5, 3) / 7, "euler": np.ones((3, 3)) / 3},
        {"w": ("1", "2", "3"), "euler": ("psi", "theta", "phi")},
        {"integrator": "rk4", "step": 0.25, "paths": {"euler": {"complete": False}}},
    )


def test_every_variable_has_units_and_a_description_and_the_run_settings_are_attributes(heavy):
    scene, tr = heavy
    ds = results.to_dataset(tr, scene)
    assert set(ds.data_vars) | {"t"} == set(tr.names)
    for name in tr.names:
        assert ds[name].attrs["units"] and ds[name].attrs["description"], name
    assert ds["q"].dims == ("time", "quaternion_component")
    assert ds["quaternion_component"].values.tolist() == ["w", "x", "y", "z"]
    assert np.array_equal(ds["q"].values, tr.q) and np.array_equal(ds["t"].values, tr.t)
    a = ds.attrs
    assert a["integrator"] == "rk4" and a["step"] == scene.step and a["torques"] == "gravity"
    assert a["sample_every"] == scene.sample_every
    assert a["scene_toml"] == scene.to_toml()
    assert type(scene).from_toml(a["scene_toml"]).data == scene.data
    assert a["exact_solution"] == "heavy_top" and 0 < a["exact_error_bound"] < 1e-10
    assert a["version_numpy"] == np.__version__


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_read_back_is_identical_to_what_was_written(heavy, tmp_path, suffix):
    scene, tr = heavy
    ds = results.to_dataset(tr, scene)
    path = results.write(ds, tmp_path / f"run{suffix}")
    xr.testing.assert_identical(results.read(path), ds)
    # writing a trajectory directly is the same as converting it first
    again = results.write(tr, tmp_path / f"again{suffix}", scene=scene)
    back = results.read(again)
    xr.testing.assert_identical(back, ds)


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_a_path_that_stopped_early_is_padded_and_says_how_many_rows_are_real(tmp_path, suffix):
    ds = results.to_dataset(ragged())
    assert ds["euler"].attrs["valid_samples"] == 3
    assert np.isnan(ds["euler"].values[3:]).all() and np.isfinite(ds["euler"].values[:3]).all()
    xr.testing.assert_identical(results.read(results.write(ds, tmp_path / f"r{suffix}")), ds)


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_a_failed_write_leaves_the_previous_results(tmp_path, suffix, monkeypatch):
    path = results.write(ragged(), tmp_path / f"run{suffix}")
    before = results.read(path)

    def broken(self, *args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf" if suffix == ".nc" else "to_zarr", broken)
    with pytest.raises(OSError, match="disk full"):
        results.write(results.to_dataset(Trajectory({"t": np.zeros(1)})), path)
    monkeypatch.undo()
    xr.testing.assert_identical(results.read(path), before)
    assert [p.name for p in tmp_path.iterdir()] == [path.name]  # no staging left behind


def test_bad_paths_and_files_are_one_line_errors(tmp_path):
    with pytest.raises(InputError, match=r"run\.csv: expected a \.nc"):
        results.write(ragged(), tmp_path / "run.csv")
    with pytest.raises(InputError, match="no such file"):
        results.read(tmp_path / "missing.nc")
    (tmp_path / "junk.nc").write_text("not netcdf")
    with pytest.raises(InputError, match=r"junk\.nc: not a readable netcdf results file"):
        results.read(tmp_path / "junk.nc")


def test_a_missing_extra_names_the_install_command(monkeypatch):
    real = optional.importlib.import_module

    def fake(name, *args):
        if name == "xarray":
            raise ModuleNotFoundError("No module named 'xarray'", name="xarray")
        return real(name, *args)

    monkeypatch.setattr(optional.importlib, "import_module", fake)
    with pytest.raises(MissingExtraError, match=r'pip install "ga-rotors\[results\]"'):
        results.to_dataset(ragged())


def test_csv_has_units_in_headers_round_trips_exactly_and_leaves_missing_cells_empty(tmp_path):
    tr = ragged()
    # blocks of 2 rows: the ragged tail (rows 3, 4) straddles a block boundary
    path = results.write_csv(tr, tmp_path / "run.csv", block_rows=2)
    rows = list(csv.reader(io.StringIO(path.read_text())))
    assert rows[0] == [
        "t [s]", "w_1 [rad/s]", "w_2 [rad/s]", "w_3 [rad/s]",
        "euler_psi [rad]", "euler_theta [rad]", "euler_phi [rad]",
    ]  # fmt: skip
    data = rows[1:]
    assert len(data) == 5
    assert np.array_equal(np.array([[float(x) for x in r[:4]] for r in data]),
                          np.column_stack([tr.t, tr.w]))  # fmt: skip
    assert [float(x) for x in data[2][4:]] == tr.euler[2].tolist()
    assert data[3][4:] == ["", "", ""] and "nan" not in path.read_text().lower()
    assert results.write_csv(tr, block_rows=3) == path.read_text()


def test_csv_of_a_scene_run_matches_its_arrays(heavy):
    _, tr = heavy
    text = results.write_csv(tr, block_rows=7)
    table = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)
    cols = tr.columns()
    assert table.shape == (len(tr), len(cols))
    for j, (_, name, comp) in enumerate(cols):
        a = tr[name] if comp is None else tr[name][:, comp]
        assert np.array_equal(table[:, j], a), name


def test_a_scene_declaring_netcdf_data_writes_a_readable_dataset(tmp_path):
    from ga_rotors.scene import write_outputs

    scene = load_scene("heavy_top").replace(
        {"time.duration": 0.01, "output.data": ["netcdf", "csv"], "output.plots": []}
    )
    tr = run_scene(scene)
    written = write_outputs(scene, tr, tmp_path / "run")
    assert [p.name for p in written] == ["heavy_top.nc", "heavy_top.csv", "heavy_top.scene.toml"]
    back = results.read(tmp_path / "run" / "heavy_top.nc")
    xr.testing.assert_identical(back, results.to_dataset(tr, scene))  # with the bound
    assert back.attrs["scene_toml"] == scene.to_toml()  # the run records its scene
    assert back.attrs["exact_solution"] == "heavy_top"
    assert (tmp_path / "run" / "heavy_top.csv").read_text().startswith("t [s],w_1 [rad/s]")


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_a_file_larger_than_the_memory_budget_is_refused_before_loading_and_read_lazily(
    heavy, tmp_path, suffix
):
    # a streamed run's file can hold more than memory: read() says so in one line instead
    # of filling it, and lazy=True reads values as they are used
    scene, tr = heavy
    path = results.write(tr, tmp_path / f"run{suffix}", scene)
    whole = results.read(path)
    small = whole.nbytes / 2**30 / 2
    with pytest.raises(InputError, match=r"GiB of data, more than max_memory_gib = .*lazy=True"):
        results.read(path, max_memory_gib=small)
    with results.read(path, lazy=True, max_memory_gib=small) as lazy:
        assert not lazy["w"].variable._in_memory  # nothing loaded yet
        xr.testing.assert_identical(lazy.load(), whole)
    assert results.read(path, max_memory_gib=2 * small).identical(whole)


@pytest.mark.parametrize("bad", [0, -1.0, float("nan"), True, "2"])
def test_a_bad_memory_budget_is_one_line_naming_it(tmp_path, bad):
    with pytest.raises(InputError, match="max_memory_gib: expected a positive number"):
        results.read(tmp_path / "missing.nc", max_memory_gib=bad)
