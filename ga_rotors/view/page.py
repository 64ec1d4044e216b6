"""One self-contained HTML page (plotly.js inlined, no network) that plays a run.

The static parts of the figure (unit sphere, the symmetry axis' trace) and the styling of
every trace are built with plotly's Python API; the page's own script (``viewer.js`` next
to this module) moves the body, ω, L and the rotor's plane when the time slider moves,
and writes the readouts. The state shown is readable from the page: ``#readouts``
carries ``data-index`` and ``data-time``, each path's quaternion cell ``data-q``. A query
string ``?t=SECONDS`` (or ``?frame=K``) opens the page at that time.
"""

from __future__ import annotations

import html
import json
from importlib import resources

import numpy as np

from .. import quaternion as Q
from .data import NEAR_LOCK, ViewData

__all__ = ["INSTALL_HINT", "MAX_FRAMES", "figure", "page_html", "require_plotly"]

#: Most slider positions a page carries (the samples are thinned evenly to this many).
MAX_FRAMES = 600
#: Most points of the symmetry axis' trace on the sphere, per path.
MAX_TRACE = 4000
INSTALL_HINT = 'the viewer needs plotly: pip install "ga-rotors[view]"'

_PATH_COLOURS = {"rotor": "#1f77b4", "quaternion": "#d62728", "euler": "#2ca02c"}
_AXIS_COLOURS = ("#e41a1c", "#4daf4a", "#377eb8")


def require_plotly():
    """Import plotly, or raise :class:`~ga_rotors.errors.InputError` saying how to install it.

    Examples
    --------
    >>> require_plotly().__name__
    'plotly'
    """
    try:
        import plotly
    except ImportError:  # pragma: no cover - the [view] extra is installed in CI
        from ..errors import InputError

        raise InputError(INSTALL_HINT) from None
    return plotly


def _thin(n: int, most: int) -> np.ndarray:
    return np.unique(np.linspace(0, n - 1, min(n, most)).round().astype(np.int64))


def _ellipsoid(moments, nu: int = 24, nv: int = 14):
    """Vertices and triangles of the uniform ellipsoid with these principal moments.

    Semi-axes aₖ² ∝ Iⱼ + Iₗ − Iₖ (a solid ellipsoid's moments), scaled to a largest
    semi-axis of 1; a flat body (Iₖ = Iⱼ + Iₗ) keeps a visible thickness.
    """
    if moments is None:
        a = np.full(3, 0.6)
    else:
        m = np.asarray(moments)
        a = np.sqrt(np.maximum(m.sum() - 2 * m, 0.0))
        a = np.maximum(a / a.max(), 0.04)
    u = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    v = np.linspace(0, np.pi, nv)
    uu, vv = np.meshgrid(u, v)
    pts = np.stack([np.cos(uu) * np.sin(vv), np.sin(uu) * np.sin(vv), np.cos(vv)], -1) * a
    idx = np.arange(nu * nv).reshape(nv, nu)
    tri = []
    for r in range(nv - 1):
        for c in range(nu):
            p, q_, s, t = idx[r, c], idx[r, (c + 1) % nu], idx[r + 1, c], idx[r + 1, (c + 1) % nu]
            tri += [(p, q_, s), (q_, t, s)]
    return pts.reshape(-1, 3), np.array(tri), a


def _sphere_wire() -> tuple[list, list, list]:
    xs, ys, zs = [], [], []
    s = np.linspace(0, 2 * np.pi, 61)
    for lat in np.radians([-60, -30, 0, 30, 60]):
        xs += [*(np.cos(lat) * np.cos(s)), None]
        ys += [*(np.cos(lat) * np.sin(s)), None]
        zs += [*np.full(s.shape, np.sin(lat)), None]
    for lon in np.radians(np.arange(0, 180, 30)):
        xs += [*(np.cos(lon) * np.sin(s)), None]
        ys += [*(np.sin(lon) * np.sin(s)), None]
        zs += [*np.cos(s), None]
    return xs, ys, zs


def figure(data: ViewData):
    """The plotly figure: one 3-D scene per path, dynamic traces empty until the page fills them.

    Examples
    --------
    >>> d = ViewData(np.array([0.0]), {"rotor": np.array([[1.0, 0, 0, 0]])}, np.zeros((1, 3)),
    ...              (1.0, 1.0, 2.0))
    >>> fig = figure(d)
    >>> len(fig.data), fig.layout.scene.aspectmode
    (11, 'cube')
    """
    require_plotly()
    import plotly.graph_objects as go

    names = list(data.paths)
    fig = go.Figure()
    _, tri, _ = _ellipsoid(data.moments)
    wire = _sphere_wire()
    k = data.axis
    width = 1.0 / len(names)
    layout = {}
    for i, name in enumerate(names):
        scene = "scene" if i == 0 else f"scene{i + 1}"
        colour = _PATH_COLOURS.get(name, "#555")
        first = i == 0
        q = data.paths[name]
        trace = Q.rotate(q[_thin(q.shape[0], MAX_TRACE)], np.eye(3)[k])
        lines = dict(mode="lines", scene=scene, hoverinfo="skip")
        fig.add_scatter3d(x=wire[0], y=wire[1], z=wire[2], line=dict(color="#ccc", width=1),
                          showlegend=False, **lines)  # fmt: skip
        fig.add_scatter3d(x=trace[:, 0], y=trace[:, 1], z=trace[:, 2],
                          line=dict(color=colour, width=3), name=f"e{k + 1} trace",
                          legendgroup="trace", showlegend=first, **lines)  # fmt: skip
        fig.add_mesh3d(x=[], y=[], z=[], i=tri[:, 0], j=tri[:, 1], k=tri[:, 2], scene=scene,
                       color=colour, opacity=0.45, flatshading=True, hoverinfo="skip",
                       name="body", showlegend=False)  # fmt: skip
        for a in range(3):
            fig.add_scatter3d(x=[], y=[], z=[], line=dict(color=_AXIS_COLOURS[a], width=6),
                              name=f"body e{a + 1}", legendgroup=f"e{a + 1}", showlegend=first,
                              **lines)  # fmt: skip
        for label, colour_v in (("ω", "#ff7f0e"), ("L", "#9467bd")):
            fig.add_scatter3d(x=[], y=[], z=[], mode="lines+markers", scene=scene,
                              line=dict(color=colour_v, width=7),
                              marker=dict(size=[0, 5], color=colour_v, symbol="diamond"),
                              name=f"{label} (space)", legendgroup=label, showlegend=first,
                              hoverinfo="skip")  # fmt: skip
        fig.add_mesh3d(x=[], y=[], z=[], scene=scene, color="#f2c94c", opacity=0.3,
                       hoverinfo="skip", name="rotor plane")  # fmt: skip
        fig.add_scatter3d(x=[], y=[], z=[], line=dict(color="#b8860b", width=5),
                          name="rotor plane, angle α", legendgroup="plane", showlegend=first,
                          **lines)  # fmt: skip
        fig.add_scatter3d(x=[], y=[], z=[], mode="markers", scene=scene,
                          marker=dict(size=5, color=colour), showlegend=False,
                          hoverinfo="skip")  # fmt: skip
        box = dict(range=[-1.5, 1.5], showbackground=False, zeroline=False,
                   showticklabels=False, showspikes=False, gridcolor="#eee")  # fmt: skip
        layout[scene] = dict(
            domain=dict(x=[i * width, (i + 1) * width], y=[0, 1]),
            xaxis=dict(box, title="x"), yaxis=dict(box, title="y"), zaxis=dict(box, title="z"),
            aspectmode="cube", camera=dict(eye=dict(x=1.2, y=1.05, z=0.7)),
            annotations=[],
        )  # fmt: skip
    fig.update_layout(
        **layout,
        margin=dict(l=0, r=0, t=30, b=0),
        legend=dict(orientation="h", y=-0.02, x=0.5, xanchor="center"),
        annotations=[
            dict(
                text=f"<b>{name}</b> path",
                x=(i + 0.5) * width,
                y=1.02,
                xref="paper",
                yref="paper",
                showarrow=False,
                font=dict(size=14),
            )
            for i, name in enumerate(names)
        ],
        uirevision="keep",
        height=560,
    )
    return fig


def _payload(data: ViewData) -> dict:
    idx = _thin(data.t.shape[0], MAX_FRAMES)
    moments = data.moments
    verts, _, semi = _ellipsoid(moments)
    w = data.w
    wi = np.minimum(idx, w.shape[0] - 1)
    L = w * np.asarray(moments) if moments is not None else None
    paths = []
    for name, q in data.paths.items():
        m = q.shape[0]
        keep = idx[idx < m]
        angles, locked = data.euler(name)
        sin_theta = np.abs(np.sin(np.radians(angles[keep, 1])))
        paths.append(
            {
                "name": name,
                "frames": int(keep.shape[0]),
                "q": q[keep].round(15).tolist(),
                "euler": angles[keep].round(10).tolist(),
                "locked": locked[keep].tolist(),
                "near": (sin_theta < NEAR_LOCK).tolist(),
                "sinTheta": sin_theta.tolist(),
                "endedAt": None if m == data.t.shape[0] else float(data.t[m - 1]),
            }
        )
    return {
        "title": data.title,
        "t": data.t[idx].tolist(),
        "w": w[wi].tolist(),
        "L": None if L is None else L[wi].tolist(),
        "wMax": float(np.linalg.norm(w, axis=1).max()),
        "LMax": None if L is None else float(np.linalg.norm(L, axis=1).max()),
        "vertices": verts.round(6).tolist(),
        "semiAxes": semi.tolist(),
        "axis": data.axis,
        "moments": None if moments is None else list(moments),
        "paths": paths,
        "notes": list(data.notes),
    }


def _script_json(obj) -> str:
    # Inside <script>, "</" would end the element and "<!--" open a comment: escape all "<".
    return json.dumps(obj, separators=(",", ":")).replace("<", "\\u003c").replace(">", "\\u003e")


def page_html(data: ViewData) -> str:
    """The complete page as one string (about 5 MB: plotly.js is inlined for offline use).

    Examples
    --------
    >>> d = ViewData(np.array([0.0]), {"rotor": np.array([[1.0, 0, 0, 0]])}, np.zeros((1, 3)),
    ...              (1.0, 1.0, 2.0), title="<demo>")
    >>> text = page_html(d)
    >>> "&lt;demo&gt;" in text, "https://" in text.split("<script>", 1)[0]
    (True, False)
    """
    require_plotly()
    from plotly.offline import get_plotlyjs

    fig = figure(data)
    here = resources.files(__package__)
    script = here.joinpath("viewer.js").read_text(encoding="utf-8")
    style = here.joinpath("viewer.css").read_text(encoding="utf-8")
    title = html.escape(data.title)
    about = f'<p id="description">{html.escape(data.description)}</p>\n' if data.description else ""
    figure_json = fig.to_json().replace("<", "\\u003c")
    rows = "".join(
        f'<tr data-path="{html.escape(p)}"><th>{html.escape(p)}</th>'
        '<td class="rotor"></td><td class="q"></td><td class="euler"></td>'
        '<td class="gimbal"></td></tr>'
        for p in data.paths
    )
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{title}</title>
<style>{style}</style>
<script>{get_plotlyjs()}</script>
</head><body>
<h1>{title}</h1>
{about}<div id="controls">
  <button id="play" type="button">play</button>
  <input id="slider" type="range" min="0" max="0" value="0" step="1" aria-label="time">
  <span id="time"></span>
</div>
<div id="figure"></div>
<table id="readouts" data-index="0" data-time="0">
<thead><tr><th>path</th><th>rotor R = w − x e23 − y e31 − z e12</th>
<th>quaternion (w, x, y, z)</th><th>z–y′–z″ (ψ, θ, φ)</th><th>gimbal</th></tr></thead>
<tbody>{rows}</tbody></table>
<p id="legend-note">Body: the uniform ellipsoid with the run's principal moments (semi-axes
{", ".join(f"{a:.2f}" for a in _ellipsoid(data.moments)[2])}). ω and L are drawn in space,
each scaled by its largest value over the run. The rotor's plane is the bivector plane of
R = cos(α/2) − I u sin(α/2), the arc its angle α. The coloured curve is the trace of body
axis e{data.axis + 1} on the unit sphere.</p>
<script type="application/json" id="view-data">{_script_json(_payload(data))}</script>
<script type="application/json" id="view-figure">{figure_json}</script>
<script>{script}</script>
</body></html>
"""
