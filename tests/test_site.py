"""The documentation site builds strictly: a broken link, a missing page or a failing example fails.

``mkdocs build --strict`` on mkdocs.yml (mkdocs-material, mkdocstrings for the API
reference from the docstrings, docs/hooks/examples.py showing the examples' outputs).
Needs the ``docs`` extra, which CI installs.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("mkdocs")
pytest.importorskip("material")
pytest.importorskip("mkdocstrings_handlers.python")

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1")
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--quiet", "-d", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=env,
        timeout=900,
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return out


def test_every_docs_page_is_in_the_site(site):
    pages = {p.relative_to(ROOT / "docs").with_suffix("") for p in (ROOT / "docs").rglob("*.md")}
    for page in pages:
        built = site / ("" if page.name == "index" else page) / "index.html"
        if page.name == "index":
            built = site / page.parent / "index.html"
        assert built.is_file(), f"docs/{page}.md was not built"


def test_every_docs_page_is_in_the_navigation():
    import re

    nav = set(re.findall(r"([\w/.-]+\.md)\s*$", (ROOT / "mkdocs.yml").read_text(), re.M))
    pages = {p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").rglob("*.md")}
    assert pages == nav, f"add to mkdocs.yml's nav: {sorted(pages - nav)}"


def test_api_reference_is_generated_from_the_docstrings(site):
    html = (site / "api" / "rotations" / "index.html").read_text(encoding="utf-8")
    assert 'id="ga_rotors.rotor.from_axis_angle"' in html
    assert "cos(α/2) − I u sin(α/2)" in html  # the module docstring, rendered


def test_examples_are_shown_with_their_output(site):
    html = (site / "view" / "index.html").read_text(encoding="utf-8")
    assert "View('a wobbling disk', paths=rotor, quaternion, 2001 samples)" in html


def test_the_site_loads_nothing_from_other_hosts(site):
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        assert "fonts.googleapis.com" not in text, page
