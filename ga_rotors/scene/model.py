"""The Scene: a validated scene and the values derived from it, each computed once.

A scene is a TOML file (read with the standard library's ``tomllib``; scene files are
data and are never evaluated) or the same nested dictionary built in Python. The schema,
every key with its type, default and units, is in ``docs/scenes.md``; in short::

    [scene]                     name, description
    [body]                      moments | tensor | shape + dimensions; mass (kg);
                                centre_of_mass (m, a body moving through space)
    [initial]                   position (m), velocity (m/s): a body moving through space
    [initial.orientation]       quaternion | euler + sequence + units | rotor | axis + angle + units
    [initial.angular_velocity]  body | space | euler_rates, + units (rad/s, deg/s, rpm)
    [time]                      duration, start, output_step (s)
    [integrator]                method, step (s), paths
    [[effects]]                 type = gravity | damping | body_torque | space_torque | user
    [[forces]]                  type = uniform_gravity | spring | point_force | linear_drag |
                                central_gravity | user (a body moving through space)
    [output]                    quantities, plots, figure_format, data, summary

Lengths, masses, times, torques and inertia are SI (m, kg, s, N·m, kg·m²). Angles and
angular rates are ambiguous, so they carry explicit ``units``; a missing ``units`` is an
error, never a guess. Every error is a :class:`ga_rotors.errors.SceneError` naming the file,
the key (dotted path) and what was expected.

Frames. Every value a scene gives and every output of its run (orientations, ω, L, the
angles, the summary, the figure, the data files) is in the *scene's body frame*: the axes
the scene writes its body in, as :func:`ga_rotors.simulation.simulate` answers for a
:class:`~ga_rotors.body.RigidBody` built from a tensor. The loops integrate in the body's
principal frame (about the pivot with gravity); it differs from the scene's body frame
when the inertia is not diagonal there (a full ``tensor``, an off-axis pivot):
:attr:`Scene.principal_rotation` P then takes principal axes to the scene's body axes,
and :attr:`Scene.body` carries P, so ``simulate(scene.body, scene.orientation,
scene.angular_velocity, ...)`` is the scene's run. :attr:`Scene.body_frame` names the
frame in a sentence (``Trajectory.meta["body_frame"]``, written into the data files).

Examples
--------
>>> scene = Scene({
...     "body": {"shape": "disk", "mass": 2.0, "radius": 0.075},
...     "initial": {"angular_velocity": {"body": [0.1, 0.0, 15.0], "units": "rad/s"}},
...     "time": {"duration": 1.0},
...     "integrator": {"step": 1e-3},
... })
>>> scene.body.moments
(0.0028125, 0.0028125, 0.005625)
>>> scene.steps, scene.sample_every, scene.exact
(1000, 1, 'symmetric_top')
>>> Scene({"body": {"moments": [1, 2, 3]}, "time": {"duraton": 1.0}, "integrator": {"step": 1}})
Traceback (most recent call last):
...
ga_rotors.errors.SceneError: <dict>: time.duraton: unknown key (did you mean 'duration'?); ...
"""

from __future__ import annotations

import copy
import functools
import math
import re
import sys
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path

import numpy as np

from .. import effects as _effects
from ..body import RigidBody
from ..errors import InputError
from ..shapes import SHAPES
from . import exact as _exact
from .reader import Reader, join
from .schema import (
    ANGLE_UNITS,
    MOTION_KEYS,
    NAME,
    ORIENTATION_FORMS,
    RATE_UNITS,
    ROTOR_BLADES,
    adaptive,
    moves,
    resolve,
)
from .toml_io import check_nesting, dumps_toml, parse_toml

__all__ = ["MAX_TURN_PER_STEP", "TIME_RESOLUTION", "Scene", "whole_steps_at"]

#: Largest spacing of float64 times, as a fraction of the step, a scene may have: beyond
#: it time values round by more than a millionth of a step (torques of t, the exact
#: solution's times and the time column would carry that error).
TIME_RESOLUTION = 1e-6
#: Largest rotation per step (rad) a scene may ask for; the step limits of the methods
#: (docs/stability.md) are a few radians, this only refuses the absurd.
MAX_TURN_PER_STEP = 1e3


def whole_steps_at(reader: Reader, span: float, step: float, key: str, message: str) -> int:
    """``span / step`` as a whole number of steps (:func:`ga_rotors.simulation.whole_steps`,
    simulate's rule), or ``message`` at ``key`` of ``reader``'s file.

    Examples
    --------
    >>> whole_steps_at(Reader("s.toml"), 0.3, 0.1, "time.duration", "not whole")
    3
    >>> whole_steps_at(Reader("s.toml"), 1.0, 0.3, "time.duration", "not whole")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: s.toml: time.duration: not whole
    """
    from ..simulation import whole_steps  # the simulation imports this package's reader

    try:
        return whole_steps(span, step)
    except InputError:
        raise reader.error(key, message) from None


class Scene:
    """A validated scene: the resolved data and what it implies.

    Parameters
    ----------
    data : mapping
        The scene as nested dicts and lists, exactly as the TOML file would hold it.
    file : str
        Name used in error messages (the file's path for :func:`load_scene`).
    base_dir : path, optional
        Where user-torque modules may also be imported from (the file's directory).

    Attributes
    ----------
    data : dict
        The resolved scene: every key, defaults filled in (what ``ga-rotors show``
        prints, as TOML; loading it again gives the same scene).
    body : RigidBody
        The scene's body: its principal moments (about the pivot with gravity) and P,
        its ``principal_rotation``; it takes and gives values in the scene's body frame.
    principal_rotation : tuple
        P: principal axes -> the scene's body axes (identity when the inertia is diagonal).
    orientation : ndarray (4,)
        Initial orientation of the scene's body frame (unit quaternion, body to space).
    angular_velocity : ndarray (3,)
        Initial body angular velocity in the scene's body frame (rad/s).
    principal_orientation, principal_angular_velocity : ndarray
        The same initial state in the principal frame the loops integrate in (q ⊗ P and
        P* ω P, converted as :func:`~ga_rotors.simulation.simulate` converts them).
    euler_angles : ndarray (3,) or None
        The initial ZYZ angles (rad) when the scene gives them directly (passed to the
        Euler-angle path exactly, rather than extracted from the quaternion).
    steps, sample_every : int
        Number of integration steps; steps between output samples.
    exact : str or None
        Which exact solution applies (:attr:`exact_reason` says why not, when None);
        :attr:`exact_solution` is that solution, built on first use and kept.
    method : Integrator
        The resolved integrator (an adaptive one at the scene's tolerance), checked
        against the scene's effects and paths.
    gravity : tuple of ndarray or None
        (weight m g in space, r = pivot -> centre of mass in the principal frame the
        torque kernels act in), or None without gravity.
    frame : ga_rotors.effects.Frame
        What building the effects' torques needs (principal rotation, mass, base_dir).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> s = load_scene("spinning_disk")
    >>> s
    Scene('spinning_disk', free, 10000 steps)
    >>> s.body.moments, s.exact, s.paths
    ((0.0028125, 0.0028125, 0.005625), 'symmetric_top', ['rotor', 'quaternion', 'euler'])
    """

    def __init__(self, data: Mapping, *, file: str = "<dict>", base_dir=None):
        self.file = str(file)
        self.base_dir = None if base_dir is None else Path(base_dir)
        reader = Reader(self.file)
        check_nesting(data, self.file)  # before the copy, which recurses
        self._given = copy.deepcopy(dict(data)) if isinstance(data, Mapping) else data
        default = Path(self.file).stem if self.file != "<dict>" else "scene"
        if not NAME.fullmatch(default):
            default = "scene"
        self.data = resolve(reader, self._given, default)
        self._derive(reader)

    # ------------------------------------------------------------------ construction

    @classmethod
    def from_toml(cls, text: str, *, file: str = "<string>", base_dir=None) -> Scene:
        """Parse TOML text (data only: ``tomllib``, nothing evaluated).

        Examples
        --------
        >>> Scene.from_toml("[body]\\nmoments = [1, 2, 3]\\n[time]\\nduration = 1\\n"
        ...                 "[integrator]\\nstep = 0.5\\n").steps
        2
        >>> Scene.from_toml("[body\\n", file="bad.toml")
        Traceback (most recent call last):
        ...
        ga_rotors.errors.SceneError: bad.toml: not valid TOML: ... (at line 1, column 6)
        """
        return cls(parse_toml(text, file), file=file, base_dir=base_dir)

    def replace(self, changes: Mapping[str, object]) -> Scene:
        """A new scene with some keys changed, given as dotted paths.

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> s = load_scene("spinning_disk").replace({"time.duration": 0.5})
        >>> s.data["time"]["duration"], s.steps
        (0.5, 500)
        """
        given = copy.deepcopy(self._given)
        for path, value in changes.items():
            _set_path(given, str(path), value, self.file)
        return Scene(given, file=self.file, base_dir=self.base_dir)

    # ------------------------------------------------------------------ derived values

    def _derive(self, reader: Reader) -> None:
        d = self.data
        body = d["body"]
        tensor, key = self._inertia(reader, body)
        mass = body.get("mass")
        self.moves = moves(d)
        self.gravity_index = next(
            (i for i, e in enumerate(d["effects"]) if e["type"] == "gravity"), None
        )
        if self.gravity_index is not None:
            tensor = self._about_pivot(reader, tensor, mass)
            key = join(join("effects", self.gravity_index), "pivot_to_com")
        self.body = self._principal(reader, tensor, key)
        if self.moves:  # the body moving through space carries its mass and centre
            try:
                self.body = replace(
                    self.body,
                    mass=mass,
                    centre_of_mass=tuple(body.get("centre_of_mass", (0.0,) * 3)),
                )
            except InputError as exc:
                raise reader.error("body.centre_of_mass", exc.detail) from None
        self.principal_rotation = self.body.principal_rotation
        self.mass = mass
        self.frame = _effects.Frame(self.principal_rotation, mass, self.base_dir, self.file)

        from .. import quaternion as Q

        self.orientation = self._orientation(reader, d["initial"]["orientation"])
        self.angular_velocity = np.asarray(
            self._angular_velocity(reader, d["initial"], self.orientation), dtype=np.float64
        )
        # the integration frame's start, as simulate converts it (the ensemble starts there)
        p = np.array(self.principal_rotation)
        self.principal_orientation = Q.multiply(self.orientation, p)
        self.principal_angular_velocity = Q.rotate(Q.conjugate(p), self.angular_velocity)
        self.position = self.velocity = None
        if self.moves:
            self.position, self.velocity = (np.array(d["initial"].get(k, [0.0, 0.0, 0.0]))
                                            for k in MOTION_KEYS)  # fmt: skip
        self.euler_angles = None
        o = d["initial"]["orientation"]
        if "euler" in o and o["sequence"] == "ZYZ" and self.principal_rotation == _IDENTITY:
            self.euler_angles = np.array(o["euler"]) * ANGLE_UNITS[o["units"]]

        time, integ = d["time"], d["integrator"]
        self.steps = whole_steps_at(
            reader, time["duration"], integ["step"], "integrator.step",
            f"expected a step that divides time.duration ({time['duration']!r} s) into whole "
            f"steps, got {integ['step']!r} s",
        )  # fmt: skip
        self.sample_every = whole_steps_at(
            reader, time["output_step"], integ["step"], "time.output_step",
            f"expected a whole multiple of integrator.step ({integ['step']!r} s), got "
            f"{time['output_step']!r} s",
        )  # fmt: skip
        if self.sample_every > self.steps:
            raise reader.error(
                "time.output_step",
                f"expected at most time.duration ({time['duration']!r} s), got "
                f"{time['output_step']!r} s",
            )
        self._check_time_grid(reader)
        self._check_magnitudes(reader)
        self.kind = "motion" if self.moves else "torqued" if d["effects"] else "free"
        self.gravity = self._gravity()
        self.method = self._method()
        self._check_integrator(reader)
        if self.moves:
            from . import motion

            self.exact, self.exact_reason = motion.applicable(self)
        else:
            self.exact, self.exact_reason = _exact.applicable(self.body, d["effects"],
                                                              self.gravity)  # fmt: skip
        self._check_outputs(reader)

    def _check_magnitudes(self, reader: Reader) -> None:
        """Refuse an initial state whose energy or squared angular momentum float64
        cannot hold (the references and summaries form L² and 2E·I: moments of 1e300 gave
        a NaN summary), or that turns more than :data:`MAX_TURN_PER_STEP` radians in one
        step, by its own rate (no fixed-step method resolves it; the step-limit estimate
        itself overflowed on ω = 1e150 rad/s) or spun up by its torques' bound in that
        step (a torque of 1e200 N·m, g = 1e308 m/s² ran into overflow warnings)."""
        key = "initial.angular_velocity"
        try:
            self.body.energy(self.angular_velocity)
        except InputError as exc:
            raise reader.error(key, exc.detail) from None
        rate = math.hypot(*self.angular_velocity)
        momentum = max(self.body.moments) * rate  # (2E·I ≤ |Iω|² with I the largest)
        if not momentum * momentum * 16.0 < sys.float_info.max:
            raise reader.error(
                key,
                f"|Iω| = {momentum:.3g} kg·m²/s: its square overflows float64 (beyond "
                f"{sys.float_info.max:.3g}); rescale the units",
            )
        if self.moves:
            speed = math.hypot(*self.velocity)
            if not 0.5 * self.mass * speed * speed * 16.0 < sys.float_info.max:
                raise reader.error(
                    "initial.velocity",
                    f"½ m v² of {self.mass:.3g} kg at {speed:.3g} m/s overflows float64; "
                    "rescale the units",
                )
            # The lever s enters the inertia about the origin (m|s|²) and the origin's
            # velocity (ω×s); the position the momentum about the space origin (m r×v):
            # their squares must fit as the energy's does (s = 1e308 m gave NaN samples).
            lever = math.hypot(*self.body.centre_of_mass)
            reach = math.hypot(*self.position)
            for where, value, what in (
                ("body.centre_of_mass", self.mass * lever * max(lever, rate * lever),
                 "the moment m|s|² and momentum m|ω×s| it adds about the body-frame origin"),
                ("initial.position", self.mass * reach * (speed + rate * lever),
                 "the angular momentum about the space origin, m|r||v|,"),
            ):  # fmt: skip
                if not value * value * 16.0 < sys.float_info.max:
                    raise reader.error(
                        where, f"{what} overflow float64 when squared; rescale the units"
                    )
        h = self.data["integrator"]["step"]
        turn = rate * h
        if not turn <= MAX_TURN_PER_STEP:
            raise reader.error(
                key,
                f"|ω|·integrator.step = {turn:.3g} rad per step, beyond {MAX_TURN_PER_STEP:g}: "
                "no method resolves that; take a smaller step",
            )
        for i, entry in enumerate(self.data["effects"]):
            bound = _effects.EFFECTS[entry["type"]].largest_torque
            if bound is None:
                continue
            torque = bound(entry, self.mass, rate)
            turn = (rate + torque * h / min(self.body.moments)) * h
            if not turn <= MAX_TURN_PER_STEP:
                raise reader.error(
                    join("effects", i),
                    f"its torque (up to {torque:.3g} N·m) would turn the body by {turn:.3g} "
                    f"rad in its first step, beyond {MAX_TURN_PER_STEP:g}: no method resolves "
                    "that; check the units, or take a smaller step",
                )

    def _check_time_grid(self, reader: Reader) -> None:
        """Refuse times float64 cannot place to :data:`TIME_RESOLUTION` of a step: with
        time.start a Unix timestamp (1.7e9 s) times are 2.4e-7 s apart, and a 1 ms step
        rounded every time value (the reported error was 3 rad instead of 5e-10)."""
        time, h = self.data["time"], self.data["integrator"]["step"]
        largest = max(abs(time["start"]), abs(time["start"] + time["duration"]))
        spacing = float(np.spacing(largest))
        if not (np.isfinite(largest) and spacing <= TIME_RESOLUTION * h):
            key = "time.start" if abs(time["start"]) >= time["duration"] else "time.duration"
            raise reader.error(
                key,
                f"float64 times near {largest:.3g} s are {spacing:.2g} s apart, more than "
                f"{TIME_RESOLUTION:g} of integrator.step ({h:g} s): the time grid would "
                "lose precision; start the clock nearer 0 (time.start) or take longer steps",
            )

    @staticmethod
    def _inertia(reader: Reader, body: dict) -> tuple[np.ndarray, str]:
        if "moments" in body:
            try:
                RigidBody(tuple(body["moments"]))
            except InputError as exc:
                raise reader.error("body.moments", exc.detail) from None
            return np.diag(body["moments"]), "body.moments"
        if "tensor" in body:
            try:
                RigidBody.from_tensor(body["tensor"])
            except InputError as exc:
                raise reader.error("body.tensor", exc.detail) from None
            t = np.array(body["tensor"], dtype=np.float64)
            return 0.5 * (t + t.T), "body.tensor"
        func, dims = SHAPES[body["shape"]]
        try:
            moments = func(body["mass"], *(body[k] for k in dims))
        except InputError as exc:
            raise reader.error(join("body", exc.key) if exc.key else "body", exc.detail) from None
        return np.diag(moments), "body.shape"

    def _about_pivot(self, reader: Reader, tensor: np.ndarray, mass) -> np.ndarray:
        key = join("effects", self.gravity_index)
        g = self.data["effects"][self.gravity_index]
        if mass is None:
            raise reader.error("body.mass", f"missing; the gravity effect ({key}) needs the mass")
        try:
            shift = _effects.inertia_about_pivot(np.zeros((3, 3)), mass, g["pivot_to_com"])
        except InputError as exc:
            raise reader.error(join(key, "pivot_to_com"), exc.detail) from None
        if g["inertia_about"] == "com":
            return tensor + shift
        # Given about the pivot: what is left about the centre of mass must be a body.
        try:
            RigidBody.from_tensor(tensor - shift)
        except InputError as exc:
            raise reader.error(
                join(key, "inertia_about"),
                "the body's inertia about the pivot minus m(|r|²1 − r rᵀ) (its inertia about "
                f"the centre of mass) is not a rigid body's inertia: {exc}",
            ) from None
        return tensor

    @staticmethod
    def _principal(reader: Reader, tensor: np.ndarray, key: str) -> RigidBody:
        """The body of ``tensor`` (scene body axes): its principal moments and P."""
        try:
            if np.count_nonzero(tensor - np.diag(np.diag(tensor))) == 0:
                return RigidBody(tuple(np.diag(tensor)))
            return RigidBody.from_tensor(tensor)
        except InputError as exc:
            raise reader.error(key, exc.detail) from None

    @staticmethod
    def _orientation(reader: Reader, o: dict) -> np.ndarray:
        from .. import euler
        from .. import quaternion as Q
        from .._validate import require_unit
        from ..isomorphism import from_even

        key = "initial.orientation"
        try:
            if "quaternion" in o:
                return require_unit(np.array(o["quaternion"]), "quaternion")
            if "euler" in o:
                angles = np.array(o["euler"]) * ANGLE_UNITS[o["units"]]
                return euler.to_quaternion(o["sequence"], angles)
            if "axis" in o:
                return Q.from_axis_angle(o["axis"], o["angle"] * ANGLE_UNITS[o["units"]])
            c = np.zeros(8)
            for name, v in o["rotor"].items():
                index, sign = ROTOR_BLADES[name]
                c[index] = sign * v
            return require_unit(from_even(c, name="rotor"), "rotor")
        except InputError as exc:
            form = next(f for f in ORIENTATION_FORMS if f in o)
            raise reader.error(join(key, form), exc.detail) from None

    @staticmethod
    def _angular_velocity(reader: Reader, initial: dict, q_user: np.ndarray) -> np.ndarray:
        from .. import quaternion as Q
        from ..kinematics import body_omega_from_euler_rates

        a = initial["angular_velocity"]
        scale = RATE_UNITS[a["units"]]
        if "body" in a:
            return np.array(a["body"]) * scale
        if "space" in a:
            return Q.rotate(Q.conjugate(q_user), np.array(a["space"]) * scale)
        o = initial["orientation"]
        angles = np.array(o["euler"]) * ANGLE_UNITS[o["units"]]
        return body_omega_from_euler_rates(
            o["sequence"], angles, np.array(a["euler_rates"]) * scale
        )

    def _gravity(self) -> tuple[np.ndarray, np.ndarray] | None:
        if self.gravity_index is None:
            return None
        g = self.data["effects"][self.gravity_index]
        weight = self.mass * np.array(g["g"])
        return weight, np.array(self.frame.to_principal(g["pivot_to_com"]))

    def _method(self):
        """The registered integrator, or for an adaptive one an instance at the tolerance."""
        from ..integrators import base

        spec = self.data["integrator"]
        method = base.get(spec["method"])
        if "tolerance" not in spec or method.rtol == spec["tolerance"]:
            return method
        return type(method)(rtol=spec["tolerance"])

    def _check_integrator(self, reader: Reader) -> None:
        from types import SimpleNamespace

        integ = self.data["integrator"]
        method = self.method
        # The effects as the check sees them (name, whether they read ω), without building
        # them: a user kernel is imported only when the scene is simulated.
        torques = [
            SimpleNamespace(
                name=f"{join('effects', i)} ({e['type']})",
                depends_on_omega=_effects.EFFECTS[e["type"]].reads_omega(e),
            )
            for i, e in enumerate(self.data["effects"])
        ]
        from .force_types import FORCE_TYPES

        forces = [
            SimpleNamespace(
                name=f"{join('forces', i)} ({f['type']})",
                depends_on_velocity=FORCE_TYPES[f["type"]].reads_velocity(f),
            )
            for i, f in enumerate(self.data.get("forces", []))
        ]
        problem = SimpleNamespace(
            kind=self.kind,
            torques=torques,
            forces=forces,
            accept_lower_order=integ.get("accept_lower_order", False),
        )
        for path in integ["paths"]:
            try:
                method.check(problem, path)
            except InputError as exc:
                key = "integrator.paths" if exc.key == "paths" else "integrator.method"
                raise reader.error(key, exc.detail) from None
        from .. import paths as _paths

        turned = [p for p in integ["paths"] if _paths.get(p).sequence]
        if turned and self.principal_rotation != _IDENTITY:
            # its state is the principal frame's angles, which are not the scene's body
            # frame's: every output is in the latter (simulate refuses it the same way)
            raise reader.error(
                "integrator.paths",
                f"the {turned[0]} path integrates the Euler angles of the principal frame, "
                f"and this body's principal axes are not its scene axes ({self._turned_by()}); "
                "use the rotor or quaternion path (the angles quantity gives ZYZ angles of "
                "the scene's body frame)",
            )

    def _check_outputs(self, reader: Reader) -> None:
        out = self.data["output"]
        if self.moves:
            for section, names, allowed in (("quantities", out["quantities"], MOTION_QUANTITIES),
                                            ("plots", out["plots"], MOTION_PLOTS)):  # fmt: skip
                for i, name in enumerate(names):
                    if name not in allowed:
                        raise reader.error(
                            join(join("output", section), i),
                            f"{name!r} is for a body turning about a fixed point; a body "
                            f"moving through space takes {', '.join(allowed)} (its summary "
                            "states its errors and balances)",
                        )
            return
        needs = {
            "error": self.exact is not None and self.exact_has_orientation,
            "omega_error": self.exact is not None,
            "potential_energy": self.gravity_index is not None,
            "position": False,
        }
        for section, names in (("quantities", out["quantities"]), ("plots", out["plots"])):
            for i, name in enumerate(names):
                if needs.get(name, True):
                    continue
                reason = (
                    "needs gravity" if name == "potential_energy"
                    else "needs a body moving through space (initial.position, "
                    "initial.velocity or forces)" if name == "position"
                    else f"needs an exact solution; this scene has none ({self.exact_reason})"
                )  # fmt: skip
                raise reader.error(join(join("output", section), i), f"{name!r} {reason}")

    @functools.cached_property
    def exact_solution(self):
        """The exact solution that applies (:class:`ga_rotors.scene.exact.Exact`), or None.

        Built on first use and kept: a run, its summary and its figure share one.
        Raises InputError (from the reference) when the state is outside its domain.

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> scene = load_scene("spinning_disk")
        >>> scene.exact_solution.name, scene.exact_solution is scene.exact_solution
        ('symmetric_top', True)
        """
        from ..errors import PrecisionError

        if self.moves:
            from . import motion

            return motion.build(self)
        effects = self.data["effects"]
        damping = effects[0]["coefficient"] if self.exact == "damped_symmetric_top" else None
        try:
            return _exact.build(
                self.exact,
                self.body,
                self.orientation,
                self.angular_velocity,
                self.data["time"]["start"],
                gravity=self.gravity,
                damping=damping,
            )
        except (InputError, PrecisionError) as exc:
            raise _exact.refusal(self.file, self.exact, exc) from None

    def _turned_by(self) -> str:
        """What makes the principal axes differ from the scene's body axes."""
        if "tensor" in self.data["body"]:
            return "body.tensor is not diagonal"
        return f"the pivot {join('effects', self.gravity_index)}.pivot_to_com is off them"

    @property
    def body_frame(self) -> str:
        """The frame every output of the scene is in, as a short sentence (what
        ``Trajectory.meta["body_frame"]`` and the data files record).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> load_scene("heavy_top").body_frame
        "the scene's body axes (body.shape): principal about the pivot"
        >>> turned = {"tensor": [[1.0, 0.1, 0.0], [0.1, 2.0, 0.0], [0.0, 0.0, 2.5]]}
        >>> load_scene("intermediate_axis_flip").replace({"body": turned}).body_frame
        "the scene's body axes (body.tensor): not principal (principal_rotation turns them)"
        """
        given = next(k for k in ("moments", "tensor", "shape") if k in self.data["body"])
        where = f"the scene's body axes (body.{given})"
        if self.moves:
            com = self.body.centre_of_mass
            axes = "principal" if self.principal_rotation == _IDENTITY else "not principal"
            origin = (
                f"its origin {math.hypot(*com):g} m from the centre of mass"
                if any(com)
                else "its origin the centre of mass"
            )
            return f"{where}: {axes}, {origin}; positions and velocities are the origin's, in space"
        if self.principal_rotation != _IDENTITY:
            return f"{where}: not principal (principal_rotation turns them)"
        return f"{where}: principal" + ("" if self.gravity_index is None else " about the pivot")

    @property
    def exact_has_orientation(self) -> bool:
        """Whether the exact solution gives the orientation (not only ω)."""
        if self.exact == "damped_symmetric_top":
            i1, i2, i3 = self.body.moments
            return i1 == i2 == i3
        return self.exact is not None

    # ------------------------------------------------------------------ accessors

    @property
    def name(self) -> str:
        return self.data["scene"]["name"]

    @property
    def description(self) -> str:
        return self.data["scene"]["description"]

    @property
    def step(self) -> float:
        return self.data["integrator"]["step"]

    @property
    def paths(self) -> list[str]:
        return list(self.data["integrator"]["paths"])

    @property
    def effects(self) -> list[dict]:
        return copy.deepcopy(self.data["effects"])

    def forces(self) -> tuple:
        """The declared ``[[forces]]`` as ForceTerms on the scene's body (imports user
        forces' modules, on the opt-in only).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> [f.name for f in load_scene("thrown_racket").forces()]
        ['uniform_gravity']
        >>> load_scene("heavy_top").forces()
        ()
        """
        from .force_types import FORCE_TYPES

        reader = Reader(self.file)
        return tuple(
            FORCE_TYPES[f["type"]].term(f, self.body, reader, join("forces", i))
            for i, f in enumerate(self.data.get("forces", []))
        )

    def torques(self) -> tuple:
        """The declared effects as TorqueTerms (imports user-torque modules).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> [t.name for t in load_scene("heavy_top").torques()]
        ['gravity']
        >>> load_scene("spinning_disk").torques()
        ()
        """
        reader = Reader(self.file)
        return tuple(
            _effects.EFFECTS[e["type"]].term(e, self.frame, reader, join("effects", i))
            for i, e in enumerate(self.data["effects"])
        )

    def to_dict(self) -> dict:
        """The resolved scene (a deep copy).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> load_scene("heavy_top").to_dict()["effects"][0]["inertia_about"]
        'com'
        """
        return copy.deepcopy(self.data)

    def to_toml(self) -> str:
        """The resolved scene as TOML text; ``Scene.from_toml`` of it is the same scene.

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> s = load_scene("spinning_disk")
        >>> Scene.from_toml(s.to_toml()).data == s.data
        True
        """
        return dumps_toml(self.data)

    def describe(self) -> str:
        """What the scene resolves to, as TOML comment lines (``ga-rotors show``).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> print("\\n".join(load_scene("heavy_top").describe().splitlines()[:2]))
        # every output is in the scene's body axes (body.shape): principal about the pivot
        # principal moments (0.002225, 0.002225, 0.00125) kg·m² about the pivot
        """
        q, w = self.orientation, self.angular_velocity
        method = self.method
        lines = [
            f"every output is in {self.body_frame}",
            f"principal moments {_fmt(self.body.moments)} kg·m²"
            + (" about the pivot" if self.gravity_index is not None else ""),
            f"principal rotation P (principal -> scene body axes): {_fmt(self.principal_rotation)}",
            f"initial orientation q0 (w, x, y, z): {_fmt(q)}",
            f"initial body angular velocity: {_fmt(w)} rad/s",
            *self._motion_lines(),
            f"problem: {self.kind}; torques: "
            + (_effects.listed(e["type"] for e in self.data["effects"]) or "none (torque-free)"),
            f"integrator: {method.name} (order {method.order}), "
            + (
                f"adaptive at tolerance {self.data['integrator']['tolerance']:g}, "
                f"{self.steps:,} output intervals"
                if adaptive(method)
                else f"{self.steps:,} steps"
            )
            + f", a sample every {self.sample_every} step(s), paths {', '.join(self.paths)}",
            f"exact solution: {self.exact or 'none'} ({self.exact_reason})",
        ]
        return "\n".join("# " + line for line in lines)

    def _motion_lines(self) -> list[str]:
        """What :meth:`describe` says of a body moving through space (nothing otherwise)."""
        if not self.moves:
            return []
        forces = _effects.listed(f["type"] for f in self.data.get("forces", [])) or "none"
        return [
            f"initial position {_fmt(self.position)} m, velocity {_fmt(self.velocity)} m/s "
            f"(the body-frame origin, space); mass {self.mass:g} kg, centre of mass "
            f"{_fmt(self.body.centre_of_mass)} m (body frame); forces: {forces}"
        ]

    def __repr__(self) -> str:
        return f"Scene({self.name!r}, {self.kind}, {self.steps} steps)"

    def _repr_html_(self) -> str:
        from ..view.tables import scene_html  # notebook display

        return scene_html(self)


_IDENTITY = (1.0, 0.0, 0.0, 0.0)

#: ``output.quantities`` and ``output.plots`` a scene moving through space can have
MOTION_QUANTITIES = ("energy", "L", "L_space", "omega_space", "angles")
MOTION_PLOTS = ("omega", "angles", "position")


def _fmt(v) -> str:
    return "(" + ", ".join(f"{float(x):.10g}" for x in v) + ")"


_PATH = re.compile(r"[A-Za-z_][\w-]*(?:\.[A-Za-z_][\w-]*|\[\d+\])*")


def _set_path(given: dict, path: str, value, file: str) -> None:
    """Set ``path`` (``a.b[2].c``) in the scene dictionary ``given``: a missing table key
    is created (the scene's validation then names a key that does not exist); an index
    past a list's end, or a path through a value that is not a table or a list, is one
    scene error naming the path.
    """
    from ..errors import SceneError

    if not _PATH.fullmatch(path):
        raise SceneError(file, path, "expected a dotted key path such as time.duration or "
                         "initial.angular_velocity.body[2]")  # fmt: skip
    parts = re.findall(r"[^.\[\]]+|\[\d+\]", path)
    node, walked = given, ""
    for i, part in enumerate(parts):
        last = i == len(parts) - 1
        if part.startswith("["):
            index = int(part[1:-1])
            if not isinstance(node, list):
                raise SceneError(file, path, f"{walked or 'the scene'} is not a list")
            if index >= len(node):
                count = f"{len(node)} entr{'y' if len(node) == 1 else 'ies'}"
                raise SceneError(file, path, f"{walked} has {count} here; set {walked} whole")
        else:
            index = part
            if not isinstance(node, dict):
                raise SceneError(file, path, f"{walked} is a value, not a table")
            if index not in node and not last:
                if parts[i + 1].startswith("["):
                    name = f"{walked}.{part}" if walked else part
                    raise SceneError(file, path, f"the scene has no {name}; set {name} whole")
                node[index] = {}
        if last:
            node[index] = value
        else:
            node = node[index]
            walked = f"{walked}{part}" if part.startswith("[") or not walked else f"{walked}.{part}"
