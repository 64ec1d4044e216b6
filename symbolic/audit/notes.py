"""The notes (Nogueira et al., 'Quatérnios'): every formula, checked.

The notes are LaTeX, so nothing was lost in extraction: each formula is read exactly as
written ('cos_2 ψ' is the notes' shorthand for cos(ψ/2)). Labels N1, N2, ... follow the
order of the notes.
"""

from __future__ import annotations

import math
from functools import cache
from itertools import permutations, product

import numpy as np
import sympy
from sympy import atan, atan2, cos, sin

from .. import hamilton, isomorphisms, rotations, rotors, trig
from ..derivation import show, step
from .common import (
    Q_SAMPLE,
    P,
    Q,
    V,
    on_unit_sphere,
    polys_equal,
    unit_matrices_equal,
)
from .core import Finding, Reading, verdict_of

# The entries are rows of the audit, reached through ENTRIES (or symbolic.audit.find):
# each builds one Finding and is not an API of its own.
__all__ = ["ENTRIES", "SOURCE"]

SOURCE = "notes"
Q0, Q1, Q2, Q3 = Q
P0, P1, P2, P3 = P


def n01_units() -> Finding:
    d = isomorphisms.quaternions_from_cl02()
    return Finding(
        SOURCE,
        "N1",
        "multiplication rules of i, j, k",
        printed=r"\mathbf{i}^2 &= \mathbf{j}^2 = \mathbf{k}^2 = -1 \\ \mathbf{ij} &= \mathbf{k}, "
        r"\mathbf{ji} = -\mathbf{k}",
        reading="i² = j² = k² = −1; ij = k, ji = −k; jk = i, kj = −i; ki = j, ik = −j",
        reconstruction="LaTeX source: nothing lost.",
        verdict=verdict_of(d.steps[0].holds and d.steps[1].holds),
        evidence="all relations computed in Cl(0,2) with i = e1, j = e2, k = e1e2.",
        checks=d.steps[:2],
        critical=True,
    )


def n02_addition() -> Finding:
    r = hamilton.symbols("r")
    add = hamilton.add
    holds = polys_equal(add(P, Q), add(Q, P)) and polys_equal(add(P, add(Q, r)), add(add(P, Q), r))
    return Finding(
        SOURCE,
        "N2",
        "addition",
        printed=r"p + q = (p_0 + q_0) + (p_1 + q_1)\mathbf{i} + (p_2 + q_2)\mathbf{j} + (p_3 "
        r"+ q_3)\mathbf{k}.",
        reading="p + q componentwise; commutative and associative",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="componentwise addition of symbolic quaternions; both laws expand to identities.",
        checks=(step("p + q = q + p, p + (q + r) = (p + q) + r", "expanded exactly", holds),),
    )


def n03_product() -> Finding:
    printed = (
        P0 * Q0 - P1 * Q1 - P2 * Q2 - P3 * Q3,
        P0 * Q1 + P1 * Q0 + P2 * Q3 - P3 * Q2,
        P0 * Q2 + P2 * Q0 + P3 * Q1 - P1 * Q3,
        P0 * Q3 + P3 * Q0 + P1 * Q2 - P2 * Q1,
    )
    rotor_side = isomorphisms.rotor_to_quaternion(
        isomorphisms.quaternion_to_rotor(P) * isomorphisms.quaternion_to_rotor(Q)
    )
    holds = polys_equal(printed, rotor_side)
    return Finding(
        SOURCE,
        "N3",
        "product, component by component",
        printed=r"&= (p_0 q_0 - p_1 q_1 - p_2 q_2 - p_3 q_3) \\ &\quad + (p_0 q_1 + p_1 q_0 + "
        r"p_2 q_3 - p_3 q_2)\mathbf{i}",
        reading="pq = (p0q0 − p1q1 − p2q2 − p3q3) + (p0q1 + p1q0 + p2q3 − p3q2) i "
        "+ (p0q2 + p2q0 + p3q1 − p1q3) j + (p0q3 + p3q0 + p1q2 − p2q1) k",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="equal to the product computed in Cl⁺(3,0) through the isomorphism "
        "q -> w − x e23 − y e31 − z e12 (an independent route to Hamilton's product).",
        checks=(step("the four components = φ⁻¹(φ(p) φ(q))", "expanded exactly", holds),),
        critical=True,
    )


def n04_condensed() -> Finding:
    pv, qv = sympy.Matrix(P[1:]), sympy.Matrix(Q[1:])
    printed = (P0 * Q0 - pv.dot(qv), *(P0 * qv + Q0 * pv + pv.cross(qv)))
    holds = polys_equal(printed, hamilton.mul(P, Q))
    return Finding(
        SOURCE,
        "N4",
        "product in scalar-vector form",
        printed=r"pq = p_0 q_0 - \mathbf{p} \cdot \mathbf{q} + p_0 \mathbf{q} + q_0 "
        r"\mathbf{p} + \mathbf{p} \times \mathbf{q}",
        reading="pq = p0 q0 − p·q + p0 q + q0 p + p × q",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="expanded exactly against the Hamilton product.",
        checks=(step("scalar-vector form = Hamilton product", "expanded exactly", holds),),
        critical=True,
    )


def n05_laws() -> Finding:
    r = hamilton.symbols("r")
    mul = hamilton.mul
    assoc = polys_equal(mul(P, mul(Q, r)), mul(mul(P, Q), r))
    distrib = polys_equal(mul(P, hamilton.add(Q, r)), hamilton.add(mul(P, Q), mul(P, r)))
    i, j = hamilton.unit("i"), hamilton.unit("j")
    noncommutative = mul(i, j) != mul(j, i)
    holds = assoc and distrib and noncommutative
    return Finding(
        SOURCE,
        "N5",
        "distributive, associative, not commutative",
        printed=r"satisfaz a propriedade associativa ($p(qr) = (pq)r$), mas não é comutativa "
        r"($pq \neq qp$)",
        reading="p(q + r) = pq + pr, p(qr) = (pq)r, pq ≠ qp in general",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence=f"associativity and distributivity for general symbolic quaternions; "
        f"ij = {mul(i, j)} but ji = {mul(j, i)}.",
        checks=(step("associative, distributive, ij ≠ ji", "expanded exactly", holds),),
    )


def n06_conjugate() -> Finding:
    qq = hamilton.mul(Q, hamilton.conj(Q))
    holds = polys_equal(qq, (hamilton.norm2(Q), 0, 0, 0))
    return Finding(
        SOURCE,
        "N6",
        "conjugate",
        printed=r"q^* = q_0 - \mathbf{q} = q_0 - q_1 \mathbf{i} - q_2 \mathbf{j} - q_3 \mathbf{k}",
        reading="q* = q0 − q1 i − q2 j − q3 k",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="q q* = |q|², real (expanded exactly); in Cl⁺(3,0) it is the reverse R̃.",
        checks=(step("q q* = q0² + q1² + q2² + q3²", show(qq[0]), holds),),
        critical=True,
    )


def n07_norm() -> Finding:
    holds = sympy.expand(hamilton.mul(Q, hamilton.conj(Q))[0] - hamilton.norm2(Q)) == 0
    return Finding(
        SOURCE,
        "N7",
        "norm",
        printed=r"|q| = \sqrt{qq^*} = \sqrt{q_0^2 + q_1^2 + q_2^2 + q_3^2}.",
        reading="|q| = √(q q*) = √(q0² + q1² + q2² + q3²)",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="q q* is the real number q0² + q1² + q2² + q3² (expanded exactly).",
        checks=(step("q q* = Σ qᵢ²", "expanded exactly", holds),),
        critical=True,
    )


def n08_polar() -> Finding:
    t, lat, lon = sympy.symbols("t lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    q = rotors.axis_angle(2 * t, u)
    unit = trig.is_identity(hamilton.norm2(q), 1)
    double = trig.all_identities(q, rotors.axis_angle(-2 * t, [-c for c in u]))
    return Finding(
        SOURCE,
        "N8",
        "a unit quaternion as cos θ + u sin θ",
        printed=r"q = q_0 + \mathbf{q} = \cos(\theta) + \mathbf{u} \sin(\theta),",
        reading="every unit q = cos θ + u sin θ with −π ≤ θ ≤ π and u the unit vector along q",
        reconstruction="nothing lost.",
        verdict=verdict_of(unit),
        evidence="cos θ + u sin θ is unit for unit u (trigonometric identity), and every unit q "
        "has this form with θ = atan2(|q|, q0) ∈ [0, π], u = q/|q|.",
        checks=(
            step(
                "|cos θ + u sin θ| = 1; (θ, u) and (−θ, −u) give the same q",
                "trigonometric identities",
                unit and double,
            ),
        ),
        notes="With u along the vector part, θ ∈ [0, π] already covers every unit q; the stated "
        "range [−π, π] admits (θ, u) and (−θ, −u) for the same q. For q = ±1 the axis u is "
        "arbitrary.",
    )


def n09_inverse() -> Finding:
    n = sympy.sqrt(hamilton.norm2(Q))
    printed = tuple(c / n for c in hamilton.conj(Q))
    product_ = tuple(sympy.simplify(c) for c in hamilton.mul(Q, printed))
    holds = product_ == (1, 0, 0, 0)
    corrected = tuple(c / hamilton.norm2(Q) for c in hamilton.conj(Q))
    corrected_ok = tuple(sympy.cancel(c) for c in hamilton.mul(Q, corrected)) == (1, 0, 0, 0)
    two = hamilton.quat(2, 0, 0, 0)
    return Finding(
        SOURCE,
        "N9",
        "inverse",
        printed=r"q^{-1} = \frac{q^*}{|q|}.",
        reading="q⁻¹ = q*/|q|",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        corrected="q⁻¹ = q*/|q|² (q q*/|q| = |q|, which is 1 only for unit q).",
        evidence=f"q · q*/|q| = {show(product_[0])}; counterexample q = 2: q*/|q| = 1 and "
        f"q · 1 = {hamilton.mul(two, (1, 0, 0, 0))[0]} ≠ 1.",
        checks=(step("q · q*/|q|² = 1", "exact rational simplification", corrected_ok),),
        critical=True,
    )


def n10_unit_inverse() -> Finding:
    product_ = hamilton.mul(hamilton.conj(Q), Q)
    holds = on_unit_sphere(product_[0] - 1) == 0 and all(
        on_unit_sphere(c) == 0 for c in product_[1:]
    )
    return Finding(
        SOURCE,
        "N10",
        "inverse of a unit quaternion",
        printed=r"Veja que se q é unitário, o inverso é igual a seu conjugado q^* .",
        reading="|q| = 1 ⟹ q⁻¹ = q*",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="q* q = 1 on |q| = 1 (remainder modulo |q|² − 1).",
        checks=(step("q* q = 1 for unit q", "exact", holds),),
        critical=True,
    )


def n11_operator() -> Finding:
    t, lat, lon = sympy.symbols("θ lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    q = rotors.axis_angle(2 * t, u)
    holds = trig.matrices_equal(hamilton.rotation_matrix(q), rotors.rodrigues_matrix(u, 2 * t))
    return Finding(
        SOURCE,
        "N11",
        "rotation operator L_q(v) = q v q*, angle 2θ about q",
        printed=r"L_q(\mathbf{v}) = q\mathbf{v}q^*.",
        reading="L_q(v) = q v q* rotates v by 2θ about the vector part of q = cos θ + u sin θ",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="M(cos θ + u sin θ) = Rodrigues(u, 2θ) (trigonometric identity, u a general "
        "unit vector): an active right-handed rotation by 2θ about u.",
        checks=(
            step("q v q* = rotation by 2θ about u", "trigonometric identity", holds),
            rotors.rotor_sandwich().steps[2],
        ),
        critical=True,
    )


def _acos_float(alpha: float) -> float:
    return 2.0 * math.acos(math.cos(alpha / 2.0))


def _angle_finding(label, printed, degrees: bool) -> Finding:
    a = sympy.Symbol("α", real=True)
    # For q = (cos(α/2), u sin(α/2)) with α ∈ [0, 2π], 2 acos(q0) = α exactly.
    exact = all(
        sympy.simplify(2 * sympy.acos(cos(v / 2)) - v) == 0
        for v in (sympy.Rational(1, 3), sympy.pi / 2, 3 * sympy.pi / 2, 2 * sympy.pi)
    )
    small = 1e-8
    lost = _acos_float(small)
    robust = 2.0 * math.atan2(math.sin(small / 2.0), math.cos(small / 2.0))
    unit = "°" if degrees else "rad"
    return Finding(
        SOURCE,
        label,
        f"rotation angle ({unit})",
        printed=printed,
        reading="α = 2 arccos(q0)" + (" · 180/π" if degrees else ""),
        reconstruction="nothing lost.",
        verdict=verdict_of(exact),
        evidence=f"for q = (cos(α/2), u sin(α/2)), α ∈ [0, 2π]: 2 arccos(cos(α/2)) = α "
        f"(checked exactly at several α; {a} and 2π − {a} describe the same rotation through q "
        "and −q).",
        checks=(
            step("2 arccos(cos(α/2)) = α on [0, 2π]", "exact at α = 1/3, π/2, 3π/2, 2π", exact),
        ),
        notes=f"In floating point 2·arccos(q0) cannot resolve small angles: α = 1e-8 rad gives "
        f"{lost!r} (2·atan2(|q|, q0) gives {robust!r}), and a q0 rounded above 1 gives NaN. "
        "The numeric package uses 2·atan2(|q|, q0).",
    )


def n12_angle() -> Finding:
    return _angle_finding("N12", r"\theta_{rot} = 2\cos^{-1}(q_0)", degrees=False)


def n13_axis() -> Finding:
    t, lat, lon = sympy.symbols("θ lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    vec = [c * sin(t) for c in u]
    # For 0 < θ < π, |q| = sin θ: q/|q| = u.
    holds = all(trig.is_identity(v, c * sin(t)) for v, c in zip(vec, u, strict=True))
    return Finding(
        SOURCE,
        "N13",
        "rotation axis",
        printed=r"\text{eixo}_{rot} = \frac{\mathbf{q}}{|\mathbf{q}|}.",
        reading="axis = q/|q| (vector part over its length)",
        reconstruction="nothing lost.",
        verdict=verdict_of(holds),
        evidence="for q = cos θ + u sin θ with 0 < θ < π, q = u sin θ and |q| = sin θ, so "
        "q/|q| = u, the axis of N11.",
        checks=(step("vector part = u sin θ", "trigonometric identity", holds),),
        notes="Undefined at q = ±1 (the identity rotation has every axis); for θ near 0 the "
        "quotient is accurate only if |q| is computed without cancellation (hypot).",
    )


def n14_expansion() -> Finding:
    sandwich = hamilton.mul(hamilton.mul(Q, hamilton.pure(V)), hamilton.conj(Q))[1:]
    qv, vv = sympy.Matrix(Q[1:]), sympy.Matrix(V)
    printed = tuple((2 * Q0**2 - 1) * vv + 2 * qv.dot(vv) * qv + 2 * Q0 * qv.cross(vv))
    unit_holds = all(on_unit_sphere(a - b) == 0 for a, b in zip(sandwich, printed, strict=True))
    general = polys_equal(sandwich, printed)
    return Finding(
        SOURCE,
        "N14",
        "rotation operator expanded: M v = (2q0² − 1) v + 2(q·v) q + 2 q0 (q × v)",
        printed=r"M\mathbf{v} = (2q_0^2 - 1)\mathbf{v} + 2(\mathbf{q} \cdot \mathbf{v})\mathbf{q} "
        r"+ 2q_0(\mathbf{q} \times \mathbf{v})",
        reading="M v = q v q* = (2q0² − 1) v + 2 (q·v) q + 2 q0 (q × v)",
        reconstruction="nothing lost.",
        verdict=verdict_of(unit_holds),
        evidence=f"equal to q v q* for every unit q (remainder modulo |q|² − 1 is 0); for "
        f"non-unit q it is not ({general}): the general form is the paper's (10), "
        "(q0² − |q|²) v + 2(q·v)q + 2q0 q×v. The notes require unit q, so this holds.",
        checks=(step("q v q* − printed ≡ 0 mod |q|² − 1", "exact", unit_holds),),
        critical=True,
    )


def _notes_matrix(q):
    q0, q1, q2, q3 = q
    return sympy.Matrix(
        [
            [
                2 * q0 * q0 - 1 + 2 * q1 * q1,
                2 * q1 * q2 + 0 - 2 * q0 * q3,
                2 * q1 * q3 + 0 + 2 * q0 * q2,
            ],
            [
                2 * q1 * q2 + 0 + 2 * q0 * q3,
                2 * q0 * q0 - 1 + 2 * q2 * q2,
                2 * q2 * q3 + 0 - 2 * q0 * q1,
            ],
            [
                2 * q1 * q3 + 0 + 2 * q0 * q2,
                2 * q2 * q3 + 0 + 2 * q0 * q1,
                2 * q0 * q0 - 1 + 2 * q3 * q3,
            ],
        ]
    )


def n15_matrix() -> Finding:
    m = hamilton.rotation_matrix(Q)
    printed = _notes_matrix(Q)
    holds = unit_matrices_equal(printed, m)
    wrong = [
        (i + 1, j + 1)
        for i in range(3)
        for j in range(3)
        if on_unit_sphere(printed[i, j] - m[i, j]) != 0
    ]
    at = dict(zip(Q, Q_SAMPLE, strict=True))
    det = sympy.nsimplify(printed.subs(at).det())
    # With the notes' own matrix, their matrix -> quaternion formula gives q2 = 0 always.
    q2_from_printed = sympy.expand((printed[0, 2] - printed[2, 0]) / 4)
    return Finding(
        SOURCE,
        "N15",
        "rotation matrix from the quaternion",
        printed=r"2q_1q_3 + 0 + 2q_0q_2 & 2q_2q_3 + 0 + 2q_0q_1 & 2q_0q_0 - 1 + 2q_3q_3",
        reading="M = [2q0² − 1 + 2q1², 2q1q2 − 2q0q3, 2q1q3 + 2q0q2; 2q1q2 + 2q0q3, 2q0² − 1 "
        "+ 2q2², "
        "2q2q3 − 2q0q1; 2q1q3 + 2q0q2, 2q2q3 + 2q0q1, 2q0² − 1 + 2q3²]",
        reconstruction="nothing lost (the '+ 0' terms are the notes' own bookkeeping).",
        verdict=verdict_of(holds),
        corrected="m31 = 2q1q3 − 2q0q2 (the other eight entries are right), as the notes' own "
        "M v formula (N14) gives.",
        evidence=f"entries differing from the matrix of q v q* (or of the notes' own M v "
        f"formula, N14) on |q| = 1: {wrong}. At q = (1, 2, 3, 4)/√30 the printed matrix has "
        f"determinant {det} (a rotation has 1). With it, the notes' own (m13 − m31)/(4q0) would "
        f"return q2 = {q2_from_printed}/q0 = 0 for every q.",
        checks=(
            step(
                "matrix of q v q* = textbook unit form",
                "on |q| = 1",
                unit_matrices_equal(m, rotors.unit_rotation_matrix(Q)),
            ),
        ),
        critical=True,
    )


def _notes_to_quaternion(m: np.ndarray) -> np.ndarray:
    q0 = math.sqrt(m[0, 0] + m[1, 1] + m[2, 2] + 1.0) / 2.0
    return np.array(
        [
            q0,
            (m[2, 1] - m[1, 2]) / (4 * q0),
            (m[0, 2] - m[2, 0]) / (4 * q0),
            (m[1, 0] - m[0, 1]) / (4 * q0),
        ]
    )


def n16_matrix_to_quaternion() -> Finding:
    m = hamilton.rotation_matrix(Q)
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    q0_ok = on_unit_sphere(tr + 1 - 4 * Q0**2) == 0
    pairs = {1: (2, 1, 1, 2), 2: (0, 2, 2, 0), 3: (1, 0, 0, 1)}
    off_ok = all(
        on_unit_sphere(m[a, b] - m[c, d] - 4 * Q0 * Q[k]) == 0 for k, (a, b, c, d) in pairs.items()
    )
    # Largest-diagonal branches (what the numeric package does): 4 q_k² = 1 + 2 m_kk − tr.
    sums_ok = all(
        on_unit_sphere(m[i, j] + m[j, i] - 4 * Q[i + 1] * Q[j + 1]) == 0
        for i in range(3)
        for j in range(i + 1, 3)
    )
    diag_ok = sums_ok and all(
        on_unit_sphere(1 + 2 * m[k - 1, k - 1] - tr - 4 * Q[k] ** 2) == 0 for k in (1, 2, 3)
    )
    # At a rotation by π (q0 = 0) the formula divides by zero; near π it loses accuracy.
    with np.errstate(divide="ignore", invalid="ignore"):
        at_pi = _notes_to_quaternion(np.diag([1.0, -1.0, -1.0]))
    eps = 1e-9
    axis = np.array([2.0, 3.0, 6.0]) / 7.0
    h = (math.pi - eps) / 2.0
    q_true = np.array([math.cos(h), *(math.sin(h) * axis)])
    w, x, y, z = q_true
    m_num = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )
    near = _notes_to_quaternion(m_num)
    err = float(np.max(np.abs(near - q_true)))
    return Finding(
        SOURCE,
        "N16",
        "quaternion from the rotation matrix",
        printed=r"q_0 &= \frac{\sqrt{m_{11} + m_{22} + m_{33} + 1}}{2} \\",
        reading="q0 = √(m11 + m22 + m33 + 1)/2, q1 = (m32 − m23)/(4q0), q2 = (m13 − m31)/(4q0), "
        "q3 = (m21 − m12)/(4q0)",
        reconstruction="nothing lost.",
        verdict=verdict_of(bool(np.all(np.isfinite(at_pi))), q0_ok and off_ok),
        corrected="valid when q0 > 0, i.e. rotation angles below π (it returns the q with "
        "q0 ≥ 0; −q is the same rotation). At angle π it divides by zero "
        f"(diag(1, −1, −1) gives {at_pi.tolist()}), and near π it loses accuracy "
        f"(angle π − 1e-9: error {err:.1e}). Robust: branch on the largest of trace, m11, m22, "
        "m33, using 4q_k² = 1 + 2m_kk − trace.",
        evidence="on |q| = 1: m11 + m22 + m33 + 1 = 4q0², m32 − m23 = 4q0q1, m13 − m31 = 4q0q2, "
        "m21 − m12 = 4q0q3 (exact), so the formula inverts the correct matrix (not the "
        "notes' printed one, see N15) wherever q0 ≠ 0.",
        checks=(
            step(
                "trace + 1 = 4q0² and the antisymmetric parts = 4q0 q",
                "exact on |q| = 1",
                q0_ok and off_ok,
            ),
            step(
                "largest-diagonal branches: 4q_k² = 1 + 2m_kk − trace, m_ij + m_ji = 4q_i q_j",
                "exact on |q| = 1",
                diag_ok,
            ),
        ),
        critical=True,
    )


def _printed_aerospace(psi, phi, theta, signs=(1, 1), half=True):
    """The notes' formulas, cos_2 x read as cos(x/2) (half=True) or as cos²x."""
    c = {a: cos(a / 2) if half else cos(a) ** 2 for a in (psi, phi, theta)}
    s = {a: sin(a / 2) if half else sin(a) ** 2 for a in (psi, phi, theta)}
    return (
        c[psi] * c[phi] * c[theta] + s[psi] * s[phi] * s[theta],
        s[psi] * c[phi] * c[theta] + signs[0] * c[psi] * s[phi] * s[theta],
        s[psi] * c[phi] * s[theta] + c[psi] * s[phi] * c[theta],
        c[psi] * c[phi] * s[theta] + signs[1] * s[psi] * s[phi] * c[theta],
    )


def _float_quaternion(seq: str, angles) -> np.ndarray:
    q = np.array([1.0, 0.0, 0.0, 0.0])
    order = list(zip(seq.lower(), angles, strict=True))
    if seq.islower():
        order = order[::-1]
    for axis, a in order:
        f = np.zeros(4)
        f[0], f[1 + "xyz".index(axis)] = math.cos(a / 2), math.sin(a / 2)
        w0, x0, y0, z0 = q
        w1, x1, y1, z1 = f
        q = np.array(
            [
                w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1,
                w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
                w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1,
                w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1,
            ]
        )
    return q


@cache
def aerospace_search() -> tuple[int, list[str]]:
    """Every sequence (intrinsic and extrinsic), assignment of (ψ, φ, θ) and angle sign:
    does any make the printed formulas the quaternion of that rotation (up to ±)?"""
    psi, phi, theta = sympy.symbols("ψ φ θ", real=True)
    printed = sympy.lambdify((psi, phi, theta), _printed_aerospace(psi, phi, theta))
    rng = np.random.default_rng(3)
    points = rng.uniform(-3.0, 3.0, size=(3, 3))
    matches, tried = [], 0
    for seq in rotations.SEQUENCES:
        for case in (seq.upper(), seq):
            for perm in permutations(range(3)):
                for signs in product((1, -1), repeat=3):
                    tried += 1
                    ok = True
                    for pt in points:
                        p = np.array(printed(*pt))
                        angles = [signs[k] * pt[perm[k]] for k in range(3)]
                        q = _float_quaternion(case, angles)
                        if not (np.allclose(p, q, atol=1e-12) or np.allclose(p, -q, atol=1e-12)):
                            ok = False
                            break
                    if ok:
                        matches.append(f"{case} {perm} {signs}")
    return tried, matches


def n17_aerospace() -> Finding:
    psi, phi, theta = sympy.symbols("ψ φ θ", real=True)
    printed = _printed_aerospace(psi, phi, theta)
    norm2 = hamilton.norm2(printed)
    norm_formula = trig.is_identity(norm2, 1 + sin(psi) * sin(phi) * sin(theta))
    corrected = _printed_aerospace(psi, phi, theta, signs=(-1, -1))
    zyx = rotations.euler_quaternion("ZYX", (theta, phi, psi))
    corrected_ok = trig.all_identities(corrected, zyx)
    tried, matches = aerospace_search()
    at = {psi: 0.3, phi: 0.5, theta: 0.7}
    squares = _printed_aerospace(psi, phi, theta, half=False)
    squares_norm = sympy.N(hamilton.norm2(squares).subs(at), 6)
    return Finding(
        SOURCE,
        "N17",
        "aerospace (Z-Y'-X'') Euler angles to quaternion",
        printed=r"q_0 &= \cos_2 \psi \times \cos_2 \phi \times \cos_2 \theta + \sin_2 \psi \times "
        r"\sin_2 \phi \times \sin_2 \theta \\",
        reading="q0 = cψcφcθ + sψsφsθ, q1 = sψcφcθ + cψsφsθ, q2 = sψcφsθ + cψsφcθ, "
        "q3 = cψcφsθ + sψsφcθ (c, s of half angles)",
        reconstruction="cos_2 ψ read as cos(ψ/2) (half angles); the notes do not say which angle "
        "belongs to which axis.",
        readings=(
            Reading(
                "cos_2 x = cos(x/2)",
                f"|q|² = 1 + sin ψ sin φ sin θ ({norm_formula}): not a unit quaternion; "
                f"{len(matches)} of {tried} conventions (12 axis orders × intrinsic/extrinsic × "
                "6 angle assignments × 8 angle signs) reproduce it",
                tested=True,
            ),
            Reading(
                "cos_2 x = cos²(x)", f"|q|² = {squares_norm} at (0.3, 0.5, 0.7): not unit either"
            ),
        ),
        verdict=verdict_of(bool(matches)),
        corrected="with θ about Z (yaw), φ about Y' (pitch), ψ about X'' (roll), q = q_z(θ) "
        "q_y(φ) q_x(ψ): q1 = sψcφcθ − cψsφsθ and q3 = cψcφsθ − sψsφcθ (two signs flipped); "
        "q0 and q2 as printed.",
        evidence="|q|² of the printed formulas is 1 + sin ψ sin φ sin θ (trigonometric "
        "identity), so they cannot be a rotation for generic angles; the corrected ones equal "
        f"q_z(θ) q_y(φ) q_x(ψ) exactly ({corrected_ok}).",
        checks=(
            step(
                "corrected formulas = q_z(θ) q_y(φ) q_x(ψ)",
                "trigonometric identities",
                corrected_ok,
            ),
        ),
        critical=True,
    )


def n18_angle_degrees() -> Finding:
    return _angle_finding("N18", r"\theta_{rot} = 2 \cos^{-1} q_0 \frac{180}{\pi}", degrees=True)


def n19_latitude() -> Finding:
    r, lat, lon = sympy.symbols("r lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    q1, q2, q3 = (r * c for c in u)
    # √(q1² + q2²) = r cos(lat) for r > 0 and lat ∈ [−π/2, π/2] (cos lat ≥ 0).
    root = r * cos(lat)
    root_ok = trig.is_identity(root**2, q1**2 + q2**2)
    tangent = trig.is_identity(q3 * cos(lat), root * sin(lat))
    return Finding(
        SOURCE,
        "N19",
        "latitude of the rotation axis",
        printed=r"\text{lat} = \tan^{-1} \frac{q_3}{\sqrt{q_1^2 + q_2^2}} \frac{180}{\pi}",
        reading="lat = arctan(q3/√(q1² + q2²)) · 180/π",
        reconstruction="nothing lost.",
        verdict=verdict_of(root_ok and tangent),
        evidence="for q = r(cos lat cos lon, cos lat sin lon, sin lat), √(q1² + q2²) = r cos lat "
        "and q3/√(q1² + q2²) = tan lat; the denominator is ≥ 0, so the one-argument arctan "
        "already returns lat ∈ [−90°, 90°].",
        checks=(step("q3/√(q1² + q2²) = tan(lat)", "trigonometric identity", root_ok and tangent),),
        notes="q and −q (the same rotation) give antipodal axes: latitude flips sign. Undefined "
        "for the identity rotation.",
    )


def n20_longitude() -> Finding:
    r, lat, lon = sympy.symbols("r lat lon", real=True)
    u = rotors.spherical_unit(lat, lon)
    q1, q2, _ = (r * c for c in u)
    tangent = trig.is_identity(q2 * cos(lon), q1 * sin(lon))
    at = {r: 1, lat: sympy.Rational(1, 5), lon: sympy.Rational(5, 2)}
    literal = sympy.N(atan(q2 / q1).subs(at), 6)
    two_arg = sympy.N(atan2(q2, q1).subs(at), 6)
    return Finding(
        SOURCE,
        "N20",
        "longitude of the rotation axis",
        printed=r"\text{lon} = \tan^{-1} \frac{q_2}{q_1} \frac{180}{\pi}",
        reading="lon = arctan(q2/q1) · 180/π",
        reconstruction="nothing lost.",
        readings=(
            Reading(
                "one-argument arctan",
                f"at lon = 2.5 rad returns {literal} = lon − π: wrong "
                "half of the sphere whenever q1 < 0",
                tested=True,
            ),
            Reading("atan2(q2, q1)", f"returns {two_arg} = lon"),
        ),
        verdict=verdict_of(abs(literal - 2.5) < 1e-9, tangent and abs(two_arg - 2.5) < 1e-9),
        corrected="lon = atan2(q2, q1) · 180/π ∈ (−180°, 180°]",
        evidence="q2/q1 = tan(lon) (trigonometric identity), which fixes lon only modulo π.",
        checks=(step("q2 cos(lon) = q1 sin(lon)", "trigonometric identity", tangent),),
    )


ENTRIES = (
    n01_units,
    n02_addition,
    n03_product,
    n04_condensed,
    n05_laws,
    n06_conjugate,
    n07_norm,
    n08_polar,
    n09_inverse,
    n10_unit_inverse,
    n11_operator,
    n12_angle,
    n13_axis,
    n14_expansion,
    n15_matrix,
    n16_matrix_to_quaternion,
    n17_aerospace,
    n18_angle_degrees,
    n19_latitude,
    n20_longitude,
)
