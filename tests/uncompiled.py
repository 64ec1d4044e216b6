"""Re-run a test file with NUMBA_DISABLE_JIT=1, so the plain-Python kernels and loops are
tested as well as the compiled ones (one mechanism, shared by every kernel test file).

Use in a test module::

    from uncompiled import uncompiled_twin
    test_agrees_uncompiled = uncompiled_twin(__file__)
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def uncompiled_twin(test_file: str):
    """A test that runs ``test_file`` in a subprocess without numba and asserts it passes."""

    @pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="already uncompiled")
    def test_agrees_uncompiled():
        env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
        proc = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", test_file],
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
        )
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]

    return test_agrees_uncompiled
