"""The pictures of the learning path (docs/learn/), each computed with the package's algebra.

Every picture is drawn from products evaluated in clifford's Cl(3,0) (through
:func:`ga_rotors.rotor.layout`) or Cl(3,0,1) (:mod:`ga_rotors.motor`, checked against
clifford's products), or from a run of :func:`ga_rotors.simulation.simulate`, so a picture
cannot disagree with the code it teaches. :data:`PICTURES` names them;
:func:`draw_all` writes them (PNG at 150 dpi by default, SVG or PDF on request)::

    python -m ga_rotors.view.diagrams docs/learn/images
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

__all__ = ["PICTURES", "draw_all", "reflect"]

_COLOURS = {"a": "#1f77b4", "b": "#d62728", "v": "#2ca02c", "image": "#9467bd", "mirror": "#555"}


def _e():
    from ..rotor import layout

    blades = layout().blades
    return blades["e1"], blades["e2"], blades["e3"]


def _mv(v):
    e1, e2, e3 = _e()
    v = [*v, 0.0, 0.0][:3]
    return float(v[0]) * e1 + float(v[1]) * e2 + float(v[2]) * e3


def _vector(m) -> np.ndarray:
    return np.array([m[(1,)], m[(2,)], m[(3,)]], dtype=float)


def reflect(v, n) -> np.ndarray:
    """Reflect the vector v in the plane (through 0) with unit normal n: v ↦ −n v n.

    Computed as a product in Cl(3,0), the way the learning path introduces it.

    Examples
    --------
    >>> reflect([1.0, 2.0, 3.0], [0.0, 0.0, 1.0])      # the mirror is the xy-plane
    array([ 1.,  2., -3.])
    """
    n = np.asarray(n, dtype=float)
    n = n / np.linalg.norm(n)
    return _vector(-_mv(n) * _mv(v) * _mv(n))


def _figure(ncols=1, width=4.2, height=3.6, projection=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        1, ncols, figsize=(width * ncols, height), subplot_kw={"projection": projection}
    )
    axes = np.atleast_1d(axes)
    if projection is None:
        for ax in axes:
            ax.set_aspect("equal")
            ax.axhline(0, color="#ddd", lw=0.8, zorder=0)
            ax.axvline(0, color="#ddd", lw=0.8, zorder=0)
    return fig, axes


def _arrow(ax, v, colour, label, origin=(0.0, 0.0), offset=(0.05, 0.05)):
    ax.annotate("", xy=(origin[0] + v[0], origin[1] + v[1]), xytext=origin,
                arrowprops=dict(arrowstyle="-|>", color=colour, lw=2))  # fmt: skip
    ax.text(origin[0] + v[0] + offset[0], origin[1] + v[1] + offset[1], label, color=colour,
            fontsize=12)  # fmt: skip


def _letter(ax, letter):
    ax.set_title(f"({letter})", loc="left", fontsize=11, fontweight="bold")


def _circulation(ax, centre, radius, clockwise, colour):
    from matplotlib.patches import FancyArrowPatch

    a0, a1 = (200, -80) if clockwise else (-20, 260)
    t = np.radians(np.linspace(a0, a1, 40))
    xs, ys = centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)
    ax.plot(xs[:-1], ys[:-1], color=colour, lw=1.5)
    ax.add_patch(FancyArrowPatch((xs[-2], ys[-2]), (xs[-1], ys[-1]), arrowstyle="-|>",
                                 mutation_scale=14, color=colour))  # fmt: skip


def geometric_product():
    """a and b in the e1e2-plane: ab = a·b + a∧b, the wedge as the oriented parallelogram."""
    a, b = np.array([2.0, 0.5]), np.array([0.8, 1.6])
    ab = _mv(a) * _mv(b)
    e1, e2, _ = _e()
    dot, wedge = float(ab[()]), float((ab(2) * ~(e1 * e2))[()])
    fig, (ax,) = _figure(width=5.0)
    ax.fill([0, a[0], a[0] + b[0], b[0]], [0, a[1], a[1] + b[1], b[1]], color="#f2c94c",
            alpha=0.5, label=f"a∧b = {wedge:g} e12 (area, orientation)")  # fmt: skip
    _circulation(ax, (a + b) / 2, 0.35, clockwise=wedge < 0, colour="#b8860b")
    _arrow(ax, a, _COLOURS["a"], "a")
    _arrow(ax, b, _COLOURS["b"], "b")
    ax.set_xlim(-0.4, 3.2)
    ax.set_ylim(-0.4, 2.5)
    ax.set_title(f"ab = a·b + a∧b = {dot:g} + {wedge:g} e12", fontsize=11)
    ax.legend(loc="upper left", fontsize=9, frameon=False)
    return fig


def bivector_orientation():
    """(a) a∧b, (b) b∧a = −a∧b, (c) a∧(b + 0.8a) = a∧b: a bivector is an oriented area."""
    a, b = np.array([1.6, 0.2]), np.array([0.4, 1.2])
    e1, e2, _ = _e()

    def wedge(x, y):
        return float(((_mv(x) ^ _mv(y)) * ~(e1 * e2))[()])

    fig, axes = _figure(3, width=3.4, height=3.2)
    cases = [(a, b, "a∧b"), (b, a, "b∧a"), (a, b + 0.8 * a, "a∧(b + 0.8a)")]
    for ax, letter, (x, y, name) in zip(axes, "abc", cases, strict=True):
        w = wedge(x, y)
        ax.fill([0, x[0], x[0] + y[0], y[0]], [0, x[1], x[1] + y[1], y[1]], color="#f2c94c",
                alpha=0.5)  # fmt: skip
        _circulation(ax, (x + y) / 2, 0.3, clockwise=w < 0, colour="#b8860b")
        _arrow(ax, x, _COLOURS["a"], "1st")
        _arrow(ax, y, _COLOURS["b"], "2nd")
        ax.set_xlim(-0.3, 3.6)
        ax.set_ylim(-0.3, 2.4)
        _letter(ax, letter)
        ax.set_xlabel(f"{name} = {w:+.2f} e12", fontsize=11)
    return fig


def reflection():
    """v and its mirror image −n v n in the line ⊥ n."""
    n = np.array([np.cos(np.radians(110)), np.sin(np.radians(110))])
    v = np.array([1.6, 0.9])
    image = reflect(v, n)[:2]
    fig, (ax,) = _figure(width=4.6)
    mirror = np.array([n[1], -n[0]]) * 2.2
    ax.plot([-mirror[0], mirror[0]], [-mirror[1], mirror[1]], color=_COLOURS["mirror"], lw=2,
            label="mirror (the line ⊥ n)")  # fmt: skip
    _arrow(ax, n * 0.8, "#555", "n")
    _arrow(ax, v, _COLOURS["v"], "v")
    _arrow(ax, image, _COLOURS["image"], "−n v n")
    ax.plot([v[0], image[0]], [v[1], image[1]], ":", color="#999")
    ax.set_xlim(-2.2, 2.2)
    ax.set_ylim(-1.6, 2.2)
    ax.legend(loc="lower left", fontsize=9, frameon=False)
    return fig


def two_reflections():
    """Reflect in n, then in m (β apart): a rotation by 2β, R = m n."""
    beta = np.radians(30)
    n = np.array([0.0, 1.0])
    m = np.array([-np.sin(beta), np.cos(beta)])
    v = np.array([1.7, 0.6])
    once = reflect(v, n)[:2]
    twice = reflect(once, m)[:2]
    fig, (ax,) = _figure(width=4.8, height=4.2)
    for normal, name, style in ((n, "mirror ⊥ n", "-"), (m, "mirror ⊥ m", "--")):
        d = np.array([normal[1], -normal[0]]) * 2.1
        ax.plot([-d[0], d[0]], [-d[1], d[1]], style, color=_COLOURS["mirror"], lw=1.5, label=name)
    _arrow(ax, v, _COLOURS["v"], "v")
    _arrow(ax, once, "#999", "−n v n")
    _arrow(ax, twice, _COLOURS["image"], "(mn) v (nm)")
    t = np.linspace(np.arctan2(v[1], v[0]), np.arctan2(twice[1], twice[0]), 40)
    ax.plot(0.7 * np.cos(t), 0.7 * np.sin(t), color=_COLOURS["image"], lw=1)
    ax.text(0.75, 0.75, "2β = 60°", color=_COLOURS["image"], fontsize=11)
    t = np.linspace(0, beta, 20)
    ax.plot(1.5 * np.cos(t + np.pi), 1.5 * np.sin(t + np.pi), color="#555", lw=1)
    ax.text(-1.95, -0.45, "β = 30°", color="#555", fontsize=11)
    ax.set_xlim(-2.2, 2.2)
    ax.set_ylim(-2.0, 2.2)
    ax.legend(loc="lower right", fontsize=9, frameon=False)
    return fig


def double_cover():
    """The rotor of a turn by α about z over 0 ≤ α ≤ 4π, against the rotation itself."""
    from ..rotor import from_axis_angle, to_matrix

    alpha = np.linspace(0, 4 * np.pi, 241)
    scalar, e12 = [], []
    cos_entry = []
    for a in alpha:
        R = from_axis_angle([0, 0, 1], a)
        scalar.append(R[()])
        e12.append(R[(1, 2)])
        cos_entry.append(to_matrix(R)[0, 0])
    fig, (ax,) = _figure(width=7.0, height=3.4)
    ax.set_aspect("auto")
    turns = alpha / (2 * np.pi)
    ax.plot(turns, scalar, lw=2, label="rotor: scalar part cos(α/2)")
    ax.plot(turns, e12, lw=2, label="rotor: e12 part −sin(α/2)")
    ax.plot(turns, cos_entry, "k:", lw=2, label="rotation matrix: entry cos α")
    ax.axvline(1, color="#aaa", lw=0.8)
    # The notes sit above the curves (all within ±1) and the legend below the axes.
    ax.text(1, 1.14, "one turn: R = −1 (the same rotation as +1)", ha="center", fontsize=9)
    ax.text(1.97, 1.14, "two turns: R = +1", ha="right", fontsize=9)
    ax.set_xlabel("turns α / 2π")
    ax.set_xlim(0, 2)
    ax.set_ylim(-1.1, 1.35)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3, fontsize=8, frameon=False)
    return fig


def _quaternion_name(q) -> str:
    k = int(np.argmax(np.abs(q)))
    return ("−" if q[k] < 0 else "") + ("1", "i", "j", "k")[k]


def isomorphism_tables():
    """Products of the images of i, j, k mapped back to ℍ: (a) the map, (b) the naive map.

    Green: equals the Hamilton product (ij = k, ...); red: its negative.
    """
    from ..isomorphism import ANTI_ISOMORPHISM, ISOMORPHISM, from_even, to_even
    from ..quaternion import multiply
    from ..rotor import layout

    lay = layout()
    units = np.eye(4)[1:]
    names = ("i", "j", "k")
    maps = ((ISOMORPHISM, "i ↦ −e23, j ↦ −e31, k ↦ −e12"),
            (ANTI_ISOMORPHISM, "naive: i ↦ e23, j ↦ e31, k ↦ e12"))  # fmt: skip
    fig, axes = _figure(2, width=3.8, height=3.6)
    for ax, letter, (table, title) in zip(axes, "ab", maps, strict=True):
        agree = np.zeros((3, 3))
        for r in range(3):
            for c in range(3):
                x, y = (lay.MultiVector(to_even(units[k], table)) for k in (r, c))
                back = from_even((x * y).value, table, name="product")
                agree[r, c] = 1.0 if np.allclose(back, multiply(units[r], units[c])) else -1.0
                ax.text(c, r, _quaternion_name(back), ha="center", va="center", fontsize=13)
        ax.imshow(agree, cmap="RdYlGn", vmin=-2, vmax=2)
        ax.set_xticks(range(3), names)
        ax.set_yticks(range(3), names)
        ax.set_xlabel("right factor")
        ax.set_ylabel("left factor")
        _letter(ax, letter)
        ax.set_title(title, fontsize=9, loc="right")
    return fig


def sandwich():
    """v ↦ R v R̃ for a turn by 120° about (1, 1, 1)/√3: the plane of R and the cone v sweeps."""
    from ..quaternion import from_axis_angle as q_axis_angle
    from ..quaternion import rotate
    from ..rotor import apply, from_axis_angle

    axis = np.ones(3) / np.sqrt(3)
    v = np.array([1.0, 0.0, 0.0])
    fig, (ax,) = _figure(width=4.8, height=4.6, projection="3d")
    path = np.array([apply(from_axis_angle(axis, a), v) for a in np.linspace(0, 2 * np.pi / 3, 40)])
    image = apply(from_axis_angle(axis, 2 * np.pi / 3), v)
    assert np.allclose(image, rotate(q_axis_angle(axis, 2 * np.pi / 3), v))
    u1 = np.cross(axis, [0, 0, 1.0])
    u1 /= np.linalg.norm(u1)
    u2 = np.cross(axis, u1)
    s = np.linspace(0, 2 * np.pi, 60)
    disk = np.outer(np.cos(s), u1) + np.outer(np.sin(s), u2)
    ax.plot_trisurf(*np.vstack([[0, 0, 0], disk * 1.1]).T, color="#f2c94c", alpha=0.3)
    for vec, colour, name in ((v, _COLOURS["v"], "v"), (image, _COLOURS["image"], "R v R̃"),
                              (axis, "#555", "u (⊥ plane of R)")):  # fmt: skip
        ax.quiver(0, 0, 0, *vec, color=colour, lw=2, arrow_length_ratio=0.12)
        ax.text(*(vec * 1.12), name, color=colour, fontsize=10)
    ax.plot(*path.T, ":", color=_COLOURS["image"])
    ax.set_box_aspect((1, 1, 1))
    ax.set_xticklabels([])
    ax.set_yticklabels([])
    ax.set_zticklabels([])
    for setter in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        setter(-1, 1)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    return fig


def rotor_kinematics():
    """Ṙ = ½ R Ω integrated (RK4) for a constant ω, against exp(−I ω t / 2)."""
    from ..rotor import from_rotation_vector
    from ..simulation import simulate

    w = np.array([0.0, 0.6, 1.2])
    tr = simulate((1.0, 1.0, 1.0), [1, 0, 0, 0], w, duration=6.0, step=0.25, paths=("rotor",))
    fig, (ax,) = _figure(width=7.0, height=3.4)
    ax.set_aspect("auto")
    t = np.linspace(0, 6, 200)
    exact = np.array([from_rotation_vector(w * s).value[[0, 4, 5, 6]] for s in t])
    labels = ("1", "e12", "e13", "e23")
    for k in range(4):
        (line,) = ax.plot(t, exact[:, k], lw=1.5, label=f"exp(−Iωt/2): {labels[k]}")
        ax.plot(tr.t, tr["rotor_blades"][:, k], "o", ms=4, color=line.get_color())
    ax.set_xlabel("t (s)")
    ax.set_title("lines: exact rotor; dots: RK4 on Ṙ = ½RΩ, h = 0.25 s", fontsize=10)
    ax.legend(loc="lower left", fontsize=8, frameon=False, ncols=2)
    return fig


def gyroscope():
    """A torque-free disk: its symmetry axis circles L (fixed in space) on the unit sphere."""
    from .. import quaternion as Q
    from ..shapes import disk
    from ..simulation import simulate

    moments = disk(2.0, 0.075)
    tr = simulate(moments, [1, 0, 0, 0], [2.5, 0.0, 2.0], duration=3.0, step=1e-3,
                  paths=("quaternion",))  # fmt: skip
    axis = Q.rotate(tr.q, [0.0, 0.0, 1.0])
    L = Q.rotate(tr.q, tr.w * np.array(moments))
    fig, (ax,) = _figure(width=4.8, height=4.6, projection="3d")
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 30), np.linspace(0, np.pi, 15))
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color="#ddd",
                      lw=0.5)  # fmt: skip
    ax.plot(*axis.T, color=_COLOURS["a"], lw=2, label="symmetry axis e3 (space)")
    l_dir = L[0] / np.linalg.norm(L[0])
    ax.quiver(0, 0, 0, *l_dir, color="#9467bd", lw=2, arrow_length_ratio=0.1, label="L")
    ax.set_box_aspect((1, 1, 1))
    ax.set_xticklabels([])
    ax.set_yticklabels([])
    ax.set_zticklabels([])
    ax.view_init(elev=20, azim=35)
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    return fig


# --------------------------------------------------------------- from rotors to motors (PGA)


def _pga():
    """e0, e1, e2, e3 of clifford's Cl(3,0,1), as ga_rotors.motor names them."""
    from ..motor import layout

    blades = layout().blades
    return blades["e0"], blades["e1"], blades["e2"], blades["e3"]


def _pga_point(x):
    from ..motor import point, to_multivector

    return to_multivector(point(np.asarray(x, dtype=float)), "point")


def _euclidean(P) -> np.ndarray:
    from ..motor import from_multivector, point_coordinates

    return point_coordinates(from_multivector(P, "point"))


def _mirror(ax, normal, offset, style, label):
    """The plane n·x = δ (n in the page) seen edge-on: a line on the page."""
    n = np.asarray(normal, dtype=float)
    foot, along = n * offset, np.array([-n[1], n[0]]) * 2.4
    ax.plot([foot[0] - along[0], foot[0] + along[0]], [foot[1] - along[1], foot[1] + along[1]],
            style, color=_COLOURS["mirror"], lw=1.5, label=label)  # fmt: skip


def two_mirrors():
    """Two reflections in planes of Cl(3,0,1): (a) meeting in a line, (b) parallel.

    The planes are vectors a, b (here ⊥ the page); the point moves by the sandwich of b a.
    Mirrors meeting at the angle β turn it by 2β about their line; mirrors δ apart slide it
    by 2δ: the translator b a = 1 − δ e01 = T(2δ e1).
    """
    from ..motor import apply, from_multivector, from_quaternion, from_translation
    from ..quaternion import from_axis_angle

    e0, e1, e2, _ = _pga()
    beta, delta = np.radians(30), 0.8
    cases = (
        (e2, -np.sin(beta) * e1 + np.cos(beta) * e2, [1.7, 0.6, 0.0],
         from_quaternion(from_axis_angle([0, 0, 1], 2 * beta)), "(a) turn by 2β = 60°"),
        (e1, e1 - delta * e0, [-1.4, 0.9, 0.0], from_translation([2 * delta, 0, 0]),
         "(b) slide by 2δ = 1.6"),
    )  # fmt: skip
    fig, axes = _figure(2, width=4.4, height=4.2)
    for ax, (a, b, v, expected, title), label_at in zip(axes, cases, ((0.08, 0.1), (-0.7, 0.3)),
                                                         strict=True):  # fmt: skip
        P = _pga_point(v)
        once = _euclidean(-a * P * a)
        twice = _euclidean((b * a) * P * ~(b * a))
        assert np.allclose(from_multivector(b * a), expected)
        assert np.allclose(twice, apply(expected, v))
        for plane, style, name in ((a, "-", "first mirror a"), (b, "--", "second mirror b")):
            n = np.array([plane[(1,)], plane[(2,)]])
            _mirror(ax, n / np.linalg.norm(n), -plane[(0,)] / np.linalg.norm(n), style, name)
        for start, end, colour in ((v, once, "#999"), (once, twice, _COLOURS["image"])):
            ax.annotate("", xy=end[:2], xytext=start[:2], arrowprops=dict(
                arrowstyle="-|>", color=colour, lw=2, shrinkA=4, shrinkB=4,
                connectionstyle="arc3,rad=0.25"))  # fmt: skip
        labelled = ((v, "P", _COLOURS["v"], (0.08, 0.1)), (once, "−aPa", "#777", (0.08, 0.1)),
                    (twice, "(ba) P (ab)", _COLOURS["image"], label_at))  # fmt: skip
        for x, name, colour, at in labelled:
            ax.plot(*x[:2], "o", color=colour, ms=6)
            ax.text(x[0] + at[0], x[1] + at[1], name, color=colour, fontsize=10)
        ax.set_xlim(-2.0, 2.2)
        ax.set_ylim(-1.6, 2.4)
        ax.set_title(title, fontsize=10, loc="left")
        ax.legend(loc="lower left", fontsize=8, frameon=False)
    axes[0].plot(0, 0, "k*", ms=12)
    axes[0].text(-1.2, 0.2, "their line (⊥ page)", fontsize=9)
    t = np.linspace(0, beta, 20)
    axes[0].plot(0.9 * np.cos(t), 0.9 * np.sin(t), color="#555", lw=1)
    axes[0].text(0.95, 0.15, "β", fontsize=11, color="#555")
    axes[1].annotate("", xy=(-1.4 + 2 * delta, -0.3), xytext=(-1.4, -0.3),
                     arrowprops=dict(arrowstyle="<->", color=_COLOURS["image"]))  # fmt: skip
    axes[1].text(-0.9, -0.6, "2δ", color=_COLOURS["image"], fontsize=11)
    axes[1].annotate("", xy=(delta, 1.9), xytext=(0.0, 1.9), arrowprops=dict(arrowstyle="<->"))
    axes[1].text(0.25, 2.0, "δ", fontsize=11)
    return fig


def translation_limit():
    """Turns by s/d about lines ⊥ the page ever farther away (d → ∞) become the slide by s."""
    from ..motor import apply, from_screw, from_translation, line

    s, start = 1.5, np.zeros(3)
    fig, (ax,) = _figure(width=5.6, height=4.4)
    sigma = np.linspace(0.0, 1.0, 50)
    for d, colour in zip((0.5, 1.0, 2.0, 8.0), ("#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd"),
                         strict=True):  # fmt: skip
        axis = line([0.0, d, 0.0], [0.0, 0.0, 1.0])
        path = apply(from_screw(axis, sigma * s / d), start)
        label = f"turn by s/d about the line at d = {d:g}"
        ax.plot(*path[:, :2].T, color=colour, lw=2, label=label)
        if d < 2.5:
            ax.plot(0.0, d, "x", color=colour, ms=9, mew=2)
    far = from_screw(line([0.0, 1e6, 0.0], [0.0, 0.0, 1.0]), s / 1e6)
    assert np.allclose(far, from_translation([s, 0.0, 0.0]), atol=1e-6)
    straight = apply(from_translation(np.outer(sigma, [s, 0.0, 0.0])), start)
    ax.plot(*straight[:, :2].T, "k--", lw=2, label="d → ∞: T = 1 − ½ s e01, the slide by s")
    ax.plot(0, 0, "ko", ms=5)
    ax.text(-0.32, -0.22, "start", fontsize=10)
    ax.set_xlim(-0.4, 2.0)
    ax.set_ylim(-0.4, 2.3)
    ax.set_xlabel("x")
    ax.set_ylabel("y  (×: where each line pierces the page)")
    ax.set_title("arc length s = 1.5 on every path", fontsize=10)
    ax.legend(loc="upper right", fontsize=8, frameon=False)
    return fig


def motor_sandwich():
    """One motor moves a plane, a line in it and a point on the line: M X M̃ keeps incidence."""
    from .. import motor
    from ..quaternion import from_axis_angle

    M = motor.from_pose(from_axis_angle([0.2, 0.3, 1.0], 1.4), [1.1, 0.5, 0.9])
    p, direction, normal = np.array([0.5, 0.1, 0.2]), np.array([1.0, 0.6, 0.0]), np.eye(3)[2]
    corners = p + np.array([[-0.6, -0.5, 0], [0.6, -0.5, 0], [0.6, 0.5, 0], [-0.6, 0.5, 0]])
    moved_p = motor.point_coordinates(motor.sandwich_point(M, motor.point(p)))
    on_line, moved_u = motor.line_coordinates(motor.sandwich_line(M, motor.line(p, direction)))
    moved_n, offset = motor.plane_coordinates(motor.sandwich_plane(M, motor.plane(normal, p[2])))
    # incidence survives the sandwich: the moved point is on the moved line and plane
    assert np.isclose(moved_n @ moved_p, offset)
    assert np.allclose(np.cross(moved_p - on_line, moved_u), 0.0, atol=1e-12)
    assert np.allclose(motor.apply(M, corners) @ moved_n, offset)
    fig, (ax,) = _figure(width=5.2, height=4.8, projection="3d")
    u = direction / np.linalg.norm(direction)
    before = (corners, p, u, "#bbb", "X")
    after = (motor.apply(M, corners), moved_p, moved_u, None, "M X M̃")
    for patch, q, w, colour, tag in (before, after):
        ax.add_collection3d(_polygon3d(patch, colour or "#f2c94c"))
        ax.plot(*np.array([q - 0.7 * w, q + 0.7 * w]).T, color=colour or _COLOURS["a"], lw=2.5)
        ax.plot(*q, "o", color=colour or _COLOURS["b"], ms=7)
        ax.text(q[0], q[1], q[2] + 0.15, tag, color="#333" if colour else _COLOURS["b"])
    ax.plot([], [], color=_COLOURS["a"], lw=2.5, label="a line in the plane")
    ax.plot([], [], "o", color=_COLOURS["b"], label="a point on the line")
    ax.plot([], [], "s", color="#f2c94c", label="a plane (grey: before M)")
    ax.set_box_aspect((1, 1, 0.8))
    ax.set(xlim=(-0.3, 2.0), ylim=(-0.6, 1.7), zlim=(0.0, 1.6), xlabel="x", ylabel="y", zlabel="z",
           xticklabels=[], yticklabels=[], zticklabels=[])  # fmt: skip
    ax.view_init(elev=24, azim=-60)
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    return fig


def _polygon3d(corners, colour):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    return Poly3DCollection([corners], facecolor=colour, edgecolor="#555", alpha=0.35)


def chasles_pole():
    """A planar rigid motion is a turn about one line ⊥ the page (Chasles): exp(s log M)."""
    from ..motor import apply, exp, from_pose, line_coordinates, log, to_screw
    from ..quaternion import from_axis_angle

    M = from_pose(from_axis_angle([0.0, 0.0, 1.0], np.radians(100)), [2.4, 0.9, 0.0])
    axis, angle, pitch = to_screw(M)
    pole, u = line_coordinates(axis)
    assert np.isclose(pitch, 0.0, atol=1e-12) and np.allclose(np.abs(u), [0, 0, 1])
    body = np.array([[0.2, -0.3, 0], [1.4, -0.3, 0], [1.4, 0.1, 0], [0.6, 0.1, 0], [0.6, 0.6, 0],
                     [0.2, 0.6, 0], [0.2, -0.3, 0]])  # fmt: skip
    s = np.linspace(0.0, 1.0, 41)
    along = exp(s[:, None] * log(M))
    fig, (ax,) = _figure(width=5.2, height=4.8)
    for k, colour, name in ((0, _COLOURS["v"], "start"), (-1, _COLOURS["image"], "M (end)")):
        ax.fill(*apply(along[k], body)[:, :2].T, color=colour, alpha=0.5, label=name)
    for k in (10, 20, 30):
        ax.plot(*apply(along[k], body)[:, :2].T, color="#aaa", lw=1)
    for corner in body[[0, 1, 4]]:
        track = apply(along, corner)[:, :2]
        assert np.allclose(
            np.linalg.norm(track - pole[:2], axis=1), np.linalg.norm(corner[:2] - pole[:2])
        )  # circles about the pole
        ax.plot(*track.T, ":", color="#555", lw=1)
        ax.plot([pole[0], corner[0]], [pole[1], corner[1]], color="#ddd", lw=0.8, zorder=0)
    ax.plot(*pole[:2], "k*", ms=14, label="the screw axis (⊥ page)")
    ax.set_title(f"turn by {np.degrees(angle):.0f}° about the axis, pitch 0", fontsize=10)
    ax.set_xlim(-0.6, 2.9)
    ax.set_ylim(-0.9, 2.7)
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    return fig


def rolling_wheel():
    """A wheel rolling along x: every point moves as if turning about the contact line.

    The velocities are the commutator ½(B P − P B) of the space velocity line B with each
    point P (computed in clifford), checked against v + ω × x from
    :func:`ga_rotors.motor.velocities`.
    """
    from .. import motor

    r, speed = 1.0, 1.0
    M = motor.from_translation([0.0, 0.0, r])  # the centre at height r
    body = motor.velocity_line([0.0, speed / r, 0.0], [speed, 0.0, 0.0])
    B = motor.sandwich_line(M, body)  # seen from space
    contact, _ = motor.line_coordinates(B)
    w, v = motor.velocities(B)
    B_mv = motor.to_multivector(np.r_[0.0, B, 0.0])
    fig, (ax,) = _figure(width=5.6, height=4.0)
    t = np.linspace(0, 2 * np.pi, 100)
    ax.plot(r * np.sin(t), r + r * np.cos(t), color="#555", lw=2)
    ax.axhline(0.0, color="#8b5a2b", lw=2)
    scale = 0.45
    for angle in np.radians(np.arange(0, 360, 45)):
        x = np.array([r * np.sin(angle), 0.0, r + r * np.cos(angle)])
        P = _pga_point(x)
        c = motor.from_multivector(0.5 * (B_mv * P - P * B_mv), "point")  # an ideal point
        velocity = np.array([-c[2], c[1], -c[0]])
        assert abs(c[3]) < 1e-12 and np.allclose(velocity, v + np.cross(w, x))
        ax.plot([contact[0], x[0]], [contact[2], x[2]], color="#ddd", lw=0.8, zorder=0)
        if np.linalg.norm(velocity) > 1e-9:
            _arrow(ax, scale * velocity[[0, 2]], _COLOURS["b"], "", origin=x[[0, 2]])
    _arrow(ax, scale * (v + np.cross(w, [0, 0, r]))[[0, 2]], _COLOURS["b"], "", origin=(0, r))
    ax.plot(contact[0], contact[2], "k*", ms=14, label="the velocity line (⊥ page): the contact")
    ax.plot([], [], color=_COLOURS["b"], lw=2, label="velocity ½(BP − PB) of each point")
    ax.set_xlim(-1.7, 2.3)
    ax.set_ylim(-0.4, 2.7)
    ax.set_xlabel("x")
    ax.set_ylabel("z")
    ax.legend(loc="upper right", fontsize=8, frameon=False)
    return fig


#: name -> function drawing it (a matplotlib Figure), in the learning path's order.
PICTURES = {
    "geometric_product": geometric_product,
    "bivector_orientation": bivector_orientation,
    "reflection": reflection,
    "two_reflections": two_reflections,
    "double_cover": double_cover,
    "isomorphism_tables": isomorphism_tables,
    "sandwich": sandwich,
    "rotor_kinematics": rotor_kinematics,
    "gyroscope": gyroscope,
    "two_mirrors": two_mirrors,
    "translation_limit": translation_limit,
    "motor_sandwich": motor_sandwich,
    "chasles_pole": chasles_pole,
    "rolling_wheel": rolling_wheel,
}


def draw_all(out_dir, fmt: str = "png", dpi: int = 150, names=None) -> list[Path]:
    """Draw the learning path's pictures into ``out_dir`` (atomically, one file each).

    Examples
    --------
    >>> import tempfile
    >>> [p.name for p in draw_all(tempfile.mkdtemp(), names=["reflection"])]
    ['reflection.png']
    """
    import matplotlib.pyplot as plt

    from ..errors import InputError
    from ..files import atomic_write
    from ..paper.figures import FIGURE_FORMATS, encode_figure

    if fmt not in FIGURE_FORMATS:
        raise InputError(f"fmt: expected {', '.join(FIGURE_FORMATS)}, got {fmt!r}")
    out = Path(out_dir)
    written = []
    for name in names or PICTURES:
        fig = PICTURES[name]()
        fig.tight_layout()
        data = encode_figure(fig, fmt, f"ga_rotors learning path: {name}", dpi=dpi)
        written.append(atomic_write(out / f"{name}.{fmt}", lambda fh, b=data: fh.write(b)))
        plt.close(fig)
    return written


if __name__ == "__main__":  # pragma: no cover
    for path in draw_all(sys.argv[1] if len(sys.argv) > 1 else "docs/learn/images"):
        print(path)
