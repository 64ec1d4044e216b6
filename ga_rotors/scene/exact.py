"""The exact solution that applies to a scene, in the scene's own time and space frame.

:func:`applicable` decides which solution applies to a body and its effects (``Scene.exact``,
with its reason when none does); :func:`build` builds the reference model from the scene's
derived values, and :class:`Exact` then answers in the scene's absolute times and space
frame. ``Scene.exact_solution`` calls it at most once per scene; a reference that refuses
the state becomes one scene error (:func:`refusal`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import quaternion as Q
from .._jit import jit
from .._quaternion_loops import largest_distance_loop
from .._validate import UNIT_TOLERANCE
from ..errors import PrecisionError, SceneError

__all__ = ["MAX_BOUND", "Exact", "applicable", "build", "refusal"]

#: The largest rounding-error bound (rad) a scene accepts from its exact reference. A
#: reference called directly refuses beyond 1e-10 rad, which the heavy top's bound passes
#: after about 560 s; a scene's long run instead takes the reference's values with their
#: bound and states it (the summary, the data files' ``exact_error_bound``), so its error
#: columns are exact to within that bound.
MAX_BOUND = 1e-6


@dataclass
class Exact:
    """An exact solution in the scene's terms: absolute times, the scene's space frame.

    ``model`` is the reference object (times from the initial state, and for the heavy
    top a space frame with gravity along −z); ``frame`` is G, the rotation taking the
    scene's space frame to the model's (None: the same).

    :attr:`ga_rotors.scene.Scene.exact_solution` builds one (once per scene).

    Examples
    --------
    >>> from ga_rotors.scene import load_scene
    >>> scene = load_scene("spinning_disk")
    >>> exact = scene.exact_solution
    >>> exact.name, exact.frame, exact.has_orientation
    ('symmetric_top', None, True)
    >>> exact.orientation_error([0.0], scene.orientation)  # the initial state itself
    array([0.])
    >>> load_scene("heavy_top").exact_solution.frame  # gravity already along −z
    array([1., 0., 0., 0.])
    """

    name: str
    model: object
    t0: float
    frame: np.ndarray | None = None
    has_orientation: bool = True

    def angular_velocity(self, t) -> np.ndarray:
        """Exact body angular velocity (n, 3) at absolute times ``t``."""
        if hasattr(self.model, "angular_velocity"):
            return self.model.angular_velocity(np.asarray(t, dtype=np.float64) - self.t0)
        return self.state(t)[1]

    def orientations(self, t) -> np.ndarray:
        """Exact orientations (n, 4) at absolute times ``t``, in the scene's space frame."""
        return self.state(t)[0]

    def orientation_error(self, t, q) -> np.ndarray:
        """Geodesic angle (rad) from orientations ``q`` (n, 4) to the exact ones at ``t``."""
        return np.atleast_1d(Q.distance(self.orientations(t), q))

    def state(self, t) -> tuple[np.ndarray | None, np.ndarray, np.ndarray | None]:
        """Orientations (n, 4) in the scene's space frame (None without them), body
        angular velocities (n, 3) and the reference's rounding-error bound (n,) in rad
        (None for a closed form without one) at absolute times ``t``.

        A reference with a bound is evaluated up to :data:`MAX_BOUND` (a long run's bound
        grows with time); beyond it, or where its values are not finite, it refuses
        (:class:`ga_rotors.errors.PrecisionError`).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> q, w, bound = load_scene("heavy_top").exact_solution.state([0.0, 1000.0])
        >>> q.shape, w.shape, bool(1e-10 < bound[1] < 1e-9)   # beyond the reference's default
        ((2, 4), (2, 3), True)
        """
        t = np.asarray(t, dtype=np.float64) - self.t0
        if hasattr(self.model, "state"):
            try:
                s = self.model.state(t, max_error=MAX_BOUND)
            except PrecisionError as exc:
                if exc.bound is None:
                    raise
                # a scene has no max_error to raise: say what the scene can change
                later = t[np.argmax(np.abs(t))] + self.t0 if t.size else self.t0
                raise PrecisionError(
                    f"the {self.name} reference's rounding-error bound reaches "
                    f"{exc.bound:.3g} rad by t = {later:g} s, beyond the {MAX_BOUND:g} rad a "
                    "scene measures its error to; shorten time.duration to have it",
                    bound=exc.bound,
                ) from None
            q, w, bound = s.q, s.w, s.error
        elif self.has_orientation:
            (q, w), bound = self.model.at(t), None
        else:
            q, w, bound = None, self.model.angular_velocity(t), None
        # G* ⊗ q; the identity (a heavy top whose gravity is already along −z) is skipped:
        # its product is q itself, bit for bit
        if q is not None and self.frame is not None and not _is_identity(self.frame):
            q = Q.multiply(Q.conjugate(self.frame), q)
        return q, w, bound

    def errors(self, t, w=None, orientations=None):
        """|ω − ω_exact| for body rates ``w`` (n, 3) and the geodesic error of each array
        of unit orientations in ``orientations`` (name -> (m, 4)), from one evaluation of
        the reference at the first rows of ``t``: a path that stopped early has fewer
        rows and is compared with the reference at its own times.

        Returns
        -------
        (ndarray or None, dict of name -> ndarray)
            The ω error (None when ``w`` is None) and each orientation's error.

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> exact = load_scene("spinning_disk").exact_solution
        >>> q, w, _ = exact.state([0.0, 0.5, 1.0])
        >>> dw, dq = exact.errors([0.0, 0.5, 1.0], w, {"rotor": q[:2]})
        >>> dw.tolist(), dq["rotor"].tolist()
        ([0.0, 0.0, 0.0], [0.0, 0.0])
        """
        orientations = orientations or {}
        found = self._reference_rows(t, w, orientations)
        if found is None:  # nothing to compare: the reference is not evaluated at all
            return (None if w is None else np.empty(0)), {n: np.empty(0) for n in orientations}
        q_ref, w_ref = found
        dw = None
        if w is not None:  # |w − w_ref| row by row, without the difference array
            dw = np.empty(w.shape[0])
            _rate_error_loop(np.ascontiguousarray(w, dtype=np.float64), w_ref, dw)
        dq = {
            name: np.atleast_1d(Q.distance(q_ref[: q.shape[0]], q))
            for name, q in orientations.items()
        }
        return dw, dq

    def largest_errors(self, t, w=None, orientations=None):
        """The largest values of :meth:`errors` (what a run's summary prints), without the
        per-sample arrays: equal to ``errors(...)``'s maxima bit for bit, from one
        evaluation of the reference.

        Returns
        -------
        (float or None, dict of name -> float or None)
            The largest ω error and each orientation's largest geodesic error; None for
            no rows (and for ω when ``w`` is None).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> exact = load_scene("spinning_disk").exact_solution
        >>> q, w, _ = exact.state([0.0, 0.5, 1.0])
        >>> exact.largest_errors([0.0, 0.5, 1.0], w, {"rotor": q[:2]})
        (0.0, {'rotor': 0.0})
        """
        orientations = orientations or {}
        found = self._reference_rows(t, w, orientations)
        if found is None:
            return None, {n: None for n in orientations}
        q_ref, w_ref = found
        dw = None
        if w is not None and w.shape[0]:
            dw = _largest_rate_error(np.ascontiguousarray(w, dtype=np.float64), w_ref)
        dq = {}
        for name, q in orientations.items():
            q = np.ascontiguousarray(q, dtype=np.float64)
            if not q.shape[0]:
                dq[name] = None
                continue
            largest, _, ok = largest_distance_loop(q_ref, q, UNIT_TOLERANCE)
            # a non-unit or non-finite orientation: as Q.distance says (raises or nan)
            dq[name] = largest if ok else float(np.max(Q.distance(q_ref[: q.shape[0]], q)))
        return dw, dq

    def _reference_rows(self, t, w, orientations: dict):
        """The reference's (q, ω) at as many first rows of ``t`` as the longest of ``w``
        and ``orientations`` has (None if none has a row): one evaluation for all."""
        sizes = [q.shape[0] for q in orientations.values()]
        rows = max([0 if w is None else w.shape[0], *sizes])
        if rows == 0:
            return None
        q_ref, w_ref, _ = self.state(np.asarray(t, dtype=np.float64)[:rows])
        return q_ref, w_ref

    def bound(self, t) -> float | None:
        """The reference's largest rounding-error bound (rad) at absolute times ``t`` (None
        for a closed form without one, or no times).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> load_scene("heavy_top").exact_solution.bound([0.0, 1.0]) < 1e-12
        True
        >>> load_scene("damped_top").exact_solution.bound([0.0]) is None
        True
        """
        t = np.atleast_1d(np.asarray(t, dtype=np.float64))
        if t.size == 0 or not hasattr(self.model, "state"):
            return None
        return float(np.max(self.state(t)[2]))


def _is_identity(q) -> bool:
    return bool(q[0] == 1.0 and q[1] == 0.0 and q[2] == 0.0 and q[3] == 0.0)


@jit
def _rate_error_squared(w, w_ref, n):
    """|w[n] − w_ref[n]|², summed as numpy's norm of the difference sums it."""
    dx, dy, dz = w[n, 0] - w_ref[n, 0], w[n, 1] - w_ref[n, 1], w[n, 2] - w_ref[n, 2]
    return dx * dx + dy * dy + dz * dz


@jit
def _rate_error_loop(w, w_ref, out):
    """out[n] = |w[n] − w_ref[n]| (as numpy's norm of the difference)."""
    for n in range(out.shape[0]):
        out[n] = math.sqrt(_rate_error_squared(w, w_ref, n))


@jit
def _largest_rate_error(w, w_ref):
    """max over rows of |w − w_ref| (:func:`_rate_error_loop`'s values): the largest
    square, then its root (√ is monotone and correctly rounded); nan if any row is."""
    best, nan_seen = 0.0, False
    for n in range(w.shape[0]):
        square = _rate_error_squared(w, w_ref, n)
        if square != square:
            nan_seen = True
        elif square > best:
            best = square
    return math.nan if nan_seen else math.sqrt(best)


def build(name: str | None, body, q0, w0, t0: float, gravity=None, damping=None) -> Exact | None:
    """The exact solution called ``name`` for this initial state, or None when ``name`` is.

    Parameters
    ----------
    name : {"symmetric_top", "asymmetric_top", "heavy_top", "damped_symmetric_top"} or None
    body : RigidBody
        The scene's body (:attr:`Scene.body`, with its principal rotation: the reference
        takes and gives states in the scene's body frame, and solves in the principal one).
    q0, w0 : array_like
        Initial orientation (4,) and body angular velocity (3,), the scene's body frame.
    t0 : float
        Initial time (s).
    gravity : (weight, r), optional
        The heavy top's weight m g (space) and pivot -> centre of mass (principal frame).
    damping : float, optional
        The damped top's isotropic coefficient c.

    Raises
    ------
    InputError
        From the reference, when the state is outside its domain, e.g. a heavy top whose
        symmetry axis starts vertical.

    Examples
    --------
    >>> from ga_rotors.body import RigidBody
    >>> exact = build("symmetric_top", RigidBody((1.0, 1.0, 2.0)), [1.0, 0, 0, 0],
    ...               [0.0, 0.0, 1.0], 0.0)
    >>> exact.orientations([2.0]).round(12).tolist()   # a steady 2 rad turn about z
    [[0.540302305868, 0.0, 0.0, 0.841470984808]]
    """
    if name == "symmetric_top":
        from ..reference.symmetric_top import SymmetricTop

        return Exact(name, SymmetricTop(body, q0, w0), t0)
    if name == "asymmetric_top":
        from ..reference.asymmetric_top import AsymmetricTop

        return Exact(name, AsymmetricTop(body, q0, w0), t0)
    if name == "heavy_top":
        from ..reference.heavy_top import HeavyTop

        weight, r = gravity
        frame = Q.from_two_vectors(weight, np.array([0.0, 0.0, -1.0]))
        mgl = float(np.linalg.norm(weight) * r[2])
        return Exact(name, HeavyTop(body, mgl, Q.multiply(frame, q0), w0), t0, frame)
    if name == "damped_symmetric_top":
        from ..reference.damped_top import DampedSymmetricTop

        model = DampedSymmetricTop(body, damping, q0, w0)
        return Exact(name, model, t0, has_orientation=model.spherical)
    return None


def applicable(body, effects, gravity=None) -> tuple[str | None, str]:
    """(name of the exact solution that applies, or None; and why, or why not).

    Parameters
    ----------
    body : RigidBody
        The body (its principal moments decide).
    effects : list of dict
        The scene's resolved effects.
    gravity : (weight, r), optional
        The gravity effect's weight and pivot -> centre of mass (principal frame).

    Examples
    --------
    >>> from ga_rotors.body import RigidBody
    >>> applicable(RigidBody((1.0, 2.0, 3.0)), [])
    ('asymmetric_top', 'torque-free, three distinct moments: Jacobi functions')
    >>> applicable(RigidBody((1.0, 2.0, 3.0)), [{"type": "damping", "coefficient": 0.1}])
    (None, 'isotropic damping has an exact solution only for a symmetric top')
    """
    i1, i2, _ = body.moments
    if not effects:
        if body.is_symmetric:
            return "symmetric_top", "torque-free, two equal moments: closed form"
        return "asymmetric_top", "torque-free, three distinct moments: Jacobi functions"
    types = [e["type"] for e in effects]
    if types == ["damping"] and not isinstance(effects[0]["coefficient"], list):
        if body.is_symmetric:
            return "damped_symmetric_top", "isotropic damping of a symmetric top"
        return None, "isotropic damping has an exact solution only for a symmetric top"
    if types == ["gravity"]:
        r = gravity[1]
        if i1 == i2 and r[0] == r[1] == 0.0 and r[2] > 0.0:
            return "heavy_top", "gravity on a symmetric top, centre of mass on its axis"
        return None, (
            "gravity has an exact (Lagrange) solution only for I1 = I2 about the pivot "
            "with the centre of mass on the body +z axis"
        )
    from ..effects import listed

    return None, f"no exact solution is known to ga_rotors for effects {listed(types)}"


#: The scene key an exact reference's refused argument comes from (the state otherwise).
_REFERENCE_KEYS = {
    "moments": "body",
    "body": "body",
    "orientation": "initial.orientation",
    "q": "initial.orientation",
    "angular_velocity": "initial.angular_velocity",
}


def refusal(file: str, name: str, exc: Exception) -> SceneError:
    """The scene error for a reference that refuses the scene's body or state (outside its
    domain or its accuracy): one line naming the file and the key the refused value came
    from, with the reference's reason.

    Examples
    --------
    >>> from ga_rotors.errors import InputError
    >>> print(refusal("top.toml", "heavy_top", InputError("axis vertical", key="orientation")))
    top.toml: initial.orientation: no exact heavy_top solution: axis vertical
    """
    key = _REFERENCE_KEYS.get(getattr(exc, "key", None), "initial")
    detail = getattr(exc, "detail", None) or str(exc)
    return SceneError(file, key, f"no exact {name} solution: {detail}")
