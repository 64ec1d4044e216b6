"""The samples of a sweep over a scene whose body moves through space, one run each.

The batched ensemble loops (:mod:`ga_rotors.ensemble`) integrate rotations about a fixed
point; a sweep over a motion scene (``initial.position``, ``initial.velocity`` or
``[[forces]]``; a thrown racket's spin drawn, say) runs each sample as the scene with the
sample's values, through :func:`ga_rotors.scene.run_scene` on its first path: every sample
is exactly ``ga-rotors run`` of that scene, its loop compiled once for all of them. It
answers what the ensemble answers (orientations and body rates at the sweep's times, in
the scene's body frame) and the body-frame origin's position and velocity in space.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["MotionRun", "run_motion_samples"]


@dataclass(frozen=True)
class MotionRun:
    """Every sample's state at the times ``t`` (k,): ``q`` (k, n, 4), ``w`` (k, n, 3),
    ``position`` and ``velocity`` (k, n, 3), as :class:`ga_rotors.ensemble.EnsembleRun`
    with the motion's position and velocity added.

    Examples
    --------
    >>> run = MotionRun(np.array([1.0]), *(np.zeros((1, 2, k)) for k in (4, 3, 3, 3)))
    >>> run.position.shape
    (1, 2, 3)
    """

    t: np.ndarray
    q: np.ndarray
    w: np.ndarray
    position: np.ndarray
    velocity: np.ndarray


def run_motion_samples(scene, values: dict, times: np.ndarray) -> MotionRun:
    """Run ``scene`` once per sample of ``values`` (key -> (n,) values) and keep each
    run's state at ``times`` (on the scene's step grid: :meth:`Sweep.run_times`).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> scene = load_scene("thrown_racket").replace({"time.duration": 0.01})
    >>> run = run_motion_samples(scene, {"initial.velocity[0]": np.array([1.0, 3.0])},
    ...                          np.array([0.005, 0.01]))
    >>> run.q.shape, run.position.shape
    ((2, 2, 4), (2, 2, 3))
    >>> (run.position[-1, :, 0] / 0.01).round(6).tolist()   # the handle moved at vx
    [1.0, 3.0]
    """
    from ..scene import run_scene

    t0, h = scene.data["time"]["start"], scene.step
    marks = np.rint((np.asarray(times, dtype=np.float64) - t0) / h).astype(np.int64)
    every = math.gcd(*(int(m) for m in marks if m > 0)) or 1  # samples only where needed
    rows = marks // every
    n = next(iter(values.values())).shape[0] if values else 1
    first = scene.paths[0]
    shape = (marks.size, n)
    q, w = np.full((*shape, 4), np.nan), np.full((*shape, 3), np.nan)
    position, velocity = np.full((*shape, 3), np.nan), np.full((*shape, 3), np.nan)
    for i in range(n):
        change = {key: float(v[i]) for key, v in values.items()}
        change.update({"time.output_step": every * h, "integrator.paths": [first],
                       "output.quantities": [], "output.plots": []})  # fmt: skip
        tr = run_scene(scene.replace(change))
        got = rows[rows < tr.w.shape[0]]  # a run that stopped keeps NaN after it
        k = got.size
        q[:k, i], w[:k, i] = tr.quaternions()[got], tr.w[got]
        position[:k, i], velocity[:k, i] = tr.positions()[got], tr.velocities()[got]
    return MotionRun(t0 + marks * h, q, w, position, velocity)
