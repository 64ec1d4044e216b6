"""A sweep file: which scene, which keys vary over a grid or by random draws, and the seed.

A sweep is data (TOML, parsed with :mod:`tomllib`, nothing evaluated)::

    [sweep]
    scene = "spinning_disk"   # a bundled scene's name, or a file relative to this one
    samples = 1000            # random draws per grid point (default 1)
    seed = 2026               # required when there are draws
    chunk = 1024              # samples per stored chunk (default 1024)
    times = [5.0, 10.0]       # output times in s (default: the end of the run)

    [set]                     # fixed changes to the scene, any key (optional)
    "time.duration" = 10.0

    [grid]                    # every combination of these values (optional)
    "initial.angular_velocity.euler_rates[2]" = [15.0, 15.7]

    [[draw]]                  # one table per randomly drawn key (optional)
    key = "body.mass"
    normal = [2.0, 0.02]      # mean, standard deviation; or uniform = [low, high]

Sample ``s`` belongs to grid point ``s // samples`` (grid points in row-major order of
the ``[grid]`` keys: the last key varies fastest). Its draws come from the random
stream of its block of :data:`BLOCK` consecutive samples, seeded by
``SeedSequence(seed, spawn_key=(block,))``: the numbers of a sample depend on the seed
and its index only, never on how the sweep is chunked or which worker runs it, nor on
the versions of numpy or scipy (the normal's quantile is ga_rotors' own, see
:data:`DRAWS_VERSION`).
Grid and draw keys must be under ``body``, ``initial`` or ``effects`` (what differs
between the samples of one ensemble); ``time`` and ``integrator`` keys go in ``[set]``.
"""

from __future__ import annotations

import hashlib
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numba
import numpy as np
from llvmlite import ir
from numba.extending import intrinsic

from .._jit import jit
from ..errors import InputError, SceneError
from ..files import aligned_empty
from ..scene.reader import Reader, join
from . import _normal

__all__ = ["BLOCK", "DISTRIBUTIONS", "DRAWS_VERSION", "Sweep", "load_sweep"]

#: Samples per random-number block (a constant of the format: changing it changes draws).
BLOCK = 4096

#: How the draws are made from the seed, recorded in every store (``draws_version``): 2
#: since the normal draws take ga_rotors' own quantile (:mod:`ga_rotors.sweep._normal`);
#: version 1 took scipy's ``ndtri``, which may differ in the last bits. A store of
#: another version with normal draws is not resumed (its remaining chunks would draw
#: other numbers than its first ones).
DRAWS_VERSION = 2

#: distribution name -> its two parameters.
DISTRIBUTIONS = {"normal": ("mean", "std"), "uniform": ("low", "high")}

_VARYING = ("body.", "initial.", "effects[")

#: The largest float64 below 1: where a normal draw's u = 1 goes (its quantile is inf).
_BELOW_ONE = np.nextafter(1.0, 0.0)


@dataclass(frozen=True)
class Sweep:
    """A validated sweep.

    Attributes
    ----------
    scene : Scene
        The base scene, with ``[set]`` applied.
    grid : tuple of (key, ndarray)
        Keys and their values, one row per value.
    draws : tuple of (key, distribution, (a, b))
    samples, seed, chunk : int
    times : ndarray or None
    text : str
        The sweep file's text; ``digest`` identifies the sweep (a store belongs to one).

    Examples
    --------
    >>> s = load_sweep('''
    ... [sweep]
    ... scene = "intermediate_axis_flip"
    ... samples = 3
    ... seed = 1
    ... [set]
    ... "time.duration" = 0.01
    ... [grid]
    ... "initial.angular_velocity.body[1]" = [10.0, 12.0]
    ... [[draw]]
    ... key = "initial.angular_velocity.body[2]"
    ... normal = [0.0, 0.01]
    ... ''')
    >>> s.size, s.keys
    (6, ['initial.angular_velocity.body[1]', 'initial.angular_velocity.body[2]'])
    >>> v = s.values(0, 6)
    >>> v["initial.angular_velocity.body[1]"].tolist()
    [10.0, 10.0, 10.0, 12.0, 12.0, 12.0]
    >>> bool(np.array_equal(s.values(2, 5)["initial.angular_velocity.body[2]"],
    ...                     v["initial.angular_velocity.body[2]"][2:5]))
    True
    """

    scene: object
    grid: tuple
    draws: tuple
    samples: int
    seed: int | None
    chunk: int
    times: np.ndarray | None
    text: str
    file: str

    @property
    def grid_points(self) -> int:
        # math.prod: exact for any size (a budget then refuses it), where numpy's int64 wraps
        return math.prod(len(v) for _, v in self.grid)

    @property
    def size(self) -> int:
        """Total number of samples."""
        return self.grid_points * self.samples

    @property
    def keys(self) -> list[str]:
        return [k for k, _ in self.grid] + [k for k, _, _ in self.draws]

    @property
    def rows(self) -> tuple[tuple[str, int], ...]:
        """Each varied key with its number of rows in :meth:`columns` (3 for a vector)."""
        widths = [int(np.prod(v.shape[1:])) for _, v in self.grid] + [1] * len(self.draws)
        return tuple(zip(self.keys, widths, strict=True))

    @property
    def chunks(self) -> int:
        return -(-self.size // self.chunk)

    @property
    def digest(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()[:16]

    def values(self, lo: int, hi: int) -> dict[str, np.ndarray]:
        """Each varied key's values for samples ``lo`` to ``hi - 1``."""
        return self.columns(lo, hi)[1]

    def columns(self, lo: int, hi: int) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """The values of samples ``lo`` to ``hi - 1`` as one array, and by key.

        ``cols`` (rows, n) holds one row per varied number, in the order of :attr:`keys`
        (a key whose values are vectors takes one row per component); the dict gives each
        key's values as views of it, what :meth:`values` returns.

        Examples
        --------
        >>> s = load_sweep('[sweep]\\nscene = "heavy_top"\\n[grid]\\n"body.mass" = [1.0, 2.0]')
        >>> cols, values = s.columns(0, 2)
        >>> cols.tolist(), values["body.mass"].tolist()
        ([[1.0, 2.0]], [1.0, 2.0])
        """
        n = hi - lo
        widths = [width for _, width in self.rows]
        cols = aligned_empty((sum(widths), n))  # its rows are written to the store as they are
        out: dict[str, np.ndarray] = {}
        row = 0
        if self.grid:
            s = np.arange(lo, hi, dtype=np.int64)
            shape = [len(v) for _, v in self.grid]
            index = np.unravel_index(s // self.samples, shape)
            for (key, v), idx, width in zip(self.grid, index, widths, strict=False):
                block = cols[row : row + width]
                block[:] = v[idx].reshape(n, width).T
                out[key] = block[0] if v.ndim == 1 else block.T.reshape(n, *v.shape[1:])
                row += width
        if self.draws:
            kinds = np.array([dist == "normal" for _, dist, _ in self.draws])
            a = np.array([p[0] for _, _, p in self.draws])
            # the uniform's width as numpy computed it (b - a in float64), the normal's std
            b = np.array([p[1] - p[0] if d == "uniform" else p[1] for _, d, p in self.draws])
            draws = cols[row:]
            _draw(_streams(self.seed, lo, hi, len(self.draws)), lo, kinds, a, b, draws)
            for j, (key, _, _) in enumerate(self.draws):
                out[key] = draws[j]
        return cols, out


def _streams(seed: int, lo: int, hi: int, nvars: int) -> np.ndarray:
    """Where the draws of samples lo..hi-1 start in their blocks' streams: one row per
    block, its PCG64 state and increment as (high, low) 64-bit words, advanced to the
    output of sample max(lo, block start), variable 0.

    Sample s, variable j takes the (s mod BLOCK)·nvars + j-th 64-bit output of its
    block's PCG64 stream, seeded by ``SeedSequence(seed, spawn_key=(block,))``. Each row
    is numpy's own generator, seeded and advanced (:meth:`numpy.random.PCG64.advance`);
    :func:`_draw` then runs the streams on in compiled code.
    """
    rows = []
    for block in range(lo // BLOCK, -(-hi // BLOCK)):
        bits = np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(block,)))
        bits.advance((max(lo, block * BLOCK) - block * BLOCK) * nvars)
        state = bits.state["state"]
        rows.append([w for v in (state["state"], state["inc"]) for w in divmod(v, 2**64)])
    return np.array(rows, dtype=np.uint64).reshape(-1, 4)  # (0, 4) for no samples


#: numpy's PCG64: the 128-bit linear congruential generator's multiplier (its output is
#: XSL-RR: the high word XOR the low one, rotated right by the top 6 bits).
_PCG_MULTIPLIER = 0x2360ED051FC65DA44385DF649FCCF645


def _plain_pcg_step(hi, lo, inc_hi, inc_lo):
    """The compiled step in Python integers, for the draws run uncompiled."""
    state = ((int(hi) << 64 | int(lo)) * _PCG_MULTIPLIER + (int(inc_hi) << 64 | int(inc_lo))) % (
        1 << 128
    )
    return np.uint64(state >> 64), np.uint64(state & (2**64 - 1))


@intrinsic
def _compiled_pcg_step(typingctx, hi, lo, inc_hi, inc_lo):
    """PCG64's state (hi, lo) after one step, state·multiplier + increment mod 2¹²⁸, in
    LLVM's 128-bit integers (numba has none; LLVM makes it three 64-bit products)."""
    words = numba.types.UniTuple(numba.types.uint64, 2)
    signature = words(numba.types.uint64, numba.types.uint64, numba.types.uint64,
                      numba.types.uint64)  # fmt: skip

    def codegen(context, builder, sig, args):
        wide, word = ir.IntType(128), ir.IntType(64)

        def join(high, low):
            high = builder.shl(builder.zext(high, wide), ir.Constant(wide, 64))
            return builder.or_(high, builder.zext(low, wide))

        state = builder.mul(join(args[0], args[1]), ir.Constant(wide, _PCG_MULTIPLIER))
        state = builder.add(state, join(args[2], args[3]))
        high = builder.trunc(builder.lshr(state, ir.Constant(wide, 64)), word)
        return context.make_tuple(builder, sig.return_type, (high, builder.trunc(state, word)))

    return signature, codegen


_pcg_step = _plain_pcg_step if numba.config.DISABLE_JIT else _compiled_pcg_step


@jit(inline="always")
def _pcg_output(hi, lo):
    """PCG64's 64-bit output of the state (hi, lo) it has just stepped to."""
    x = hi ^ lo
    turn = hi >> np.uint64(58)
    return (x >> turn) | (x << ((np.uint64(64) - turn) & np.uint64(63)))


@jit(inline="always")
def _uniform(x):
    """u in (0, 1] from the 64-bit output x: k = x >> 11 (what ``Generator.integers(0,
    2**53)`` gives: Lemire's method never rejects for a range of 2⁵³), u = (k + ½)·2⁻⁵³ in
    float64 (k = 2⁵³ − 1 rounds to 1: k + ½ rounds to even above 2⁵²)."""
    return (float(x >> np.uint64(11)) + 0.5) * 2.0**-53


@jit
def _draw(streams, lo, normal, a, b, out):
    """out[j, i]: draw j of sample lo + i (:func:`_from_uniform`), from its block's
    stream (``streams``, :func:`_streams`), the samples of a block in order, their
    variables in order: the stream's outputs as they come, with no array of them. The
    streams fill ``out`` with the uniform u, which :func:`_from_uniform` then maps."""
    nvars, n = out.shape
    block = -1
    hi = low = inc_hi = inc_lo = np.uint64(0)
    for i in range(n):
        if i == 0 or (lo + i) % BLOCK == 0:
            block += 1
            hi, low = streams[block, 0], streams[block, 1]
            inc_hi, inc_lo = streams[block, 2], streams[block, 3]
        for j in range(nvars):
            hi, low = _pcg_step(hi, low, inc_hi, inc_lo)
            out[j, i] = _uniform(_pcg_output(hi, low))
    _from_uniform(normal, a, b, out)


@jit
def _from_uniform(normal, a, b, out):
    """Row j of ``out``, uniform u (:func:`_uniform`), made draw j in place: a normal draw
    is inverse_normal(u)·std + mean (:mod:`ga_rotors.sweep._normal`, with u = 1 taken as
    :data:`_BELOW_ONE` so that the quantile stays finite), a uniform one u·(high − low) +
    low (``b`` holds the width), one rounding per operation.

    A normal row takes the central piece of the quantile for every u at once (a loop
    without a branch, which LLVM vectorises), lists where u lies in a tail (15 % of the
    draws, at random: a branch per draw would be mispredicted that often) and takes the
    tail piece there, one after the other (so the processor overlaps their logarithms),
    then scales the row. Measured on one thread, 983,040 samples of two normal draws in
    chunks of 65,536, the streams' set-up included: 13 ms, against about 29 ms with
    scipy's ``ndtri`` called per draw (26.5 ms for the draw loop, 2.7 for the streams).
    """
    nvars, n = out.shape
    x = np.empty(n)
    tails = np.empty(n, dtype=np.int64)
    for j in range(nvars):
        row, aj, bj = out[j], a[j], b[j]
        if normal[j]:
            for i in range(n):
                row[i] = min(row[i], _BELOW_ONE)
                x[i] = _normal.central(row[i])
            k = 0
            for i in range(n):
                tails[k] = i
                k += _normal.in_tail(row[i])
            for m in range(k):
                x[tails[m]] = _normal.tail(row[tails[m]])
            for i in range(n):
                row[i] = x[i] * bj + aj
        else:
            for i in range(n):
                row[i] = row[i] * bj + aj


def load_sweep(source) -> Sweep:
    """Read a sweep from a ``.toml`` file or from TOML text.

    Examples
    --------
    >>> load_sweep('[sweep]\\nscene = "heavy_top"\\nsamples = 2').size
    2
    >>> load_sweep('[sweep]\\nscene = "heavy_top"\\nsampels = 2')
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: <string>: sweep.sampels: unknown key (did you mean 'samples'?); ...
    """
    from ..scene import load_scene

    if isinstance(source, Path) or (isinstance(source, str) and source.endswith(".toml")):
        path = Path(source)
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise InputError(f"{path}: cannot read the sweep file ({exc.strerror})") from None
        file, base = str(path), path.parent
    else:
        text, file, base = str(source), "<string>", Path(".")
    r = Reader(file)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(file, "", f"not valid TOML: {exc}") from None
    top = r.table(data, "", ("sweep", "set", "grid", "draw"), ("sweep",))
    sw = r.table(top["sweep"], "sweep", ("scene", "samples", "seed", "chunk", "times"), ("scene",))
    name = r.string(sw["scene"], "sweep.scene")
    candidate = base / name
    try:
        scene = load_scene(candidate if candidate.suffix == ".toml" else name)
    except InputError as exc:
        raise SceneError(file, "sweep.scene", str(exc)) from None
    samples = _count(r, sw.get("samples", 1), "sweep.samples")
    chunk = _count(r, sw.get("chunk", 1024), "sweep.chunk")
    times = None
    if "times" in sw:
        times = np.array(r.numbers(sw["times"], "sweep.times"))
        if not times.size:
            raise r.error("sweep.times", "expected at least one output time (s)")
    changes = r.table(top.get("set", {}), "set", _any_keys(top.get("set", {})))
    if changes:
        try:
            scene = scene.replace(changes)
        except InputError as exc:
            raise SceneError(file, "set", str(exc)) from None
    grid = []
    for key, values in r.table(top.get("grid", {}), "grid", _any_keys(top.get("grid", {}))).items():
        _varying(r, key, join("grid", key))
        items = r.array(values, join("grid", key))
        if not items:
            raise r.error(join("grid", key), "expected at least one value")
        try:
            grid.append((key, np.array(items, dtype=np.float64)))
        except (TypeError, ValueError):
            raise r.error(join("grid", key), "expected numbers or equal-length arrays") from None
    draws = []
    for i, d in enumerate(r.array(top.get("draw", []), "draw")):
        key = join("draw", i)
        d = r.table(d, key, ("key", *DISTRIBUTIONS), ("key",))
        k = r.string(d["key"], join(key, "key"))
        _varying(r, k, join(key, "key"))
        dist = r.one_of(d, key, DISTRIBUTIONS)
        a, b = r.vector(d[dist], join(key, dist), 2, unit=" and ".join(DISTRIBUTIONS[dist]))
        if dist == "normal" and b < 0:
            raise r.error(join(key, dist), f"expected std ≥ 0, got {b:g}")
        if dist == "uniform" and b < a:
            raise r.error(join(key, dist), f"expected low ≤ high, got [{a:g}, {b:g}]")
        draws.append((k, dist, (a, b)))
    keys = [k for k, _ in grid] + [k for k, _, _ in draws]
    if len(set(keys)) != len(keys):
        raise r.error("draw", "a key is varied twice (in grid and draw, or in two draws)")
    # checked even when unused: a typo'd seed should not pass silently
    seed = _count(r, sw["seed"], "sweep.seed", zero=True) if "seed" in sw else None
    if draws and seed is None:
        raise r.error("sweep.seed", "missing; random draws need a seed")
    seed = seed if draws else None
    return Sweep(scene, tuple(grid), tuple(draws), samples, seed, chunk, times, text, file)


def _any_keys(table) -> list:
    return list(table) if isinstance(table, dict) else []


def _count(r: Reader, value, key: str, zero: bool = False) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < (0 if zero else 1):
        raise r.error(key, f"expected an integer ≥ {0 if zero else 1}, got {value!r}")
    return int(value)


def _varying(r: Reader, key: str, where: str) -> None:
    if not key.startswith(_VARYING):
        raise r.error(
            where,
            f"{key!r} cannot vary between the samples of one ensemble (they share the time "
            "grid and integrator); vary keys under body, initial or effects, or set it in [set]",
        )
