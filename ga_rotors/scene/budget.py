"""What a scene will cost, estimated before it runs, and the budget it must fit.

A scene file may ask for anything: 10⁹ samples (7.5 GiB of arrays, 40 GB of CSV), 10¹²
steps (days). Before integrating, :func:`check` estimates the steps (every path
integrates every step), the memory and the disk the run takes, and refuses a scene beyond
the budget with one line that names the key and how to raise the budget (``ga-rotors run
--max-steps N --max-disk GIB``, or ``Budget(...)`` in Python).

Two kinds of run, two memory estimates:

* a run whose samples stay in memory (:func:`ga_rotors.scene.run_scene`, the user asked
  for arrays): per sample the time, ω, each path's state and the requested quantities,
  8 bytes each, times :data:`WORKING_COPIES` for the copies made while deriving
  quantities and writing files;
* a streamed run (:func:`ga_rotors.scene.stream_scene`, ``ga-rotors run``): one piece of
  samples at a time and the figure's thinned copy, whatever the number of steps; what
  grows with the run is the disk its files take, :data:`BYTES_PER_VALUE` per value and
  format (CSV text, binary formats), checked against ``max_disk_gib``.

They are estimates (they leave out the interpreter), meant to refuse the absurd, not to
bill the exact.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from ..errors import InputError

__all__ = ["BYTES_PER_VALUE", "CHUNK_STEPS", "DEFAULT", "Budget", "Estimate", "check", "estimate"]

#: Float64 copies of the sample arrays alive at the peak (the loop's output, the
#: normalised orientations and quantities, the text of a CSV file).
WORKING_COPIES = 3

#: Bytes a value takes on disk, per format of ``output.data`` (CSV: up to 24 characters of
#: ``%.17g`` and a separator; the binary formats: float64, uncompressed at most).
BYTES_PER_VALUE = {"csv": 25, "npz": 8, "netcdf": 8, "zarr": 8}

#: Steps per piece of a streamed run (each path): a few MB of samples at most.
CHUNK_STEPS = 2**17

#: Pieces a streamed run's summary may fall behind its integration and files (each a
#: few MB of samples): the summary, a long run's largest cost, then still measures the
#: last ones while the figure is drawn (:mod:`ga_rotors.scene.output`).
SUMMARY_LAG = 8

#: Pieces a streamed run's summary is held back when a figure is drawn: the figure is
#: drawn on one core at the end, and these pieces are measured on the other meanwhile
#: rather than during the run, where both cores are busy (:mod:`ga_rotors.scene.output`).
#: Measured on the 10⁷-step heavy top (two cores, idle): 12 pieces finish with the figure
#: (the summary also lags up to SUMMARY_LAG more on its own); 24 outlast it by 0.1 s.
SUMMARY_DELAY = 12

#: Samples per piece of a streamed run kept at once (the piece, its quantities, the
#: writers' copies, the pieces the summary has yet to measure) on top of the thinned
#: copy's rows (COLUMNS x (2 + 2 x columns)).
_STREAM_COPIES = 4 + SUMMARY_LAG + SUMMARY_DELAY

#: Compilation estimates from this many seconds on are shown (``ga-rotors run``).
COMPILE_NOTICE_SECONDS = 10.0

#: Columns a path's state occupies per sample.
_PATH_COLUMNS = {"rotor": 4, "quaternion": 4, "euler": 3, "motor": 8}
#: Numbers a motion scene's summary keeps per sample until its report: t, ω, position,
#: velocity and the primary path's state (8 for a motor).
MOTION_SUMMARY_COLUMNS = 1 + 3 + 3 + 3 + 8
#: Columns of each quantity per sample (per path for ``error``).
_QUANTITY_COLUMNS = {"angles": 3, "omega_space": 3, "L_space": 3, "L": 3}


@dataclass(frozen=True)
class Budget:
    """The most a run may take: integration steps (summed over paths), memory and disk.

    Examples
    --------
    >>> Budget().max_steps, Budget().max_memory_gib, Budget().max_disk_gib
    (100000000, 2.0, 20.0)
    >>> Budget(max_steps=0)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: max_steps: expected a positive number, got 0
    """

    max_steps: int = 10**8
    max_memory_gib: float = 2.0
    max_disk_gib: float = 20.0

    def __post_init__(self):
        for field in fields(self):  # a subclass's limits too (a sweep's max_files)
            value = getattr(self, field.name)
            if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
                raise InputError(f"expected a positive number, got {value!r}", key=field.name)


#: The budget ``ga-rotors run`` and :func:`ga_rotors.scene.run_scene` use by default.
DEFAULT = Budget()


@dataclass(frozen=True)
class Estimate:
    """Steps (all paths), bytes of memory and bytes of files a scene needs
    (see :func:`estimate`).

    Examples
    --------
    >>> Estimate(steps=2000, samples=1002, bytes=240480, disk=200400).bytes / 2**20 < 1
    True
    """

    steps: int
    samples: int
    bytes: int
    disk: int = 0
    #: CPU seconds numba takes to compile the run's loops when none is cached yet
    #: (:func:`ga_rotors.scene.schema.compile_seconds`, per path).
    compile_seconds: float = 0.0

    def __str__(self) -> str:
        compiling = (
            f", about {self.compile_seconds:.0f} s to compile its loops on a first run"
            if self.compile_seconds >= COMPILE_NOTICE_SECONDS
            else ""
        )
        return (
            f"{self.steps:.3g} steps, {self.samples:.3g} samples: about "
            f"{_size(self.bytes)} of memory, {_size(self.disk)} of files{compiling}"
        )


def _size(n: int) -> str:
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n / 2**10:.3g} KiB"


def estimate(scene, streamed: bool = False) -> Estimate:
    """The steps, the memory and the disk ``scene`` will take, its samples in memory or
    ``streamed`` to its files.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> e = estimate(load_scene("heavy_top"))
    >>> e.steps, e.samples, round(e.bytes / 2**20, 1), round(e.disk / 2**20, 1)
    (60000, 6002, 2.5, 2.6)
    >>> long = load_scene("heavy_top").replace({"time.duration": 500})
    >>> print(estimate(long))
    1e+07 steps, 1e+06 samples: about 412 MiB of memory, 429 MiB of files
    >>> print(estimate(long, streamed=True))
    1e+07 steps, 1e+06 samples: about 97.1 MiB of memory, 429 MiB of files
    """
    from .thinning import COLUMNS

    paths = scene.paths
    samples = scene.steps // scene.sample_every + 2
    columns = 1 + 3 + sum(_PATH_COLUMNS.get(p, 4) for p in paths)
    if scene.moves:  # position and velocity, and the quaternion path's centre of mass
        columns += 6 + 3 * ("quaternion" in paths)
    for name in scene.data["output"]["quantities"]:
        columns += len(paths) if name == "error" else _QUANTITY_COLUMNS.get(name, 1)
    per_value = sum(BYTES_PER_VALUE.get(f, 8) for f in scene.data["output"]["data"])
    if streamed:
        piece = min(samples, CHUNK_STEPS // scene.sample_every + 2)
        thinned = min(samples, COLUMNS * (2 + 2 * columns)) if scene.data["output"]["plots"] else 0
        memory = (piece * _STREAM_COPIES + thinned) * columns * 8
        if scene.moves and scene.data["output"]["summary"]:
            # the balances integrate over the whole run: the summary keeps the primary
            # path's samples (ga_rotors.scene.motion_summary)
            memory += samples * MOTION_SUMMARY_COLUMNS * 8
    else:
        memory = samples * columns * 8 * WORKING_COPIES
    from .schema import compile_seconds

    effects = len(scene.data["effects"]) + len(scene.data.get("forces", []))  # terms
    return Estimate(
        steps=scene.steps * len(paths),
        samples=samples,
        bytes=memory,
        disk=samples * columns * per_value,
        compile_seconds=len(paths) * compile_seconds(effects, scene.method.evaluations),
    )


def check(scene, budget: Budget = DEFAULT, streamed: bool = False) -> Estimate:
    """Refuse ``scene`` (SceneError naming the key) when it is beyond ``budget``, its
    samples kept in memory or ``streamed`` to its files.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> s = load_scene("heavy_top").replace({"time.duration": 3e5})
    >>> check(s)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: ...heavy_top.toml: time.duration: 300000 s needs 6e+09 ...
    >>> check(s, Budget(max_steps=10**10, max_memory_gib=500)).steps
    6000000000

    Streamed, the memory is bounded, and the files are what grows:

    >>> check(s, Budget(max_steps=10**10), streamed=True)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: ...: time.duration: 300000 s needs about 251 GiB of files ...
    """
    from .reader import Reader

    e = estimate(scene, streamed)
    gib = e.bytes / 2**30
    over, raise_with = [], []
    if e.steps > budget.max_steps:
        over.append(f"{e.steps:.3g} integration steps (budget {budget.max_steps:.3g})")
        raise_with.append("--max-steps N")
    if gib > budget.max_memory_gib:
        over.append(
            f"about {gib:.3g} GiB of memory for {e.samples:.3g} samples (budget "
            f"{budget.max_memory_gib:g} GiB; time.output_step sets how many are kept)"
        )
        raise_with.append("--max-memory GIB")
    if streamed and e.disk / 2**30 > budget.max_disk_gib:
        over.append(
            f"about {e.disk / 2**30:.3g} GiB of files for {e.samples:.3g} samples (budget "
            f"{budget.max_disk_gib:g} GiB; time.output_step sets how many are written)"
        )
        raise_with.append("--max-disk GIB")
    if over:
        duration = scene.data["time"]["duration"]
        raise Reader(scene.file).error(
            "time.duration",
            f"{duration:g} s needs {' and '.join(over)}; to run it anyway raise the budget: "
            f"ga-rotors run {' '.join(raise_with)}",
        )
    return e
