"""The ``ga-rotors`` command itself: its version, a bare call, the command table, ``-m``."""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import pytest

from ga_rotors.cli import COMMANDS, main

ROOT = Path(__file__).resolve().parent.parent


def test_version_is_the_distributions_and_printed_by_the_command(capsys):
    import ga_rotors

    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0
    assert capsys.readouterr().out == f"ga-rotors {version('ga-rotors')}\n"
    assert ga_rotors.__version__ == version("ga-rotors")


def test_the_version_is_written_once_in_pyproject():
    # The package reads it from the installed metadata; no second copy in the sources.
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    written = version("ga-rotors")
    assert f'version = "{written}"' in text
    copies = [
        p.relative_to(ROOT)
        for p in (ROOT / "ga_rotors").rglob("*.py")
        if f'"{written}"' in p.read_text(encoding="utf-8")
    ]
    assert not copies


def test_bare_command_lists_every_command_and_exits_0(capsys):
    assert main([]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: ga-rotors")
    for name in COMMANDS:
        assert f"    {name} " in out, name


def test_every_command_is_a_module_of_the_cli_package_with_the_protocol():
    for name, modname in COMMANDS.items():
        assert modname == f"ga_rotors.cli.{name}"
        module = importlib.import_module(modname)
        assert callable(module.add_arguments) and callable(module.run)
        assert (module.__doc__ or "").strip(), f"{modname}: the docstring is the command's help"


def test_unknown_command_is_refused_by_argparse(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["no-such-command"])
    assert exit_.value.code == 2
    assert "invalid choice: 'no-such-command'" in capsys.readouterr().err


def test_python_dash_m_ga_rotors_runs_the_command():
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.run(
        [sys.executable, "-m", "ga_rotors", "--version"],
        env=env, capture_output=True, text=True, timeout=120, cwd=ROOT,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == f"ga-rotors {version('ga-rotors')}"
    bare = subprocess.run(
        [sys.executable, "-m", "ga_rotors"],
        env=env, capture_output=True, text=True, timeout=120, cwd=ROOT,
    )  # fmt: skip
    assert bare.returncode == 0 and "scenes" in bare.stdout


def test_building_the_parser_imports_no_heavy_library():
    # ga-rotors --help and every command's argument parsing stay fast: heavy imports
    # happen inside a command's run.
    code = (
        "import sys\n"
        "from ga_rotors.cli import build_parser\n"
        "build_parser()\n"
        "heavy = ('numpy', 'sympy', 'clifford', 'scipy', 'numba', 'matplotlib',\n"
        "         'importlib.metadata')  # the version is read only for --version\n"
        "print([m for m in heavy if m in sys.modules])"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=ROOT, capture_output=True, text=True
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[]"
