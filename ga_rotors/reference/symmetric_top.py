r"""The torque-free symmetric top in closed form.

Two equal principal moments :math:`I_\perp` and a distinct :math:`I_k` about body axis
:math:`k` (x, y or z). With :math:`L_s = q_0 (\mathsf{I}\omega_0) q_0^*` the space-frame
angular momentum (constant) and :math:`L_k = I_k \omega_k(0)`:

.. math::

    q(t) = \operatorname{Exp}(t L_s / I_\perp) \otimes q_0 \otimes \operatorname{Exp}(t \nu e_k),
    \qquad \nu = \Bigl(\frac{1}{I_k} - \frac{1}{I_\perp}\Bigr) L_k

with :math:`\operatorname{Exp}(v)` the unit quaternion of rotation vector :math:`v`.
Derivation: :math:`A(t) = \operatorname{Exp}(t L_s/I_\perp)` and
:math:`B(t) = \operatorname{Exp}(t \nu e_k)` give
:math:`\dot q = \tfrac12\, q \otimes (0, q^* (L_s/I_\perp) q + \nu e_k)`. Since :math:`A`
fixes :math:`L_s` and :math:`B` rotates about :math:`e_k`, the body momentum
:math:`L_b = q^* L_s q = B^* L_b(0) B` keeps its :math:`k` component :math:`L_k`, so the
bracket is :math:`L_b/I_\perp + (1/I_k - 1/I_\perp) L_k e_k = \mathsf{I}^{-1} L_b = \omega`:
the orientation obeys :math:`\dot q = \tfrac12\, q \otimes (0, \mathsf{I}^{-1} q^* L_s q)`
with :math:`L_s` fixed, which is exactly torque-free motion (Euler's equations plus the
kinematics). The body rate :math:`\omega(t) = \mathsf{I}^{-1} L_b(t)` is the transverse
part of :math:`\omega_0` turning about :math:`e_k` at rate :math:`-\nu`, with
:math:`\omega_k` constant.

A body given by a rotated tensor (:meth:`ga_rotors.body.RigidBody.from_tensor`) is solved
in its principal frame and answered in the user's body frame, as ``simulate`` integrates
it (:meth:`~ga_rotors.body.RigidBody.to_principal`).

Accuracy: every angle is formed as :math:`t \cdot \text{rate}` and reduced by sin/cos once,
so the result is exact to a few ulp of the total turned angle
(:math:`\lvert L_s\rvert t/I_\perp \approx 314` rad in the paper's 10 s run: ~1e-13 rad).
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from .._kernels import qconj, qmul, qrotate, quat_from_rotvec
from .._validate import as_float_array, require_unit
from ..body import RigidBody
from ..errors import InputError

__all__ = ["SymmetricTop", "symmetry_axis"]


@jit
def _orientations(t, q0, ls, inv_perp, nu, k, out_q, out_w, inertia):
    for n in range(t.shape[0]):
        s = t[n]
        a = quat_from_rotvec((s * ls[0] * inv_perp, s * ls[1] * inv_perp, s * ls[2] * inv_perp))
        spin = [0.0, 0.0, 0.0]
        spin[k] = s * nu
        b = quat_from_rotvec((spin[0], spin[1], spin[2]))
        q = qmul(qmul(a, q0), b)
        lb = qrotate(qconj(q), ls)
        out_q[n, 0] = q[0]
        out_q[n, 1] = q[1]
        out_q[n, 2] = q[2]
        out_q[n, 3] = q[3]
        out_w[n, 0] = lb[0] / inertia[0]
        out_w[n, 1] = lb[1] / inertia[1]
        out_w[n, 2] = lb[2] / inertia[2]


def symmetry_axis(moments) -> int:
    """The index k of a symmetric top's distinct moment (2 for a sphere), or InputError.

    Examples
    --------
    >>> symmetry_axis((0.0056, 0.0028, 0.0028)), symmetry_axis((1.0, 1.0, 1.0))
    (0, 2)
    """
    i1, i2, i3 = moments
    if i1 == i2:
        return 2
    if i2 == i3:
        return 0
    if i1 == i3:
        return 1
    raise InputError(
        f"body: moments {tuple(moments)} have no two exactly equal; the closed forms are for "
        "symmetric tops (use ga_rotors.reference.asymmetric_top)"
    )


class SymmetricTop:
    """Exact torque-free motion of a body with two equal principal moments.

    Parameters
    ----------
    body : RigidBody or array_like (3,)
        Principal moments; two must be exactly equal (a sphere, all equal, is allowed). A
        RigidBody's ``principal_rotation`` is honoured: orientation and angular velocity,
        given and returned, are those of the user's body frame.
    orientation : array_like (4,)
        Initial body->space unit quaternion.
    angular_velocity : array_like (3,)
        Initial body-frame ω.

    Attributes
    ----------
    axis : int
        The symmetry axis k in the principal frame.
    nu : float
        ν, the body-frame precession rate about the symmetry axis.
    space_momentum : ndarray (3,)
        L_s, the constant space-frame angular momentum.

    Examples
    --------
    A disk spinning about its symmetry axis z with a small wobble:

    >>> from ga_rotors import shapes
    >>> top = SymmetricTop(shapes.disk(2.0, 0.075), [1.0, 0, 0, 0], [0.1, 0.0, 15.0])
    >>> top.axis, round(top.nu, 12)
    (2, -15.0)
    >>> q, w = top.at([0.0, 1.0])
    >>> w[:, 2].tolist()                       # ω along the symmetry axis is constant
    [15.0, 15.0]
    """

    def __init__(self, body, orientation, angular_velocity):
        self.body = body if isinstance(body, RigidBody) else RigidBody(body)
        moments = self.body.moments
        k = symmetry_axis(moments)
        q0 = as_float_array(orientation, "orientation", last=4)
        w0 = as_float_array(angular_velocity, "angular_velocity", last=3)
        if q0.shape != (4,) or w0.shape != (3,):
            raise InputError("orientation and angular_velocity: expected shapes (4,) and (3,)")
        self.moments = moments
        self.axis = k
        self.q0 = tuple(float(c) for c in require_unit(q0, "orientation"))
        self.w0 = tuple(float(c) for c in w0)
        qp, wp = self.body.to_principal(self.q0, self.w0)
        self._q0 = tuple(float(c) for c in qp)
        perp = moments[(k + 1) % 3]
        lb0 = tuple(float(m * w) for m, w in zip(moments, wp, strict=True))
        self.space_momentum = np.array(qrotate(self._q0, lb0))
        self.nu = (1.0 / moments[k] - 1.0 / perp) * lb0[k]
        self._inv_perp = 1.0 / perp

    def at(self, t) -> tuple[np.ndarray, np.ndarray]:
        """Orientations (n, 4) and body angular velocities (n, 3) at times ``t`` (s).

        Times are measured from the initial state.
        """
        t = np.ascontiguousarray(as_float_array(t, "t").reshape(-1))
        q = np.empty((t.shape[0], 4))
        w = np.empty((t.shape[0], 3))
        _orientations(
            t, self._q0, tuple(self.space_momentum), self._inv_perp, self.nu, self.axis, q, w,
            self.moments,
        )  # fmt: skip
        return self.body.from_principal(q, w)

    def orientation_error(self, t, q) -> np.ndarray:
        """Geodesic angle (rad) between orientations ``q`` (n, 4) and the exact ones at ``t``.

        Examples
        --------
        >>> top = SymmetricTop((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.3, 0.0, 1.0])
        >>> q, _ = top.at([0.5, 1.0])
        >>> top.orientation_error([0.5, 1.0], q).tolist()
        [0.0, 0.0]
        """
        from ..quaternion import distance

        ref, _ = self.at(t)
        q = as_float_array(q, "q", last=4).reshape(-1, 4)
        if q.shape != ref.shape:
            raise InputError(f"q: expected {ref.shape[0]} orientations, got shape {q.shape}")
        return np.atleast_1d(distance(ref, q))
