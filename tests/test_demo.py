"""`ga-rotors demo`: runs, reports agreement at round-off, refuses bad arguments cleanly."""

from __future__ import annotations

import re

from ga_rotors.cli import main


def test_demo_runs_and_reports_round_off_agreement(capsys):
    assert main(["demo", "--count", "20", "--seed", "3"]) == 0
    out = capsys.readouterr().out
    gap = float(re.search(r"between R1 R2 and q1 q2:\s+(\S+) rad", out).group(1))
    assert gap <= 2e-15  # a few roundings of a composed rotation, doubled by the angle
    assert "1e-300 -> 1e-300" in out and "locked=True" in out


def test_demo_rejects_a_bad_count_without_traceback(capsys):
    assert main(["demo", "--count", "0"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ga-rotors: error: --count") and "Traceback" not in err


def test_demo_refuses_a_count_too_large_and_a_negative_seed_in_one_line(capsys):
    # found by a probe: 10^11 died allocating 2.9 TiB, a negative seed in numpy's traceback
    assert main(["demo", "--count", "100000000000"]) == 2
    assert "--count: at most 100000 rotations" in capsys.readouterr().err
    assert main(["demo", "--seed", "-1"]) == 2
    err = capsys.readouterr().err
    assert "--seed: expected an integer ≥ 0, got -1" in err and err.count("\n") == 1
