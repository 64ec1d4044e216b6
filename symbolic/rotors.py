"""Rotors in Cl(3,0) against Hamilton quaternions: the sandwich, its matrix, the kinematics.

The map φ(q) = w - x e23 - y e31 - z e12 (an isomorphism ℍ -> Cl⁺(3,0), see
:mod:`symbolic.isomorphisms`) carries every quaternion statement the numeric package
uses to a rotor statement, and these derivations check the two sides agree exactly:

* R v R̃ = q v q* for every vector v (no unit assumption: both are quadratic in q), and
  its matrix is the familiar M(q); R̃ = φ(q*).
* R = cos(α/2) - I u sin(α/2) rotates by α about the unit vector u (Rodrigues).
* Ṙ = ½ R Ω with Ω = -I ω is φ of q̇ = ½ q (0, ω), and ½(Ω v - v Ω) = ω × v, which is
  what makes ω the body angular velocity: d/dt (R v R̃) = (R ω R̃) × (R v R̃).

Examples
--------
>>> rotor_sandwich().ok
True
>>> rotor_kinematics().ok
True
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy

from . import hamilton, trig
from .derivation import Derivation, show, step
from .isomorphisms import CL3, quaternion_to_rotor, rotor_to_quaternion

__all__ = [
    "E1",
    "E2",
    "E3",
    "PSEUDOSCALAR",
    "Kinematics",
    "Sandwich",
    "axis_angle",
    "dual_bivector",
    "rodrigues_matrix",
    "rotor_kinematics",
    "rotor_sandwich",
    "spherical_unit",
    "unit_rotation_matrix",
    "vector",
    "vector_part",
]


E1, E2, E3 = CL3.basis_vectors()
PSEUDOSCALAR = CL3.pseudoscalar()


def vector(v) -> object:
    """v1 e1 + v2 e2 + v3 e3.

    Examples
    --------
    >>> vector((1, 2, 3))
    e1 + 2*e2 + 3*e3
    """
    return v[0] * E1 + v[1] * E2 + v[2] * E3


def vector_part(m) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """(v1, v2, v3) of the grade-1 part of a Cl(3,0) multivector.

    Examples
    --------
    >>> vector_part(vector((1, 2, 3)) + 5)
    (1, 2, 3)
    """
    return (m[(1,)], m[(2,)], m[(3,)])


def dual_bivector(w):
    """Ω = -I ω = -(ω1 e23 + ω2 e31 + ω3 e12): the bivector of angular velocity ω.

    Examples
    --------
    >>> dual_bivector((0, 0, 2))
    -2*e12
    """
    return -(PSEUDOSCALAR * vector(w))


def unit_rotation_matrix(q) -> sympy.Matrix:
    """The textbook form of M(q) for a unit q (diagonal 1 - 2(y² + z²), ...).

    Examples
    --------
    >>> unit_rotation_matrix((1, 0, 0, 0))
    Matrix([
    [1, 0, 0],
    [0, 1, 0],
    [0, 0, 1]])
    """
    w, x, y, z = q
    return sympy.Matrix(
        [
            [1 - 2 * (y**2 + z**2), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x**2 + z**2), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x**2 + y**2)],
        ]
    )


def rodrigues_matrix(axis, angle) -> sympy.Matrix:
    """cos α I + sin α [u]× + (1 - cos α) u uᵀ: rotation by α about the unit vector u.

    Examples
    --------
    >>> import sympy
    >>> rodrigues_matrix((0, 0, 1), sympy.pi / 2)
    Matrix([
    [0, -1, 0],
    [1,  0, 0],
    [0,  0, 1]])
    """
    u = sympy.Matrix(axis)
    ux = sympy.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return (
        sympy.cos(angle) * sympy.eye(3) + sympy.sin(angle) * ux + (1 - sympy.cos(angle)) * u * u.T
    )


def axis_angle(angle, axis) -> hamilton.Quat:
    """cos(angle/2) + u sin(angle/2): the unit quaternion of a rotation by angle about unit u.

    Examples
    --------
    >>> import sympy
    >>> axis_angle(sympy.pi, (1, 0, 0))
    (0, 1, 0, 0)
    """
    return (sympy.cos(angle / 2), *(c * sympy.sin(angle / 2) for c in axis))


def spherical_unit(lat, lon) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """A general unit vector (cos lat cos lon, cos lat sin lon, sin lat).

    Examples
    --------
    >>> spherical_unit(0, 0)
    (1, 0, 0)
    """
    return (sympy.cos(lat) * sympy.cos(lon), sympy.cos(lat) * sympy.sin(lon), sympy.sin(lat))


@dataclass(frozen=True)
class Sandwich(Derivation):
    """R v R̃ = q v q*, with the matrix M(q) it defines.

    Examples
    --------
    >>> rotor_sandwich().rotor
    'q0 - q3*e12 + q2*e13 - q1*e23'
    """

    rotor: str = ""
    matrix: sympy.Matrix | None = None


@cache
def rotor_sandwich() -> Sandwich:
    """The rotor sandwich equals the quaternion rotation operator, entry by entry.

    Examples
    --------
    >>> rotor_sandwich().matrix[2, 2]
    q0**2 - q1**2 - q2**2 + q3**2
    """
    q = hamilton.symbols("q")
    v = sympy.symbols("v1:4", real=True)
    r = quaternion_to_rotor(q)
    image = r * vector(v) * r.reverse()
    from_quaternion = hamilton.rotate(q, v)
    m = hamilton.rotation_matrix(q)
    m_rotor = sympy.Matrix(3, 3, lambda i, j: sympy.diff(vector_part(image)[i], v[j]))
    norm2 = hamilton.norm2(q)
    alpha, lat, lon = sympy.symbols("alpha lat lon", real=True)
    u = spherical_unit(lat, lon)
    q_axis = axis_angle(alpha, u)
    m_axis = hamilton.rotation_matrix(q_axis)
    steps = (
        step(
            "R̃ = φ(q*): reversing a rotor conjugates its quaternion",
            f"R = {r}\nR̃ = {r.reverse()}",
            r.reverse() == quaternion_to_rotor(hamilton.conj(q)),
        ),
        step(
            "R v R̃ is a pure vector (grades 0, 2, 3 vanish identically)",
            f"grades present: {sorted(image.grades)}",
            image.grades <= {1},
        ),
        step(
            "R v R̃ = q (0, v) q*, component by component, for every q (no unit assumption)",
            "\n".join(f"e{k + 1}: {show(c)}" for k, c in enumerate(vector_part(image))),
            all(
                sympy.expand(a - b) == 0
                for a, b in zip(vector_part(image), from_quaternion, strict=True)
            ),
        ),
        step(
            "its matrix M(q) = ∂(R v R̃)/∂v is the quaternion one",
            f"M = {show(m_rotor)}",
            (m_rotor - m).is_zero_matrix,
        ),
        step(
            "for |q| = 1 it is the textbook form: M - M_unit = (|q|² - 1) I",
            f"M_unit = {show(unit_rotation_matrix(q))}",
            (m - unit_rotation_matrix(q) - (norm2 - 1) * sympy.eye(3))
            .applyfunc(sympy.expand)
            .is_zero_matrix,
        ),
        step(
            "M is a rotation up to scale: Mᵀ M = |q|⁴ I and det M = |q|⁶",
            "expanded exactly",
            (m.T * m - norm2**2 * sympy.eye(3)).applyfunc(sympy.expand).is_zero_matrix
            and sympy.expand(m.det() - norm2**3) == 0,
        ),
        step(
            "q = cos(α/2) + u sin(α/2) (|u| = 1) rotates by α about u: M = Rodrigues",
            "u = (cos lat cos lon, cos lat sin lon, sin lat); entries equal as trig identities",
            trig.matrices_equal(m_axis, rodrigues_matrix(u, alpha)),
        ),
    )
    return Sandwich(
        "Rotor sandwich = quaternion rotation operator",
        "With R = φ(q) = w - x e23 - y e31 - z e12, the rotor action v -> R v R̃ is the "
        "quaternion operator v -> q v q*, and both have the matrix M(q).",
        steps,
        critical=True,
        rotor=str(r),
        matrix=m,
    )


@dataclass(frozen=True)
class Kinematics(Derivation):
    """Ṙ = ½ R Ω  ⟺  q̇ = ½ q (0, ω).

    Examples
    --------
    >>> rotor_kinematics().quaternion_rate[0]
    -omega1*q1/2 - omega2*q2/2 - omega3*q3/2
    """

    rotor_rate: str = ""
    quaternion_rate: tuple[sympy.Expr, ...] = ()


@cache
def rotor_kinematics() -> Kinematics:
    """dR/dt = ½ R Ω with Ω = -Iω is the quaternion kinematics q̇ = ½ q ⊗ (0, ω).

    Examples
    --------
    >>> [s.holds for s in rotor_kinematics().steps]
    [True, True, True, True, True]
    """
    q = hamilton.symbols("q")
    w = sympy.symbols("omega1:4", real=True)
    v = sympy.symbols("v1:4", real=True)
    r = quaternion_to_rotor(q)
    big_omega = dual_bivector(w)
    rotor_rate = r * big_omega / 2
    quat_rate = hamilton.scale(sympy.Rational(1, 2), hamilton.mul(q, hamilton.pure(w)))
    commutator = big_omega.commutator(vector(v))
    cross = sympy.Matrix(w).cross(sympy.Matrix(v))
    # d/dt (R v R̃) with v fixed in the body, Ṙ = ½RΩ and (Ṙ)~ = ½ Ω̃ R̃ = -½ Ω R̃:
    velocity = rotor_rate * vector(v) * r.reverse() + r * vector(v) * rotor_rate.reverse()
    space_w = r * vector(w) * r.reverse()
    space_v = r * vector(v) * r.reverse()
    cross_space = sympy.Matrix(vector_part(space_w)).cross(sympy.Matrix(vector_part(space_v)))
    steps = (
        step(
            "Ω = -I ω = -(ω1 e23 + ω2 e31 + ω3 e12) = φ((0, ω))",
            f"Ω = {big_omega}",
            big_omega == quaternion_to_rotor(hamilton.pure(w)),
        ),
        step(
            "φ⁻¹(½ R Ω) = ½ q ⊗ (0, ω), component by component",
            "\n".join(f"{n}: {show(c)}" for n, c in zip("wxyz", quat_rate, strict=True)),
            hamilton.is_equal(rotor_to_quaternion(rotor_rate), quat_rate),
        ),
        step(
            "½(Ω v - v Ω) = ω × v: the bivector Ω acts on vectors as the cross product by ω",
            f"½(Ωv - vΩ) = {commutator}",
            all(
                sympy.expand(a - b) == 0
                for a, b in zip(vector_part(commutator), cross, strict=True)
            )
            and commutator.grades <= {1},
        ),
        step(
            "so a body-fixed v moves as d/dt(R v R̃) = (R ω R̃) × (R v R̃): ω is the body "
            "angular velocity",
            "|q|² d/dt(R v R̃) = (R ω R̃) × (R v R̃), expanded exactly (for unit q the factor is 1)",
            velocity.grades <= {1}
            and all(
                sympy.expand(a * hamilton.norm2(q) - b) == 0
                for a, b in zip(vector_part(velocity), cross_space, strict=True)
            ),
        ),
        step(
            "the space-frame form: q̇ = ½ (0, ω_s) ⊗ q with ω_s = q ω q* / |q|²",
            "q ⊗ (0, ω) = (0, q ω q*/|q|²) ⊗ q",
            hamilton.is_equal(
                hamilton.scale(hamilton.norm2(q), hamilton.mul(q, hamilton.pure(w))),
                hamilton.mul(hamilton.pure(vector_part(space_w)), q),
            ),
        ),
    )
    return Kinematics(
        "Rotor kinematics Ṙ = ½ R Ω  ⟺  q̇ = ½ q ⊗ (0, ω)",
        "Because φ is an injective algebra map with φ((0, ω)) = Ω = -Iω, the rotor equation "
        "and the quaternion equation are the same equation, written in two algebras.",
        steps,
        critical=True,
        rotor_rate=str(rotor_rate),
        quaternion_rate=quat_rate,
    )
