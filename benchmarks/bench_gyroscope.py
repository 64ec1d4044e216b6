"""The paper's 10,000-step gyroscope run: the project's RK4 against compiled floors and peers.

Usage (from the repository root)::

    python benchmarks/bench_gyroscope.py [--repeats 7] [--no-main-job]

Every timing is the minimum over repeats after a warm-up run, measured in this process
(the main job in fresh subprocesses), so the ratios compare methods under the same load.
Rows:

* ga_rotors RK4, rotor and quaternion paths: ``Integrator.run`` end to end (allocation and
  Python wrapper included) and the compiled loop alone;
* compiled floors: a minimal hand-written numba RK4 on (q, ω) and the same loop in C
  (``gcc -O3 -march=native``, compiled here and loaded with ctypes), both storing every step
  like the project's loop;
* peers: MuJoCo (one free body, same inertia, its RK4; C rollout and a Python mj_step loop),
  scipy's DOP853 at rtol 1e-9, clifford's MultiVector RK4 inside numba and at object level.

Each row also reports its final-state geodesic error against the exact solution, so a fast
row that integrates something else would show.
"""

from __future__ import annotations

import argparse
import ctypes
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ga_rotors import euler, shapes  # noqa: E402
from ga_rotors._jit import jit  # noqa: E402
from ga_rotors.integrators import (  # noqa: E402
    Problem,
    _cache,
    get,
)
from ga_rotors.kinematics import body_omega_from_zyz_rates  # noqa: E402
from ga_rotors.paths import rotor as rotor_path  # noqa: E402
from ga_rotors.quaternion import distance  # noqa: E402
from ga_rotors.reference.symmetric_top import SymmetricTop  # noqa: E402

H = 1e-3
N = 10_000
MOMENTS = shapes.disk(2.0, 0.075)
ANGLES0 = np.radians([0.0, 15.0, 0.0])
W0 = body_omega_from_zyz_rates(ANGLES0, [0.02, 0.02, 15.7])
Q0 = euler.to_quaternion("ZYZ", ANGLES0)
EXACT_FINAL = SymmetricTop(MOMENTS, Q0, W0).at([N * H])[0][0]


def best(fn, repeats: int) -> float:
    fn()  # warm-up: loads compiled code, touches memory
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def interleaved(fns: dict, repeats: int) -> dict:
    """Minimum time of each function, timed round-robin so that load changes on a shared
    machine hit every contender alike."""
    for fn in fns.values():
        fn()
    times = {name: [] for name in fns}
    for _ in range(repeats):
        for name, fn in fns.items():
            t = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - t)
    return {name: min(v) for name, v in times.items()}


def error(q) -> float:
    q = np.asarray(q, dtype=np.float64)
    return float(distance(q / np.linalg.norm(q), EXACT_FINAL))


# ------------------------------------------------------------------ the compiled floors


@jit
def floor_rk4(q0, w0, h, n, i1, i2, i3, out_q, out_w):
    """Hand-written RK4 on (q, ω): scalar locals, no abstraction, every step stored."""
    a, b, c, d = q0[0], q0[1], q0[2], q0[3]
    x, y, z = w0[0], w0[1], w0[2]
    k1_, k2_, k3_ = (i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3
    out_q[0, 0], out_q[0, 1], out_q[0, 2], out_q[0, 3] = a, b, c, d
    out_w[0, 0], out_w[0, 1], out_w[0, 2] = x, y, z
    for i in range(n):
        # stage 1
        qa1 = 0.5 * (-b * x - c * y - d * z)
        qb1 = 0.5 * (a * x + c * z - d * y)
        qc1 = 0.5 * (a * y - b * z + d * x)
        qd1 = 0.5 * (a * z + b * y - c * x)
        wx1, wy1, wz1 = k1_ * y * z, k2_ * z * x, k3_ * x * y
        # stage 2
        a2, b2, c2, d2 = a + 0.5 * h * qa1, b + 0.5 * h * qb1, c + 0.5 * h * qc1, d + 0.5 * h * qd1
        x2, y2, z2 = x + 0.5 * h * wx1, y + 0.5 * h * wy1, z + 0.5 * h * wz1
        qa2 = 0.5 * (-b2 * x2 - c2 * y2 - d2 * z2)
        qb2 = 0.5 * (a2 * x2 + c2 * z2 - d2 * y2)
        qc2 = 0.5 * (a2 * y2 - b2 * z2 + d2 * x2)
        qd2 = 0.5 * (a2 * z2 + b2 * y2 - c2 * x2)
        wx2, wy2, wz2 = k1_ * y2 * z2, k2_ * z2 * x2, k3_ * x2 * y2
        # stage 3
        a3, b3, c3, d3 = a + 0.5 * h * qa2, b + 0.5 * h * qb2, c + 0.5 * h * qc2, d + 0.5 * h * qd2
        x3, y3, z3 = x + 0.5 * h * wx2, y + 0.5 * h * wy2, z + 0.5 * h * wz2
        qa3 = 0.5 * (-b3 * x3 - c3 * y3 - d3 * z3)
        qb3 = 0.5 * (a3 * x3 + c3 * z3 - d3 * y3)
        qc3 = 0.5 * (a3 * y3 - b3 * z3 + d3 * x3)
        qd3 = 0.5 * (a3 * z3 + b3 * y3 - c3 * x3)
        wx3, wy3, wz3 = k1_ * y3 * z3, k2_ * z3 * x3, k3_ * x3 * y3
        # stage 4
        a4, b4, c4, d4 = a + h * qa3, b + h * qb3, c + h * qc3, d + h * qd3
        x4, y4, z4 = x + h * wx3, y + h * wy3, z + h * wz3
        qa4 = 0.5 * (-b4 * x4 - c4 * y4 - d4 * z4)
        qb4 = 0.5 * (a4 * x4 + c4 * z4 - d4 * y4)
        qc4 = 0.5 * (a4 * y4 - b4 * z4 + d4 * x4)
        qd4 = 0.5 * (a4 * z4 + b4 * y4 - c4 * x4)
        wx4, wy4, wz4 = k1_ * y4 * z4, k2_ * z4 * x4, k3_ * x4 * y4
        s = h / 6.0
        a += s * (qa1 + 2.0 * (qa2 + qa3) + qa4)
        b += s * (qb1 + 2.0 * (qb2 + qb3) + qb4)
        c += s * (qc1 + 2.0 * (qc2 + qc3) + qc4)
        d += s * (qd1 + 2.0 * (qd2 + qd3) + qd4)
        x += s * (wx1 + 2.0 * (wx2 + wx3) + wx4)
        y += s * (wy1 + 2.0 * (wy2 + wy3) + wy4)
        z += s * (wz1 + 2.0 * (wz2 + wz3) + wz4)
        out_q[i + 1, 0], out_q[i + 1, 1], out_q[i + 1, 2], out_q[i + 1, 3] = a, b, c, d
        out_w[i + 1, 0], out_w[i + 1, 1], out_w[i + 1, 2] = x, y, z


C_SOURCE = r"""
#include <stddef.h>
#define STAGE(a,b,c,d,x,y,z,qa,qb,qc,qd,wx,wy,wz) \
    qa = 0.5*(-(b)*(x)-(c)*(y)-(d)*(z)); qb = 0.5*((a)*(x)+(c)*(z)-(d)*(y)); \
    qc = 0.5*((a)*(y)-(b)*(z)+(d)*(x)); qd = 0.5*((a)*(z)+(b)*(y)-(c)*(x)); \
    wx = k1*(y)*(z); wy = k2*(z)*(x); wz = k3*(x)*(y);
void rk4(const double *q0, const double *w0, double h, long n, double i1, double i2,
         double i3, double *out_q, double *out_w) {
    double a=q0[0], b=q0[1], c=q0[2], d=q0[3], x=w0[0], y=w0[1], z=w0[2];
    double k1=(i2-i3)/i1, k2=(i3-i1)/i2, k3=(i1-i2)/i3, s=h/6.0, hh=0.5*h;
    double qa1,qb1,qc1,qd1,wx1,wy1,wz1, qa2,qb2,qc2,qd2,wx2,wy2,wz2;
    double qa3,qb3,qc3,qd3,wx3,wy3,wz3, qa4,qb4,qc4,qd4,wx4,wy4,wz4;
    out_q[0]=a; out_q[1]=b; out_q[2]=c; out_q[3]=d; out_w[0]=x; out_w[1]=y; out_w[2]=z;
    for (long i = 0; i < n; i++) {
        STAGE(a,b,c,d,x,y,z,qa1,qb1,qc1,qd1,wx1,wy1,wz1)
        STAGE(a+hh*qa1,b+hh*qb1,c+hh*qc1,d+hh*qd1,x+hh*wx1,y+hh*wy1,z+hh*wz1,
              qa2,qb2,qc2,qd2,wx2,wy2,wz2)
        STAGE(a+hh*qa2,b+hh*qb2,c+hh*qc2,d+hh*qd2,x+hh*wx2,y+hh*wy2,z+hh*wz2,
              qa3,qb3,qc3,qd3,wx3,wy3,wz3)
        STAGE(a+h*qa3,b+h*qb3,c+h*qc3,d+h*qd3,x+h*wx3,y+h*wy3,z+h*wz3,
              qa4,qb4,qc4,qd4,wx4,wy4,wz4)
        a += s*(qa1+2.0*(qa2+qa3)+qa4); b += s*(qb1+2.0*(qb2+qb3)+qb4);
        c += s*(qc1+2.0*(qc2+qc3)+qc4); d += s*(qd1+2.0*(qd2+qd3)+qd4);
        x += s*(wx1+2.0*(wx2+wx3)+wx4); y += s*(wy1+2.0*(wy2+wy3)+wy4);
        z += s*(wz1+2.0*(wz2+wz3)+wz4);
        double *q = out_q + 4*(i+1), *w = out_w + 3*(i+1);
        q[0]=a; q[1]=b; q[2]=c; q[3]=d; w[0]=x; w[1]=y; w[2]=z;
    }
}
"""


def build_c(tmp: Path):
    """Compile the C floor with gcc (None if there is no gcc)."""
    gcc = shutil.which("gcc")
    if gcc is None:
        return None
    src, lib = tmp / "rk4.c", tmp / "rk4.so"
    src.write_text(C_SOURCE)
    subprocess.run(
        [gcc, "-O3", "-march=native", "-shared", "-fPIC", str(src), "-o", str(lib)], check=True
    )
    dll = ctypes.CDLL(str(lib))
    p = ctypes.POINTER(ctypes.c_double)
    dll.rk4.argtypes = [p, p, ctypes.c_double, ctypes.c_long, ctypes.c_double, ctypes.c_double,
                        ctypes.c_double, p, p]  # fmt: skip
    dll.rk4.restype = None
    return dll


# ------------------------------------------------------------------------------ peers


def mujoco_model():
    import mujoco

    i1, i2, i3 = MOMENTS
    xml = f"""
    <mujoco>
      <option timestep="{H}" integrator="RK4" gravity="0 0 0"/>
      <worldbody>
        <body name="disk">
          <freejoint/>
          <inertial pos="0 0 0" mass="2" diaginertia="{i1!r} {i2!r} {i3!r}"/>
        </body>
      </worldbody>
    </mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    return mujoco, model, data


def mujoco_initial(mujoco, model, data):
    mujoco.mj_resetData(model, data)
    data.qpos[3:7] = Q0  # free joint: position, then quaternion (w, x, y, z)
    data.qvel[3:6] = W0  # free joint angular velocity: body frame
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, state, spec)
    return state


def scipy_dop853():
    from scipy.integrate import solve_ivp

    i1, i2, i3 = MOMENTS

    def rhs(t, y):
        a, b, c, d, x, yy, z = y
        return [
            0.5 * (-b * x - c * yy - d * z),
            0.5 * (a * x + c * z - d * yy),
            0.5 * (a * yy - b * z + d * x),
            0.5 * (a * z + b * yy - c * x),
            (i2 - i3) * yy * z / i1,
            (i3 - i1) * z * x / i2,
            (i1 - i2) * x * yy / i3,
        ]

    def run():
        sol = solve_ivp(rhs, (0.0, N * H), [*Q0, *W0], method="DOP853", rtol=1e-9, atol=1e-12)
        return sol.y[:4, -1], sol.nfev

    return run


def clifford_rotor_rk4():
    """RK4 on Ṙ = ½ R Ω with clifford MultiVectors: inside numba, and at object level."""
    import clifford
    import numba

    layout, blades = clifford.Cl(3)
    e1, e2, e3, pseudo = blades["e1"], blades["e2"], blades["e3"], blades["e123"]
    i1, i2, i3 = MOMENTS

    def make(decorate):
        @decorate
        def rates(R, x, y, z):
            omega = -(pseudo * (x * e1 + y * e2 + z * e3))
            return (
                0.5 * R * omega,
                (i2 - i3) * y * z / i1,
                (i3 - i1) * z * x / i2,
                (i1 - i2) * x * y / i3,
            )

        @decorate
        def run(R, x, y, z, h, n):
            for _ in range(n):
                k1, a1, b1, c1 = rates(R, x, y, z)
                k2, a2, b2, c2 = rates(R + 0.5 * h * k1, x + 0.5 * h * a1, y + 0.5 * h * b1,
                                       z + 0.5 * h * c1)  # fmt: skip
                k3, a3, b3, c3 = rates(R + 0.5 * h * k2, x + 0.5 * h * a2, y + 0.5 * h * b2,
                                       z + 0.5 * h * c2)  # fmt: skip
                k4, a4, b4, c4 = rates(R + h * k3, x + h * a3, y + h * b3, z + h * c3)
                s = h / 6.0
                R = R + s * (k1 + 2.0 * (k2 + k3) + k4)
                x = x + s * (a1 + 2.0 * (a2 + a3) + a4)
                y = y + s * (b1 + 2.0 * (b2 + b3) + b4)
                z = z + s * (c1 + 2.0 * (c2 + c3) + c4)
            return R

        return run

    R0 = layout.MultiVector()
    R0.value[[0, 4, 5, 6]] = rotor_path.initial_state(Q0)
    compiled, plain = make(numba.njit), make(lambda f: f)

    def as_quaternion(R):
        return rotor_path.quaternions(np.asarray(R.value)[[0, 4, 5, 6]])

    return (
        lambda: as_quaternion(compiled(R0, *W0, H, N)),
        lambda: as_quaternion(plain(R0, *W0, H, N)),
    )


def main_job_wall(repeats: int) -> tuple[float, float]:
    """(min wall, CPU of that run: user + sys of the command and its figure workers)."""
    import resource

    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    runs = []
    with tempfile.TemporaryDirectory() as out:
        cmd = [sys.executable, "-m", "ga_rotors", "paper", "--out", out]
        subprocess.run(cmd, env=env, check=True, capture_output=True)  # warm the caches
        for _ in range(repeats):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t = time.perf_counter()
            subprocess.run(cmd, env=env, check=True, capture_output=True)
            wall = time.perf_counter() - t
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            runs.append((wall, cpu))
    return min(runs)


# ------------------------------------------------------------------------------- main


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--no-main-job", action="store_true")
    args = parser.parse_args(argv)
    r = args.repeats
    rows: list[tuple[str, float, float | None, str]] = []  # name, seconds, error, note

    rk4 = get("rk4")
    problem = Problem(MOMENTS)
    contenders, results, notes = {}, {}, {}
    for path, x0 in (("rotor", rotor_path.initial_state(Q0)), ("quaternion", Q0)):

        def end_to_end(path=path, x0=x0):
            results[f"run {path}"] = rk4.run(problem, path, x0, W0, 0.0, H, N, 1)

        loop = _cache.specialise(rk4, problem, path).module.loop
        out = (np.empty(N + 1), np.empty((N + 1, 4)), np.empty((N + 1, 3)))
        params, stats = np.zeros(0), np.zeros(0)

        def loop_only(loop=loop, x0=x0, out=out, params=params, stats=stats):
            loop(x0, W0, 0.0, H, 0, N, 1, MOMENTS, params, *out, stats)

        contenders[f"ga_rotors rk4, {path} path (run)"] = end_to_end
        notes[f"ga_rotors rk4, {path} path (run)"] = "Integrator.run, fresh output arrays"
        contenders[f"ga_rotors rk4, {path} path (loop)"] = loop_only
        notes[f"ga_rotors rk4, {path} path (loop)"] = "compiled loop, reused arrays"

    out_q, out_w = np.empty((N + 1, 4)), np.empty((N + 1, 3))
    contenders["floor: hand-written numba RK4"] = lambda: floor_rk4(
        Q0, W0, H, N, *MOMENTS, out_q, out_w
    )
    notes["floor: hand-written numba RK4"] = "reused arrays"

    tmpdir = tempfile.TemporaryDirectory()
    dll = build_c(Path(tmpdir.name))
    if dll is not None:
        cq, cw = np.empty((N + 1, 4)), np.empty((N + 1, 3))
        dp = ctypes.POINTER(ctypes.c_double)
        q0c, w0c = np.ascontiguousarray(Q0), np.ascontiguousarray(W0)
        args_c = (q0c.ctypes.data_as(dp), w0c.ctypes.data_as(dp), H, N, *MOMENTS,
                  cq.ctypes.data_as(dp), cw.ctypes.data_as(dp))  # fmt: skip
        contenders["floor: C gcc -O3 -march=native"] = lambda: dll.rk4(*args_c)
        notes["floor: C gcc -O3 -march=native"] = "ctypes, reused arrays"

    timed = interleaved(contenders, r)
    for name, t in timed.items():
        if "rotor path (run)" in name:
            err = error(rotor_path.quaternions(results["run rotor"].x[-1]))
        elif "quaternion path (run)" in name:
            err = error(results["run quaternion"].x[-1])
        elif name.startswith("floor: hand"):
            err = error(out_q[-1])
        elif name.startswith("floor: C"):
            err = error(cq[-1])
        else:
            err = None
        rows.append((name, t, err, notes[name]))
    floor = timed["floor: hand-written numba RK4"]
    c_floor = timed.get("floor: C gcc -O3 -march=native")

    try:
        mujoco, model, data = mujoco_model()
        from mujoco import rollout

        state0 = mujoco_initial(mujoco, model, data)

        def mj_rollout():
            return rollout.rollout(model, data, state0[None, :], nstep=N)

        t = best(mj_rollout, r)
        st = mj_rollout()[0]
        q_mj = st[0][-1, 1 + 3 : 1 + 7]  # state: time, qpos (pos 3, quat 4), ...
        note = f"mujoco {mujoco.__version__}"
        rows.append(("MuJoCo RK4 (rollout, C loop)", t, error(q_mj), note))

        def mj_python():
            mujoco.mj_setState(model, data, state0, mujoco.mjtState.mjSTATE_FULLPHYSICS)
            for _ in range(N):
                mujoco.mj_step(model, data)

        t = best(mj_python, max(1, r // 2))
        rows.append(("MuJoCo RK4 (Python mj_step loop)", t, error(data.qpos[3:7]), ""))
    except ImportError:
        print("MuJoCo not installed: skipped (pip install '.[peers]')")

    dop = scipy_dop853()
    res = {}
    t = best(lambda: res.update(r=dop()), max(1, r // 2))
    rows.append(("scipy DOP853 rtol 1e-9", t, error(res["r"][0]), f"{res['r'][1]} f-evals"))

    in_numba, object_level = clifford_rotor_rk4()
    res = {}
    t = best(lambda: res.update(q=in_numba()), max(1, r // 2))
    rows.append(("clifford MultiVector RK4 in numba", t, error(res["q"]), ""))
    t0 = time.perf_counter()
    q_obj = object_level()
    rows.append(("clifford MultiVector RK4, objects", time.perf_counter() - t0, error(q_obj),
                 "one run"))  # fmt: skip

    print(f"The paper's run: RK4, {N:,} steps of {H * 1e3:g} ms, disk, θ₀ = 15°; "
          f"min of {r} repeats after warm-up.")  # fmt: skip
    head = f"{'':38}{'time':>12}{'ns/step':>11}{'/numba':>9}{'/C':>9}{'error (rad)':>13}"
    print(head)
    for name, t, err, note in rows:
        c_ratio = f"{t / c_floor:9.2f}" if c_floor else f"{'-':>9}"
        e = f"{err:13.1e}" if err is not None else f"{'':13}"
        print(f"{name:38}{t * 1e3:10.3f}ms{t / N * 1e9:11.1f}{t / floor:9.2f}{c_ratio}{e}  {note}")

    if not args.no_main_job:
        wall, cpu = main_job_wall(5)
        print(f"\nmain job `ga-rotors paper` (import, cached JIT, 4 scenes x 3 paths, 9 "
              f"figures, 4 CSV): {wall:.2f} s wall (min of 5, warm cache), "
              f"{cpu:.2f} s CPU in its 3 processes")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
