"""Two threads of a new process loading the same generated modules at once, the first
load slowed so the second finds its module registered but not yet run."""

from __future__ import annotations

import importlib.util
import sys
import threading
import time


def race_first_load(monkeypatch, run):
    """Unload the generated modules (and the memo of specialisations), slow the first
    load down, and call ``run()`` from two threads, the second 0.1 s after the first;
    return (the slowed module names, the errors raised, the results returned). Callers
    first reset whatever else remembers what ``run`` derived."""
    from ga_rotors import _modules
    from ga_rotors.integrators import _cache

    for name in [name for name in sys.modules if name.startswith("_ga_rotors_gen_")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setattr(_cache, "_MEMO", {})
    slowed = []

    def slow(spec):  # load_registered; the first load leaves time for the other thread
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module
        if not slowed:
            slowed.append(spec.name)
            time.sleep(0.3)
        spec.loader.exec_module(module)
        return module

    monkeypatch.setattr(_modules, "load_registered", slow)
    start, errors, results = threading.Barrier(2), [], []

    def one(delay):
        start.wait()
        time.sleep(delay)  # the first thread is the one that loads
        try:
            results.append(run())
        except Exception as exc:  # reported by the caller's assertion
            errors.append(exc)

    threads = [threading.Thread(target=one, args=(delay,)) for delay in (0.0, 0.1)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return slowed, errors, results
