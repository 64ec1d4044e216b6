"""The docstring standard, enforced: every public module says what it holds and declares
its public API in ``__all__``, and every public function or class (in a module's
``__all__``, defined there) has a numpydoc Examples section with at least one doctest
(which ``pytest --doctest-modules`` runs).

Public modules: every module of ``ga_rotors`` (``ga_rotors.symbolic`` included) whose
dotted name has no part starting with "_". Compiled kernels (numba dispatchers) and cached
functions (``functools.cache``) are checked through to the Python function they wrap. The
sub-command modules of :data:`ga_rotors.cli.COMMANDS` are exempt for ``add_arguments``
and ``run``: the protocol the CLI calls, not user API.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import pytest

from ga_rotors.cli import COMMANDS

ROOTS = ("ga_rotors",)
COMMAND_PROTOCOL = ("add_arguments", "run")
# A section header "Examples" underlined with dashes, and a doctest prompt after it.
EXAMPLES = re.compile(r"^Examples\n-{8,}\n(?:.*\n)*?\s*>>> ", re.M)


def public_modules() -> list[str]:
    names = []
    for root in ROOTS:
        package = importlib.import_module(root)
        names.append(root)
        for info in pkgutil.walk_packages(package.__path__, root + "."):
            if not any(part.startswith("_") for part in info.name.split(".")[1:]):
                names.append(info.name)
    return names


MODULES = public_modules()


def documented_object(obj):
    """The Python function or class whose docstring documents ``obj``: a numba
    dispatcher's ``py_func``, a cached function's ``__wrapped__``, else ``obj``."""
    return inspect.unwrap(getattr(obj, "py_func", obj))


def undocumented(module_name: str) -> list[str]:
    """Names in ``module_name.__all__`` defined there whose docstring lacks Examples."""
    module = importlib.import_module(module_name)
    missing = []
    for name in module.__all__:
        obj = documented_object(getattr(module, name))
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        if getattr(obj, "__module__", None) != module_name:
            continue  # a re-export: checked where it is defined
        if module_name in COMMANDS.values() and name in COMMAND_PROTOCOL:
            continue
        if not EXAMPLES.search(inspect.getdoc(obj) or ""):
            missing.append(f"{module_name}.{name}")
    return missing


def test_the_walk_finds_the_packages_and_skips_private_modules():
    found = set(MODULES)
    assert {"ga_rotors.quaternion", "ga_rotors.integrators.base"} <= found
    assert "ga_rotors.symbolic.audit" in found
    assert not [m for m in MODULES if "._" in m]


def test_compiled_and_cached_functions_are_checked_through_to_their_python_function():
    from ga_rotors.reference import coning
    from ga_rotors.symbolic import rotors

    assert documented_object(coning.coning_rate) is coning.coning_rate.py_func
    assert inspect.isfunction(documented_object(rotors.rotor_sandwich))
    assert "ga_rotors.reference.coning.coning_rate" not in undocumented(
        "ga_rotors.reference.coning"
    )


def test_the_examples_pattern_needs_a_header_and_a_doctest():
    assert EXAMPLES.search("Sum.\n\nExamples\n--------\n>>> 1 + 1\n2\n")
    assert not EXAMPLES.search("Sum.\n\nExamples\n--------\nSee the docs.\n")
    assert not EXAMPLES.search("Sum.\n\n>>> 1 + 1\n2\n")
    assert not EXAMPLES.search("Sum; Examples are in the docs.\n>>> 1 + 1\n")


def test_every_public_function_and_class_has_examples():
    missing = [name for module in MODULES for name in undocumented(module)]
    assert not missing, "public names without an Examples section (doctested):\n  " + (
        "\n  ".join(missing)
    )


@pytest.mark.parametrize("module_name", MODULES)
def test_every_public_module_says_what_it_holds(module_name):
    doc = (importlib.import_module(module_name).__doc__ or "").strip()
    assert doc, f"{module_name} has no module docstring"


@pytest.mark.parametrize("module_name", MODULES)
def test_every_public_module_declares_its_api(module_name):
    module = importlib.import_module(module_name)
    assert isinstance(getattr(module, "__all__", None), list | tuple), (
        f"{module_name} has no __all__"
    )
    absent = [name for name in module.__all__ if not hasattr(module, name)]
    assert not absent, f"{module_name}.__all__ names what it does not define: {absent}"
