"""What a scene will cost, estimated before it runs, and the budget it must fit.

A scene file may ask for anything: 10⁹ samples (7.5 GiB of arrays), 10¹² steps (days).
Before integrating, :func:`check` estimates the steps (every path integrates every step)
and the memory of the stored samples, and refuses a scene beyond the budget with one
line that names the key and how to raise the budget (``ga-rotors run --max-steps N
--max-memory GIB``, or ``run_scene(scene, budget=Budget(...))``).

The memory estimate counts the arrays a run keeps: per sample the time, ω, each path's
state, and the requested quantities, 8 bytes each, times :data:`WORKING_COPIES` for the
copies made while deriving quantities and writing files. It is an estimate (it leaves
out the interpreter and the figure), meant to refuse the absurd, not to bill the exact.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError

__all__ = ["DEFAULT", "Budget", "Estimate", "check", "estimate"]

#: Float64 copies of the sample arrays alive at the peak (the loop's output, the
#: normalised orientations and quantities, the text of a CSV file).
WORKING_COPIES = 3

#: Columns a path's state occupies per sample.
_PATH_COLUMNS = {"rotor": 4, "quaternion": 4, "euler": 3}
#: Columns of each quantity per sample (per path for ``error``).
_QUANTITY_COLUMNS = {"angles": 3, "omega_space": 3, "L_space": 3, "L": 3}


@dataclass(frozen=True)
class Budget:
    """The most a run may take: integration steps (summed over paths) and memory.

    Examples
    --------
    >>> Budget().max_steps, Budget().max_memory_gib
    (100000000, 2.0)
    >>> Budget(max_steps=0)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: max_steps: expected a positive number, got 0
    """

    max_steps: int = 10**8
    max_memory_gib: float = 2.0

    def __post_init__(self):
        for name in ("max_steps", "max_memory_gib"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
                raise InputError(f"expected a positive number, got {value!r}", key=name)


#: The budget ``ga-rotors run`` and :func:`ga_rotors.scene.run_scene` use by default.
DEFAULT = Budget()


@dataclass(frozen=True)
class Estimate:
    """Steps (all paths) and bytes of samples a scene needs (see :func:`estimate`).

    Examples
    --------
    >>> Estimate(steps=2000, samples=1002, bytes=240480).bytes / 2**20 < 1
    True
    """

    steps: int
    samples: int
    bytes: int


def estimate(scene) -> Estimate:
    """The steps and the memory ``scene`` will take.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> e = estimate(load_scene("heavy_top"))
    >>> e.steps, e.samples, round(e.bytes / 2**20, 1)
    (60000, 6002, 2.5)
    """
    paths = scene.paths
    samples = scene.steps // scene.sample_every + 2
    columns = 1 + 3 + sum(_PATH_COLUMNS.get(p, 4) for p in paths)
    for name in scene.data["output"]["quantities"]:
        columns += len(paths) if name == "error" else _QUANTITY_COLUMNS.get(name, 1)
    return Estimate(
        steps=scene.steps * len(paths),
        samples=samples,
        bytes=samples * columns * 8 * WORKING_COPIES,
    )


def check(scene, budget: Budget = DEFAULT) -> Estimate:
    """Refuse ``scene`` (SceneError naming the key) when it is beyond ``budget``.

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
    """
    from .reader import Reader

    e = estimate(scene)
    gib = e.bytes / 2**30
    over = []
    if e.steps > budget.max_steps:
        over.append(f"{e.steps:.3g} integration steps (budget {budget.max_steps:.3g})")
    if gib > budget.max_memory_gib:
        over.append(
            f"about {gib:.3g} GiB for {e.samples:.3g} samples (budget "
            f"{budget.max_memory_gib:g} GiB; time.output_step sets how many are kept)"
        )
    if over:
        duration = scene.data["time"]["duration"]
        raise Reader(scene.file).error(
            "time.duration",
            f"{duration:g} s needs {' and '.join(over)}; to run it anyway raise the budget: "
            "ga-rotors run --max-steps N --max-memory GIB",
        )
    return e
