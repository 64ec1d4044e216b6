"""One self-contained HTML page that plays a run, drawn by the package's own small script.

The page is the run's data (one JSON element), a legend and readouts written here, and
``viewer.js`` (next to this module), which projects the body, its axes, ω, L, the rotor's
plane and the symmetry axis' trace onto a 2-D canvas per orientation path, depth-sorted,
at the slider's time. No library travels with it and nothing is loaded from the network:
a page is a few hundred kilobytes and opens at once, WebGL or not.

The state shown is readable from the page: ``#readouts`` carries ``data-index`` and
``data-time``, each path's quaternion cell ``data-q``; each canvas carries ``data-camera``
(its projection) and ``data-elements`` (where each element was drawn, in CSS pixels), and
each legend entry ``data-drawn``. A query string ``?t=SECONDS`` (or ``?frame=K``) opens the
page at that time.
"""

from __future__ import annotations

import html
import json
from importlib import resources

import numpy as np

from .. import quaternion as Q
from ..errors import InputError
from .data import NEAR_LOCK, ViewData

__all__ = ["ELEMENTS", "MAX_FRAMES", "MAX_TRACE", "page_html", "payload"]

#: Most slider positions a page carries (the samples are thinned evenly to this many).
MAX_FRAMES = 600
#: Most points of the symmetry axis' trace on the sphere, per path.
MAX_TRACE = 4000
#: Farthest point of the body from the point it turns about, in drawing units (the unit
#: sphere of the trace has radius 1; ω and L reach 1.2 and 1.45).
BODY_REACH = 0.85

#: What the page draws, in legend order: key -> (legend text, colour). The body axes keep
#: the usual red, green, blue; ω, L, the rotor's plane and the body are in hues apart from
#: them (the Okabe–Ito colour-blind-safe set, with black for L).
ELEMENTS = {
    "body": ("body", "#a7b0ba"),
    "pivot": ("pivot: the fixed point, joined to the centre of mass", "#000000"),
    "e1": ("body axis e1", "#d55e00"),
    "e2": ("body axis e2", "#009e73"),
    "e3": ("body axis e3", "#0072b2"),
    "omega": ("ω, angular velocity, in space", "#c2188c"),
    "L": ("L = Iω, angular momentum, in space", "#1a1a1a"),
    "plane": ("the rotor's plane (its bivector) and angle α", "#e6c700"),
    "trace": ("trace of the symmetry axis on the unit sphere", "#56b4e9"),
    "trail": ("path of the centre of mass through space", "#6a3d9a"),
}

#: For a body moving through space: how far the whole flight reaches from the view's centre
#: across or up the picture (drawing units; the picture shows 1.65 each way), the smallest
#: body drawn (its reach, enlarged up to it and said so), and the size of ω, L, the rotor's
#: plane and the trace's sphere around its centre of mass.
FLIGHT_REACH = 1.5
SMALLEST_BODY = 0.2
MOVING_GLYPH = 0.4

#: Drawn length of each vector at its largest over the run (drawing units).
_LENGTHS = {"omega": 1.2, "L": 1.45}


def _thin(n: int, most: int) -> np.ndarray:
    return np.unique(np.linspace(0, n - 1, min(n, most)).round().astype(np.int64))


def _norms(v: np.ndarray) -> np.ndarray:
    """Row norms that do not overflow for finite rows (|(1e308, 1e308, 0)| is 1.4e308)."""
    scale = np.abs(v).max(axis=1)
    safe = np.where(scale > 0, scale, 1.0)
    return scale * np.sqrt(((v / safe[:, None]) ** 2).sum(axis=1))


def _vector(key: str, values: np.ndarray, rows: np.ndarray, unit: str) -> dict:
    norms = _norms(values)
    largest = float(norms.max())
    shown = values[rows] / largest if largest > 0 else np.zeros((rows.size, 3))
    return {"key": key, "values": shown.round(6).tolist(), "max": largest, "unit": unit,
            "length": _LENGTHS[key]}  # fmt: skip


def _body(data: ViewData, scale: float) -> dict | None:
    """The body's mesh at ``scale`` drawing units per metre, in its body frame."""
    solid = data.solid
    if solid is None:
        return None
    vertices, faces, tones = solid.mesh()
    centre = np.asarray(solid.centre)
    reach = np.linalg.norm(vertices - centre, axis=1).max()
    label = solid.label or f"{solid.kind}"
    return {
        "label": label,
        "vertices": (vertices * scale).round(4).tolist(),
        "faces": faces,
        "tones": tones,
        "centre": (centre * scale).round(6).tolist(),
        "axisLength": round(float(reach * scale * 1.3), 4),
        "pivot": None if solid.pivot is None else (np.asarray(solid.pivot) * scale).tolist(),
    }


def _scale(data: ViewData) -> float:
    """Drawing units per metre: the body (and its path through space) within BODY_REACH."""
    reach = data.solid.extent() if data.solid is not None else 0.0
    moved = max((float(_norms(p).max()) for p in data.positions.values()), default=0.0)
    return BODY_REACH / (reach + moved) if reach + moved > 0 else 1.0


def _camera(data: ViewData) -> dict:
    """Where the view looks from: for a body moving through space, from the side of its
    flight (the centre of mass' horizontal travel runs across the picture, left to right),
    a little from above; a closed orbit from higher up; else the default."""
    if not data.positions:
        return {"azimuth": 40.0, "elevation": 22.0}
    trail = next(iter(_trails(data).values()))
    travel = trail[-1] - trail[0]
    spread = np.ptp(trail, axis=0)
    if np.hypot(*travel[:2]) > 0.5 * np.hypot(*spread[:2]):
        heading = np.degrees(np.arctan2(travel[1], travel[0]))
        return {"azimuth": round(float(heading - 70.0), 3), "elevation": 15.0}
    return {"azimuth": 40.0, "elevation": 35.0}


def _basis(camera: dict) -> tuple[np.ndarray, np.ndarray]:
    """The picture's right and up directions in space (viewer.js's ``basis``)."""
    a, e = np.radians(camera["azimuth"]), np.radians(camera["elevation"])
    eye = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.array([-np.sin(a), np.cos(a), 0.0])
    return right, np.cross(eye, right)


def _frame(data: ViewData, camera: dict) -> tuple[np.ndarray, float, float]:
    """(centre in m, drawing units per metre of the flight, of the body) of a body moving
    through space, seen from ``camera``: the whole flight (every path's origin, and its
    centre of mass with the body's reach around it) fills the picture to
    :data:`FLIGHT_REACH` across or up; a body that would be drawn smaller than
    :data:`SMALLEST_BODY` is enlarged to it."""
    reach = 0.0
    if data.solid is not None:
        vertices = data.solid.mesh()[0]
        reach = float(np.linalg.norm(vertices - np.asarray(data.solid.centre), axis=1).max())
    origins = np.concatenate(list(data.positions.values()))
    centres = np.concatenate(list(_trails(data).values()))
    right, up = _basis(camera)
    lo, hi = [], []
    for axis in (right, up):
        a, b = origins @ axis, centres @ axis
        lo.append(min(a.min(), b.min() - reach))
        hi.append(max(a.max(), b.max() + reach))
    lo, hi = np.array(lo), np.array(hi)
    middle = (lo + hi) / 2.0
    mean = centres.mean(axis=0)  # a point of space whose picture is the middle
    centre = mean + right * (middle[0] - mean @ right) + up * (middle[1] - mean @ up)
    half = float(np.max(hi - lo)) / 2.0
    scale = FLIGHT_REACH / half if half > 0 else 1.0
    body = max(scale, SMALLEST_BODY / reach) if reach > 0 else scale
    return centre, scale, body


def _trails(data: ViewData) -> dict:
    """Per path with positions, its centre of mass in space at each sample (m)."""
    centre = np.asarray(data.solid.centre if data.solid is not None else (0.0, 0.0, 0.0))
    return {k: p + Q.rotate(data.paths[k][: p.shape[0]], centre)
            for k, p in data.positions.items()}  # fmt: skip


def payload(data: ViewData) -> dict:
    """The page's data: everything ``viewer.js`` draws, thinned to :data:`MAX_FRAMES`.

    Examples
    --------
    >>> d = ViewData(np.array([0.0, 1.0]), {"rotor": np.array([[1.0, 0, 0, 0]] * 2)},
    ...              np.array([[0.0, 0.0, 2.0], [0.0, 1.0, 1.0]]), (1.0, 1.0, 2.0))
    >>> p = payload(d)
    >>> p["vectors"][0]["max"], p["vectors"][0]["values"][0], p["vectors"][1]["key"]
    (2.0, [0.0, 0.0, 1.0], 'L')
    """
    n = data.t.shape[0]
    idx = _thin(n, MAX_FRAMES)
    wi = np.minimum(idx, data.w.shape[0] - 1)
    moving = bool(data.positions)
    camera = _camera(data)
    if moving:
        centre, scale, body_scale = _frame(data, camera)
        trails = _trails(data)
    else:
        centre, scale = np.zeros(3), _scale(data)
        body_scale, trails = scale, {}
    axis = data.symmetry_direction
    vectors = [_vector("omega", data.w, wi, "rad/s")]
    if data.L is not None:
        vectors.append(_vector("L", data.L, wi, "kg·m²/s"))
    paths = []
    for name, q in data.paths.items():
        m = q.shape[0]
        keep = idx[idx < m]
        angles, locked = data.euler(name)
        sin_theta = np.abs(np.sin(np.radians(angles[keep, 1])))
        traced = _thin(m, MAX_TRACE)
        position = data.positions.get(name)
        trail = trails.get(name)
        drawn = None if trail is None else _thin(trail.shape[0], MAX_TRACE)
        paths.append({
            "name": name,
            "frames": int(keep.shape[0]),
            "q": q[keep].round(15).tolist(),
            "euler": angles[keep].round(10).tolist(),
            "locked": locked[keep].tolist(),
            "near": (sin_theta < NEAR_LOCK).tolist(),
            "sinTheta": sin_theta.tolist(),
            "endedAt": None if m == n else float(data.t[m - 1]),
            "trace": Q.rotate(q[traced], axis).round(4).tolist(),
            "traceUpTo": np.searchsorted(traced, keep, side="right").tolist(),
            "position": None if position is None
            else ((position[keep] - centre) * scale).round(6).tolist(),
            "trail": None if trail is None else ((trail[drawn] - centre) * scale).round(5).tolist(),
            "trailUpTo": None if trail is None
            else np.searchsorted(drawn, keep, side="right").tolist(),
        })  # fmt: skip
    lines = [
        {"key": line.key, "label": line.label, "colour": line.colour,
         "point": ((line.point[idx] - centre) * scale).round(6).tolist(),
         "direction": (line.direction[idx] / np.maximum(_norms(line.direction[idx]), 1e-300)
                       [:, None]).round(6).tolist()}
        for line in data.lines
    ]  # fmt: skip
    return {
        "format": 2,
        "title": data.title,
        "t": data.t[idx].tolist(),
        "body": _body(data, body_scale),
        "metresPerUnit": None if data.solid is None or data.solid.relative else 1.0 / scale,
        "bodyEnlarged": body_scale / scale,
        "glyph": MOVING_GLYPH if moving else 1.0,
        "inertia": None if data.inertia is None else data.inertia.tolist(),
        "symmetry": axis.tolist(),
        "vectors": vectors,
        "paths": paths,
        "lines": lines,
        "elements": _elements(data),
        "camera": camera,
    }


def _elements(data: ViewData) -> list[dict]:
    present = {"body": data.solid is not None, "pivot": data.solid is not None
               and data.solid.pivot is not None, "L": data.L is not None,
               "trail": bool(data.positions)}  # fmt: skip
    out = [{"key": k, "label": text, "colour": colour}
           for k, (text, colour) in ELEMENTS.items() if present.get(k, True)]  # fmt: skip
    out += [{"key": line.key, "label": line.label, "colour": line.colour} for line in data.lines]
    return out


def _script_json(obj) -> str:
    """JSON for a ``<script>`` element: never NaN or Infinity (invalid JSON: the page would
    stay blank), and no ``<``, ``>`` or ``&`` that could end the element."""
    try:
        text = json.dumps(obj, separators=(",", ":"), ensure_ascii=False, allow_nan=False)
    except ValueError:  # pragma: no cover - ViewData refuses non-finite input first
        raise InputError(
            "the page's data holds a value JSON cannot carry (NaN or infinity)"
        ) from None
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _swatch(key: str, colour: str) -> str:
    if key in ("body", "plane"):
        shape = f'<rect x="2" y="1" width="24" height="12" rx="2" fill="{colour}"/>'
    elif key == "pivot":
        shape = '<circle cx="14" cy="7" r="4.5" fill="#fff" stroke="#000" stroke-width="2.5"/>'
    else:
        width = 4 if key in ("omega", "L") else 2.5
        dash = ' stroke-dasharray="6 3"' if key == "velocity" else ""
        shape = (
            f'<line x1="2" y1="7" x2="26" y2="7" stroke="{colour}" stroke-width="{width}"{dash}/>'
        )
    return f'<svg width="28" height="14" aria-hidden="true">{shape}</svg>'


def _legend(data: ViewData, body: dict | None) -> str:
    items = []
    for e in _elements(data):
        text = html.escape(e["label"])
        if e["key"] == "body" and body is not None:
            text += ": " + html.escape(body["label"])
        items.append(f'<li data-element="{html.escape(e["key"])}" data-drawn="false">'
                     f'{_swatch(e["key"], e["colour"])} {text}</li>')  # fmt: skip
    return "\n".join(items)


def page_html(data: ViewData) -> str:
    """The complete page as one string (a few hundred kB; works offline, from a file).

    Examples
    --------
    >>> d = ViewData(np.array([0.0]), {"rotor": np.array([[1.0, 0, 0, 0]])}, np.zeros((1, 3)),
    ...              (1.0, 1.0, 2.0), title="<demo>")
    >>> text = page_html(d)
    >>> "&lt;demo&gt;" in text, "https://" in text, len(text) < 100_000
    (True, False, True)
    """
    here = resources.files(__package__)
    script = here.joinpath("viewer.js").read_text(encoding="utf-8")
    style = here.joinpath("viewer.css").read_text(encoding="utf-8")
    data_json = payload(data)
    title = html.escape(data.title)
    about = f'<p id="description">{html.escape(data.description)}</p>\n' if data.description else ""
    panels = "".join(
        f'<figure class="panel" data-path="{html.escape(p)}"><figcaption><b>{html.escape(p)}'
        f'</b> path</figcaption><canvas role="img" aria-label="the body on the '
        f'{html.escape(p)} path"></canvas></figure>'
        for p in data.paths
    )
    rows = "".join(
        f'<tr data-path="{html.escape(p)}"><th>{html.escape(p)}</th>'
        '<td class="rotor"></td><td class="q"></td><td class="euler"></td>'
        '<td class="gimbal"></td></tr>'
        for p in data.paths
    )
    vectors = {v["key"]: v for v in data_json["vectors"]}
    scales = "; ".join(
        f"{'ω' if k == 'omega' else 'L'} is drawn {v['length']} units long at its largest, "
        f"{v['max']:.4g} {v['unit']}"
        for k, v in vectors.items()
    )
    size = ("to scale, " + f"{data_json['metresPerUnit']:.3g} m per unit"
            if data_json["metresPerUnit"] else "its size relative")  # fmt: skip
    if data_json["bodyEnlarged"] > 1.0 + 1e-9:
        size += f" (the body itself enlarged {data_json['bodyEnlarged']:.3g}× to be seen)"
    where = ("turning about the origin" if not data.positions else
             "moving through space, framed to show its whole flight; ω, L, the rotor's plane, "
             f"the space axes and the trace's sphere (radius {MOVING_GLYPH:g} units) are "
             "drawn around its centre of mass at a fixed size")  # fmt: skip
    sphere = ("the unit sphere (radius 1) carries the trace" if not data.positions
              else "a sphere around the centre of mass carries the trace")  # fmt: skip
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<style>{style}</style>
</head><body>
<h1>{title}</h1>
{about}<div id="controls">
  <button id="play" type="button">play</button>
  <input id="slider" type="range" min="0" max="0" value="0" step="1" aria-label="time">
  <span id="time"></span>
</div>
<div id="panels">{panels}</div>
<ul id="legend">
{_legend(data, data_json["body"])}
</ul>
<table id="readouts" data-index="0" data-time="0">
<thead><tr><th>path</th><th>rotor R = w − x e23 − y e31 − z e12</th>
<th>quaternion (w, x, y, z)</th><th>z–y′–z″ (ψ, θ, φ)</th><th>gimbal</th></tr></thead>
<tbody>{rows}</tbody></table>
<p id="legend-note">Space axes x, y, z in grey; {sphere}.
The body is drawn {size}, {where}. {scales}. The rotor's plane is the
plane of the bivector of R = cos(α/2) − I u sin(α/2) (the plane ⊥ u), the arc its angle α.
Drag a picture to turn the view; double-click to reset it.</p>
<script type="application/json" id="view-data">{_script_json(data_json)}</script>
<script>{script}</script>
</body></html>
"""
