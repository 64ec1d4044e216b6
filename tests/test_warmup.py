"""Compiling ahead: tasks, parallel workers, markers, and the commands that warm themselves."""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

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


def test_warm_runs_each_task_once_in_parallel_workers_and_remembers_it(cache):
    tasks = warmup.scene_tasks("heavy_top")
    log = io.StringIO()
    assert warmup.warm(tasks, processes=2, stream=log) == []
    lines = log.getvalue().splitlines()
    assert lines[0].startswith("ga-rotors: compiling 2 loop set(s) in 2 process(es)")
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
    failed = warmup.warm([bad, *warmup.scene_tasks("spinning_disk")], processes=2, stream=log)
    assert [(t.label, e.split(":")[0]) for t, e in failed] == [("broken", "TypeError")]
    assert "broken (" in log.getvalue() and "failed: TypeError" in log.getvalue()
    assert len(list((cache / "warm").iterdir())) == len(warmup.scene_tasks("spinning_disk"))


def test_one_process_runs_the_tasks_here(cache):
    log = io.StringIO()
    assert warmup.warm(warmup.scene_tasks("spinning_disk"), processes=1, stream=log) == []
    assert "in 1 process(es)" in log.getvalue()


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
    assert "ga-rotors: compiling" in err and "in 1 process(es)" in err
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
    assert "ga-rotors: compiling 4 loop set(s) in 1 process(es)" in err
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

class Quick(warmup.Task):
    def run(self):
        pass

class Slow(warmup.Task):
    def run(self):
        time.sleep(120)

real = warmup.scene_tasks("spinning_disk")
tasks = {
    "two waiting": [Quick("quick", Name("q")), Slow("s1", Name("s1")), Slow("s2", Name("s2"))],
    "compiling": [real[0], Slow("slow", Name("s"))],
    "again": real,
}[sys.argv[1]]
warmup.all_tasks = lambda: tasks
sys.exit(main(["cache", "--warm"]))
"""


def _children(pid: int) -> list[int]:
    path = Path(f"/proc/{pid}/task/{pid}/children")
    return [int(p) for p in path.read_text().split()] if path.exists() else []


def _start_warm(
    which: str, env: dict, workers: int, after: str | None = None
) -> tuple[subprocess.Popen, list[int]]:
    """``cache --warm`` in a subprocess, once ``workers`` of its workers run (after the
    progress line of the task ``after``, whose worker has then been reaped)."""
    proc = subprocess.Popen(
        [sys.executable, "-c", _WARM, which], env=env, text=True,
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
    )  # fmt: skip
    assert "compiling" in proc.stdout.readline()
    if after is not None:
        assert f"] {after} (" in proc.stdout.readline()
    deadline = time.monotonic() + 60
    while len(kids := _children(proc.pid)) < workers and time.monotonic() < deadline:
        time.sleep(0.05)
    assert len(kids) == workers, proc.stdout.read()
    return proc, kids


needs_proc = pytest.mark.skipif(
    not Path(f"/proc/{os.getpid()}/task/{os.getpid()}/children").exists(),
    reason="lists a process's children through Linux's /proc",
)


@needs_proc
@pytest.mark.parametrize(
    ("signum", "status", "line"),
    [(signal.SIGINT, 130, "ga-rotors: interrupted"), (signal.SIGTERM, 143, "terminated")],
)
def test_stopping_a_warm_up_stops_its_workers(tmp_path, signum, status, line):
    env = {**os.environ, "GA_ROTORS_CACHE_DIR": str(tmp_path)}
    proc, workers = _start_warm("two waiting", env, workers=2, after="quick")
    proc.send_signal(signum)
    assert proc.wait(timeout=30) == status, proc.stdout.read()
    assert line in proc.stdout.read()
    assert not [pid for pid in workers if Path(f"/proc/{pid}").exists()]


@needs_proc
def test_a_warm_up_killed_while_compiling_leaves_a_usable_cache(tmp_path):
    env = {**os.environ, "GA_ROTORS_CACHE_DIR": str(tmp_path)}
    proc, workers = _start_warm("compiling", env, workers=1)
    time.sleep(0.3)  # into the compilation
    proc.terminate()
    assert proc.wait(timeout=30) == 143
    assert not Path(f"/proc/{workers[0]}").exists()
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


class _Dies(warmup.Task):
    """A task whose worker is killed (out of memory, a user's kill -9) before it reports."""

    def run(self):
        os.kill(os.getpid(), signal.SIGKILL)


class _Quick(warmup.Task):
    def run(self):
        pass


def test_a_worker_killed_before_reporting_is_a_failed_task_not_an_error(cache):
    class Key:
        def __init__(self, text):
            self.text = text

        def to_toml(self):
            return self.text

    log = io.StringIO()
    failed = warmup.warm([_Quick("quick", Key("q")), _Dies("dies", Key("d"))], 2, stream=log)
    assert [(t.label, e) for t, e in failed] == [("dies", "the worker was killed (signal 9)")]
    assert "dies (0.0 s) failed: the worker was killed" in log.getvalue()


def test_a_result_cut_short_is_reported_as_such():
    assert warmup._result(b"(1.5, None)", 0) == (1.5, None)
    assert warmup._result(b"(1.5, 'Type", 0) == (
        0.0,
        "the worker ended while reporting its result",
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
