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
        "--define",
        "--euclidean",
        "--motors",
        "--points",
        "--lines",
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


def test_every_verdict_prints_the_identity_as_read(capsys):
    for argv, status in [
        (["prove", "(a^b)|c == a*(b|c) - b*(a|c)", "--vectors", "a,b,c"], 0),
        (["prove", "a*b == b*a", "--vectors", "a,b"], 1),
        (["prove", "exp(x*e12)*exp(y*e12) == exp((x+y)*e12)", "--scalars", "x,y"], 3),
    ]:
        assert main(argv) == status
        lines = capsys.readouterr().out.splitlines()
        assert lines[1].startswith("  read as: ")
    assert main(["prove", "(a^b)|c == 0", "--vectors", "a,b,c"]) == 1
    assert "read as: (a ^ b) | c == 0" in capsys.readouterr().out


def test_definitions_name_expressions_and_are_checked(capsys):
    argv = ["prove", "T*~T == 1", "--signature", "4,1", "--euclidean", "t"]
    assert main([*argv, "--define", "T=1 + einf*t/2"]) == 0
    assert "where: T = 1 + ((einf * t) / 2)" in capsys.readouterr().out
    defines = ["--define", "T=a", "--define", "S=T*T"]
    assert main(["prove", "S == T*T", "--vectors", "a", *defines]) == 0
    capsys.readouterr()
    for defines, message in [
        (["T=S", "S=a"], "defined after it"),
        (["T=T*a"], "defined after it"),
        (["a=1"], "already declared"),
        (["e1=1"], "basis blade name"),
        (["T"], "NAME=EXPRESSION"),
        (["T=a*b^a"], "define T: expression: the readings differ"),
    ]:
        extra = [x for d in defines for x in ("--define", d)]
        assert main(["prove", "a == a", "--vectors", "a,b", *extra]) == 2, defines
        assert message in capsys.readouterr().err


def test_a_400_digit_integer_is_exact_not_an_overflow(capsys):
    # issue 30: an OverflowError in the numeric pre-check; the proof is exact
    big = "9" * 400
    assert main(["prove", f"a*{big} == {big}*a", "--vectors", "a"]) == 0
    assert main(["prove", f"a*{big} == a", "--vectors", "a"]) == 1
    captured = capsys.readouterr()
    assert "Warning" not in captured.err and captured.err == ""


def test_timeout_inf_is_no_limit_and_nan_is_refused(capsys):
    # issue 30: --timeout inf ended in signal.setitimer's OverflowError
    assert main(["prove", "a^a == 0", "--vectors", "a", "--timeout", "inf"]) == 0
    assert main(["prove", "a^a == 0", "--vectors", "a", "--timeout", "1e300"]) == 0
    assert main(["prove", "a^a == 0", "--vectors", "a", "--timeout", "nan"]) == 2
    assert "--timeout" in capsys.readouterr().err


LONG = "x" * 1900


@pytest.mark.parametrize(
    "argv",
    [
        ["prove", f"{LONG} == 0"],
        ["prove", f"{LONG}(a) == 0"],
        ["prove", "a == 0", "--vectors", LONG],
        ["prove", "a == 0", "--vectors", "a", "--signature", LONG],
        ["prove", "a == 0", "--vectors", "a", "--blades", f"B:{LONG}"],
        ["prove", "a == 0", "--vectors", "a", "--define", f"T={LONG}"],
        ["prove", "a == 0", "--vectors", "a", "--define", f"{LONG}=a"],
        ["prove", "a == 0", "--vectors", "a", "--orthogonal", f"a,{LONG}"],
        ["prove", "--catalogue", "--only", LONG],
        ["prove", "--catalogue", "--only", "jacobi", "--write", f"/nonexistent/{LONG}"],
        ["prove", "(" + "a*" * 300 + "a) == a", "--vectors", "a"],
        ["prove", "a\x1b[2J == a", "--vectors", "a"],
    ],
    ids=range(12),
)
def test_an_error_is_one_short_line_without_control_characters(argv, capsys):
    # issue 30, item 11: echoes are cut, never kilobytes, never raw escapes
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and len(err) < 300, err[:300]
    assert "\x1b" not in err
