"""The closing summary of a scene whose body moves through space: its accuracy, stated.

:class:`MotionSummary` measures a whole rigid motion (a scene with ``initial.position``,
``initial.velocity`` or ``[[forces]]``) as :class:`~ga_rotors.scene.summary.RunSummary`
measures a rotation:

* the **exact reference**, where the scene is one (:mod:`ga_rotors.scene.motion`: free
  flight, a spring at the centre of mass): each path's largest orientation error (rad)
  and position error of the body-frame origin (m);
* the **balances** of energy, linear momentum and angular momentum
  (:func:`ga_rotors.balances.balances`, on the primary path's samples): a conserved
  quantity's drift, or the change less the integral of its source (the work of the
  forces, their impulse, their moment), each relative to its scale;
* the **cross-check** of the motor and quaternion paths (largest angle and distance);
* which of these figures the run has, and which it cannot have and why.

Distances are also given relative to the run's length scale, the largest distance of the
body-frame origin from the space origin over the run (an orbit's radius, a throw's
reach), which is what "agree to 1e-8 of the length scale" means.

The balances integrate their sources over the whole run, so the primary path's samples
(t, ω, its state, position and velocity: at most 18 numbers a sample,
:data:`ga_rotors.scene.budget.MOTION_SUMMARY_COLUMNS`, which the run's memory budget
counts) are kept until the report; the rest is accumulated piece by piece. The balances
evaluate each declared term's kernel once per sample from Python (a few microseconds
each): about a second per term and 10⁵ samples.
"""

from __future__ import annotations

import numpy as np

from ..effects import listed
from ..trajectory import Trajectory
from . import motion
from .model import Scene
from .reports import Report, mark_incomplete

__all__ = ["MotionSummary"]


class MotionSummary:
    """The summary of a motion scene's run, handed over piece by piece.

    Examples
    --------
    >>> from ga_rotors.scene import load_scene, run_pieces
    >>> scene = load_scene("thrown_racket").replace({"time.duration": 0.2})
    >>> summary = MotionSummary(scene)
    >>> for piece in run_pieces(scene, chunk_steps=150):
    ...     summary.add(piece)
    >>> rep = summary.report()
    >>> rep.values["error_motor"] < 1e-9, rep.values["position_error_motor"] < 1e-9
    (True, True)
    >>> rep.values["balance_energy"] < 1e-10, rep.values["motor_vs_quaternion"] < 1e-12
    (True, True)
    """

    def __init__(self, scene: Scene):
        from ..errors import GaRotorsError

        self.scene = scene
        self.meta: dict = {}
        self.kept: dict[str, list] = {}
        self.maxima: dict[str, float] = {}
        self.cross: dict[tuple, list] = {}
        self.exact_failure: str | None = None
        self.terms = self.failure = None
        self.reach = 0.0
        try:  # built here, where the run's opt-in to user code holds
            self.terms = (scene.forces(), scene.torques())
        except GaRotorsError as exc:
            self.failure = f"not evaluated: {exc}"
        self.reference = None
        if scene.exact is not None:
            try:
                self.reference = scene.exact_solution.reference
            except GaRotorsError as exc:
                self.exact_failure = f"exact solution ({scene.exact}): not evaluated: {exc}"

    def _max(self, key: str, value: float) -> None:
        old = self.maxima.get(key)
        self.maxima[key] = value if old is None or value > old else old

    def add(self, piece: Trajectory) -> None:
        """Take the next piece of the run (the first holds sample 0)."""
        from .. import paths as _paths
        from .. import quaternion as Q

        self.meta = piece.meta
        n = piece.w.shape[0]
        if n == 0:
            return
        primary = _paths.resolve(piece.paths[0], True).array
        for name in ("t", "w", "position", "velocity", primary):
            self.kept.setdefault(name, []).append(np.array(piece[name][:n]))
        self.reach = max(self.reach, float(np.linalg.norm(piece["position"], axis=1).max()))
        live = [p for p in piece.paths if piece.positions(p).shape[0]]
        for path in live:  # how far each path's rotation part drifted off the unit sphere
            norms = np.linalg.norm(piece.quaternions(path), axis=1)
            self._max(f"norm_drift_{path}", float(np.abs(norms - 1.0).max()))
        unit = {p: Q.normalize(piece.quaternions(p)) for p in live}
        positions = {p: piece.positions(p) for p in live}
        if self.reference is not None:
            for path, (angle, miss) in motion.errors(self.reference, self.scene.data["time"]
                                                     ["start"], piece.t, unit,
                                                     positions).items():  # fmt: skip
                self._max(f"error_{path}", angle)
                self._max(f"position_error_{path}", miss)
        if len(live) > 1:
            self._cross(piece, live, unit)

    def _cross(self, piece: Trajectory, live: list, unit: dict) -> None:
        from .. import paths as _paths
        from ..crosscheck import cross_check

        if len(live) < len(piece.paths):  # a path that stopped: compare the others
            keep = {_paths.resolve(p, True).array for p in piece.paths if p not in live}
            piece = Trajectory({n: piece[n] for n in piece.names if n not in keep},
                               piece.components, piece.meta)  # fmt: skip
        for c in cross_check(piece, unit):
            old = self.cross.setdefault(c.paths, [c.max_angle, c.at_time, c.max_distance,
                                                  c.distance_at, 0])  # fmt: skip
            if c.max_angle > old[0]:
                old[0], old[1] = c.max_angle, c.at_time
            if c.max_distance > old[2]:
                old[2], old[3] = c.max_distance, c.distance_at
            old[4] += c.samples

    # ------------------------------------------------------------------ the report

    def _trajectory(self) -> Trajectory:
        """The primary path's samples of the whole run, as one Trajectory."""
        arrays = {name: np.concatenate(parts) for name, parts in self.kept.items()}
        components = {n: c for n, c in self.meta.get("components", {}).items() if n in arrays}
        return Trajectory(arrays, components, self.meta)

    def report(self) -> Report:
        """The :class:`Report` of the pieces taken so far (all of them: the run's)."""
        scene, meta = self.scene, self.meta
        rep = Report(scene.name)
        spec = scene.data["integrator"]
        how = (
            f"adaptive at tolerance {spec['tolerance']:g}, sampled every {meta['step']:g} s"
            if "tolerance" in spec
            else f"{meta['steps']:,} steps of {meta['step']:g} s"
        )
        forces = listed(f["type"] for f in scene.data.get("forces", [])) or "none"
        torques = listed(meta["torques"]) or "none"
        rep.lines.append(f"scene {scene.name}: {meta['integrator']}, {how}; a body moving "
                         f"through space; forces: {forces}; torques: {torques}")  # fmt: skip
        rep.lines.append("paths:")
        for path, info in meta["paths"].items():
            status = "complete" if info["complete"] else f"stopped at t = {info['ended_at']:g} s"
            drift = self.maxima.get(f"norm_drift_{path}")
            if drift is not None:
                rep.values[f"norm_drift_{path}"] = drift
                status += f", max | |q| − 1 | = {drift:.1e}"
            rep.lines.append(f"  {path:<11} {status}")
        if self.reach > 0.0:
            rep.values["length_scale"] = self.reach
        self._exact_lines(rep)
        self._balance_lines(rep)
        self._cross_lines(rep)
        self._accuracy_line(rep)
        t_end = scene.data["time"]["start"] + meta["steps"] * meta["step"]
        mark_incomplete(rep, meta, t_end)
        return rep

    def _relative(self, distance: float) -> str:
        if self.reach <= 0.0:
            return ""
        return f" ({distance / self.reach:.1e} of the length scale {self.reach:.3g} m)"

    def _exact_lines(self, rep: Report) -> None:
        scene = self.scene
        if scene.exact is None:
            rep.lines.append(f"exact solution: none ({scene.exact_reason})")
            return
        if self.exact_failure is not None:
            rep.lines.append(self.exact_failure)
            return
        rep.lines.append(f"exact solution ({scene.exact}: {scene.exact_reason}):")
        for path in scene.paths:
            if f"error_{path}" not in self.maxima:
                continue
            angle, miss = self.maxima[f"error_{path}"], self.maxima[f"position_error_{path}"]
            rep.values[f"error_{path}"] = angle
            rep.values[f"position_error_{path}"] = miss
            rep.lines.append(f"  {path:<11} max orientation error {angle:.2e} rad, max "
                             f"position error {miss:.2e} m{self._relative(miss)}")  # fmt: skip

    def _balance_lines(self, rep: Report) -> None:
        from .. import balances
        from ..errors import GaRotorsError

        primary = self.meta["primary"]
        rep.lines.append(f"balances ({primary} path; conserved: its drift; else its change "
                         "less the integral of its source over the samples):")  # fmt: skip
        if self.failure is None and not self.kept:
            self.failure = "not measured: no samples"
        if self.failure is None:
            try:
                rows = balances.balances(self._trajectory(), self.scene.body, *self.terms)
            except GaRotorsError as exc:
                self.failure = f"not evaluated: {exc}"
            else:
                for row in rows:
                    rep.values[f"balance_{row.name}"] = row.relative
                    rep.lines.append(f"  {row}")
                return
        rep.lines.append(f"  {self.failure}")

    def _cross_lines(self, rep: Report) -> None:
        if len(self.scene.paths) < 2:
            return
        from ..crosscheck import PathComparison

        rep.lines.append("cross-check (largest angle and distance between the paths):")
        for pair, (angle, at, far, far_at, samples) in self.cross.items():
            rep.values[f"{pair[0]}_vs_{pair[1]}"] = angle
            rep.values[f"{pair[0]}_vs_{pair[1]}_distance"] = far
            line = str(PathComparison(pair, angle, at, samples, far, far_at))
            rep.lines.append(f"  {line}{self._relative(far)}")

    def _accuracy_line(self, rep: Report) -> None:
        scene = self.scene
        has, lacks = [], []
        if any(k.startswith("error_") for k in rep.values):
            has.append("the error against the exact solution")
        elif scene.exact is None:
            lacks.append(f"an exact error ({scene.exact_reason})")
        else:
            lacks.append("an exact error (the reference was not evaluated)")
        if any(k.startswith("balance_") for k in rep.values):
            has.append("the energy and momentum balances")
        else:
            lacks.append(f"the balances ({self.failure})")
        if len(scene.paths) > 1:
            has.append("the paths' cross-check")
        else:
            lacks.append("a cross-check (one path; integrator.paths can list motor and "
                         "quaternion)")  # fmt: skip
        line = "accuracy: measured by " + (", ".join(has) if has else "nothing")
        if lacks:
            line += "; not available: " + "; ".join(lacks)
        rep.lines.append(line)
