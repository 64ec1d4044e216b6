"""A scene run's figure: one panel per entry of ``output.plots``, stamped with a data digest.

:func:`draw` builds a matplotlib Figure (panels in :data:`PANELS`: ω, the ZYZ angles,
space-frame momentum, invariant drift, error against the exact solution);
:func:`render` writes it in the scene's ``output.figure_format`` (a 150-dpi palette PNG,
or vector SVG or PDF) with :func:`data_digest` in its metadata, a digest of what the
figure shows that is robust to round-off, so a test can tell whether a committed figure
still matches the code (:func:`figure_png`: the PNG).
"""

from __future__ import annotations

import hashlib
import textwrap
import warnings

import numpy as np

from ..trajectory import Trajectory
from .model import Scene

__all__ = [
    "DIGEST_PREFIX",
    "PANELS",
    "data_digest",
    "draw",
    "energy_balance",
    "energy_balance_drawn",
    "figure_png",
    "render",
]

DIGEST_PREFIX = "ga_rotors scene data "

_WIDTH = 9.0  # the right quarter holds the legends, beside the data, never over it
_ROW = 1.55
_DPI = 150  # 7 pt tick labels are 15 px


def data_digest(scene: Scene, trajectory: Trajectory, digits: int = 6) -> str:
    """A digest of what determines a scene's figure, robust to round-off.

    The resolved scene's text and the samples of ``t``, ``w`` and the primary path's
    orientation, each array rounded to ``digits`` decimals of its own largest magnitude
    (values at round-off level, such as a component that is zero in exact arithmetic,
    round to 0 and cannot change the digest from one machine to the next).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> s = load_scene("spinning_disk").replace({"time.duration": 0.1})
    >>> data_digest(s, run_scene(s)) == data_digest(s, run_scene(s))
    True
    """
    from .. import paths as _paths

    h = hashlib.sha256(scene.to_toml().encode())
    primary = _paths.get(trajectory.meta["primary"]).array
    for name in ("t", "w", primary):
        a = np.asarray(trajectory[name], dtype=np.float64)
        scale = float(np.abs(a).max()) or 1.0
        h.update(name.encode())
        h.update(np.round(a / scale * 10.0**digits).astype(np.int64).tobytes())
    return h.hexdigest()[:16]


# ---------------------------------------------------------------------------- panels


class _Context:
    """What the panels draw from, each piece computed once and only if a panel needs it."""

    def __init__(self, scene: Scene, tr: Trajectory):
        self.scene, self.tr = scene, tr
        self.t = tr.t[: tr.w.shape[0]]
        self._cache: dict = {}

    def get(self, name: str):
        if name not in self._cache:
            self._cache[name] = getattr(self, f"_{name}")()
        return self._cache[name]

    def _q(self):
        from .. import quaternion as Q

        return Q.normalize(self.tr.quaternions())[: self.t.shape[0]]

    def _angles(self):
        from .. import euler
        from ..errors import GimbalLockWarning

        with warnings.catch_warnings():  # a locked sample is still drawn: its rotation is exact
            warnings.simplefilter("ignore", GimbalLockWarning)
            a = euler.from_quaternion(self.get("q"), "ZYZ")
        a[:, 0], a[:, 2] = np.unwrap(a[:, 0]), np.unwrap(a[:, 2])
        return np.degrees(a)

    def _exact(self):
        return self.scene.exact_solution


#: Legends to the right of their panel.
_BESIDE = dict(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
#: A curve closer than this fraction of its panel's height to one drawn before it is
#: hidden under it at the figure's resolution.
_HIDDEN = 0.01


def _line(ax, t, y, *, log: bool = False, **style):
    """Draw ``y(t)`` on ``ax`` (``log``: on a log axis); beyond
    :data:`~ga_rotors.scene.thinning.KEEP_ALL` rows, through its envelope only
    (:func:`~ga_rotors.scene.thinning.envelope`, a slice per pixel column of the saved
    figure, within the x limits :func:`draw` set): the same pixels, a tenth of the
    vertices and of the strokes for the renderer (a thinned copy keeps every array's
    extremes, most of them not this line's)."""
    from .thinning import KEEP_ALL, envelope

    if t.shape[0] > KEEP_ALL:
        pixels = round(ax.get_position().width * _WIDTH * _DPI)
        rows = envelope(t, y, pixels, bounds=ax.get_xlim())
        t, y = t[rows], y[rows]
    return (ax.semilogy if log else ax.plot)(t, y, **style)


def _state_overlaps(ax, unit: str, ys: list) -> None:
    """Draw dashed each curve that lies on an earlier one of a linear panel (``ys``: each
    line's values, in drawing order), and say so in its legend label ("ω2 (dashed): on the
    ω1 line, ≤ 0.05 rad/s apart")."""
    lines = ax.get_lines()
    ys = [np.asarray(y, dtype=np.float64) for y in ys]
    span = max((float(np.ptp(np.concatenate(ys))) if ys else 0.0), 1e-300)
    for k in range(1, len(lines)):
        for j in range(k):
            if ys[j].shape != ys[k].shape:
                continue
            gap = float(np.abs(ys[k] - ys[j]).max())
            if gap <= _HIDDEN * span:
                lines[k].set_linestyle((0, (4, 3)))
                lines[k].set_linewidth(1.2)
                label = f"{lines[k].get_label()} (dashed): on the\n{lines[j].get_label()} line"
                lines[k].set_label(f"{label}, ≤ {gap:.2g} {unit} apart".rstrip())
                break


def _omega(axes, ctx: _Context) -> None:
    (ax,) = axes
    ys = [ctx.tr.w[:, k] for k in range(3)]
    for k, y in enumerate(ys):
        _line(ax, ctx.t, y, lw=0.8, label=f"ω{k + 1}")
    _state_overlaps(ax, "rad/s", ys)
    ax.set_ylabel("body ω (rad/s)", fontsize=8)
    ax.legend(**_BESIDE)


def _angles(axes, ctx: _Context) -> None:
    a = ctx.get("angles")
    _line(axes[0], ctx.t, a[:, 1], lw=0.8, color="C1")
    axes[0].set_ylabel("θ (°)", fontsize=8)
    _line(axes[1], ctx.t, a[:, 0], lw=0.8)
    axes[1].set_ylabel("ψ (°)", fontsize=8)


def _momentum(axes, ctx: _Context) -> None:
    from .. import quaternion as Q

    (ax,) = axes
    L = Q.rotate(ctx.get("q"), ctx.scene.body.momentum(ctx.tr.w))
    for k, name in enumerate("xyz"):
        _line(ax, ctx.t, L[:, k], lw=0.8, label=f"L{name}")
    _state_overlaps(ax, "kg·m²/s", [L[:, k] for k in range(3)])
    ax.set_ylabel("space L (kg·m²/s)", fontsize=8)
    ax.legend(**_BESIDE)


def _position(axes, ctx: _Context) -> None:
    (ax,) = axes
    p = ctx.tr.positions()
    n = min(p.shape[0], ctx.t.shape[0])
    for k, name in enumerate("xyz"):
        _line(ax, ctx.t[:n], p[:n, k], lw=0.8, label=name)
    ax.set_ylabel("origin in space (m)", fontsize=8)
    ax.legend(**_BESIDE)


def _invariants(axes, ctx: _Context) -> None:
    from .summary import invariant_series

    (ax,) = axes
    rows = invariant_series(ctx.scene, ctx.tr, ctx.get("q"))
    if rows:
        floor = 1e-17  # exact zeros have no place on a log axis
        for _, label, deviation, _ in rows:
            if not deviation.any():  # conserved exactly: a line at the floor says so
                label = f"{label}: exactly 0\n(drawn at {floor:.0e})"
            _line(ax, ctx.t, np.maximum(deviation, floor), log=True, lw=0.8, label=label)
        ax.set_ylabel("relative drift", fontsize=8)
        ax.legend(**_BESIDE)
    elif ctx.scene.exact == "damped_symmetric_top":
        exact = ctx.get("exact")
        L = np.linalg.norm(ctx.scene.body.momentum(ctx.tr.w), axis=-1)
        L_exact = exact.model.momentum_norm(ctx.t - ctx.t[0])
        gap = float(np.abs(L - L_exact).max() / np.abs(L_exact).max())
        label = f"|L| exact (dashed): on the\nsimulated line, ≤ {gap:.0e}\nof |L₀| apart"
        _line(ax, ctx.t, L, log=True, lw=0.8, label="|L| simulated")
        _line(ax, ctx.t, L_exact, log=True, ls=(0, (4, 3)), lw=1.2, label=label)
        ax.set_ylabel("|L| (kg·m²/s)", fontsize=8)
        ax.legend(**_BESIDE)
    elif not energy_balance_drawn(ctx.scene):
        # The balance would call the user's torque again, outside the run's opt-in.
        ax.text(0.5, 0.5, "energy balance not drawn: it would run the user torque again",
                ha="center", transform=ax.transAxes, fontsize=8)  # fmt: skip
    else:
        _energy_balance(ax, ctx)


def energy_balance_drawn(scene: Scene) -> bool:
    """Whether the invariants panel of ``scene`` draws :func:`energy_balance` (its effects
    conserve nothing simple; not the damped top, drawn against its exact |L|; no user
    torque, which would run again outside the run's opt-in).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> [energy_balance_drawn(load_scene(name)) for name in ("heavy_top", "damped_top")]
    [False, False]
    """
    types = [e["type"] for e in scene.data["effects"]]
    if "invariants" not in scene.data["output"]["plots"]:
        return False
    if types in ([], ["gravity"], ["space_torque"]):  # invariant_series has rows to draw
        return False
    return scene.exact != "damped_symmetric_top" and "user" not in types


def energy_balance(scene: Scene, tr: Trajectory, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(E − E₀, W): the kinetic energy gained and the work the torques did, per sample.

    Nothing is conserved under a general torque, but energy balances: dE/dt = τ·ω, so
    E(t) − E(0) = W(t) = ∫ τ·ω dt (trapezoid rule on the samples; their spacing limits the
    agreement, not the integrator). Damping makes W negative: the energy dissipated.

    Examples
    --------
    >>> from ga_rotors.scene import Scene, run_scene
    >>> scene = Scene({"body": {"moments": [1.0, 2.0, 3.0]},
    ...                "initial": {"angular_velocity": {"body": [0.0, 0.0, 1.0],
    ...                                                 "units": "rad/s"}},
    ...                "time": {"duration": 1.0}, "integrator": {"step": 1e-3},
    ...                "effects": [{"type": "body_torque", "torque": [0.0, 0.0, 0.5]}]})
    >>> tr = run_scene(scene)
    >>> gain, work = energy_balance(scene, tr, tr.quaternions())
    >>> round(float(gain[-1]), 6), round(float(work[-1]), 6)   # ω₃ 1 → 7/6: ΔE = 0.5·3·(49/36 − 1)
    (0.541667, 0.541667)
    """
    w = tr.w
    t = tr.t[: w.shape[0]]
    q = q[: w.shape[0]]
    from ..effects import torque_power

    # the kernels act in the principal frame (τ·ω is the same number in any frame)
    qp, wp = (q, w) if scene.body.is_principal else scene.body.to_principal(q, w)
    power = torque_power(scene.torques(), t, qp, wp)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    energy = scene.body.energy(w)
    return energy - energy[0], work


def _energy_balance(ax, ctx: _Context) -> None:
    if "energy_gain" in ctx.tr:  # a thinned copy: accumulated over every sample as it ran
        gain, work = ctx.tr["energy_gain"], ctx.tr["torque_work"]
    else:
        gain, work = energy_balance(ctx.scene, ctx.tr, ctx.get("q"))
    _line(ax, ctx.t, gain, lw=1.0, label="kinetic energy gained E − E₀")
    _line(ax, ctx.t, work, lw=1.2, ls=(0, (4, 3)), label="work done by the torques ∫τ·ω dt")
    ax.set_ylabel("energy (J)", fontsize=8)
    ax.legend(**_BESIDE)


def _error(axes, ctx: _Context) -> None:
    from .. import quaternion as Q

    (ax,) = axes
    exact = ctx.get("exact")
    first = None
    for k, path in enumerate(ctx.scene.paths):
        q = Q.normalize(ctx.tr.quaternions(path))
        e = exact.orientation_error(ctx.tr.t[: q.shape[0]], q)
        label = path
        if first is None:
            first = (path, e)
        else:  # drawn dashed on top; say so when it hides the first path's line
            m = min(e.shape[0], first[1].shape[0])
            gap = float(np.abs(e[:m] - first[1][:m]).max()) / max(float(first[1].max()), 1e-300)
            if gap < 1e-2:
                label = f"{path} (dashed): on the\n{first[0]} line, ≤ {gap:.0e} apart"
        style = dict(lw=0.8, ls="-") if k == 0 else dict(lw=1.2, ls=(0, (4, 3)))
        _line(ax, ctx.tr.t[: q.shape[0]], np.maximum(e, 1e-17), log=True, label=label, **style)
    ax.set_ylabel("error (rad)", fontsize=8)
    ax.legend(**_BESIDE)


#: plot name -> (rows, drawing function); the names are :data:`ga_rotors.scene.schema.PLOTS`.
#: ``angles`` draws nutation θ and precession ψ (the spin φ, a near-straight line that
#: would flatten both, is in the data when ``angles`` is a quantity).
PANELS = {
    "omega": (1, _omega),
    "angles": (2, _angles),
    "momentum": (1, _momentum),
    "invariants": (1, _invariants),
    "error": (1, _error),
    "position": (1, _position),
}


def draw(scene: Scene, trajectory: Trajectory):
    """A matplotlib Figure with one panel per ``output.plots`` entry (in that order).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> scene = load_scene("damped_top").replace({"time.duration": 0.1})
    >>> len(draw(scene, run_scene(scene)).axes)     # omega, invariants
    2
    """
    from matplotlib import rcParams
    from matplotlib.figure import Figure

    from .thinning import KEEP_ALL

    plots = scene.data["output"]["plots"]
    rows = sum(PANELS[p][0] for p in plots)
    height = _ROW * rows + 0.95
    fig = Figure(figsize=(_WIDTH, height))
    fig.subplots_adjust(left=0.1, right=0.76, top=1 - 0.6 / height, bottom=0.45 / height,
                        hspace=0.12)  # fmt: skip
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    ctx = _Context(scene, trajectory)
    t = ctx.t
    if t.shape[0] > KEEP_ALL and t[-1] > t[0]:
        # the limits autoscaling would give, set before the lines, whose envelopes are
        # sliced at the pixel columns between them (_line)
        margin = rcParams["axes.xmargin"] * (t[-1] - t[0])
        axes[0].set_xlim(t[0] - margin, t[-1] + margin)
    row = 0
    for p in plots:
        n, func = PANELS[p]
        func(axes[row : row + n], ctx)
        row += n
    for letter, ax in zip("abcdefghij", axes, strict=False):
        ax.tick_params(which="both", labelsize=7)  # a log axis labels minor ticks too
        if ax.get_yscale() == "linear":  # no "1e−8+1.572e1" offset text
            ax.ticklabel_format(axis="y", useOffset=False)
        # y given: matplotlib then skips placing the title above top tick labels there are
        # none of (measuring every axis' labels for it was a tenth of a figure's drawing)
        ax.set_title(f"({letter})", loc="left", y=1.0, fontsize=8, fontweight="bold", pad=2)
    axes[-1].set_xlabel("t (s)", fontsize=8)
    title = scene.name + (f": {scene.description}" if scene.description else "")
    lines = textwrap.wrap(title, 110)  # two lines at most, cut at a word
    if len(lines) > 2:
        lines[1] = textwrap.shorten(lines[1] + " " + lines[2], 109, placeholder="…")
        lines[1] = lines[1].replace(".…", "…")
    fig.suptitle("\n".join(lines[:2]), fontsize=9)
    return fig


def render(scene: Scene, trajectory: Trajectory, fmt: str | None = None) -> bytes:
    """The scene's figure as the bytes of a ``fmt`` file (default: the scene's
    ``output.figure_format``), carrying :func:`data_digest` in its metadata.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> scene = load_scene("damped_top").replace({"time.duration": 0.1,
    ...                                           "output.figure_format": "pdf"})
    >>> render(scene, run_scene(scene))[:5]
    b'%PDF-'
    """
    from ..paper.figures import encode_figure

    fmt = scene.data["output"]["figure_format"] if fmt is None else fmt
    description = DIGEST_PREFIX + data_digest(scene, trajectory)
    return encode_figure(draw(scene, trajectory), fmt, description, dpi=_DPI)


def figure_png(scene: Scene, trajectory: Trajectory) -> bytes:
    """The scene's figure as PNG bytes, carrying :func:`data_digest` in its metadata.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> scene = load_scene("damped_top").replace({"time.duration": 0.1})
    >>> figure_png(scene, run_scene(scene))[1:4]
    b'PNG'
    """
    return render(scene, trajectory, "png")
