"""Generate ``ga_rotors/_motor_kernels.py`` from clifford's Cl(3,0,1) layout.

The compiled motor loops cannot call clifford's MultiVector objects, so they use scalar
kernels on tuples of coefficients (:mod:`ga_rotors._pga` gives the blade orders). Those
kernels are not written by hand: this generator reads clifford's geometric multiplication
table (``layout.gmt``) of Cl(3,0,1), multiplies multivectors whose coefficients are SymPy
symbols, and prints every product term by term. ``tests/test_motor_kernels.py`` checks
that running the generator reproduces the committed file byte for byte (so it cannot
drift) and that the kernels agree with clifford's MultiVector products.

Run ``python -m ga_rotors._generate_motor_kernels`` after changing this file.

Conventions used (docs/conventions.md, "Motors"): the Euclidean even part of a motor is
the rotor of the quaternion r under :data:`ga_rotors.isomorphism.ISOMORPHISM`
(w − x e23 − y e31 − z e12); its ideal part is e0123 times the rotor of a second
quaternion d (which works out as d = (e0123, e01, e02, e03) coefficients, no signs); the
translator by t is T = 1 − ½ e0 t (e0 t = e0 ∧ t = t₁e01 + t₂e02 + t₃e03), which moves
points by +t; the motor of the pose (q, t) is T(t) R(q): rotate, then translate.
"""

from __future__ import annotations

import sys
from pathlib import Path

TARGET = Path(__file__).with_name("_motor_kernels.py")


def _sympy():
    import sympy

    return sympy


def _layout():
    from ._pga import BLADES, layout

    found = tuple(n or "1" for n in layout().names)
    if found != BLADES:
        raise RuntimeError(f"clifford's Cl(3,0,1) blades {found} are not _pga.BLADES {BLADES}")
    return layout()


def _zero(n=16):
    return [_sympy().Integer(0)] * n


def _product(layout, left, right):
    """Geometric product of two multivectors given as 16 SymPy coefficients."""
    sp = _sympy()
    gmt = layout.gmt
    out = _zero()
    coords = gmt.coords
    for i, j, k, s in zip(coords[0], coords[1], coords[2], gmt.data, strict=True):
        if left[i] != 0 and right[k] != 0:
            out[j] = out[j] + sp.Integer(int(s)) * left[i] * right[k]
    return [sp.expand(c) for c in out]


def _reverse(layout, coeffs):
    """clifford's reversion applied blade by blade."""
    out = list(coeffs)
    for i in range(layout.gaDims):
        basis = layout.MultiVector()
        basis.value[i] = 1.0
        out[i] = coeffs[i] * int((~basis).value[i])
    return out


def _symbols(prefix: str, indices) -> list:
    """16 coefficients: symbols ``prefix0, prefix1, …`` at ``indices``, zero elsewhere."""
    sp = _sympy()
    coeffs = _zero()
    for n, idx in enumerate(indices):
        coeffs[idx] = sp.Symbol(f"{prefix}{n}")
    return coeffs


def _blade(layout, name: str):
    coeffs = _zero()
    coeffs[layout.names.index("" if name == "1" else name)] = _sympy().Integer(1)
    return coeffs


def _render(expr) -> str:
    """``expr`` as Python source: monomials in a fixed order, a common factor pulled out."""
    sp = _sympy()
    expr = sp.expand(expr)
    if expr == 0:
        return "0.0"
    gens = sorted(expr.free_symbols, key=lambda s: (s.name[0], int(s.name[1:])))
    terms = sp.Poly(expr, *gens).terms() if gens else [((), expr)]
    magnitudes = {abs(c) for _, c in terms}
    common = magnitudes.pop() if len(magnitudes) == 1 else sp.Integer(1)
    parts = []
    for monom, c in terms:
        c = c / common
        factors = [g.name for g, e in zip(gens, monom, strict=True) for _ in range(e)]
        body = " * ".join(factors) if factors else "1.0"
        if abs(c) != 1:
            body = f"{float(abs(c))!r} * {body}"
        parts.append(("-" if c < 0 else "+", body))
    text = ("-" if parts[0][0] == "-" else "") + parts[0][1]
    for sign, body in parts[1:]:
        text += f" {sign} {body}"
    if common != 1:
        text = f"{float(common)!r} * ({text})"
    return text


def _tuple(exprs, indent: str = "    ") -> str:
    lines = "".join(f"{indent}    {_render(e)},\n" for e in exprs)
    return f"(\n{lines}{indent})"


def _unpack(prefix: str, n: int) -> str:
    return ", ".join(f"{prefix}{i}" for i in range(n)) + ("," if n == 1 else "")


def _function(name, args, doc, body_lines, result) -> str:
    head = f"@jit\ndef {name}({', '.join(a for a, _ in args)}):\n    \"\"\"{doc}\"\"\"\n"
    unpack = "".join(f"    {_unpack(p, n)} = {a}\n" for a, (p, n) in args if p)
    body = "".join(f"    {line}\n" for line in body_lines)
    return head + unpack + body + f"    return {result}\n"


def _names(indices) -> str:
    from ._pga import BLADES

    return ", ".join(BLADES[i] for i in indices)


def _sandwich(layout, grade_indices, kind: str) -> str:
    """M X M̃ for X of one grade, as two products: Y = M X, then the grade of X in Y M̃."""
    from ._pga import MOTOR

    m = _symbols("m", MOTOR)
    x = _symbols("x", grade_indices)
    y_full = _product(layout, m, x)
    y_at = [i for i, c in enumerate(y_full) if c != 0]
    y = _symbols("y", y_at)
    z = _product(layout, y, _reverse(layout, m))
    y_line = f"{_unpack('y', len(y_at))} = {_tuple([y_full[i] for i in y_at], '')}"
    return _function(
        f"sandwich_{kind}",
        [("m", ("m", 8)), ("x", ("x", len(grade_indices)))],
        f"M X M̃ for a unit motor M and a {kind} X ({_names(grade_indices)}).",
        y_line.splitlines(),
        _tuple([z[i] for i in grade_indices]),
    )


def _dual_tables(layout):
    """(component, blade index, sign) of r and d: M = R(r) + e0123 R(d), R the isomorphism."""
    from ._pga import BLADES, MOTOR
    from .isomorphism import BLADES as CL3_BLADES
    from .isomorphism import ISOMORPHISM

    rotor_table, ideal_table = [], []
    pseudo = _blade(layout, "e0123")
    for component, cl3_blade, sign in ISOMORPHISM:
        index = BLADES.index(CL3_BLADES[cl3_blade])
        rotor_table.append((component, index, int(sign)))
        image = _product(layout, pseudo, [sign * c for c in _blade(layout, BLADES[index])])
        (found,) = [i for i, c in enumerate(image) if c != 0]
        ideal_table.append((component, found, int(image[found])))
    for _, index, _ in rotor_table + ideal_table:
        if index not in MOTOR:
            raise RuntimeError(f"blade {BLADES[index]} of the dual-quaternion map is not even")
    return rotor_table, ideal_table


def generate() -> str:
    """The source text of ``_motor_kernels.py``, computed from clifford's layout."""
    from ._pga import LINE, MOTOR, PLANE, POINT

    sp = _sympy()
    layout = _layout()
    order = _names(MOTOR)
    funcs: list[str] = []

    a = _symbols("a", MOTOR)
    b = _symbols("b", MOTOR)
    prod = _product(layout, a, b)
    funcs.append(_function(
        "mmul", [("a", ("a", 8)), ("b", ("b", 8))],
        f"Geometric product a b of two even multivectors ({order}).",
        [], _tuple([prod[i] for i in MOTOR]),
    ))  # fmt: skip
    rev = _reverse(layout, a)
    funcs.append(_function(
        "mrev", [("a", ("a", 8))],
        "Reverse ã (the inverse of a unit motor).", [], _tuple([rev[i] for i in MOTOR]),
    ))  # fmt: skip

    for indices, kind in ((PLANE, "plane"), (LINE, "line"), (POINT, "point")):
        funcs.append(_sandwich(layout, indices, kind))

    # What the rigid-motion equations need (ga_rotors.paths.motor): the kinematics
    # Ṁ = ½ M B with a bivector B, and the commutator of two lines in the Euler–Poincaré
    # equation Π̇ = Π × B + W (X × Y = ½ (X Y − Y X), a line again).
    line_b = _symbols("b", LINE)
    mb = _product(layout, a, line_b)
    funcs.append(_function(
        "mmul_line", [("a", ("a", 8)), ("b", ("b", 6))],
        "Geometric product a B of an even multivector a and a bivector B (a line).",
        [], _tuple([mb[i] for i in MOTOR]),
    ))  # fmt: skip
    line_a = _symbols("a", LINE)
    ab, ba = _product(layout, line_a, line_b), _product(layout, line_b, line_a)
    commutator = [sp.Rational(1, 2) * (x - y) for x, y in zip(ab, ba, strict=True)]
    if any(sp.expand(commutator[i]) != 0 for i in range(16) if i not in LINE):
        raise RuntimeError("the commutator of two bivectors is not a bivector")
    funcs.append(_function(
        "line_commutator", [("a", ("a", 6)), ("b", ("b", 6))],
        "The commutator product A × B = ½ (A B − B A) of two bivectors (lines).",
        [], _tuple([commutator[i] for i in LINE]),
    ))  # fmt: skip

    rotor_table, ideal_table = _dual_tables(layout)
    r = [sp.Symbol(f"r{i}") for i in range(4)]
    d = [sp.Symbol(f"d{i}") for i in range(4)]
    motor = _zero()
    r_of, d_of = _zero(4), _zero(4)
    for component, index, sign in rotor_table:
        motor[index] = motor[index] + sign * r[component]
        r_of[component] = sign * sp.Symbol(f"a{MOTOR.index(index)}")
    for component, index, sign in ideal_table:
        motor[index] = motor[index] + sign * d[component]
        d_of[component] = sign * sp.Symbol(f"a{MOTOR.index(index)}")
    funcs.append(_function(
        "dual_parts", [("a", ("a", 8))],
        "The quaternions (r, d) of a = R(r) + e0123 R(d), R(q) = w − x e23 − y e31 − z e12.",
        [], f"{_tuple(r_of)}, {_tuple(d_of)}",
    ))  # fmt: skip
    funcs.append(_function(
        "from_dual_parts", [("r", ("r", 4)), ("d", ("d", 4))],
        "The motor R(r) + e0123 R(d) of two quaternions: the inverse of dual_parts.",
        [], _tuple([motor[i] for i in MOTOR]),
    ))  # fmt: skip

    # The translator T = 1 − ½ e0 ∧ t and the pose T(t) R(q).
    t = _symbols("t", (2, 3, 4))  # e1, e2, e3
    e0 = _blade(layout, "e0")
    e0t = _product(layout, e0, t)  # e0 t = e0 ∧ t (e0 ⊥ t)
    translator = [c - sp.Rational(1, 2) * w for c, w in zip(_blade(layout, "1"), e0t, strict=True)]
    rotor = _zero()
    for component, index, sign in rotor_table:
        rotor[index] = sign * sp.Symbol(f"q{component}")
    pose = _product(layout, translator, rotor)
    funcs.append(_function(
        "motor_from_pose", [("q", ("q", 4)), ("t", ("t", 3))],
        "T(t) R(q): rotate by the quaternion q, then translate by t (T = 1 − ½ e0 t).",
        [], _tuple([pose[i] for i in MOTOR]),
    ))  # fmt: skip

    # The translation of a unit motor M = T R: T = M R̃ with R the Euclidean part of M.
    euclidean = [a[i] if i in (0, 8, 9, 10) else 0 for i in range(16)]
    back = _product(layout, a, _reverse(layout, euclidean))
    t_of = [-2 * back[layout.names.index(n)] for n in ("e01", "e02", "e03")]
    funcs.append(_function(
        "translation", [("a", ("a", 8))],
        "t of a unit motor M = T(t) R: −2 times the e01, e02, e03 parts of M R̃.",
        [], _tuple(t_of),
    ))  # fmt: skip

    names = sorted(f.split("def ", 1)[1].split("(", 1)[0] for f in funcs)
    listed = "".join(f'    "{n}",\n' for n in names)
    header = (
        '"""Motor kernels on Cl(3,0,1): GENERATED, do not edit.\n\n'
        "Generated by ``python -m ga_rotors._generate_motor_kernels`` from clifford's\n"
        "Cl(3,0,1) multiplication table. Motors are 8-tuples of coefficients in clifford's\n"
        f"blade order restricted to even grades: ({order});\n"
        "planes, lines and points are the tuples of their grade (ga_rotors._pga). The\n"
        "sandwiches keep the grade of X: the other grades of M X M̃ vanish for unit motors.\n"
        '"""\n\n'
        "from ._jit import jit\n\n"
        f"__all__ = [\n{listed}]\n\n\n"
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
