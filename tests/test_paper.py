"""`ga-rotors paper`: files written, figures current, errors reported without tracebacks."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ga_rotors import cli
from ga_rotors.paper import figures as paper_figures
from ga_rotors.paper.digest import data_digest
from ga_rotors.paper.runs import run_all

ROOT = Path(__file__).resolve().parent.parent
DIGEST = data_digest(run_all())


def test_committed_figures_show_what_the_code_computes():
    figures = sorted((ROOT / "docs" / "figures").glob("*.png"))
    assert {p.stem for p in figures} == set(paper_figures.FIGURES)
    for png in figures:
        assert paper_figures.read_digest(png) == DIGEST, (
            f"{png.name} is stale: run ga-rotors paper --out docs/figures --figures-only"
        )


def test_data_and_summary_are_written(tmp_path, capsys):
    assert cli.main(["paper", "--out", str(tmp_path / "new"), "--no-figures"]) == 0
    out = capsys.readouterr().out
    assert "rotor-quat" in out and "disk_0.001deg" in out
    names = sorted(p.name for p in (tmp_path / "new").iterdir())
    csvs = ["paper_15deg.csv", "paper_0.001deg.csv", "disk_15deg.csv", "disk_0.001deg.csv"]
    assert names == sorted(["summary.txt", *csvs, *(f"{n}-metadata.json" for n in csvs)])
    text = (tmp_path / "new" / "paper_0.001deg.csv").read_text()
    header = text.splitlines()[0].split(",")
    assert header[:4] == ["t [s]", "w_1 [rad/s]", "w_2 [rad/s]", "w_3 [rad/s]"]
    assert "error_euler [rad]" in header
    assert "nan" not in text.lower()
    data = np.loadtxt(tmp_path / "new" / "disk_15deg.csv", delimiter=",", skiprows=1)
    assert data.shape == (10001, len(header))
    # docs/gyroscope.md shows this table; its rotor, quaternion and |R| columns (set by
    # RK4's error, not by rounding) must be what the command prints. The rounding-level
    # rotor-quat column and the Euler path's near-pole figures may differ across machines.
    doc = (ROOT / "docs" / "gyroscope.md").read_text(encoding="utf-8")
    shown = doc.split("```text\n", 1)[1].split("```", 1)[0].splitlines()[1:]
    printed = [ln for ln in out.splitlines() if ln.split()[:1] and ln.split()[0] in _SCENES]
    assert len(shown) == len(printed) == 4
    for a, b in zip(shown, printed, strict=True):
        cols_a, cols_b = a.split(), b.split()
        assert [cols_a[i] for i in (0, 2, 3, 5)] == [cols_b[i] for i in (0, 2, 3, 5)], (a, b)


_SCENES = ("paper_15deg", "paper_0.001deg", "disk_15deg", "disk_0.001deg")


def test_full_command_draws_every_figure_in_its_worker(tmp_path):
    # A subprocess, so the forked figure worker runs as it does for users.
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
    proc = subprocess.run(
        [sys.executable, "-m", "ga_rotors", "paper", "--out", str(tmp_path)],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert "wrote 19 files" in proc.stdout  # 10 figures, summary, 4 CSV and their metadata
    for stem in paper_figures.FIGURES:
        assert paper_figures.read_digest(tmp_path / f"{stem}.png") == DIGEST
    assert not list(tmp_path.glob(".*.tmp"))


def test_worker_shares_cover_every_figure_once():
    from ga_rotors.paper.reproduce import _SHARES

    drawn = [stem for share in _SHARES for stem in share]
    assert sorted(drawn) == sorted(paper_figures.FIGURES)


def test_out_that_is_a_file_is_refused_without_traceback(tmp_path, capsys):
    target = tmp_path / "taken"
    target.write_text("x")
    assert cli.main(["paper", "--out", str(target)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ga-rotors: error: --out:") and "Traceback" not in err


def test_figure_worker_failure_is_reported(tmp_path, monkeypatch):
    from ga_rotors.errors import GaRotorsError
    from ga_rotors.paper import reproduce

    # a share naming a figure that does not exist: its drawing process fails
    monkeypatch.setattr(reproduce, "_SHARES", (*reproduce._SHARES, ("no_such_figure",)))
    (tmp_path / "summary.txt").write_text("the previous run's")
    says = "drawing the figures failed: KeyError: 'no_such_figure'"
    with pytest.raises(GaRotorsError, match=says):
        reproduce.reproduce(tmp_path, data=True, parallel=True)
    # All or nothing: the data were written before the figures failed, and are not moved
    # in; the previous set stays, and no staging folder or temporary file is left.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["summary.txt"]
    assert (tmp_path / "summary.txt").read_text() == "the previous run's"
