"""Source generation: one integrator's templates specialised for one problem and path.

For one (integrator, problem kind, path, declared torque or ω(t) kernels) :func:`source`
writes the text of a Python module, in one of four *forms*:

* ``"loop"``: a run's module::

      from ga_rotors._jit import jit as _jit
      from ga_rotors._kernels import euler_rates
      from ga_rotors.paths.quaternion import rate as o_rate
      ...
      from ga_rotors.effects import gravity as _term_0

      @_jit
      def torque(t, q, w, params):            # the kind's slots (ga_rotors.integrators.kinds)
          return _term_0(t, q, w, params[0:6])

      @_jit
      def accel(t, x, w, inertia, params):
          return euler_rates(inertia, w, torque(t, o_quat(x), w, params))

      @_jit(inline='always')                  # into the loop: invariants hoisted
      def rk4_step(t, x, w, h, inertia, params):
          ...                                   # the template's source, verbatim

      step = rk4_step

      @_jit
      def fixed_step_loop(...):               # the kind's loop template
          ...

      loop = fixed_step_loop

      @_jit
      def limit(inertia, w, h, nsteps):       # the integrator's step limit, measured
          return _measure(inertia, w, h, nsteps, (1.0, 1.0, 0.5, ...), True, True)

      @_jit
      def judged_run(...):                    # limit, loop and watch: a run's one call
          ...

      run = judged_run

* ``"batch"``: the same step, with every function it reaches compiled inline (templates
  and slots ``inline="always"``, imported kernels through :func:`ga_rotors._jit.inline`),
  inside the kind's batched loop (:func:`~ga_rotors.integrators.loops.batch_chunk`) over
  struct-of-arrays states, its row slots written for the path's and the kind's sizes;
  ``loop`` runs the chunks over the cores, ``serial`` in the calling thread. What the kind
  stores per body (the Euler coefficients) is computed once per body and read back where
  the inline kernels would compute it. ``"batch-moments"``: the same, storing nothing
  (for a step that unpacks ``inertia`` into three names, which the longer tuple cannot be);
  ``"batch-centred"``: the ``"batch"`` form binding the path's kernels of a body frame at
  the centre of mass (:func:`centred`), for bodies that all have theirs there;
* ``"rhs"`` (no integrator): the kind's vector-field template with the kind's and the
  path's slots, for scipy-style integrators.

Every global a template uses is resolved in the template's own module: compiled kernels
become imports, numeric constants are copied, slots are bound here. A global that is a
plain Python function (a template) must be among the integrator's steps or ``helpers``,
and a name the template's module does not define is refused: both in one line naming the
template and the name, before numba sees the text.
"""

from __future__ import annotations

import builtins
import dis
import importlib
import inspect
import textwrap
import types

from ..errors import InputError
from ..paths import resolve as resolve_path
from . import loops, slots
from .base import Integrator
from .kinds import KINDS
from .problem import Problem

__all__ = ["BATCH", "BATCH_CENTRED", "BATCH_MOMENTS", "FORMS", "LOOP", "RHS", "centred", "source"]

LOOP, RHS, BATCH, BATCH_MOMENTS = "loop", "rhs", "batch", "batch-moments"
BATCH_CENTRED = "batch-centred"
FORMS = (LOOP, RHS, BATCH, BATCH_MOMENTS, BATCH_CENTRED)

#: Built-in torque kernels that read their parameters p[j] one by one, so they run the same
#: on a tuple as on an array: a batch hands them a tuple per body, which lives in registers
#: and keeps the loop over bodies vectorised (an array view per body is an object LLVM
#: cannot keep in SIMD lanes: the gravity loop ran 5-7x slower per body-step). A user or
#: registered kernel may use array operations and gets its body's column as an array.
_BUILT_IN = ("body_torque", "damping", "gravity", "isotropic_damping", "space_torque",
             "vertical_gravity")  # fmt: skip
_BUILT_IN_FORCES = ("body_force", "central_field", "drag_force", "space_force",
                    "spring_force", "weight")  # fmt: skip
INDEXING_KERNELS = frozenset(("ga_rotors.effects", name) for name in _BUILT_IN) | frozenset(
    ("ga_rotors.forces", name) for name in _BUILT_IN_FORCES
)


def _global_names(code: types.CodeType) -> set[str]:
    """The global names a function's code reads (nested code objects included)."""
    names = {i.argval for i in dis.get_instructions(code) if i.opname == "LOAD_GLOBAL"}
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _global_names(const)
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
        for name in sorted(_global_names(func.__code__)):
            dep = pool.get(name)
            if dep is not None and dep is not func and func.__globals__.get(name) is dep:
                visit(dep)
        seen[func.__name__] = func

    for func in start:
        visit(func)
    return list(seen.values())


class _Imports:
    """Global name -> how the generated module gets it; refuses conflicting bindings.

    ``inline``: the batched forms, where each compiled kernel is imported under a private
    alias and bound to its inline form (``replace`` as :func:`ga_rotors._jit.inline`'s,
    written into the module as ``_STORED``)."""

    def __init__(self, inline: bool = False, stand_in: tuple | None = None):
        self.lines: dict[str, str] = {}
        self.objects: dict[str, object] = {}
        self.modules: set[str] = set()
        self.inline = inline
        self.stand_in = stand_in  # (the stored kernel, the stand-in's name) or None
        self.bindings: dict[str, str] = {}  # name -> "_inline(...)" lines, after the imports

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
        if not (self.inline and hasattr(obj, "py_func")):
            alias = "" if qual == name else f" as {name}"
            self.bind(name, obj, f"from {module} import {qual}{alias}", module)
            return
        compiled = f"_c_{name}"
        self.bind(compiled, obj, f"from {module} import {qual} as {compiled}", module)
        self.objects[name] = obj
        if self.stand_in is not None and obj is self.stand_in[0]:
            self.bindings[name] = f"{name} = {self.stand_in[1]}"
        else:
            stored = "_STORED" if self.stand_in is not None else "()"
            self.bindings[name] = f"{name} = _inline({compiled}, {stored})"


def _resolve_globals(templates: list, generated: set[str], imports: _Imports, owner: str):
    template_names = {f.__name__ for f in templates}
    for func in templates:
        for name in sorted(_global_names(func.__code__)):
            if name in template_names or name in generated or name in slots.ALL_SLOTS:
                continue  # pasted here, generated here, or bound by the caller
            if name not in func.__globals__:
                if hasattr(builtins, name):
                    continue
                raise InputError(
                    f"template {func.__name__} of {owner}: {name!r} is not defined in its "
                    f"module {func.__module__}"
                )
            obj = func.__globals__[name]
            if isinstance(obj, types.ModuleType):
                imports.bind(name, obj, f"import {obj.__name__} as {name}", obj.__name__)
            elif isinstance(obj, bool | int | float) or (
                isinstance(obj, tuple) and all(isinstance(v, int | float) for v in obj)
            ):
                imports.bind(name, obj, f"{name} = {obj!r}", None)
            elif _is_template(obj) and not _jit_disabled():
                raise InputError(
                    f"template {func.__name__} of {owner} calls {name}, a plain Python "
                    f"function that is not among its helpers: add {name} to helpers= "
                    "(or compile it as a kernel)"
                )
            elif callable(obj):
                imports.kernel(name, obj)
            else:
                raise InputError(
                    f"template {func.__name__}: global {name!r} is a {type(obj).__name__}; "
                    "templates may use compiled kernels, modules and numeric constants"
                )


def _jit_disabled() -> bool:
    """Whether numba compiles nothing (``NUMBA_DISABLE_JIT=1``): kernels are then plain
    functions too, and a plain function called from a template runs as it is."""
    from numba.core import config

    return bool(config.DISABLE_JIT)


def _literal(value) -> str:
    """``value`` (a number, a boolean, or a tuple of them) as source text that reads back
    exactly (floats by repr)."""
    if isinstance(value, bool | int | float):
        return repr(value)
    if isinstance(value, tuple):
        return "(" + "".join(_literal(v) + ", " for v in value) + ")"
    raise InputError(f"step limit constants: expected numbers or tuples, got {value!r}")


def _limit_source(integrator: Integrator, judged: bool, imports: _Imports) -> str:
    measure = getattr(integrator.step_limit, "measure", None)
    if measure is None or not judged:  # judged in Python, or nothing to judge
        return "def limit(inertia, w, h, nsteps):\n    return 0.0, 1.0\n"
    imports.kernel("_measure", measure)
    constants = "".join(", " + _literal(c) for c in integrator.step_limit.constants)
    return (
        "def limit(inertia, w, h, nsteps):\n"
        f"    return _measure(inertia, w, h, nsteps{constants})\n"
    )


def _rows(prefix: str, first: int, size: int, put: bool = True) -> list[str]:
    """``{prefix}_rows``, ``{prefix}_get`` (and ``{prefix}_put``) for ``size`` rows of a
    chunk's block that start at row ``first`` (see :func:`_batch_slots`)."""
    rows = "".join(f"s[{k * _BLOCK}:{(k + 1) * _BLOCK}], " for k in range(first, first + size))
    get = "".join(f"r[{k}][i], " for k in range(size))
    out = [
        f"def {prefix}_rows(s):\n    return ({rows.rstrip()})\n",
        f"def {prefix}_get(r, i):\n    return ({get.rstrip()})\n",
    ]
    if put:
        body = "".join(f"    r[{k}][i] = v[{k}]\n" for k in range(size))
        out.append(f"def {prefix}_put(r, i, v):\n{body}")
    return out


#: Bodies in a chunk's block: its rows lie this many numbers apart (loops.BLOCK).
_BLOCK = loops.BLOCK


def _copy_rows(source: str, first: int, size: int) -> str:
    """Lines copying ``size`` rows of ``source`` (lo:hi) into the block from row ``first``."""
    return "".join(
        f"    s[{k * _BLOCK}:{k * _BLOCK} + n] = {source}[{k - first}, lo:hi]\n"
        for k in range(first, first + size)
    )


def _batch_slots(kind, problem: Problem, dim: int, stored: bool, imports: _Imports) -> list[str]:
    """The batched loop's slots for these sizes (see :mod:`.slots`).

    A chunk's bodies are copied into one block (``chunk_load``): each number of the state,
    the body (and what the kind stores per body) and the parameters is a row of
    :data:`~.loops.BLOCK` numbers at a fixed place in one array, and the step reads and
    writes them there (``x_get``, ``x_put``, ...). All the rows the loop over bodies
    touches are then one array at constant distances, which LLVM's vectoriser can check
    for overlap at compile time. Rows of separate arrays (the states' own rows) need a
    runtime check between every two of them, and past LLVM's limit (a whole motion's 14
    state rows and its body's: "too many memory checks") the loop ran one body at a time,
    4 to 6 times slower than the rotation's (benchmarks/bench_motion.py)."""
    rate, size = kind.rate, kind.body_size
    extra = kind.stored_size if stored and kind.stored is not None else 0
    terms = (*problem.torques, *problem.forces)
    indexing = all(term.location in INDEXING_KERNELS for term in terms)
    nparams = problem.params().size if indexing else 0
    first_body, first_param = dim + rate, dim + rate + size + extra
    total = first_param + nparams
    load = (
        "def chunk_load(x, w, body, params, lo, hi):\n"
        "    n = hi - lo\n"
        f"    s = np.empty({max(total, 1) * _BLOCK})\n"
        + _copy_rows("x", 0, dim) + _copy_rows("w", dim, rate)
        + _copy_rows("body", first_body, size)
        + _copy_rows("params", first_param, nparams)
    )  # fmt: skip
    if extra:
        moments = ", ".join(f"body[{k}, lo + i]" for k in range(size))
        load += (
            "    for i in range(n):\n"
            f"        e = _c_stored(({moments},))\n"
            f"        for j in range({extra}):\n"
            f"            s[({first_body + size} + j) * {_BLOCK} + i] = e[j]\n"
        )
    out = [load + "    return s\n"]
    store = "".join(
        f"    out_{name}[{k - first}, lo:hi] = s[{k * _BLOCK}:{k * _BLOCK} + n]\n"
        for name, first, count in (("x", 0, dim), ("w", dim, rate))
        for k in range(first, first + count)
    )
    out.append("def chunk_store(s, out_x, out_w, lo, hi):\n    n = hi - lo\n" + store)
    out += _rows("x", 0, dim) + _rows("w", dim, rate)
    out += _rows("body", first_body, size + extra, put=False)
    if indexing:
        out += _rows("param", first_param, nparams, put=False)
        out[-2] = out[-2].replace("def param_rows(s):", "def param_rows(s, a, lo, hi):")
    else:
        out.append("def param_rows(s, a, lo, hi):\n    return a[:, lo:hi]\n")
        out.append("def param_get(r, i):\n    return r[:, i]\n")
    return out


def centred(problem: Problem, form: str) -> bool:
    """Whether ``form`` of ``problem`` binds the path's kernels of a body frame at the
    centre of mass (a path's ``CENTRED`` names): a whole motion whose centre of mass is
    the frame's origin, in a form whose body is the problem's own; a batch's bodies each
    carry their own centre of mass, so a batch binds them in the ``"batch-centred"`` form
    only (for bodies all at their centres, :func:`~._runner.run_batch` decides).

    Examples
    --------
    >>> centred(Problem((1.0, 2.0, 3.0), mass=1.0), LOOP)
    True
    >>> centred(Problem((1.0, 2.0, 3.0), mass=1.0, centre_of_mass=(0.0, 0.1, 0.0)), LOOP)
    False
    >>> centred(Problem((1.0, 2.0, 3.0), mass=1.0), BATCH)
    False
    """
    if not KINDS[problem.kind].moves:
        return False
    return form == BATCH_CENTRED or (form in (LOOP, RHS) and not any(problem.centre_of_mass))


def source(
    integrator: Integrator | None, problem: Problem, path: str, form: str = LOOP,
    cache: bool = True,
) -> tuple[str, list[str]]:  # fmt: skip
    """The module text specialising ``integrator`` for ``problem`` on ``path`` in ``form``
    (see the module's text), and the modules it imports. ``integrator=None`` with the
    ``"rhs"`` form; ``cache=False``: the functions compile without numba's disk cache.

    Examples
    --------
    >>> from ga_rotors.integrators import get
    >>> text, modules = source(get("rk4"), Problem((1.0, 2.0, 3.0)), "quaternion")
    >>> "step = rk4_step" in text, "torque" in text, "ga_rotors.paths.quaternion" in modules
    (True, False, True)
    """
    kind = KINDS[problem.kind]
    batch = form in (BATCH, BATCH_MOMENTS, BATCH_CENTRED)
    if form == RHS:
        name, step, templates, entry, loop = "vector_field", None, [], None, kind.rhs
    else:
        name = integrator.name
        step = integrator.steps[problem.kind]
        pool = {f.__name__: f for f in (*integrator.steps.values(), *integrator.helpers)}
        for f in pool.values():
            if not _is_template(f):
                raise InputError(f"template {f!r}: expected a plain (uncompiled) Python function")
        templates = _reachable([step], pool)
        if batch:
            if kind.batch is None:
                raise InputError(f"{problem.kind} problems have no batched runs", key="batch")
            loop, entry = kind.batch, loops.batch_loop
        else:
            loop, entry = kind.loop, loops.judged_run
    used = set().union(*(_global_names(f.__code__) for f in (*templates, loop)))

    stored = form in (BATCH, BATCH_CENTRED) and kind.stored is not None
    imports = _Imports(inline=batch, stand_in=(kind.stored, "stored_values") if stored else None)
    if stored:  # computed once per body by the kernel itself, read back by stored_values
        func = kind.stored.py_func
        imports.bind("_c_stored", kind.stored,
                     f"from {func.__module__} import {func.__qualname__} as _c_stored",
                     func.__module__)  # fmt: skip
    generated: list[str] = []
    # the kind's slots that the step (or the loop) reaches, and the slots they call
    wanted = [s for s in kind.slots if s in used]
    for slot in wanted:
        for extra in sorted(kind.slots[slot].calls):
            if extra not in used:
                used.add(extra)
                if extra in kind.slots and extra not in wanted:
                    wanted.append(extra)
    every_kind = set().union(*(k.slots for k in KINDS.values()))
    for slot in sorted((used & every_kind) - set(kind.slots)):
        raise InputError(f"{name}: its {problem.kind} step calls {slot}(), which "
                         f"{problem.kind} problems do not have")  # fmt: skip
    if kind.evaluates is not None and kind.evaluates not in used:
        raise InputError(f"{name}: its {problem.kind} step never evaluates {kind.evaluates}()")
    for slot in wanted:
        generated.append(kind.slots[slot].write(problem, imports))

    spec = resolve_path(path, kind.moves)
    module = spec.load()
    swaps = getattr(module, "CENTRED", {}) if centred(problem, form) else {}
    for slot, attr in slots.PATH_SLOTS.items():
        if slot in used:
            if not hasattr(module, attr):
                raise InputError(f"{name}: uses {slot}, which the {path!r} path does not have")
            imports.kernel(slot, getattr(module, swaps.get(attr, attr)))
    for slot, attr in slots.KIND_SLOTS.items():
        if slot in used:
            imports.kernel(slot, getattr(kind, attr))

    names = {"step", "loop", "limit", "batch_loop", "stored_values", *slots.GENERATED_SLOTS}
    pasted = [*templates, loop, *([entry] if entry is not None else [])]
    _resolve_globals(pasted, names, imports, name)
    if form == LOOP:
        limit_text = _limit_source(integrator, kind.judged, imports)
    if batch:
        generated += _batch_slots(kind, problem, spec.dim, stored, imports)

    if cache:
        header = "from ga_rotors._jit import jit as _jit\n"
    else:
        header = "from functools import partial\n\nfrom ga_rotors._jit import jit\n\n"
        header += "_jit = partial(jit, cache=False)\n"
    body = [header]
    if batch:
        body.append("from ga_rotors._jit import inline as _inline\nimport numpy as np\n")
    constants = [v for v in imports.lines.values() if not v.startswith(("from ", "import "))]
    body += [line + "\n" for line in sorted(set(imports.lines.values()) - set(constants))]
    body += [line + "\n" for line in sorted(constants)]
    inlined = "\n\n@_jit(inline='always')\n"
    small = inlined if batch else "\n\n@_jit\n"
    if stored:
        size = kind.body_size
        body.append(f"{small}def stored_values(inertia):\n"
                    f"    return inertia[{size}:{size + kind.stored_size}]\n")  # fmt: skip
        body.append("\n\n_STORED = ((_c_stored, stored_values),)\n")
    if imports.bindings:
        body.append("\n" + "".join(line + "\n" for _, line in sorted(imports.bindings.items())))
    for text in generated:
        body.append(small + text)
    # The templates are compiled into the loop that calls them in every form: a step
    # compiled on its own is a call LLVM does not inline (too large), so what depends on
    # loop invariants only (the Euler coefficients' divisions, 1/m) was divided again in
    # every step (8 divisions an RK4 step; inline, the motion loops of
    # benchmarks/bench_motion.py went from 82 to 75 ns a step on the motor path and 42 to
    # 32 on the quaternion path, and compile no slower: fewer functions).
    for func in templates:
        body.append(inlined + _template_source(func))
    if step is not None:
        body.append(f"\n\nstep = {step.__name__}\n")
    body.append("\n\n@_jit\n" + _template_source(loop))
    if batch:
        driver = _template_source(entry)
        body.append("\n\n@_jit(parallel=True)\n" + driver + "\n\nloop = batch_loop\n")
        serial = driver.replace("def batch_loop(", "def batch_serial(", 1)
        body.append("\n\n@_jit\n" + serial + "\n\nserial = batch_serial\n")
    else:
        alias = "rhs" if form == RHS else "loop"
        body.append(f"\n\n{alias} = {loop.__name__}\n")
    if form == LOOP:
        body.append("\n\n@_jit\n" + limit_text)
        body.append("\n\n@_jit\n" + _template_source(entry))
        body.append(f"\n\nrun = {entry.__name__}\n")
    terms = [t.name for t in (*problem.torques, *problem.forces)] or (
        [problem.omega.name] if problem.omega else []
    )
    doc = (
        f'"""Generated by ga_rotors.integrators._source; do not edit.\n\n'
        f"integrator={name} problem={problem.kind} path={path} form={form} terms={terms}\n"
        '"""\n\n'
    )
    return doc + "".join(body), sorted(imports.modules)
