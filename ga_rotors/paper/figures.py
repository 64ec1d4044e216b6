"""Figures 3–10 of the paper, redrawn from :mod:`ga_rotors.paper.runs`, plus the errors.

Each figure has two columns: the paper's printed inertia (left) and the consistent disk
(right), so the reader sees at once what the paper's model does and what a disk spinning
about its symmetry axis does. Every PNG carries the data digest
(:func:`ga_rotors.paper.digest.data_digest`) in its ``Description`` metadata, which the
tests compare with a fresh run.

Speed: building matplotlib Axes (ticks, spines, text) costs far more than drawing 10,000
points, so one canvas per layout is built once and reused, its lines' data swapped
between figures. This module needs only numpy and matplotlib: it draws from
:class:`FigureData`, plain arrays, so a worker process can draw without importing the
simulation stack.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = [
    "DIGEST_PREFIX",
    "FIGURES",
    "FIGURE_FORMATS",
    "FigureData",
    "draw_all",
    "encode_figure",
    "figure_data",
    "palette_png",
    "read_digest",
]

DIGEST_PREFIX = "ga_rotors paper data "

#: Figure file formats (``ga-rotors paper --format``, ``ga-rotors run --format``, a
#: scene's ``output.figure_format``) -> what each is for.
FIGURE_FORMATS = {
    "png": "150-dpi palette PNG (the default): small, sharp on screen",
    "svg": "vector SVG: any zoom, for the web and for editing",
    "pdf": "vector PDF: for print and LaTeX",
}

#: file stem -> title; the order is the paper's.
FIGURES = {
    "fig03_euler_angles_15deg": "Fig. 3: Euler angles, θ₀ = 15° (Euler-angle path; rotor dashed)",
    "fig04_body_rates_15deg": "Fig. 4: body angular velocity, θ₀ = 15°",
    "fig05_quaternion_15deg": "Fig. 5: quaternion path, θ₀ = 15°",
    "fig06_euler_path_0.001deg": "Fig. 6: Euler angles from the Euler-angle path, θ₀ = 0.001°",
    "fig07_rotor_angles_0.001deg": "Fig. 7: Euler angles of the rotor path, θ₀ = 0.001°",
    "fig06_07_overlay_0.001deg": "Figs. 6–7 overlaid: Euler-angle path (solid) and rotor path "
    "(dashed), θ₀ = 0.001°",
    "fig08_euler_rates_0.001deg": "Fig. 8: angle rates along the Euler-angle path, θ₀ = 0.001°",
    "fig09_body_rates_0.001deg": "Fig. 9: body angular velocity, θ₀ = 0.001°",
    "fig10_quaternion_0.001deg": "Fig. 10: quaternion path, θ₀ = 0.001°",
    "errors": "Geodesic error against the exact solution (RK4, Δt = 1 ms)",
}

_DEG = 180.0 / np.pi
_DPI = 150  # 8 pt text is 17 px: legible on screen and in print
_WIDTH = 9.0
_ROW = 1.45
#: Arrays the figures read from a scene's trajectory.
_ARRAYS = (
    "t", "w", "q", "euler", "angles", "psi_plus_phi", "euler_rates", "error_R", "error_q",
    "error_euler",
)  # fmt: skip
#: Two curves in one panel: what each is (the second is drawn dashed, on top).
_PAIR_LABELS = {
    "fig03": ("Euler-angle path", "rotor path"),
    "fig06_07": ("Euler-angle path (Fig. 6)", "rotor path (Fig. 7)"),
}


@dataclass
class FigureData:
    """What the figures need from one scene: labels and plain arrays.

    Examples
    --------
    >>> from ga_rotors.paper.runs import run_case
    >>> [d] = figure_data([run_case("disk", 15.0, steps=10)])
    >>> d.model, d.theta0_deg, d.arrays["q"].shape
    ('disk', 15.0, (11, 4))
    """

    model: str
    label: str
    theta0_deg: float
    arrays: dict


def figure_data(runs) -> list[FigureData]:
    """Light copies of :class:`ga_rotors.paper.runs.PaperRun` for drawing.

    Examples
    --------
    >>> from ga_rotors.paper.runs import run_all
    >>> data = figure_data(run_all(steps=10))
    >>> [(d.model, d.theta0_deg) for d in data]
    [('paper', 15.0), ('paper', 0.001), ('disk', 15.0), ('disk', 0.001)]
    >>> sorted(data[0].arrays) == sorted([*_ARRAYS, "path_gap"])
    True
    """
    from ..quaternion import distance

    data = []
    for s in runs:
        arrays = {k: s.trajectory[k] for k in _ARRAYS}
        # How far apart the two paths' orientations are (Figs. 6–7 overlaid), in degrees.
        q_euler = s.trajectory.quaternions("euler")
        q_rotor = s.trajectory.quaternions("rotor")[: q_euler.shape[0]]
        arrays["path_gap"] = np.degrees(distance(q_euler, q_rotor))
        data.append(FigureData(s.model.name, s.model.label, s.theta0_deg, arrays))
    return data


def _panels(stem: str, d: FigureData) -> list[tuple[str, list[tuple[np.ndarray, np.ndarray]]]]:
    """(y label, [(t, y), ...]) per panel; a second curve is drawn dashed."""
    a = d.arrays
    t = a["t"]
    te = t[: a["euler"].shape[0]]
    path, rotor = a["euler"] * _DEG, a["angles"] * _DEG
    names = ("ψ (°)", "θ (°)", "φ (°)")
    if stem.startswith("fig06_07"):
        gap = a["path_gap"]
        return [
            ("θ (°)", [(te, path[:, 1]), (t, rotor[:, 1])]),
            ("ψ + φ (°)", [(te, path[:, 0] + path[:, 2]), (t, a["psi_plus_phi"] * _DEG)]),
            ("paths apart (°)", [(te[: gap.shape[0]], gap)]),
        ]
    if stem.startswith("fig03"):
        return [(n, [(te, path[:, k]), (t, rotor[:, k])]) for k, n in enumerate(names)]
    if stem.startswith(("fig04", "fig09")):
        return [(f"ω {ax} (rad/s)", [(t, a["w"][:, k])]) for k, ax in enumerate(("x3", "y3", "z3"))]
    if stem.startswith(("fig05", "fig10")):
        return [(f"q{k}", [(t, a["q"][:, k])]) for k in range(4)]
    if stem.startswith("fig06"):
        rows = [(n, [(te, path[:, k])]) for k, n in enumerate(names)]
        return [*rows, ("ψ + φ (°)", [(te, path[:, 0] + path[:, 2])])]
    if stem.startswith("fig07"):
        rows = [(n, [(t, rotor[:, k])]) for k, n in enumerate(names)]
        return [*rows, ("ψ + φ (°)", [(t, a["psi_plus_phi"] * _DEG)])]
    if stem.startswith("fig08"):
        r = a["euler_rates"]
        labels = ("dψ/dt (rad/s)", "dθ/dt (rad/s)", "dφ/dt (rad/s)")
        return [(n, [(te, r[:, k])]) for k, n in enumerate(labels)]
    raise KeyError(stem)


class _Canvas:
    """A reusable grid of Axes with two lines each."""

    def __init__(self, nrows: int, log: bool = False, three: bool = False):
        from matplotlib.figure import Figure

        height = _ROW * nrows + 0.7
        self.fig = Figure(figsize=(_WIDTH, height))
        self.fig.subplots_adjust(
            left=0.08, right=0.99, top=1 - 0.6 / height, bottom=0.45 / height, wspace=0.22,
            hspace=0.15,
        )  # fmt: skip
        self.axes = self.fig.subplots(nrows, 2, sharex=True, squeeze=False)
        styles = ("-", "--", "-") if three else ("-", "--")
        self.lines = []
        from matplotlib.ticker import LogLocator, MaxNLocator, MultipleLocator

        for ax in self.axes.flat:
            if log:
                ax.set_yscale("log")
            # Tick objects are matplotlib's main cost: few, and fixed ones on the time axis.
            ax.xaxis.set_major_locator(MultipleLocator(2.0))
            ax.yaxis.set_major_locator(LogLocator(numticks=4) if log else MaxNLocator(4))
            ax.tick_params(labelsize=7)
            self.lines.append([ax.plot([], [], s, lw=1.0)[0] for s in styles])
        for ax in self.axes[-1]:
            ax.set_xlabel("t (s)", fontsize=8)

    def fill(self, title: str, columns: list[tuple[str, list]], symlog: bool = False) -> None:
        for col, (heading, panels) in enumerate(columns):
            self.axes[0, col].set_title(heading, fontsize=8)
            for row, (ylabel, curves) in enumerate(panels):
                ax = self.axes[row, col]
                lines = self.lines[row * 2 + col]
                peak = max(float(np.nanmax(np.abs(y))) for _, y in curves)
                # Spikes of 1e4 would flatten everything else on a linear axis: symlog,
                # linear below 1 (the rates between the spikes), logarithmic above.
                spiky = symlog and peak > 10.0
                if spiky:
                    shift, scale = 0.0, 1.0
                else:
                    shift, scale, ylabel = _readable(ylabel, curves, ax.get_yscale() == "log")
                for k, line in enumerate(lines):
                    if k < len(curves):
                        t, y = curves[k]
                        line.set_data(t, (y - shift) / scale)
                        line.set_visible(True)
                    else:
                        line.set_visible(False)
                if spiky:
                    ax.set_yscale("symlog", linthresh=1.0)
                ax.set_ylabel(ylabel, fontsize=8)
                ax.relim(visible_only=True)
                ax.autoscale_view()
                # Panel letters in reading order, as the text cites them ("Fig. 6(a)").
                letter = "abcdefghijklmnop"[row * len(columns) + col]
                ax.set_title(f"({letter})", loc="left", fontsize=8, fontweight="bold")
        self.fig.suptitle(title, fontsize=10)


def _readable(ylabel: str, curves, log: bool) -> tuple[float, float, str]:
    """(shift, scale, label) so that ticks need no offset text such as ``1e−8+1.572e1``.

    A panel whose values vary by less than 1e-3 of their size shows y − shift, and a panel
    whose values are all tiny or huge shows y / scale; both are written into the label.
    """
    values = np.concatenate([np.asarray(y, dtype=float) for _, y in curves])
    values = values[np.isfinite(values)]
    if log or values.size == 0:
        return 0.0, 1.0, ylabel
    lo, hi = float(values.min()), float(values.max())
    shift = 0.0
    if hi > lo and (hi - lo) < 1e-3 * max(abs(lo), abs(hi)):
        shift = float(f"{values[0]:.4g}")
    span = max(abs(lo - shift), abs(hi - shift))
    exponent = int(np.floor(np.log10(span))) if span > 0 else 0
    scale = 10.0**exponent if (exponent < -2 or exponent > 3) else 1.0
    name, _, unit = ylabel.partition(" (")
    unit = unit.removesuffix(")")
    if shift:
        name = f"{name} − {shift:g}"
    if scale != 1.0:
        unit = f"1e{exponent} {unit}".strip()
    return shift, scale, f"{name} ({unit})" if unit else name


def palette_png(fig, description: str, dpi: int = _DPI) -> bytes:
    """A matplotlib Figure as a 256-colour palette PNG (a third of the RGB size: these are
    line plots, and 256 colours keep the anti-aliased text sharp), with ``description`` in
    its ``Description`` text chunk and its resolution in ``pHYs``.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> fig = Figure(figsize=(2, 1))
    >>> _ = fig.add_subplot().plot([0, 1], [0, 1])
    >>> png = palette_png(fig, "made by a doctest")
    >>> png[:8], read_digest(io.BytesIO(png), prefix="made by ")
    (b'\\x89PNG\\r\\n\\x1a\\n', 'a doctest')
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image, PngImagePlugin

    canvas = FigureCanvasAgg(fig)
    fig.set_dpi(dpi)
    canvas.draw()
    image = Image.frombuffer("RGBA", canvas.get_width_height(), canvas.buffer_rgba())
    image = image.convert("RGB").quantize(colors=256, method=Image.Quantize.FASTOCTREE)
    info = PngImagePlugin.PngInfo()
    info.add_text("Description", description)
    buf = io.BytesIO()
    image.save(buf, format="png", pnginfo=info, dpi=(dpi, dpi))
    return buf.getvalue()


def encode_figure(fig, fmt: str, description: str, dpi: int = _DPI) -> bytes:
    """A matplotlib Figure as the bytes of a ``fmt`` file (a key of :data:`FIGURE_FORMATS`),
    with ``description`` in its metadata: the PNG's ``Description`` (:func:`palette_png`),
    the SVG's ``<dc:description>``, the PDF's ``Subject``.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> fig = Figure(figsize=(2, 1))
    >>> _ = fig.add_subplot().plot([0, 1], [0, 1])
    >>> encode_figure(fig, "pdf", "made by a doctest")[:5]
    b'%PDF-'
    >>> b"made by a doctest" in encode_figure(fig, "svg", "made by a doctest")
    True
    """
    if fmt not in FIGURE_FORMATS:
        from ..errors import InputError

        raise InputError(f"expected one of {', '.join(FIGURE_FORMATS)}, got {fmt!r}", key="format")
    if fmt == "png":
        return palette_png(fig, description, dpi=dpi)
    buf = io.BytesIO()
    key = "Description" if fmt == "svg" else "Subject"
    fig.savefig(buf, format=fmt, metadata={key: description})
    return buf.getvalue()


def _error_columns(data: list[FigureData]) -> tuple[list[tuple[str, list]], float]:
    """The error panels, and the largest relative gap between the rotor and quaternion
    paths' errors (the legend states their overlap: the dashed line lies on the solid one)."""
    floor = 1e-17  # an exact zero (t = 0) has no place on a log axis
    columns = []
    gap = 0.0
    for model in dict.fromkeys(d.model for d in data):
        panels = []
        for d in (d for d in data if d.model == model):
            t = d.arrays["t"]
            curves = []
            for name in ("error_R", "error_q", "error_euler"):
                e = d.arrays[name]
                curves.append((t[: e.shape[0]], np.maximum(e, floor)))
            e_r, e_q = d.arrays["error_R"], d.arrays["error_q"]
            scale = max(float(np.abs(e_r).max()), floor)
            gap = max(gap, float(np.abs(e_r - e_q).max()) / scale)
            panels.append((f"θ₀ = {d.theta0_deg:g}°: error (rad)", curves))
        columns.append((f"{model}: rotor, quaternion, Euler-angle path", panels))
    return columns, gap


def draw_all(
    data: list[FigureData], out_dir, digest: str, stems=None, fmt: str = "png"
) -> list[Path]:
    """Write figures as ``<out_dir>/<stem>.<fmt>`` (atomically); return the paths.

    ``stems``: the figures to draw (default: all of :data:`FIGURES`, in order). ``fmt``:
    ``png`` (150 dpi, the data digest in its metadata), or ``svg``/``pdf`` (vector, the
    digest in the file's description/subject).

    Examples
    --------
    >>> import tempfile
    >>> from ga_rotors.paper.runs import run_case
    >>> data = figure_data([run_case(m, 15.0, steps=10) for m in ("paper", "disk")])
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     [png] = draw_all(data, tmp, "0123abcd", stems=["fig04_body_rates_15deg"])
    ...     png.name, read_digest(png)
    ('fig04_body_rates_15deg.png', '0123abcd')
    """
    from matplotlib.ticker import MaxNLocator

    from ..files import atomic_write

    out_dir = Path(out_dir)
    by_key = {(d.model, d.theta0_deg): d for d in data}
    canvases: dict[int, _Canvas] = {}
    written = []
    for stem in FIGURES if stems is None else stems:
        title = FIGURES[stem]
        if stem == "errors":
            canvas = _Canvas(2, log=True, three=True)
            columns, gap = _error_columns(data)
            canvas.fill(title, columns)
            canvas.axes[0, 0].legend(
                canvas.lines[0],
                ["rotor", f"quaternion (on the rotor's line: they differ by ≤ {gap:.0e} of it)",
                 "Euler-angle path"],
                fontsize=7, loc="lower right",
            )  # fmt: skip
        else:
            theta = 15.0 if stem.endswith("_15deg") else 0.001
            pair = [by_key[("paper", theta)], by_key[("disk", theta)]]
            columns = [(d.label, _panels(stem, d)) for d in pair]
            nrows = len(columns[0][1])
            if nrows not in canvases:
                canvases[nrows] = _Canvas(nrows)
            canvas = canvases[nrows]
            for ax in canvas.axes.flat:  # a reused canvas: back to the defaults
                ax.set_yscale("linear")
                ax.yaxis.set_major_locator(MaxNLocator(4))
                if ax.get_legend():
                    ax.get_legend().remove()
            canvas.fill(title, columns, symlog=stem.startswith("fig08"))
            pair_labels = _PAIR_LABELS.get(stem[:8] if stem.startswith("fig06_07") else stem[:5])
            if pair_labels:
                canvas.axes[0, 0].legend(canvas.lines[0], pair_labels, fontsize=7,
                                         loc="upper right")  # fmt: skip
        payload = encode_figure(canvas.fig, fmt, DIGEST_PREFIX + digest)
        written.append(atomic_write(out_dir / f"{stem}.{fmt}", lambda fh, b=payload: fh.write(b)))
    return written


def read_digest(png, prefix: str = DIGEST_PREFIX) -> str | None:
    """The data digest stored in a figure written by :func:`draw_all` (or by
    :func:`palette_png` with ``prefix``), or None.

    Examples
    --------
    >>> from matplotlib.figure import Figure
    >>> png = io.BytesIO(palette_png(Figure(figsize=(1, 1)), DIGEST_PREFIX + "0123abcd"))
    >>> read_digest(png)
    '0123abcd'
    >>> read_digest(png, prefix="another prefix ") is None
    True
    """
    from PIL import Image

    with Image.open(png) as im:
        text = im.info.get("Description", "")
    return text[len(prefix) :] if text.startswith(prefix) else None
