"""Packaging: ``symbolic/`` installs as ``ga_rotors.symbolic``, never as a top-level package.

The repository keeps ``symbolic/`` at its top level; ``ga_rotors/symbolic`` is a symbolic
link to it, so ``ga_rotors.symbolic`` resolves the same way from an installed wheel, from
an editable install and from the source tree that shadows an installed copy (CI runs the
suite from the repository root after a non-editable ``pip install ".[test]"``). A top-level
``symbolic`` would overwrite the unrelated PyPI package of that name.
"""

from __future__ import annotations

import re
import tomllib
from importlib.metadata import distribution, distributions
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def test_ga_rotors_symbolic_is_the_repositorys_symbolic_folder():
    link = ROOT / "ga_rotors" / "symbolic"
    assert link.is_symlink() and link.resolve() == (ROOT / "symbolic").resolve()
    import ga_rotors.symbolic.audit

    assert Path(ga_rotors.symbolic.audit.__file__).resolve().parent == ROOT / "symbolic" / "audit"


def test_the_configuration_packages_ga_rotors_only():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert config["tool"]["setuptools"]["packages"]["find"]["include"] == ["ga_rotors*"]
    # what setuptools' discovery makes of it, from this tree
    setuptools = pytest.importorskip("setuptools")
    found = setuptools.find_packages(str(ROOT), include=["ga_rotors*"])
    assert "ga_rotors.symbolic" in found and "ga_rotors.symbolic.audit" in found
    assert not [p for p in found if not p.startswith("ga_rotors")]


def installed_files() -> list[str] | None:
    """Paths in the RECORD of an installed (not editable) ga-rotors, or None.

    The RECORD, not ``Distribution.files``: from the repository root a build's
    ``ga_rotors.egg-info`` is found first, and its files are the source tree's.
    """
    for dist in distributions(name="ga-rotors"):
        record = dist.read_text("RECORD")
        if record:
            paths = [row.rsplit(",", 2)[0] for row in record.splitlines() if row]
            if "ga_rotors/__init__.py" in paths:
                return paths
    return None


def test_the_installed_distribution_has_no_top_level_symbolic():
    files = installed_files()
    if files is None:
        pytest.skip("no installed wheel (an editable install); CI installs the wheel")
    assert "ga_rotors/symbolic/__init__.py" in files
    assert "ga_rotors/symbolic/audit/__init__.py" in files
    tops = {f.split("/")[0] for f in files if not f.split("/")[0].endswith(".dist-info")}
    tops -= {"..", "bin"}  # the console script, installed beside site-packages
    assert tops == {"ga_rotors"}, tops


def test_the_metadata_a_user_sees():
    meta = distribution("ga-rotors").metadata
    assert meta["License"] == "MIT" or "MIT" in (meta.get("License-Expression") or "")
    classifiers = meta.get_all("Classifier") or []
    assert "License :: OSI Approved :: MIT License" in classifiers
    assert any(c.startswith("Programming Language :: Python :: 3") for c in classifiers)
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License")
    assert re.fullmatch(r"\d+\.\d+\.\d+", meta["Version"])
