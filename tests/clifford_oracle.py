"""An independent evaluator of the prover's expressions, in clifford's algebra.

Elements are numpy arrays in the blade order of ``clifford.Cl(p, q, r)``; products use
clifford's own multiplication tables (``gmt``, ``omt``, ``imt``, ``lcmt``) through numpy,
so nothing is compiled and a signature costs milliseconds. Every operation of the prover's
language is written here from its definition, not from the prover's code: the complements
from clifford's outer-product table (as clifford's ``right_complement_func``), the vee as
clifford's ``vee``, the inverse by solving x y = 1 (as clifford's ``inv``), exp by its
series with scaling and squaring, up and down as clifford's ``ConformalLayout``.

The prover's blade names are mapped here too: in Cl(p, q, 1) its e0, e1, … are clifford's
e1, e2, … (the project's PGA convention); elsewhere the names agree.
"""

from __future__ import annotations

import math
from functools import cache

import clifford
import numpy as np

from ga_rotors.symbolic.prover.grammar import Binary, Name, Number, Unary


@cache
def algebra(sig: tuple[int, int, int]) -> Algebra:
    return Algebra(sig)


class Algebra:
    def __init__(self, sig):
        layout, _ = clifford.Cl(*sig)
        self.sig = tuple(sig)
        self.metric = tuple(int(s) for s in layout.sig)
        self.n = layout.dims
        self.dim = layout.gaDims
        self.tuples = list(layout.bladeTupList)
        self.grades = np.array([len(t) for t in self.tuples])
        self.gmt = layout.gmt.todense()  # [i, k, j]: blade k in blade_i blade_j
        self.omt = layout.omt.todense()
        self.imt = layout.imt.todense()
        self.lcmt = layout.lcmt.todense()
        shift = 1 if sig[2] == 1 else 0  # the prover's e0 is clifford's e1 in Cl(p,q,1)
        self.index = {
            ("1" if not t else "e" + "".join(str(i - shift) for i in t)): k
            for k, t in enumerate(self.tuples)
        }
        pseudo = self.dim - 1
        # right complement: e_A ↦ s e_Ā with e_A ∧ (s e_Ā) = I, left: (s e_Ā) ∧ e_A = I; Ā is
        # at index dim-1-A in clifford's order; indexed here by the output blade k = Ā
        self.right = np.array([1 / self.omt[pseudo - k, pseudo, k] for k in range(self.dim)])
        self.left = np.array([1 / self.omt[k, pseudo, pseudo - k] for k in range(self.dim)])

    # -- elements -------------------------------------------------------------------------------
    def zero(self) -> np.ndarray:
        return np.zeros(self.dim)

    def scalar(self, x: float) -> np.ndarray:
        out = self.zero()
        out[0] = x
        return out

    def blade(self, name: str) -> np.ndarray:
        """A prover blade name (e0 … in Cl(p,q,1)) or 'e31'-style unordered names."""
        digits = name[1:]
        ordered = "".join(sorted(digits))
        sign = _permutation_sign(digits, ordered)
        out = self.zero()
        out[self.index["e" + ordered]] = sign
        return out

    def vector(self, coeffs) -> np.ndarray:
        out = self.zero()
        for i, c in enumerate(coeffs):
            out[1 + i] = c
        return out

    def from_names(self, coeffs: dict) -> np.ndarray:
        """{prover blade name: value} -> array (values may be SymPy numbers)."""
        out = self.zero()
        for name, value in coeffs.items():
            out[self.index[name]] += float(value)
        return out

    # -- products and involutions ---------------------------------------------------------------
    def gp(self, a, b):
        return np.einsum("i,ikj,j->k", a, self.gmt, b)

    def op(self, a, b):
        return np.einsum("i,ikj,j->k", a, self.omt, b)

    def ip(self, a, b):
        return np.einsum("i,ikj,j->k", a, self.imt, b)

    def lc(self, a, b):
        return np.einsum("i,ikj,j->k", a, self.lcmt, b)

    def rc(self, a, b):
        return self.rev(self.lc(self.rev(b), self.rev(a)))

    def rev(self, a):
        return a * np.where((self.grades * (self.grades - 1) // 2) % 2, -1.0, 1.0)

    def involute(self, a):
        return a * np.where(self.grades % 2, -1.0, 1.0)

    def grade(self, a, k):
        return np.where(self.grades == k, a, 0.0)

    def right_complement(self, a):
        return self.right * a[::-1]

    def left_complement(self, a):
        return self.left * a[::-1]

    def pseudoscalar(self):
        out = self.zero()
        out[-1] = 1.0
        return out

    def dual(self, a):
        square = self.gp(self.pseudoscalar(), self.pseudoscalar())[0]
        if square == 0:
            return self.right_complement(a)
        return self.gp(a, self.pseudoscalar() / square)

    def undual(self, a):
        if self.gp(self.pseudoscalar(), self.pseudoscalar())[0] == 0:
            return self.left_complement(a)
        return self.gp(a, self.pseudoscalar())

    def vee(self, a, b):
        return self.left_complement(self.op(self.right_complement(a), self.right_complement(b)))

    def inverse(self, a):
        # x y = 1: the matrix of y -> x y, solved (clifford's inv does the same)
        matrix = np.einsum("i,ikj->kj", a, self.gmt)
        y, *_ = np.linalg.lstsq(matrix, self.scalar(1.0), rcond=None)
        if np.max(np.abs(matrix @ y - self.scalar(1.0))) > 1e-8:
            raise ZeroDivisionError("not invertible")
        return y

    def exp(self, a):
        norm = max(np.max(np.abs(a)), 1e-300)
        halvings = max(0, math.ceil(math.log2(norm)) + 4)
        x = a / 2**halvings
        term, total = self.scalar(1.0), self.scalar(1.0)
        for k in range(1, 30):
            term = self.gp(term, x) / k
            total = total + term
        for _ in range(halvings):
            total = self.gp(total, total)
        return total

    def log(self, a):
        """The principal log of a + b (b a bivector with b² scalar): closed form, checked
        against exp."""
        s, b = a[0], self.grade(a, 2)
        beta = self.gp(b, b)[0]
        if beta < 0:
            phi = math.atan2(math.sqrt(-beta), s) / math.sqrt(-beta)
        elif beta > 0:
            phi = math.asinh(math.sqrt(beta)) / math.sqrt(beta)
        else:
            phi = 1.0
        out = b * phi
        assert np.allclose(self.exp(out), a, atol=1e-8 * (1 + np.max(np.abs(a))))
        return out

    def conformal(self):
        """(eo, einf, base vector indices) as clifford's ConformalLayout defines them."""
        ep, en = np.zeros(self.dim), np.zeros(self.dim)
        ep[self.n - 1], en[self.n] = 1.0, 1.0  # the last two basis vectors: +1 then -1
        return 0.5 * (en - ep), en + ep, list(range(1, self.n - 1))

    def up(self, x):
        eo, einf, _ = self.conformal()
        return x + 0.5 * self.gp(x, x)[0] * einf + eo

    def down(self, x):
        eo, einf, _ = self.conformal()
        homogeneous = x / -self.ip(x, einf)[0]
        e0 = self.op(einf, eo)
        return self.gp(self.op(homogeneous, e0), e0)


def _permutation_sign(digits: str, ordered: str) -> int:
    items = list(digits)
    sign = 1
    for i in range(len(items)):
        for j in range(len(items) - 1 - i):
            if items[j] > items[j + 1]:
                items[j], items[j + 1] = items[j + 1], items[j]
                sign = -sign
    assert "".join(items) == ordered
    return sign


def evaluate(node, env: dict[str, np.ndarray], alg: Algebra) -> np.ndarray:
    """The value of a parsed expression with the symbols of ``env`` (arrays)."""

    def ev(n):
        if isinstance(n, Number):
            return alg.scalar(float(n.value))
        if isinstance(n, Name):
            if n.name in env:
                return env[n.name]
            if n.name == "I":
                return alg.pseudoscalar()
            if n.name in ("eo", "einf"):
                eo, einf, _ = alg.conformal()
                return eo if n.name == "eo" else einf
            return alg.blade(n.name)
        if isinstance(n, Unary):
            x = ev(n.operand)
            return {"-": -x, "+": x, "~": alg.rev(x)}[n.op]
        if isinstance(n, Binary):
            if n.op == "**":
                k = int(n.right.value)
                x = ev(n.left) if k >= 0 else alg.inverse(ev(n.left))
                out = alg.scalar(1.0)
                for _ in range(abs(k)):
                    out = alg.gp(out, x)
                return out
            a, b = ev(n.left), ev(n.right)
            if n.op == "/":
                return alg.gp(a, alg.inverse(b))
            return {
                "+": lambda: a + b,
                "-": lambda: a - b,
                "*": lambda: alg.gp(a, b),
                "^": lambda: alg.op(a, b),
                "|": lambda: alg.ip(a, b),
                "&": lambda: alg.vee(a, b),
                ">>": lambda: alg.gp(alg.gp(a, b), alg.rev(a)),
            }[n.op]()
        args = [ev(a) for a in n.args]
        name = n.name
        if name == "grade":
            return alg.grade(args[0], int(n.args[1].value))
        table = {
            "lc": alg.lc,
            "rc": alg.rc,
            "inner": alg.ip,
            "scalar": lambda a, b: alg.grade(alg.gp(a, b), 0),
            "comm": lambda a, b: (alg.gp(a, b) - alg.gp(b, a)) / 2,
            "vee": alg.vee,
            "join": alg.vee,
            "meet": alg.op,
            "sandwich": lambda a, b: alg.gp(alg.gp(a, b), alg.rev(a)),
            "rev": alg.rev,
            "involute": alg.involute,
            "conj": lambda a: alg.rev(alg.involute(a)),
            "even": lambda a: np.where(alg.grades % 2 == 0, a, 0.0),
            "dual": alg.dual,
            "undual": alg.undual,
            "exp": alg.exp,
            "log": alg.log,
            "inverse": alg.inverse,
            "norm2": lambda a: alg.grade(alg.gp(a, alg.rev(a)), 0),
            "norm": lambda a: alg.scalar(math.sqrt(alg.gp(a, alg.rev(a))[0])),
            "up": alg.up,
            "down": alg.down,
        }
        return table[name](*args)

    return ev(node)
