"""The paper's §4: the three axis quaternions (20)-(22), their composition (23)-(24), the
quaternion kinematics (25)-(37), the Euler-angle extraction (38)-(40), the time step,
and the claim that |q| stays 1.

Derived here: with Hamilton's product (eq. 1) and q acting body to space (eqs. 10, 33),
the intrinsic z-y'-z'' rotation is q = q_z(ψ) q_y(θ) q_z(φ) = q̂_z1 q̂_y2 q̂_z3, and
q̇ = ½ q ⊗ (0, ω) with ω in the body frame B3.
"""

from __future__ import annotations

from functools import cache
from itertools import product

import sympy
from sympy import atan, atan2, cos, sin

from .. import hamilton, rotations, rotors, trig
from ..derivation import show, step
from .common import (
    ANGLE_SAMPLE,
    ANGLES,
    OMEGA,
    PHI,
    PSI,
    Q_SAMPLE,
    RATES,
    THETA,
    Q,
    c2,
    polys_equal,
    s2,
    zyz_body_rates,
    zyz_consistent,
    zyz_matrix,
    zyz_quaternion,
)
from .core import Finding, Reading, verdict_of
from .paper_quaternions import _printed_q12

# The entries are rows of the audit, reached through ENTRIES (or symbolic.audit.find):
# each builds one Finding and is not an API of its own.
__all__ = ["ENTRIES", "SOURCE"]

SOURCE = "paper"
WX, WY, WZ = OMEGA
Q0, Q1, Q2, Q3 = Q


def _axis_entry(label, axis, angle, unit, printed, name) -> Finding:
    q = rotations.axis_quaternion(axis, angle)
    reading = (cos(angle / 2), *(sin(angle / 2) if u == unit else 0 for u in "ijk"))
    same = trig.all_identities(q, reading)
    rotates = trig.matrices_equal(hamilton.rotation_matrix(q), rotations.axis_matrix(axis, angle))
    return Finding(
        SOURCE,
        label,
        f"{name} quaternion about {axis}",
        printed=printed,
        reading=f"q̂ = cos({angle}/2) + {unit} sin({angle}/2)",
        reconstruction="the fraction bars of the half angle were lost.",
        verdict=verdict_of(same and rotates),
        evidence=f"eq. (11) with u = {unit}: M(q) = R{axis}({angle}) exactly (trigonometric "
        "identity), an active right-handed rotation.",
        checks=(
            step(
                f"M(cos({angle}/2) + {unit} sin({angle}/2)) = R{axis}({angle})",
                "entry-wise trigonometric identity",
                rotates,
            ),
        ),
        critical=True,
    )


def eq20() -> Finding:
    return _axis_entry("(20)", "z", PSI, "k", "q ^ z 1 = cos ψ 2 + k sen ψ 2", "precession")


def eq21() -> Finding:
    return _axis_entry("(21)", "y", THETA, "j", "q ^ y 2 = cos θ 2 + j sen θ 2", "nutation")


def eq22() -> Finding:
    return _axis_entry("(22)", "z", PHI, "k", "q ^ z 3 = cos ϕ 2 + k sen ϕ 2", "spin")


def _qz1_qy2_qz3():
    return (
        rotations.axis_quaternion("z", PSI),
        rotations.axis_quaternion("y", THETA),
        rotations.axis_quaternion("z", PHI),
    )


def geodesic(a, b) -> sympy.Expr:
    """Rotation angle of a* b (both unit): 2 atan2(|vec|, |scalar|), evaluated numerically."""
    d = hamilton.mul(hamilton.conj(a), b)
    vec = sympy.sqrt(sum(sympy.N(c) ** 2 for c in d[1:]))
    return sympy.N(2 * atan2(vec, abs(sympy.N(d[0]))), 6)


def eq23() -> Finding:
    qz1, qy2, qz3 = _qz1_qy2_qz3()
    printed = hamilton.mul(hamilton.mul(qz3, qy2), qz1)
    derived = zyz_quaternion()
    as_rotation = trig.matrices_equal(hamilton.rotation_matrix(printed), zyz_matrix())
    gap = geodesic(
        tuple(c.subs(ANGLE_SAMPLE) for c in printed), tuple(c.subs(ANGLE_SAMPLE) for c in derived)
    )
    reversed_product = hamilton.mul(hamilton.mul(qz1, qy2), qz3)  # = qz3 ⊙ qy2 ⊙ qz1, a ⊙ b = b a
    reversed_ok = trig.all_identities(reversed_product, derived)
    return Finding(
        SOURCE,
        "(23)",
        "composition of the three rotations",
        printed="q ^ = q ^ z 3 q ^ y 2 q ^ z 1 = q 0 + i q 1 + j q 2 + k q 3",
        reading="q̂ = q̂_z3 q̂_y2 q̂_z1 = q_z(φ) q_y(θ) q_z(ψ)",
        reconstruction="nothing lost.",
        readings=(
            Reading(
                "Hamilton's product (ij = k, the paper's eq. 1)",
                f"q_z(φ) q_y(θ) q_z(ψ) is a different rotation from the z-y'-z'' one "
                f"(M(q) = Rz(ψ)Ry(θ)Rz(φ)? {as_rotation})",
                tested=True,
            ),
            Reading(
                "the reversed ('natural order', Shuster) product a ⊙ b = b a",
                f"the printed order would then be right ({reversed_ok}), "
                "but the paper fixes ij = k in eq. (1)",
            ),
        ),
        verdict=verdict_of(as_rotation),
        corrected="q̂ = q̂_z1 q̂_y2 q̂_z3 = q_z(ψ) q_y(θ) q_z(φ): intrinsic rotations compose by "
        "right multiplication. This is the order whose components eq. (24) prints.",
        evidence=f"M(q_z(ψ) q_y(θ) q_z(φ)) = Rz(ψ)Ry(θ)Rz(φ), the matrix of (14)-(15); the "
        f"printed order differs from it by a rotation of {gap} rad at (ψ, θ, φ) = "
        "(0.3, 0.5, 0.7) rad (geodesic angle).",
        checks=(zyz_consistent(),),
        critical=True,
    )


def printed24(sign_q0: int = -1):
    return (
        c2(PSI) * c2(THETA) * c2(PHI) + sign_q0 * s2(PSI) * c2(THETA) * s2(PHI),
        c2(PSI) * s2(THETA) * s2(PHI) - s2(PSI) * s2(THETA) * c2(PHI),
        c2(PSI) * s2(THETA) * c2(PHI) + s2(PSI) * s2(THETA) * s2(PHI),
        s2(PSI) * c2(THETA) * c2(PHI) + c2(PSI) * c2(THETA) * s2(PHI),
    )


def eq24() -> Finding:
    qz1, qy2, qz3 = _qz1_qy2_qz3()
    derived = zyz_quaternion()
    printed_order = hamilton.mul(hamilton.mul(qz3, qy2), qz1)
    holds = trig.all_identities(printed24(), derived)
    plus = printed24(+1)
    plus_any = trig.all_identities(plus, derived) or trig.all_identities(plus, printed_order)
    matches_23 = trig.all_identities(printed24(), printed_order)
    return Finding(
        SOURCE,
        "(24)",
        "components of the composed quaternion",
        printed="q 0 = cos ψ 2 cos θ 2 cos ϕ 2 sen ψ 2 cos θ 2 sen ϕ 2 q 1 = cos ψ 2 sen θ 2 "
        "sen ϕ 2 "
        "- sen ψ 2 sen θ 2 cos ϕ 2 q 2 = cos ψ 2 sen θ 2 cos ϕ 2 + sen ψ 2 sen θ 2 sen ϕ 2 "
        "q 3 = sen ψ 2 cos θ 2 cos ϕ 2 + cos ψ 2 cos θ 2 sen ϕ 2",
        reading="q0 = cψ cθ cφ − sψ cθ sφ, q1 = cψ sθ sφ − sψ sθ cφ, q2 = cψ sθ cφ + sψ sθ sφ, "
        "q3 = sψ cθ cφ + cψ cθ sφ (all half angles)",
        reconstruction="fraction bars of the half angles lost; the operator between the two "
        "products of q0 is missing and is read as a lost minus.",
        readings=(
            Reading(
                "q0 with '−'",
                f"= components of q_z(ψ) q_y(θ) q_z(φ): {holds}; of the "
                f"printed (23) order q_z(φ) q_y(θ) q_z(ψ): {matches_23}",
                tested=True,
            ),
            Reading("q0 with '+'", f"matches either order? {plus_any}"),
        ),
        verdict=verdict_of(holds),
        evidence="entry-wise trigonometric identities: these are the components of "
        "q_z(ψ) q_y(θ) q_z(φ) = q0 + ..., i.e. (24) computes the corrected order of (23) "
        "(q1 = sin(θ/2) sin((φ − ψ)/2) changes sign under ψ <-> φ).",
        checks=(zyz_consistent(),),
        critical=True,
        notes="Since (24) is right and (23) is not, the paper's computations (which use 24) "
        "are unaffected by the misprinted order.",
    )


def eq25() -> Finding:
    # Constant body ω = α̇ u about a fixed unit axis u: the exact solution is
    # q(t) = q(0) r(t) with r(t) = cos(α(t)/2) + u sin(α(t)/2), α = α̇ t. It satisfies
    # q̇ = ½ q (0, ω) (body frame), and q(t + Δt) = q(t) r(Δt) since r(t) r(Δt) = r(t + Δt).
    t, dt, rate, lat, lon = sympy.symbols("t Δt α̇ lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    q0 = hamilton.symbols("a")

    def r(tau):
        return rotors.axis_angle(rate * tau, u)

    q_t = hamilton.mul(q0, r(t))
    lhs = tuple(sympy.diff(c, t) for c in q_t)
    rhs = hamilton.scale(
        sympy.Rational(1, 2), hamilton.mul(q_t, hamilton.pure([rate * c for c in u]))
    )
    solves = trig.all_identities(lhs, rhs)
    step_right = trig.all_identities(hamilton.mul(q_t, r(dt)), hamilton.mul(q0, r(t + dt)))
    return Finding(
        SOURCE,
        "(25)",
        "increment by right multiplication",
        printed="q ^ ( t + Δ t ) = q ^ ( t ) Δ r ^ ( t )",
        reading="q̂(t + Δt) = q̂(t) Δr̂(t)",
        reconstruction="nothing lost.",
        verdict=verdict_of(solves and step_right),
        evidence="for constant body ω = α̇ u, q(t) = q(0)(cos(α̇t/2) + u sin(α̇t/2)) solves "
        "q̇ = ½ q (0, ω) and q(t + Δt) = q(t) Δr with Δr the rotation by α̇Δt about u "
        "(trigonometric identities): right multiplication = increment in the body frame, "
        "consistent with the body ω of (33)-(34).",
        checks=(
            step(
                "q(0) r(t) solves q̇ = ½ q (0, α̇u); q(t) r(Δt) = q(t + Δt)",
                "trigonometric identities (u a general unit vector)",
                solves and step_right,
            ),
        ),
        critical=True,
    )


def eq26() -> Finding:
    da, lat, lon = sympy.symbols("Δα lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    r = rotors.axis_angle(da, u)
    unit = trig.is_identity(hamilton.norm2(r), 1)
    rotates = trig.matrices_equal(hamilton.rotation_matrix(r), rotors.rodrigues_matrix(u, da))
    return Finding(
        SOURCE,
        "(26)",
        "the increment quaternion",
        printed="Δ r ^ ( t ) = cos Δ α 2 + u ( t ) sen Δ α 2",
        reading="Δr̂(t) = cos(Δα/2) + u(t) sin(Δα/2)",
        reconstruction="fraction bars lost.",
        verdict=verdict_of(unit and rotates),
        evidence="eq. (11) for the increment: unit norm, and M(Δr) is the rotation by Δα about u "
        "(trigonometric identity).",
        checks=(
            step(
                "|Δr| = 1 and M(Δr) = Rodrigues(u, Δα)",
                "trigonometric identities",
                unit and rotates,
            ),
        ),
    )


def eq27() -> Finding:
    x = sympy.Symbol("Δα", real=True)
    err_c = sympy.series(cos(x / 2) - 1, x, 0, 2).removeO()
    err_s = sympy.series(sin(x / 2) - x / 2, x, 0, 2).removeO()
    first_order = err_c == 0 and err_s == 0
    lead = sympy.series(cos(x / 2) - 1, x, 0, 3).removeO()
    norm_growth = sympy.expand(1 + (x / 2) ** 2)
    return Finding(
        SOURCE,
        "(27)",
        "small-angle increment",
        printed="Δ r ^ ( t ) = 1 + u ( t ) Δ α 2",
        reading="Δr̂(t) ≈ 1 + u(t) Δα/2",
        reconstruction="the fraction bar of Δα/2 lost; the text states the approximations "
        "cos(Δα/2) ≈ 1, sin(Δα/2) ≈ Δα/2 (their ≈ signs were lost too).",
        verdict=verdict_of(first_order),
        evidence=f"(26) − (27) = O(Δα²): the scalar error is {show(lead)} + O(Δα⁴), the vector "
        f"error O(Δα³). Exact only to first order: |1 + uΔα/2|² = {show(norm_growth)}.",
        checks=(
            step(
                "cos(Δα/2) − 1 and sin(Δα/2) − Δα/2 have no term below Δα²",
                f"series: {show(lead)}, ...",
                first_order,
            ),
        ),
    )


def eq28() -> Finding:
    da = sympy.Symbol("Δα", real=True)
    u = sympy.symbols("u1:4", real=True)
    incr = (1, *(c * da / 2 for c in u))
    lhs = hamilton.sub(hamilton.mul(Q, incr), Q)
    rhs = hamilton.scale(da / 2, hamilton.mul(Q, hamilton.pure(u)))
    holds = polys_equal(lhs, rhs)
    return Finding(
        SOURCE,
        "(28)",
        "first-order increment",
        printed="q ^ ( t + Δ t ) - q ^ ( t ) = q ^ ( t ) u ( t ) Δ α 2",
        reading="q̂(t + Δt) − q̂(t) = q̂(t) u(t) Δα/2",
        reconstruction="the fraction bar of Δα/2 lost.",
        verdict=verdict_of(holds),
        evidence="(25) with (27): q (1 + (0, u)Δα/2) − q = (Δα/2) q (0, u), expanded exactly.",
        checks=(step("q(1 + uΔα/2) − q = (Δα/2) q u", "expanded exactly", holds),),
    )


def eq29() -> Finding:
    da = sympy.Symbol("Δα", real=True)
    u = sympy.symbols("u1:4", real=True)
    true_increment = hamilton.scale(da / 2, hamilton.mul(Q, hamilton.pure(u)))  # from (28)
    printed = hamilton.scale(da / 2, hamilton.pure(u))
    holds = polys_equal(true_increment, printed)
    n2 = hamilton.norm2(Q)
    left_divided = tuple(
        sympy.cancel(c / n2) for c in hamilton.mul(hamilton.conj(Q), true_increment)
    )
    left_holds = all(sympy.simplify(a - b) == 0 for a, b in zip(left_divided, printed, strict=True))
    point = {**dict(zip(Q, Q_SAMPLE, strict=True)), da: 1, u[0]: 1, u[1]: 0, u[2]: 0}
    lhs_value = [sympy.nsimplify(c.subs(point)) for c in true_increment]
    rhs_value = [sympy.nsimplify(c.subs(point)) for c in printed]
    return Finding(
        SOURCE,
        "(29)",
        "the increment with u as a pure quaternion",
        printed="q ^ ( t + Δ t ) q ^ ( t ) = Δ α 2 0 u ( t )",
        reading="q̂(t + Δt) − q̂(t) = (Δα/2) [0; u(t)]",
        reconstruction="the minus between the two q̂'s and the fraction bar of Δα/2 were lost "
        "(as in eq. 30, which lost the same minus); the text says (29) only rewrites u as a "
        "quaternion of zero scalar part, and (30) goes on from (28).",
        readings=(
            Reading(
                "q̂(t + Δt) − q̂(t) = (Δα/2)(0, u)",
                "fails: the factor q̂(t) of (28) is missing",
                tested=True,
            ),
            Reading(
                "[q̂(t + Δt) − q̂(t)] divided on the left by q̂(t), i.e. "
                "q̂(t)⁻¹(q̂(t + Δt) − q̂(t)) = (Δα/2)(0, u)",
                f"holds ({left_holds}): (28) multiplied on the left by q̂⁻¹; would need a "
                "lost fraction bar as well",
            ),
            Reading(
                "q̂(t + Δt)/q̂(t) = (Δα/2)(0, u) (fraction bar only)",
                "fails: q̂(t)⁻¹ q̂(t + Δt) = Δr̂ = 1 + (0, u)Δα/2, off by 1",
            ),
        ),
        verdict=verdict_of(holds),
        corrected="q̂(t + Δt) − q̂(t) = (Δα/2) q̂(t) ⊗ [0; u(t)]",
        evidence=f"at q̂(t) = (1, 2, 3, 4)/√30, u = e1, Δα = 1: (28) gives {lhs_value}, the "
        f"printed right side {rhs_value}.",
        checks=(step("q⁻¹ (28) = (Δα/2)(0, u)", "exact rational simplification", left_holds),),
    )


def _limit_entry(label, printed, reading, evidence, holds, reconstruction) -> Finding:
    return Finding(
        SOURCE,
        label,
        "the limit Δt -> 0",
        printed=printed,
        reading=reading,
        reconstruction=reconstruction,
        verdict=verdict_of(holds),
        evidence=evidence,
        checks=(
            step(
                "d/dt q = ½ q (0, α̇ u) for q = q(0)(cos(α/2) + u sin(α/2))",
                "trigonometric identity (α(t) arbitrary)",
                holds,
            ),
        ),
    )


@cache
def _fixed_axis_rate_identity() -> bool:
    """q = a r(α) with r(α) = cos(α/2) + u sin(α/2): dq/dt = ½ q (0, α̇ u) for any α(t)."""
    alpha, rate, lat, lon = sympy.symbols("α α̇ lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    a = hamilton.symbols("a")
    q = hamilton.mul(a, rotors.axis_angle(alpha, u))
    qdot = tuple(sympy.diff(c, alpha) * rate for c in q)
    rhs = hamilton.scale(
        sympy.Rational(1, 2), hamilton.mul(q, hamilton.pure([rate * c for c in u]))
    )
    return trig.all_identities(qdot, rhs)


def eq30() -> Finding:
    return _limit_entry(
        "(30)",
        "d q ^ ( t ) d t = lim Δ t 0 q ^ ( t + Δ t ) q ^ ( t ) Δ t = lim Δ t 0 1 2 q ^ ( t ) "
        "Δ α Δ t 0 u ( t )",
        "dq̂/dt = lim_{Δt->0} [q̂(t + Δt) − q̂(t)]/Δt = lim_{Δt->0} ½ q̂(t) (Δα/Δt) [0; u(t)]",
        "(28) divided by Δt; the limit exists because Δα/Δt -> α̇. Checked on the exact "
        "solution for a fixed axis: dq/dt = ½ q (0, α̇ u) for any α(t).",
        _fixed_axis_rate_identity(),
        "fraction bars (d/dt, the difference quotient, Δα/Δt), the minus of the difference "
        "and the arrow of Δt -> 0 were lost.",
    )


def eq31() -> Finding:
    return _limit_entry(
        "(31)",
        "d q ^ ( t ) d t = 1 2 q ^ ( t ) α 0 u ( t )",
        "dq̂/dt = ½ q̂(t) α̇ [0; u(t)],  with α̇ = lim Δα/Δt",
        "the limit of (30); the same exact check.",
        _fixed_axis_rate_identity(),
        "the overdot of α̇ and the fraction bar of ½ were lost ('sendo α=ΔαΔt' is "
        "α̇ = Δα/Δt in the limit).",
    )


def eq32() -> Finding:
    alpha, rate, lat, lon = sympy.symbols("α α̇ lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    r = rotors.axis_angle(alpha, u)
    rdot = tuple(sympy.diff(c, alpha) * rate for c in r)
    w = hamilton.mul(hamilton.conj(r), rdot)
    holds = trig.all_identities(w, (0, *(rate * c / 2 for c in u)))
    return Finding(
        SOURCE,
        "(32)",
        "angular velocity of the increment",
        printed="ω ( t ) = α u ( t )",
        reading="ω(t) = α̇ u(t)",
        reconstruction="the overdot of α̇ was lost.",
        verdict=verdict_of(holds),
        evidence="for r = cos(α/2) + u sin(α/2), 2 r* ṙ = (0, α̇ u): the body angular velocity of "
        "a rotation about a fixed axis is the rate times the axis (trigonometric identity).",
        checks=(step("2 r* ṙ = (0, α̇ u)", "trigonometric identity", holds),),
    )


@cache
def _zyz_kinematics() -> bool:
    """q̇ = ½ q ⊗ (0, ω_B3) for q = q_z(ψ)q_y(θ)q_z(φ), ω_B3 from (15)."""
    q = zyz_quaternion()
    qdot = tuple(rotations.time_derivative(c, ANGLES, RATES) for c in q)
    omega, _ = zyz_body_rates()
    return trig.all_identities(
        qdot, hamilton.scale(sympy.Rational(1, 2), hamilton.mul(q, hamilton.pure(omega)))
    )


def eq33() -> Finding:
    holds = _zyz_kinematics()
    kin = rotors.rotor_kinematics()
    return Finding(
        SOURCE,
        "(33)",
        "quaternion kinematics",
        printed="d q ^ ( t ) d t = 1 2 q ^ ( t ) 0 ω ( t )",
        reading="dq̂/dt = ½ q̂(t) ⊗ [0; ω(t)]   (ω in the body frame B3)",
        reconstruction="fraction bars (d/dt, ½) lost.",
        verdict=verdict_of(holds),
        evidence="for q = q_z(ψ)q_y(θ)q_z(φ) with arbitrary Euler rates, q̇ = ½ q ⊗ (0, ω_B3) "
        "with ω_B3 from (15), exactly (trigonometric identity); in Cl(3,0) it is Ṙ = ½ R Ω.",
        checks=(
            step("q̇ = ½ q (0, ω_B3) along z-y-z", "trigonometric identity", holds),
            *kin.steps[:2],
        ),
        critical=True,
    )


def eq34() -> Finding:
    holds = _zyz_kinematics()
    return Finding(
        SOURCE,
        "(34)",
        "quaternion kinematics with body components",
        printed="d q ^ ( t ) d t = 1 2 q ^ ( t ) 0 ω x 3 ω y 3 ω z 3",
        reading="dq̂/dt = ½ q̂(t) ⊗ [0; ωx3; ωy3; ωz3]",
        reconstruction="fraction bars and column brackets lost.",
        verdict=verdict_of(holds),
        evidence="(33) with the body components of (15); the same identity.",
        checks=(step("q̇ = ½ q (0, ωx3, ωy3, ωz3) along z-y-z", "trigonometric identity", holds),),
        critical=True,
    )


def _body_form():
    return hamilton.scale(sympy.Rational(1, 2), hamilton.mul(Q, hamilton.pure(OMEGA)))


def eq35() -> Finding:
    qv, w = sympy.Matrix(Q[1:]), sympy.Matrix(OMEGA)
    product_ = (-qv.dot(w), *(Q0 * w + qv.cross(w)))  # (q0 + q)(0 + ω)
    second = (Q0 * 0 - qv.dot(w), *(0 * qv + Q0 * w + qv.cross(w)))
    product_ok = polys_equal(hamilton.mul(Q, hamilton.pure(OMEGA)), product_)
    holds = polys_equal(_body_form(), second)
    half_holds = polys_equal(_body_form(), hamilton.scale(sympy.Rational(1, 2), second))
    return Finding(
        SOURCE,
        "(35)",
        "kinematics through the scalar-vector product",
        printed="q 0 q 1 q 2 q 3 = 1 2 ( q 0 + q ) ( 0 + ω ) = q 0 0 q ω + 0 q + q 0 ω + q × ω "
        "= - q ω + q 0 ω + q × ω",
        reading="q̇ = ½ (q0 + q)(0 + ω) = q0·0 − q·ω + 0 q + q0 ω + q × ω = −q·ω + q0 ω + q × ω",
        reconstruction="overdots of q̇ lost; the minus before q·ω in the middle member and the "
        "dot of the scalar product lost. The factor ½ is printed once, in the first member "
        "only.",
        readings=(
            Reading(
                "as printed, ½ only in the first member",
                f"the product is right ({product_ok}) but the 2nd and 3rd members equal "
                "(q0 + q)(0 + ω), twice the first",
                tested=True,
            ),
            Reading(
                "½ meant to carry through the chain",
                f"then every member equals ½ q (0, ω) ({half_holds})",
            ),
        ),
        verdict=verdict_of(holds),
        corrected="q̇ = ½ (q0 + q)(0 + ω) = ½ (−q·ω + q0 ω + q × ω)",
        evidence="(q0 + q)(0 + ω) = (−q·ω, q0 ω + q × ω) exactly; so the printed chain "
        "equates ½ X with X.",
        checks=(step("(q0 + q)(0 + ω) = (−q·ω, q0 ω + q × ω)", "expanded exactly", product_ok),),
    )


def printed36(signs=(-1, -1, -1, -1)):
    """(36) with the four lost signs: overall sign of q̇0, before q2ωz in q̇1, leading in q̇2,
    before q1ωy in q̇3."""
    a, b, c, d = signs
    half = sympy.Rational(1, 2)
    return (
        a * half * (Q1 * WX + Q2 * WY + Q3 * WZ),
        half * (Q0 * WX + Q3 * WY + b * Q2 * WZ),
        half * (c * Q3 * WX + Q0 * WY + Q1 * WZ),
        half * (Q2 * WX + d * Q1 * WY + Q0 * WZ),
    )


def eq36() -> Finding:
    body = _body_form()
    space = hamilton.scale(sympy.Rational(1, 2), hamilton.mul(hamilton.pure(OMEGA), Q))
    tested = printed36()
    holds = polys_equal(tested, body)
    is_space = polys_equal(tested, space)
    restorations = list(product((1, -1), repeat=4))
    body_matches = [s for s in restorations if polys_equal(printed36(s), body)]
    space_matches = [s for s in restorations if polys_equal(printed36(s), space)]
    return Finding(
        SOURCE,
        "(36)",
        "kinematics, component by component",
        printed="q 0 = 1 2 q 1 ω x 3 + q 2 ω y 3 + q 3 ω z 3 q 1 = 1 2 q 0 ω x 3 + q 3 ω y 3 "
        "q 2 ω z 3 "
        "q 2 = 1 2 q 3 ω x 3 + q 0 ω y 3 + q 1 ω z 3 q 3 = 1 2 q 2 ω x 3 q 1 ω y 3 + q 0 ω z 3",
        reading="q̇0 = −½(q1ωx + q2ωy + q3ωz), q̇1 = ½(q0ωx + q3ωy − q2ωz), "
        "q̇2 = ½(−q3ωx + q0ωy + q1ωz), q̇3 = ½(q2ωx − q1ωy + q0ωz)",
        reconstruction="overdots and parentheses lost; four signs lost (before ½ in q̇0, before "
        "q2ωz3 in q̇1, before q3ωx3 in q̇2, before q1ωy3 in q̇3); every '+' is as printed.",
        readings=(
            Reading(
                "the restoration above",
                f"= ½ (0, ω) ⊗ q ({is_space}), not ½ q ⊗ (0, ω) ({holds})",
                tested=True,
            ),
            Reading(
                "all 16 ways of restoring the four lost signs",
                f"{len(body_matches)} give the body form ½ q ⊗ (0, ω); {len(space_matches)} "
                "gives the space form: the printed '+ q3ωy3' (q̇1) and '+ q1ωz3' (q̇2) "
                "are the signs of ½ (0, ω) ⊗ q",
            ),
        ),
        verdict=verdict_of(holds),
        corrected="q̇0 = −½(q1ωx3 + q2ωy3 + q3ωz3), q̇1 = ½(q0ωx3 − q3ωy3 + q2ωz3), "
        "q̇2 = ½(q3ωx3 + q0ωy3 − q1ωz3), q̇3 = ½(−q2ωx3 + q1ωy3 + q0ωz3), i.e. ½ q ⊗ (0, ω) as "
        "in (34) and (37). The printed signs are those of q̇ = ½ (0, ω) ⊗ q, the kinematics "
        "for ω given in the space frame.",
        evidence=f"½ q ⊗ (0, ω) − ½ (0, ω) ⊗ q = (0, q × ω) ≠ 0; the printed system contradicts "
        f"(37), which it claims to restate. Body-form restorations: {body_matches}.",
        checks=(
            step(
                "½ q (0, ω) − ½ (0, ω) q = (0, q × ω)",
                "expanded exactly",
                polys_equal(
                    hamilton.sub(body, space), (0, *sympy.Matrix(Q[1:]).cross(sympy.Matrix(OMEGA)))
                ),
            ),
        ),
        critical=True,
    )


def eq37() -> Finding:
    m = sympy.Matrix(
        [
            [Q0, -Q1, -Q2, -Q3],
            [Q1, Q0, -Q3, Q2],
            [Q2, Q3, Q0, -Q1],
            [Q3, -Q2, Q1, Q0],
        ]
    )
    printed = tuple(m * sympy.Matrix([0, *OMEGA]) / 2)
    holds = polys_equal(printed, _body_form())
    is_left = (m - hamilton.left_matrix(Q)).is_zero_matrix
    return Finding(
        SOURCE,
        "(37)",
        "kinematics in matrix form",
        printed="q 0 q 1 q 2 q 3 = 1 2 q 0 - q 1 - q 2 - q 3 q 1 q 0 - q 3 q 2 q 2 q 3 q 0 - q 1 "
        "q 3 - q 2 q 1 q 0 0 ω x 3 ω y 3 ω z 3",
        reading="q̇ = ½ [q0 −q1 −q2 −q3; q1 q0 −q3 q2; q2 q3 q0 −q1; q3 −q2 q1 q0] [0; ωx3; "
        "ωy3; ωz3]",
        reconstruction="overdots, ½'s fraction bar and brackets lost; every sign of the matrix "
        "survived (ASCII hyphens).",
        verdict=verdict_of(holds),
        evidence=f"the matrix is L(q), the matrix of left multiplication by q ({is_left}), so "
        "(37) is ½ q ⊗ (0, ω): the body-frame kinematics, matching (34) and contradicting (36).",
        checks=(step("L(q)(0, ω)/2 = ½ q ⊗ (0, ω)", "expanded exactly", holds),),
        critical=True,
    )


def _zyz_point(psi, theta, phi):
    return {PSI: psi, THETA: theta, PHI: phi}


def _q_entries(point):
    """Printed (12) Q evaluated at the z-y-z quaternion of the given angles."""
    q = [sympy.N(c.subs(point), 30) for c in zyz_quaternion()]
    return _printed_q12(q, minus=True)


@cache
def _extraction_identities() -> dict[str, bool]:
    """Q entries of (12) at the z-y-z quaternion, as trigonometric identities."""
    qm = _printed_q12(zyz_quaternion(), minus=True)
    s, c = sin, cos
    return {
        "Q31 = cψ sθ": trig.is_identity(qm[2, 0], c(PSI) * s(THETA)),
        "Q32 = sψ sθ": trig.is_identity(qm[2, 1], s(PSI) * s(THETA)),
        "Q33 = cθ": trig.is_identity(qm[2, 2], c(THETA)),
        "Q13 = −sθ cφ": trig.is_identity(qm[0, 2], -s(THETA) * c(PHI)),
        "Q23 = sθ sφ": trig.is_identity(qm[1, 2], s(THETA) * s(PHI)),
        "q0² + q3² = cos²(θ/2)": trig.is_identity(
            zyz_quaternion()[0] ** 2 + zyz_quaternion()[3] ** 2, c(THETA / 2) ** 2
        ),
        "q1² + q2² = sin²(θ/2)": trig.is_identity(
            zyz_quaternion()[1] ** 2 + zyz_quaternion()[2] ** 2, s(THETA / 2) ** 2
        ),
    }


def _identities_step():
    ids = _extraction_identities()
    return step(
        "at the z-y-z quaternion, (12)'s Q has the entries that (38)-(40) use",
        "; ".join(ids),
        all(ids.values()),
    )


def _entries_match_printed_q(entries: dict) -> bool:
    """The q-expressions printed in (38)-(40) equal the named entries of (12)'s Q."""
    qm = _printed_q12(Q, minus=True)
    return all(sympy.expand(expr - qm[i, j]) == 0 for (i, j), expr in entries.items())


def eq38() -> Finding:
    point = _zyz_point(sympy.Rational(5, 2), sympy.Rational(1, 2), sympy.Rational(7, 10))
    qm = _q_entries(point)
    literal = sympy.N(atan(qm[2, 1] / qm[2, 0]), 6)
    two_arg = sympy.N(atan2(qm[2, 1], qm[2, 0]), 6)
    printed_exprs = _entries_match_printed_q(
        {(2, 1): 2 * (Q2 * Q3 - Q0 * Q1), (2, 0): 2 * (Q1 * Q3 + Q0 * Q2)}
    )
    ids = _extraction_identities()
    tangent = ids["Q31 = cψ sθ"] and ids["Q32 = sψ sθ"]
    return Finding(
        SOURCE,
        "(38)",
        "precession angle from the quaternion",
        printed="ψ = arctan Q (3,2) Q (3,1) = arctan 2 q 2 q 3 - q 0 q 1 2 q 1 q 3 + q 0 q 2",
        reading="ψ = arctan(Q32/Q31) = arctan[2(q2q3 − q0q1) / 2(q1q3 + q0q2)]",
        reconstruction="fraction bars and parentheses lost; the signs survived.",
        readings=(
            Reading(
                "one-argument arctan",
                f"at ψ = 2.5 rad (θ = 0.5, φ = 0.7) it returns "
                f"{literal} = ψ − π: right only for |ψ| < π/2",
                tested=True,
            ),
            Reading("atan2(Q32, Q31)", f"returns {two_arg}: ψ in (−π, π] whenever sin θ > 0"),
        ),
        verdict=verdict_of(
            abs(literal - sympy.Rational(5, 2)) < 1e-9,
            tangent and abs(two_arg - sympy.Rational(5, 2)) < 1e-9,
        ),
        corrected="ψ = atan2(Q32, Q31) = atan2(2(q2q3 − q0q1), 2(q1q3 + q0q2)), valid for "
        "0 < θ < π (θ ∈ [0, π] by (39)); undefined at sin θ = 0 (gimbal lock).",
        evidence="with (12)'s Q at q = q_z(ψ)q_y(θ)q_z(φ): Q31 = cos ψ sin θ, Q32 = sin ψ sin θ "
        f"(trigonometric identities), so tan ψ = Q32/Q31; the q-expressions printed are "
        f"(12)'s entries ({printed_exprs}).",
        checks=(_identities_step(),),
        critical=True,
    )


def eq39() -> Finding:
    theta = sympy.pi / 12  # 15°, the paper's initial nutation
    point = _zyz_point(sympy.Rational(3, 10), theta, sympy.Rational(7, 10))
    qm = _q_entries(point)
    printed_value = sympy.N(sympy.asin(qm[2, 2]), 6)
    corrected_value = sympy.N(sympy.acos(qm[2, 2]), 6)
    q = [sympy.N(c.subs(point), 30) for c in zyz_quaternion()]
    robust = sympy.N(
        2 * atan2(sympy.sqrt(q[1] ** 2 + q[2] ** 2), sympy.sqrt(q[0] ** 2 + q[3] ** 2)), 6
    )
    printed_exprs = _entries_match_printed_q({(2, 2): 2 * (Q0**2 + Q3**2) - 1})
    ids = _extraction_identities()
    return Finding(
        SOURCE,
        "(39)",
        "nutation angle from the quaternion",
        printed="θ = arcsen Q (3,3) = arcsen 2 q 0 2 + q 3 2 − 1",
        reading="θ = arcsin Q33 = arcsin[2(q0² + q3²) − 1]",
        reconstruction="parentheses lost; the − of '− 1' survived.",
        verdict=verdict_of(abs(printed_value - sympy.N(theta)) < 1e-9),
        corrected="θ = arccos Q33 = arccos[2(q0² + q3²) − 1] ∈ [0, π]; better "
        "θ = 2 atan2(√(q1² + q2²), √(q0² + q3²)), which keeps full precision near θ = 0 "
        "(the paper's 0.001° case) where arccos loses half the digits.",
        evidence=f"Q33 = cos θ (trigonometric identity). At θ = 15°: arcsin Q33 = "
        f"{printed_value} rad = {sympy.N(printed_value * 180 / sympy.pi, 4)}°, arccos Q33 = "
        f"{corrected_value} rad = 15°; the atan2 form gives {robust}. The printed q-expression "
        f"is (12)'s Q33 ({printed_exprs}).",
        checks=(
            _identities_step(),
            step(
                "q0² + q3² = cos²(θ/2), q1² + q2² = sin²(θ/2)",
                "trigonometric identities",
                ids["q0² + q3² = cos²(θ/2)"] and ids["q1² + q2² = sin²(θ/2)"],
            ),
        ),
        critical=True,
    )


def eq40() -> Finding:
    phi = sympy.Rational(5, 2)
    point = _zyz_point(sympy.Rational(3, 10), sympy.Rational(1, 2), phi)
    qm = _q_entries(point)
    literal = sympy.N(atan(-qm[1, 2] / qm[0, 2]), 6)
    naive = sympy.N(atan2(-qm[1, 2], qm[0, 2]), 6)
    right = sympy.N(atan2(qm[1, 2], -qm[0, 2]), 6)
    printed_exprs = _entries_match_printed_q(
        {(1, 2): 2 * (Q2 * Q3 + Q0 * Q1), (0, 2): 2 * (Q1 * Q3 - Q0 * Q2)}
    )
    ids = _extraction_identities()
    return Finding(
        SOURCE,
        "(40)",
        "spin angle from the quaternion",
        printed="ϕ = arctan - Q (2,3) Q (1,3) = arctan − 2 q 2 q 3 + q 0 q 1 2 q 1 q 3 - q 0 q 2",
        reading="φ = arctan(−Q23/Q13) = arctan[−2(q2q3 + q0q1) / 2(q1q3 − q0q2)]",
        reconstruction="fraction bars and parentheses lost; the signs survived.",
        readings=(
            Reading(
                "one-argument arctan", f"at φ = 2.5 rad it returns {literal} = φ − π", tested=True
            ),
            Reading(
                "atan2(−Q23, Q13) (the minus kept on the numerator)", f"returns {naive}: off by π"
            ),
            Reading("atan2(Q23, −Q13)", f"returns {right} = φ"),
        ),
        verdict=verdict_of(
            abs(literal - phi) < 1e-9,
            ids["Q13 = −sθ cφ"] and ids["Q23 = sθ sφ"] and abs(right - phi) < 1e-9,
        ),
        corrected="φ = atan2(Q23, −Q13) = atan2(2(q2q3 + q0q1), −2(q1q3 − q0q2)) for 0 < θ < π; "
        "the quadrant needs the minus on the denominator: atan2(−Q23, Q13) is off by π.",
        evidence="Q13 = −sin θ cos φ, Q23 = sin θ sin φ (trigonometric identities), so "
        f"tan φ = −Q23/Q13; the q-expressions are (12)'s entries ({printed_exprs}).",
        checks=(_identities_step(),),
        critical=True,
    )


def time_step() -> Finding:
    x = sympy.Symbol("x", real=True)
    z = sympy.I * x
    rk4 = 1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24
    gain2 = sympy.expand(rk4 * sympy.conjugate(rk4))
    rate = sympy.Rational(157, 10)  # the spin rate, rad/s
    read_dt, printed_dt = sympy.Rational(1, 1000), sympy.Integer(1000)
    gain_read = sympy.sqrt(gain2.subs(x, rate * read_dt))
    gain_printed = sympy.sqrt(gain2.subs(x, rate * printed_dt))
    stable = gain_read <= 1
    return Finding(
        SOURCE,
        "Δt (§4)",
        "integration time step",
        printed="com 10000 amostras temporais e passo de integração Δt=1.0×103 s",
        reading="Δt = 1.0 × 10⁻³ s (10 000 steps: 10 s of motion)",
        reconstruction="the minus of the exponent was lost (printed 10³).",
        readings=(
            Reading(
                "Δt = 10⁻³ s",
                f"RK4 on a rotation at 15.7 rad/s: |R(iωΔt)| = "
                f"{sympy.N(gain_read, 17)} per step: stable",
                tested=True,
            ),
            Reading(
                "Δt = 10³ s as printed",
                f"|R(iωΔt)| = {sympy.N(gain_printed, 4)} per step: RK4 explodes at once; "
                "and 10⁴ steps would span 10⁷ s (116 days)",
            ),
        ),
        verdict=verdict_of(stable),
        evidence=f"RK4's amplification on y′ = iω y is R(z) = 1 + z + z²/2 + z³/6 + z⁴/24; "
        f"|R(ix)|² = {show(gain2)} (exact), ≤ 1 only for x ≤ 2√2.",
        checks=(
            step(
                "|R(ix)|² = 1 − x⁶/72 + x⁸/576",
                show(gain2),
                sympy.expand(gain2 - (1 - x**6 / 72 + x**8 / 576)) == 0,
            ),
        ),
    )


def norm_claim() -> Finding:
    x = sympy.Symbol("x", positive=True)
    z = sympy.I * x
    rk4 = 1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24
    gain2 = sympy.expand(rk4 * sympy.conjugate(rk4))  # |R(ix)|², a polynomial
    # q̇ = ½ q (0, ω) is linear in q with eigenvalues ±i|ω|/2: per step the norm is
    # multiplied by |R(i|ω|Δt/2)| when ω is constant. 1 − |R| = (1 − |R|²)/(1 + |R|), so its
    # leading term is half the lowest term of the polynomial 1 − |R|².
    leading = sympy.Poly(1 - gain2, x).terms()[-1]
    leading = leading[1] * x ** leading[0][0] / 2
    x_paper = sympy.Rational(157, 10) * sympy.Rational(1, 1000) / 2
    gain_paper = sympy.sqrt(gain2.subs(x, x_paper))
    per_step = sympy.N(1 - gain_paper, 30)
    over_run = sympy.N(1 - gain_paper**10000, 30)
    return Finding(
        SOURCE,
        "Fig. 5 text",
        "|q| stays exactly 1 under RK4",
        printed="O módulo de q^, obtido a partir da eq. (7) é igual a 1 para qualquer instante "
        "de tempo, garantindo que a operação realizada é apenas de rotação.",
        reading="|q̂(t)| = 1 at every time step of the RK4 integration",
        reconstruction="nothing lost.",
        verdict=verdict_of(per_step == 0, 0 < sympy.N(over_run) < 1e-9),
        corrected="equal to 1 to plotting precision only: RK4 is not norm-preserving; for "
        f"constant ω it multiplies |q| by 1 − {show(leading)} + … per step, x = |ω|Δt/2. "
        f"At 15.7 rad/s and Δt = 1 ms: {sympy.N(per_step, 3)} per step, "
        f"{sympy.N(over_run, 3)} after 10⁴ steps (more for faster spins or longer runs).",
        evidence=f"1 − |R(ix)|² = {show(sympy.expand(1 - gain2))} exactly, and "
        f"1 − |R| = (1 − |R|²)/(1 + |R|), so 1 − |R(ix)| = {show(leading)} + O(x⁸).",
        checks=(
            step(
                "1 − |R(ix)| = x⁶/144 + O(x⁸)",
                show(leading),
                sympy.simplify(leading.coeff(x, 6) - sympy.Rational(1, 144)) == 0,
            ),
        ),
    )


ENTRIES = (
    eq20,
    eq21,
    eq22,
    eq23,
    eq24,
    eq25,
    eq26,
    eq27,
    eq28,
    eq29,
    eq30,
    eq31,
    eq32,
    eq33,
    eq34,
    eq35,
    eq36,
    eq37,
    eq38,
    eq39,
    eq40,
    time_step,
    norm_claim,
)
