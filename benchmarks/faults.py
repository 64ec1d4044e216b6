"""Fault trials: kill, SIGTERM and a full disk while `ga-rotors run` and `paper` write.

Run from the repository root (as root for the disk-full trials, which mount a small
tmpfs; without the privilege they are skipped with a notice)::

    python benchmarks/faults.py                 # 60 trials: counts for docs/stability.md
    python benchmarks/faults.py --trials 10     # a quick look

Each trial starts from an output folder holding a complete *previous* set (a shorter run,
so every file differs from the new set), runs the command into it and interrupts it:

* ``kill``: SIGKILL after a random delay (0 … the command's measured duration);
* ``term``: SIGTERM after a random delay (the command must exit 143 with one line);
* ``full``: no signal; the folder is on a tmpfs with room for the previous set but not
  for the previous and the new one together (the command must exit 2 with one line).

and then checks the folder: it must hold exactly the previous set or exactly the new set
(byte for byte, against a reference run), never a mix or a part ("partial"); no staging
folder or temporary file may be left ("leftover") — after SIGKILL only once the next
command into the same folder has run (it clears what the killed one left; the script
runs it and counts what it found). Tracebacks in stderr are counted too.
"""

from __future__ import annotations

import argparse
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE = """[scene]
name = "trial"
[body]
shape = "disk"
mass = 2.0
radius = 0.075
[initial.angular_velocity]
body = [0.3, 0.1, 15.7]
units = "rad/s"
[time]
duration = {duration}
[integrator]
step = 0.001
paths = ["rotor", "quaternion"]
[output]
data = ["csv", "npz"]
plots = ["omega"]
"""

COMMANDS = {
    "run": lambda folder, out, d: [
        "run", str(folder / f"trial_{d}.toml"), "--out", str(out), "--no-progress"],
    "paper": lambda folder, out, d: ["paper", "--out", str(out)]
    + ([] if d == "new" else ["--no-figures"]),
}  # fmt: skip


def _command(kind: str, folder: Path, out: Path, which: str) -> list[str]:
    return [sys.executable, "-m", "ga_rotors", *COMMANDS[kind](folder, out, which)]


def _snapshot(out: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(out.iterdir()) if p.is_file()}


def _debris(place: Path) -> list[str]:
    return [
        str(p)
        for p in place.rglob("*")
        if p.name.startswith(".ga_rotors-staging-") or p.name.endswith(".tmp")
    ]


def _run(cmd, env, timeout=600) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)


def _prepare(kind, folder, out, env, previous):
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    for name, data in previous.items():
        (out / name).write_bytes(data)


def references(kind: str, folder: Path, env) -> tuple[dict, dict, float]:
    """The previous and the new set of ``kind``, and how long the new command takes."""
    sets = {}
    took = 0.0
    for which in ("old", "new"):
        out = folder / f"ref_{kind}_{which}"
        start = time.perf_counter()
        proc = _run(_command(kind, folder, out, which), env)
        if proc.returncode != 0:
            raise SystemExit(f"reference {kind} {which} failed:\n{proc.stderr}")
        took = time.perf_counter() - start
        sets[which] = _snapshot(out)
    return sets["old"], sets["new"], took


def _mount_small(where: Path, size: int) -> bool:
    where.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(where)],
        capture_output=True, text=True,
    )  # fmt: skip
    return proc.returncode == 0


def trial(kind, mode, folder, env, old, new, took, rng) -> dict:
    """One trial; returns what was found."""
    if mode == "full":
        mount = folder / f"small_{kind}"
        size_old = sum(len(v) for v in old.values())
        size_new = sum(len(v) for v in new.values())
        # room for the previous set plus a random part of the new one (never all of it)
        room = size_old + int(rng.uniform(0.0, 0.9) * size_new) + 64 * 1024
        if not _mount_small(mount, room):
            return {"skipped": True}
        out = mount / "out"
    else:
        mount = None
        out = folder / f"out_{kind}"
    try:
        _prepare(kind, folder, out, env, old)
        cmd = _command(kind, folder, out, "new")
        proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                text=True)  # fmt: skip
        if mode in ("kill", "term"):
            time.sleep(rng.uniform(0.0, took))
            proc.send_signal(signal.SIGKILL if mode == "kill" else signal.SIGTERM)
        _, err = proc.communicate(timeout=600)
        status = proc.returncode
        got = _snapshot(out)
        result = {
            "status": status,
            "partial": got not in (old, new),
            "new": got == new,
            "traceback": "Traceback" in err,
            "debris_now": len(_debris(out.parent)),
            "one_line": err.strip().count("\n") == 0,
        }
        # -15: the signal came after the command had finished (its handler is restored
        # as main() returns); acceptable only with the complete new set in place
        if mode == "term" and status not in (0, 143) and not (status == -15 and got == new):
            result["bad_status"] = True
        if mode == "full" and status not in (0, 2):
            result["bad_status"] = True
        if mode == "kill" and result["debris_now"]:
            # the next command into the same folder clears what the killed one left
            again = _run(cmd, env)
            result["next_ok"] = again.returncode == 0 and _snapshot(out) == new
        result["leftover"] = len(_debris(out.parent))
        return result
    finally:
        if mount is not None:
            subprocess.run(["umount", str(mount)], capture_output=True)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=60, help="trials in all (default 60)")
    parser.add_argument("--seed", type=int, default=11)
    args = parser.parse_args(argv)
    rng = random.Random(args.seed)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
    env.pop("GA_ROTORS_ALLOW_USER_CODE", None)
    folder = Path(tempfile.mkdtemp(prefix="ga_rotors_faults-"))
    for which, duration in (("old", 0.5), ("new", 2.0)):
        (folder / f"trial_{which}.toml").write_text(SCENE.format(duration=duration))
    refs = {kind: references(kind, folder, env) for kind in ("run", "paper")}
    for kind, (_, _, took) in refs.items():
        print(f"{kind}: reference run {took:.1f} s")
    plan = [(kind, mode) for kind in ("run", "paper") for mode in ("kill", "term", "full")]
    counts: dict = {}
    for i in range(args.trials):
        kind, mode = plan[i % len(plan)]
        old, new, took = refs[kind]
        r = trial(kind, mode, folder, env, old, new, took, rng)
        c = counts.setdefault((kind, mode), {"trials": 0, "skipped": 0, "partial": 0,
                                             "leftover": 0, "traceback": 0, "new": 0,
                                             "debris_cleared": 0, "bad": 0})  # fmt: skip
        if r.get("skipped"):
            c["skipped"] += 1
            continue
        c["trials"] += 1
        c["partial"] += r["partial"]
        c["leftover"] += r["leftover"] > 0
        c["traceback"] += r["traceback"]
        c["new"] += r["new"]
        c["debris_cleared"] += bool(r.get("next_ok"))
        c["bad"] += bool(r.get("bad_status")) or (mode != "kill" and not r["one_line"]
                                                   and r["status"] != 0)  # fmt: skip
        print(f"{i + 1:3d} {kind:5s} {mode:4s} exit {r['status']:4d} "
              f"{'new' if r['new'] else 'previous' if not r['partial'] else 'PARTIAL'} "
              f"debris after kill {r['debris_now']} left {r['leftover']}")  # fmt: skip
    print()
    print(
        "| command | fault | trials | new set | previous set | partial | leftovers | "
        "tracebacks | bad exit/message | killed-run debris cleared by the next run |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    total = {"trials": 0, "partial": 0, "leftover": 0, "traceback": 0, "bad": 0}
    for (kind, mode), c in counts.items():
        previous = c["trials"] - c["new"] - c["partial"]
        print(f"| {kind} | {mode} | {c['trials']} | {c['new']} | {previous} "
              f"| {c['partial']} | {c['leftover']} | {c['traceback']} | {c['bad']} | "
              f"{c['debris_cleared'] if mode == 'kill' else '–'} |"
              + (f" ({c['skipped']} skipped: no tmpfs)" if c["skipped"] else ""))  # fmt: skip
        for k in total:
            total[k] += c[k]
    print(
        f"\ntotal: {total['trials']} trials, {total['partial']} partial sets, "
        f"{total['leftover']} with leftovers, {total['traceback']} tracebacks, "
        f"{total['bad']} bad exits or messages"
    )
    shutil.rmtree(folder, ignore_errors=True)
    return 1 if total["partial"] or total["leftover"] or total["traceback"] else 0


if __name__ == "__main__":
    sys.exit(main())
