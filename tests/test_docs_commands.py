"""Every ``ga-rotors`` command option that README.md or a docs page shows is exercised by
some test: a test function whose string constants hold both the command and the option
(as ``main(["run", ..., "--out", ...])`` or a shell line do).

This is a static check of the suite itself, so that a documented option cannot go
untested unnoticed (``scenes --figures`` and ``sweep --scheduler`` had no test until this
check found them). ``ga-rotors prove``'s help examples are run one by one by
tests/test_prove_cli.py, so their options count as exercised.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from ga_rotors.cli import prove as prove_command

ROOT = Path(__file__).resolve().parent.parent
COMMAND = re.compile(r"(?:ga-rotors|python -m ga_rotors)\s+([a-z][a-z-]*)([^\n`]*)")
OPTION = re.compile(r"(?<![\w-])(--[a-z][\w-]*)")


def documented() -> dict[tuple[str, str], set[str]]:
    """(command, option) -> the pages showing it."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    found: dict[tuple[str, str], set[str]] = {}
    for page in pages:
        for m in COMMAND.finditer(page.read_text(encoding="utf-8")):
            for option in OPTION.findall(m.group(2)):
                found.setdefault((m.group(1), option), set()).add(str(page.relative_to(ROOT)))
    return found


def _strings(node) -> set[str]:
    out = set()
    for sub in ast.walk(node):
        if isinstance(sub, ast.Constant) and isinstance(sub.value, str):
            out.add(sub.value)
            out.update(sub.value.split())
    return {s.split("=")[0] for s in out}


def exercised() -> list[set[str]]:
    """The string tokens of each test function (its body and its decorators)."""
    tests = []
    for path in sorted((ROOT / "tests").glob("test_*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef) and node.name.startswith("test"):
                tokens = _strings(node)
                for decorator in node.decorator_list:
                    tokens |= _strings(decorator)
                tests.append(tokens)
    prove_examples = " ".join(
        line for line in prove_command.__doc__.splitlines() if "ga-rotors prove" in line
    )
    tests.append({"prove", *prove_examples.split()})
    return tests


def test_the_documents_show_commands_with_options():
    found = documented()
    assert ("run", "--out") in found and ("sweep", "--scheduler") in found  # the scan works


def test_every_documented_option_is_exercised_by_a_test():
    tests = exercised()
    missing = [
        f"ga-rotors {command} {option} (shown in {', '.join(sorted(pages))})"
        for (command, option), pages in sorted(documented().items())
        if not any(command in t and option in t for t in tests)
    ]
    assert not missing, "no test runs:\n" + "\n".join(missing)
