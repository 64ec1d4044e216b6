"""The body as the viewer draws it: its own shape, not an ellipsoid of its moments about a pivot.

A :class:`Solid` is a shape (disk, ring, cylinder, rod, box, sphere, ellipsoid) with its
dimensions, where its centre of mass sits in the body frame, how its own axes are turned in
the body frame, and the pivot when the body turns about one. :func:`from_scene` reads it from
a scene's ``[body]`` (the shape and dimensions it names, or the uniform ellipsoid of the
moments or tensor it gives, taken about the centre of mass) and its gravity effect (the
pivot at the origin, the centre of mass at ``pivot_to_com``). :func:`from_inertia` makes the
ellipsoid for a run that knows only its inertia. :meth:`Solid.mesh` gives the polygons the
page draws.

Examples
--------
The heavy top is a disk of radius 5 cm whose centre is 4 cm above the pivot: drawn as that
disk, not as the egg its inertia about the pivot would give.

>>> from ga_rotors.scene import load_scene
>>> solid = from_scene(load_scene("heavy_top"))
>>> solid.kind, solid.size, solid.centre, solid.pivot
('disk', (0.05,), (0.0, 0.0, 0.04), (0.0, 0.0, 0.0))
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .. import quaternion as Q
from ..errors import InputError

__all__ = ["KINDS", "THIN", "Solid", "from_inertia", "from_scene"]

#: Shape name -> the names of its dimensions (metres, or relative units for an ellipsoid of
#: moments given without a mass). The scene's shapes, with their symmetry axis on z, and the
#: ellipsoid (semi-axes along its own x, y, z).
KINDS = {
    "disk": ("radius",),
    "ring": ("radius",),
    "cylinder": ("radius", "height"),
    "rod": ("length", "radius"),
    "box": ("a", "b", "c"),
    "sphere": ("radius",),
    "ellipsoid": ("a", "b", "c"),
}

#: Thinnest a drawn dimension may be, as a fraction of the largest: an ideal disk or hoop has
#: no thickness, and a slender rod would vanish at the page's scale.
THIN = 0.06

_IDENTITY = (1.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Solid:
    """A body's shape in its body frame.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.
    size : tuple of float
        The dimensions :data:`KINDS` names, in metres (relative units when ``relative``).
    centre : tuple of float
        The centre of mass in the body frame (m); the body frame's origin is the point the
        body turns about (the pivot, or the centre of mass itself).
    rotation : tuple of float
        Unit quaternion taking the shape's own axes to the body frame.
    pivot : tuple of float or None
        The fixed point the body turns about, in the body frame (the origin), or None for a
        free body.
    relative : bool
        True when the size is known only up to scale (moments without a mass).
    label : str
        What the page's legend says the body is.

    Examples
    --------
    >>> Solid("box", (1.0, 2.0, 3.0)).extent()
    1.8708286933869707
    >>> Solid("cone", (1.0,))
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: kind: expected one of disk, ring, cylinder, rod, box, \
sphere, ellipsoid, got 'cone'
    """

    kind: str
    size: tuple
    centre: tuple = (0.0, 0.0, 0.0)
    rotation: tuple = _IDENTITY
    pivot: tuple | None = None
    relative: bool = False
    label: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"expected one of {', '.join(KINDS)}, got {self.kind!r:.40}",
                             key="kind")  # fmt: skip
        names = KINDS[self.kind]
        size = tuple(float(x) for x in np.ravel(self.size))
        if len(size) != len(names) or not all(np.isfinite(x) and x > 0 for x in size):
            raise InputError(f"expected {len(names)} finite positive {', '.join(names)}, got "
                             f"{self.size!r:.60}", key="size")  # fmt: skip
        object.__setattr__(self, "size", size)
        for key in ("centre", "pivot"):
            value = getattr(self, key)
            if value is not None:
                v = tuple(float(x) for x in np.ravel(value))
                if len(v) != 3 or not all(np.isfinite(v)):
                    raise InputError(f"expected 3 finite numbers, got {value!r:.60}", key=key)
                object.__setattr__(self, key, v)
        r = np.asarray(self.rotation, dtype=np.float64)
        object.__setattr__(self, "rotation", tuple(float(x) for x in Q.normalize(r)))

    def turned(self, p) -> Solid:
        """The same solid described in another body frame: ``p`` takes this frame's axes to
        the new frame's (v_new = p v p*).

        Examples
        --------
        >>> s = Solid("disk", (1.0,), centre=(0.0, 0.0, 0.5))
        >>> quarter = (np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0)   # about x
        >>> np.round(s.turned(quarter).centre, 12).tolist()
        [0.0, -0.5, 0.0]
        """
        p = Q.normalize(np.asarray(p, dtype=np.float64))
        move = lambda v: None if v is None else tuple(Q.rotate(p, v).tolist())  # noqa: E731
        return replace(self, centre=move(self.centre), pivot=move(self.pivot),
                       rotation=tuple(Q.multiply(p, self.rotation).tolist()))  # fmt: skip

    def mesh(self, segments: int = 48) -> tuple[np.ndarray, list[list[int]], list[int]]:
        """(vertices (k, 3) in the body frame, faces as vertex-index lists, a tone 0/1 per face).

        Each face's vertices run counter-clockwise seen from outside (the page culls faces
        turned away). Tones alternate by sector (disk, ring, cylinder, rod), face (box) or
        octant (sphere, ellipsoid), so a spin about a symmetry axis shows.

        Examples
        --------
        >>> v, faces, tones = Solid("disk", (2.0,)).mesh(segments=8)
        >>> v.shape, len(faces), sorted(set(tones))
        ((18, 3), 24, [0, 1])
        >>> float(np.abs(v[:, :2]).max()), float(np.ptp(v[:, 2])) == 2.0 * THIN
        (2.0, True)
        """
        local, faces, tones, inside = _SHAPES[self.kind](self._drawn_size(), segments)
        faces = [_outward(local, f, inside) for f in faces]
        body = Q.rotate(np.asarray(self.rotation), local) + np.asarray(self.centre)
        return body, faces, tones

    def extent(self) -> float:
        """The largest distance of the drawn shape from the body frame's origin (m)."""
        vertices, _, _ = self.mesh(segments=24)
        return float(np.linalg.norm(vertices, axis=1).max())

    def _drawn_size(self) -> tuple:
        s = self.size
        if self.kind == "disk":
            return (s[0], THIN * s[0])  # radius, drawn thickness
        if self.kind == "ring":
            return (s[0], THIN * s[0] / 2)  # radius, tube radius
        if self.kind == "rod":
            return (max(s[1], THIN * s[0] / 2), s[0])  # radius, length
        largest = max(s)
        return tuple(max(x, THIN * largest / 2) for x in s)


def _outward(v: np.ndarray, face: list[int], inside) -> list[int]:
    p = v[face]
    normal = np.cross(p[1] - p[0], p[2] - p[0])
    centroid = p.mean(axis=0)
    return face if np.dot(normal, centroid - inside(centroid)) >= 0 else face[::-1]


def _centre(_point):
    return np.zeros(3)


def _cylinder(size, segments):
    radius, height = size
    a = np.linspace(0.0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(a), radius * np.sin(a), np.zeros(segments)], axis=1)
    lift = np.array([0.0, 0.0, height / 2])
    v = np.vstack([ring + lift, ring - lift, [lift, -lift]])
    ct, cb, n = 2 * segments, 2 * segments + 1, segments
    faces, tones = [], []
    for k in range(n):
        j = (k + 1) % n
        tone = (8 * k // n) % 2
        faces += [[ct, k, j], [cb, n + j, n + k], [n + k, n + j, j, k]]
        tones += [tone] * 3
    return v, faces, tones, _centre


def _disk(size, segments):
    return _cylinder(size, segments)


def _rod(size, segments):
    return _cylinder(size, segments)


def _ellipsoid(size, segments):
    nu = max(2 * segments // 3 // 4 * 4, 8)  # a curved surface needs fewer than a rim
    nv = nu // 2
    u = np.linspace(0.0, 2 * np.pi, nu, endpoint=False)
    rings = np.linspace(0.0, np.pi, nv + 1)[1:-1]
    v = [[0.0, 0.0, 1.0]]
    for th in rings:
        v += [[np.sin(th) * np.cos(x), np.sin(th) * np.sin(x), np.cos(th)] for x in u]
    v.append([0.0, 0.0, -1.0])
    v = np.asarray(v) * np.asarray(size)
    south = len(v) - 1

    def at(r, k):
        return 1 + r * nu + k % nu

    def tone(r, k):
        return (4 * k // nu + (2 * r >= len(rings))) % 2

    faces, tones = [], []
    for k in range(nu):
        faces.append([0, at(0, k), at(0, k + 1)])
        tones.append(tone(0, k))
        faces.append([south, at(len(rings) - 1, k + 1), at(len(rings) - 1, k)])
        tones.append(tone(len(rings) - 1, k))
        for r in range(len(rings) - 1):
            faces.append([at(r, k), at(r + 1, k), at(r + 1, k + 1), at(r, k + 1)])
            tones.append(tone(r, k))
    return v, faces, tones, _centre


def _sphere(size, segments):
    return _ellipsoid(size * 3, segments)


def _box(size, _segments, cuts: int = 3):
    half = np.asarray(size) / 2
    v, faces, tones = [], [], []
    grid = np.linspace(-1.0, 1.0, cuts + 1)
    for axis in range(3):
        for sign in (-1.0, 1.0):
            i, j = (axis + 1) % 3, (axis + 2) % 3
            base = len(v)
            for a in grid:
                for b in grid:
                    p = np.zeros(3)
                    p[axis], p[i], p[j] = sign, a, b
                    v.append(p * half)
            for a in range(cuts):
                for b in range(cuts):
                    k = base + a * (cuts + 1) + b
                    faces.append([k, k + cuts + 1, k + cuts + 2, k + 1])
                    tones.append((axis + (sign > 0)) % 2)
    return np.asarray(v), faces, tones, _centre


def _ring(size, segments, tube_segments: int = 12):
    radius, tube = size
    u = np.linspace(0.0, 2 * np.pi, segments, endpoint=False)
    w = np.linspace(0.0, 2 * np.pi, tube_segments, endpoint=False)
    v = []
    for x in u:
        for y in w:
            r = radius + tube * np.cos(y)
            v.append([r * np.cos(x), r * np.sin(x), tube * np.sin(y)])
    faces, tones = [], []
    for k in range(segments):
        for m in range(tube_segments):
            a = k * tube_segments + m
            b = ((k + 1) % segments) * tube_segments + m
            c = ((k + 1) % segments) * tube_segments + (m + 1) % tube_segments
            d = k * tube_segments + (m + 1) % tube_segments
            faces.append([a, b, c, d])
            tones.append((8 * k // segments) % 2)

    def inside(point):  # the nearest point of the tube's centre circle
        rho = np.hypot(point[0], point[1])
        return np.array([point[0], point[1], 0.0]) * (radius / rho)

    return np.asarray(v), faces, tones, inside


_SHAPES = {"disk": _disk, "ring": _ring, "cylinder": _cylinder, "rod": _rod, "box": _box,
           "sphere": _sphere, "ellipsoid": _ellipsoid}  # fmt: skip


def _semi_axes(moments, mass) -> tuple[tuple, bool]:
    """Semi-axes of the uniform solid ellipsoid with these moments about its centre:
    aₖ² = 5 (Iⱼ + Iₗ − Iₖ) / (2m); up to scale (largest 1) without a mass."""
    m = np.asarray(moments, dtype=np.float64)
    squares = np.maximum(m.sum() - 2 * m, 0.0)
    if mass is None:
        a = np.sqrt(squares / squares.max())
        return tuple(np.maximum(a, THIN / 2).tolist()), True
    a = np.sqrt(2.5 * squares / mass)
    return tuple(np.maximum(a, THIN * a.max() / 2).tolist()), False


def from_inertia(inertia, mass=None, centre=(0.0, 0.0, 0.0), pivot=None) -> Solid:
    """The uniform solid ellipsoid with this inertia about its centre of mass.

    Parameters
    ----------
    inertia : array_like, shape (3,) or (3, 3)
        Principal moments, or the tensor in the body frame (kg·m²), about the centre of mass.
    mass : float, optional
        The mass (kg): the ellipsoid's size in metres; without it the size is relative.
    centre, pivot
        As for :class:`Solid`.

    Examples
    --------
    A uniform ellipsoid of semi-axes (1, 2, 3) m and mass 5 kg has moments
    m(b² + c²)/5, m(a² + c²)/5, m(a² + b²)/5:

    >>> s = from_inertia((13.0, 10.0, 5.0), mass=5.0)
    >>> s.kind, np.round(s.size, 12).tolist(), s.relative
    ('ellipsoid', [1.0, 2.0, 3.0], False)
    >>> np.round(from_inertia((1.0, 1.0, 2.0)).size, 12).tolist()   # a flat disk, to scale
    [1.0, 1.0, 0.03]
    """
    from ..body import RigidBody

    t = np.asarray(inertia, dtype=np.float64)
    body = RigidBody(tuple(t)) if t.shape == (3,) else RigidBody.from_tensor(t)
    size, relative = _semi_axes(body.moments, mass)
    label = "uniform ellipsoid of the body's moments" + (" (its size relative: no mass given)"
                                                          if relative else "")  # fmt: skip
    return Solid("ellipsoid", size, centre, body.principal_rotation, pivot, relative, label)


def from_scene(scene) -> Solid:
    """The solid a scene describes, in the scene's body frame (the frame its file is written in).

    A ``[body]`` given by ``shape`` is that shape with its dimensions; one given by
    ``moments`` or ``tensor`` is the uniform ellipsoid of its inertia about the centre of
    mass (for a tensor given about the pivot, ``inertia_about = "pivot"``, the pivot's share
    m(|r|²1 − r rᵀ) is taken off first). With gravity the pivot is the origin and the centre
    of mass is at ``pivot_to_com``; for a body moving through space, at its
    ``body.centre_of_mass``.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> s = from_scene(load_scene("intermediate_axis_flip"))
    >>> s.kind, s.pivot
    ('box', None)
    """
    from ..effects import inertia_about_pivot
    from ..shapes import SHAPES

    body = scene.data["body"]
    mass = body.get("mass")
    centre, pivot, about_pivot = (0.0, 0.0, 0.0), None, False
    if scene.gravity_index is not None:
        gravity = scene.data["effects"][scene.gravity_index]
        centre, pivot = tuple(gravity["pivot_to_com"]), (0.0, 0.0, 0.0)
        about_pivot = gravity.get("inertia_about") == "pivot"
    elif scene.moves:  # a body moving through space: its frame's origin may be off the centre
        centre = tuple(scene.body.centre_of_mass)
    if "shape" in body:
        kind = body["shape"]
        size = tuple(body[k] for k in SHAPES[kind][1])
        words = ", ".join(f"{k} {body[k]:g} m" for k in SHAPES[kind][1])
        return Solid(kind, size, centre, _IDENTITY, pivot, False, f"uniform {kind}: {words}")
    tensor = np.diag(body["moments"]) if "moments" in body else np.asarray(body["tensor"])
    if about_pivot:
        tensor = tensor - inertia_about_pivot(np.zeros((3, 3)), mass, centre)
    return from_inertia(tensor, mass, centre, pivot)
