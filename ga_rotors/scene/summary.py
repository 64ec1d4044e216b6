"""The closing summary of a scene run: invariants, cross-check, exact solution, physics checks.

:func:`report` measures one simulated scene:

* **invariants** that the declared effects conserve, as the largest drift over the run
  relative to a stated scale: torque-free, the kinetic energy, |L| and the space-frame L;
  with gravity alone, the total energy (kinetic + m g·r about the pivot) and the vertical
  component of L (and for a symmetric top with its centre of mass on the axis, the body
  component L₃); with a constant space torque τ alone, L − τ t. Damping, body torques and
  user torques conserve nothing this simple;
* the **work–energy balance** of every torqued run, E − E₀ = ∫τ·ω dt, which holds for
  any torque: its largest residual, with the estimated share of the quadrature of the
  samples' power (:class:`WorkBalance`);
* the **cross-check** of the orientation paths (:func:`ga_rotors.crosscheck.cross_check`);
* the **exact solution** (:attr:`ga_rotors.scene.Scene.exact_solution`): each path's largest
  geodesic error and the largest |ω − ω_exact|;
* which of these **accuracy** figures the run has, and which it cannot have and why (no
  exact solution known, nothing conserved, one path);
* **physics readouts** measured from the samples and compared with their exact values:
  the heavy top's nutation bounds, nutation period and mean precession rate; the asymmetric
  top's times between flips of the middle-axis rate against 2K(m)/λ; the damped top's |L|.

Readouts are measured between samples with cubic Hermite interpolation, which uses the
sampled values *and* their exact derivatives (from the state), so its error is O(Δ⁴) in
the output step Δ rather than the O(Δ²) of linear interpolation.
"""

from __future__ import annotations

import math

import numpy as np

from .._jit import jit
from .._kernels import gravity_potential, kinetic_energy, qmul, qrotate, qunit
from .._validate import UNIT_TOLERANCE
from ..effects import listed
from ..trajectory import Trajectory
from .model import Scene
from .reports import Report, mark_incomplete

__all__ = [
    "Report",
    "RunSummary",
    "extrema",
    "hermite_at",
    "invariant_series",
    "report",
    "status_report",
    "summary_for",
    "zero_crossings",
]


# ---------------------------------------------------------------------------- Hermite


def _hermite(y0, y1, d0, d1, h):
    """Coefficients (c0, c1, c2, c3) in s ∈ [0, 1] of the cubic through (y, h·dy) at 0, 1."""
    m0, m1 = h * d0, h * d1
    return y0, m0, 3 * (y1 - y0) - 2 * m0 - m1, 2 * (y0 - y1) + m0 + m1


def zero_crossings(t, y, dy) -> np.ndarray:
    """Times where ``y`` changes sign, located on the cubic Hermite interpolant.

    Parameters
    ----------
    t, y, dy : array_like (n,)
        Sample times, values and exact derivatives.

    Examples
    --------
    >>> t = np.linspace(0.0, 10.0, 41)
    >>> zero_crossings(t, np.sin(t), np.cos(t)) / np.pi
    array([0.99999996, 2.00000005, 2.99999991])
    """
    t, y, dy = (np.asarray(a, dtype=np.float64) for a in (t, y, dy))
    i = np.nonzero(np.signbit(y[:-1]) != np.signbit(y[1:]))[0]
    i = i[y[i] != 0.0]
    h = t[i + 1] - t[i]
    c0, c1, c2, c3 = _hermite(y[i], y[i + 1], dy[i], dy[i + 1], h)
    s = y[i] / (y[i] - y[i + 1])  # the secant's root, then Newton on the cubic
    for _ in range(8):
        p = c0 + s * (c1 + s * (c2 + s * c3))
        dp = c1 + s * (2 * c2 + 3 * s * c3)
        s = np.clip(s - np.where(dp != 0, p / np.where(dp != 0, dp, 1.0), 0.0), 0.0, 1.0)
    return t[i] + s * h


def hermite_at(t, y, dy, times) -> np.ndarray:
    """Values at ``times`` of the cubic Hermite interpolant of samples ``y`` with exact
    derivatives ``dy`` (error O(Δ⁴) for sample spacing Δ).

    Examples
    --------
    >>> t = np.linspace(0.0, 3.0, 31)
    >>> float(hermite_at(t, np.sin(t), np.cos(t), [1.234])[0] - np.sin(1.234)) < 1e-7
    True
    """
    t, y, dy = (np.asarray(a, dtype=np.float64) for a in (t, y, dy))
    times = np.asarray(times, dtype=np.float64)
    i = np.clip(np.searchsorted(t, times) - 1, 0, t.size - 2)
    h = t[i + 1] - t[i]
    s = (times - t[i]) / h
    c0, c1, c2, c3 = _hermite(y[i], y[i + 1], dy[i], dy[i + 1], h)
    return c0 + s * (c1 + s * (c2 + s * c3))


def extrema(t, y, dy) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Interior local extrema of ``y`` on its cubic Hermite interpolant.

    Returns
    -------
    times, values : ndarray
    is_max : ndarray of bool

    Examples
    --------
    >>> t = np.linspace(0.0, 7.0, 36)
    >>> when, value, is_max = extrema(t, np.cos(t), -np.sin(t))
    >>> (when / np.pi).round(7).tolist(), value.round(8).tolist(), is_max.tolist()
    ([1.0, 2.0], [-1.0, 1.0], [False, True])
    """
    t, y, dy = (np.asarray(a, dtype=np.float64) for a in (t, y, dy))
    i = np.nonzero(np.signbit(dy[:-1]) != np.signbit(dy[1:]))[0]
    i = i[dy[i] != 0.0]
    h = t[i + 1] - t[i]
    c0, c1, c2, c3 = _hermite(y[i], y[i + 1], dy[i], dy[i + 1], h)
    # p'(s) = c1 + 2 c2 s + 3 c3 s² = 0: the root in [0, 1] (p' changes sign there).
    a, b, c = 3 * c3, 2 * c2, c1
    disc = np.sqrt(np.maximum(b * b - 4 * a * c, 0.0))
    q = -0.5 * (b + np.copysign(disc, b))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.where(a != 0, q / a, np.inf)
        r2 = np.where(q != 0, c / q, -c / np.where(b != 0, b, 1.0))
    s = np.where((r1 >= 0) & (r1 <= 1), r1, r2)
    s = np.clip(s, 0.0, 1.0)
    return t[i] + s * h, c0 + s * (c1 + s * (c2 + s * c3)), dy[i] > 0


# ---------------------------------------------------------------------------- measuring


def invariant_series(scene: Scene, tr: Trajectory, q: np.ndarray, start=None) -> list[tuple]:
    """The conserved quantities of ``scene``'s effects along ``tr``.

    Parameters
    ----------
    start : tuple (t, w, q, t_end), optional
        The run's first sample (time, ω, normalised orientation) and last time, when
        ``tr`` is a later piece of the run (:class:`RunSummary`); by default ``tr``'s own
        first sample and last time.

    Returns
    -------
    list of (key, label, deviation, scale)
        ``deviation`` (n,) is |value(t) − value(0)| (vector norm for vectors) divided by
        the scale described by the string ``scale``. Empty when nothing simple is conserved.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> scene = load_scene("heavy_top").replace({"time.duration": 0.1})
    >>> tr = run_scene(scene)
    >>> [row[0] for row in invariant_series(scene, tr, tr.quaternions())]
    ['total_energy', 'vertical_momentum', 'axial_momentum']
    """
    from .. import quaternion as Q

    body, w = scene.body, tr.w
    t = tr.t[: w.shape[0]]
    if start is None:
        start = (tr.t[0], w[0], q[0], tr.t[-1])
    t_first, w_first, q_first, t_end = start
    w_first, q_first = np.asarray(w_first)[None, :], np.asarray(q_first)[None, :]
    types = [e["type"] for e in scene.data["effects"]]
    L_first = Q.rotate(q_first, body.momentum(w_first))
    L0 = float(np.linalg.norm(L_first[0]))
    if types != ["gravity"]:  # (gravity's invariants are measured in one compiled pass)
        L_space = Q.rotate(q, body.momentum(w))

    def dev(values, first, scale):
        d = np.abs(values - first[0])
        d = np.linalg.norm(d, axis=-1) if d.ndim > 1 else d
        return d / scale if scale > 0 else d

    rows = []
    if not types:
        e, e0 = body.energy(w), np.atleast_1d(body.energy(w_first))
        norm, norm0 = np.linalg.norm(L_space, axis=-1), np.linalg.norm(L_first, axis=-1)
        rows += [
            ("energy", "energy", dev(e, e0, e0[0]), "relative to E₀"),
            ("momentum_norm", "|L|", dev(norm, norm0, L0), "relative to |L₀|"),
            ("space_momentum", "space-frame L", dev(L_space, L_first, L0), "relative to |L₀|"),
        ]
    elif types == ["gravity"]:
        weight, r = scene.gravity  # r in the principal frame, where the samples go
        scale = float(body.energy(w_first[0]) + np.linalg.norm(weight) * np.linalg.norm(r))
        up = -weight / np.linalg.norm(weight)
        states = (*_principal(body, q, w), *_principal(body, q_first, w_first))
        total, vertical, axial = _gravity_deviations(body.moments, *states, weight, r, up,
                                                     scale, L0)  # fmt: skip
        rows += [
            ("total_energy", "total energy", total, "relative to E_kin,0 + m|g||r|"),
            ("vertical_momentum", "vertical L", vertical, "relative to |L₀|"),
        ]
        if scene.exact == "heavy_top":
            rows.append(("axial_momentum", "body L₃", axial, "relative to |L₀|"))
    elif types == ["space_torque"]:
        tau = np.array(scene.data["effects"][0]["torque"])
        free = L_space - (t - t_first)[:, None] * tau
        scale = L0 + float(np.linalg.norm(tau)) * float(t_end - t_first)
        rows.append(("space_momentum", "L − τ t", dev(free, L_first, scale),
                     "relative to |L₀| + |τ| T"))  # fmt: skip
    return rows


@jit
def _gravity_loop(q, w, moments, r, weight, up, first, scale, l0, tol, out):
    """Per row: the total energy ½ Σ Iₖ ωₖ² − (q r q*)·(m g) (the kernels of the run's
    energy columns), the vertical Lₛ·up and the body L₃, as |value − first| over its
    scale (``first`` None: the values themselves) — the operations of body.energy,
    body.momentum, quaternion.rotate and the dot products, in their order. Returns
    whether every row is finite."""
    bad = 0.0
    i0, i1, i2 = moments
    for n in range(out.shape[1]):
        unit = qunit((q[n, 0], q[n, 1], q[n, 2], q[n, 3]), tol)
        w0, w1, w2 = w[n, 0], w[n, 1], w[n, 2]
        body_l = (w0 * i0, w1 * i1, w2 * i2)
        space_l = qrotate(unit, body_l)
        total = kinetic_energy((w0, w1, w2), (i0, i1, i2)) + gravity_potential(unit, r, weight)
        vertical = (space_l[0] * up[0] + space_l[1] * up[1]) + space_l[2] * up[2]
        values = (total, vertical, body_l[2])
        for k in range(3):
            if first is None:
                out[k, n] = values[k]
            else:
                d = abs(values[k] - first[k])
                out[k, n] = d / scale[k] if scale[k] > 0 else d
            bad += out[k, n] * 0.0
    return bad == 0.0


def _principal(body, q, w):
    """Orientations and body rates of the scene's body frame in the principal frame the
    body's moments are diagonal in (as given when they are the same)."""
    return (q, w) if body.is_principal else body.to_principal(q, w)


def _gravity_deviations(moments, q, w, q_first, w_first, weight, r, up, scale, l0):
    """total energy, vertical L and body L₃ deviations (each (n,)) for :func:`invariant_series`
    from one compiled pass (:func:`_gravity_loop`) over principal-frame samples; the first
    sample through the same pass."""
    from .. import quaternion as Q
    from ..body import RigidBody

    body = RigidBody(moments)
    args = (np.asarray(body.moments, dtype=np.float64), *(np.asarray(a, dtype=np.float64)
            for a in (r, weight, up)))  # fmt: skip
    first = np.empty((3, 1))
    q, w = (np.ascontiguousarray(a, dtype=np.float64) for a in (q, w))
    ok = _gravity_loop(q_first, w_first, *args, None, None, l0, UNIT_TOLERANCE, first)
    out = np.empty((3, w.shape[0]))
    scales = np.array([scale, l0, l0])
    ok = ok and _gravity_loop(q, w, *args, first[:, 0].copy(), scales, l0, UNIT_TOLERANCE, out)
    if not ok:  # what body.energy, body.momentum and Q.rotate say of these values
        body.energy(w), body.momentum(w), Q.rotate(q, r)
    return out[0], out[1], out[2]


@jit
def _largest_norm_drift(a):
    """max over rows of | |a[n]| − 1 | (|a[n]| as numpy's norm sums its squares); nan if a
    row is, −1 for no rows."""
    best = -1.0
    for n in range(a.shape[0]):
        square = 0.0
        for k in range(a.shape[1]):
            square += a[n, k] * a[n, k]
        drift = abs(math.sqrt(square) - 1.0)
        if drift > best:
            best = drift
        elif not drift <= best:
            return math.nan
    return best


@jit
def _unwrap_step(raw, prev_raw, total):
    """numpy's unwrap of the step from ``prev_raw`` to ``raw`` (np.mod as numpy computes
    it: fmod, then the divisor's sign), its correction added to the running ``total``."""
    two_pi = 2.0 * math.pi
    dd = raw - prev_raw
    mod = np.fmod(dd + math.pi, two_pi)
    if mod != 0.0:
        if mod < 0.0:
            mod += two_pi
    else:
        mod = 0.0
    ddmod = mod - math.pi
    if ddmod == -math.pi and dd > 0.0:
        ddmod = math.pi
    return total + ((ddmod - dd) if not abs(dd) < math.pi else 0.0)


@jit
def _azimuth_loop(x, y, prev_raw, total, wanted, out):
    """The azimuth atan2(y, x) of rows 1…, unwrapped as numpy's unwrap does it (its
    corrections in one running sum from ``total``; row 0's raw azimuth is ``prev_raw``),
    at the rows ``wanted`` (increasing, each ≥ 1) into ``out``; returns (the last row's
    raw azimuth, the running sum).

    Two rows on the same side of the x axis (y of one sign bit) have their azimuths both
    in [0, π] or both in [−π, −0]: the step between them is at most π and its correction
    exactly 0 (at π too: numpy's mod maps it back to π). So only a step across the axis
    needs its two arctangents, and only the rows read need theirs.
    """
    k = 0
    for n in range(1, x.shape[0]):
        if np.signbit(y[n]) != np.signbit(y[n - 1]):
            raw = math.atan2(y[n], x[n])
            total = _unwrap_step(raw, math.atan2(y[n - 1], x[n - 1]), total)
        if k < wanted.shape[0] and wanted[k] == n:
            out[k] = math.atan2(y[n], x[n]) + total
            k += 1
    last = x.shape[0] - 1
    return (math.atan2(y[last], x[last]) if last > 0 else prev_raw), total


@jit
def _axis_readouts_loop(frame, q, w, out, tol):
    for n in range(q.shape[0]):
        fq = qunit(qmul(frame, (q[n, 0], q[n, 1], q[n, 2], q[n, 3])), tol)
        axis = qrotate(fq, (0.0, 0.0, 1.0))
        ws = qrotate(fq, (w[n, 0], w[n, 1], w[n, 2]))
        u = axis[2]
        out[0, n] = u
        out[1, n] = ws[0] * axis[1] - ws[1] * axis[0]  # (ω_s × axis)_z
        out[2, n], out[3, n] = axis[0], axis[1]
        # ψ is the azimuth of the axis; with ω_s = ψ̇ ẑ + θ̇ n̂ + φ̇ e₃ (ZYZ),
        # ψ̇ = (ω_s·ẑ − cos θ ω_s·e₃) / sin²θ exactly, so ψ too is Hermite-interpolated.
        along = ws[0] * axis[0] + ws[1] * axis[1] + ws[2] * axis[2]
        out[4, n] = (ws[2] - u * along) / (1.0 - u * u)


def _axis_readouts(frame, q, w):
    """The heavy top's symmetry axis in the frame ``frame`` ⊗ q (gravity along −z) for unit
    orientations ``q`` (n, 4) and body rates ``w`` (n, 3): cos θ, its exact rate
    (ω_s × axis)_z, the axis's x and y (its azimuth is atan2(y, x)) and ψ̇, each (n,)."""
    out = np.empty((5, q.shape[0]))
    q, w = (np.ascontiguousarray(a, dtype=np.float64) for a in (q, w))
    _axis_readouts_loop(np.asarray(frame, dtype=np.float64), q, w, out, UNIT_TOLERANCE)
    return out[0], out[1], out[2], out[3], out[4]


# ---------------------------------------------------------------------------- work and energy


def interval_weights(nodes, a: float, b: float) -> np.ndarray:
    """Weights w with Σ wᵢ f(nodesᵢ) = ∫ₐᵇ p(t) dt, p the polynomial through the samples
    of f at ``nodes`` (any spacing; exact for polynomials of their degree).

    Examples
    --------
    >>> (interval_weights([0.0, 1.0, 2.0, 3.0], 1.0, 2.0) * 24).round(12).tolist()
    [-1.0, 13.0, 13.0, -1.0]
    >>> float(interval_weights([0.0, 0.5, 1.0], 0.0, 1.0) @ np.array([0.0, 0.25, 1.0]))
    0.3333333333333333
    """
    x = (np.asarray(nodes, dtype=np.float64) - a) / (b - a)
    out = np.empty(x.size)
    for i in range(x.size):
        others = np.delete(x, i)
        basis = np.polynomial.Polynomial.fromroots(others) / np.prod(x[i] - others)
        whole = basis.integ()
        out[i] = whole(1.0) - whole(0.0)
    return out * (b - a)


def _running(total: float, terms: np.ndarray) -> np.ndarray:
    """total + terms[0], + terms[1], …, added one at a time: the same sums whatever the
    pieces a run comes in."""
    return np.cumsum(np.concatenate([[total], terms]))[1:]


class WorkBalance:
    """The work–energy balance E(t) − E₀ = W(t) = ∫₀ᵗ τ·ω dt along a run, taken piece by
    piece (the same numbers, bit for bit, whatever the pieces): it holds for every torque
    (dE/dt = τ·ω from Euler's equations), so its residual is an accuracy figure of any
    torqued run, exact solution or not.

    W is integrated from the samples' power by a fourth-order rule (the cubic through the
    four samples around each output interval, one-sided at the ends), so the residual
    measures the integration, not the sampling, as long as the quadrature's own error is
    below it: that error is estimated by the same integral with the cubic through the
    samples shifted by one (:attr:`quadrature`, an overestimate by about 2.7×), and stated.
    Both are relative to E₀ + ∫|τ·ω| dt.

    Examples
    --------
    E = t⁴/4 with P = t³: the balance holds to the quadrature's rounding.

    >>> t = np.linspace(0.0, 2.0, 41)
    >>> b = WorkBalance()
    >>> for part in (slice(0, 17), slice(17, 41)):
    ...     b.add(t[part], t[part] ** 3, 1.0 + t[part] ** 4 / 4)
    >>> b.finish()
    >>> b.residual < 1e-15, b.quadrature < 1e-15
    (True, True)
    """

    def __init__(self):
        self.t = self.p = self.e = np.empty(0)  # the samples from global index ``base`` on
        self.base = 0
        self.next = 0  # the next interval to integrate starts at sample ``next``
        self.work = 0.0  # W at sample ``next``
        self.e0 = None
        self.largest = 0.0  # max |E − E₀ − W|
        self.checked = 0.0  # Σ |rule − check|
        self.magnitude = 0.0  # ∫ |P| dt
        self.finished = False

    def add(self, t, power, energy) -> None:
        """Samples of the run, in order: times, power τ·ω and kinetic energy."""
        t, power, energy = (np.asarray(a, dtype=np.float64) for a in (t, power, energy))
        if self.e0 is None and energy.size:
            self.e0 = float(energy[0])
        self.t = np.concatenate([self.t, t])
        self.p = np.concatenate([self.p, power])
        self.e = np.concatenate([self.e, energy])
        self._integrate(final=False)

    def finish(self) -> None:
        """The run has ended: integrate what waited for samples after it."""
        if not self.finished:
            self.finished = True
            self._integrate(final=True)

    @property
    def scale(self) -> float:
        return abs(self.e0 or 0.0) + self.magnitude

    @property
    def residual(self) -> float:
        """Largest |E − E₀ − W| over the run so far, relative to :attr:`scale`."""
        return self.largest / self.scale if self.scale > 0 else self.largest

    @property
    def quadrature(self) -> float:
        """The estimated error of W from the quadrature, relative to :attr:`scale`."""
        return self.checked / self.scale if self.scale > 0 else self.checked

    def _integrate(self, final: bool) -> None:
        """Integrate the intervals whose rules have their samples: a centred cubic needs
        two samples beyond its interval, the first intervals the first five samples; at
        the end, what is left takes the cubics that fit."""
        last = self.base + self.t.size - 1  # the last sample's global index
        if last < 1 or (not final and last < 4):
            return
        end = last if final else last - 1  # intervals next … end − 1
        j = self.next
        if j < min(2, end):
            self._take(*self._one_by_one(j, min(2, end), last))
            j = self.next
        if j < min(end, last - 1):
            self._take(*self._centred(j, min(end, last - 1) - 1))
            j = self.next
        if j < end:
            self._take(*self._one_by_one(j, end, last))
        keep = max(self.next - 3, self.base)
        cut = keep - self.base
        self.t, self.p, self.e, self.base = self.t[cut:], self.p[cut:], self.e[cut:], keep

    def _at(self, j0: int, j1: int):
        return slice(j0 - self.base, j1 - self.base)

    def _centred(self, lo: int, hi: int):
        """Intervals lo…hi by the centred rule, each checked by the one behind."""
        t, p = self.t, self.p
        j = np.arange(lo, hi + 1) - self.base
        h = t[j + 1] - t[j]
        # written out, not a matrix product: each interval's value is then the same
        # operations whatever the batch it is in (a streamed run's pieces)
        a, b, c, d, e = p[j - 2], p[j - 1], p[j], p[j + 1], p[j + 2]
        values = h * ((13.0 * (c + d) - (b + e)) / 24.0)
        checks = h * ((a - 5.0 * b + 19.0 * c + 9.0 * d) / 24.0)
        spacing = np.stack([t[j - 1] - t[j - 2], t[j] - t[j - 1], h, t[j + 2] - t[j + 1]])
        uneven = np.flatnonzero(np.abs(spacing - h).max(axis=0) > 1e-9 * h)
        for k in uneven:  # the rule's spacing is not the samples' (a short last step)
            values[k], checks[k] = self._general(lo + k, lo + k - 1, lo + k - 2)
        return lo, values, checks

    def _one_by_one(self, j0: int, j1: int, last: int):
        """Intervals j0 … j1 − 1 near the ends, by the cubics that fit in the samples."""
        values, checks = [], []
        for j in range(j0, j1):
            start = min(max(j - 1, 0), max(last - 3, 0))
            other = next((c for c in (start - 1, start + 1) if 0 <= c and c + 3 <= last), None)
            values_j, check_j = self._general(j, start, other)
            values.append(values_j)
            checks.append(check_j)
        return j0, np.array(values), np.array(checks)

    def _general(self, j: int, start: int, other: int | None):
        t, p = self.t, self.p
        last = self.base + t.size - 1
        a, b = t[j - self.base], t[j + 1 - self.base]
        nodes = self._at(start, min(start + 3, last) + 1)
        value = interval_weights(t[nodes], a, b) @ p[nodes]
        if other is None:  # too few samples for a second cubic: the trapezoid checks
            return value, 0.5 * (b - a) * (p[j - self.base] + p[j + 1 - self.base])
        nodes = self._at(other, other + 4)
        return value, interval_weights(t[nodes], a, b) @ p[nodes]

    def _take(self, j0: int, values: np.ndarray, checks: np.ndarray) -> None:
        if j0 != self.next or not values.size:
            return
        n = values.size
        work = _running(self.work, values)
        gained = self.e[self._at(j0 + 1, j0 + n + 1)] - self.e0
        self.largest = max(self.largest, float(np.max(np.abs(gained - work))))
        self.checked = float(_running(self.checked, np.abs(values - checks))[-1])
        at = self._at(j0, j0 + n + 1)
        power = np.abs(self.p[at])
        self.magnitude = float(_running(self.magnitude, 0.5 * np.diff(self.t[at]) * (
            power[1:] + power[:-1]))[-1])  # fmt: skip
        self.work = float(work[-1])
        self.next = j0 + n


class RunSummary:
    """The summary of a run handed over piece by piece (:func:`report` is its one-piece use).

    What :func:`report` measures is accumulated as the pieces arrive: largest drifts,
    errors and path disagreements as running maxima; the physics readouts' extrema and
    zero crossings found on each piece with the previous piece's last sample in front, so
    none is lost at a boundary. It keeps a few numbers per piece (and one per extremum or
    flip), never the samples, and the report of a run in pieces is the report of the run
    whole.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene, run_pieces
    >>> scene = load_scene("spinning_disk").replace({"time.duration": 1.0})
    >>> summary = RunSummary(scene)
    >>> for piece in run_pieces(scene, chunk_steps=300):
    ...     summary.add(piece)
    >>> rep = summary.report()
    >>> rep.values["error_rotor"] < 1e-9, rep.values["rotor_vs_quaternion"] < 1e-13
    (True, True)
    """

    def __init__(self, scene: Scene):
        self.scene = scene
        self.meta: dict = {}
        self.first = None  # (t, w, q, t_end): the run's first sample and last time
        self.last = None  # the previous piece's last (t, w, q), in front of the next piece
        self.maxima: dict[str, float] = {}
        self.labels: dict[str, tuple[str, str]] = {}
        self.cross: dict[tuple, list] = {}
        self.exact_failure: str | None = None
        self.found: dict[str, list] = {"when": [], "value": [], "is_max": [], "flips": []}
        self.psi = None  # the heavy top's azimuth: (last raw, carried correction)
        self.peak_psi: list[float] = []  # ψ at the first and at the latest peak of θ
        self.final = None  # the last (t, w)
        self.balance = self.balance_failure = None
        self.terms = ()
        if scene.data["effects"]:
            from ..errors import GaRotorsError

            try:  # built here, where the run's opt-in to user code holds
                self.terms = scene.torques()
                self.balance = WorkBalance()
            except GaRotorsError as exc:
                self.balance_failure = f"not evaluated: {exc}"

    def _max(self, key: str, values) -> None:
        if values is not None and np.size(values):
            value = float(np.max(values))
            old = self.maxima.get(key)
            self.maxima[key] = value if old is None or value > old else old

    def add(self, piece: Trajectory) -> None:
        """Take the next piece of the run (the first holds sample 0)."""
        from .. import paths as _paths
        from .. import quaternion as Q

        self.meta = piece.meta
        for path in piece.paths:
            spec = _paths.get(path)
            if spec.on_unit_sphere:
                drift = _largest_norm_drift(np.ascontiguousarray(piece[spec.array], dtype=float))
                self._max(f"norm_drift_{path}", None if drift < 0.0 else drift)
        w = piece.w
        n = w.shape[0]
        if n == 0:
            return
        t = piece.t[:n]
        # each path's orientations normalised once, for the invariants, the cross-check
        # and the exact errors alike
        unit = {path: Q.normalize(piece.quaternions(path)) for path in piece.paths}
        q = unit[piece.paths[0]][:n]
        if self.first is None:
            t_end = float(piece.t[0]) + piece.meta["steps"] * piece.meta["step"]
            self.first = (float(t[0]), w[0].copy(), q[0].copy(), t_end)
        for key, label, deviation, scale in invariant_series(self.scene, piece, q, self.first):
            self.labels[key] = (label, scale)
            self._max(f"drift_{key}", deviation)
        if self.balance is not None:
            self._balance(t, q, w)
        if len(self.scene.paths) > 1:
            self._cross(piece, unit)
        if self.scene.exact is not None and self.exact_failure is None:
            self._exact(piece, t, w, q, unit)
        self.last = (t[-1:].copy(), w[-1:].copy(), q[-1:].copy())
        self.final = (float(t[-1]), w[-1].copy())

    def _balance(self, t, q, w) -> None:
        """Add the samples' power τ·ω (the run's own torque terms, in the principal frame
        their kernels act in) and kinetic energy to the work–energy balance."""
        from ..effects import torque_power
        from ..errors import GaRotorsError

        body = self.scene.body
        try:
            energy = body.energy(w)
            power = torque_power(self.terms, t, *_principal(body, q, w))
        except GaRotorsError as exc:
            self.balance, self.balance_failure = None, f"not evaluated: {exc}"
            return
        if not (np.all(np.isfinite(power)) and np.all(np.isfinite(energy))):
            self.balance = None
            self.balance_failure = "not evaluated: the power τ·ω is not finite at some sample"
            return
        self.balance.add(t, power, energy)

    def _cross(self, piece: Trajectory, unit: dict) -> None:
        from .. import paths as _paths
        from ..crosscheck import cross_check

        # a path that stopped has no rows in the pieces after: the others still compare
        ended = [_paths.get(p).array for p in piece.paths if piece[_paths.get(p).array].size == 0]
        if len(piece.paths) - len(ended) < 2:
            return
        if ended:
            keep = [n for n in piece.names if n not in ended]
            piece = Trajectory({n: piece[n] for n in keep}, piece.components, piece.meta)
        for c in cross_check(piece, unit):
            old = self.cross.setdefault(c.paths, [c.max_angle, c.at_time, 0])
            if c.max_angle > old[0]:
                old[0], old[1] = c.max_angle, c.at_time
            old[2] += c.samples

    def _exact(self, piece: Trajectory, t, w, q, unit: dict) -> None:
        from .. import quaternion as Q
        from ..errors import GaRotorsError

        scene = self.scene
        try:
            exact = scene.exact_solution
            # the run's own quantities, where it has them; the rest from one evaluation of
            # the reference at the piece's times (a path that stopped early has fewer rows)
            need_w = "omega_error" not in piece
            quats = {}
            if exact.has_orientation:
                for path in scene.paths:
                    if f"error_{path}" not in piece:
                        quats[path] = (
                            unit[path] if path in unit else Q.normalize(piece.quaternions(path))
                        )
            dw, dq = exact.largest_errors(piece.t, w if need_w else None, quats)
            self._max("omega_error", dw if need_w else piece["omega_error"])
            if exact.has_orientation:
                for path in scene.paths:
                    error = dq[path] if path in quats else piece[f"error_{path}"]
                    self._max(f"error_{path}", error)
        except GaRotorsError as exc:
            self.exact_failure = f"exact solution ({scene.exact}): not evaluated: {exc}"
            return
        if self.last is not None:  # the previous piece's last sample goes in front
            t = np.concatenate([self.last[0], t])
            w = np.concatenate([self.last[1], w])
            q = np.concatenate([self.last[2], q])
        if scene.exact == "heavy_top":
            self._heavy_top(exact, t, w, q)
        elif scene.exact == "asymmetric_top":
            from .._kernels import free_euler_rates

            b = sorted(range(3), key=lambda k: scene.body.moments[k])[1]
            _, w = _principal(scene.body, None, w)  # the middle principal axis's rate
            rates = free_euler_rates.py_func(scene.body.moments, (w[:, 0], w[:, 1], w[:, 2]))
            self.found["flips"].append(zero_crossings(t, w[:, b], rates[b]))

    def _heavy_top(self, exact, t, w, q) -> None:
        # the model's space frame (gravity along −z): cos θ, its exact rate, the axis's
        # azimuth (as x, y) and ψ̇, in one compiled pass; the symmetry axis is principal z
        q, w = _principal(self.scene.body, q, w)
        u, du, x, y, dpsi = _axis_readouts(exact.frame, q, w)
        when, value, is_max = extrema(t, u, du)
        for key, found in (("when", when), ("value", value), ("is_max", is_max)):
            self.found[key].append(found)
        peaks = when[~is_max]
        self._psi_at_peaks(t, x, y, dpsi, peaks[[0, -1]] if peaks.size else peaks)

    def _psi_at_peaks(self, t, x, y, dpsi, ends) -> None:
        """ψ, unwrapped along the run, Hermite-interpolated at the times ``ends`` (this
        piece's first and last peak of θ, or none): it is read at the two samples around
        each only. Row 0 is the run's first sample (its raw azimuth, nothing carried) or
        the previous piece's last (raw azimuth + the correction carried)."""
        if self.psi is None:
            self.psi = (math.atan2(y[0], x[0]), 0.0)
        rows = np.clip(np.searchsorted(t, ends) - 1, 0, t.size - 2)
        around = np.unique(np.concatenate([rows, rows + 1]))
        later = around > 0
        psi = np.full(around.size, self.psi[0] + self.psi[1])  # row 0's, where it is read
        found = np.empty(int(later.sum()))
        self.psi = _azimuth_loop(x, y, *self.psi, around[later], found)
        psi[later] = found
        if ends.size:
            at = [
                hermite_at(t[[i, i + 1]], psi[np.searchsorted(around, [i, i + 1])],
                           dpsi[[i, i + 1]], [end])[0]
                for i, end in zip(rows, ends, strict=True)
            ]  # fmt: skip
            first = self.peak_psi[0] if self.peak_psi else float(at[0])
            self.peak_psi = [first, float(at[-1])]

    # ------------------------------------------------------------------ the report

    def report(self) -> Report:
        """The :class:`Report` of the pieces taken so far (all of them: the run's)."""
        scene, meta = self.scene, self.meta
        rep = Report(scene.name)
        torques = listed(meta["torques"]) or "none (torque-free)"
        spec = scene.data["integrator"]
        how = (
            f"adaptive at tolerance {spec['tolerance']:g}, sampled every {meta['step']:g} s"
            if "tolerance" in spec
            else f"{meta['steps']:,} steps of {meta['step']:g} s"
        )
        rep.lines.append(f"scene {scene.name}: {meta['integrator']}, {how}; torques: {torques}")
        rep.lines.append("paths (geodesic angles below are between rotations: states normalised):")
        self._paths(rep)
        rep.lines.append(f"invariants ({meta['primary']} path):")
        self._invariants(rep)
        self._balance_line(rep)
        if len(scene.paths) > 1:
            from ..crosscheck import PathComparison

            rep.lines.append("cross-check (largest geodesic angle between paths):")
            for pair, (angle, at, samples) in self.cross.items():
                rep.values[f"{pair[0]}_vs_{pair[1]}"] = angle
                rep.lines.append(f"  {PathComparison(pair, angle, at, samples)}")
        self._exact_lines(rep)
        self._accuracy_line(rep)
        mark_incomplete(rep, meta, self.first[3] if self.first is not None else 0.0)
        return rep

    def _balance_line(self, rep: Report) -> None:
        """The work–energy balance of a torqued run, with its residual and the share of
        it the sampling's quadrature may account for."""
        if not self.scene.data["effects"]:
            return
        label = "work–energy balance"
        if self.balance is None:
            rep.lines.append(f"  {label:<22} {self.balance_failure}")
            return
        self.balance.finish()
        if self.balance.next == 0:
            rep.lines.append(f"  {label:<22} not measured: fewer than two samples")
            return
        residual, quadrature = self.balance.residual, self.balance.quadrature
        rep.values["balance_residual"] = residual
        rep.values["balance_quadrature"] = quadrature
        limited = ": the output step limits it" if residual <= quadrature else ""
        rep.lines.append(
            f"  {label:<22} max drift {residual:9.2e}  (|E − E₀ − ∫τ·ω dt| relative to "
            f"E₀ + ∫|τ·ω| dt; quadrature ≲ {quadrature:.1e}{limited})"
        )

    def _accuracy_line(self, rep: Report) -> None:
        """Which accuracy figures this run has, and which it cannot have and why."""
        scene = self.scene
        types = listed(e["type"] for e in scene.data["effects"])
        has, lacks = [], []
        if self.labels:
            has.append("the drift of its conserved quantities")
        else:
            lacks.append(f"a conserved quantity (none simple under {types})")
        if "balance_residual" in rep.values:
            has.append("the work–energy balance")
        elif scene.data["effects"]:
            lacks.append(f"the work–energy balance ({self.balance_failure or 'no samples'})")
        if "omega_error" in rep.values:
            has.append("the error against the exact solution")
        elif scene.exact is None:
            lacks.append(f"an exact error ({scene.exact_reason})")
        else:
            lacks.append("an exact error (the reference was not evaluated)")
        if len(scene.paths) > 1:
            has.append("the paths' cross-check")
        else:
            lacks.append("a cross-check (one path; integrator.paths can list more)")
        line = "accuracy: measured by " + (", ".join(has) if has else "nothing")
        if lacks:
            line += "; not available: " + "; ".join(lacks)
        rep.lines.append(line)

    def _paths(self, rep: Report) -> None:
        for path, info in self.meta["paths"].items():
            status = "complete" if info["complete"] else f"stopped at t = {info['ended_at']:g} s"
            line = f"  {path:<11} {status}"
            drift = self.maxima.get(f"norm_drift_{path}")
            if drift is not None:
                rep.values[f"norm_drift_{path}"] = drift
                line += f", max | |{path}| − 1 | = {drift:.1e}"
            watch = info.get("watch")
            if watch and watch.get("unresolved_steps"):
                line += (
                    f"; {watch['unresolved_steps']} steps did not resolve the Euler rates (from "
                    f"t = {watch['first_unresolved']:g} s; min |sin θ| "
                    f"{watch['min_abs_sin_theta']:.1e})"
                )
            rep.lines.append(line)

    def _invariants(self, rep: Report) -> None:
        if not self.labels:
            types = listed(e["type"] for e in self.scene.data["effects"])
            rep.lines.append(f"  none simple under {types}")
            return
        for key, (label, scale) in self.labels.items():
            value = self.maxima[f"drift_{key}"]
            rep.values[f"drift_{key}"] = value
            rep.lines.append(f"  {label:<22} max drift {value:9.2e}  ({scale})")

    def _exact_lines(self, rep: Report) -> None:
        scene = self.scene
        if scene.exact is None:
            rep.lines.append(f"exact solution: none ({scene.exact_reason})")
            return
        if self.exact_failure is not None:
            rep.lines.append(self.exact_failure)
            return
        if "omega_error" not in self.maxima:  # no sample at all
            return
        exact = scene.exact_solution
        # the reference's rounding bound grows with time: stated, so a long run's errors
        # are read against what the reference itself resolves
        bound = exact.bound(np.linspace(self.first[0], self.final[0], 1000))
        if bound is None:
            rep.lines.append(f"exact solution ({scene.exact}):")
        else:
            rep.values["exact_bound"] = bound
            rep.lines.append(
                f"exact solution ({scene.exact}; the reference's own rounding bound "
                f"{bound:.1e} rad):"
            )
        for path in scene.paths:
            key = f"error_{path}"
            if key in self.maxima:
                rep.values[key] = self.maxima[key]
                rep.lines.append(f"  {path:<11} max orientation error {self.maxima[key]:.2e} rad")
        rep.values["omega_error"] = self.maxima["omega_error"]
        rep.lines.append(f"  {'ω':<11} max |ω − ω_exact| {self.maxima['omega_error']:.2e} rad/s")
        if scene.exact == "heavy_top":
            self._heavy_top_lines(exact, rep)
        elif scene.exact == "asymmetric_top":
            self._flip_lines(exact, rep)
        elif scene.exact == "damped_symmetric_top":
            self._damped_lines(exact, rep)

    def _heavy_top_lines(self, exact, rep: Report) -> None:
        nut = exact.model.nutation()
        when = np.concatenate(self.found["when"])
        value = np.concatenate(self.found["value"])
        is_max = np.concatenate(self.found["is_max"]).astype(bool)
        if when.size < 3:
            rep.lines.append("  nutation: fewer than 3 extrema of θ in the run; not measured")
            return
        theta = np.arccos(np.clip(value, -1.0, 1.0))
        low = ~is_max  # minima of cos θ are the maxima of θ
        measured = {"theta_min": float(theta[is_max].min()), "theta_max": float(theta[low].max())}
        peaks = when[low]
        if peaks.size >= 2:
            measured["period"] = float((peaks[-1] - peaks[0]) / (peaks.size - 1))
            start, end = self.peak_psi
            measured["mean_precession"] = float((end - start) / (peaks[-1] - peaks[0]))
        exact_values = {
            "theta_min": nut.theta_min,
            "theta_max": nut.theta_max,
            "period": nut.period,
            "mean_precession": nut.mean_precession,
        }
        units = {"theta_min": "°", "theta_max": "°", "period": " s", "mean_precession": " rad/s"}
        for key, value in measured.items():
            ref = exact_values[key]
            shown, ref_shown = (
                (np.degrees(value), np.degrees(ref)) if "theta" in key else (value, ref)
            )
            rep.values[f"{key}"] = value
            rep.values[f"{key}_exact"] = ref
            rep.values[f"{key}_error"] = abs(value - ref)
            rep.lines.append(
                f"  {key.replace('_', ' '):<22} {shown:.10g}{units[key]} (exact {ref_shown:.10g}"
                f"{units[key]}, difference {abs(value - ref):.1e})"
            )

    def _flip_lines(self, exact, rep: Report) -> None:
        model = exact.model
        b = sorted(range(3), key=lambda k: self.scene.body.moments[k])[1]
        flips = np.concatenate(self.found["flips"]) if self.found["flips"] else np.empty(0)
        axis = f"ω{b + 1}" if self.scene.body.is_principal else f"principal ω{b + 1}"
        if flips.size < 2 or not np.isfinite(model.flip_period):
            rep.lines.append(f"  flips of {axis}: {flips.size} in the run; period not measured")
            return
        gaps = np.diff(flips)
        rep.values["flip_period"] = float(gaps.mean())
        rep.values["flip_period_exact"] = model.flip_period
        rep.values["flip_period_error"] = float(np.abs(gaps - model.flip_period).max())
        rep.lines.append(
            f"  flips of {axis}: {flips.size}, mean interval {gaps.mean():.10g} s "
            f"(exact 2K(m)/λ = {model.flip_period:.10g} s, m = {model.m:.6g}; largest "
            f"difference {rep.values['flip_period_error']:.1e} s)"
        )

    def _damped_lines(self, exact, rep: Report) -> None:
        t_last, w_last = self.final
        body = self.scene.body
        measured = np.linalg.norm(body.momentum(w_last))
        ref = float(exact.model.momentum_norm([t_last - self.first[0]])[0])
        rep.values["momentum_final"] = float(measured)
        rep.values["momentum_final_exact"] = ref
        # a body at rest stays at rest: |L| = 0, and a relative difference means nothing
        diff = (
            f"relative difference {abs(measured - ref) / ref:.1e}"
            if ref > 0
            else f"difference {abs(measured - ref):.1e}"
        )
        rep.lines.append(
            f"  |L| at the end {measured:.10g} (exact {ref:.10g}, {diff}); "
            f"|L₀| = {np.linalg.norm(body.momentum(self.first[1])):.6g}"
        )


def status_report(scene: Scene, meta: dict) -> Report:
    """What a run with ``output.summary`` off reports: only whether it completed (the
    INCOMPLETE line of :meth:`RunSummary.report`), nothing measured, so such a run pays
    for no summary.

    Parameters
    ----------
    meta : dict
        The run's ``Trajectory.meta`` (its paths' status, steps and step).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene, run_scene
    >>> scene = load_scene("spinning_disk").replace({"time.duration": 0.1})
    >>> status_report(scene, run_scene(scene).meta).values
    {}
    """
    rep = Report(scene.name)
    t_end = scene.data["time"]["start"] + meta["steps"] * meta["step"]
    mark_incomplete(rep, meta, t_end)
    return rep


def summary_for(scene: Scene):
    """The summary that measures ``scene``'s run: a :class:`RunSummary` for a rotation
    about a fixed point, a :class:`~ga_rotors.scene.motion_summary.MotionSummary` for a
    body moving through space; both take the run piece by piece (``add``) and give its
    :class:`Report` (``report``).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> type(summary_for(load_scene("heavy_top"))).__name__
    'RunSummary'
    >>> type(summary_for(load_scene("thrown_racket"))).__name__
    'MotionSummary'
    """
    if scene.moves:
        from .motion_summary import MotionSummary

        return MotionSummary(scene)
    return RunSummary(scene)


def report(scene: Scene, trajectory: Trajectory) -> Report:
    """Measure a simulated scene (see the module docstring); :class:`RunSummary` of the
    whole trajectory as one piece.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> scene = load_scene("spinning_disk").replace({"time.duration": 1.0})
    >>> rep = report(scene, run_scene(scene))
    >>> rep.values["error_rotor"] < 1e-9, rep.values["rotor_vs_quaternion"] < 1e-13
    (True, True)
    """
    summary = summary_for(scene)
    summary.add(trajectory)
    return summary.report()
