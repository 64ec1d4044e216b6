"""Results formats: CF Datasets (read by cf_xarray and pint-xarray), netCDF/zarr round
trips and chunks, NPZ attributes, CSV that reads back bit for bit with every reader."""

from __future__ import annotations

import importlib.util
import io
import json
import math
import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors import optional
from ga_rotors.errors import InputError
from ga_rotors.optional import MissingExtraError
from ga_rotors.scene import load_scene, run_scene
from ga_rotors.trajectory import Trajectory

xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")
pytest.importorskip("zarr")

from ga_rotors import results  # noqa: E402
from ga_rotors.results import table  # noqa: E402

QUANTITIES = ["energy", "potential_energy", "total_energy", "L", "L_space", "omega_space",
              "angles", "error", "omega_error"]  # fmt: skip


@pytest.fixture(scope="module")
def heavy():
    """The heavy top with every quantity, on both paths, 21 samples."""
    scene = load_scene("heavy_top").replace(
        {"time.duration": 0.01, "output.quantities": QUANTITIES,
         "integrator.paths": ["rotor", "quaternion"]}
    )  # fmt: skip
    return scene, run_scene(scene)


def ragged():
    """An Euler-angle path that stopped after 3 of 5 samples."""
    t = np.linspace(0.0, 1.0, 5)
    return Trajectory(
        {"t": t, "w": np.arange(15.0).reshape(5, 3) / 7, "euler": np.ones((3, 3)) / 3},
        {"w": ("1", "2", "3"), "euler": ("psi", "theta", "phi")},
        {"integrator": "rk4", "step": 0.25, "paths": {"euler": {"complete": False}}},
    )


# ------------------------------------------------------------------------- the Dataset


def test_every_variable_has_units_and_a_long_name_and_the_run_settings_are_attributes(heavy):
    scene, tr = heavy
    ds = results.to_dataset(tr, scene)
    assert set(ds.data_vars) | {"t"} == set(tr.names)
    for name in ds.variables:
        if name in ds.data_vars or name == "time":
            assert ds[name].attrs["units"] and ds[name].attrs["long_name"], name
    assert ds["q"].dims == ("time", "quaternion_component")
    assert ds["quaternion_component"].values.tolist() == ["w", "x", "y", "z"]
    assert np.array_equal(ds["q"].values, tr.q) and np.array_equal(ds["time"].values, tr.t)
    a = ds.attrs
    assert a["Conventions"] == "CF-1.10" and a["title"] == "ga_rotors run of the scene heavy_top"
    assert a["integrator"] == "rk4" and a["step"] == scene.step and a["torques"] == "gravity"
    assert a["sample_every"] == scene.sample_every and a["source"].startswith("ga_rotors: rk4")
    assert a["scene_toml"] == scene.to_toml()
    assert type(scene).from_toml(a["scene_toml"]).data == scene.data
    assert a["exact_solution"] == "heavy_top" and 0 < a["exact_error_bound"] < 1e-10
    assert a["version_numpy"] == np.__version__
    assert a["body_frame"] == scene.body_frame == tr.meta["body_frame"]  # the run names it


def test_cf_xarray_finds_the_time_axis_and_pint_xarray_quantifies_every_variable(heavy):
    pytest.importorskip("cf_xarray")
    pytest.importorskip("pint_xarray")
    import cf_xarray.units  # UDUNITS spellings: its registry must read the units too

    scene, tr = heavy
    ds = results.to_dataset(tr, scene)
    assert ds.cf.axes == {"T": ["time"]}
    assert ds.cf.standard_names == {"time": ["time"]}
    xr.testing.assert_identical(ds.cf["time"], ds["time"])
    for registry in (None, cf_xarray.units.units):  # pint's own, and cf_xarray's UDUNITS one
        quantified = ds.pint.quantify(unit_registry=registry)
        units = quantified["w"].data._REGISTRY
        for name in ds.data_vars:
            assert quantified[name].data.units == units.Unit(ds[name].attrs["units"]), name
        assert quantified["time"].data.units == units.second
        assert quantified["L"].data.units == units.Unit("kg*m**2/s")
        assert quantified["q"].data.units == units.dimensionless


def test_time_is_an_index_in_seconds(tmp_path):
    # a run of 40 s sampled every 0.1 s: t = 30 s is row 300, not row 30 (t = 3 s)
    scene = load_scene("spinning_disk").replace(
        {"time.duration": 40.0, "time.output_step": 0.1, "output.quantities": []}
    )
    ds = results.read(results.write(run_scene(scene), tmp_path / "run.nc", scene))
    assert ds.indexes["time"].equals(ds.get_index("time")) and "time" in ds.xindexes
    row = ds.sel(time=30.0)
    assert float(row["time"]) == 30.0 == ds["time"].values[300]
    assert np.array_equal(row["w"].values, ds["w"].values[300])
    assert ds.sel(time=slice(10.0, 10.25)).sizes["time"] == 3


def test_no_attribute_names_the_machine(tmp_path, monkeypatch):
    # a scene from a folder of its own, compiled into a cache of its own: neither, nor
    # the home or working folder, appears in any attribute (the generated loop's file did)
    cache = tmp_path / "cache-of-this-machine"
    monkeypatch.setenv("GA_ROTORS_CACHE_DIR", str(cache))
    folder = tmp_path / "my-scenes"
    folder.mkdir()
    (folder / "top.toml").write_text(load_scene("spinning_disk").to_toml())
    scene = load_scene(folder / "top.toml").replace({"time.duration": 0.05})
    ds = results.to_dataset(run_scene(scene), scene)
    values = [str(v) for v in ds.attrs.values()]
    values += [str(v) for name in ds.variables for v in ds[name].attrs.values()]
    for place in {str(tmp_path), os.path.expanduser("~"), os.getcwd(), str(cache)} - {"/"}:
        assert not any(place in v for v in values), place
    assert json.loads(ds.attrs["paths_json"])["rotor"] == {
        "complete": True, "ended_at": 0.05, "samples": 6
    }  # fmt: skip


def test_the_body_frame_is_the_runs_own_or_the_default_that_holds_for_it():
    tr = ragged()
    assert results.to_dataset(tr).attrs["body_frame"] == "the body axes the inertia was given in"
    named = tr.extended({}, meta={"body_frame": "the disk's axes, as the tensor gives them"})
    assert results.to_dataset(named).attrs["body_frame"] == (
        "the disk's axes, as the tensor gives them"
    )
    principal = tr.extended({}, meta={"principal_rotation": (0.0, 0.0, math.sqrt(0.5),
                                                             math.sqrt(0.5))})  # fmt: skip
    assert (
        results.to_dataset(principal)
        .attrs["body_frame"]
        .startswith("the principal axes of inertia")
    )
    assert results.to_dataset(Trajectory({"t": np.zeros(1)})).attrs["body_frame"] == (
        "not recorded"
    )


# ---------------------------------------------------------------------- netCDF and zarr


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_read_back_is_identical_to_what_was_written(heavy, tmp_path, suffix):
    scene, tr = heavy
    ds = results.to_dataset(tr, scene)
    path = results.write(ds, tmp_path / f"run{suffix}")
    xr.testing.assert_identical(results.read(path), ds)
    # writing a trajectory directly is the same as converting it first
    again = results.write(tr, tmp_path / f"again{suffix}", scene=scene)
    xr.testing.assert_identical(results.read(again), ds)
    # what was read writes again (its own encodings are not carried over)
    third = results.write(results.read(path), tmp_path / f"third{suffix}")
    xr.testing.assert_identical(results.read(third), ds)


def _chunks(path, name):
    if path.suffix == ".nc":
        import h5netcdf

        with h5netcdf.File(path, "r") as f:
            return f.variables[name].chunks
    return tuple(json.loads((path / name / ".zarray").read_text())["chunks"])


def test_a_short_run_is_a_few_kilobytes_and_chunks_are_sized_to_the_data(tmp_path, monkeypatch):
    """61 rows (7.8 kB of data, the rest HDF5's own structure): 28 kB of netCDF written
    whole (contiguous), 42 kB streamed (chunked along an unlimited time, 61 rows a chunk):
    it was 2.1 MB, every variable chunked 16,384 rows long; zarr chunks of the run's rows.
    A stream longer than CHUNK_ROWS rows is chunked by CHUNK_ROWS."""
    from ga_rotors.results import store
    from ga_rotors.results.streams import NetcdfStream, ZarrStream
    from ga_rotors.scene import stream_scene

    scene = load_scene("spinning_disk").replace(
        {"time.duration": 6.0, "time.output_step": 0.1, "output.data": ["netcdf", "zarr"],
         "output.plots": [], "output.quantities": ["energy", "angles"],
         "integrator.paths": ["rotor", "quaternion"]}
    )  # fmt: skip
    tr = run_scene(scene)
    assert len(tr) == 61
    stream_scene(scene, tmp_path / "streamed", chunk_steps=1000)
    whole = results.write(tr, tmp_path / "whole.nc", scene)
    assert whole.stat().st_size < 32_000
    assert (tmp_path / "streamed" / "spinning_disk.nc").stat().st_size < 48_000
    assert _chunks(tmp_path / "streamed" / "spinning_disk.zarr", "w") == (61, 3)
    assert _chunks(results.write(tr, tmp_path / "whole.zarr"), "q") == (61, 4)
    monkeypatch.setattr(store, "CHUNK_ROWS", 4)
    meta = {"steps": 10**7, "sample_every": 5}
    for cls, suffix in ((NetcdfStream, ".nc"), (ZarrStream, ".zarr")):
        out = cls(tmp_path / f"long{suffix}")
        for lo in (0, 3, 6):
            piece = Trajectory({"t": np.arange(lo, lo + 3.0), "w": np.ones((3, 3))}, meta=meta)
            out.append(piece)
        out.close(meta)
        assert _chunks(tmp_path / f"long{suffix}", "w") == (4, 3), suffix
        assert results.read(tmp_path / f"long{suffix}")["time"].values.tolist() == list(range(9))


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
    with pytest.raises(InputError, match=r"path: cannot write .*: disk full"):
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
    with pytest.raises(InputError, match="path: expected a file or folder name, got an empty"):
        results.write(ragged(), "")
    long = tmp_path / ("x" * 3000 + ".nc")
    with pytest.raises(InputError, match="File name too long") as e:
        results.read(long)
    assert len(str(e.value)) < 250 and f"({len(str(long))} characters)" in str(e.value)
    with pytest.raises(InputError, match=r"path: file name 'x+'\.\.\. is 3003 bytes long; at most"):
        results.write(ragged(), long)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["junk.nc"]


def test_a_missing_extra_names_the_install_command(monkeypatch):
    real = optional.importlib.import_module

    def fake(name, *args):
        if name == "xarray":
            raise ModuleNotFoundError("No module named 'xarray'", name="xarray")
        return real(name, *args)

    monkeypatch.setattr(optional.importlib, "import_module", fake)
    with pytest.raises(MissingExtraError, match=r'pip install "\.\[results\]" in the ga_rotors'):
        results.to_dataset(ragged())


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


# --------------------------------------------------------------------------------- NPZ


def test_an_npz_archive_holds_the_arrays_labels_and_attributes(heavy, tmp_path):
    scene, tr = heavy
    data = np.load(tr.to_npz(tmp_path / "run.npz"))
    for name in tr.names:
        assert np.array_equal(data[name], tr[name]), name
    assert data["q__components"].tolist() == ["w", "x", "y", "z"]
    attributes = json.loads(data["attributes.json"])
    assert attributes["attributes"]["body_frame"] == scene.body_frame
    assert attributes["attributes"]["scene_toml"] == scene.to_toml()
    assert attributes["variables"]["L"] == {
        "units": "kg m^2/s",
        "long_name": "body-frame angular momentum Iw",
    }


# --------------------------------------------------------------------------------- CSV

ENGINES = [e for e in table.ENGINES if e == "numpy" or importlib.util.find_spec(e)]

#: float64 values of every kind: subnormals, signed zeros, infinities, NaN, any bits
FLOATS = st.one_of(
    st.floats(width=64, allow_nan=True, allow_infinity=True, allow_subnormal=True),
    st.sampled_from(
        [
            0.0,
            -0.0,
            5e-324,
            -5e-324,
            2.2250738585072014e-308,
            2.225073858507201e-308,
            1.7976931348623157e308,
            0.1,
            1 / 3,
            1e16,
            9007199254740993.0,
            1e-7,
            1e21,
            1e22,
        ]
    ),
    st.integers(0, 2**64 - 1).map(lambda b: float(np.array(b, np.uint64).view(np.float64))),
)


@st.composite
def trajectories(draw):
    """t and a 3-column array, each of any float64 values, the array possibly stopped."""
    n = draw(st.integers(1, 12))
    t = np.array(draw(st.lists(FLOATS, min_size=n, max_size=n)))
    rows = draw(st.integers(0, n))
    w = np.array(draw(st.lists(FLOATS, min_size=3 * rows, max_size=3 * rows))).reshape(rows, 3)
    return Trajectory({"t": t, "w": w}, {"w": ("1", "2", "3")}, {"integrator": "rk4"})


def _cells(text):
    """Data rows of a results CSV, split into cells (the header row left out)."""
    lines = text.splitlines()
    assert lines[0].startswith("t [s]")
    return [line.split(",") for line in lines[1:]]


@pytest.mark.parametrize("engine", ENGINES)
@settings(max_examples=150, deadline=None)
@given(tr=trajectories())
def test_csv_values_read_back_bit_for_bit_and_stopped_cells_are_empty(engine, tr):
    cells = _cells(results.write_csv(tr, engine=engine))
    assert len(cells) == len(tr)
    for r, row in enumerate(cells):
        assert len(row) == 4
        expected = [tr.t[r], *(tr.w[r] if r < tr.w.shape[0] else [None] * 3)]
        for cell, value in zip(row, expected, strict=True):
            if value is None:
                assert cell == ""
            else:  # the same bits: -0.0 stays negative, every NaN is a NaN
                back = float(cell)
                assert back == value or (math.isnan(back) and math.isnan(value)), (cell, value)
                assert math.copysign(1.0, back) == math.copysign(1.0, value) or math.isnan(value)


@pytest.mark.parametrize("engine", ENGINES)
def test_csv_text_is_the_shortest_that_reads_back(engine):
    tr = Trajectory({"t": np.array([0.1, 1 / 3, 2.5, 1e-7, 5e-324])})
    cells = [row[0] for row in _cells(results.write_csv(tr, engine=engine))]
    assert cells[:3] == ["0.1", "0.3333333333333333", "2.5"]
    assert float(cells[3]) == 1e-7 and len(cells[3]) <= 5 and cells[4] == "5e-324"


HEADERS = ["t [s]", "w_1 [rad/s]", "w_2 [rad/s]", "w_3 [rad/s]",
           "euler_psi [rad]", "euler_theta [rad]", "euler_phi [rad]"]  # fmt: skip


@pytest.mark.parametrize("engine", ENGINES)
def test_csv_opens_in_every_reader_with_no_options(engine, tmp_path):
    """The header row first, then the data: what pandas, polars, numpy's loadtxt and a
    spreadsheet's header detection expect (before, a '# body_frame' line came first)."""
    pd = pytest.importorskip("pandas")
    pl = pytest.importorskip("polars")
    stopped = ragged()
    full = stopped.extended({"euler": np.ones((5, 3)) / 3})  # every path complete
    path = results.write_csv(full, tmp_path / "run.csv", engine=engine)
    assert path.read_text().splitlines()[0] == ",".join(HEADERS)
    expected = np.column_stack([full.t, full.w, full.euler])
    read = {
        "pandas": pd.read_csv(path).to_numpy(),
        "polars": pl.read_csv(path).to_numpy(),
        "numpy": np.loadtxt(path, delimiter=",", skiprows=1),
    }
    assert list(pd.read_csv(path).columns) == HEADERS == pl.read_csv(path).columns
    for reader, values in read.items():
        assert np.array_equal(values.astype(float), expected), reader
    assert results.write_csv(full, engine=engine) == path.read_text()


@pytest.mark.parametrize("engine", ENGINES)
def test_a_stopped_path_reads_as_missing_values(engine, tmp_path):
    pd = pytest.importorskip("pandas")
    pl = pytest.importorskip("polars")
    tr = ragged()
    path = results.write_csv(tr, tmp_path / "run.csv", engine=engine)
    expected = np.column_stack([tr.t, tr.w, np.vstack([tr.euler, np.full((2, 3), np.nan)])])
    read = {
        "pandas": pd.read_csv(path).to_numpy(),
        "polars": pl.read_csv(path).to_numpy(),
        "numpy": np.genfromtxt(path, delimiter=",", skip_header=1),
    }
    for reader, values in read.items():
        assert np.array_equal(values.astype(float), expected, equal_nan=True), reader


def _sidecar(csv_path) -> dict:
    return json.loads((csv_path.parent / (csv_path.name + "-metadata.json")).read_text())


def _properties(document) -> dict:
    return {p["schema:name"]: p["schema:value"] for p in document["schema:additionalProperty"]}


def test_the_csvw_sidecar_describes_every_column_and_the_run(tmp_path):
    tr = ragged().extended({}, meta={"body_frame": "disk axes\n,t [s]\r\nmore"})
    path = results.write_csv(tr, tmp_path / "run.csv")
    assert path.read_text().splitlines()[0] == ",".join(HEADERS)  # the frame is not there
    text = (tmp_path / "run.csv-metadata.json").read_text()
    document = json.loads(text)  # valid JSON, and the JSON-LD context CSVW requires
    assert document["@context"] == "http://www.w3.org/ns/csvw"
    assert document["url"] == "run.csv" and str(tmp_path) not in text  # relative, no machine
    columns = document["tableSchema"]["columns"]
    assert [c["titles"] for c in columns] == HEADERS
    assert [c["name"] for c in columns] == [h.split(" [")[0] for h in HEADERS]
    assert {c["datatype"] for c in columns} == {"double"}
    assert [c["schema:unitText"] for c in columns] == ["s"] + ["rad/s"] * 3 + ["rad"] * 3
    assert columns[5]["dc:description"].endswith("; zyz_angle theta")
    attrs = _properties(document)
    assert attrs["body_frame"] == "disk axes\n,t [s]\r\nmore"  # as given: JSON escapes it
    assert attrs == json.loads(json.dumps(results.provenance(tr.meta)))  # one source


def test_a_csvw_processor_validates_the_pair_and_reads_the_values(tmp_path):
    csvw = pytest.importorskip("csvw")  # the CSVW reference library (cldf), an oracle
    tr = ragged().extended({"my gain": np.arange(5.0)})  # a user's array: no unit, no name
    path = results.write_csv(tr, tmp_path / "run.csv")
    columns = _sidecar(path)["tableSchema"]["columns"]
    assert columns[-1] == {"titles": "my gain", "datatype": "double"}
    described = csvw.CSVW(str(tmp_path / "run.csv-metadata.json"), validate=True)
    assert described.is_valid, [str(w.message) for w in described.warnings]
    rows = list(described.tables[0].iterdicts())
    assert [row["t"] for row in rows] == tr.t.tolist()
    assert [row["w_2"] for row in rows] == tr.w[:, 1].tolist()
    assert [row["euler_phi"] for row in rows] == [*tr.euler[:, 2].tolist(), None, None]
    assert [list(row.values())[-1] for row in rows] == tr["my gain"].tolist()
    assert path.name in str(described.tables[0].url)


def test_write_csv_leaves_the_previous_pair_when_the_sidecar_fails(tmp_path, monkeypatch):
    path = results.write_csv(ragged(), tmp_path / "run.csv")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    assert sorted(before) == ["run.csv", "run.csv-metadata.json"]

    def fails(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(table, "metadata_text", fails)
    longer = Trajectory({"t": np.arange(9.0)}, meta={"integrator": "rk4"})
    with pytest.raises(InputError, match=r"path: cannot write .*: No space left on device"):
        results.write_csv(longer, path)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before  # no debris either


def test_csv_engines_write_the_same_values(heavy):
    _, tr = heavy
    tables = [np.loadtxt(io.StringIO(results.write_csv(tr, engine=e)), delimiter=",",
                         skiprows=1) for e in ENGINES]  # fmt: skip
    for values in tables:
        assert values.shape == (len(tr), len(tr.columns()))
        assert np.array_equal(values, tables[0])
    for j, (_, name, comp) in enumerate(tr.columns()):
        a = tr[name] if comp is None else tr[name][:, comp]
        assert np.array_equal(tables[0][:, j], a), name


def test_an_unknown_engine_is_one_line(tmp_path):
    with pytest.raises(InputError, match="engine: expected one of polars, numpy"):
        results.write_csv(ragged(), engine="excel")
    with pytest.raises(InputError, match="engine: expected one of polars, numpy"):
        results.write_csv(ragged(), tmp_path / "run.csv", engine="excel")
    assert list(tmp_path.iterdir()) == []


def test_a_scene_declaring_netcdf_and_csv_writes_both_readable(tmp_path):
    from ga_rotors.scene import write_outputs

    scene = load_scene("heavy_top").replace(
        {"time.duration": 0.01, "output.data": ["netcdf", "csv"], "output.plots": []}
    )
    tr = run_scene(scene)
    written = write_outputs(scene, tr, tmp_path / "run")
    assert [p.name for p in written] == [
        "heavy_top.nc", "heavy_top.csv", "heavy_top.csv-metadata.json", "heavy_top.scene.toml"
    ]  # fmt: skip
    back = results.read(tmp_path / "run" / "heavy_top.nc")
    xr.testing.assert_identical(back, results.to_dataset(tr, scene))  # with the bound
    assert back.attrs["scene_toml"] == scene.to_toml()  # the run records its scene
    csv_lines = (tmp_path / "run" / "heavy_top.csv").read_text().splitlines()
    assert csv_lines[0].startswith("t [s],w_1 [rad/s]")
    # the sidecar carries the netCDF file's attributes, the body frame and the bound included
    attrs = _properties(_sidecar(tmp_path / "run" / "heavy_top.csv"))
    assert attrs.keys() == back.attrs.keys()
    for key, value in back.attrs.items():
        assert np.array_equal(attrs[key], value), key
    assert attrs["body_frame"] == back.attrs["body_frame"] and attrs["exact_error_bound"] > 0


@pytest.mark.skipif(not hasattr(os, "fork"), reason="POSIX fork")
def test_a_forked_process_writes_csv_after_its_parent_used_polars(tmp_path):
    """polars' thread pool does not survive fork: a forked worker writing a scene's CSV
    with it after the parent had used it waited forever (seen as a forked warm-up worker
    hanging behind test_stream's polars CSVs). A forked process writes with the next
    engine."""
    import signal

    pytest.importorskip("polars")
    results.write_csv(ragged(), engine="polars")  # the parent's pool is in use
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child reports by its exit status
        signal.alarm(60)  # a hang ends the child, which the parent sees as a failure
        try:
            results.write_csv(ragged(), tmp_path / "child.csv")
            os._exit(0 if table.csv_engine() != "polars" else 3)
        finally:
            os._exit(1)
    _, status = os.waitpid(pid, 0)
    assert os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0, status
    assert (tmp_path / "child.csv").read_text() == results.write_csv(ragged(), engine="numpy")
    assert table.csv_engine() == "polars"  # the parent keeps its default
