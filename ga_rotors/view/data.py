"""What the viewer shows, as plain arrays: the one place a Trajectory is read.

:class:`ViewData` holds the sample times, one unit-quaternion array per orientation path,
the body angular velocity and the principal moments; everything drawn on the page (the
body, ω and L in space, the rotor's plane, the symmetry axis' trace, the Euler angles) is
derived from these. :func:`from_trajectory` is the adapter from a
:class:`~ga_rotors.trajectory.Trajectory`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from .. import quaternion as Q
from ..errors import InputError

__all__ = ["NEAR_LOCK", "ViewData", "from_trajectory", "symmetry_axis"]

#: |sin θ| below which the page flags the z–y′–z″ angles as near gimbal lock: their
#: rates ψ̇, φ̇ grow as 1/sin θ there (exact lock is ``ga_rotors.euler``'s own flag).
NEAR_LOCK = 1e-2

_IDENTITY = (1.0, 0.0, 0.0, 0.0)


def symmetry_axis(moments) -> int:
    """Index (0, 1, 2) of the principal axis whose moment stands apart from the other two.

    For a symmetric top that is its figure axis. A tie goes to the largest moment (the
    normal of a flat body), then to the last axis (z for a sphere).

    Examples
    --------
    >>> symmetry_axis((1.0, 1.0, 2.0)), symmetry_axis((3.0, 1.0, 1.0))
    (2, 0)
    >>> symmetry_axis((3.0, 2.0, 1.0)), symmetry_axis((1.0, 1.0, 1.0))
    (0, 2)
    """
    m = np.asarray(moments, dtype=np.float64)
    gap = [min(abs(m[k] - m[j]) for j in range(3) if j != k) for k in range(3)]
    return max(range(3), key=lambda k: (gap[k], m[k], k))


@dataclass
class ViewData:
    """Samples of one run, ready to draw.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Sample times (s).
    paths : dict of str -> ndarray, shape (m, 4)
        Unit quaternions (w, x, y, z), principal frame to space, per orientation path
        (``m <= n``: a path that stopped early has fewer rows).
    w : ndarray, shape (n, 3)
        Body angular velocity (rad/s) in the principal frame.
    moments : tuple of float, optional
        Principal moments (kg·m²); None for a prescribed ω(t) (no body, no L).
    title : str
        Shown as the page's heading.
    description : str
        Shown under the heading (a scene's description: what the run is about).

    Examples
    --------
    >>> d = ViewData(np.array([0.0, 1.0]), {"quaternion": np.array([[1.0, 0, 0, 0]] * 2)},
    ...              np.zeros((2, 3)), (1.0, 1.0, 2.0))
    >>> d.axis, d.euler("quaternion")[1].tolist()
    (2, [True, True])
    """

    t: np.ndarray
    paths: dict
    w: np.ndarray
    moments: tuple | None = None
    title: str = "ga_rotors"
    description: str = ""
    notes: list = field(default_factory=list)

    def __post_init__(self):
        self.t = np.asarray(self.t, dtype=np.float64)
        n = self.t.shape[0]
        if self.t.ndim != 1 or n < 1:
            raise InputError(f"t: expected a non-empty 1-D array, got shape {self.t.shape}")
        if not self.paths:
            raise InputError("paths: nothing to show (no orientation path)")
        self.paths = {k: _unit(v, k, n) for k, v in self.paths.items()}
        self.w = np.asarray(self.w, dtype=np.float64)
        if self.w.ndim != 2 or self.w.shape[1] != 3 or self.w.shape[0] > n:
            raise InputError(f"w: expected shape (<= {n}, 3), got {self.w.shape}")
        if not (np.isfinite(self.w).all() and np.isfinite(self.t).all()):
            # A NaN would also be invalid JSON on the page, which would then stay blank.
            raise InputError("w: contains non-finite values" if np.isfinite(self.t).all()
                             else "t: contains non-finite values")  # fmt: skip
        if self.moments is not None:
            self.moments = tuple(float(x) for x in self.moments)

    @property
    def axis(self) -> int:
        """The principal axis whose trace on the unit sphere is drawn."""
        return 2 if self.moments is None else symmetry_axis(self.moments)

    def euler(self, path: str) -> tuple[np.ndarray, np.ndarray]:
        """z–y′–z″ angles (m, 3) in degrees and the gimbal-lock flags of ``path``."""
        from .. import euler
        from ..errors import GimbalLockWarning

        with warnings.catch_warnings():  # locked samples are flagged on the page
            warnings.simplefilter("ignore", GimbalLockWarning)
            angles, locked = euler.from_quaternion(self.paths[path], "ZYZ", return_gimbal=True)
        return np.degrees(angles), np.asarray(locked)


def _unit(q, name: str, n: int) -> np.ndarray:
    q = np.asarray(q, dtype=np.float64)
    if q.ndim != 2 or q.shape[1] != 4 or not 1 <= q.shape[0] <= n:
        raise InputError(f"paths[{name!r}]: expected shape (<= {n}, 4), got {q.shape}")
    if not np.isfinite(q).all():
        raise InputError(f"paths[{name!r}]: contains non-finite values")
    return Q.normalize(q)


def from_trajectory(
    trajectory, moments=None, title: str = "ga_rotors", principal=None, description: str = ""
):
    """The viewer's data for a :class:`~ga_rotors.trajectory.Trajectory`.

    Parameters
    ----------
    trajectory : Trajectory
        Any run with ``t``, ``w`` and at least one orientation path.
    moments : array_like, optional
        Principal moments; default ``trajectory.meta["moments"]``.
    title : str
        The page's heading.
    principal : array_like, shape (4,), optional
        P taking principal axes to the trajectory's body axes, when they differ (a body
        given by a full tensor to :func:`ga_rotors.simulation.simulate`): the page draws
        the principal frame, q ⊗ P and P* ω P.
    description : str
        Shown under the heading.

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.1, 0.0, 1.0], duration=1.0,
    ...               step=0.01, paths=("rotor", "quaternion"))
    >>> d = from_trajectory(tr, title="disk")
    >>> sorted(d.paths), d.moments, d.w.shape
    (['quaternion', 'rotor'], (1.0, 1.0, 2.0), (101, 3))
    """
    if not trajectory.paths:
        raise InputError(f"trajectory: no orientation path (it has {', '.join(trajectory.names)})")
    paths = {p: trajectory.quaternions(p) for p in trajectory.paths}  # primary first
    w = np.asarray(trajectory.w, dtype=np.float64)
    if moments is None:
        moments = trajectory.meta.get("moments")
    if principal is not None and tuple(principal) != _IDENTITY:
        p = Q.normalize(np.asarray(principal, dtype=np.float64))
        paths = {k: Q.multiply(v, p) for k, v in paths.items()}
        w = Q.rotate(Q.conjugate(p), w)
    return ViewData(trajectory.t, paths, w, moments, title, description)
