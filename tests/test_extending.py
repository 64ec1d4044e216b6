"""docs/extending.md, run as written: a toy torque effect, Euler-angle path, output format,
integrator and problem kind registered through exactly the documented steps, in a fresh
process (registries are per process, so the suite's own registries stay as shipped), then
checked against independent oracles."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "extending.md"
BLOCK = re.compile(
    r"^```python (file=(?P<file>\S+)|run)[ \t]*\n(?P<code>.*?)^```[ \t]*$", re.S | re.M
)

# Run after the page's script, in its namespace: what the toy extensions must satisfy.
CHECKS = """
import json as _json
from scipy.spatial.transform import Rotation
from ga_rotors import kinematics, quaternion as Q

# the rotation part of the free flight, on the built-in quaternion path
free = get("rk4").run(Problem((1.0, 2.0, 3.0)), "quaternion", pose0[:4], rates0[:3], 0.0,
                      1e-3, 2000, 100)
rng = np.random.default_rng(5)
q = Q.normalize(rng.normal(size=4))
m, B = rng.normal(size=3), rng.normal(size=3)
tau = my_extensions.magnetic_torque(0.0, tuple(q), (0.0, 0.0, 0.0), np.concatenate([m, B]))
body_B = Rotation.from_quat([q[1], q[2], q[3], q[0]]).inv().apply(B)
angles = np.array([0.4, 1.1, -0.7])
w = np.array([0.3, -0.8, 0.5])
rates = np.array(my_extensions.rate(tuple(angles), tuple(w)))
inertia = np.array(scene.body.moments)
b_body = Q.rotate(Q.conjugate(Q.normalize(tr.quaternions())), [0.5, 0.0, 0.0])
energy = 0.5 * np.einsum("ni,i,ni->n", tr.w, inertia, tr.w) - b_body[:, 2]
print(_json.dumps({
    "torque": float(np.abs(np.array(tau) - np.cross(m, body_B)).max()),
    "to_quat": float(Q.distance(my_extensions.to_quat(tuple(angles)),
                                gr.euler.to_quaternion("ZXZ", angles))),
    "rate": float(np.abs(kinematics.body_omega_from_euler_rates("ZXZ", angles, rates) - w).max()),
    "cross_check": check.max_angle,
    "paths": list(tr.meta["paths"]),
    "energy_drift": float(np.abs(energy - energy[0]).max() / abs(energy[0])),
    "json_q": float(np.abs(np.array(_json.loads(written[0].read_text())["q"])
                           - tr.quaternions()).max()),
    "files": [p.name for p in written],
    "effect_in_schema": "magnetic" in gr.effects.EFFECTS,
    "heun_order": float(np.log2(coarse.error / fine.error)),
    "heun_evaluations": [coarse.evaluations, fine.evaluations],
    "flight_position": float(np.abs(flight.x[:, 4:] - np.outer(flight.t, rates0[3:])).max()),
    "flight_rotation_is_rk4s": bool(np.array_equal(flight.x[:, :4], free.x)
                                    and np.array_equal(flight.w[:, :3], free.w)),
    "flight_v": bool((flight.w[:, 3:] == rates0[3:]).all()),
    "terminal": float(abs(-fall.velocities()[-1, 2] - terminal) / terminal),
    "heun_simulate": float(Q.distance(
        gr.simulate([1.0, 2.0, 3.0], [1, 0, 0, 0], [1.0, 0.5, 0.2], duration=1.0, step=1e-3,
                    integrator="heun").quaternions()[-1],
        gr.simulate([1.0, 2.0, 3.0], [1, 0, 0, 0], [1.0, 0.5, 0.2], duration=1.0, step=1e-3,
                    integrator="rk4").quaternions()[-1])),
}))
"""


def documented_steps() -> tuple[dict[str, str], str]:
    files: dict[str, str] = {}
    script = []
    for m in BLOCK.finditer(PAGE.read_text(encoding="utf-8")):
        if m["file"]:
            files[m["file"]] = files.get(m["file"], "") + m["code"] + "\n"
        else:
            script.append(m["code"])
    return files, "\n".join(script)


def test_the_page_documents_each_extension_with_its_files():
    text = PAGE.read_text(encoding="utf-8")
    for heading in ("## A torque effect", "## An Euler-angle path", "## An output format",
                    "## An integrator", "## A problem kind", "## A force"):  # fmt: skip
        assert heading in text
    files, script = documented_steps()
    assert list(files) == ["my_extensions.py", "my_motion.py"]
    assert "import my_extensions" in script and "import my_motion" in script
    assert files["my_motion.py"].count("integrators.register_kind(") == 1
    module = files["my_extensions.py"]
    assert module.count("integrators.TemplateIntegrator(") == 1  # the toy integrator
    for registration in ("effects.register(", "paths.register(", "formats.register("):
        assert module.count(registration) == 1, registration


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_toy_extensions_registered_as_documented_work_end_to_end(tmp_path):
    files, script = documented_steps()
    for name, code in files.items():
        (tmp_path / name).write_text(code, encoding="utf-8")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), str(ROOT)])}
    proc = subprocess.run(
        [sys.executable, "-c", script + textwrap.dedent(CHECKS)],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.strip().splitlines()
    assert lines[0].startswith("rotor vs euler_zxz: max ")
    assert lines[1] == "['compass.json', 'compass.scene.toml']"
    got = json.loads(lines[-1])
    assert got["torque"] < 1e-14 and got["to_quat"] < 1e-15 and got["rate"] < 1e-14
    assert got["paths"] == ["rotor", "euler_zxz"]
    # RK4 at h = 1e-3 on two parametrisations of one slow motion (|ω| < 1): ~(h|ω|)⁴ apart
    assert got["cross_check"] < 1e-12
    # The dipole's energy ½ω·Iω − m·b is conserved by the motion; RK4 drifts by h⁴
    assert got["energy_drift"] < 1e-12
    assert got["json_q"] == 0.0 and got["effect_in_schema"]
    # The toy integrator, registered as documented: the study runs it at its declared cost
    # (2 evaluations a step) and measures its order, 2; simulate runs it like a built-in
    # (Heun against RK4 at h = 1e-3 for 1 s on a slow top: O(h²) apart, ~1e-7).
    assert lines[2].startswith("heun: 8000 evaluations")
    assert abs(got["heun_order"] - 2.0) < 0.05 and got["heun_evaluations"] == [8000.0, 16000.0]
    assert 1e-10 < got["heun_simulate"] < 1e-5
    # The new kind, run by RK4 on the new path: the centre moves by v t (RK4 is exact on
    # a line: rounding only), and the rotation is the free body's on the quaternion path,
    # bit for bit (the same arithmetic, component by component)
    assert lines[3] == "after 2 s the centre is at [2.0, 0.0, 10.0]"
    assert got["flight_position"] < 1e-12
    assert got["flight_rotation_is_rk4s"] and got["flight_v"]
    # The new force, as documented: after ten time constants v_t/g the fall is at its
    # terminal speed √(m g / k) (tanh(10) = 1 − 4e-9), to RK4's error at h = 1 ms
    assert lines[4].startswith("after 20 s the ball falls at ")
    assert got["terminal"] < 1e-7
