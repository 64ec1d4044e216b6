"""The documentation site builds strictly: a broken link, a missing page or a failing example fails.

``mkdocs build --strict`` on mkdocs.yml (mkdocs-material, mkdocstrings for the API
reference from the docstrings, docs/hooks/examples.py showing the examples' outputs,
docs/hooks/sphinx_roles.py linking the docstrings' Sphinx roles, docs/hooks/viewer.py
putting the viewer's page on the site).
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


def test_module_constants_are_documented_by_their_comments(site):
    # ga_rotors.euler: "#: The 24 valid sequences ..." above SEQUENCES (griffe-sphinx), so
    # the constant has its entry and :data:`SEQUENCES` elsewhere links to it.
    html = (site / "api" / "rotations" / "index.html").read_text(encoding="utf-8")
    assert 'id="ga_rotors.euler.SEQUENCES"' in html
    assert 'href="#ga_rotors.euler.SEQUENCES"' in html


def test_every_public_module_is_in_the_api_reference():
    """Every module a user can import by a public name (no ``_`` in its path) has its
    section in docs/api/, except the command-line modules (``--help`` and the guides)."""
    import pkgutil
    import re

    import ga_rotors

    shown = set()
    for page in (ROOT / "docs" / "api").glob("*.md"):
        shown |= set(re.findall(r"^::: ([\w.]+)", page.read_text(encoding="utf-8"), re.M))
    public = {"ga_rotors"}
    for info in pkgutil.walk_packages(ga_rotors.__path__, "ga_rotors."):
        parts = info.name.split(".")
        if not any(p.startswith("_") for p in parts) and parts[1] != "cli":
            public.add(info.name)
    assert public - shown == set(), "add to a page of docs/api/"
    assert shown - public == set(), "docs/api/ names a module that is gone"


def test_learning_path_solutions_are_folded_and_checked(site):
    # A student reads the exercise first; the worked solution (code the suite runs, with
    # its output) opens on request.
    pages = sorted(p for p in (ROOT / "docs" / "learn").glob("*.md") if p.name != "index.md")
    assert len(pages) == 9
    for page in pages:
        html = (site / "learn" / page.stem / "index.html").read_text(encoding="utf-8")
        solution = html.split("<summary>Worked solution", 1)[1].split("</details>", 1)[0]
        assert '<div class="highlight"><pre>' in solution, page.name  # the code, shown
        assert html.count("<details") == 1, page.name


def test_examples_are_shown_with_their_output(site):
    html = (site / "view" / "index.html").read_text(encoding="utf-8")
    assert "View('a wobbling disk', paths=rotor, quaternion, 2001 samples)" in html


def test_the_viewer_plays_on_the_site(site):
    # docs/view.md frames the page ga-rotors view writes, written into the site by its hook.
    html = (site / "view" / "index.html").read_text(encoding="utf-8")
    assert '<iframe class="viewer" src="heavy_top.view.html"' in html
    page = (site / "view" / "heavy_top.view.html").read_text(encoding="utf-8")
    assert "<h1>heavy_top</h1>" in page and 'id="view-data"' in page and "ga_rotors viewer" in page


def test_the_site_loads_nothing_from_other_hosts(site):
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        assert "fonts.googleapis.com" not in text, page


ROLE_TEXT = ("`:func:", ":func:`", ":mod:`", ":class:`", ":data:`", ":meth:`", ":attr:`")


def test_sphinx_roles_in_docstrings_become_links_or_code(site):
    # ga_rotors.scene.run's docstring: :func:`ga_rotors.simulation.simulate`, rendered on
    # the dynamics page, and :data:`ga_rotors.scene.budget.DEFAULT` on this one; the
    # Scene's :attr:`exact_reason` (set in __init__, no entry of its own) is code.
    html = (site / "api" / "scenes" / "index.html").read_text(encoding="utf-8")
    simulate = (
        'href="../dynamics/#ga_rotors.simulation.simulate"><code>ga_rotors.simulation.simulate()'
    )
    assert simulate in html
    assert (
        'href="#ga_rotors.scene.budget.DEFAULT"><code>ga_rotors.scene.budget.DEFAULT</code>' in html
    )
    assert (
        '<span title="ga_rotors.scene.model.Scene.exact_reason"><code>exact_reason</code>' in html
    )
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        assert not any(role in text for role in ROLE_TEXT), page


@pytest.fixture(scope="module")
def roles():
    """The griffe extension (docs/hooks/sphinx_roles.py) and a loader holding ga_rotors."""
    import importlib.util

    import griffe

    path = ROOT / "docs" / "hooks" / "sphinx_roles.py"
    spec = importlib.util.spec_from_file_location("sphinx_roles", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    loader = griffe.GriffeLoader(search_paths=[str(ROOT)])
    loader.load("ga_rotors")
    return module, loader


@pytest.mark.parametrize(
    ("role", "shown", "identifier"),
    [
        (":func:`run_scene`", "run_scene()", "ga_rotors.scene.run.run_scene"),
        (":class:`~ga_rotors.scene.Scene`", "Scene", "ga_rotors.scene.model.Scene"),
        (":mod:`ga_rotors.view`", "ga_rotors.view", "ga_rotors.view"),
        (
            ":attr:`Scene.exact_reason`",
            "Scene.exact_reason",
            "ga_rotors.scene.model.Scene.exact_reason",
        ),
        (
            ":meth:`the replace method <ga_rotors.scene.Scene.replace>`",
            "the replace method",
            "ga_rotors.scene.model.Scene.replace",
        ),
        (":class:`numpy.ndarray`", "numpy.ndarray", None),
        (":func:`ga_rotors.scene.no_such_function`", "ga_rotors.scene.no_such_function()", None),
    ],
)
def test_a_role_is_resolved_where_sphinx_would_look(roles, role, shown, identifier, caplog):
    import logging

    extension, loader = roles
    module = loader.modules_collection.get_member("ga_rotors.scene.run")  # where the role sits
    with caplog.at_level(logging.INFO):
        out = extension._reference(extension.ROLE.search(role), module, loader)
    code = f"<code>{shown}</code>"
    if identifier is None:
        assert out == code
    else:
        assert out == f'<autoref identifier="{identifier}" optional>{code}</autoref>'
    # A ga_rotors name that does not exist is a warning: the strict build fails on it.
    warned = [r for r in caplog.records if r.levelno >= logging.WARNING]
    assert bool(warned) == ("no_such" in role)
