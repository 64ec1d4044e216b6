"""Shared test configuration.

Hypothesis runs derandomised so CI is reproducible, with no deadline because the first
call of a compiled kernel includes loading it from numba's cache.
"""

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "default",
    deadline=None,
    derandomize=True,
    max_examples=100,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("thorough", deadline=None, max_examples=2000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))

# The helper modules of this folder are data for the tests (user kernels a test imports
# only on its opt-in): --doctest-modules imported them while collecting, so a test
# asserting that nothing had imported one yet failed after a full collection.
collect_ignore_glob = ["_*.py"]

#: The long mode (``GA_ROTORS_LONG=1``, run before a release): tests marked ``long`` run,
#: the exhaustive versions of what the default suite checks on one representative each.
LONG = os.environ.get("GA_ROTORS_LONG") == "1"


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "long: the exhaustive version of a default test (every integrator, every case); "
        "runs with GA_ROTORS_LONG=1",
    )


#: Test files that take long (mostly compiling loops on an empty cache), longest first, as
#: measured from a fresh clone (``--durations=0``, summed by file): the suite runs them
#: first, so that two workers finish together (pytest-xdist
#: would otherwise order the files by their number of tests, and a long file with few
#: tests would start last).
LONG_FILES = [
    "tests/test_ensemble.py",
    "tests/test_docs.py",
    "tests/test_stream.py",
    "tests/test_accuracy.py",
    "tests/test_motion.py",
    "tests/test_integrator_orders.py",
    "tests/test_motion_bench.py",
    "tests/test_warmup.py",
    "tests/test_torque_support.py",
    "tests/test_prove.py",
    "tests/test_site.py",
    "tests/test_run_path.py",
    "tests/test_learn.py",
    "tests/test_effects.py",
    "tests/test_extending.py",
    "tests/test_sweep_input.py",
    "tests/test_stability_values.py",
    "tests/test_forces.py",
]
#: Files whose tests compile the same loops, run in one worker one after the other (in two
#: workers at once, an empty cache compiles each loop twice): docs/ensembles.md's examples
#: and the ensemble tests share their batched RK4 loops.
SAME_WORKER = {"tests/test_docs.py": "tests/test_ensemble.py"}


def pytest_collection_modifyitems(config, items):
    rank = {name: i for i, name in enumerate(LONG_FILES)}
    items.sort(key=lambda item: rank.get(item.nodeid.split("::", 1)[0], len(rank)))
    if LONG:
        return
    skip = pytest.mark.skip(reason="long mode: set GA_ROTORS_LONG=1 (every integrator or case)")
    for item in items:
        if item.get_closest_marker("long") is not None:
            item.add_marker(skip)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """pytest-xdist's ``--dist loadfile`` in the order of the collection (see
    :data:`LONG_FILES`), the files of :data:`SAME_WORKER` as one unit."""
    from xdist.scheduler import LoadFileScheduling

    class Scheduling(LoadFileScheduling):
        def _split_scope(self, nodeid):
            scope = super()._split_scope(nodeid)
            return SAME_WORKER.get(scope, scope)

    if config.getvalue("dist") != "loadfile":
        return None
    config.option.loadscopereorder = False
    return Scheduling(config, log)


@pytest.fixture
def tests_code(monkeypatch):
    """Opt in to user torques from this folder (tests/_torques_for_tests.py), as a user
    would with GA_ROTORS_ALLOW_USER_CODE (ga_rotors.trust)."""
    monkeypatch.setenv("GA_ROTORS_ALLOW_USER_CODE", str(Path(__file__).resolve().parent))


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty compiled-loop cache for one test (tests/test_cache.py, test_warmup.py):
    generated modules and warm-up markers start from nothing. It stands in for pytest's own
    ``cache`` fixture, which the suite does not use."""
    from ga_rotors.integrators import _cache

    directory = tmp_path / "generated"
    monkeypatch.setattr(_cache, "_candidates", lambda: [directory])
    monkeypatch.setattr(_cache, "_MEMO", {})
    monkeypatch.setattr(_cache, "_PRUNED", False)
    _cache.cache_location.cache_clear()
    yield directory
    _cache.cache_location.cache_clear()
