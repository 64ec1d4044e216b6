"""A simulation's result: named arrays on one time grid, exportable to CSV and NPZ.

Only what was computed is present: a path that was not asked for has no array, an output
nobody requested is not computed. Whatever paths were integrated, the orientation is
handed out by name, in one convention: :meth:`Trajectory.quaternions` gives unit
quaternions (w, x, y, z) and :meth:`Trajectory.rotors` clifford rotors, for any path.
Names used by :func:`ga_rotors.simulation.simulate`:

============= ========= ==============================================================
name          shape     meaning
============= ========= ==============================================================
t             (n,)      sample times (s)
w             (n, 3)    body angular velocity of the primary path (rad/s)
rotor_blades  (n, 4)    rotor path, raw: coefficients on clifford's blades
                        (1, e12, e13, e23) — *not* a quaternion; use ``quaternions()``
q             (n, 4)    quaternion path: (w, x, y, z)
euler         (m, 3)    Euler-angle path: integrated ZYZ angles (ψ, θ, φ), rad
energy        (n,)      kinetic energy ½ ω·Iω (J) of the primary path
L             (n, 3)    body-frame angular momentum Iω
L_space       (n, 3)    space-frame angular momentum q (Iω) q*
angles        (n, 3)    ZYZ angles (ψ, θ, φ) of the primary path's orientation
motor         (n, 8)    motor path of a moving body, raw: its motors (1, e01, e02, e03,
                        e12, e13, e23, e0123) of the body frame; use ``motors()``
q_com         (n, 7)    quaternion path of a moving body, raw: q (w, x, y, z) and the
                        centre of mass (m); use ``quaternions()``, ``positions()``
position      (n, 3)    where the body-frame origin is, in space (m), primary path
velocity      (n, 3)    its velocity in space (m/s), primary path
============= ========= ==============================================================

An array can be shorter than ``t`` (``m < n``) when its path stopped early because its
state stopped being finite (the Euler-angle path hitting sin θ = 0 exactly); its first
``m`` rows are the valid samples, and ``meta["paths"][name]`` says when it ended. CSV
export leaves such cells empty, never NaN.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import paths as _paths
from .errors import InputError

__all__ = ["Trajectory"]


class Trajectory:
    """Named arrays sampled on the grid ``t``.

    Parameters
    ----------
    arrays : dict of str -> ndarray
        Must contain ``t`` (1-D); every other array has at most ``len(t)`` rows.
    components : dict of str -> tuple of str, optional
        Column names of multi-column arrays (``q`` -> ``("w", "x", "y", "z")``).
    meta : dict, optional
        How the data were made (integrator, step, body, per-path status).

    Examples
    --------
    >>> tr = Trajectory({"t": np.array([0.0, 0.5]), "w": np.zeros((2, 3))},
    ...                 {"w": ("1", "2", "3")})
    >>> tr.names
    ('t', 'w')
    >>> tr.w.shape
    (2, 3)
    >>> print(tr.to_csv().splitlines()[0])
    t [s],w_1 [rad/s],w_2 [rad/s],w_3 [rad/s]
    """

    def __init__(self, arrays: dict, components: dict | None = None, meta: dict | None = None):
        if "t" not in arrays:
            raise InputError("arrays: a trajectory needs the sample times 't'")
        t = np.asarray(arrays["t"], dtype=np.float64)
        if t.ndim != 1:
            raise InputError(f"t: expected a 1-D array, got shape {t.shape}")
        self._arrays = {"t": t}
        for name, a in arrays.items():
            if name == "t":
                continue
            a = np.asarray(a, dtype=np.float64)
            if a.ndim == 0 or a.shape[0] > t.shape[0]:
                raise InputError(
                    f"{name}: expected at most {t.shape[0]} rows (len(t)), got shape {a.shape}"
                )
            self._arrays[name] = a
        self.components = {k: tuple(v) for k, v in (components or {}).items()}
        self.meta = dict(meta or {})
        self._quaternions: dict[str, np.ndarray] = {}

    # ------------------------------------------------------------------ orientation

    def _present(self, name: str):
        """The path called ``name`` as this trajectory holds it (for a moving body, a
        path's motion variant), or None."""
        spec = _paths.PATHS[name]
        if spec.array in self._arrays:
            return spec
        if spec.motion is not None and spec.motion.array in self._arrays:
            return spec.motion
        return None

    @property
    def paths(self) -> tuple[str, ...]:
        """The orientation paths present, primary first.

        Examples
        --------
        >>> from ga_rotors import simulate
        >>> simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.5,
        ...          step=0.1, paths=("quaternion", "rotor")).paths
        ('rotor', 'quaternion')
        """
        present = [name for name in _paths.PATHS if self._present(name) is not None]
        primary = self.meta.get("primary")
        if primary in present:
            present.remove(primary)
            present.insert(0, primary)
        return tuple(present)

    def _path(self, path: str | None) -> str:
        present = self.paths
        if path is None:
            if not present:
                raise InputError("path: this trajectory holds no orientation path")
            return present[0]
        _paths.get(path)  # an unknown name gets the list of valid ones
        if path not in present:
            raise InputError(
                f"path: the trajectory has no {path!r} path (it has {', '.join(present) or 'none'}"
                "; only the requested paths are integrated)"
            )
        return path

    def _moving(self, path: str | None):
        """The spec of ``path`` (default: the primary one) of a moving body, or InputError."""
        spec = self._present(self._path(path))
        if not spec.moves:
            raise InputError("this trajectory is a rotation about a fixed point: it has no "
                             "positions (simulate with position= for a body moving through "
                             "space)", key="path")  # fmt: skip
        return spec

    def quaternions(self, path: str | None = None) -> np.ndarray:
        """The orientation of ``path`` as quaternions (m, 4), (w, x, y, z), body -> space.

        Parameters
        ----------
        path : {"rotor", "quaternion", "euler"}, optional
            Which integrated path (default: the primary one, ``meta["primary"]``).

        Returns
        -------
        ndarray (m, 4), read-only
            Hamilton quaternions in ``docs/conventions.md``'s convention, whatever the path
            integrated; their norms are the path's own (an integrator that does not
            renormalise drifts from 1 by its error). ``m`` is the path's sample count
            (fewer than ``len(t)`` when it stopped early).

        Examples
        --------
        A quarter turn about z, integrated on the rotor path (its raw state is on
        clifford's blades, where k is −e12):

        >>> import math
        >>> from ga_rotors import simulate
        >>> tr = simulate((1.0, 1.0, 1.0), [1.0, 0, 0, 0], [0.0, 0.0, math.pi / 2],
        ...               duration=1.0, step=0.01)
        >>> tr.quaternions()[-1].round(9).tolist()
        [0.707106781, 0.0, 0.0, 0.707106781]
        >>> tr["rotor_blades"][-1].round(9).tolist()
        [0.707106781, -0.707106781, 0.0, 0.0]
        """
        path = self._path(path)
        if path not in self._quaternions:
            spec = self._present(path)
            q = np.array(spec.load().quaternions(self._arrays[spec.array]), dtype=np.float64)
            q.flags.writeable = False  # computed once and shared: nobody may change it
            self._quaternions[path] = q
        return self._quaternions[path]

    def positions(self, path: str | None = None) -> np.ndarray:
        """Where the body-frame origin is (m, 3), in space (m), on ``path`` (default: the
        primary one) of a body moving through space.

        The motor path's are its motors' translations; the quaternion path's, its centre
        of mass less the turned lever to it, c − q s q* (``meta["centre_of_mass"]`` is s).

        Examples
        --------
        >>> from ga_rotors import RigidBody, simulate
        >>> body = RigidBody((1.0, 1.0, 1.0), mass=1.0, centre_of_mass=(1.0, 0.0, 0.0))
        >>> tr = simulate(body, [1.0, 0, 0, 0], [0.0, 0.0, np.pi], duration=1.0, step=1e-2,
        ...               velocity=[0.0, -np.pi, 0.0], paths=("motor", "quaternion"))
        >>> tr.velocities()[0].round(15) + 0.0        # the origin circles the resting centre
        array([ 0.        , -3.14159265,  0.        ])
        >>> tr.positions("quaternion")[-1].round(6) + 0.0   # half a turn later
        array([2., 0., 0.])
        >>> tr.positions("motor")[-1].round(6) + 0.0
        array([2., 0., 0.])
        """
        spec = self._moving(path)
        s = self.meta.get("centre_of_mass", (0.0, 0.0, 0.0))
        return spec.load().positions(self._arrays[spec.array], s)

    def velocities(self) -> np.ndarray:
        """The body-frame origin's velocity (n, 3) in space (m/s), of the primary path.

        Examples
        --------
        >>> from ga_rotors import RigidBody, simulate
        >>> tr = simulate(RigidBody((1.0, 1.0, 1.0), mass=1.0), [1.0, 0, 0, 0], [0.0, 0, 0],
        ...               duration=1.0, step=0.5, velocity=[1.0, 2.0, 3.0])
        >>> tr.velocities()[-1].tolist()
        [1.0, 2.0, 3.0]
        """
        self._moving(None)
        return self._arrays["velocity"]

    def motors(self, path: str | None = None) -> np.ndarray:
        """The poses (m, 8) of ``path`` (default: the primary one) of a body moving through
        space, as motors T(p) R(q) of Cl(3,0,1) (:mod:`ga_rotors.motor`): the motor path's
        own states, or those of the quaternions and positions of the quaternion path.

        Examples
        --------
        >>> from ga_rotors import RigidBody, simulate
        >>> tr = simulate(RigidBody((1.0, 1.0, 1.0), mass=1.0), [1.0, 0, 0, 0], [0.0, 0, 0],
        ...               duration=1.0, step=0.5, velocity=[2.0, 0.0, 0.0],
        ...               paths=("motor", "quaternion"))
        >>> tr.motors("quaternion")[-1].tolist()            # at x = 2: T = 1 − ½ e0 t
        [1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        """
        spec = self._moving(path)
        if spec.array == "motor":
            return self._arrays["motor"]
        from .motor import from_pose
        from .quaternion import normalize

        return from_pose(normalize(self.quaternions(path)), self.positions(path))

    def velocity_lines(self) -> np.ndarray:
        """The velocity lines (n, 6) of the primary path of a body moving through space,
        in space: M B M̃ with B = −I₃ω − e0 v the body-frame velocity line
        (:func:`ga_rotors.motor.velocity_line`), on the blades (e01, e02, e03, e12, e13,
        e23). Its direction is the space angular velocity; its axis, the instantaneous
        screw axis the body turns about and slides along (what a view draws).

        Examples
        --------
        A body at rest on (1, 0, 0) turning about the z axis through that point: its
        velocity line is the axis, −(the line through (1, 0, 0) along z).

        >>> from ga_rotors import RigidBody, motor, simulate
        >>> tr = simulate(RigidBody((1.0, 1.0, 1.0), mass=1.0), [1.0, 0, 0, 0], [0, 0, 2.0],
        ...               duration=1.0, step=0.01, sample_every=50, position=[1.0, 0.0, 0.0])
        >>> B = tr.velocity_lines()[-1]
        >>> point, direction = motor.line_coordinates(-B / 2.0)
        >>> point.round(12) + 0.0, direction.round(12) + 0.0
        (array([1., 0., 0.]), array([0., 0., 1.]))
        """
        from . import motor
        from .quaternion import conjugate, normalize, rotate

        self._moving(None)
        n = self.w.shape[0]
        q = normalize(self.quaternions()[:n])
        body_v = rotate(conjugate(q), self._arrays["velocity"][:n])
        moving = motor.normalize(self.motors()[:n])  # a path's own drift off unit norm aside
        return motor.sandwich_line(moving, motor.velocity_line(self.w, body_v))

    def rotors(self, path: str | None = None):
        """The orientation of ``path`` as clifford rotors of Cl(3,0).

        R = w − x e23 − y e31 − z e12 for each quaternion of :meth:`quaternions`, acting
        as v ↦ R v R̃ (``docs/conventions.md``).

        Returns
        -------
        clifford.MVArray (m,)
            One :class:`clifford.MultiVector` per sample; index it like a list, or use
            ``.value`` for the (m, 8) coefficients on all eight blades.

        Examples
        --------
        >>> import math
        >>> from ga_rotors import simulate
        >>> tr = simulate((1.0, 1.0, 1.0), [1.0, 0, 0, 0], [0.0, 0.0, math.pi / 2],
        ...               duration=1.0, step=0.01, paths="quaternion")
        >>> R = tr.rotors()[-1]
        >>> R
        0.70711 - (0.70711^e12)
        >>> from ga_rotors import rotor
        >>> rotor.apply(R, [1.0, 0.0, 0.0]).round(9).tolist()   # x turns to y
        [0.0, 1.0, 0.0]
        """
        from clifford import MultiVector, MVArray

        from .isomorphism import to_even
        from .rotor import layout

        coefficients = to_even(self.quaternions(path))
        return MVArray([MultiVector(layout(), c) for c in coefficients])

    def extended(self, arrays: dict, components: dict | None = None, meta: dict | None = None):
        """This trajectory with more arrays (and meta entries); its orientations, already
        converted, are shared rather than converted again.

        Examples
        --------
        >>> tr = Trajectory({"t": np.array([0.0, 0.5])})
        >>> tr.extended({"energy": np.ones(2)}, meta={"scene": "demo"}).names
        ('t', 'energy')
        """
        out = Trajectory(
            {**self._arrays, **arrays},
            {**self.components, **(components or {})},
            {**self.meta, **(meta or {})},
        )
        out._quaternions = self._quaternions
        return out

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the arrays present, in insertion order."""
        return tuple(self._arrays)

    def __getattr__(self, name: str) -> np.ndarray:
        arrays = self.__dict__.get("_arrays", {})
        if name in arrays:
            return arrays[name]
        hint = ""
        if name == "R":  # the rotor path's raw state was once exposed under this name
            hint = (
                "; the orientation is tr.quaternions() (w, x, y, z) or tr.rotors() (clifford), "
                "the rotor path's raw blade coefficients are tr['rotor_blades']"
            )
        raise AttributeError(
            f"trajectory has no array {name!r}; it has {', '.join(arrays) or 'none'} "
            f"(only requested paths and outputs are computed){hint}"
        )

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._arrays[name]
        except KeyError:
            raise KeyError(
                f"trajectory has no array {name!r}; it has {', '.join(self._arrays)}"
            ) from None

    def __contains__(self, name: str) -> bool:
        return name in self._arrays

    def __len__(self) -> int:
        return self._arrays["t"].shape[0]

    def _repr_html_(self) -> str:
        from .view.tables import trajectory_html  # notebook display

        return trajectory_html(self)

    def view(self, **kwargs):
        """An interactive page of this run (:class:`ga_rotors.view.View`).

        In Jupyter the returned view displays itself inline; ``.save(path)`` writes the
        self-contained page. Keywords as for :func:`ga_rotors.view.from_trajectory`.

        Examples
        --------
        >>> from ga_rotors import simulate
        >>> tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.1, 0.0, 1.0], duration=0.5,
        ...               step=0.1)
        >>> tr.view(title="disk")
        View('disk', paths=rotor, 6 samples)
        """
        from .view import View

        return View.from_trajectory(self, **kwargs)

    def __repr__(self) -> str:
        shapes = ", ".join(f"{k}{tuple(v.shape)}" for k, v in self._arrays.items())
        return f"Trajectory({shapes})"

    def columns(self) -> list[tuple[str, str, int | None]]:
        """(column header, array name, component index or None), in CSV order."""
        out = []
        for name, a in self._arrays.items():
            if a.ndim == 1:
                out.append((name, name, None))
                continue
            labels = self.components.get(name) or tuple(str(i) for i in range(a.shape[1]))
            if len(labels) != a.shape[1]:
                raise InputError(f"components of {name}: {len(labels)} labels for {a.shape[1]}")
            out.extend((f"{name}_{lab}", name, i) for i, lab in enumerate(labels))
        return out

    def to_csv(self, path=None) -> str | Path:
        """Write every array as CSV columns, the unit in each header, and the columns'
        units and the run's attributes (the body frame among them) in a W3C CSVW metadata
        file beside it (``<path>-metadata.json``): both, or neither, written.

        The first line holds the headers (``q_w [1]``, ``w_1 [rad/s]``...), then a row per
        sample; each value is the shortest text that reads back as the same float64;
        cells past the end of a shorter array are empty. Without ``path``, return the CSV
        text. This is :func:`ga_rotors.results.write_csv` (read it back with
        ``pandas.read_csv(path)``, ``polars.read_csv(path)`` or ``numpy.loadtxt(path,
        delimiter=",", skiprows=1)``).

        Examples
        --------
        >>> tr = Trajectory({"t": np.array([0.0, 0.1])}, meta={"integrator": "rk4"})
        >>> print(tr.to_csv().replace("0.0", "0"), end="")
        t [s]
        0
        0.1
        """
        from .results.table import write_csv

        return write_csv(self, path)

    def to_npz(self, path) -> Path:
        """Write every array, the component labels and the run's attributes (its
        ``attributes.json`` member) to a ``.npz`` file, atomically
        (:func:`ga_rotors.results.npz.write_npz`).

        Examples
        --------
        >>> import tempfile, pathlib
        >>> tr = Trajectory({"t": np.arange(3.0)})
        >>> p = tr.to_npz(pathlib.Path(tempfile.mkdtemp()) / "run.npz")
        >>> sorted(np.load(p).files)
        ['attributes.json', 't']
        """
        from .results.npz import write_npz

        return write_npz(self, path)
