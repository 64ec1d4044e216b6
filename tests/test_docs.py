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
