"""ga-rotors run / scenes / show: exit codes, messages, atomic outputs, progress."""

from __future__ import annotations

import io
import os
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import numpy as np
import pytest

from ga_rotors.cli import main
from ga_rotors.cli.run import ProgressBar
from ga_rotors.scene import Scene, bundled, load_scene

ROOT = Path(__file__).resolve().parent.parent

SHORT = """
[scene]
name = "short"

[body]
shape = "disk"
mass = 2.0
radius = 0.075

[initial.angular_velocity]
body = [0.2, 0.0, 15.0]
units = "rad/s"

[time]
duration = 0.2
output_step = 0.01

[integrator]
step = 0.001
paths = ["rotor", "quaternion"]

[output]
plots = ["omega", "error"]
data = ["csv", "npz"]
"""


@pytest.fixture
def short(tmp_path) -> Path:
    path = tmp_path / "short.toml"
    path.write_text(SHORT)
    return path


def test_run_writes_what_the_scene_declares(short, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", str(short), "--out", str(out), "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "rotor vs quaternion" in printed and "exact solution (symmetric_top)" in printed
    names = sorted(p.name for p in out.iterdir())
    assert names == ["short.csv", "short.csv-metadata.json", "short.npz", "short.png",
                     "short.scene.toml", "short.summary.txt"]  # fmt: skip
    assert Scene.from_toml((out / "short.scene.toml").read_text()).data == load_scene(short).data
    data = np.load(out / "short.npz")
    assert data["t"].shape == (21,) and data["rotor_blades"].shape == (21, 4)
    assert (out / "short.summary.txt").read_text().startswith("scene short: rk4")


def test_run_without_declared_files_writes_nothing(short, tmp_path, capsys):
    text = SHORT.replace('plots = ["omega", "error"]\ndata = ["csv", "npz"]\n', "data = []\n")
    path = tmp_path / "quiet.toml"
    path.write_text(text)
    out = tmp_path / "never"
    assert main(["run", str(path), "--out", str(out)]) == 0
    assert not out.exists()
    assert "no files declared" in capsys.readouterr().out


def test_run_without_output_data_writes_the_binary_default(short, tmp_path, capsys):
    import xarray as xr

    text = SHORT.replace('plots = ["omega", "error"]\ndata = ["csv", "npz"]\n', "")
    path = tmp_path / "quiet.toml"
    path.write_text(text)
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ["short.nc", "short.scene.toml", "short.summary.txt"]
    with xr.open_dataset(out / "short.nc") as ds:
        assert ds.sizes["time"] == 21 and ds.attrs["Conventions"] == "CF-1.10"


@pytest.mark.parametrize("when", ["drawing", "mid-run"])
@pytest.mark.parametrize("existing", [False, True], ids=["new-dir", "existing-dir"])
def test_a_failed_run_leaves_no_half_written_files(short, tmp_path, monkeypatch, existing, when):
    from ga_rotors.results import streams
    from ga_rotors.scene import figures

    out = tmp_path / "out"
    if existing:
        out.mkdir()
        (out / "short.csv").write_text("previous run\n")
    # The data files are streamed into the staging folder as the run goes; then the
    # figure is drawn. A failure in either place (Ctrl-C mid-run) leaves --out as it was.
    written = []
    real_append = streams.CsvStream.append

    def spy_append(self, piece):
        if when == "mid-run" and written:
            raise KeyboardInterrupt  # the second piece: the files are half written
        written.append(self.path)
        return real_append(self, piece)

    def broken_figure(scene, trajectory, fmt=None):
        assert written and Path(written[0]).exists()  # the data files exist (staged)
        raise RuntimeError("injected failure while drawing")

    monkeypatch.setattr(streams.CsvStream, "append", spy_append)
    monkeypatch.setattr(figures, "render", broken_figure)
    argv = ["run", str(short), "--out", str(out), "--no-progress", "--chunk-steps", "50"]
    if when == "drawing":
        with pytest.raises(RuntimeError, match="injected failure"):
            main(argv)
    else:
        assert main(argv) == 130  # Ctrl-C: "ga-rotors: interrupted"
    assert written and not Path(written[0]).exists()
    if existing:
        assert sorted(p.name for p in out.iterdir()) == ["short.csv"]
        assert (out / "short.csv").read_text() == "previous run\n"
    else:
        assert not out.exists()
    assert not any(".staging-" in p.name for p in tmp_path.rglob("*"))


def test_bad_scene_exits_2_with_one_line_and_no_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SHORT.replace('units = "rad/s"\n', ""))
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.run([sys.executable, "-m", "ga_rotors", "run", str(bad)], env=env,
                          capture_output=True, text=True, timeout=120)  # fmt: skip
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip() == (
        f"ga-rotors: error: {bad}: initial.angular_velocity.units: missing; angular rates "
        'are ambiguous without units: expected one of "rad/s", "deg/s", "rpm"'
    )


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "no_such_scene"], "no_such_scene: no such file, and no bundled scene"),
        (["show", "heavytop"], "did you mean 'heavy_top'"),
    ],
)
def test_cli_errors_are_one_line(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("ga-rotors: error: ") and message in err and err.count("\n") == 1


def test_scenes_lists_every_bundled_scene(capsys):
    assert main(["scenes"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == sorted(bundled())
    assert all(len(line.split(maxsplit=1)) == 2 for line in lines)  # each has a description


def test_show_prints_a_loadable_scene_with_every_default(capsys):
    assert main(["show", "intermediate_axis_flip"]) == 0
    text = capsys.readouterr().out
    data = tomllib.loads(text)  # the derived values are comments
    assert data["initial"]["orientation"] == {"quaternion": [1.0, 0.0, 0.0, 0.0]}
    assert data["time"]["start"] == 0.0 and data["output"]["summary"] is True
    assert Scene(data).data == load_scene("intermediate_axis_flip").data
    assert "# exact solution: asymmetric_top" in text


# ---------------------------------------------------------------------------- progress


class FakeStream(io.StringIO):
    def __init__(self, tty: bool):
        super().__init__()
        self._tty = tty

    def isatty(self) -> bool:
        return self._tty


def test_progress_bar_on_a_terminal_redraws_in_place():
    stream = FakeStream(tty=True)
    bar = ProgressBar(stream, delay=0.0)
    for done in (10, 50, 100):
        bar.last = -1.0  # as if 0.1 s had passed between chunks
        bar(done, 100)
    bar.close()
    text = stream.getvalue()
    assert text.count("\r[") == 3 and text.endswith("\n") and "100.0%" in text


def test_progress_bar_is_silent_for_short_runs_and_off_a_terminal():
    quiet = FakeStream(tty=True)
    bar = ProgressBar(quiet)  # default delay: nothing within the first 0.5 s
    bar(100, 100)
    bar.close()
    assert quiet.getvalue() == ""
    log = FakeStream(tty=False)
    bar = ProgressBar(log, delay=0.0)  # not a terminal, not forced: nothing
    bar(100, 100)
    assert log.getvalue() == ""
    forced = ProgressBar(log, enabled=True, delay=0.0)  # --progress in a log: tenths
    for done in range(0, 101, 5):
        forced(done, 100)
    assert log.getvalue().count("\n") == 11 and "\r" not in log.getvalue()


def test_run_reports_progress_while_the_loops_run(short, tmp_path, monkeypatch, capsys):
    seen = []
    monkeypatch.setattr(ProgressBar, "__call__", lambda self, d, t: seen.append((d, t)))
    argv = ["run", str(short), "--out", str(tmp_path / "o"), "--progress", "--chunk-steps", "50"]
    assert main(argv) == 0
    assert seen[-1] == (400, 400) and len(seen) == 2 * 4  # two paths, four pieces each
    assert seen == sorted(seen)


def test_run_prints_the_packages_warnings_as_one_line_each(tmp_path, capsys):
    """A spin started upright puts every sample's ZYZ angles at gimbal lock: the run says
    so in one line on stderr, with no source excerpt."""
    path = tmp_path / "upright_spin.toml"
    path.write_text(
        textwrap.dedent(
            """
            [body]
            moments = [1.0, 1.0, 2.0]
            [initial.angular_velocity]
            body = [0.0, 0.0, 1.0]
            units = "rad/s"
            [time]
            duration = 0.01
            [integrator]
            step = 0.005
            [output]
            quantities = ["angles"]
            """
        ),
        encoding="utf-8",
    )
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "gimbal" in line.lower()]
    assert lines and all(line.startswith("ga-rotors: warning: ") for line in lines)
    assert "warnings.warn" not in err and ".py:" not in err


@pytest.mark.parametrize(("fmt", "missing"), [("netcdf", "h5netcdf"), ("zarr", "zarr")])
def test_a_data_format_without_its_extra_is_refused_before_anything_runs(
    short, tmp_path, monkeypatch, capsys, fmt, missing
):
    """A scene asking for netCDF or zarr without the ``results`` extra gets one line naming
    the file, the key and the install command before the warm-up or the run starts (it
    used to integrate a first piece, and the warm-up reported each path as failed)."""
    import ga_rotors.optional as optional
    import ga_rotors.warmup as warmup

    real = optional.importlib.import_module

    def fake(name, *args):
        if name == missing:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return real(name, *args)

    monkeypatch.setattr(optional.importlib, "import_module", fake)
    monkeypatch.setattr(warmup, "warm", lambda *a, **k: pytest.fail("the warm-up ran"))
    path = tmp_path / "wants.toml"
    path.write_text(SHORT.replace('data = ["csv", "npz"]', f'data = ["csv", "{fmt}"]'))
    out = tmp_path / "out"
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (
        f"ga-rotors: error: {path}: output.data[1]: '{fmt}': {missing} is not installed; it "
        'comes with the results extra: pip install ".[results]" in the ga_rotors repository'
    )
    assert not out.exists()
    from ga_rotors.errors import SceneError
    from ga_rotors.scene import stream_scene

    with pytest.raises(SceneError, match=r"output\.data\[1\]"):  # the API refuses too
        stream_scene(load_scene(path), out)


@pytest.mark.parametrize("fmt", [None, "svg", "pdf"])
def test_scenes_figures_writes_the_bundled_scenes_figures(tmp_path, monkeypatch, capsys, fmt):
    """``ga-rotors scenes --figures DIR [--format F]`` as docs/scenes.md shows it, on two of
    the bundled scenes (tests/test_scenes_bundled.py checks every committed figure's data):
    the PNGs carry the digest of the data the committed figures show."""
    import ga_rotors.scene as scene_pkg
    from ga_rotors.paper.figures import read_digest
    from ga_rotors.scene.figures import DIGEST_PREFIX

    two = {n: d for n, d in bundled().items() if n in ("damped_top", "heavy_top")}
    monkeypatch.setattr(scene_pkg, "bundled", lambda: two)
    argv = ["scenes", "--figures", str(tmp_path)] + ([] if fmt is None else ["--format", fmt])
    assert main(argv) == 0
    suffix = fmt or "png"
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"{n}.{suffix}" for n in sorted(two)]
    assert capsys.readouterr().out.count("wrote ") == 2
    committed = Path(__file__).resolve().parent.parent / "docs" / "figures" / "scenes"
    for name in two:
        data = (tmp_path / f"{name}.{suffix}").read_bytes()
        if suffix == "png":
            written = read_digest(tmp_path / f"{name}.png", DIGEST_PREFIX)
            assert written is not None
            assert written == read_digest(committed / f"{name}.png", DIGEST_PREFIX)
        else:
            assert (b"<svg" in data[:400]) if suffix == "svg" else data.startswith(b"%PDF-")


def test_scenes_format_without_figures_is_one_line(capsys):
    assert main(["scenes", "--format", "svg"]) == 2
    assert capsys.readouterr().err.strip() == (
        "ga-rotors: error: --format: only with --figures DIR (the figures' format)"
    )


def test_scenes_figures_empty_is_one_line_not_the_current_folder(tmp_path, monkeypatch, capsys):
    # Path("") is the current folder: every bundled scene's figure landed there.
    monkeypatch.chdir(tmp_path)
    assert main(["scenes", "--figures", ""]) == 2
    assert capsys.readouterr().err == (
        "ga-rotors: error: --figures: expected a file or folder name, got an empty one\n"
    )
    assert list(tmp_path.iterdir()) == []


def test_scenes_figures_names_a_missing_folder_escaped(tmp_path, monkeypatch, capsys):
    # a relative name: a long temporary folder's path would be shortened in the message
    monkeypatch.chdir(tmp_path)
    assert main(["scenes", "--figures", "no\x1b[2Jne"]) == 2
    err = capsys.readouterr().err
    assert err.endswith("no\\x1b[2Jne is not a directory\n") and "\x1b" not in err


# ---------------------------------------------------------------------------- Ctrl-C


def _command(run):
    """main's inner part (parsing and all: ``cli._main``) replaced by ``run``."""
    return lambda argv: run()


def _sigint():
    import signal

    os.kill(os.getpid(), signal.SIGINT)


def test_an_interrupt_a_library_swallows_still_exits_130(monkeypatch, capsys):
    """Issue 30 item 6: a Ctrl-C that lands where Python drops the exception (a weakref
    callback, a lookup) let a sweep finish and exit 0. The handler records it: the command
    that goes on to finish exits 130 with one line."""
    import ga_rotors.cli as cli

    def swallowed():
        try:
            _sigint()
        except KeyboardInterrupt:
            pass  # as a callback's caller would drop it
        return 0

    monkeypatch.setattr(cli, "_main", _command(swallowed))
    assert main(["scenes"]) == 130
    assert capsys.readouterr().err == "ga-rotors: interrupted\n"


def test_an_interrupt_turned_into_another_error_exits_130_with_one_line(monkeypatch, capsys):
    """Ctrl-C during a lazy import gave a 41-line traceback: the half-imported module raised
    a RuntimeError when imported again. Whatever the interrupt becomes, one line, 130."""
    import ga_rotors.cli as cli

    def wrapped():
        try:
            _sigint()
        except KeyboardInterrupt:
            raise RuntimeError("CPU dispatcher tracer already initialized") from None

    monkeypatch.setattr(cli, "_main", _command(wrapped))
    assert main(["scenes"]) == 130
    assert capsys.readouterr().err == "ga-rotors: interrupted\n"


def test_no_interrupt_no_130(monkeypatch):
    import ga_rotors.cli as cli

    def broken():
        raise RuntimeError("a bug")

    monkeypatch.setattr(cli, "_main", _command(broken))
    with pytest.raises(RuntimeError, match="a bug"):  # a bug stays a traceback
        main(["scenes"])


@pytest.mark.parametrize("delay", [0.02, 0.05, 0.1, 0.3])
def test_ctrl_c_while_the_command_starts_is_one_line_and_130(tmp_path, delay):
    """Once main has started, Ctrl-C while it imports the commands' modules (the first
    half second of a cold start) ends with one line and 130, never a traceback."""
    import signal
    import time

    script = (
        "import sys\nfrom ga_rotors.cli import main\nprint('ready', flush=True)\n"
        "sys.exit(main(['run', 'spinning_disk', '--out', sys.argv[1], '--no-progress']))\n"
    )
    child = subprocess.Popen(
        [sys.executable, "-c", script, str(tmp_path / "out")],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    assert child.stdout.readline() == "ready\n"
    time.sleep(delay)
    child.send_signal(signal.SIGINT)
    _, err = child.communicate(timeout=120)
    assert child.returncode == 130, err
    assert err.splitlines() == ["ga-rotors: interrupted"], err
    assert not (tmp_path / "out").exists()  # nothing half-written


def test_ctrl_c_dropped_in_a_callback_still_stops_the_run(tmp_path, monkeypatch, capsys):
    """An interrupt that lands where Python drops exceptions (llvmlite's object-cache
    callback while numba loads a loop; here a ``__del__``) is raised again once the callback
    has returned: the run stops with one line and 130 and writes nothing. It used to go on
    and write its whole output (the flaky [0.1] case of the test above)."""
    import signal

    from ga_rotors import scene as scene_module

    real = scene_module.stream_scene

    class Callback:
        def __del__(self):
            signal.getsignal(signal.SIGINT)(signal.SIGINT, None)  # Ctrl-C arrives here

    def interrupted_in_a_callback(*args, **kwargs):
        Callback()  # collected at once: its exception goes to sys.unraisablehook
        return real(*args, **kwargs)

    monkeypatch.setattr(scene_module, "stream_scene", interrupted_in_a_callback)
    out = tmp_path / "out"
    assert main(["run", "spinning_disk", "--out", str(out), "--no-progress"]) == 130
    assert capsys.readouterr().err.splitlines() == ["ga-rotors: interrupted"]
    assert not out.exists()


# ---------------------------------------------------------------------------- compile budget


def test_the_compile_estimate_grows_with_the_effects_and_is_shown(short, tmp_path, monkeypatch,
                                                                  capsys):  # fmt: skip
    """Issue 30 item 8: compile time grew faster than linearly with the effects and nothing
    said so before a run. The estimate (per path, a method's stages and its torque terms)
    is part of the scene's budget estimate and printed past a threshold."""
    from ga_rotors.scene import budget

    base = load_scene(short).replace({"output.plots": []})
    torque = {"type": "body_torque", "torque": [0.0, 0.0, 1e-4]}
    few, many = (budget.estimate(base.replace({"effects": [torque] * n})).compile_seconds
                 for n in (2, 64))  # fmt: skip
    assert 0 < budget.estimate(base).compile_seconds < few < many
    assert many / len(base.paths) > 1.5 * few / len(base.paths)  # the terms' share
    monkeypatch.setattr(budget, "COMPILE_NOTICE_SECONDS", 0.5)
    assert main(["run", str(short), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    assert "to compile its loops on a first run" in capsys.readouterr().err
