"""Cross-check the orientation paths of one simulation against each other.

The rotor path (Ṙ = ½ R Ω in Cl(3,0)) and the quaternion path (q̇ = ½ q ⊗ (0, ω)) are the
same differential equation written in two isomorphic algebras, integrated with the same
method and step: they must agree to round-off. The Euler-angle path is a different ODE (in
coordinates singular at sin θ = 0) and agrees only where its step resolves its rates.

For a body moving through space the motor path (the body frame's motor and its velocity
line, rotation and translation coupled when the origin is not the centre of mass) and the
quaternion path (the centre of mass moving by Newton's law, the body turning about it) are
different equations of the same motion: they agree to the integrator's error, in angle
and in the distance between the body origins each path puts in space.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from . import paths as _paths
from ._quaternion_loops import largest_distance_loop
from ._validate import UNIT_TOLERANCE
from .errors import InputError
from .trajectory import Trajectory

__all__ = ["PathComparison", "cross_check"]


@dataclass(frozen=True)
class PathComparison:
    """Largest geodesic angle between two paths over their common samples.

    :func:`cross_check` returns one per pair of paths; ``str`` gives the line a run prints.

    Examples
    --------
    >>> print(PathComparison(("rotor", "quaternion"), 3.1e-15, 2.5, 1001))
    rotor vs quaternion: max 3.1e-15 rad at t = 2.5 s (1001 samples)
    """

    paths: tuple[str, str]
    max_angle: float
    at_time: float
    samples: int
    #: for a moving body, the largest distance (m) between the body origins of the two
    #: paths, and when; None for a rotation about a fixed point
    max_distance: float | None = None
    distance_at: float | None = None

    def __str__(self) -> str:
        a, b = self.paths
        text = f"{a} vs {b}: max {self.max_angle:.3g} rad at t = {self.at_time:g} s"
        if self.max_distance is not None:
            text += f", max {self.max_distance:.3g} m apart at t = {self.distance_at:g} s"
        return text + f" ({self.samples} samples)"


def cross_check(trajectory: Trajectory, normalised=None) -> list[PathComparison]:
    """Compare every pair of orientation paths present in ``trajectory``.

    Parameters
    ----------
    trajectory : Trajectory
    normalised : dict, optional
        path -> its orientations already normalised (``quaternion.normalize`` of
        ``trajectory.quaternions(path)``), for a caller that has them (a run's summary
        uses them for its exact errors too); the others are computed here.

    Returns
    -------
    list of PathComparison
        One per pair, in the order of :data:`ga_rotors.paths.PATHS` (rotor, quaternion,
        euler).

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.3, 2.0, 0.1], duration=10.0,
    ...               step=1e-2, paths=("rotor", "quaternion"))
    >>> [c] = cross_check(tr)
    >>> c.paths, c.max_angle < 1e-13
    (('rotor', 'quaternion'), True)
    """
    from .quaternion import distance, normalize

    present = [p for p in _paths.PATHS if p in trajectory.paths]
    moving = "position" in trajectory  # a body moving through space
    if len(present) < 2:
        raise InputError(f"trajectory: cross-checking needs two paths, it has {present}")
    # Between rotations: each path's own norm drift is not a disagreement.
    given = normalised or {}
    quats = {p: given[p] if p in given else normalize(trajectory.quaternions(p)) for p in present}
    out = []
    for a, b in combinations(present, 2):
        n = min(quats[a].shape[0], quats[b].shape[0])
        qa, qb = (np.ascontiguousarray(quats[p][:n], dtype=np.float64) for p in (a, b))
        # the largest of distance(qa, qb) and its first row, without every angle
        angle, i, ok = largest_distance_loop(qa, qb, UNIT_TOLERANCE)
        if not ok or n == 0:  # what distance says of these rows: raises, or nan (or none)
            d = np.atleast_1d(distance(qa, qb))
            i = int(np.argmax(d))
            angle = d[i]
        far = at = None
        if moving:
            gap = np.linalg.norm(trajectory.positions(a)[:n] - trajectory.positions(b)[:n],
                                 axis=-1)  # fmt: skip
            k = int(np.argmax(gap)) if n else 0
            far, at = (float(gap[k]), float(trajectory.t[k])) if n else (0.0, 0.0)
        out.append(PathComparison((a, b), float(angle), float(trajectory.t[i]), n, far, at))
    return out
