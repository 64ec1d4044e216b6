"""Specialise loop templates: generate, cache on disk, import, compile (numba cache=True).

For one (integrator, problem kind, path, declared torque or ω(t) kernels) this module
writes a Python module such as::

    from ga_rotors._jit import jit as _jit
    from ga_rotors._kernels import euler_rates
    from ga_rotors.paths.quaternion import rate as o_rate
    ...
    from ga_rotors.effects import gravity as _term_0

    @_jit
    def torque(t, q, w, params):
        return _term_0(t, q, w, params[0:6])

    @_jit
    def accel(t, x, w, inertia, params):
        return euler_rates(inertia, w, torque(t, o_quat(x), w, params))

    @_jit
    def rk4_step(t, x, w, h, inertia, params):
        ...                                   # the template's source, verbatim

    step = rk4_step

    @_jit
    def fixed_step_loop(...):
        ...

    loop = fixed_step_loop

    @_jit
    def limit(inertia, w, h, nsteps):       # the integrator's step limit, measured
        return _measure(inertia, w, h, nsteps, (1.0, 1.0, 0.5, ...), True, True)

    @_jit
    def judged_run(...):                    # limit, loop and watch: a run's one call
        ...

    run = judged_run

Every global a template uses is resolved in the template's own module: compiled kernels
become imports, numeric constants are copied, slots are bound here. The file name holds a
SHA-256 of the text and of every source file the module can reach (the whole ga_rotors
package, plus the modules of kernels from elsewhere), so an edit anywhere gives a new
file and numba's cache, keyed on that file, can never serve stale machine code.

Cache directory: ``$GA_ROTORS_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/ga_rotors`` or
``~/.cache/ga_rotors``; if that is not writable, a per-user directory under the system
temp dir; if nothing is writable, the module is compiled in memory without caching (a
one-off cost of about a second per loop, reported by :func:`cache_location`).
"""

from __future__ import annotations

import functools
import hashlib
import importlib
import importlib.util
import inspect
import os
import sys
import textwrap
import types
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _modules
from .._modules import GENERATED_LOCK, load_source
from .._private_dir import private_directory
from ..errors import InputError
from ..files import write_text
from ..paths import get as get_path
from . import loops, slots
from .base import FREE, KINEMATIC, TORQUED, Integrator, LoopResult, Problem

__all__ = [
    "Specialisation",
    "bare_loop",
    "cache_location",
    "clear_cache",
    "prepared",
    "run_loop",
    "run_prepared",
    "run_segments",
    "source",
    "specialise",
    "vector_field",
]

PACKAGE_ROOT = Path(__file__).resolve().parent.parent
#: Steps per call of the compiled loop when progress is reported (~10 ms of RK4).
CHUNK_STEPS = 131_072
_MEMO: dict[tuple, Specialisation] = {}


@dataclass(frozen=True)
class Specialisation:
    """A generated, imported module and its compiled loop."""

    module: types.ModuleType
    path: Path | None
    source: str

    @property
    def loop(self):
        return self.module.loop


# ---------------------------------------------------------------------------- source text


def _code_names(code: types.CodeType) -> set[str]:
    names = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _code_names(const)
    return names


def _template_source(func) -> str:
    src = textwrap.dedent(inspect.getsource(func))
    if not src.startswith("def "):
        raise InputError(
            f"template {func.__qualname__}: expected a plain module-level function without "
            "decorators"
        )
    return src


def _is_template(obj) -> bool:
    return isinstance(obj, types.FunctionType) and not hasattr(obj, "py_func")


def _reachable(start: list, pool: dict[str, types.FunctionType]) -> list:
    """Templates reachable from ``start`` through global names, in dependency order."""
    seen: dict[str, types.FunctionType] = {}

    def visit(func):
        if func.__name__ in seen:
            return
        for name in sorted(_code_names(func.__code__)):
            dep = pool.get(name)
            if dep is not None and dep is not func:
                visit(dep)
        seen[func.__name__] = func

    for func in start:
        visit(func)
    return list(seen.values())


class _Imports:
    """Global name -> how the generated module gets it; refuses conflicting bindings."""

    def __init__(self):
        self.lines: dict[str, str] = {}
        self.objects: dict[str, object] = {}
        self.modules: set[str] = set()

    def bind(self, name: str, obj, line: str, module: str | None) -> None:
        if name in self.objects and self.objects[name] is not obj:
            raise InputError(f"template global {name!r} is bound to two different objects")
        self.objects[name] = obj
        self.lines[name] = line
        if module:
            self.modules.add(module)

    def kernel(self, name: str, obj) -> None:
        func = getattr(obj, "py_func", obj)
        module, qual = func.__module__, func.__qualname__
        if getattr(importlib.import_module(module), qual, None) is not obj:
            raise InputError(f"{module}.{qual} is not importable under its own name")
        alias = "" if qual == name else f" as {name}"
        self.bind(name, obj, f"from {module} import {qual}{alias}", module)


def _resolve_globals(templates: list, generated: set[str], imports: _Imports) -> None:
    template_names = {f.__name__ for f in templates}
    for func in templates:
        for name in sorted(_code_names(func.__code__)):
            if name in template_names or name in generated or name not in func.__globals__:
                continue
            obj = func.__globals__[name]
            if name in slots.ALL_SLOTS:
                continue  # bound by the caller (path kernels) or generated
            if isinstance(obj, types.ModuleType):
                imports.bind(name, obj, f"import {obj.__name__} as {name}", obj.__name__)
            elif isinstance(obj, bool | int | float) or (
                isinstance(obj, tuple) and all(isinstance(v, int | float) for v in obj)
            ):
                imports.bind(name, obj, f"{name} = {obj!r}", None)
            elif callable(obj):
                imports.kernel(name, obj)
            else:
                raise InputError(
                    f"template {func.__name__}: global {name!r} is a {type(obj).__name__}; "
                    "templates may use compiled kernels, modules and numeric constants"
                )


def _torque_source(problem: Problem, imports: _Imports) -> str:
    calls, offset = [], 0
    for n, term in enumerate(problem.torques):
        alias = f"_term_{n}"
        imports.kernel(alias, term.kernel)
        size = len(term.params)
        calls.append(f"{alias}(t, q, w, params[{offset}:{offset + size}])")
        offset += size
    if len(calls) == 1:
        body = f"    return {calls[0]}\n"
    else:
        body = "".join(f"    a{n} = {c}\n" for n, c in enumerate(calls))
        sums = [" + ".join(f"a{n}[{k}]" for n in range(len(calls))) for k in range(3)]
        body += f"    return ({sums[0]}, {sums[1]}, {sums[2]})\n"
    return "def torque(t, q, w, params):\n" + body


def _omega_source(problem: Problem, imports: _Imports) -> str:
    imports.kernel("_omega_0", problem.omega.kernel)
    size = len(problem.omega.params)
    return f"def omega(t, params):\n    return _omega_0(t, params[0:{size}])\n"


def _accel_source(kind: str, imports: _Imports) -> str:
    from .. import _kernels

    if kind == FREE:
        imports.kernel("free_euler_rates", _kernels.free_euler_rates)
        return "def accel(t, x, w, inertia, params):\n    return free_euler_rates(inertia, w)\n"
    imports.kernel("euler_rates", _kernels.euler_rates)
    return (
        "def accel(t, x, w, inertia, params):\n"
        "    return euler_rates(inertia, w, torque(t, o_quat(x), w, params))\n"
    )


def _literal(value) -> str:
    """``value`` (a number, a boolean, or a tuple of them) as source text that reads back
    exactly (floats by repr)."""
    if isinstance(value, bool | int | float):
        return repr(value)
    if isinstance(value, tuple):
        return "(" + "".join(_literal(v) + ", " for v in value) + ")"
    raise InputError(f"step limit constants: expected numbers or tuples, got {value!r}")


def _limit_source(integrator: Integrator, kind: str, imports: _Imports) -> str:
    measure = getattr(integrator.step_limit, "measure", None)
    if measure is None or kind == KINEMATIC:  # judged in Python, or nothing to judge
        return "def limit(inertia, w, h, nsteps):\n    return 0.0, 1.0\n"
    imports.kernel("_measure", measure)
    constants = "".join(", " + _literal(c) for c in integrator.step_limit.constants)
    return (
        "def limit(inertia, w, h, nsteps):\n"
        f"    return _measure(inertia, w, h, nsteps{constants})\n"
    )


def source(integrator: Integrator, problem: Problem, path: str) -> str:
    """The text of the module that specialises ``integrator`` for ``problem`` on ``path``."""
    return _generate(integrator, problem, path, cache=True)[0]


def _generate(
    integrator: Integrator | None, problem: Problem, path: str, cache: bool
) -> tuple[str, list[str]]:
    """Module text and the modules it imports. ``integrator=None``: the vector field."""
    kind = problem.kind
    if integrator is None:
        name, step, templates, entry = "vector_field", None, [], None
        loop = loops.kinematic_rhs if kind == KINEMATIC else loops.dynamics_rhs
        alias = "rhs"
    else:
        name, step, entry = integrator.name, integrator.steps[kind], loops.judged_run
        loop = loops.kinematic_loop if kind == KINEMATIC else loops.fixed_step_loop
        alias = "loop"
        pool = {f.__name__: f for f in (*integrator.steps.values(), *integrator.helpers)}
        for f in pool.values():
            if not _is_template(f):
                raise InputError(f"template {f!r}: expected a plain (uncompiled) Python function")
        templates = _reachable([step], pool)
    used = set().union(*(_code_names(f.__code__) for f in (*templates, loop)))

    imports = _Imports()
    generated: list[str] = []
    needs_torque = "torque" in used or ("accel" in used and kind == TORQUED)
    if needs_torque and kind != TORQUED:
        raise InputError(f"{name}: its {kind} step calls torque(), which needs torques")
    if kind == TORQUED and not needs_torque:
        raise InputError(f"{name}: its torqued step never evaluates the torque")
    if needs_torque:
        generated.append(_torque_source(problem, imports))
    if "accel" in used:
        if kind == KINEMATIC:
            raise InputError(f"{name}: a kinematic step cannot call accel()")
        generated.append(_accel_source(kind, imports))
        used |= {"o_quat"} if kind == TORQUED else set()
    if "omega" in used:
        if kind != KINEMATIC:
            raise InputError(f"{name}: only kinematic steps may call omega()")
        generated.append(_omega_source(problem, imports))
    if kind == KINEMATIC and "omega" not in used:
        raise InputError(f"{name}: its kinematic step never evaluates omega()")

    spec = get_path(path)
    module = spec.load()
    for slot, attr in slots.PATH_SLOTS.items():
        if slot in used:
            if not hasattr(module, attr):
                raise InputError(f"{name}: uses {slot}, which the {path!r} path does not have")
            imports.kernel(slot, getattr(module, attr))

    names = {"torque", "accel", "omega", "step", "loop", "rhs", "limit"}
    _resolve_globals([*templates, loop, *([entry] if entry else [])], names, imports)
    if entry is not None:
        limit_text = _limit_source(integrator, kind, imports)

    if cache:
        header = "from ga_rotors._jit import jit as _jit\n"
    else:
        header = "from functools import partial\n\nfrom ga_rotors._jit import jit\n\n"
        header += "_jit = partial(jit, cache=False)\n"
    body = [header, *(line + "\n" for line in sorted(imports.lines.values()))]
    for text in generated:
        body.append("\n\n@_jit\n" + text)
    for func in templates:
        body.append("\n\n@_jit\n" + _template_source(func))
    if step is not None:
        body.append(f"\n\nstep = {step.__name__}\n")
    body.append("\n\n@_jit\n" + _template_source(loop))
    body.append(f"\n\n{alias} = {loop.__name__}\n")
    if entry is not None:
        body.append("\n\n@_jit\n" + limit_text)
        body.append("\n\n@_jit\n" + _template_source(entry))
        body.append(f"\n\nrun = {entry.__name__}\n")
    terms = [t.name for t in problem.torques] or ([problem.omega.name] if problem.omega else [])
    doc = (
        f'"""Generated by ga_rotors.integrators._codegen; do not edit.\n\n'
        f"integrator={name} problem={kind} path={path} terms={terms}\n"
        '"""\n\n'
    )
    text = doc + "".join(body)
    return text, sorted(imports.modules)


# ---------------------------------------------------------------------------- the cache


def _candidates() -> list[Path]:
    env = os.environ.get("GA_ROTORS_CACHE_DIR")
    if env:
        return [Path(env) / "generated"]
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return [Path(base) / "ga_rotors" / "generated"]


#: What to do when the cache folder is not private (ga_rotors._private_dir).
_WAY_OUT = (
    "remove the folder (or chmod 700 it if it is yours), or set GA_ROTORS_CACHE_DIR to a "
    "folder of your own"
)


@functools.lru_cache(maxsize=1)
def cache_location() -> Path | None:
    """The directory generated modules go to, or None when compiling in memory.

    Private (mode 0700, the user's own: :func:`ga_rotors._private_dir.private_directory`);
    one that exists but is not private is refused with an InputError. No fallback under
    the shared temporary directory: with no usable folder, loops compile in memory.
    """
    for directory in _candidates():
        found = private_directory(directory, way_out=_WAY_OUT)
        if found is not None:
            return found
    return None


#: Generated modules of *another* version of the package (another package digest) written
#: more than this many days ago are deleted the first time a process generates a module:
#: upgrades and edits do not pile up files forever, and a version still in use elsewhere
#: (a release beside a working copy) only recompiles a module once per period.
PRUNE_AFTER_DAYS = 14


@dataclass(frozen=True)
class CacheFile:
    """One generated module in the cache, and its numba cache files."""

    path: Path
    version: str
    files: tuple[Path, ...]
    bytes: int
    mtime: float


def cached_modules(
    directory: Path | None = None, *, other_than: str | None = None, before: float | None = None
) -> list[CacheFile]:
    """Every generated module in ``directory`` (default: :func:`cache_location`).

    ``version`` is the package digest the module was made by (:func:`version_tag`),
    ``files`` the module and its compiled files under ``__pycache__``. ``other_than`` keeps
    only modules of other versions, ``before`` only modules written before that time (a
    ``time.time()`` value): both are decided from the module's name and its own mtime,
    before the compiled files (several per module, tens of thousands in a full cache) are
    listed and measured, so pruning costs little when nothing is stale.
    """
    directory = cache_location() if directory is None else Path(directory)
    if directory is None or not directory.is_dir():
        return []
    chosen = []
    for f in directory.glob("gen_*.py"):
        parts = f.name[:-3].rsplit("_", 2)
        version = parts[1] if len(parts) == 3 else ""
        if other_than is not None and version == other_than:
            continue
        try:
            mtime = f.stat().st_mtime
        except OSError:  # deleted meanwhile by another process
            continue
        if before is None or mtime < before:
            chosen.append((f, version, mtime))
    if not chosen:
        return []
    compiled: dict[str, list[Path]] = {}
    pycache = directory / "__pycache__"
    if pycache.is_dir():
        for f in pycache.iterdir():
            compiled.setdefault(f.name.split(".", 1)[0], []).append(f)
    out = []
    for f, version, mtime in chosen:
        files = (f, *compiled.get(f.name[:-3], ()))
        try:
            size = sum(g.stat().st_size for g in files)
        except OSError:
            continue
        out.append(CacheFile(f, version, files, size, mtime))
    return sorted(out, key=lambda c: c.path.name)


def _delete(entries) -> int:
    removed = 0
    for entry in entries:
        for f in entry.files:
            try:
                f.unlink()
                removed += 1
            except OSError:
                pass
    return removed


def clear_cache(every_version: bool = False) -> int:
    """Delete this version's generated modules and their numba cache (``every_version``:
    all versions'); return how many files went."""
    entries = cached_modules()
    removed = _delete(e for e in entries if every_version or e.version == version_tag())
    _MEMO.clear()
    return removed


def prune_cache(max_age_days: float = PRUNE_AFTER_DAYS, now: float | None = None) -> int:
    """Delete modules of other package versions not written for ``max_age_days``.

    Returns how many files went. Modules of this version are never pruned.
    """
    import time

    limit = (time.time() if now is None else now) - max_age_days * 86400.0
    return _delete(cached_modules(other_than=version_tag(), before=limit))


_PRUNED = False


def _prune_once() -> None:
    global _PRUNED
    if not _PRUNED:
        _PRUNED = True
        prune_cache()


@functools.cache
def _file_digest(path: str) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


@functools.lru_cache(maxsize=1)
def _package_digest() -> str:
    h = hashlib.sha256()
    for f in sorted(PACKAGE_ROOT.rglob("*.py")):
        h.update(str(f.relative_to(PACKAGE_ROOT)).encode())
        h.update(_file_digest(str(f)).encode())
    return h.hexdigest()


def version_tag() -> str:
    """Eight hex digits of the package digest: which version of ga_rotors made a module."""
    return _package_digest()[:8]


def _digest(text: str, modules: list[str]) -> str:
    import numba

    h = hashlib.sha256(text.encode())
    h.update(_package_digest().encode())
    h.update(numba.__version__.encode())
    for name in modules:
        if name == "ga_rotors" or name.startswith("ga_rotors."):
            continue
        file = getattr(sys.modules.get(name) or importlib.import_module(name), "__file__", None)
        if file:
            h.update(_file_digest(file).encode())
    return h.hexdigest()[:20]


def _write_once(path: Path, text: str) -> None:
    """Create ``path`` with ``text`` atomically; an existing identical file is left alone
    (rewriting it would change its mtime and invalidate numba's cache for it)."""
    if path.exists():
        try:
            if path.read_text(encoding="utf-8") == text:
                return
        except OSError:
            pass
    write_text(path, text)


def _import_file(name: str, path: Path) -> types.ModuleType:
    return _modules.load_registered(importlib.util.spec_from_file_location(name, path))


def _memo_key(integrator, problem: Problem, path: str) -> tuple:
    terms = (problem.omega,) if problem.omega is not None else problem.torques
    return (
        "vector_field" if integrator is None else integrator.name,
        id(integrator),
        problem.kind,
        path,
        tuple((term.location, len(term.params)) for term in terms),
    )


def specialise(integrator: Integrator | None, problem: Problem, path: str) -> Specialisation:
    """Generate (or reuse) and import the module for this combination.

    ``integrator=None`` gives the vector field's module (see :func:`vector_field`).
    """
    key = _memo_key(integrator, problem, path)
    found = _MEMO.get(key)
    if found is not None:
        return found
    with GENERATED_LOCK:  # one thread at a time makes and loads generated modules
        found = _MEMO.get(key)  # made by the thread this one waited for
        return found if found is not None else _specialise(key, integrator, problem, path)


def _specialise(key, integrator: Integrator | None, problem: Problem, path: str):
    directory = cache_location()
    text, modules = _generate(integrator, problem, path, cache=directory is not None)
    digest = _digest(text, modules)
    label = "rhs" if integrator is None else integrator.name
    stem = f"gen_{label}_{problem.kind}_{path}_{version_tag()}_{digest}"
    modname = f"_ga_rotors_{stem}"
    file = directory / f"{stem}.py" if directory is not None else None
    loaded = sys.modules.get(modname)
    if loaded is not None and getattr(loaded, "__file__", None) == str(file or f"<{modname}>"):
        module = loaded
    elif file is not None:
        try:
            _prune_once()
            _write_once(file, text)
            module = _import_file(modname, file)
        except OSError:
            text, _ = _generate(integrator, problem, path, cache=False)
            file, module = None, load_source(modname, text)
    else:
        module = load_source(modname, text)
    result = Specialisation(module, file, text)
    _MEMO[key] = result
    return result


# ---------------------------------------------------------------------------- running


@dataclass(frozen=True)
class _Prepared:
    """What every run of one (integrator, problem, path) shares, derived once."""

    owner: Integrator  # held, so that the id in the problem's key is never reused
    loop: object
    run: object  # the module's judged_run: limit, loop and watch in one compiled call
    source: Path | None
    dim: int
    shape: tuple[int]  # (dim,), the state's shape
    stats: np.ndarray  # the path's initial watch statistics (copied per run)
    inertia: tuple[float, float, float]
    params: np.ndarray
    #: judged_run's flags for this problem: JUDGE when the limit is measured in the
    #: compiled module (and the problem has a body), REFUSE too when a run past it raises
    flags: int
    #: the integrator declares a limit the compiled module cannot judge (a plain Python
    #: function, without a ``measure``): :meth:`Integrator.check_step` judges it
    python_limit: bool


def _entry(dispatcher, sample: tuple):
    """The machine code ``dispatcher`` compiles (or loads from its cache) for the types of
    ``sample``, as a function that skips the dispatcher's typing of every argument on
    every call (a quarter of a microsecond for judged_run's thirteen): only for a caller
    that passes exactly those types, as :func:`run_prepared` makes sure it does (states
    converted and checked, counts as ints, times as floats, its own output arrays).
    Uncompiled (``NUMBA_DISABLE_JIT=1``), the function itself."""
    compile_signature = getattr(dispatcher, "compile", None)
    if compile_signature is None:
        return dispatcher
    import numba

    return compile_signature(tuple(numba.typeof(a) for a in sample))


def _prepare(integrator: Integrator, problem: Problem, path: str) -> _Prepared:
    spec = get_path(path)
    kernels = spec.load()
    compiled = specialise(integrator, problem, path)
    stats = (
        kernels.initial_stats() if hasattr(kernels, "initial_stats") else np.zeros(kernels.NSTATS)
    )
    inertia = problem.inertia if problem.inertia is not None else (1.0, 1.0, 1.0)
    limited = integrator.step_limit is not None and problem.inertia is not None
    measured = limited and hasattr(integrator.step_limit, "measure")
    flags = 0
    if measured and problem.kind != KINEMATIC:
        flags = loops.JUDGE | (loops.REFUSE if integrator.step_limit_action == "raise" else 0)
    params = problem.params()
    # the types run_prepared passes: states, t0, h, nsteps, every, inertia, params,
    # the three output arrays, the statistics, flags
    sample = (np.empty(spec.dim), np.empty(3), 0.0, 0.0, 1, 1, inertia, params,
              np.empty(1), np.empty((1, spec.dim)), np.empty((1, 3)), stats, 0)  # fmt: skip
    return _Prepared(
        integrator, compiled.loop, _entry(compiled.module.run, sample), compiled.path,
        spec.dim, (spec.dim,), stats, inertia, params, flags, limited and not measured,
    )  # fmt: skip


def prepared(integrator: Integrator, problem: Problem, path: str, checked: bool = False):
    """The :class:`_Prepared` run of ``integrator`` on ``problem`` and ``path``, derived
    once and kept by the problem; ``checked``: :meth:`Integrator.check` passed first
    (kept under its own key, so one look-up serves a checked run)."""
    if checked:
        return problem.derived(
            ("checked run", id(integrator), path),
            lambda: integrator.check_once(problem, path) or prepared(integrator, problem, path),
        )
    return problem.derived(
        ("loop", id(integrator), path), lambda: _prepare(integrator, problem, path)
    )


def _counts(nsteps, every) -> tuple[int, int]:
    if type(nsteps) is not int or type(every) is not int or nsteps < 1 or every < 1:
        if not (isinstance(nsteps, int | np.integer) and nsteps >= 1):
            raise InputError(f"nsteps: expected a positive integer, got {nsteps!r}")
        if not (isinstance(every, int | np.integer) and every >= 1):
            raise InputError(f"every: expected a positive integer, got {every!r}")
        nsteps, every = int(nsteps), int(every)
    return nsteps, every


def _state(value, shape: tuple[int], name: str) -> np.ndarray:
    """``value`` as a contiguous float64 vector of ``shape`` (the array itself if it is one)."""
    a = np.ascontiguousarray(value, dtype=np.float64)
    if a.shape != shape:
        raise InputError(f"expected shape {shape}, got {a.shape}", key=name)
    return a


_NO_W = np.zeros(3)  # ω of a kinematic run (read by no loop)
_W_SHAPE = (3,)
_F64 = np.float64
# module-level names: a global look-up each instead of a global and an attribute
_empty, _contiguous = np.empty, np.ascontiguousarray
_new_tuple = tuple.__new__  # a LoopResult without the named tuple's keyword-handling __new__


def run_prepared(prep: _Prepared, x0, w0, t0, h, nsteps, every, flags: int = 0, progress=None):
    """One run of a prepared loop: (LoopResult, value, bound, crossing), the last three
    ``judged_run``'s verdicts (see :mod:`~.loops`; ``flags`` as there, the prepared ones
    being the caller's to add). ``progress``: in chunks, not judged (see :func:`run_loop`).
    A refused run (``REFUSE``, past the limit) returns None for the result.

    The counts and states are checked here on every run (a wrong one gets its one line,
    naming ``nsteps``, ``every``, ``x0`` or ``w0``); the rest was derived once. Every
    run pays this function's Python (about 0.6 µs), so it is written for that: locals,
    no helper calls on the common path."""
    if type(nsteps) is not int or type(every) is not int or nsteps < 1 or every < 1:
        nsteps, every = _counts(nsteps, every)
    rows = nsteps // every + 1 + (1 if nsteps % every else 0)
    stats = prep.stats
    if stats.size:  # a path's watch statistics (empty arrays need no copy)
        stats = stats.copy()
    out_t = _empty(rows)
    out_x = _empty((rows, prep.dim))
    out_w = _empty((rows, 3))
    x = _contiguous(x0, dtype=_F64)
    w = _NO_W if w0 is None else _contiguous(w0, dtype=_F64)
    if x.shape != prep.shape or w.shape != _W_SHAPE:
        _state(x, prep.shape, "x0")
        _state(w, _W_SHAPE, "w0")
    if progress is None:  # the common case: one call of the compiled loop
        written, value, bound, crossing = prep.run(
            x, w, float(t0), float(h), nsteps, every, prep.inertia, prep.params,
            out_t, out_x, out_w, stats, flags,
        )  # fmt: skip
        if written == 0:
            return None, value, bound, crossing
    else:
        t0, h = float(t0), float(h)
        written = _chunked(prep, x, w, t0, h, nsteps, every, out_t, out_x, out_w, stats, progress)
        value, bound, crossing = 0.0, 1.0, -1
    if written < rows:
        out_t, out_x, out_w = out_t[:written], out_x[:written], out_w[:written]
    result = _new_tuple(LoopResult, (out_t, out_x, out_w, written == rows, stats, prep.source))
    return result, value, bound, crossing


def run_loop(
    integrator: Integrator,
    problem: Problem,
    path: str,
    x0,
    w0,
    t0: float,
    h: float,
    nsteps: int,
    every: int,
    progress=None,
) -> LoopResult:
    """Run the specialised loop and return the finite samples (no checks: see
    :meth:`Integrator.integrate`).

    Everything that depends only on (integrator, problem, path) — the generated module,
    the path's dimension and statistics, the packed parameters — is derived once and
    kept by the problem (:meth:`Problem.derived`); a run only checks its counts and
    states, allocates its samples and calls the loop.

    With ``progress``, the loop runs in chunks of about :data:`CHUNK_STEPS` steps (whole
    multiples of ``every``) and ``progress(steps_done)`` is called after each. Each chunk
    starts from the last stored sample, which is the exact state (samples store the
    state itself), at its step number (a step's time is t0 + k·h, whichever chunk takes
    it), and the watch statistics carry over, so the samples are the same as one call's,
    bit for bit (:func:`run_segments`).
    """
    prep = prepared(integrator, problem, path)
    return run_prepared(prep, x0, w0, t0, h, nsteps, every, 0, progress)[0]


def _chunked(prep, x, w, t0, h, nsteps, every, out_t, out_x, out_w, stats, progress) -> int:
    """The loop in chunks of about :data:`CHUNK_STEPS` steps; the number of rows written."""
    chunk = max(1, CHUNK_STEPS // every) * every
    done = row = 0
    while True:
        n = min(chunk, nsteps - done)
        got = prep.loop(
            x, w, t0, h, done, n, every, prep.inertia, prep.params,
            out_t[row:], out_x[row:], out_w[row:], stats,
        )  # fmt: skip
        done += n
        expected = n // every + 1 + (1 if n % every else 0)
        progress(done)
        if got < expected or done == nsteps:
            return row + got
        row += got - 1  # the next chunk's first sample is this chunk's last
        x, w = out_x[row].copy(), out_w[row].copy()


def run_segments(
    integrator: Integrator, problem: Problem, path: str, x0, w0, t0: float, h: float,
    nsteps: int, every: int, chunk: int, progress=None,
):  # fmt: skip
    """The run of :func:`run_loop` as consecutive pieces of about ``chunk`` steps each.

    A generator of :class:`LoopResult`: the first holds sample 0 and the samples of the
    first ``chunk`` steps (rounded up to whole multiples of ``every``), each next one the
    samples after the previous piece's last. Each piece continues from the previous one's
    last sample (the exact state) at its step number, with the watch statistics carried
    over, so the pieces joined are the samples of one call, bit for bit, and memory holds
    one piece at a time. A piece whose state stopped being finite is the last one
    (``complete`` False); ``stats`` of the last piece are the run's.

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> rk4, problem = get("rk4"), Problem((1.0, 2.0, 3.0))
    >>> args = (problem, "quaternion", (1.0, 0, 0, 0), (0.1, 0.0, 2.0), 0.0, 0.01, 100, 10)
    >>> pieces = list(run_segments(rk4, *args, chunk=30))
    >>> [len(p.t) for p in pieces]
    [4, 3, 3, 1]
    >>> whole = run_loop(rk4, *args)
    >>> bool((np.concatenate([p.x for p in pieces]) == whole.x).all())
    True
    """
    prep = prepared(integrator, problem, path)
    for name, value in (("nsteps", nsteps), ("every", every), ("chunk", chunk)):
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
            raise InputError(f"{name}: expected a positive integer, got {value!r}")
    nsteps, every = int(nsteps), int(every)
    span = max(1, int(chunk) // every) * every
    stats = prep.stats.copy() if prep.stats.size else prep.stats
    x = np.ascontiguousarray(x0, dtype=np.float64)
    w = np.ascontiguousarray(w0 if w0 is not None else (0.0, 0.0, 0.0), dtype=np.float64)
    t0, h = float(t0), float(h)
    done = 0
    while done < nsteps:
        n = min(span, nsteps - done)
        rows = n // every + 1 + (1 if n % every else 0)
        out_t, out_x, out_w = np.empty(rows), np.empty((rows, prep.dim)), np.empty((rows, 3))
        got = prep.loop(
            x, w, t0, h, done, n, every, prep.inertia, prep.params, out_t, out_x, out_w, stats
        )
        first = 0 if done == 0 else 1  # a later piece's sample 0 is the previous one's last
        done += n
        if progress is not None:
            progress(done)
        yield LoopResult(
            t=out_t[first:got], x=out_x[first:got], w=out_w[first:got],
            complete=got == rows, stats=stats, source=prep.source,
        )  # fmt: skip
        if got < rows:
            return
        x, w = out_x[-1].copy(), out_w[-1].copy()


def vector_field(problem: Problem, path: str):
    """The specialised right-hand side f(t, y) -> ẏ, for scipy-style integrators.

    ``y`` is the path's state followed by ω (dynamics) or the state alone (kinematic);
    the returned function evaluates one compiled call per evaluation and returns a new
    array. Only the declared torques enter it, as in the loops.

    Examples
    --------
    >>> import numpy as np
    >>> f = vector_field(Problem((1.0, 2.0, 3.0)), "quaternion")
    >>> f(0.0, np.array([1.0, 0, 0, 0, 0, 0, 2.0])).tolist()
    [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    """
    compiled = specialise(None, problem, path).module.rhs
    params = problem.params()
    inertia = problem.inertia if problem.inertia is not None else (1.0, 1.0, 1.0)
    dim = get_path(path).dim + (0 if problem.kind == KINEMATIC else 3)

    def f(t, y):
        y = np.ascontiguousarray(y, dtype=np.float64)
        if y.shape != (dim,):
            raise InputError(f"y: expected shape ({dim},), got {y.shape}")
        out = np.empty(dim)
        compiled(float(t), y, inertia, params, out)
        return out

    return f


def bare_loop(integrator: Integrator, problem: Problem, path: str, x0, w0, t0, h, nsteps, every):
    """A zero-argument call of the compiled loop alone, its arrays allocated beforehand:
    the floor :meth:`Integrator.run` is measured against (its per-call overhead is its time
    minus this one's; ``benchmarks/bench_overhead.py``).

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> call = bare_loop(get("rk4"), Problem((1.0, 2.0, 3.0)), "quaternion",
    ...                  (1.0, 0, 0, 0), (0.0, 0.0, 2.0), 0.0, 0.01, 100, 100)
    >>> call()  # rows written: the start and the end
    2
    """
    prep = prepared(integrator, problem, path)
    rows = nsteps // every + 1 + (1 if nsteps % every else 0)
    out_t, out_x, out_w = np.empty(rows), np.empty((rows, prep.dim)), np.empty((rows, 3))
    stats = prep.stats.copy()
    x = np.ascontiguousarray(x0, dtype=np.float64)
    w = np.ascontiguousarray(w0, dtype=np.float64)
    loop, inertia, params = prep.loop, prep.inertia, prep.params
    t0, h = float(t0), float(h)

    def call():
        return loop(x, w, t0, h, 0, nsteps, every, inertia, params, out_t, out_x, out_w, stats)

    return call
