"""The package's import graph has no cycle.

Every module's imports are read with ``ast`` (function-level imports included: a lazy
import that closes a cycle still ties the two modules together), resolved to modules of
the installed ``ga_rotors`` package (``from pkg import name`` counts as an import of
``pkg.name`` when that is a module, else of ``pkg``), and the graph is checked acyclic.
"""

from __future__ import annotations

import ast
from pathlib import Path

import ga_rotors

ROOT = Path(ga_rotors.__file__).resolve().parent


def _modules() -> dict[str, Path]:
    out = {}
    for file in ROOT.rglob("*.py"):
        parts = ["ga_rotors", *file.relative_to(ROOT).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = file
    return out


def _imports(name: str, file: Path, modules: dict[str, Path]) -> set[str]:
    package = name.split(".") if file.name == "__init__.py" else name.split(".")[:-1]
    found = set()
    for node in ast.walk(ast.parse(file.read_text(encoding="utf-8"), str(file))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            for alias in node.names:
                sub = f"{source}.{alias.name}"
                found.add(sub if sub in modules else source)
    return {m for m in found if m in modules and m != name}


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    return {name: _imports(name, file, modules) for name, file in modules.items()}


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of ``graph`` as a list of nodes (first repeated at the end), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node):
        state[node] = 1
        path.append(node)
        for dep in sorted(graph[node]):
            if state.get(dep) == 1:
                return [*path[path.index(dep) :], dep]
            if dep not in state:
                found = visit(dep)
                if found:
                    return found
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_the_cycle_finder_finds_a_cycle_and_resolves_relative_imports(tmp_path):
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None
    pkg = tmp_path / "base.py"
    pkg.write_text("from . import loops\nfrom .template import X\n\ndef f():\n    import numpy\n")
    modules = {"ga_rotors.x": None, "ga_rotors.x.loops": None, "ga_rotors.x.template": None}
    found = _imports("ga_rotors.x.base", pkg, modules)
    assert found == {"ga_rotors.x.loops", "ga_rotors.x.template"}


def test_the_package_has_no_import_cycle():
    graph = _graph()
    assert "ga_rotors.integrators.base" in graph and graph["ga_rotors.integrators.template"]
    cycle = _cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)
