"""How every hot loop in ga_rotors is compiled.

One decorator, so the whole package shares one policy:

* ``cache=True``: compiled machine code is written next to the source and reused by
  later processes, so users pay the JIT cost once per installation, not per start.
* ``error_model="numpy"``: division by zero gives inf/nan instead of raising inside the
  loop; the Python wrappers check results and raise a clear error instead.
* no ``fastmath``: it would let LLVM assume no NaN/inf, which breaks the finiteness
  checks the wrappers rely on, and reorders the sums the error analysis assumes.

Kernels stay plain Python functions underneath. Setting ``NUMBA_DISABLE_JIT=1`` runs
them uncompiled; the test suite does that once to check compiled and uncompiled
kernels agree.
"""

from __future__ import annotations

import numba

_OPTIONS = {"cache": True, "nogil": True, "error_model": "numpy"}


def jit(func=None, **options):
    """Compile ``func`` with the package's numba policy (lazily, on first call)."""
    merged = {**_OPTIONS, **options}

    def wrap(f):
        return numba.njit(**merged)(f)

    return wrap(func) if func is not None else wrap
