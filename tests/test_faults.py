"""Faults while a command writes (issue 11): SIGTERM, two commands into one --out.

Every command that writes leaves its complete new output or the previous one, never a
partial set, and no debris (staging folders, temporary files). The random kill/SIGTERM/
disk-full trials are in benchmarks/faults.py (counts in docs/stability.md); these are the
deterministic cases.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from ga_rotors import cli

ROOT = Path(__file__).resolve().parent.parent
SCENE = "spinning_disk"
ARGS = ["--no-progress"]


def _scene(tmp_path, duration: float) -> Path:
    path = tmp_path / f"disk_{duration:g}.toml"
    path.write_text(
        '[scene]\nname = "disk"\n[body]\nshape = "disk"\nmass = 1.0\nradius = 0.1\n'
        '[initial.angular_velocity]\nbody = [0.1, 0.0, 10.0]\nunits = "rad/s"\n'
        f'[time]\nduration = {duration}\n[integrator]\nstep = 0.01\npaths = ["quaternion"]\n'
        '[output]\ndata = ["csv", "npz"]\n'
    )
    return path


def _listing(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


@pytest.mark.skipif(not hasattr(signal, "SIGTERM"), reason="POSIX signals")
def test_sigterm_while_writing_leaves_the_previous_set(tmp_path, monkeypatch, capsys):
    out = tmp_path / "out"
    handler = signal.getsignal(signal.SIGTERM)
    assert cli.main(["run", str(_scene(tmp_path, 0.1)), "--out", str(out), *ARGS]) == 0
    before = {p: p.read_bytes() for p in out.iterdir()}
    from ga_rotors.results.streams import NpzStream

    real = NpzStream.close

    def killed_midway(self, meta):
        real(self, meta)  # the CSV and this file are written in the staging folder...
        os.kill(os.getpid(), signal.SIGTERM)  # ...when the run is told to stop

    monkeypatch.setattr(NpzStream, "close", killed_midway)
    capsys.readouterr()
    assert cli.main(["run", str(_scene(tmp_path, 0.2)), "--out", str(out), *ARGS]) == 143
    assert "terminated (SIGTERM)" in capsys.readouterr().err
    assert {p: p.read_bytes() for p in out.iterdir()} == before
    assert _listing(tmp_path) == sorted(
        ["disk_0.1.toml", "disk_0.2.toml", "out", *(f"out/{p.name}" for p in before)]
    )
    assert signal.getsignal(signal.SIGTERM) is handler  # main() put it back


def test_two_runs_into_one_new_out_give_one_complete_set(tmp_path):
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    procs = [
        subprocess.Popen(
            [sys.executable, "-m", "ga_rotors", "run", str(_scene(tmp_path, d)), "--out",
             str(out), *ARGS],
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        )
        for d in (0.1, 0.2)
    ]  # fmt: skip
    for p in procs:
        assert p.wait(timeout=300) == 0, p.stderr.read()
    names = [
        "disk.csv",
        "disk.csv-metadata.json",
        "disk.npz",
        "disk.scene.toml",
        "disk.summary.txt",
    ]
    assert _listing(out) == names
    # One run's set, not a mix: the scene file written with the data says which.
    duration = "0.1" if "duration = 0.1" in (out / "disk.scene.toml").read_text() else "0.2"
    rows = (out / "disk.csv").read_text().count("\n") - 1  # the headers
    assert rows == {"0.1": 11, "0.2": 21}[duration]
