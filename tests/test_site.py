"""The documentation site builds as the README says: ``mkdocs build --strict``, warnings counted.

The build of mkdocs.yml (mkdocs-material, mkdocstrings for the API reference from the
docstrings, docs/hooks/examples.py showing the examples' outputs, docs/hooks/mathml.py
typesetting the formulas, docs/hooks/sphinx_roles.py linking the docstrings' Sphinx roles,
docs/hooks/viewer.py putting the viewer's page on the site) runs once for this module, with
``GA_ROTORS_DOCS_EXAMPLES=skip``: tests/test_docs.py runs every example already, and the
examples hook is tested here on a page of its own. Needs the ``docs`` extra, which CI
installs.
"""

from __future__ import annotations

import logging
import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

pytest.importorskip("mkdocs")
pytest.importorskip("material")
pytest.importorskip("mkdocstrings_handlers.python")

ROOT = Path(__file__).resolve().parents[1]


def _hook(name: str):
    """A module of docs/hooks/, loaded as mkdocs loads it."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, ROOT / "docs" / "hooks" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    """The README's build (no --quiet, which would keep warnings from counting), into a
    folder of its own: (site folder, finished process)."""
    out = tmp_path_factory.mktemp("site")
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1", GA_ROTORS_DOCS_EXAMPLES="skip")
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-d", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=env,
        timeout=900,
    )
    return out, done


@pytest.fixture(scope="module")
def site(build):
    out, done = build
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return out


def test_the_strict_build_passes_without_a_warning(build):
    _, done = build
    log = done.stdout + done.stderr
    assert done.returncode == 0, log[-3000:]
    warnings = re.findall(r"^(?:WARNING|ERROR)\b.*$", log, re.M)
    assert warnings == [], "\n".join(warnings)
    assert "Documentation built in" in log  # the log was read, not an empty one


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
    # the module docstring, rendered, its formulas typeset
    intro = html.split("A rotor is an even multivector", 1)[1].split("Examples", 1)[0]
    assert intro.count("<math ") >= 4 and 'display="block"' in intro


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
    assert len(pages) == 10
    for page in pages:
        html = (site / "learn" / page.stem / "index.html").read_text(encoding="utf-8")
        solutions = html.split("<summary>Worked solution")[1:]
        assert solutions, page.name
        for solution in solutions:
            solution = solution.split("</details>", 1)[0]
            assert '<div class="highlight"><pre>' in solution, page.name  # the code, shown
        assert html.count("<details") == len(solutions), page.name  # nothing else folded


def _page(src_uri: str):
    return SimpleNamespace(file=SimpleNamespace(src_uri=src_uri))


EXAMPLE_PAGE = """# A page

```python
x = 6 * 7
print("x =", x)
```

```python
y = x + 1
```
"""


def test_examples_are_shown_with_their_output(monkeypatch):
    examples = _hook("examples")
    monkeypatch.delenv("GA_ROTORS_DOCS_EXAMPLES", raising=False)
    out = examples.on_page_markdown(EXAMPLE_PAGE, _page("page.md"), {}, None)
    printed = '```python\nx = 6 * 7\nprint("x =", x)\n```\n\n```text title="output"\nx = 42\n```'
    assert printed in out
    assert out.count('title="output"') == 1  # the second block prints nothing
    with pytest.raises(NameError):  # a failing example fails the build
        examples.on_page_markdown("```python\nno_such_name\n```\n", _page("bad.md"), {}, None)


def test_the_suite_builds_without_running_the_examples_twice(monkeypatch):
    examples = _hook("examples")
    monkeypatch.setenv(*examples.SKIP)
    page = EXAMPLE_PAGE + "```python\nraise AssertionError('must not run')\n```\n"
    assert examples.on_page_markdown(page, _page("page.md"), {}, None) == page


def test_the_viewer_plays_on_the_site(site):
    # docs/view.md frames the page ga-rotors view writes, written into the site by its hook.
    html = (site / "view" / "index.html").read_text(encoding="utf-8")
    assert '<iframe class="viewer" src="heavy_top.view.html"' in html
    page = (site / "view" / "heavy_top.view.html").read_text(encoding="utf-8")
    assert "<h1>heavy_top</h1>" in page and 'id="view-data"' in page and "ga_rotors viewer" in page
    # and the learning path's last page frames the thrown racket's flight
    html = (site / "learn" / "motors" / "index.html").read_text(encoding="utf-8")
    assert '<iframe class="viewer" src="thrown_racket.view.html"' in html
    page = (site / "learn" / "motors" / "thrown_racket.view.html").read_text(encoding="utf-8")
    assert "<h1>thrown_racket</h1>" in page and '"trail":[[' in page


#: An attribute that makes the browser fetch something: scripts, styles, fonts, images, frames.
FETCHED = re.compile(
    r"<(?:script|link|img|iframe|source|audio|video|embed|object)\b[^>]*?"
    r"\b(?:src|href|srcset|data|poster)\s*=\s*[\"']?\s*(?:https?:)?//",
    re.I,
)
CSS_FETCHED = re.compile(r"(?:url\(\s*[\"']?|@import\s+[\"'])\s*(?:https?:)?//", re.I)


def test_the_site_loads_nothing_from_other_hosts(site):
    # Links a reader follows (<a href>) may go anywhere; nothing is fetched to show a page.
    for page in site.rglob("*.html"):
        text = page.read_text(encoding="utf-8")
        assert not FETCHED.search(text), (page, FETCHED.search(text)[0])
        assert not CSS_FETCHED.search(text), page
    for sheet in site.rglob("*.css"):
        text = sheet.read_text(encoding="utf-8")
        assert not CSS_FETCHED.search(text), (sheet, CSS_FETCHED.search(text)[0])
    assert FETCHED.search('<script src="https://cdn.example/x.js">')  # the pattern works
    assert FETCHED.search("<link rel=stylesheet href=//fonts.example/css>")
    assert CSS_FETCHED.search("@font-face{src:url(https://fonts.example/a.woff2)}")


def _prose(html: str) -> str:
    """The text a reader sees outside code, scripts and typeset formulas."""
    for element in ("pre", "code", "script", "style", "math", "textarea"):
        html = re.sub(rf"<{element}\b.*?</{element}>", " ", html, flags=re.S)
    return re.sub(r"<[^>]+>", " ", html)


#: A formula left as LaTeX: \(...\), \[...\], $$, or $x$ around a LaTeX command or script.
RAW_MATH = re.compile(r"\\\(|\\\[|\$\$|\$(?=[^$\s])[^$]*?(?:\\[A-Za-z]+|[_^])[^$]*?\$")


def test_formulas_are_typeset_as_mathml(site):
    learn = sorted((ROOT / "docs" / "learn").glob("*.md"))
    pages = [f"learn/{p.stem}" if p.stem != "index" else "learn" for p in learn]
    pages += ["conventions", "api/rotations", "api/dynamics", ""]
    # the audit (generated by symbolic/audit, every finding's formulas), the guides, the
    # exact references' docstrings (elliptic functions, damped top, coning, heavy top's
    # precision) and the orientation paths' (api/integrators)
    pages += ["audit", "gyroscope", "isomorphisms", "rotations", "accuracy", "api/reference"]
    pages += ["api/integrators", "learn/motors"]
    least = {"audit": 1000, "gyroscope": 60, "isomorphisms": 20, "api/reference": 250}
    least |= {"api/integrators": 40, "learn/motors": 80}
    for name in pages:
        html = (site / name / "index.html").read_text(encoding="utf-8")
        assert html.count("<math ") >= least.get(name, 3), name
    for page in site.rglob("*.html"):
        html = page.read_text(encoding="utf-8")
        assert 'class="arithmatex"' not in html, page
        found = RAW_MATH.search(_prose(html))
        assert found is None, (page, found and found[0])
    assert RAW_MATH.search(_prose(r"<p>so $\dot q = x$ and</p>"))  # the pattern works
    assert RAW_MATH.search(_prose(r"<p>\(a_1\)</p>"))
    assert not RAW_MATH.search(_prose(r"<p>costs $5 and $6</p><code>$a_1$</code>"))


def test_a_displayed_formula_is_a_block_and_its_parts_are_marked_up(site):
    html = (site / "learn" / "kinematics" / "index.html").read_text(encoding="utf-8")
    block = html.split('<math xmlns="http://www.w3.org/1998/Math/MathML" display="block">')[1]
    block = block.split("</math>")[0]
    # R-dot = 1/2 R Omega: an over-dot, a fraction, Omega
    assert "<mover><mi>R</mi><mo>&#x002D9;</mo></mover>" in block
    assert "<mfrac><mn>1</mn><mn>2</mn></mfrac>" in block and "&#x003A9;" in block


@pytest.mark.parametrize(
    ("latex", "expected"),
    [
        # bars as fences around what they enclose, not operators between it and what follows
        (
            r"\lvert \omega \rvert h",
            "<mrow><mo>&#x0007C;</mo><mi>&#x003C9;</mi><mo>&#x0007C;</mo></mrow><mi>h</mi>",
        ),
        (r"|w| h", "<mrow><mo>&#x0007C;</mo><mi>w</mi><mo>&#x0007C;</mo></mrow><mi>h</mi>"),
        # an operator name with a digit, upright and whole, no space before its parenthesis
        (
            r"2 \operatorname{atan2}(y, x)",
            '<mo lspace="0.1667em" rspace="0">atan2</mo><mo stretchy="false">&#x00028;</mo>',
        ),
        (r"\cos\alpha", '<mo lspace="0.1667em" rspace="0.1667em">cos</mo><mi>&#x003B1;</mi>'),
        # a minus after an operator is a sign
        (r"i \mapsto -e_{23}", '<mo>&#x021A6;</mo><mo form="prefix">&#x02212;</mo>'),
        (r"\begin{aligned} a &= b \\ c &= d \end{aligned}", "<mtable"),
    ],
)
def test_mathml_of_one_formula(latex, expected):
    assert expected in _hook("mathml").to_mathml(latex)


@pytest.mark.parametrize("latex", [r"\nosuchcommand x", r"a^{", r"\left( x"])
def test_a_formula_that_does_not_typeset_is_a_warning(latex, caplog):
    mathml = _hook("mathml")
    with pytest.raises(mathml.MathError):
        mathml.to_mathml(latex)
    html = f'<p>see <span class="arithmatex">\\({latex}\\)</span></p>'
    with caplog.at_level(logging.WARNING):
        assert mathml.typeset(html, "page.md") == html  # left as it was, and
    (record,) = caplog.records  # a warning, which fails mkdocs build --strict
    assert record.levelno == logging.WARNING and "page.md" in record.getMessage()


ROLE_TEXT = (
    "`:func:",
    ":func:`",
    ":mod:`",
    ":class:`",
    ":data:`",
    ":meth:`",
    ":attr:`",
    ":math:`",
    ".. math::",
)


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
        assert not any(role in _prose(text) for role in ROLE_TEXT), page


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


@pytest.mark.parametrize(
    ("where", "role", "identifier"),
    [
        # a method inherited from the base class, named unqualified in a method's docstring
        (
            "ga_rotors.integrators.template.TemplateIntegrator.run",
            ":meth:`check_step`",
            "ga_rotors.integrators.base.Integrator.check_step",
        ),
        # a sibling method, from the class itself and from one of its methods
        (
            "ga_rotors.results.streams.NetcdfStream",
            ":meth:`append`",
            "ga_rotors.results.streams.NetcdfStream.append",
        ),
        (
            "ga_rotors.results.streams.NetcdfStream.close",
            ":meth:`append`",
            "ga_rotors.results.streams.NetcdfStream.append",
        ),
        # in a module's docstring, a method every writer has: no single target, code text
        ("ga_rotors.results.streams", ":meth:`append`", None),
    ],
)
def test_an_unqualified_role_is_resolved_from_where_it_is_written(
    roles, where, role, identifier, caplog
):
    extension, loader = roles
    obj = loader.modules_collection.get_member(where)
    with caplog.at_level(logging.WARNING):
        out = extension._reference(extension.ROLE.search(role), obj, loader)
    code = "<code>append()</code>" if "append" in role else "<code>check_step()</code>"
    if identifier is None:
        assert out == code
    else:
        assert out == f'<autoref identifier="{identifier}" optional>{code}</autoref>'
    assert not caplog.records  # nothing for --strict to fail on


def test_every_docstring_formula_typesets(roles):
    """Every :math: role and .. math:: block of the package, including the docstrings that
    only ``help()`` shows (``ga_rotors._kernels`` and other private modules), converts with
    the site's own converter."""
    extension, loader = roles
    mathml = _hook("mathml")
    failed, count, modules = [], 0, set()
    for obj in extension._walk(loader.modules_collection.get_member("ga_rotors")):
        if obj.docstring is None:
            continue
        text = obj.docstring.value
        found = [(m["tex"], False) for m in extension.MATH_ROLE.finditer(text)]
        blocks = re.findall(r"^[ \t]*\$\$\n(.*?)\n[ \t]*\$\$$", extension.typeset_math(text),
                            re.S | re.M)  # fmt: skip
        found += [(block, True) for block in blocks]
        for tex, display in found:
            count += 1
            modules.add(obj.module.path)
            try:
                mathml.to_mathml(tex, display=display)
            except mathml.MathError as err:
                failed.append(f"{obj.path}: {err}")
    assert count > 500 and "ga_rotors._kernels" in modules  # the walk reached them all
    assert failed == []


def test_docstring_math_becomes_the_sites_math(roles):
    extension, _ = roles
    docstring = (
        "Rates :math:`\\dot R = \\tfrac12 R \\Omega` and\n"
        "\n"
        ".. math::\n"
        "\n"
        "    \\dot q = \\tfrac12 q \\otimes (0, \\omega)\n"
        "      + 0\n"
        "\n"
        "after the block.\n"
    )
    assert extension.typeset_math(docstring) == (
        "Rates $\\dot R = \\tfrac12 R \\Omega$ and\n"
        "\n"
        "$$\n"
        "\\dot q = \\tfrac12 q \\otimes (0, \\omega)\n"
        "  + 0\n"
        "$$\n"
        "\n"
        "after the block.\n"
    )


def _closure(requirements) -> set[str]:
    """The installed distributions ``requirements`` (strings as in a package's metadata)
    bring, recursively; environment markers are ignored (every branch counts)."""
    import importlib.metadata as md

    from packaging.requirements import Requirement

    seen: set[str] = set()
    todo = [Requirement(r) for r in requirements]
    while todo:
        req = todo.pop()
        name = req.name.lower().replace("_", "-")
        key = f"{name}{sorted(req.extras)}"
        if key in seen:
            continue
        seen.add(key)
        seen.add(name)
        try:
            dist = md.distribution(name)
        except md.PackageNotFoundError:
            continue
        for text in dist.requires or []:
            sub = Requirement(text)
            wanted = (
                sub.marker is None
                or any(f'extra == "{e}"' in str(sub.marker) for e in req.extras)
                or "extra ==" not in str(sub.marker)
            )
            if wanted:
                todo.append(sub)
    return seen


def test_the_docs_extra_brings_every_package_the_pages_examples_import():
    """The README's docs command installs ``.[docs]`` on top of the package: the examples
    the build runs may import only what that brings (cf_xarray and pint-xarray were once
    only in the test extra, and the command failed on a fresh machine)."""
    import ast
    import importlib.metadata as md

    closure = _closure(["ga-rotors[docs]"])
    providers = md.packages_distributions()
    pages = sorted((ROOT / "docs").rglob("*.md"))
    hook = _hook("examples")
    missing = set()
    for page in pages:
        for block in hook.FENCE.findall(page.read_text(encoding="utf-8")):
            for node in ast.walk(ast.parse(block)):
                names = []
                if isinstance(node, ast.Import):
                    names = [a.name for a in node.names]
                elif isinstance(node, ast.ImportFrom) and not node.level:
                    names = [node.module]
                for module in (n.split(".")[0] for n in names):
                    if module in sys.stdlib_module_names or module == "ga_rotors":
                        continue
                    dists = {d.lower().replace("_", "-") for d in providers.get(module, [])}
                    if not dists & closure:
                        missing.add(f"{page.name}: {module}")
    assert not missing, sorted(missing)
