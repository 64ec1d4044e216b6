"""`ga-rotors prove`: every example of its help runs with the documented exit status,
bad input is one line with status 2, and the catalogue options write and check a page.
"""

from __future__ import annotations

import shlex

import pytest

from ga_rotors.cli import main
from ga_rotors.cli import prove as command

EXAMPLES = [
    line.strip()[len("ga-rotors ") :].split("#")
    for line in command.__doc__.splitlines()
    if line.strip().startswith("ga-rotors prove") and "--catalogue" not in line
]


@pytest.mark.parametrize("example", EXAMPLES, ids=[e[0][:50] for e in EXAMPLES])
def test_help_examples_run_with_their_exit_status(example, capsys):
    args = shlex.split(example[0])
    comment = example[1] if len(example) > 1 else ""
    status = (
        "refuted" if "refuted" in comment else "undecided" if "undecided" in comment else "proved"
    )
    assert main(args) == {"proved": 0, "refuted": 1, "undecided": 3}[status]
    out = capsys.readouterr().out
    assert status in out


def test_examples_cover_every_kind_of_option():
    text = " ".join(e[0] for e in EXAMPLES)
    for option in (
        "--signature",
        "--vectors",
        "--rotors",
        "--bivectors",
        "--units",
        "--orthogonal",
        "--blades",
        "--latex",
    ):
        assert option in text


def test_refuted_prints_the_counterexample(capsys):
    assert main(["prove", "a*b == b*a", "--vectors", "a,b"]) == 1
    out = capsys.readouterr().out
    assert "counterexample (exact):" in out and "lhs = " in out and "rhs = " in out


def test_undecided_exits_3_with_the_reason(capsys):
    assert main(["prove", "exp(x*e12)*exp(y*e12) == exp((x+y)*e12)", "--scalars", "x,y"]) == 3
    assert "addition theorem" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv, message",
    [
        (["prove", "a*b =="], "column 7"),
        (["prove", "a*b == c", "--vectors", "a,b"], "'c' is not declared"),
        (["prove", "a == a", "--vectors", "a", "--signature", "3"], "signature"),
        (["prove", "a == a", "--vectors", "a", "--blades", "B"], "--blades|blades"),
        (["prove", "inverse(n) == n", "--nulls", "n", "--signature", "1,3"], "not invertible"),
        (["prove", "a*b^c == 0", "--vectors", "a,b,c"], "readings differ"),
        (["prove", "a == a", "--vectors", "a", "--draws", "0"], "--draws"),
        (["prove", "a == a", "--vectors", "a", "--draws", "1000000000000"], "from 1 to"),
        (["prove", "a == a", "--vectors", "a", "--seed", "-1"], "--seed: expected an integer ≥ 0"),
        (["prove", "a == a", "--vectors", "a", "--timeout", "0"], "--timeout"),
        (["prove"], "give an identity"),
        (["prove", "a == a", "--catalogue"], "not both"),
        (["prove", "a == a", "--vectors", "a", "--long"], "go with --catalogue"),
        (["prove", "--catalogue", "--only", "nope"], "no such catalogue key"),
        (
            ["prove", "--catalogue", "--only", "jacobi", "--write", "/nonexistent/x.md"],
            "existing directory",
        ),
        (["prove", "--catalogue", "--only", "jacobi", "--check", "missing.md"], "no such file"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert any(m in err for m in message.split("|"))


def test_catalogue_write_and_check(tmp_path, capsys):
    page = tmp_path / "identities.md"
    only = ["--only", "jacobi", "--only", "bivector-square"]
    assert main(["prove", "--catalogue", *only, "--write", str(page)]) == 0
    assert "| jacobi |" in page.read_text(encoding="utf-8")
    assert main(["prove", "--catalogue", *only, "--check", str(page)]) == 0
    page.write_text(page.read_text(encoding="utf-8").replace("jacobi", "jacobi2"))
    capsys.readouterr()
    assert main(["prove", "--catalogue", *only, "--check", str(page)]) == 1
    assert "out of date" in capsys.readouterr().err


def test_catalogue_long_option_is_accepted(capsys, monkeypatch):
    # the n = 5 signatures on one cheap entry (the full long run is the long-mode test)
    assert main(["prove", "--catalogue", "--long", "--only", "wedge-self"]) == 0
    assert "Cl(4,1)" in capsys.readouterr().out
