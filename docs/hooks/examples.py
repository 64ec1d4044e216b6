"""mkdocs hook: show each page's Python examples together with what they print.

The ```python blocks of a page run in order in one namespace, in a temporary working
directory, as tests/test_docs.py runs them; each block that prints is followed on the site
by an "output" block. An example that raises fails the build. Only the repository's own
docs run here: the build is a developer's command, not something a reader's input reaches.

With ``GA_ROTORS_DOCS_EXAMPLES=skip`` in the environment the pages are built without running
their examples (and so without outputs): tests/test_site.py builds the site that way, because
tests/test_docs.py already runs every example once in the suite.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import tempfile

os.environ.setdefault("MPLBACKEND", "Agg")

FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)
#: The environment variable, and its value, that leave the examples unrun.
SKIP = ("GA_ROTORS_DOCS_EXAMPLES", "skip")


def on_page_markdown(markdown: str, page, config, files) -> str:
    if not FENCE.search(markdown) or os.environ.get(SKIP[0]) == SKIP[1]:
        return markdown
    namespace = {"__name__": "docs_" + page.file.src_uri.replace("/", "_").removesuffix(".md")}
    here = os.getcwd()

    def run(match: re.Match) -> str:
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile(match.group(1), page.file.src_uri, "exec"), namespace)
        text = out.getvalue().rstrip()
        if not text:
            return match.group(0)
        return f'{match.group(0)}\n\n```text title="output"\n{text}\n```'

    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        try:
            return FENCE.sub(run, markdown)
        finally:
            os.chdir(here)
