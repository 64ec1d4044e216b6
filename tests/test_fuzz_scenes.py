"""Fuzzing scene files (issue 11): every bad scene is one line, never a traceback or a hang.

Hypothesis takes a bundled scene, applies one to three mutations (a value replaced by a
hostile one, a key deleted or added, a table replaced, nesting made deep, effects
repeated) and runs it the way a user would, ``ga-rotors run FILE --out DIR`` (in this
process, through :func:`ga_rotors.cli.main`, with a small step and memory budget so a
scene that asks for too much is refused rather than run). Hostile values: wrong types,
0, negatives, 1e300, 1e-320, ±inf, NaN, integers beyond 64 bits, a Unix timestamp as a
time, 10⁹ samples, empty and 10,000-character strings, names with slashes, NUL and
non-ASCII, deep arrays and tables, TOML dates, integers beyond float64 (10⁴⁰⁰), strings
and keys with control characters (escape sequences, a bidirectional override, newlines),
effects declared thousands of times, and the file saved with a UTF-8 byte-order mark.
Each run must end in one of three ways:

* exit 0, with a summary free of NaN and inf;
* exit 2, with exactly one line on stderr (``ga-rotors: error: FILE: KEY: ...``) of at
  most :data:`MAX_LINE` characters, none of them a control character, and no output
  folder;
* exit 3, with ``INCOMPLETE`` as the summary's first line (a path stopped early);

within :data:`HANG_SECONDS`, with no exception escaping ``main`` (a traceback) and no
NumPy RuntimeWarning (a silent inf or NaN). Fast by default; ``GA_ROTORS_FUZZ=long``
runs :data:`LONG_EXAMPLES` scenes (the count in docs/stability.md).
"""

from __future__ import annotations

import contextlib
import copy
import io
import json
import math
import os
import re
import signal
import tomllib
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ga_rotors import cli
from ga_rotors.scene import bundled, bundled_path

LONG = os.environ.get("GA_ROTORS_FUZZ", "") == "long"
EXAMPLES = 60
LONG_EXAMPLES = 1200
HANG_SECONDS = 120
MAX_LINE = 600
BUDGET = ["--max-steps", "3e5", "--max-memory", "0.05", "--no-progress"]

#: How the runs ended, over the session (printed at the end with ``-s``).
OUTCOMES: dict[str, int] = {}
#: The long search's failures (first line each), reported together at its end.
FAILURES: list[str] = []

_HOSTILE = [
    0, -1, 1, 3, 0.0, -0.0, -1.5, 1e300, -1e300, 1e-320, 5e-324, 1e-12, math.inf, -math.inf,
    math.nan, 2**63 - 1, 10**30, -(10**30), 1.7e9, 1e9, True, False, "", "x" * 10_000,
    "../../escape", "a/b", "ü", "\u0000", "rk4", "gravity", "quaternion", "deg", "rad/s",
    [], [1], [1, 2, 3], [0.0, 0.0, 0.0], [1e300, 1e300, 1e300], [math.nan, 0, 0],
    ["a", "b", "c"], [[1, 2], [3]], {}, {"x": 1}, "1979-05-27T07:32:00Z",
    10**400, -(10**400), [1, 2, 10**400], "\x1b]0;title\x07\x1b[2J", "top\n", "a\u202eb",
]  # fmt: skip

#: Keys that would act on a terminal if echoed raw.
_HOSTILE_KEYS = ["\x1b]0;title\x07", "\x1b[2J", "a\nb", "\u202eevil", "\x00", "\x7f"]

#: How many times the effects list repeats one entry: the cap, and far beyond it.
_EFFECT_COUNTS = [0, 1, 2, 3, 65, 2000]


class Hang(Exception):
    """A run exceeded HANG_SECONDS."""


def _deep(depth: int, kind: str):
    value: object = 1.0
    for _ in range(depth):
        value = [value] if kind == "array" else {"a": value}
    return value


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        if re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", v):
            return v  # a TOML date-time
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def to_toml(data: dict) -> str:
    """A scene dict as TOML: one ``key = value`` line per section, inline tables inside."""
    lines, tables = [], []
    for key, value in data.items():
        if key == "effects" and isinstance(value, list) and all(isinstance(e, dict) for e in value):
            for e in value:  # [[effects]] headers last: a key after one belongs to it
                tables.append("[[effects]]")
                tables += [f"{json.dumps(k)} = {_toml_value(x)}" for k, x in e.items()]
        else:
            lines.append(f"{json.dumps(key)} = {_toml_value(value)}")
    return "\n".join(lines + tables) + "\n"


def _leaves(value, prefix=()):
    """Every (path, value) in nested dicts and lists, tables included."""
    yield prefix, value
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _leaves(v, (*prefix, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _leaves(v, (*prefix, i))


def _set(data, path, value) -> None:
    target = data
    for p in path[:-1]:
        target = target[p]
    target[path[-1]] = value


def _base(name: str) -> dict:
    data = tomllib.loads(bundled_path(name).read_text(encoding="utf-8"))
    data.setdefault("output", {})["plots"] = []  # figures cost seconds; mutations may add them
    return data


BASES = {name: _base(name) for name in bundled()}


@st.composite
def mutated(draw) -> dict:
    name = draw(st.sampled_from(sorted(BASES)))
    data = json.loads(json.dumps(BASES[name]))  # a deep copy
    for _ in range(draw(st.integers(1, 3))):
        paths = [p for p, _ in _leaves(data) if p]
        op = draw(st.sampled_from(["replace", "replace", "replace", "delete", "add", "deep",
                                   "effects", "many", "key"]))  # fmt: skip
        if op == "effects":
            data["effects"] = [
                {
                    "type": "gravity",
                    "pivot_to_com": [0, 0, copy.deepcopy(draw(st.sampled_from(_HOSTILE)))],
                }
                for _ in range(draw(st.integers(0, 3)))
            ]
            continue
        if op == "many":
            entry = {"type": "body_torque", "torque": [0.0, 0.0, 1e-4]}
            data["effects"] = [dict(entry) for _ in range(draw(st.sampled_from(_EFFECT_COUNTS)))]
            continue
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        if op == "replace":
            _set(data, path, copy.deepcopy(draw(st.sampled_from(_HOSTILE))))  # not shared
        elif op == "delete":
            parent = data
            for p in path[:-1]:
                parent = parent[p]
            parent.pop(path[-1])
        elif op == "add":
            parent = data
            for p in path[:-1]:
                parent = parent[p]
            if isinstance(parent, dict):
                parent[draw(st.sampled_from(["extra", "x" * 300, "durations", ""]))] = 1
        elif op == "key":
            tables = [p for p, v in _leaves(data) if isinstance(v, dict)]
            parent = data
            for p in draw(st.sampled_from(tables)):
                parent = parent[p]
            parent[draw(st.sampled_from(_HOSTILE_KEYS))] = 1
        else:  # last: walking a 500-deep value again would exhaust this test's stack
            _set(data, path, _deep(draw(st.sampled_from([5, 50, 500])),
                                   draw(st.sampled_from(["array", "table"]))))  # fmt: skip
            break
    return data


def _alarm(signum, frame):
    raise Hang


def run_file(path: Path, out: Path) -> tuple[int, str, str, list]:
    """``ga-rotors run path --out out`` in this process: (status, stdout, stderr, warnings)."""
    stdout, stderr = io.StringIO(), io.StringIO()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(HANG_SECONDS)
    try:
        with (
            contextlib.redirect_stdout(stdout),
            contextlib.redirect_stderr(stderr),
            warnings.catch_warnings(record=True) as caught,
        ):
            warnings.simplefilter("always")
            status = cli.main(["run", str(path), "--out", str(out), *BUDGET])
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    return status, stdout.getvalue(), stderr.getvalue(), caught


def check_scene(text: str, folder: Path) -> str:
    """Run one scene file; return the outcome, or fail with the file's text."""
    path = folder / "fuzz.toml"
    path.write_text(text, encoding="utf-8")
    out = folder / "out"
    shown = text if len(text) < 3000 else text[:3000] + "..."
    try:
        status, stdout, stderr, caught = run_file(path, out)
    except Hang:
        raise AssertionError(f"hang (> {HANG_SECONDS} s) on:\n{shown}") from None
    except BaseException as exc:
        raise AssertionError(f"traceback {type(exc).__name__}: {exc!s:.300} on:\n{shown}") from None
    noisy = [w for w in caught if issubclass(w.category, RuntimeWarning)]
    assert not noisy, f"RuntimeWarning {noisy[0].message} on:\n{shown}"
    if status == 2:
        lines = stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("ga-rotors: error: "), (stderr, shown)
        assert len(lines[0]) <= MAX_LINE, f"{len(lines[0])}-character error: {lines[0][:200]}"
        assert lines[0].isprintable(), f"raw control characters in {lines[0]!r}"
        assert not out.exists(), f"exit 2 but {out} was written:\n{shown}"
        return "refused"
    assert status in (0, 3), f"exit {status}: {stderr[-500:]}\n{shown}"
    if status == 3:
        assert stdout.startswith("INCOMPLETE"), (stdout[:300], shown)
        return "incomplete"
    assert not re.search(r"\b(nan|inf)\b", stdout, re.I), f"NaN/inf in:\n{stdout}\n{shown}"
    return "ran"


@settings(
    max_examples=LONG_EXAMPLES if LONG else EXAMPLES,
    derandomize=not LONG,
    deadline=None,
    suppress_health_check=list(HealthCheck),
    database=None,
)
@given(mutated(), st.sampled_from(["", "", "", "\ufeff"]))
def test_mutated_scenes_run_or_are_refused_in_one_line(tmp_path_factory, data, mark):
    folder = tmp_path_factory.mktemp("fuzz")
    try:
        outcome = check_scene(mark + to_toml(data), folder)
    except AssertionError as exc:
        if not LONG:
            raise
        outcome = "FAILED"  # the long search counts every failure instead of stopping
        FAILURES.append(str(exc).splitlines()[0])
    OUTCOMES[outcome] = OUTCOMES.get(outcome, 0) + 1


def test_mutated_scenes_long_search_found_nothing():
    assert not FAILURES, "\n".join(FAILURES[:20])


@pytest.mark.parametrize(
    ("edit", "key"),
    [
        ({"time": {"duration": 1.0, "start": 1.7e9}}, "time.start"),  # a Unix timestamp
        ({"time": {"duration": 1e9}}, "time.duration"),  # beyond the budget
        ({"time": {"duration": 1e300}, "integrator": {"step": 1e-300}}, "integrator.step"),
        ({"scene": {"name": "n" * 10_000}}, "scene.name"),
        ({"time": {"duration": 1.0, "output_step": 1e300}}, "time.output_step"),
    ],
    ids=["unix-start", "budget", "uncountable-steps", "long-name", "sample-beyond-int64"],
)
def test_found_scenes_are_refused_by_key(tmp_path, edit, key):
    data = json.loads(json.dumps(BASES["spinning_disk"]))
    for section, values in edit.items():
        data.setdefault(section, {}).update(values)
    (tmp_path / "s.toml").write_text(to_toml(data))
    status, _, stderr, _ = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert status == 2 and f": {key}: " in stderr and len(stderr) <= MAX_LINE, stderr


def teardown_module():
    if OUTCOMES:
        print(f"\nfuzzed scenes: {sum(OUTCOMES.values())} ({OUTCOMES})")
        for line in sorted(set(FAILURES)):
            print("  ", line[:300])


@pytest.mark.parametrize("depth", [500, 5000])
def test_deep_nesting_is_one_line(tmp_path, depth):
    # tomllib recurses per level: a RecursionError traceback before (found by fuzzing)
    (tmp_path / "s.toml").write_text("[body]\nmoments = " + "[" * depth + "1" + "]" * depth)
    status, _, stderr, _ = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert status == 2 and stderr.strip().endswith("arrays or tables nested too deeply")


def test_a_huge_file_is_not_read(tmp_path, monkeypatch):
    from ga_rotors.scene import loading

    monkeypatch.setattr(loading, "MAX_FILE_BYTES", 1000)
    (tmp_path / "s.toml").write_text("# padding\n" * 200)
    status, _, stderr, _ = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert status == 2 and "a scene file is at most 1,000" in stderr


def test_reading_a_file_costs_its_size_not_the_cap(tmp_path):
    # A buffered read(limit + 1) allocated the whole 10 MB cap for every scene file read
    # (found as the saved-result viewer's memory bound failing).
    import tracemalloc

    from ga_rotors.scene.toml_io import read_file

    (tmp_path / "s.toml").write_text("x = 1\n")
    tracemalloc.start()
    try:
        text = read_file(tmp_path / "s.toml", 10**7)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert text == "x = 1\n" and peak < 100_000, peak


@pytest.mark.parametrize("limit, refused", [(1000, False), (999, True)])
def test_the_cap_holds_at_its_edge(tmp_path, limit, refused):
    from ga_rotors.errors import SceneError
    from ga_rotors.scene.toml_io import read_file

    (tmp_path / "s.toml").write_text("#" * 999 + "\n")  # 1000 bytes
    if refused:
        with pytest.raises(SceneError, match="1,000 bytes; a scene file is at most 999"):
            read_file(tmp_path / "s.toml", limit)
    else:
        assert len(read_file(tmp_path / "s.toml", limit)) == 1000


@pytest.mark.skipif(not os.path.isfile("/proc/self/status"), reason="no /proc")
def test_a_file_whose_size_the_kernel_does_not_know_is_read_to_the_cap():
    # /proc files are regular files of size 0 that hold text: read on past the stated size
    from ga_rotors.errors import SceneError
    from ga_rotors.scene.toml_io import read_file

    assert os.stat("/proc/self/status").st_size == 0
    assert "Name:" in read_file("/proc/self/status", 10**6)
    with pytest.raises(SceneError, match=r"bytes; a scene file is at most 10$"):
        read_file("/proc/self/status", 10)


def test_a_long_run_whose_norm_drifts_keeps_its_quantities(tmp_path):
    # RK4 lets |q| drift (here 3.5e-5 over 12,000 steps): the angles, space-frame ω and L
    # come from the normalised orientation and the drift is reported; before, the run
    # exited 2 ("q: expected unit quaternions") and wrote nothing.
    (tmp_path / "s.toml").write_text(
        "[body]\nmoments = [1.0, 2.0, 3.0]\n[initial.angular_velocity]\nbody = [0.5, 3.0, 0.5]\n"
        'units = "rad/s"\n[time]\nduration = 600.0\noutput_step = 1.0\n[integrator]\nstep = 0.05'
        '\npaths = ["quaternion"]\n[output]\nquantities = ["angles", "omega_space", "L_space"]\n'
        'data = ["npz"]\n'
    )
    status, stdout, stderr, _ = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert status == 0, stderr
    drift = float(re.search(r"max \| \|quaternion\| − 1 \| = (\S+)", stdout).group(1))
    assert 1e-6 < drift < 1e-3
    import numpy as np

    with np.load(tmp_path / "out" / "s.npz") as npz:
        assert all(np.all(np.isfinite(npz[k])) for k in ("angles", "omega_space", "L_space"))


@pytest.mark.parametrize(("theta", "status"), [(30.0, 0), (0.0, 3)])
def test_dop853_on_the_euler_path_runs_or_says_incomplete(tmp_path, theta, status):
    # Always a crash before (the path's watch report read dop853's statistics; at θ = 0,
    # its singularity, scipy's failed solution had no array): now it runs, or it starts
    # on the singularity and stops at once, said first, exit 3.
    (tmp_path / "s.toml").write_text(
        "[body]\nmoments = [1.0, 2.0, 3.0]\n[initial.orientation]\n"
        f'euler = [0.0, {theta}, 0.0]\nsequence = "ZYZ"\nunits = "deg"\n'
        '[initial.angular_velocity]\nbody = [0.1, 0.2, 3.0]\nunits = "rad/s"\n'
        '[time]\nduration = 1.0\n[integrator]\nstep = 0.001\npaths = ["euler"]\n'
        'method = "dop853"\n'
    )
    got, stdout, stderr, _ = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert got == status, stderr
    assert stdout.startswith("INCOMPLETE") == (status == 3)


def test_a_pivot_whose_inertia_overflows_is_refused_by_key(tmp_path):
    data = json.loads(json.dumps(BASES["heavy_top"]))
    data["effects"][0]["pivot_to_com"] = [0, 0, 1e300]  # m |r|² = inf: NaN moments before
    (tmp_path / "s.toml").write_text(to_toml(data))
    status, _, stderr, _ = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert status == 2 and ": effects[0].pivot_to_com: " in stderr and "overflows" in stderr


def test_a_damped_body_at_rest_has_a_summary_without_nan(tmp_path):
    # ω = 0 (the angular velocity deleted): |L| = 0 made the damped summary divide 0/0
    data = json.loads(json.dumps(BASES["damped_top"]))
    data["initial"].pop("angular_velocity", None)
    (tmp_path / "s.toml").write_text(to_toml(data))
    assert check_scene(to_toml(data), tmp_path) == "ran"


def test_a_heavy_top_too_weak_for_its_reference_is_one_line(tmp_path):
    # pivot 1e-320 m from the centre of mass: the reference's root search did not
    # converge (RuntimeError traceback, found by the scene fuzzer); now one line
    data = json.loads(json.dumps(BASES["fast_spinner"]))
    data["time"]["duration"] = 0.01
    data["effects"] = [{"type": "gravity", "pivot_to_com": [0, 0, 1e-320]}]
    text = to_toml(data)
    assert check_scene(text, tmp_path) in ("refused", "ran")


#: Issue 30's scene files, each one line naming its key (or the file), exit 2, no traceback,
#: no warning: (TOML text after the spinning disk's, the key, a fragment of the message).
ISSUE_30 = {
    "int-beyond-float": ('[body]\nmoments = [1, 2, 1' + "0" * 400 + ']\n', "body.moments[2]",
                         "an integer of 401 digits, beyond float64"),
    "int-of-5000-digits": ('[body]\nmoments = [1, 2, ' + "9" * 5000 + ']\n', None,
                           "Exceeds the limit (4300 digits)"),
    "headers-2000-deep": ("[" + ".".join(["a"] * 2000) + "]\nx = 1\n", None,
                          "arrays or tables nested too deeply"),
    "tolerance-5e-324": ('[integrator]\nmethod = "dop853"\ntolerance = 5e-324\nstep = 1e-3\n',
                         "integrator.tolerance", "100 ulps"),
    "moments-1e300": ("[body]\nmoments = [1e300, 2e300, 2.5e300]\n",
                      "initial.angular_velocity", "its square overflows float64"),
    "box-of-1e308-kg": ('[body]\nshape = "box"\nmass = 1e308\na = 0.1\nb = 0.06\nc = 0.02\n',
                        "initial.angular_velocity", "its square overflows float64"),
    "start-1.8e308": ("[time]\nduration = 0.1\nstart = -1.8e308\n", "time.start", "finite"),
    "g-1e308": ('[body]\nshape = "disk"\nmass = 1.0\nradius = 0.1\n[[effects]]\n'
                'type = "gravity"\ng = [1e308, 0, 0]\npivot_to_com = [0, 0, 0.1]\n',
                "effects[0]", "would turn the body by"),
    "space-torque-1e200": ('[[effects]]\ntype = "space_torque"\ntorque = [1e200, 0, 0]\n',
                           "effects[0]", "would turn the body by"),
    "2000-effects": ('[[effects]]\ntype = "body_torque"\ntorque = [0, 0, 1e-4]\n' * 2000,
                     "effects", "2,000 entries; a scene declares at most 64"),
    "2000-user-effects": ("".join(f'[[effects]]\ntype = "user"\nfunction = "m{i}:f"\n'
                                  for i in range(2000)), "effects", "at most 64"),
    "escape-in-a-key": ('[body]\nmoments = [1, 2, 3]\n"\\u001b]0;pwned\\u0007\\u001b[2J" = 1\n',
                        "body.\\x1b]0;pwned\\x07\\x1b[2J", "unknown key"),
    "name-with-a-newline": ('[scene]\nname = "top\\n"\n', "scene.name", "a file name"),
}  # fmt: skip


def _issue_30_scene(tail: str) -> str:
    """The spinning disk, 0.1 s of it, with ``tail``'s tables in place of its own."""
    data = json.loads(json.dumps(BASES["spinning_disk"]))
    data["time"] = {"duration": 0.1}
    for section in re.findall(r"^\[\[?(\w+)", tail, re.M):
        data.pop(section, None)
    return to_toml(data) + tail


@pytest.mark.parametrize("case", list(ISSUE_30))
def test_issue_30_scenes_are_one_line(tmp_path, case):
    tail, key, fragment = ISSUE_30[case]
    (tmp_path / "s.toml").write_text(_issue_30_scene(tail), encoding="utf-8")
    status, _, stderr, caught = run_file(tmp_path / "s.toml", tmp_path / "out")
    assert status == 2, (status, stderr[-500:])
    line = stderr.strip()
    assert "\n" not in line and len(line) <= MAX_LINE and line.isprintable(), line[:300]
    assert (f": {key}: " in line) if key else ("s.toml: " in line), line
    assert fragment in line, line
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)]


def test_a_scene_saved_with_a_byte_order_mark_runs(tmp_path):
    """Issue 30 item 12: a scene saved with a UTF-8 byte-order mark (as Windows editors do)
    was refused as "not valid TOML"."""
    text = bundled_path("spinning_disk").read_text(encoding="utf-8")
    (tmp_path / "s.toml").write_text("\ufeff" + text, encoding="utf-8")
    from ga_rotors.scene import load_scene

    assert load_scene(tmp_path / "s.toml").data == load_scene("spinning_disk").data | {
        "scene": load_scene(tmp_path / "s.toml").data["scene"]
    }


def test_a_file_name_too_long_is_one_line(capsys):
    """load_scene("a" * 5000) raised the system's OSError (issue 30 item 12)."""
    assert cli.main(["show", "a" * 5000]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "File name too long" in err and len(err) < 400
