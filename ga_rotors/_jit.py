"""How every hot loop in ga_rotors is compiled.

One decorator, so the whole package shares one policy:

* ``cache=True``: compiled machine code is written next to the source and reused by
  later processes, so users pay the JIT cost once per installation, not per start.
* ``error_model="numpy"``: division by zero gives inf/nan instead of raising inside the
  loop; the Python wrappers check results and raise a clear error instead.
* ``no_cfunc_wrapper=True``: numba otherwise compiles, for every function, a C-callable
  wrapper that only serves passing the function as a first-class value into another
  compiled function, which ga_rotors never does (kernels reach a loop by import, see
  ``integrators._source``); without it a cold ``ga-rotors paper`` compiles in about
  10 % less CPU (7.7 s -> 6.95 s, three pairs of runs, a loaded machine).
* no ``fastmath``: it would let LLVM assume no NaN/inf, which breaks the finiteness
  checks the wrappers rely on, and reorders the sums the error analysis assumes.

Kernels stay plain Python functions underneath. Setting ``NUMBA_DISABLE_JIT=1`` runs
them uncompiled; the test suite does that once to check compiled and uncompiled
kernels agree. :func:`plain` gives one kernel's uncompiled form, for code that calls a
kernel once per call (one rotor at a time) and should not start numba for it;
:func:`inline` its inline form, for a loop over many bodies that must see every formula
it calls (the batched loops of :mod:`ga_rotors.integrators`).
"""

from __future__ import annotations

import types

import numba

_OPTIONS = {"cache": True, "nogil": True, "error_model": "numpy", "no_cfunc_wrapper": True}


def jit(func=None, **options):
    """Compile ``func`` with the package's numba policy (lazily, on first call)."""
    merged = {**_OPTIONS, **options}

    def wrap(f):
        return numba.njit(**merged)(f)

    return wrap(func) if func is not None else wrap


def plain(kernel):
    """The uncompiled form of a compiled kernel: the same source, run by the interpreter.

    Kernels it calls are uncompiled too (its global names are rebound to their plain
    forms), so calling it never starts numba. For one rotor or quaternion at a time this is
    what the public functions want: numba's first call in a process costs about 0.3 s of
    CPU (it loads its typing registries and imports scipy.linalg) even when the machine
    code is cached, and each later call pays more for boxing a tuple than the arithmetic
    costs (1.2 µs against 0.8 µs for a rotor product, measured). A function that is not
    compiled (``NUMBA_DISABLE_JIT=1``, or a plain function) is returned as it is.

    Examples
    --------
    >>> from ga_rotors import _kernels as K
    >>> plain(K.qexp_pure)((0.0, 0.0, 0.0))
    (1.0, 0.0, 0.0, 0.0)
    """
    func = getattr(kernel, "py_func", None)
    if func is None:
        return kernel
    found = _PLAIN.get(id(kernel))
    if found is not None:
        return found[1]
    env = dict(func.__globals__)
    out = types.FunctionType(func.__code__, env, func.__name__, func.__defaults__, func.__closure__)
    out.__doc__, out.__qualname__, out.__module__ = func.__doc__, func.__qualname__, func.__module__
    _PLAIN[id(kernel)] = (kernel, out)  # before the callees: kernels may call each other
    for name in _names(func.__code__):
        if hasattr(env.get(name), "py_func"):
            env[name] = plain(env[name])
    return out


#: id(compiled kernel) -> (the kernel, kept alive so its id is not reused; its plain form)
_PLAIN: dict[int, tuple] = {}


def inline(kernel, replace: tuple = ()):
    """The same Python function as ``kernel``, compiled with ``inline="always"``, its calls
    to other compiled kernels rebound to their inline forms too.

    numba optimises each compiled function on its own and links its callees afterwards,
    so a loop that calls kernels makes real calls, and LLVM cannot vectorise it across
    bodies; the inline form puts the *same formula* (the same source, not a rewrite) into
    the loop. ``replace``: pairs (kernel, stand-in) — wherever the inline forms would call
    that kernel they call the stand-in (a batched loop reads values a kernel computed
    once per body instead of computing them in every stage). A function that is not
    compiled is returned as it is.

    Examples
    --------
    >>> from ga_rotors import _kernels as K
    >>> inline(K.free_euler_rates) is inline(K.free_euler_rates)
    True
    >>> inline(K.free_euler_rates).targetoptions["inline"]
    'always'
    """
    key = (id(kernel), replace)
    found = _INLINE.get(key)
    if found is not None:
        return found[1]
    for old, new in replace:
        if kernel is old:
            return new
    func = getattr(kernel, "py_func", None)
    if func is None:
        return kernel
    scope = dict(func.__globals__)
    for name in _names(func.__code__):
        if hasattr(scope.get(name), "py_func"):
            scope[name] = inline(scope[name], replace)
    copy = types.FunctionType(func.__code__, scope, func.__name__, func.__defaults__)
    out = numba.njit(inline="always", error_model="numpy")(copy)
    _INLINE[key] = (kernel, out)
    return out


#: (id(compiled kernel), replace) -> (the kernel, kept alive; its inline form)
_INLINE: dict[tuple, tuple] = {}


def _names(code: types.CodeType) -> set[str]:
    names = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _names(const)
    return names
