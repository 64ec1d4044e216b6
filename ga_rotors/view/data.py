"""What the viewer shows, as checked plain arrays: the one place a Trajectory is read.

:class:`ViewData` holds the sample times, one unit-quaternion array per orientation path,
the body angular velocity, the inertia and the body's :class:`~ga_rotors.view.geometry.Solid`,
all in one body frame (the trajectory's); everything drawn on the page (the body, ω and
L = Iω in space, the rotor's plane, the symmetry axis' trace, the Euler angles) is derived
from these. Every input is checked here, so the page's data is always valid JSON: real,
finite numbers, strictly increasing times, and text without control characters.
:func:`from_trajectory` is the adapter from a :class:`~ga_rotors.trajectory.Trajectory`.

Rigid motion: ``positions`` (per path, the body frame's origin in space at each sample)
moves the body, and ``lines`` draws lines in space, each given per sample; for a body
moving through space :func:`from_trajectory` gives both, the line being the velocity
line's axis (:func:`screw_axes`, the instantaneous screw axis). Both are optional and the
page draws what is there.
"""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass, field

import numpy as np

from .. import quaternion as Q
from .._validate import as_float_array
from ..errors import InputError
from .geometry import Solid, from_inertia

__all__ = [
    "NEAR_LOCK",
    "VELOCITY_LINE",
    "Line",
    "ViewData",
    "from_trajectory",
    "screw_axes",
    "symmetry_axis",
    "visible_text",
]

#: The velocity line's legend text and colour (a brown apart from the axes', ω's and L's).
VELOCITY_LINE = ("velocity line: the instantaneous screw axis, M B M̃", "#8c510a")

#: |sin θ| below which the page flags the z–y′–z″ angles as near gimbal lock: their
#: rates ψ̇, φ̇ grow as 1/sin θ there (exact lock is ``ga_rotors.euler``'s own flag).
NEAR_LOCK = 1e-2

#: Longest title or path name the page shows (longer ones are cut, saying so).
TEXT_LIMIT = 200

_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\u2028\u2029\u200e\u200f\u202a-\u202e"
                      r"\u2066-\u2069]")  # fmt: skip


def visible_text(text, key: str, newlines: bool = False, limit: int | None = TEXT_LIMIT) -> str:
    """``text`` with every control character shown as its escape (``\\x1b``), never acted on.

    Scene names and descriptions come from files anyone may write: a terminal escape or a
    bidirectional override in a title must show as what it is. Tabs (and, where
    ``newlines``, line breaks) stay; text longer than ``limit`` is cut, saying so.

    Examples
    --------
    >>> visible_text("top\\x1b[2J", "title")
    'top\\\\x1b[2J'
    >>> visible_text("a\\nb", "title"), visible_text("a\\nb", "description", newlines=True)
    ('a\\\\nb', 'a\\nb')
    >>> visible_text(3, "title")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: title: expected text, got int
    """
    if not isinstance(text, str):
        raise InputError(f"expected text, got {type(text).__name__}", key=key)
    pattern = _CONTROL if newlines else re.compile(_CONTROL.pattern[:-1] + r"\n]")
    shown = pattern.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), text)
    if limit is not None and len(shown) > limit:
        shown = f"{shown[:limit]}… ({len(shown)} characters)"
    return shown


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


@dataclass(frozen=True)
class Line:
    """A line drawn in space at every sample: through ``point`` along ``direction``.

    Parameters
    ----------
    key : str
        The element's name on the page (its legend entry and element list).
    label : str
        What the legend says it is.
    point, direction : ndarray, shape (n, 3)
        A point of the line (m) and its direction, space frame, one row per sample.
    colour : str
        ``#rrggbb``.

    Examples
    --------
    A body thrown along x, and its velocity line:

    >>> t = np.linspace(0.0, 1.0, 3)
    >>> where = np.outer(t, [2.0, 0.0, 0.0])
    >>> line = Line("velocity", "velocity line", where, np.tile([1.0, 0, 0], (3, 1)), "#7b3294")
    >>> d = ViewData(t, {"rotor": np.tile([1.0, 0, 0, 0], (3, 1))}, np.zeros((3, 3)),
    ...              positions={"rotor": where}, lines=[line])
    >>> d.lines[0].key, d.positions["rotor"][-1].tolist()
    ('velocity', [2.0, 0.0, 0.0])
    """

    key: str
    label: str
    point: np.ndarray
    direction: np.ndarray
    colour: str = "#555555"


@dataclass
class ViewData:
    """Samples of one run, ready to draw.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Sample times (s): real, finite, strictly increasing.
    paths : dict of str -> ndarray, shape (m, 4)
        Unit quaternions (w, x, y, z), body frame to space, per orientation path
        (``m <= n``: a path that stopped early has fewer rows).
    w : ndarray, shape (n, 3)
        Body angular velocity (rad/s) in the body frame.
    inertia : array_like, shape (3,) or (3, 3), optional
        Principal moments (when the body frame is principal) or the inertia tensor in the
        body frame (kg·m², about the point the body turns about); None for a prescribed ω(t)
        (no L is drawn).
    title : str
        Shown as the page's heading.
    description : str
        Shown under the heading (a scene's description: what the run is about).
    solid : Solid, optional
        The body's shape in the body frame; default the uniform ellipsoid of ``inertia``.
    positions : dict of str -> ndarray, shape (m, 3), optional
        Per path, where the body frame's origin is in space at each sample (m); default at
        rest at the origin.
    lines : sequence of Line
        Lines drawn in space at each sample.

    Examples
    --------
    >>> d = ViewData(np.array([0.0, 1.0]), {"quaternion": np.array([[1.0, 0, 0, 0]] * 2)},
    ...              np.zeros((2, 3)), (1.0, 1.0, 2.0))
    >>> d.symmetry_direction.tolist(), d.euler("quaternion")[1].tolist()
    ([0.0, 0.0, 1.0], [True, True])
    >>> ViewData(np.array([0.0, 2.0, 1.0]), d.paths, np.zeros((3, 3)))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: t: expected strictly increasing times, got t[2] = 1 after t[1] = 2
    """

    t: np.ndarray
    paths: dict
    w: np.ndarray
    inertia: np.ndarray | None = None
    title: str = "ga_rotors"
    description: str = ""
    solid: Solid | None = None
    positions: dict = field(default_factory=dict)
    lines: tuple = ()

    def __post_init__(self):
        self.t = _times(self.t)
        n = self.t.shape[0]
        if not isinstance(self.paths, dict) or not self.paths:
            raise InputError("paths: nothing to show (no orientation path)")
        self.paths = {visible_text(k, "paths"): _unit(v, k, n) for k, v in self.paths.items()}
        self.w = _rows(self.w, "w", n, exact=False)
        self.title = visible_text(self.title, "title")
        self.description = visible_text(self.description, "description", newlines=True,
                                        limit=20 * TEXT_LIMIT).strip()  # fmt: skip
        self.inertia = None if self.inertia is None else _tensor(self.inertia)
        if self.solid is None and self.inertia is not None:
            self.solid = from_inertia(self.inertia)
        if self.solid is not None and not isinstance(self.solid, Solid):
            raise InputError(f"expected a Solid, got {type(self.solid).__name__}", key="solid")
        unknown = set(self.positions) - set(self.paths)
        if unknown:
            raise InputError(f"positions: no path named {sorted(unknown)[0]!r:.40}")
        self.positions = {k: _rows(v, f"positions[{k!r}]", self.paths[k].shape[0])
                          for k, v in self.positions.items()}  # fmt: skip
        self.lines = tuple(_line(x, n) for x in self.lines)
        self.L = None if self.inertia is None else _momentum(self.inertia, self.w, self.t)

    @property
    def moments(self) -> tuple | None:
        """The principal moments (kg·m²), increasing; None without inertia."""
        if self.inertia is None:
            return None
        from ..body import RigidBody

        return RigidBody.from_tensor(self.inertia).moments

    @property
    def symmetry_direction(self) -> np.ndarray:
        """Unit vector, body frame: the principal axis whose moment stands apart (its trace on
        the unit sphere is drawn); z without inertia."""
        if self.inertia is None:
            return np.array([0.0, 0.0, 1.0])
        from ..body import RigidBody

        body = RigidBody.from_tensor(self.inertia)
        axis = Q.rotate(np.asarray(body.principal_rotation), np.eye(3)[symmetry_axis(body.moments)])
        axis[np.abs(axis) < 1e-15] = 0.0
        return axis if axis[np.argmax(np.abs(axis))] > 0 else -axis

    def euler(self, path: str) -> tuple[np.ndarray, np.ndarray]:
        """z–y′–z″ angles (m, 3) in degrees and the gimbal-lock flags of ``path``."""
        from .. import euler
        from ..errors import GimbalLockWarning

        with warnings.catch_warnings():  # locked samples are flagged on the page
            warnings.simplefilter("ignore", GimbalLockWarning)
            angles, locked = euler.from_quaternion(self.paths[path], "ZYZ", return_gimbal=True)
        return np.degrees(angles), np.asarray(locked)


def _times(t) -> np.ndarray:
    t = as_float_array(t, "t")
    if t.ndim != 1 or t.shape[0] < 1:
        raise InputError(f"t: expected a non-empty 1-D array, got shape {t.shape}")
    back = np.flatnonzero(np.diff(t) <= 0)
    if back.size:
        k = int(back[0]) + 1
        raise InputError(f"t: expected strictly increasing times, got t[{k}] = {t[k]:.6g} "
                         f"after t[{k - 1}] = {t[k - 1]:.6g}")  # fmt: skip
    return t


def _rows(a, key: str, n: int, exact: bool = True) -> np.ndarray:
    a = as_float_array(a, key)
    if a.ndim != 2 or a.shape[1] != 3 or not (a.shape[0] == n if exact else 1 <= a.shape[0] <= n):
        want = f"({n}, 3)" if exact else f"(<= {n}, 3)"
        raise InputError(f"{key}: expected shape {want}, got {a.shape}")
    return a


def _unit(q, name: str, n: int) -> np.ndarray:
    key = f"paths[{name!r:.40}]"
    q = as_float_array(q, key)
    if q.ndim != 2 or q.shape[1] != 4 or not 1 <= q.shape[0] <= n:
        raise InputError(f"{key}: expected shape (<= {n}, 4), got {q.shape}")
    return Q.normalize(q)


def _tensor(inertia) -> np.ndarray:
    from ..body import RigidBody

    a = as_float_array(inertia, "inertia")
    if a.shape == (3,):
        RigidBody(tuple(a.tolist()))  # checks: positive, a rigid body's moments
        return np.diag(a)
    if a.shape != (3, 3):
        raise InputError(f"inertia: expected moments (3,) or a tensor (3, 3), got {a.shape}")
    RigidBody.from_tensor(a)
    return 0.5 * (a + a.T)


def _momentum(inertia: np.ndarray, w: np.ndarray, t: np.ndarray) -> np.ndarray:
    """L = I ω per sample, refused (one line) where float64 cannot hold it."""
    with np.errstate(over="ignore", invalid="ignore"):
        L = w @ inertia.T
        scale = np.abs(L).max(axis=1)
        bad = ~np.isfinite(scale)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise InputError(
            f"L = Iω overflows float64 at t = {t[k]:.6g} s (|ω| components up to "
            f"{np.abs(w[k]).max():.3g} rad/s, moments up to {np.abs(inertia).max():.3g} kg·m²); "
            "nothing to draw: rescale the units", key="L"
        )  # fmt: skip
    return L


def _line(line, n: int) -> Line:
    if not isinstance(line, Line):
        raise InputError(f"lines: expected Line items, got {type(line).__name__}")
    key = visible_text(line.key, "lines")
    if not re.fullmatch(r"#[0-9a-fA-F]{6}", str(line.colour)):
        raise InputError(f"lines[{key!r}]: colour: expected #rrggbb, got {line.colour!r:.20}")
    return Line(key, visible_text(line.label, f"lines[{key!r}].label"),
                _rows(line.point, f"lines[{key!r}].point", n),
                _rows(line.direction, f"lines[{key!r}].direction", n), line.colour)  # fmt: skip


def from_trajectory(trajectory, body=None, *, title: str = "ga_rotors", description: str = "",
                    solid: Solid | None = None) -> ViewData:  # fmt: skip
    """The viewer's data for a :class:`~ga_rotors.trajectory.Trajectory`.

    Parameters
    ----------
    trajectory : Trajectory
        Any run with ``t``, ``w`` and at least one orientation path.
    body : RigidBody or array_like, optional
        The body, in the trajectory's body frame: a :class:`~ga_rotors.body.RigidBody`
        (one made by ``RigidBody.from_tensor`` carries its tensor's frame), principal
        moments (3,) or a tensor (3, 3); default ``trajectory.meta["moments"]``, which
        describes the trajectory's frame only when that frame is principal.
    title : str
        The page's heading.
    description : str
        Shown under the heading.
    solid : Solid, optional
        The body's shape (default: the uniform ellipsoid of its inertia).

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.1, 0.0, 1.0], duration=1.0,
    ...               step=0.01, paths=("rotor", "quaternion"))
    >>> d = from_trajectory(tr, title="disk")
    >>> sorted(d.paths), d.moments, d.w.shape
    (['quaternion', 'rotor'], (1.0, 1.0, 2.0), (101, 3))
    """
    from ..body import RigidBody

    if not trajectory.paths:
        raise InputError(f"trajectory: no orientation path (it has {', '.join(trajectory.names)})")
    paths = {p: trajectory.quaternions(p) for p in trajectory.paths}  # primary first
    if body is None:
        body = trajectory.meta.get("moments")
    if isinstance(body, RigidBody):
        r = Q.to_matrix(np.asarray(body.principal_rotation))
        body = r @ np.diag(body.moments) @ r.T
    positions, lines = {}, ()
    if "position" in trajectory:  # a body moving through space, and its velocity line
        positions = {p: trajectory.positions(p) for p in paths}
        n = trajectory.w.shape[0]
        lever = Q.rotate(
            Q.normalize(paths[trajectory.paths[0]][:n]),
            np.asarray(trajectory.meta.get("centre_of_mass", (0.0, 0.0, 0.0))),
        )
        centre = positions[trajectory.paths[0]][:n] + lever
        point, direction = screw_axes(trajectory.velocity_lines(), centre)
        lines = (Line("velocity", *VELOCITY_LINE[:1], point, direction, VELOCITY_LINE[1]),)
    return ViewData(trajectory.t, paths, trajectory.w, body, title, description, solid,
                    positions, lines)  # fmt: skip


def screw_axes(lines, near) -> tuple[np.ndarray, np.ndarray]:
    """The axes of space velocity lines (n, 6) (:meth:`Trajectory.velocity_lines`): each
    one's point nearest ``near`` (n, 3), m, and its unit direction, the angular velocity's.

    The velocity of the point x is v(x) = v₀ + ω × x (v₀ that of the point at the space
    origin); it is along ω on the line through ω × v₀ / |ω|² (Chasles: the body turns
    about that axis and slides along it). A pure translation (ω = 0) has its axis at
    infinity: the line through ``near`` along the velocity stands in for it.

    Examples
    --------
    Turning at 2 rad/s about z while the point at the origin moves along y at 2 m/s: the
    axis is the vertical through (−1, 0, 0), where ω × x cancels v₀.

    >>> from ga_rotors import motor
    >>> B = motor.velocity_line([[0.0, 0.0, 2.0]], [[0.0, 2.0, 0.0]])
    >>> point, direction = screw_axes(B, [[1.0, 0.0, 5.0]])
    >>> point.round(12) + 0.0, direction + 0.0
    (array([[-1.,  0.,  5.]]), array([[0., 0., 1.]]))
    """
    from .. import motor

    w, v0 = motor.velocities(lines)
    near = np.broadcast_to(np.asarray(near, dtype=np.float64), w.shape)
    rate = np.linalg.norm(w, axis=-1, keepdims=True)
    turning = rate[..., 0] > 0.0
    safe = np.where(rate > 0.0, rate, 1.0)
    u = w / safe
    on_axis = np.cross(w, v0) / (safe * safe)
    point = on_axis + np.einsum("...i,...i->...", near - on_axis, u)[..., None] * u
    # a translation: through the point, along its velocity (or along z at rest)
    v = v0 + np.cross(w, near)
    speed = np.linalg.norm(v, axis=-1, keepdims=True)
    along = np.where(speed > 0.0, v / np.where(speed > 0.0, speed, 1.0), [0.0, 0.0, 1.0])
    return (np.where(turning[..., None], point, near),
            np.where(turning[..., None], u, along))  # fmt: skip
