"""Per-call overhead of a fixed-step run through the public API.

The overhead of a call is its time minus the time of its compiled loop alone (called
directly with its arrays allocated beforehand,
:func:`ga_rotors.integrators._runner.bare_loop`): what the call costs around the loop
— the checks, the step limit (judged in the same compiled call as the loop), allocating
the samples, building the result. Three calls
are timed interleaved (loop, ``Integrator.run``, ``simulate``), repeated, and reported as
medians with min–max; ``benchmarks/bench_overhead.py`` prints the same table.
"""

from __future__ import annotations

import statistics
import time

import numpy as np

__all__ = ["measure_overhead", "overhead_table"]

#: (method, steps) combinations measured: the cheapest call (a few steps: overhead is
#: most of it) and a longer one.
COMBINATIONS = (("rk4", 10), ("rk4", 1000), ("split4", 10), ("dp8", 10))


def measure_overhead(method: str = "rk4", nsteps: int = 10, rounds: int = 2000) -> dict:
    """Median and min–max (µs) of the bare loop, ``Integrator.run`` and ``simulate`` on the
    asymmetric top (1, 2, 3), quaternion path, one sample at the end, interleaved.

    Returns ``{"loop": (median, min, max), "run": ..., "simulate": ...,
    "run overhead": median run − median loop, "simulate overhead": ...}``.

    Examples
    --------
    >>> found = measure_overhead("rk4", 10, rounds=20)
    >>> sorted(found)
    ['loop', 'run', 'run overhead', 'simulate', 'simulate overhead']
    >>> found["loop"][1] <= found["loop"][0] <= found["loop"][2]
    True
    """
    from ..integrators import Problem, get
    from ..integrators._runner import bare_loop
    from ..simulation import simulate

    integ = get(method)
    problem = Problem((1.0, 2.0, 3.0))
    q0, w0 = np.array([1.0, 0.0, 0.0, 0.0]), np.array([1.0, 0.5, 0.2])
    h = 1e-3
    calls = {
        "loop": bare_loop(integ, problem, "quaternion", q0, w0, 0.0, h, nsteps, nsteps),
        "run": lambda: integ.run(problem, "quaternion", q0, w0, 0.0, h, nsteps, nsteps),
        "simulate": lambda: simulate(
            (1.0, 2.0, 3.0),
            q0,
            w0,
            duration=h * nsteps,
            step=h,
            paths="quaternion",
            integrator=method,
            sample_every=nsteps,
        ),
    }
    times: dict[str, list[float]] = {name: [] for name in calls}
    for call in calls.values():
        call()
    for _ in range(rounds):
        for name, call in calls.items():
            start = time.perf_counter()
            call()
            times[name].append(time.perf_counter() - start)
    out = {
        name: tuple(1e6 * x for x in (statistics.median(t), min(t), max(t)))
        for name, t in times.items()
    }
    out["run overhead"] = out["run"][0] - out["loop"][0]
    out["simulate overhead"] = out["simulate"][0] - out["loop"][0]
    return out


def overhead_table(quick: bool = False) -> str:
    """Markdown: per (method, steps), the loop's time and the overhead of ``Integrator.run``
    and ``simulate`` over it (µs; medians, min–max of the call).

    Examples
    --------
    >>> print(overhead_table(quick=True).splitlines()[0])
    | method, steps | compiled loop µs | Integrator.run µs | overhead | simulate µs | overhead |
    """
    rows = [
        "| method, steps | compiled loop µs | Integrator.run µs | overhead | simulate µs "
        "| overhead |",
        "|---|---|---|---|---|---|",
    ]

    def cell(t):
        return f"{t[0]:.3g} ({t[1]:.3g}–{t[2]:.3g})"

    for method, nsteps in COMBINATIONS[:1] if quick else COMBINATIONS:
        m = measure_overhead(method, nsteps, rounds=50 if quick else 3000)
        rows.append(
            f"| {method}, {nsteps} | {cell(m['loop'])} | {cell(m['run'])} | "
            f"{m['run overhead']:.3g} | {cell(m['simulate'])} | {m['simulate overhead']:.3g} |"
        )
    return "\n".join(rows)
