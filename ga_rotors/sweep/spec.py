"""A sweep file read and validated: which scene, which keys vary over a grid or by
random draws, and where each sample's values come from.

The file's format, for users, is the section "The sweep file" of ``docs/ensembles.md``;
it is data (TOML through the scene files' guards, nothing evaluated).

The draws are a format too (the tests pin them bit for bit). Sample ``s`` is its
position in row-major order over the grid's axes (in the file's order), then
``sample``. It takes its numbers from the stream of its block of :data:`BLOCK`
consecutive samples, ``Generator(PCG64(SeedSequence(seed, spawn_key=(s // BLOCK,))))``:
the uniform numbers ``(s mod BLOCK)·d`` to ``(s mod BLOCK)·d + d − 1`` (``d`` draws a
sample, in the order of the ``[[draw]]`` tables), each ``u = Generator.random() + 2⁻⁵⁴``
(never 0). A normal draw is ``mean + std·ndtri(u)`` (:func:`scipy.special.ndtri`, ``u``
kept below 1), a uniform one ``low + u·(high − low)``. So a sample's numbers depend on
the seed and its position only, never on how the sweep is chunked or who draws it.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ECHO_LIMIT, InputError
from ..scene.model import whole_steps_at
from ..scene.reader import Reader, join

__all__ = [
    "BLOCK",
    "DEFAULT_CHUNK",
    "DISTRIBUTIONS",
    "Draw",
    "Sweep",
    "coordinate_name",
    "load_sweep",
    "read_sweep",
]

#: Samples per random-number block (a constant of the format: changing it changes draws).
BLOCK = 4096

#: Samples a chunk holds at most, unless the sweep file says otherwise.
DEFAULT_CHUNK = 65536

#: distribution name -> its two parameters.
DISTRIBUTIONS = {"normal": ("mean", "std"), "uniform": ("low", "high")}

#: Largest seed (SeedSequence takes any, the store's attribute a 128-bit integer).
MAX_SEED = 2**128 - 1

_VARYING = ("body.", "initial.", "effects[", "forces[")
_PARTS = re.compile(r"[^.\[\]]+|\[\d+\]")

#: The largest float64 below 1: where a normal draw's u that rounded to 1 goes.
_BELOW_ONE = np.nextafter(1.0, 0.0)


def coordinate_name(key: str) -> str:
    """The name of a varied key's coordinate in a sweep store: the scene key with every
    run of characters other than letters, digits and ``_`` made one ``_`` (a valid
    Python identifier and netCDF name: ``ds.body_moments_0``).

    Examples
    --------
    >>> coordinate_name("body.moments[0]"), coordinate_name("effects[1].pivot_to_com[2]")
    ('body_moments_0', 'effects_1_pivot_to_com_2')
    """
    return re.sub(r"[^A-Za-z0-9_]+", "_", key).strip("_")


def block_shape(shape: tuple[int, ...], most: int) -> tuple[int, ...]:
    """A block of at most ``most`` elements of an array of ``shape`` that is consecutive
    in row-major order: whole trailing axes while they fit, part of the next, one along
    the others. The axis cut is cut into as few pieces as fit, of equal lengths as far
    as they go (10⁶ samples in blocks of at most 65,536: 16 of 62,500, not 15 and a
    sixteenth of 17,984), so that chunks run on a few threads finish together.

    Examples
    --------
    >>> block_shape((3, 5, 4), 10), block_shape((3, 5, 4), 100), block_shape((10**6,), 65536)
    ((1, 2, 4), (3, 5, 4), (62500,))
    """
    out, inner = list(shape), 1
    for i in reversed(range(len(out))):
        if inner * out[i] > most:
            pieces = -(-out[i] // max(1, most // inner))
            out[i] = -(-out[i] // pieces)
            out[:i] = [1] * i
            break
        inner *= out[i]
    return tuple(out)


@dataclass(frozen=True)
class Draw:
    """A randomly drawn key: ``normal`` (a = mean, b = std) or ``uniform`` (a = low,
    b = high).

    Examples
    --------
    >>> d = Draw("body.mass", "uniform", 1.0, 3.0)
    >>> d.centre, d.from_uniform(np.array([0.25, 1.0])).tolist()
    (2.0, [1.5, 3.0])
    >>> Draw("body.mass", "normal", 2.0, 0.1).from_uniform(np.array([0.5])).tolist()
    [2.0]
    """

    key: str
    distribution: str
    a: float
    b: float

    @property
    def centre(self) -> float:
        """The value a grid point's nominal run takes: the mean, or the interval's middle."""
        return self.a if self.distribution == "normal" else self.a + (self.b - self.a) / 2

    def from_uniform(self, u: np.ndarray) -> np.ndarray:
        """This draw's values for the uniform numbers ``u`` in (0, 1], made in ``u``."""
        if self.distribution == "normal":
            from scipy.special import ndtri

            ndtri(np.minimum(u, _BELOW_ONE, out=u), out=u)
            u *= self.b
        else:
            u *= self.b - self.a
        u += self.a
        return u


@dataclass(frozen=True)
class Sweep:
    """A validated sweep.

    Attributes
    ----------
    scene : Scene
        The base scene, with ``[set]`` applied.
    grid : tuple of (key, ndarray)
        Each grid key and its values.
    draws : tuple of Draw
    samples : int
        Draws per grid point (1 without draws).
    seed : int or None
    chunk : int
        Samples a chunk holds at most.
    times : ndarray
        The output times (s) as the file gives them (default: the end of the run).
    text, file : str
        The sweep file's text and name.

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
    >>> s.dims, s.shape, s.size
    (('initial_angular_velocity_body_1', 'sample'), (2, 3), 6)
    >>> s.values(0, 6)["initial.angular_velocity.body[1]"].tolist()
    [10.0, 10.0, 10.0, 12.0, 12.0, 12.0]
    """

    scene: object
    grid: tuple
    draws: tuple
    samples: int
    seed: int | None
    chunk: int
    times: np.ndarray
    text: str
    file: str

    # ------------------------------------------------------------------ the layout

    @property
    def keys(self) -> list[str]:
        """The varied keys: the grid's, then the draws'."""
        return [k for k, _ in self.grid] + [d.key for d in self.draws]

    @property
    def names(self) -> dict[str, str]:
        """Each varied key -> its coordinate's name (:func:`coordinate_name`)."""
        return {key: coordinate_name(key) for key in self.keys}

    @property
    def dims(self) -> tuple[str, ...]:
        """The samples' dimensions: one per grid key, then ``sample`` with draws."""
        return tuple(coordinate_name(k) for k, _ in self.grid) + ("sample",) * bool(self.draws)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for _, v in self.grid) + (self.samples,) * bool(self.draws)

    @property
    def grid_points(self) -> int:
        # math.prod: exact for any size (a budget then refuses it), where numpy's int64 wraps
        return math.prod(len(v) for _, v in self.grid)

    @property
    def size(self) -> int:
        """Total number of samples."""
        return self.grid_points * self.samples

    @property
    def chunk_shape(self) -> tuple[int, ...]:
        """A chunk's extent along each of :attr:`dims` (:func:`block_shape` of at most
        :attr:`chunk` samples): a chunk is a block of consecutive samples, and a
        rectangle of the store.

        Examples
        --------
        >>> s = load_sweep('[sweep]\\nscene = "heavy_top"\\nchunk = 4\\n[grid]\\n'
        ...                '"body.mass" = [1.0, 2.0, 3.0]\\n'
        ...                '"effects[0].pivot_to_com[2]" = [0.03, 0.04]')
        >>> s.shape, s.chunk_shape, s.chunks
        ((3, 2), (2, 2), 2)
        """
        return block_shape(self.shape, self.chunk)

    @property
    def chunk_counts(self) -> tuple[int, ...]:
        """Chunks along each dimension."""
        return tuple(-(-n // c) for n, c in zip(self.shape, self.chunk_shape, strict=True))

    @property
    def chunks(self) -> int:
        return math.prod(self.chunk_counts)

    def chunk_region(self, c: int) -> tuple[int, int, dict[str, slice]]:
        """Chunk ``c``'s samples ``lo`` to ``hi - 1`` and its region of the store."""
        at = np.unravel_index(c, self.chunk_counts)
        start = [int(i) * n for i, n in zip(at, self.chunk_shape, strict=True)]
        stop = [min(a + n, m) for a, n, m in zip(start, self.chunk_shape, self.shape, strict=True)]
        lo = int(np.ravel_multi_index(start, self.shape))
        count = math.prod(b - a for a, b in zip(start, stop, strict=True))
        region = {d: slice(a, b) for d, a, b in zip(self.dims, start, stop, strict=True)}
        return lo, lo + count, region

    # ------------------------------------------------------------------ the values

    def values(self, lo: int, hi: int) -> dict[str, np.ndarray]:
        """Each varied key's values for samples ``lo`` to ``hi - 1``.

        Examples
        --------
        >>> s = load_sweep('[sweep]\\nscene = "heavy_top"\\nsamples = 4\\nseed = 7\\n'
        ...                '[[draw]]\\nkey = "body.mass"\\nuniform = [1.0, 2.0]')
        >>> a = s.values(0, 4)["body.mass"]
        >>> bool(np.array_equal(s.values(1, 3)["body.mass"], a[1:3])), bool(np.all(a > 1))
        (True, True)
        """
        out = self._at_points(np.arange(lo, hi, dtype=np.int64) // self.samples)
        if self.draws:
            u = self._uniform(lo, hi)
            out.update((d.key, d.from_uniform(u[j])) for j, d in enumerate(self.draws))
        return out

    def nominal_values(self) -> dict[str, np.ndarray]:
        """Each varied key's value in each grid point's nominal run: the point's grid
        values and the draws' centres (:attr:`Draw.centre`)."""
        points = self.grid_points
        return self._at_points(np.arange(points)) | {
            d.key: np.full(points, d.centre) for d in self.draws
        }

    def _at_points(self, points: np.ndarray) -> dict[str, np.ndarray]:
        """Each grid key's values at the grid points ``points`` (row-major numbers)."""
        if not self.grid:
            return {}
        index = np.unravel_index(points, [len(v) for _, v in self.grid])
        return {key: v[i] for (key, v), i in zip(self.grid, index, strict=True)}

    def _uniform(self, lo: int, hi: int) -> np.ndarray:
        """The uniform numbers of samples lo..hi-1 from their blocks, one row a draw."""
        nvars = len(self.draws)
        u = np.empty((hi - lo, nvars))
        for block in range(lo // BLOCK, -(-hi // BLOCK)):
            a, b = max(lo, block * BLOCK), min(hi, (block + 1) * BLOCK)
            bits = np.random.PCG64(np.random.SeedSequence(self.seed, spawn_key=(block,)))
            bits.advance((a - block * BLOCK) * nvars)
            np.random.Generator(bits).random(out=u[a - lo : b - lo])
        rows = np.ascontiguousarray(u.T)  # each draw's values contiguous, as the store's
        rows += 2.0**-54
        return rows

    def run_times(self) -> np.ndarray:
        """:attr:`times` on the scene's step grid, as the ensemble computes them."""
        t0, h = self.scene.data["time"]["start"], self.scene.step
        return t0 + np.rint((self.times - t0) / h) * h

    # ------------------------------------------------------------------ what it is

    @property
    def digests(self) -> dict[str, str]:
        """What a store begun by this sweep records, to refuse resuming it with other
        inputs: the resolved scene (``[set]`` applied), the sweep's settings, and the
        versions that make its numbers."""
        settings = dict(samples=self.samples, seed=self.seed, chunk=self.chunk,
                        times=self.times.tolist(), grid=[[k, v.tolist()] for k, v in self.grid],
                        draws=[[d.key, d.distribution, d.a, d.b] for d in self.draws])  # fmt: skip
        return {
            "scene_digest": _sha(self.scene.to_toml()),
            "sweep_digest": _sha(json.dumps(settings, sort_keys=True)),
            "made_with": _versions(),
        }


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()[:16]


@functools.cache
def _versions() -> str:
    """The packages whose versions make a sweep's numbers: ga_rotors, numpy (the
    streams), scipy (the normal quantile), numba (the loops)."""
    from importlib.metadata import PackageNotFoundError, version

    out = []
    for package in ("ga-rotors", "numpy", "scipy", "numba"):
        try:
            out.append(f"{package} {version(package)}")
        except PackageNotFoundError:
            out.append(f"{package} (unknown)")
    return ", ".join(out)


# ---------------------------------------------------------------------- reading


def load_sweep(source) -> Sweep:
    """Read a sweep from a ``.toml`` file or from TOML text.

    Examples
    --------
    >>> load_sweep('[sweep]\\nscene = "heavy_top"\\n[grid]\\n"body.mass" = [1, 2]').size
    2
    >>> load_sweep('[sweep]\\nscene = "heavy_top"\\nsampels = 2')
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: <string>: sweep.sampels: unknown key (did you mean 'samples'?); ...
    """
    from ..scene.loading import MAX_FILE_BYTES
    from ..scene.toml_io import read_file

    if isinstance(source, Path) or (isinstance(source, str) and source.endswith(".toml")):
        path = Path(source)
        return read_sweep(read_file(path, MAX_FILE_BYTES, what="sweep"), str(path), path.parent)
    return read_sweep(str(source))


def read_sweep(text: str, file: str = "<string>", base=".", scene=None) -> Sweep:
    """The sweep of the TOML ``text``; ``file`` names it in errors, and a scene file it
    names is found relative to ``base``. ``scene``: the resolved scene to take instead of
    the one the text names (with its ``[set]`` already applied: how a Dask worker
    rebuilds the sweep it was sent).

    Examples
    --------
    >>> read_sweep('[sweep]\\nscene = "heavy_top"\\n[grid]\\n"body.mass" = [1, 2]').shape
    (2,)
    """
    from ..scene.toml_io import parse_toml

    r = Reader(file)
    data = parse_toml(text, file)
    _printable(r, data)
    top = r.table(data, "", ("sweep", "set", "grid", "draw"), ("sweep",))
    sw = r.table(top["sweep"], "sweep", ("scene", "samples", "seed", "chunk", "times"), ("scene",))
    if scene is None:
        scene = _scene(r, sw, top.get("set", {}), Path(base))
    grid = tuple(
        (key, _grid_values(r, scene, key, values))
        for key, values in r.table(top.get("grid", {}), "grid").items()
    )
    draws = tuple(_draw(r, scene, i, d) for i, d in enumerate(r.array(top.get("draw", []), "draw")))
    keys, first = [k for k, _ in grid] + [d.key for d in draws], {}
    for i, key in enumerate(keys):
        if first.setdefault(coordinate_name(key), i) != i:
            raise r.error("draw" if draws else "grid", f"{key!r} is varied twice (or two keys "
                          "differ only in punctuation)")  # fmt: skip
    if not keys:
        raise r.error("grid", "nothing varies; give [grid] values or [[draw]] tables")
    # the scene checks every key once now (an unknown key, a number where it wants a
    # vector), rather than the first chunk after the store is made
    probe = {k: float(v[0]) for k, v in grid} | {d.key: d.centre for d in draws}
    try:
        scene.replace(probe)
    except InputError as exc:
        shown = ", ".join(f"{k} = {v!r}" for k, v in probe.items())
        refused = f"{exc.key}: {exc.detail}" if exc.key else str(exc)
        raise r.error("", f"the scene refuses the first grid point ({shown}): {refused}") from None
    # checked even when unused: a typo'd seed should not pass silently
    seed = _count(r, sw["seed"], "sweep.seed", low=0, high=MAX_SEED) if "seed" in sw else None
    if draws and seed is None:
        raise r.error("sweep.seed", "missing; random draws need a seed")
    samples = _count(r, sw.get("samples", 1), "sweep.samples")
    if samples > 1 and not draws:
        raise r.error(
            "sweep.samples",
            f"{samples} samples of each grid point without [[draw]] "
            "tables would all be the same run; add a [[draw]] or leave samples out",
        )
    chunk = _count(r, sw.get("chunk", DEFAULT_CHUNK), "sweep.chunk")
    times = _times(r, scene, sw.get("times"))
    return Sweep(scene, grid, draws, samples, seed if draws else None, chunk, times, text, r.file)


def _scene(r: Reader, sw: dict, changes, base: Path):
    from ..scene import load_scene

    name = r.string(sw["scene"], "sweep.scene")
    candidate = base / name
    try:
        scene = load_scene(candidate if candidate.suffix == ".toml" else name)
    except InputError as exc:
        raise r.error("sweep.scene", str(exc)) from None
    changes = r.table(changes, "set")
    try:
        return scene.replace(changes) if changes else scene
    except InputError as exc:
        raise r.error("set", str(exc)) from None


def _printable(r: Reader, data) -> None:
    """Refuse control characters in the keys and strings of a sweep file: none has a use
    for them, and echoed in an error they would reach the user's terminal raw."""
    todo = [data]
    while todo:
        value = todo.pop()
        if isinstance(value, dict):
            todo += [*value, *value.values()]
        elif isinstance(value, list):
            todo += value
        elif isinstance(value, str) and not value.isprintable():
            shown = repr(value)[: 2 * ECHO_LIMIT]
            raise r.error("", f"control characters in a key or string ({shown}); a sweep "
                          "file has no use for them")  # fmt: skip


def _count(r: Reader, value, key: str, low: int = 1, high: float = math.inf) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        shown = repr(value) if not isinstance(value, int) or abs(value) < 10**30 else "a larger one"
        upper = f" and ≤ {high:.3g}" if high < math.inf else ""
        raise r.error(key, f"expected an integer ≥ {low}{upper}, got {shown}")
    return value


def _varying(r: Reader, scene, key: str, where: str) -> None:
    """Refuse a key that cannot vary between samples, or that is not a single number."""
    if not key.startswith(_VARYING):
        raise r.error(
            where,
            f"{key!r} cannot vary between the samples of one ensemble (they share the time "
            "grid and integrator); vary keys under body, initial, effects or forces, or set "
            "it in [set]",
        )
    node = scene.data
    for part in _PARTS.findall(key):
        try:
            node = node[int(part[1:-1]) if part.startswith("[") else part]
        except (KeyError, IndexError, TypeError):
            return  # not in the resolved scene: the scene's own check names it
    if isinstance(node, list | dict):
        size = f"{len(node)} numbers" if isinstance(node, list) else "a table"
        raise r.error(
            where,
            f"{key!r} is {size}; vary one number at a time: its components "
            f"{key}[0], {key}[1], ... each as a key of its own",
        )


def _grid_values(r: Reader, scene, key: str, values) -> np.ndarray:
    where = join("grid", key)
    _varying(r, scene, key, where)
    values = r.numbers(values, where)
    if not values:
        raise r.error(where, "expected at least one value")
    return np.array(values)


def _draw(r: Reader, scene, i: int, d) -> Draw:
    where = join("draw", i)
    d = r.table(d, where, ("key", *DISTRIBUTIONS), ("key",))
    key = r.string(d["key"], join(where, "key"))
    _varying(r, scene, key, join(where, "key"))
    dist = r.one_of(d, where, DISTRIBUTIONS)
    where = join(where, dist)
    a, b = r.vector(d[dist], where, 2, unit=" and ".join(DISTRIBUTIONS[dist]))
    if dist == "normal" and b < 0:
        raise r.error(where, f"expected std ≥ 0, got {b:g}")
    if dist == "uniform" and b < a:
        raise r.error(where, f"expected low ≤ high, got [{a:g}, {b:g}]")
    if not math.isfinite(b - a if dist == "uniform" else a + 40 * b):
        raise r.error(where, "the draws would overflow float64; choose smaller values")
    return Draw(key, dist, a, b)


def _times(r: Reader, scene, value) -> np.ndarray:
    """Increasing output times after the start, each a whole number of steps into the run
    (default, ``value`` None: the end of the run)."""
    start, duration, h = scene.data["time"]["start"], scene.data["time"]["duration"], scene.step
    times = r.numbers([start + duration] if value is None else value, "sweep.times")
    if not times:
        raise r.error("sweep.times", "expected at least one output time (s)")
    for i, (before, t) in enumerate(zip((-math.inf, *times), times, strict=False)):
        key = join("sweep.times", i)
        if not start < t <= start + duration * (1 + 1e-12):
            raise r.error(key, f"{t!r} s is outside the run (from {start!r} s to "
                          f"{start + duration!r} s, the start excluded)")  # fmt: skip
        whole_steps_at(r, t - start, h, key, f"{t!r} s is not a whole number of steps ({h!r} s) "
                      f"after the start ({start!r} s)")  # fmt: skip
        if t <= before:
            raise r.error(key, f"expected increasing times, got {t!r} s after {before!r} s")
    return np.array(times)
