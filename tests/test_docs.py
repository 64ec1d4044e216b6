"""Every ```python block in docs/*.md runs, so the docs cannot rot.

Blocks of one page run in order in one namespace (a page is a tutorial), inside a
temporary working directory so examples that write files leave nothing behind.
Other fences (console, text, toml) are shown to readers, not run.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parent.parent / "docs"
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)


def python_blocks(page: Path) -> list[tuple[int, str]]:
    text = page.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start()) + 2, m.group(1)) for m in FENCE.finditer(text)]


PAGES = sorted(p for p in DOCS.rglob("*.md") if python_blocks(p))


def test_docs_have_runnable_examples():
    assert PAGES, "docs/ has no page with a ```python example"


@pytest.mark.parametrize("page", PAGES, ids=[p.relative_to(DOCS).as_posix() for p in PAGES])
def test_doc_examples_run(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "docs_" + page.relative_to(DOCS).with_suffix("").as_posix()}
    for line, code in python_blocks(page):
        exec(compile(code, f"{page}:{line}", "exec"), namespace)


#: What a development diary leaves in a guide: a commit hash (7 to 40 hex digits, letters and
#: digits mixed), the machine's load average, an optimisation "round N".
DIARY = re.compile(
    r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b|load average|\bround\s+\d+\b",
    re.I,
)
#: Guides whose owners are moving their history out at the time of writing: when one comes
#: clean, its strict xfail fails and the line goes.
STILL_DIARIES: dict[str, str] = {}
GUIDES = sorted(DOCS.rglob("*.md"))


@pytest.mark.parametrize(
    "page",
    [
        pytest.param(p, marks=pytest.mark.xfail(strict=True, reason=STILL_DIARIES[p.name]))
        if p.name in STILL_DIARIES
        else p
        for p in GUIDES
    ],
    ids=[p.relative_to(DOCS).as_posix() for p in GUIDES],
)
def test_guides_are_not_diaries(page):
    text = page.read_text(encoding="utf-8")
    found = [m[0] for m in DIARY.finditer(text)]
    assert found == [], f"{page.name}: history belongs in benchmarks/NOTES.md: {found[:5]}"


def test_the_diary_pattern_finds_what_it_should():
    for diary in ("at commit e085ede", "load average 1.3", "Round 11: the draws", "since round 7"):
        assert DIARY.search(diary), diary
    for guide in ("0.0028125 kg m²", "44.45304011°", "seed 20261124", "a facade", "1e-16 rad"):
        assert not DIARY.search(guide), guide
