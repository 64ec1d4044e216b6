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
and its index only, never on how the sweep is chunked or which worker runs it.
Grid and draw keys must be under ``body``, ``initial`` or ``effects`` (what differs
between the samples of one ensemble); ``time`` and ``integrator`` keys go in ``[set]``.
"""

from __future__ import annotations

import hashlib
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, SceneError
from ..scene.reader import Reader, join

__all__ = ["BLOCK", "DISTRIBUTIONS", "Sweep", "load_sweep"]

#: Samples per random-number block (a constant of the format: changing it changes draws).
BLOCK = 4096

#: distribution name -> its two parameters.
DISTRIBUTIONS = {"normal": ("mean", "std"), "uniform": ("low", "high")}

_VARYING = ("body.", "initial.", "effects[")

#: The largest float64 below 1: where a normal draw's u = 1 goes (ndtri(1) is inf).
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
    def chunks(self) -> int:
        return -(-self.size // self.chunk)

    @property
    def digest(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()[:16]

    def values(self, lo: int, hi: int) -> dict[str, np.ndarray]:
        """Each varied key's values for samples ``lo`` to ``hi - 1``."""
        s = np.arange(lo, hi, dtype=np.int64)
        out: dict[str, np.ndarray] = {}
        if self.grid:
            shape = [len(v) for _, v in self.grid]
            index = np.unravel_index(s // self.samples, shape)
            for (key, v), idx in zip(self.grid, index, strict=True):
                out[key] = v[idx]
        if self.draws:
            u = _uniforms(self.seed, lo, hi, len(self.draws))
            for j, (key, dist, (a, b)) in enumerate(self.draws):
                x = u[:, j].copy()  # contiguous, and then worked on in place
                if dist == "normal":
                    from scipy.special import ndtri

                    np.minimum(x, _BELOW_ONE, out=x)  # u = 1 (once in 2⁵³): ndtri gives inf
                    ndtri(x, out=x)
                    x *= b
                    x += a
                else:
                    x *= b - a
                    x += a
                out[key] = x
        return out


def _uniforms(seed: int, lo: int, hi: int, nvars: int) -> np.ndarray:
    """Uniforms in (0, 1) for samples lo..hi-1, from their blocks' own streams.

    Sample s, variable j takes the (s mod BLOCK)·nvars + j-th 64-bit output x of its
    block's PCG64 stream, as k = x >> 11 (what ``Generator.integers(0, 2**53)`` gives:
    Lemire's method never rejects for a range of 2⁵³), then u = (k + ½)·2⁻⁵³ in float64:
    in (0, 1], since k = 2⁵³ − 1 rounds to 1 (k + ½ rounds to even above 2⁵²), which a
    normal draw takes as :data:`_BELOW_ONE` so its inverse CDF stays finite.
    """
    out = np.empty((hi - lo, nvars))
    for block in range(lo // BLOCK, -(-hi // BLOCK)):
        start = block * BLOCK
        a, b = max(lo, start), min(hi, start + BLOCK)
        bits = np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(block,)))
        raw = bits.random_raw((b - start) * nvars)[(a - start) * nvars :]
        out[a - lo : b - lo] = (raw >> np.uint64(11)).reshape(b - a, nvars)
    out += 0.5
    out *= 2.0**-53
    return out


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
