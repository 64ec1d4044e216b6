"""The README's quick start is what CI runs: two commands, the second one in .ci/run; the
first installs, compiles the loops ahead (``cache --warm``) and runs the paper."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _quick_start_commands() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return [b.strip() for b in re.findall(r"```console\n(.*?)```", section, re.S)]


def test_quick_start_is_two_commands_main_job_then_tests():
    main_job, tests = _quick_start_commands()
    assert "\n" not in main_job and "\n" not in tests
    assert main_job.endswith("ga-rotors paper")
    # the install step compiles the loops ahead, so the first paper run loads them
    assert main_job.split(" && ")[-2:] == [
        ".venv/bin/ga-rotors cache --warm",
        ".venv/bin/ga-rotors paper",
    ]
    assert tests.endswith("python -m pytest") and re.search(r'"\.\[test(,\w+)*\]"', tests)


def test_ci_runs_exactly_the_readmes_test_command():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert _quick_start_commands()[1] in ci


def test_readme_links_work_on_a_package_index():
    # A package index shows the README without the repository: relative links would break.
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    links = re.findall(r"\]\(([^)\s]+)\)", text)
    assert links and all(re.match(r"https?://", link) for link in links), links


def test_every_install_the_readme_shows_installs_from_this_repository():
    # The package is not on a package index: `pip install "ga-rotors[x]"` would fail for a
    # newcomer, so every pip line installs "." with extras that pyproject.toml declares.
    import tomllib

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"][
        "optional-dependencies"
    ]
    installs = re.findall(r"pip install ([^`&\n]+?)(?:`| &&|\n)", text)
    assert len(installs) >= 5, installs
    for target in installs:
        spec = target.strip().strip('"')
        assert re.fullmatch(r"\.(\[[\w,]+\])?", spec), f"installs {target!r}, not this repository"
        for extra in re.findall(r"\w+", spec[2:-1]):
            assert extra in extras, f"README names the extra {extra!r}, not in pyproject.toml"
