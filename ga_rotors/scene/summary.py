"""The closing summary of a scene run: invariants, cross-check, exact solution, physics checks.

:func:`report` measures one simulated scene:

* **invariants** that the declared effects conserve, as the largest drift over the run
  relative to a stated scale: torque-free, the kinetic energy, |L| and the space-frame L;
  with gravity alone, the total energy (kinetic + m g·r about the pivot) and the vertical
  component of L (and for a symmetric top with its centre of mass on the axis, the body
  component L₃); with a constant space torque τ alone, L − τ t. Damping, body torques and
  user torques conserve nothing this simple (the exact solution, where one exists, is the
  check);
* the **cross-check** of the orientation paths (:func:`ga_rotors.crosscheck.cross_check`);
* the **exact solution** (:attr:`ga_rotors.scene.Scene.exact_solution`): each path's largest
  geodesic error and the largest |ω − ω_exact|;
* **physics readouts** measured from the samples and compared with their exact values:
  the heavy top's nutation bounds, nutation period and mean precession rate; the asymmetric
  top's times between flips of the middle-axis rate against 2K(m)/λ; the damped top's |L|.

Readouts are measured between samples with cubic Hermite interpolation, which uses the
sampled values *and* their exact derivatives (from the state), so its error is O(Δ⁴) in
the output step Δ rather than the O(Δ²) of linear interpolation.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..trajectory import Trajectory
from .model import Scene

__all__ = ["Report", "extrema", "hermite_at", "invariant_series", "report", "zero_crossings"]


@dataclass
class Report:
    """A run's summary: ``lines`` to print and ``values`` (name -> number) to test.

    :func:`report` fills one from a simulated scene; ``str`` joins the lines.

    Examples
    --------
    >>> rep = Report("demo", ["scene demo: rk4", "  energy drift 1e-15"], {"energy": 1e-15})
    >>> print(rep)
    scene demo: rk4
      energy drift 1e-15
    >>> rep.values["energy"]
    1e-15
    """

    scene: str
    lines: list[str] = field(default_factory=list)
    values: dict[str, float] = field(default_factory=dict)

    def __str__(self) -> str:
        return "\n".join(self.lines)


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


def invariant_series(scene: Scene, tr: Trajectory, q: np.ndarray) -> list[tuple]:
    """The conserved quantities of ``scene``'s effects along ``tr``.

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
    types = [e["type"] for e in scene.data["effects"]]
    L_body = body.momentum(w)
    L_space = Q.rotate(q, L_body)
    L0 = float(np.linalg.norm(L_space[0]))

    def dev(values, scale):
        d = np.abs(values - values[0])
        d = np.linalg.norm(d, axis=-1) if d.ndim > 1 else d
        return d / scale if scale > 0 else d

    rows = []
    if not types:
        e = body.energy(w)
        rows += [
            ("energy", "energy", dev(e, e[0]), "relative to E₀"),
            ("momentum_norm", "|L|", dev(np.linalg.norm(L_space, axis=-1), L0),
             "relative to |L₀|"),
            ("space_momentum", "space-frame L", dev(L_space, L0), "relative to |L₀|"),
        ]  # fmt: skip
    elif types == ["gravity"]:
        weight, r = scene.gravity
        total = body.energy(w) - Q.rotate(q, r) @ weight
        scale = float(body.energy(w[0]) + np.linalg.norm(weight) * np.linalg.norm(r))
        up = -weight / np.linalg.norm(weight)
        rows += [
            ("total_energy", "total energy", dev(total, scale), "relative to E_kin,0 + m|g||r|"),
            ("vertical_momentum", "vertical L", dev(L_space @ up, L0), "relative to |L₀|"),
        ]
        if scene.exact == "heavy_top":
            rows.append(("axial_momentum", "body L₃", dev(L_body[:, 2], L0), "relative to |L₀|"))
    elif types == ["space_torque"]:
        tau = np.array(scene.data["effects"][0]["torque"])
        free = L_space - (t - t[0])[:, None] * tau
        scale = L0 + float(np.linalg.norm(tau)) * float(t[-1] - t[0])
        rows.append(("space_momentum", "L − τ t", dev(free, scale), "relative to |L₀| + |τ| T"))
    return rows


def _invariants(scene: Scene, tr: Trajectory, q: np.ndarray, rep: Report) -> None:
    rows = invariant_series(scene, tr, q)
    if not rows:
        types = ", ".join(e["type"] for e in scene.data["effects"])
        rep.lines.append(f"  none simple under {types}")
        return
    for key, label, deviation, scale in rows:
        value = float(deviation.max())
        rep.values[f"drift_{key}"] = value
        rep.lines.append(f"  {label:<22} max drift {value:9.2e}  ({scale})")


def _paths(tr: Trajectory, rep: Report) -> None:
    from .. import paths as _paths

    for path, info in tr.meta["paths"].items():
        status = "complete" if info["complete"] else f"stopped at t = {info['ended_at']:g} s"
        line = f"  {path:<11} {status}"
        spec = _paths.get(path)
        if spec.on_unit_sphere:
            drift = float(np.abs(np.linalg.norm(tr[spec.array], axis=-1) - 1.0).max())
            rep.values[f"norm_drift_{path}"] = drift
            line += f", max | |{path}| − 1 | = {drift:.1e}"
        watch = info.get("watch")
        if watch and watch.get("unresolved_steps"):
            line += (
                f"; {watch['unresolved_steps']} steps did not resolve the Euler rates (from t = "
                f"{watch['first_unresolved']:g} s; min |sin θ| {watch['min_abs_sin_theta']:.1e})"
            )
        rep.lines.append(line)


def _heavy_top(scene: Scene, exact, tr: Trajectory, q: np.ndarray, rep: Report) -> None:
    from .. import quaternion as Q

    nut = exact.model.nutation()
    w = tr.w
    t = tr.t[: w.shape[0]]
    frame_q = Q.multiply(exact.frame, q)  # the model's space frame: gravity along −z
    axis = Q.rotate(frame_q, np.array([0.0, 0.0, 1.0]))
    w_space = Q.rotate(frame_q, w)
    u, du = axis[:, 2], np.cross(w_space, axis)[:, 2]  # cos θ and its exact rate
    when, value, is_max = extrema(t, u, du)
    if when.size < 3:
        rep.lines.append("  nutation: fewer than 3 extrema of θ in the run; not measured")
        return
    theta = np.arccos(np.clip(value, -1.0, 1.0))
    low = ~is_max  # minima of cos θ are the maxima of θ
    measured = {"theta_min": float(theta[is_max].min()), "theta_max": float(theta[low].max())}
    peaks = when[low]
    if peaks.size >= 2:
        measured["period"] = float((peaks[-1] - peaks[0]) / (peaks.size - 1))
        # ψ is the azimuth of the axis; with ω_s = ψ̇ ẑ + θ̇ n̂ + φ̇ e₃ (ZYZ),
        # ψ̇ = (ω_s·ẑ − cos θ ω_s·e₃) / sin²θ exactly, so ψ too is Hermite-interpolated.
        psi = np.unwrap(np.arctan2(axis[:, 1], axis[:, 0]))
        dpsi = (w_space[:, 2] - u * np.einsum("ij,ij->i", w_space, axis)) / (1.0 - u * u)
        ends = hermite_at(t, psi, dpsi, peaks[[0, -1]])
        measured["mean_precession"] = float((ends[1] - ends[0]) / (peaks[-1] - peaks[0]))
    exact_values = {
        "theta_min": nut.theta_min,
        "theta_max": nut.theta_max,
        "period": nut.period,
        "mean_precession": nut.mean_precession,
    }
    units = {"theta_min": "°", "theta_max": "°", "period": " s", "mean_precession": " rad/s"}
    for key, value in measured.items():
        ref = exact_values[key]
        shown, ref_shown = (np.degrees(value), np.degrees(ref)) if "theta" in key else (value, ref)
        rep.values[f"{key}"] = value
        rep.values[f"{key}_exact"] = ref
        rep.values[f"{key}_error"] = abs(value - ref)
        rep.lines.append(
            f"  {key.replace('_', ' '):<22} {shown:.10g}{units[key]} (exact {ref_shown:.10g}"
            f"{units[key]}, difference {abs(value - ref):.1e})"
        )


def _flips(scene: Scene, exact, tr: Trajectory, rep: Report) -> None:
    from .._kernels import free_euler_rates

    model = exact.model
    w = tr.w
    t = tr.t[: w.shape[0]]
    b = sorted(range(3), key=lambda k: scene.body.moments[k])[1]
    rates = free_euler_rates.py_func(scene.body.moments, (w[:, 0], w[:, 1], w[:, 2]))
    flips = zero_crossings(t, w[:, b], rates[b])
    if flips.size < 2 or not np.isfinite(model.flip_period):
        rep.lines.append(f"  flips of ω{b + 1}: {flips.size} in the run; period not measured")
        return
    gaps = np.diff(flips)
    rep.values["flip_period"] = float(gaps.mean())
    rep.values["flip_period_exact"] = model.flip_period
    rep.values["flip_period_error"] = float(np.abs(gaps - model.flip_period).max())
    rep.lines.append(
        f"  flips of ω{b + 1}: {flips.size}, mean interval {gaps.mean():.10g} s "
        f"(exact 2K(m)/λ = {model.flip_period:.10g} s, m = {model.m:.6g}; largest difference "
        f"{rep.values['flip_period_error']:.1e} s)"
    )


def _damped(scene: Scene, exact, tr: Trajectory, rep: Report) -> None:
    w = tr.w
    t = tr.t[: w.shape[0]]
    measured = np.linalg.norm(scene.body.momentum(w[-1]))
    ref = float(exact.model.momentum_norm([t[-1] - t[0]])[0])
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
        f"|L₀| = {np.linalg.norm(scene.body.momentum(w[0])):.6g}"
    )


def _exact(scene: Scene, tr: Trajectory, q: np.ndarray, rep: Report) -> None:
    from .. import quaternion as Q
    from ..errors import GaRotorsError

    if scene.exact is None:
        rep.lines.append(f"exact solution: none ({scene.exact_reason})")
        return
    try:
        exact = scene.exact_solution
        t = tr.t[: tr.w.shape[0]]
        w_err = np.linalg.norm(tr.w - exact.angular_velocity(t), axis=-1)
        errors = {}
        if exact.has_orientation:
            for path in scene.paths:
                qp = Q.normalize(tr.quaternions(path))
                errors[path] = float(exact.orientation_error(tr.t[: qp.shape[0]], qp).max())
    except GaRotorsError as exc:
        rep.lines.append(f"exact solution ({scene.exact}): not evaluated: {exc}")
        return
    rep.lines.append(f"exact solution ({scene.exact}):")
    for path, value in errors.items():
        rep.values[f"error_{path}"] = value
        rep.lines.append(f"  {path:<11} max orientation error {value:.2e} rad")
    rep.values["omega_error"] = float(w_err.max())
    rep.lines.append(f"  {'ω':<11} max |ω − ω_exact| {w_err.max():.2e} rad/s")
    if scene.exact == "heavy_top":
        _heavy_top(scene, exact, tr, q, rep)
    elif scene.exact == "asymmetric_top":
        _flips(scene, exact, tr, rep)
    elif scene.exact == "damped_symmetric_top":
        _damped(scene, exact, tr, rep)


def report(scene: Scene, trajectory: Trajectory) -> Report:
    """Measure a simulated scene (see the module docstring).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> from ga_rotors.scene import run_scene
    >>> scene = load_scene("spinning_disk").replace({"time.duration": 1.0})
    >>> rep = report(scene, run_scene(scene))
    >>> rep.values["error_rotor"] < 1e-9, rep.values["rotor_vs_quaternion"] < 1e-13
    (True, True)
    """
    from .. import quaternion as Q
    from ..crosscheck import cross_check

    rep = Report(scene.name)
    tr = trajectory
    method = tr.meta["integrator"]
    torques = ", ".join(tr.meta["torques"]) or "none (torque-free)"
    spec = scene.data["integrator"]
    how = (
        f"adaptive at tolerance {spec['tolerance']:g}, sampled every {tr.meta['step']:g} s"
        if "tolerance" in spec
        else f"{tr.meta['steps']:,} steps of {tr.meta['step']:g} s"
    )
    rep.lines.append(f"scene {scene.name}: {method}, {how}; torques: {torques}")
    rep.lines.append("paths (geodesic angles below are between rotations: states normalised):")
    _paths(tr, rep)
    q = Q.normalize(tr.quaternions())[: tr.w.shape[0]]
    rep.lines.append(f"invariants ({tr.meta['primary']} path):")
    _invariants(scene, tr, q, rep)
    if len(scene.paths) > 1:
        rep.lines.append("cross-check (largest geodesic angle between paths):")
        for c in cross_check(tr):
            rep.values[f"{c.paths[0]}_vs_{c.paths[1]}"] = c.max_angle
            rep.lines.append(f"  {c}")
    _exact(scene, tr, q, rep)
    stopped = {p: i for p, i in tr.meta["paths"].items() if not i["complete"]}
    if stopped:  # said first: every figure above covers only the steps taken
        t_end = float(tr.t[0]) + tr.meta["steps"] * tr.meta["step"] if tr.t.size else 0.0
        where = ", ".join(f"{p} at t = {i['ended_at']:g} s" for p, i in stopped.items())
        rep.lines.insert(
            0,
            f"INCOMPLETE: the run stopped before t = {t_end:g} s ({where}); the figures "
            "below cover only the steps taken",
        )
        rep.values["incomplete"] = 1.0
    return rep
