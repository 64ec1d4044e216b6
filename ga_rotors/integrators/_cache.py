"""The disk cache of generated modules: where they live, naming, loading, pruning, clearing.

:func:`specialise` gives the imported module of one specialisation (see
:mod:`._source`): made once per process (kept in memory), and written once per
installation into a private cache directory, named by a SHA-256 of its text and of every
source file it can reach (the whole ga_rotors package, the numba version, and the modules
of kernels from elsewhere), then imported from there, so numba's on-disk cache (keyed on
that file) keeps its machine code across processes and can never serve stale code.

Cache directory: ``$GA_ROTORS_CACHE_DIR/generated`` if set, else
``$XDG_CACHE_HOME/ga_rotors/generated`` or ``~/.cache/ga_rotors/generated``; private
(:func:`ga_rotors._private_dir.private_directory`). If nothing is writable, modules are
compiled in memory without caching (a one-off cost of about a second per loop). Modules of
other package versions are pruned after :data:`PRUNE_AFTER_DAYS`; ``ga-rotors cache``
lists and clears them.
"""

from __future__ import annotations

import functools
import hashlib
import importlib
import importlib.util
import os
import sys
import time
import types
from dataclasses import dataclass
from pathlib import Path

from .. import _modules
from .._private_dir import private_directory
from ..files import write_text
from . import _source
from .base import Integrator
from .problem import Problem

__all__ = [
    "PRUNE_AFTER_DAYS",
    "CacheFile",
    "Specialisation",
    "cache_location",
    "cached_modules",
    "clear_cache",
    "prune_cache",
    "specialise",
    "version_tag",
]

PACKAGE_ROOT = Path(__file__).resolve().parent.parent
_MEMO: dict[tuple, Specialisation] = {}


@dataclass(frozen=True)
class Specialisation:
    """A generated, imported module (``path`` None when compiled in memory) and its text."""

    module: types.ModuleType
    path: Path | None
    source: str


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


def _memo_key(integrator, problem: Problem, path: str, form: str) -> tuple:
    terms = (problem.omega,) if problem.omega is not None else (*problem.torques, *problem.forces)
    return (
        form,
        "field" if integrator is None else integrator.name,
        id(integrator),
        problem.kind,
        path,
        tuple((term.location, len(term.params)) for term in terms),
        _source.centred(problem, form),  # other kernels bound (the frame at the centre)
    )


def specialise(
    integrator: Integrator | None, problem: Problem, path: str, form: str = _source.LOOP
) -> Specialisation:
    """Generate (or reuse) and import the module of ``integrator`` for ``problem`` on
    ``path`` in ``form`` (:mod:`._source`; ``integrator=None`` with ``"rhs"``).

    Thread-safe: made and loaded under :data:`ga_rotors._modules.GENERATED_LOCK` (a
    module is registered before it has run; a thread finding it half made would fail).

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> spec = specialise(get("rk4"), Problem((1.0, 2.0, 3.0)), "quaternion")
    >>> spec.path is None or spec.path.name.startswith("gen_rk4_free_quaternion_loop_")
    True

    Its text is kept for tracebacks and ``inspect`` (even for a module compiled in
    memory):

    >>> import inspect
    >>> inspect.getsource(spec.module.step.py_func).splitlines()[:2]
    ["@_jit(inline='always')", 'def rk4_step(t, x, w, h, inertia, params):']
    """
    key = _memo_key(integrator, problem, path, form)
    found = _MEMO.get(key)
    if found is not None:
        return found
    with _modules.GENERATED_LOCK:
        found = _MEMO.get(key)  # made by the thread this one waited for
        if found is None:
            found = _MEMO[key] = _specialise(integrator, problem, path, form)
        return found


def _specialise(integrator, problem: Problem, path: str, form: str) -> Specialisation:
    directory = cache_location()
    text, modules = _source.source(integrator, problem, path, form, cache=directory is not None)
    label = "field" if integrator is None else integrator.name
    stem = f"gen_{label}_{problem.kind}_{path}_{form}_{version_tag()}_{_digest(text, modules)}"
    modname = f"_ga_rotors_{stem}"
    file = directory / f"{stem}.py" if directory is not None else None
    loaded = sys.modules.get(modname)
    if loaded is not None and getattr(loaded, "__file__", None) == str(file or f"<{modname}>"):
        return Specialisation(loaded, file, text)
    if file is not None:
        try:
            _prune_once()
            _write_once(file, text)
            _modules.remember_source(str(file), text)
            spec = importlib.util.spec_from_file_location(modname, file)
            return Specialisation(_modules.load_registered(spec), file, text)
        except OSError:  # the cache went away or filled up: compiled in memory instead
            text, _ = _source.source(integrator, problem, path, form, cache=False)
    return Specialisation(_modules.load_source(modname, text), None, text)
