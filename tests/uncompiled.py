"""Re-run test files with NUMBA_DISABLE_JIT=1, so the plain-Python kernels and loops are
tested as well as the compiled ones (one mechanism, shared by every kernel test file).

Use in a test module::

    from uncompiled import uncompiled_twin
    test_agrees_uncompiled = uncompiled_twin(__file__)

Every module that does so registers its file at import; in one process, the first twin
that runs starts ONE subprocess for all registered files (interpreter, NumPy, SciPy and
hypothesis start once instead of once per file), and each twin then checks its own file's
outcome. Under pytest-xdist, where the files are spread over the workers, each twin runs
its own file (the registered ones together would run once per worker).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
_REGISTERED: list[str] = []
_RUN: dict[str, subprocess.CompletedProcess] = {}


def _run(files: list[str]) -> subprocess.CompletedProcess:
    key = "\n".join(files)
    if key not in _RUN:
        env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
        _RUN[key] = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-rf", "-p", "no:cacheprovider", "-n", "0",
             *files],
            cwd=ROOT, env=env, capture_output=True, text=True,
        )  # fmt: skip
    return _RUN[key]


def uncompiled_twin(test_file: str):
    """A test asserting that ``test_file`` passes with numba disabled."""
    test_file = str(Path(test_file).resolve())
    if test_file not in _REGISTERED:
        _REGISTERED.append(test_file)
    name = Path(test_file).name

    @pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="already uncompiled")
    def test_agrees_uncompiled():
        proc = _run([test_file] if os.environ.get("PYTEST_XDIST_WORKER") else _REGISTERED)
        failed = [
            line
            for line in proc.stdout.splitlines()
            if line.startswith(("FAILED", "ERROR")) and name in line
        ]
        report = proc.stdout[-3000:] + proc.stderr[-3000:]
        assert proc.returncode in (0, 1), report  # 2+: interrupted, usage or collection error
        assert not failed, "\n".join(failed) + "\n" + report
        assert proc.returncode == 0 or any(
            line.startswith("FAILED") for line in proc.stdout.splitlines()
        ), report

    return test_agrees_uncompiled
