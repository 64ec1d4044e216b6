"""Symbols, derived reference forms and evidence helpers shared by the audit entries.

Every reference form here is derived (from the Hamilton table, the rotor algebra or
rotation matrices), and the expensive ones are cached so the whole audit derives each
only once per process.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache

import sympy

from .. import hamilton, rotations, trig
from ..derivation import Step, show, step

__all__ = [
    "ANGLES",
    "ANGLE_SAMPLE",
    "OMEGA",
    "PHI",
    "PHID",
    "PSI",
    "PSID",
    "Q0",
    "Q1",
    "Q2",
    "Q3",
    "Q_SAMPLE",
    "RATES",
    "RATE_NAMES",
    "THETA",
    "THETAD",
    "WX",
    "WY",
    "WZ",
    "P",
    "Q",
    "V",
    "c2",
    "matrix_str",
    "numeric",
    "on_unit_sphere",
    "polys_equal",
    "s2",
    "unit_matrices_equal",
    "zyz_body_rates",
    "zyz_consistent",
    "zyz_matrix",
    "zyz_quaternion",
]


# The paper's Euler angles (ψ precession, θ nutation, φ spin) and their rates.
PSI, THETA, PHI = sympy.symbols("ψ θ φ", real=True)
ANGLES = (PSI, THETA, PHI)
RATE_NAMES = ("ψ̇", "θ̇", "φ̇")
PSID, THETAD, PHID = sympy.symbols(RATE_NAMES, real=True)
RATES = (PSID, THETAD, PHID)
# Body angular velocity components (ωx3, ωy3, ωz3) and a vector v.
WX, WY, WZ = sympy.symbols("ωx ωy ωz", real=True)
OMEGA = (WX, WY, WZ)
V = sympy.symbols("v1:4", real=True)
Q = hamilton.symbols("q")
Q0, Q1, Q2, Q3 = Q
P = hamilton.symbols("p")

#: A fixed, exactly unit quaternion for counterexamples: (1, 2, 3, 4)/√30 -> rational
#: squares make every matrix entry rational.
Q_SAMPLE = tuple(sympy.Rational(c) / sympy.sqrt(30) for c in (1, 2, 3, 4))
#: Fixed Euler angles for counterexamples (radians), chosen with no symmetry.
ANGLE_SAMPLE = {PSI: sympy.Rational(3, 10), THETA: sympy.Rational(1, 2), PHI: sympy.Rational(7, 10)}


def c2(a):
    """cos(a/2): the notes' shorthand ``cos_2 a``.

    Examples
    --------
    >>> c2(PSI), c2(sympy.pi / 2)
    (cos(ψ/2), sqrt(2)/2)
    """
    return sympy.cos(a / 2)


def s2(a):
    """sin(a/2): the notes' shorthand ``sin_2 a``.

    Examples
    --------
    >>> s2(THETA), s2(sympy.pi / 3)
    (sin(θ/2), 1/2)
    """
    return sympy.sin(a / 2)


@cache
def zyz_quaternion() -> hamilton.Quat:
    """q_z(ψ) q_y(θ) q_z(φ): intrinsic z-y'-z'', body to space.

    Examples
    --------
    >>> w = zyz_quaternion()[0]
    >>> w
    -sin(φ/2)*sin(ψ/2)*cos(θ/2) + cos(θ/2)*cos(φ/2)*cos(ψ/2)
    >>> trig.is_identity(w, c2(THETA) * c2(PSI + PHI))  # w = cos(θ/2) cos((ψ + φ)/2)
    True
    """
    return rotations.euler_quaternion("ZYZ", ANGLES)


@cache
def zyz_matrix() -> sympy.Matrix:
    """Rz(ψ) Ry(θ) Rz(φ): the same rotation as a matrix, body to space (active).

    Examples
    --------
    >>> m = zyz_matrix()
    >>> m[2, 2], m[0, 2]  # the body z axis in space: nutation θ, precession ψ
    (cos(θ), sin(θ)*cos(ψ))
    """
    return rotations.euler_matrix("ZYZ", ANGLES)


@cache
def zyz_consistent() -> Step:
    """Our own check: the quaternion and matrix constructions of z-y'-z'' agree.

    Examples
    --------
    >>> zyz_consistent().holds
    True
    """
    return step(
        "M(q_z(ψ) q_y(θ) q_z(φ)) = Rz(ψ) Ry(θ) Rz(φ) (quaternion and matrix routes agree)",
        "entry-wise trigonometric identity",
        trig.matrices_equal(hamilton.rotation_matrix(zyz_quaternion()), zyz_matrix()),
    )


@cache
def zyz_body_rates() -> tuple[tuple[sympy.Expr, ...], Step]:
    """ω in the body frame from the Euler rates, derived three ways that must agree:
    the axis-by-axis closed form, [ω]× = Rᵀ Ṙ, and (0, ω) = 2 q* q̇.

    Examples
    --------
    >>> omega, check = zyz_body_rates()
    >>> omega
    (θ̇*sin(φ) - ψ̇*sin(θ)*cos(φ), θ̇*cos(φ) + ψ̇*sin(θ)*sin(φ), φ̇ + ψ̇*cos(θ))
    >>> check.holds
    True
    """
    omega = rotations.body_rates_by_axes("ZYZ", ANGLES, RATES)
    omega_m = rotations.body_rates_from_matrix("ZYZ", ANGLES, RATES)
    omega_q, scalar = rotations.body_rates_from_quaternion("ZYZ", ANGLES, RATES)
    agree = trig.all_identities(omega, omega_m) and trig.all_identities(omega, omega_q)
    check = step(
        "body ω from Euler rates: the axis sum, [ω]× = Rᵀ Ṙ and (0, ω) = 2 q* q̇ agree",
        "ω = " + show(omega) + "; the scalar part of 2 q* q̇ vanishes",
        agree and trig.is_zero(scalar),
    )
    return omega, check


def numeric(expr, point: dict, digits: int = 6) -> str:
    """``expr`` at ``point``, evaluated to ``digits`` significant digits, as text.

    Examples
    --------
    >>> numeric(sympy.cos(THETA), ANGLE_SAMPLE)  # θ = 1/2
    '0.877583'
    >>> numeric(sympy.sqrt(2), {}, digits=3)
    '1.41'
    """
    return sympy.sstr(sympy.N(sympy.sympify(expr).subs(point), digits))


def polys_equal(a: Sequence, b: Sequence) -> bool:
    """Exact polynomial equality of two sequences of expressions.

    Examples
    --------
    >>> polys_equal(hamilton.add(P, Q), hamilton.add(Q, P))
    True
    >>> polys_equal(hamilton.mul(P, Q), hamilton.mul(Q, P))  # Hamilton's product
    False
    """
    return all(sympy.expand(x - y) == 0 for x, y in zip(a, b, strict=True))


def matrix_str(m: sympy.Matrix) -> str:
    """A matrix on one line, rows separated by ';', entries rendered by ``show``.

    Examples
    --------
    >>> matrix_str(sympy.Matrix([[1, PSI**2], [0, sympy.cos(THETA)]]))
    '[1, ψ²; 0, cos(θ)]'
    """
    return "[" + "; ".join(", ".join(show(x) for x in m.row(r)) for r in range(m.rows)) + "]"


def on_unit_sphere(expr, q=Q) -> sympy.Expr:
    """Remainder of expr modulo q0² + q1² + q2² + q3² − 1 (zero iff it vanishes for unit q).

    The divisor is monic in q0, so the remainder is canonical (degree ≤ 1 in q0).

    Examples
    --------
    >>> on_unit_sphere(hamilton.norm2(Q))
    1
    >>> on_unit_sphere(Q0**2)
    -q1**2 - q2**2 - q3**2 + 1
    """
    return sympy.expand(sympy.rem(sympy.expand(expr), hamilton.norm2(q) - 1, q[0]))


def unit_matrices_equal(a: sympy.Matrix, b: sympy.Matrix) -> bool:
    """Entry-wise equality for every unit q.

    Examples
    --------
    >>> m = hamilton.rotation_matrix(Q)
    >>> m[0, 0]
    q0**2 + q1**2 - q2**2 - q3**2
    >>> unit_matrices_equal(m[:1, :1], sympy.Matrix([[1 - 2 * (Q2**2 + Q3**2)]]))
    True
    >>> polys_equal(m[:1, :1], [1 - 2 * (Q2**2 + Q3**2)])  # only on |q| = 1
    False
    """
    return all(on_unit_sphere(x - y) == 0 for x, y in zip(a, b, strict=True))
