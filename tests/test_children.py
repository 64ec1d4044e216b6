"""Child processes end with the command that started them, even a killed one.

Before ga_rotors._children, a SIGKILLed ``ga-rotors paper`` left its drawing pool's
workers waiting on their queue forever, holding the command's pipes open (found by the
fault trials of benchmarks/faults.py, which then hung).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

POOL = """
from concurrent.futures import ProcessPoolExecutor
import os, sys, time
from ga_rotors._children import context, exit_with_parent
pool = ProcessPoolExecutor(2, mp_context=context(), initializer={init})
pids = {{pool.submit(os.getpid).result() for _ in range(8)}}
print(*pids, flush=True)
time.sleep(600)
"""


def _alive(pid: int) -> bool:
    """Whether ``pid`` still runs (a zombie nobody reaped has ended)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def _workers_after_kill(init: str, wait: float) -> list[int]:
    parent = subprocess.Popen(
        [sys.executable, "-c", POOL.format(init=init)], stdout=subprocess.PIPE, text=True
    )
    try:
        pids = [int(p) for p in parent.stdout.readline().split()]
        assert pids, "the pool's workers did not answer"
    finally:
        parent.send_signal(signal.SIGKILL)
        parent.wait()
    deadline = time.monotonic() + wait
    while time.monotonic() < deadline and any(_alive(p) for p in pids):
        time.sleep(0.05)
    return [p for p in pids if _alive(p)]


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="reads /proc to see the workers")
def test_pool_workers_end_when_their_command_is_killed():
    assert _workers_after_kill("exit_with_parent", wait=20.0) == []


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="reads /proc to see the workers")
def test_without_the_watch_workers_outlive_a_killed_command():
    """The control: the standard pool alone leaves them (so the test above can fail)."""
    left = _workers_after_kill("None", wait=1.0)
    for pid in left:
        os.kill(pid, signal.SIGKILL)
    assert left
