"""Fit the rational approximations of :mod:`ga_rotors.sweep._normal` (run to print them).

``python -m ga_rotors.sweep._fit_normal`` prints the coefficient tuples that module
holds. Each piece is fitted to the exact inverse normal CDF (mpmath at 40 digits: the
root of ``ncdf(x) = p``) on Chebyshev nodes of its interval, minimising the relative
error: a linearised least-squares fit, reweighted by the previous denominator (Loeb's
iteration) and then by the error itself (Lawson's, towards the minimax fit). The
variables keep every coefficient positive (no cancellation in float64's Horner sums).
"""

from __future__ import annotations

import mpmath as mp

#: |u - 1/2| up to which the central piece applies; the tails cover p = min(u, 1 - u) ≤
#: 1/2 - CENTRAL.
CENTRAL = 0.425
#: The tails' variable r = sqrt(-ln p) runs from sqrt(-ln 0.075) = 1.60943… up to
#: sqrt(54 ln 2) = 6.1180 (p = 2⁻⁵⁴, the smallest u a draw makes); fitted on a little more.
TAIL_FROM, TAIL_TO = 1.6, 6.125


def _exact(p):
    """x with ncdf(x) = p, for 0 < p ≤ 1/2 (mpf)."""
    x = mp.sqrt(2) * mp.erfinv(2 * p - 1) if p > mp.mpf("0.01") else None
    if x is None:  # erfinv(2p - 1) near -1 loses digits: a root of the CDF itself
        guess = -mp.sqrt(-2 * mp.log(p))
        x = mp.findroot(lambda v: mp.ncdf(v) - p, guess, tol=(p * mp.mpf(10) ** -30) ** 2)
    return x


def _nodes(a, b, n: int) -> list:
    return [(a + b) / 2 + (b - a) / 2 * mp.cos(mp.pi * (k + mp.mpf(1) / 2) / n) for k in range(n)]


def fit(xs, fs, degree: int, loeb: int = 12, lawson: int = 30):
    """(max relative error, P, Q) of P(x)/Q(x) ≈ f, Q(0) = 1, both of ``degree``."""
    n = len(xs)
    below, weights, best = [mp.mpf(1)] * n, [mp.mpf(1)] * n, None
    for it in range(loeb + lawson):
        a, b = mp.matrix(n, 2 * degree + 1), mp.matrix(n, 1)
        for i, (x, f) in enumerate(zip(xs, fs, strict=True)):
            w = mp.sqrt(weights[i]) / (f * below[i])
            for k in range(degree + 1):
                a[i, k] = w * x**k
            for k in range(1, degree + 1):
                a[i, degree + k] = -w * f * x**k
            b[i] = w * f
        c = mp.qr_solve(a, b)[0]
        p = [c[k] for k in range(degree + 1)]
        q = [mp.mpf(1)] + [c[degree + k] for k in range(1, degree + 1)]
        below = [mp.polyval(q[::-1], x) for x in xs]
        err = [mp.polyval(p[::-1], x) / d / f - 1 for x, d, f in zip(xs, below, fs, strict=True)]
        worst = max(abs(e) for e in err)
        if best is None or worst < best[0]:
            best = (worst, p, q)
        if it >= loeb:
            weights = [w * abs(e) for w, e in zip(weights, err, strict=True)]
            total = sum(weights)
            weights = [w / total * n for w in weights]
    return best


def central(degree: int = 8, nodes: int = 100):
    """The central piece: x = q·P(s)/Q(s), q = u - 1/2, s = CENTRAL² - q²."""
    c2 = mp.mpf(CENTRAL) ** 2
    ss = _nodes(mp.mpf(0), c2, nodes)
    fs = []
    for s in ss:
        q = mp.sqrt(c2 - s)
        fs.append(-_exact(mp.mpf(1) / 2 - q) / q if q > 0 else mp.sqrt(2 * mp.pi))
    return fit(ss, fs, degree)


def tail(degree: int = 8, nodes: int = 100):
    """The tails: -x(p) = P(r - TAIL_FROM)/Q(r - TAIL_FROM), r = sqrt(-ln p)."""
    rs = _nodes(mp.mpf(TAIL_FROM), mp.mpf(TAIL_TO), nodes)
    fs = [-_exact(mp.exp(-r * r)) for r in rs]
    return fit([r - TAIL_FROM for r in rs], fs, degree)


def main() -> None:
    mp.mp.dps = 40
    for name, (err, p, q) in (("CENTRAL", central()), ("TAIL", tail())):
        print(f"# {name.lower()}: largest relative error of the fit {mp.nstr(err, 3)}")
        for part, coefficients in (("P", p), ("Q", q)):
            print(f"_{name}_{part} = (")
            for v in coefficients:
                print(f"    {float(v)!r},")
            print(")")


if __name__ == "__main__":
    main()
