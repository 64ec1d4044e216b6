"""Compiling ahead: tasks, markers, and the commands that warm themselves.

The cold ``cache --warm`` of every bundled loop followed by ``paper`` and ``run`` (two
minutes of compiling) runs in the long mode only: ``GA_ROTORS_LONG=1``."""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
import time

import pytest

from ga_rotors import warmup
from ga_rotors.cli import main
from ga_rotors.scene import bundled, load_scene


def test_scene_tasks_are_the_scene_on_each_path_for_two_samples():
    scene = load_scene("heavy_top")
    tasks = warmup.scene_tasks(scene)
    assert [t.scene.paths for t in tasks] == [[p] for p in scene.paths]
    for t in tasks:
        assert t.scene.steps == warmup.TASK_SAMPLES * scene.sample_every
        assert t.scene.method is scene.method and t.scene.data["effects"] == scene.data["effects"]
        # the scene's own data formats (their writers compile too), no figure to draw
        assert t.scene.data["output"]["data"] == scene.data["output"]["data"]
        assert t.scene.data["output"]["plots"] == []


def test_all_tasks_cover_the_paper_and_every_bundled_scene_and_path():
    labels = [t.label for t in warmup.all_tasks()]
    want = {f"{n}: {p} path" for n in bundled() for p in load_scene(n).paths}
    assert set(labels) == want | {"paper: its other computations"}
    assert len(labels) == len(set(labels))


def test_warm_runs_each_task_once_here_and_remembers_it(cache):
    tasks = warmup.scene_tasks("heavy_top")
    log = io.StringIO()
    assert warmup.warm(tasks, stream=log) == []
    lines = log.getvalue().splitlines()
    assert lines[0].startswith("ga-rotors: compiling 2 loop set(s), once per installed version")
    assert lines[-1].startswith("ga-rotors: compiled in ")
    assert sorted(line.split("] ")[1].split(" (")[0] for line in lines[1:3]) == sorted(
        t.label for t in tasks
    )
    assert len(list((cache / "warm").iterdir())) == 2
    again = io.StringIO()
    assert warmup.warm(tasks, stream=again) == [] and again.getvalue() == ""
    assert main(["cache", "--clear"]) == 0
    assert not list((cache / "warm").iterdir())


class _Unreadable:
    """Stands for a scene that fails in the worker."""

    def to_toml(self):
        return "not a scene"


def test_a_failing_task_is_reported_not_raised_and_not_remembered(cache):
    bad = warmup.Task("broken", _Unreadable())
    log = io.StringIO()
    failed = warmup.warm([bad, *warmup.scene_tasks("spinning_disk")], stream=log)
    assert [(t.label, e.split(":")[0]) for t, e in failed] == [("broken", "TypeError")]
    assert "broken (" in log.getvalue() and "failed: TypeError" in log.getvalue()
    assert len(list((cache / "warm").iterdir())) == len(warmup.scene_tasks("spinning_disk"))


def test_cache_warm_command(cache, monkeypatch, capsys):
    # The whole list compiles every bundled loop (a minute of CPU): the command runs end
    # to end here on one scene's tasks; the list itself is checked above.
    monkeypatch.setattr(warmup, "all_tasks", lambda: warmup.scene_tasks("spinning_disk"))
    assert main(["cache", "--warm"]) == 0
    out = capsys.readouterr().out
    n = len(warmup.scene_tasks("spinning_disk"))
    assert f"compiling {n} loop set(s)" in out and f"{n} of {n} loop sets compiled" in out
    assert main(["cache", "--warm"]) == 0
    assert capsys.readouterr().out == f"{n} of {n} loop sets compiled and cached\n"


def test_cache_warm_command_reports_a_failure(cache, monkeypatch, capsys):
    monkeypatch.setattr(warmup, "all_tasks", lambda: [warmup.Task("broken", _Unreadable())])
    assert main(["cache", "--warm"]) == 1
    captured = capsys.readouterr()
    assert "0 of 1 loop sets compiled" in captured.out
    assert captured.err.startswith("ga-rotors: broken: TypeError")


def test_run_warms_its_scene_first_then_never_again(cache, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", "spinning_disk", "--out", str(out), "--progress"]) == 0
    err = capsys.readouterr().err
    assert "ga-rotors: compiling" in err
    assert "spinning_disk: rotor path" in err
    assert main(["run", "spinning_disk", "--out", str(out), "--progress"]) == 0
    assert "compiling" not in capsys.readouterr().err


def test_run_warms_silently_without_progress(cache, tmp_path, capsys):
    # Like the progress bar: shown on a terminal or with --progress, so that a scene the
    # run refuses still gets exactly one line on stderr.
    assert main(["run", "heavy_top", "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    assert "compiling" not in capsys.readouterr().err
    assert len(list((cache / "warm").iterdir())) == len(warmup.scene_tasks("heavy_top"))


def test_paper_warms_itself_after_checking_its_output_directory(cache, tmp_path, capsys):
    taken = tmp_path / "taken"
    taken.write_text("x")
    assert main(["paper", "--out", str(taken), "--no-figures"]) == 2
    assert "compiling" not in capsys.readouterr().err  # refused before any compiling
    assert main(["paper", "--out", str(tmp_path / "out"), "--no-figures"]) == 0
    err = capsys.readouterr().err
    assert "ga-rotors: compiling 4 loop set(s)" in err
    assert "paper: its other computations" in err and "paper_15deg: euler path" in err


# ------------------------------------------------------------------ stopping a warm-up

_WARM = """
import signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)  # as in a terminal
from ga_rotors import warmup
from ga_rotors.cli import main

class Name:
    def __init__(self, text):
        self.text = text

    def to_toml(self):
        return self.text

class Slow(warmup.Task):
    def run(self):
        time.sleep(120)

real = warmup.scene_tasks("spinning_disk")
tasks = {
    "waiting": [Slow("slow", Name("s"))],
    "compiling": [real[0], Slow("slow", Name("s"))],
    "again": real,
}[sys.argv[1]]
warmup.all_tasks = lambda: tasks
sys.exit(main(["cache", "--warm"]))
"""


def _start_warm(which: str, env: dict) -> subprocess.Popen:
    """``cache --warm`` in a subprocess, once it has said it is compiling."""
    proc = subprocess.Popen(
        [sys.executable, "-c", _WARM, which], env=env, text=True,
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
    )  # fmt: skip
    assert "compiling" in proc.stdout.readline()
    return proc


@pytest.mark.parametrize(
    ("signum", "status", "line"),
    [(signal.SIGINT, 130, "ga-rotors: interrupted"), (signal.SIGTERM, 143, "terminated")],
)
def test_stopping_a_warm_up_stops_it_at_once(tmp_path, signum, status, line):
    env = {**os.environ, "GA_ROTORS_CACHE_DIR": str(tmp_path)}
    proc = _start_warm("waiting", env)
    proc.send_signal(signum)
    assert proc.wait(timeout=30) == status, proc.stdout.read()
    assert line in proc.stdout.read()


def test_a_warm_up_killed_while_compiling_leaves_a_usable_cache(tmp_path):
    env = {**os.environ, "GA_ROTORS_CACHE_DIR": str(tmp_path)}
    proc = _start_warm("compiling", env)
    time.sleep(0.3)  # into the compilation
    proc.terminate()
    assert proc.wait(timeout=30) == 143
    again = subprocess.run(
        [sys.executable, "-c", _WARM, "again"], env=env, capture_output=True, text=True
    )
    n = len(warmup.scene_tasks("spinning_disk"))
    assert again.returncode == 0 and f"{n} of {n} loop sets compiled" in again.stdout
    run = subprocess.run(
        [sys.executable, "-m", "ga_rotors", "run", "spinning_disk", "--out", str(tmp_path / "o"),
         "--no-progress"],
        env=env, capture_output=True, text=True,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert "compiling" not in run.stderr


@pytest.mark.skipif(
    os.environ.get("GA_ROTORS_LONG") != "1",
    reason="long mode: set GA_ROTORS_LONG=1 (a cold cache --warm, about two minutes)",
)
def test_paper_and_run_compile_nothing_after_cache_warm(tmp_path):
    """README command 1: ``cache --warm`` then ``paper``; and ``run``, in pieces. Every
    kernel they call (loops, conversions, figure data, the CSV number formatting) must be
    cached by the warm-up, or the first run after install pays the compiling the warm-up
    was for. numba reports each function it compiles and saves (NUMBA_DEBUG_CACHE): none."""
    env = {**os.environ, "GA_ROTORS_CACHE_DIR": str(tmp_path / "loops"),
           "NUMBA_CACHE_DIR": str(tmp_path / "numba")}  # fmt: skip
    warm = subprocess.run(
        [sys.executable, "-m", "ga_rotors", "cache", "--warm"], env=env,
        capture_output=True, text=True,
    )  # fmt: skip
    assert warm.returncode == 0, warm.stdout + warm.stderr
    for command in (["paper"], ["run", "heavy_top", "--no-progress"]):  # run: in pieces
        done = subprocess.run(
            [sys.executable, "-m", "ga_rotors", *command, "--out", str(tmp_path / command[0])],
            env={**env, "NUMBA_DEBUG_CACHE": "1"}, capture_output=True, text=True,
        )  # fmt: skip
        assert done.returncode == 0, done.stderr
        text = done.stdout + done.stderr
        compiled = [line for line in text.splitlines() if "data saved" in line]
        assert not compiled, "\n".join(compiled)


class _WrappedInterrupt(warmup.Task):
    """Ctrl-C arriving inside a library that hands it on wrapped in an error of its own."""

    def run(self):
        try:
            raise KeyboardInterrupt
        except BaseException as exc:
            raise RuntimeError("interrupted while importing") from exc


def test_an_interruption_wrapped_by_a_library_stops_the_warm_up(cache):
    class Key:
        def to_toml(self):
            return "wrapped"

    with pytest.raises(KeyboardInterrupt):
        warmup.warm([_WrappedInterrupt("wrapped", Key()), *warmup.scene_tasks("spinning_disk")],
                    stream=io.StringIO())  # fmt: skip
    assert not (cache / "warm").exists() or not list((cache / "warm").iterdir())
