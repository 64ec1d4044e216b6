"""Measured figures of docs/stability.md: fast spin and long runs, every fixed-step method.

Run from the repository root: ``python benchmarks/bench_stability.py`` (about 30 s).
Prints two Markdown tables: (1) the fast spinner, 1000 rad/s at h = 1 ms for 1 s, on an
asymmetric body (1, 1.5, 2) and on the flat disk (1, 1, 2), against the exact references;
(2) 10⁶ steps of h = 0.01 on the (1, 2, 3) top: |L|, space-frame L and energy drift;
(3) extreme bodies, on the setups of tests/test_stability_bodies.py (imported from there,
so the printed figures and the tested ones are the same runs): each method's turn per step
on the sphere and the near-sphere against its prediction, and the rods.
"""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ga_rotors import quaternion as Q
from ga_rotors.integrators import Problem, get, names
from ga_rotors.reference.asymmetric_top import AsymmetricTop
from ga_rotors.reference.symmetric_top import SymmetricTop

TILT = np.array((0.3, 0.1, 0.9, 0.2)) / np.sqrt(0.95)


def methods():
    out = []
    for n in names():
        integ = get(n)
        if "free" in integ.problems and "quaternion" in integ.paths and n != "dop853":
            out.append(n)
    return out


def fast_spin():
    print("| method | body | complete | orientation error (rad) | max ΔE/E | ‖ω⊥‖ end / start |")
    print("|---|---|---|---|---|---|")
    for label, inertia, ref in (("(1, 1.5, 2)", (1.0, 1.5, 2.0), AsymmetricTop),
                                ("disk (1, 1, 2)", (1.0, 1.0, 2.0), SymmetricTop)):  # fmt: skip
        w0 = (5.0, 3.0, 1000.0)
        exact = ref(inertia, TILT, w0).at([1.0])[0][0]
        i = np.array(inertia)
        e0 = 0.5 * (i * np.array(w0) ** 2).sum()
        for name in methods():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = get(name).run(Problem(inertia), "quaternion", TILT, w0, 0.0, 1e-3, 1000, 1)
            with np.errstate(all="ignore"):
                e = 0.5 * (run.w**2 * i).sum(1)
                de = np.abs(e - e0).max() / e0
                err = Q.distance(exact, Q.normalize(run.x[-1])) if run.complete else np.nan
                wp = np.hypot(*run.w[-1, :2]) / np.hypot(*w0[:2])
            status = "yes" if run.complete else f"stopped at {run.t[-1]:g} s"
            print(f"| {name} | {label} | {status} | {err:.2g} | {de:.2g} | {wp:.3g} |")


def long_runs():
    inertia, w0, h, n = (1.0, 2.0, 3.0), (1.0, 0.5, 0.2), 0.01, 10**6
    i = np.array(inertia)
    print("| method | time (s) | max Δ‖L‖/‖L‖ | max ‖ΔL_space‖/‖L‖ | max ΔE/E |")
    print("|---|---|---|---|---|")
    for name in ("split2", "split4", "split6", "split_sym", "lgvi", "rk4", "rk4_renorm"):
        get(name).run(Problem(inertia), "quaternion", TILT, w0, 0.0, h, 10, 10)  # compile
        t0 = time.perf_counter()
        run = get(name).run(Problem(inertia), "quaternion", TILT, w0, 0.0, h, n, 1000)
        elapsed = time.perf_counter() - t0
        L = run.w * i
        ln = np.linalg.norm(L, axis=1)
        ls = Q.rotate(Q.normalize(run.x), L)
        e = 0.5 * (run.w**2 * i).sum(1)
        print(f"| {name} | {elapsed:.2f} | {np.abs(ln / ln[0] - 1).max():.2g} | "
              f"{(np.linalg.norm(ls - ls[0], axis=1) / ln[0]).max():.2g} | "
              f"{np.abs(e / e[0] - 1).max():.2g} |")  # fmt: skip


def extreme_bodies():
    from tests import test_stability_bodies as B

    print("| method | predicted (rad) | nearly spherical | spherical |")
    print("|---|---|---|---|")
    sphere = (1.0, 1.0, 1.0)
    for name in sorted(B.TURN):
        errors = []
        for body, ref in ((B.NEAR_SPHERE, AsymmetricTop), (sphere, SymmetricTop)):
            run, predicted = B._turn_error(body, name)
            exact = ref(body, B.Q0, B.W0).at(run.t)[0]
            errors.append(Q.distance(exact, Q.normalize(run.x)).max())
        print(f"| {name} | {predicted:.4g} | {errors[0]:.4g} | {errors[1]:.4g} |")
    print()
    print("| method | rod | orientation error (rad) | max \\|ω₃ − ω₃(0)\\| (rad/s) |")
    print("|---|---|---|---|")
    for thin in (1e-6, 1e-12):
        rod, h, n = (1.0, 1.0, thin), 0.01, 1000
        for name in ("rk4", "dp8", "split_sym", "split2", "split4", "split6", "lgvi"):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = get(name).run(Problem(rod), "quaternion", B.Q0, B.ROD_W, 0.0, h, n, 1)
            exact = SymmetricTop(rod, B.Q0, B.ROD_W).at(run.t)[0]
            err = Q.distance(exact, Q.normalize(run.x)).max()
            dw = np.abs(run.w[:, 2] - B.ROD_W[2]).max()
            print(f"| {name} | (1, 1, {thin:g}) | {err:.2g} | {dw:.2g} |")


if __name__ == "__main__":
    fast_spin()
    print()
    long_runs()
    print()
    extreme_bodies()
