"""Generate ``ga_rotors/_rotor_kernels.py`` from clifford's Cl(3,0) layout.

The compiled rotor path cannot call clifford's MultiVector objects in its hot loop, so it
uses scalar kernels on 4-tuples. Those kernels are not written by hand: this generator
reads clifford's geometric multiplication table (``layout.gmt``), restricts it to the
even subalgebra Cl⁺(3,0) (blades 1, e12, e13, e23 in clifford's order), and prints every
product term by term. ``tests/test_rotor_kernels.py`` checks that running the generator
reproduces the committed file byte for byte (so it cannot drift) and that the kernels agree
with clifford's MultiVector products on random inputs.

Run ``python -m ga_rotors._generate_rotor_kernels`` after changing this file.

Conventions used (docs/conventions.md): I = e123, body angular velocity ω enters the rotor
equation as Ṙ = ½ R Ω with Ω = −I ω; the quaternion ↔ rotor map is the one table of
:data:`ga_rotors.isomorphism.ISOMORPHISM` (i ↦ −e23, j ↦ −e31, k ↦ −e12).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

TARGET = Path(__file__).with_name("_rotor_kernels.py")


def _layout():
    import clifford

    layout, blades = clifford.Cl(3)
    return layout, blades


class _Poly:
    """A polynomial with Fraction coefficients; monomials keep insertion order (stable output)."""

    def __init__(self, terms=None):
        self.terms: dict[tuple[str, ...], Fraction] = dict(terms or {})

    def add(self, mono: tuple[str, ...], coef) -> None:
        c = self.terms.get(mono, Fraction(0)) + Fraction(coef)
        if c == 0:
            self.terms.pop(mono, None)
        else:
            self.terms[mono] = c

    def render(self) -> str:
        if not self.terms:
            return "0.0"
        mags = {abs(c) for c in self.terms.values()}
        common = mags.pop() if len(mags) == 1 else Fraction(1)
        parts = []
        for mono, c in self.terms.items():
            c = c / common
            body = " * ".join(mono)
            if abs(c) != 1:
                body = f"{float(abs(c))!r} * {body}"
            sign = "-" if c < 0 else "+"
            parts.append((sign, body))
        text = ("-" if parts[0][0] == "-" else "") + parts[0][1]
        for sign, body in parts[1:]:
            text += f" {sign} {body}"
        if common != 1:
            text = f"{float(common)!r} * ({text})"
        return text


def _even_indices(layout) -> list[int]:
    return [i for i, blade in enumerate(layout.bladeTupList) if len(blade) % 2 == 0]


def _blade_index(layout, name: str) -> int:
    tup = tuple(int(ch) for ch in name[1:]) if name else ()
    return layout.bladeTupList.index(tup)


def _product(layout, left: list[_Poly], right: list[_Poly]) -> list[_Poly]:
    """Full-algebra geometric product of two multivectors with polynomial coefficients."""
    gmt = layout.gmt
    n = layout.gaDims
    out = [_Poly() for _ in range(n)]
    coords = gmt.coords
    data = gmt.data
    # Walk the sparse table in (i, k, j) order so terms come out grouped by left blade.
    entries = sorted(zip(coords[0], coords[2], coords[1], data, strict=True))
    for i, k, j, s in entries:
        for ma, ca in left[i].terms.items():
            for mb, cb in right[k].terms.items():
                out[j].add(ma + mb, Fraction(int(s)) * ca * cb)
    return out


def _symbols(layout, prefix: str, indices: list[int]) -> list[_Poly]:
    coeffs = [_Poly() for _ in range(layout.gaDims)]
    for n, idx in enumerate(indices):
        coeffs[idx] = _Poly({(f"{prefix}{n}",): 1})
    return coeffs


def _constant(layout, blades: dict[str, int]) -> list[_Poly]:
    coeffs = [_Poly() for _ in range(layout.gaDims)]
    for name, value in blades.items():
        coeffs[_blade_index(layout, name)] = _Poly({(): value})
    return coeffs


def _scale(coeffs: list[_Poly], factor) -> list[_Poly]:
    return [_Poly({m: c * Fraction(factor) for m, c in p.terms.items()}) for p in coeffs]


def _tuple_expr(polys: list[_Poly], indent: str) -> str:
    lines = "".join(f"{indent}    {p.render()},\n" for p in polys)
    return f"(\n{lines}{indent})"


def _names(layout, indices: list[int]) -> str:
    names = []
    for i in indices:
        tup = layout.bladeTupList[i]
        names.append("e" + "".join(str(d) for d in tup) if tup else "1")
    return ", ".join(names)


def generate() -> str:
    """The source text of ``_rotor_kernels.py``, computed from clifford's layout."""
    layout, _ = _layout()
    even = _even_indices(layout)
    vec = [i for i, b in enumerate(layout.bladeTupList) if len(b) == 1]
    biv = [i for i, b in enumerate(layout.bladeTupList) if len(b) == 2]
    pseudo = [i for i, b in enumerate(layout.bladeTupList) if len(b) == 3]
    order = _names(layout, even)

    a = _symbols(layout, "a", even)
    b = _symbols(layout, "b", even)
    w = _symbols(layout, "w", vec)
    q_symbols = ["q0", "q1", "q2", "q3"]

    funcs: list[str] = []

    prod = _product(layout, a, b)
    funcs.append(
        "@jit\ndef rmul(a, b):\n"
        f'    """Geometric product a b of two even multivectors ({order})."""\n'
        "    a0, a1, a2, a3 = a\n    b0, b1, b2, b3 = b\n"
        f"    return {_tuple_expr([prod[i] for i in even], '    ')}\n"
    )

    # Reverse: apply clifford's own reversion to each even basis blade.
    rev_terms = []
    for n, i in enumerate(even):
        basis = layout.MultiVector()
        basis.value[i] = 1.0
        sign = int((~basis).value[i])
        rev_terms.append(_Poly({(f"a{n}",): sign}))
    funcs.append(
        "@jit\ndef rrev(a):\n"
        '    """Reverse ~a (the inverse of a unit rotor)."""\n'
        "    a0, a1, a2, a3 = a\n"
        f"    return {_tuple_expr(rev_terms, '    ')}\n"
    )

    # Ω = −I ω, I = e123, as a bivector.
    minus_i = _constant(layout, {"e" + "".join(map(str, layout.bladeTupList[pseudo[0]])): -1})
    omega = _product(layout, minus_i, w)
    assert all(not omega[i].terms for i in range(layout.gaDims) if i not in biv)
    funcs.append(
        "@jit\ndef omega_bivector(w):\n"
        f'    """Ω = −I ω for body angular velocity ω, as ({_names(layout, biv)})."""\n'
        "    w0, w1, w2 = w\n"
        f"    return {_tuple_expr([omega[i] for i in biv], '    ')}\n"
    )

    rate = _product(layout, _scale(a, Fraction(1, 2)), omega)
    funcs.append(
        "@jit\ndef rotor_rate(a, w):\n"
        '    """Ṙ = ½ R Ω with Ω = −I ω: the rotor kinematics for body angular velocity ω."""\n'
        "    a0, a1, a2, a3 = a\n    w0, w1, w2 = w\n"
        f"    return {_tuple_expr([rate[i] for i in even], '    ')}\n"
    )

    # Quaternion <-> rotor: each quaternion component goes to one blade with a sign.
    from .isomorphism import EVEN, ISOMORPHISM

    if tuple(even) != EVEN:
        raise RuntimeError(f"clifford's even blades {even} are not isomorphism.EVEN {EVEN}")

    rotor_of_q = [_Poly() for _ in range(layout.gaDims)]
    quat_of_r = [_Poly() for _ in range(4)]
    for component, blade, sign in ISOMORPHISM:
        rotor_of_q[blade].add((q_symbols[component],), int(sign))
        quat_of_r[component].add((f"a{even.index(blade)}",), int(sign))
    funcs.append(
        "@jit\ndef rotor_from_quat(q):\n"
        '    """The rotor of unit quaternion q = (w, x, y, z): i ↦ −e23, j ↦ −e31, k ↦ −e12."""\n'
        "    q0, q1, q2, q3 = q\n"
        f"    return {_tuple_expr([rotor_of_q[i] for i in even], '    ')}\n"
    )
    funcs.append(
        "@jit\ndef quat_from_rotor(a):\n"
        '    """The unit quaternion (w, x, y, z) of rotor a: the inverse of rotor_from_quat."""\n'
        "    a0, a1, a2, a3 = a\n"
        f"    return {_tuple_expr(quat_of_r, '    ')}\n"
    )

    header = (
        '"""Rotor kernels on the even subalgebra Cl⁺(3,0): GENERATED, do not edit.\n\n'
        "Generated by ``python -m ga_rotors._generate_rotor_kernels`` from clifford's Cl(3)\n"
        "multiplication table. Rotors are 4-tuples of coefficients in clifford's blade order\n"
        f"restricted to even grades: ({order}).\n"
        '"""\n\n'
        "from ._jit import jit\n\n"
        '__all__ = ["omega_bivector", "quat_from_rotor", "rmul", "rotor_from_quat", '
        '"rotor_rate", "rrev"]\n\n\n'
    )
    return header + "\n\n".join(funcs)


def main(argv: list[str] | None = None) -> int:
    text = generate()
    tmp = TARGET.with_suffix(".py.tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(TARGET)
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
