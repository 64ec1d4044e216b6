"""The cache of generated loop modules: named by version, listed, pruned, cleared."""

from __future__ import annotations

import os
import stat
import tempfile
import time
from pathlib import Path

import pytest
from _torques_for_tests import constant_omega

from ga_rotors.cli import main
from ga_rotors.errors import InputError
from ga_rotors.integrators import PrescribedOmega, Problem, _cache, get

DAY = 86400.0


def _fake(directory, version, age_days, now):
    """A generated module of ``version`` written ``age_days`` ago, with numba cache files."""
    stem = f"gen_rk4_free_quaternion_{version}_0123456789abcdef0123"
    (directory / "__pycache__").mkdir(parents=True, exist_ok=True)
    files = [
        directory / f"{stem}.py",
        directory / "__pycache__" / f"{stem}.fixed_step_loop-61.py311.nbi",
        directory / "__pycache__" / f"{stem}.fixed_step_loop-61.py311.1.nbc",
    ]
    for f in files:
        f.write_text("x")
        os.utime(f, (now - age_days * DAY, now - age_days * DAY))
    return files


def _specialise():
    problem = Problem(omega=PrescribedOmega(constant_omega, (0.0, 0.0, 1.0)))
    return _cache.specialise(get("rk4"), problem, "quaternion")


def test_module_names_carry_the_package_version(cache):
    spec = _specialise()
    assert spec.path.name.split("_")[-2] == _cache.version_tag()
    (entry,) = _cache.cached_modules()
    assert entry.path == spec.path and entry.version == _cache.version_tag()


def test_prune_deletes_only_old_modules_of_other_versions(cache):
    now = time.time()
    mine = _cache.version_tag()
    old_other = _fake(cache, "deadbeef", 30, now)
    new_other = _fake(cache, "0badcafe", 1, now)
    old_mine = _fake(cache, mine, 30, now)
    assert _cache.prune_cache(now=now) == 3
    assert not any(f.exists() for f in old_other)
    assert all(f.exists() for f in new_other + old_mine)
    # just inside the limit: kept
    assert _cache.prune_cache(max_age_days=1.0 + 1 / 24, now=now) == 0


def test_the_first_module_a_process_generates_prunes_the_cache(cache):
    now = time.time()
    old_other = _fake(cache, "deadbeef", _cache.PRUNE_AFTER_DAYS + 1, now)
    _specialise()
    assert not any(f.exists() for f in old_other)
    again = _fake(cache, "deadbeef", _cache.PRUNE_AFTER_DAYS + 1, now)
    _cache._MEMO.clear()
    _specialise()  # once per process: a second generation does not list the directory again
    assert all(f.exists() for f in again)


def test_cache_command_reports_and_clears(cache, capsys):
    now = time.time()
    _fake(cache, "deadbeef", 2, now)
    _specialise()
    assert main(["cache"]) == 0
    out = capsys.readouterr().out
    assert f"cache: {cache}" in out
    assert f"this version ({_cache.version_tag()}): 1 module" in out
    assert "other versions: 1 module, 3 B (deleted 14 days after they were made)" in out
    # --clear says what it removes and keeps other versions' modules.
    assert main(["cache", "--clear"]) == 0
    out = capsys.readouterr().out
    assert f"removing 1 module of this version ({_cache.version_tag()})" in out
    assert "kept 1 module of other versions" in out
    assert [f.name.split("_")[-2] for f in cache.glob("gen_*")] == ["deadbeef"]
    # --clear --all removes every version's.
    assert main(["cache", "--clear", "--all"]) == 0
    out = capsys.readouterr().out
    assert "removing 1 module of every version, 3 B" in out and "removed 3 files" in out
    assert list(cache.glob("gen_*")) == [] and list((cache / "__pycache__").iterdir()) == []
    assert main(["cache", "--all"]) == 2  # --all alone is a mistake: one line
    assert "--all: only with --clear" in capsys.readouterr().err


def test_cache_command_without_a_writable_directory(tmp_path, monkeypatch, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setattr(_cache, "_candidates", lambda: [blocker / "generated"])
    _cache.cache_location.cache_clear()
    try:
        assert main(["cache"]) == 0
        assert "compiled in memory" in capsys.readouterr().out
    finally:
        _cache.cache_location.cache_clear()


# ---------------------------------------------------------------------------- a private cache


@pytest.fixture
def env_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("GA_ROTORS_CACHE_DIR", str(tmp_path / "c"))
    _cache.cache_location.cache_clear()
    yield tmp_path / "c"
    _cache.cache_location.cache_clear()


def test_a_new_cache_is_private(env_cache):
    where = _cache.cache_location()
    assert where == env_cache / "generated"
    for folder in (where, env_cache):
        assert stat.S_IMODE(os.stat(folder).st_mode) == 0o700


@pytest.mark.parametrize("folder", ["c", "c/generated"])
def test_a_cache_others_can_write_into_is_refused(env_cache, capsys, folder):
    (env_cache / "generated").mkdir(parents=True)
    os.chmod(env_cache.parent / folder, 0o777)
    with pytest.raises(InputError, match=r"can be written by others \(mode 777\)"):
        _cache.cache_location()
    assert main(["cache"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "GA_ROTORS_CACHE_DIR" in err and "chmod 700" in err


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="needs chown")
def test_a_cache_owned_by_someone_else_is_refused(env_cache):
    (env_cache / "generated").mkdir(parents=True, mode=0o700)
    os.chown(env_cache / "generated", 4242, 4242)
    with pytest.raises(InputError, match="belongs to user id 4242, not to you"):
        _cache.cache_location()


def test_no_shared_temporary_fallback(tmp_path, monkeypatch):
    # No usable cache folder (HOME read-only): loops compile in memory; nothing is
    # written under the shared temporary folder at a predictable name.
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.delenv("GA_ROTORS_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))
    monkeypatch.setattr(_cache, "_MEMO", {})
    _cache.cache_location.cache_clear()
    try:
        assert _cache.cache_location() is None
        assert _specialise().path is None
        assert not list(Path(tempfile.gettempdir()).glob("ga_rotors-*/generated/gen_*"))
    finally:
        _cache.cache_location.cache_clear()


def test_threads_specialising_the_same_loop_at_once_wait_for_one_another(monkeypatch):
    """Single runs started from several threads of a new process all load the same
    generated module; a module is in sys.modules before it has run, and a thread finding
    it there half made used it ("has no attribute ...")."""
    from _loading_race import race_first_load

    from ga_rotors.integrators import problem
    from ga_rotors.scene import load_scene, run_scene

    def once():  # the heavy top's loop is generated for its torque; a new scene each
        # time, so nothing it derived (its prepared loops) is reused
        return run_scene(load_scene("heavy_top").replace({"time.duration": 0.01}))

    expected = once()  # compiled and cached; then unloaded again, with the problems
    monkeypatch.setattr(problem, "_PROBLEMS", {})  # that kept their prepared loops
    slowed, errors, results = race_first_load(monkeypatch, once)
    assert slowed and errors == []
    for tr in results:
        for path in ("rotor", "quaternion"):
            assert (tr.quaternions(path) == expected.quaternions(path)).all()
