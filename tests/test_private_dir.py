"""The compiled-code cache's folder: resolved once, every component checked with lstat, the
resolved path used (issue 30 item 9)."""

from __future__ import annotations

import os
import stat

import pytest

from ga_rotors._private_dir import private_directory
from ga_rotors.errors import InputError
from ga_rotors.integrators import _cache

ROOT = hasattr(os, "geteuid") and os.geteuid() == 0
OTHER = 4242  # a user id that is not ours


@pytest.fixture
def place(tmp_path):
    """A folder of ours (0700) with a world-writable folder in it, as /tmp would be."""
    os.chmod(tmp_path, 0o700)
    shared = tmp_path / "shared"
    shared.mkdir()
    os.chmod(shared, 0o777)
    mine = tmp_path / "mine"
    mine.mkdir(mode=0o700)
    return tmp_path, shared, mine


@pytest.mark.skipif(not ROOT, reason="needs to give a link to another user (lchown)")
def test_a_link_owned_by_another_user_is_followed_once_and_never_again(place, monkeypatch):
    """Issue 30 item 9: GA_ROTORS_CACHE_DIR a link owned by another user in a world-writable
    folder was accepted (os.stat follows it to a private folder of ours) and then used as
    the unresolved path, so its owner could re-point it at their own folder after the check
    and have their code imported. Now the path is resolved once and only the resolved path
    is used: re-pointing the link changes nothing."""
    base, shared, mine = place
    link = shared / "cache"
    os.symlink(mine, link)
    os.lchown(link, OTHER, OTHER)
    monkeypatch.setenv("GA_ROTORS_CACHE_DIR", str(link))
    _cache.cache_location.cache_clear()
    try:
        where = _cache.cache_location()
        assert where == mine / "generated"  # the resolved path, not the link's
        assert stat.S_IMODE(os.stat(where).st_mode) == 0o700
        theirs = base / "theirs"
        theirs.mkdir()
        os.chown(theirs, OTHER, OTHER)
        os.unlink(link)  # the link's owner points it at their folder
        os.symlink(theirs, link)
        assert _cache.cache_location() == mine / "generated"  # what is used: unchanged
        with pytest.raises(InputError, match="belongs to user id 4242"):
            private_directory(link / "generated")  # resolved anew: theirs, refused
    finally:
        _cache.cache_location.cache_clear()


@pytest.mark.skipif(not ROOT, reason="needs another user's folder (chown)")
def test_a_link_to_another_users_folder_is_refused(place):
    base, shared, _ = place
    theirs = base / "theirs"
    theirs.mkdir(mode=0o700)
    os.chown(theirs, OTHER, OTHER)
    os.symlink(theirs, shared / "cache")
    with pytest.raises(InputError, match=r"theirs belongs to user id 4242, not to you"):
        private_directory(shared / "cache" / "generated")


def test_a_folder_above_that_others_can_write_into_is_refused_unless_sticky(place):
    """Whoever can write into a folder on the way can rename what is below it and put their
    own in its place; a sticky folder (/tmp) lets them add entries but not move ours."""
    _, shared, _ = place
    under = shared / "deep" / "cache"
    with pytest.raises(InputError, match=r"shared can be written by others \(mode 777\)"):
        private_directory(under / "generated")
    os.chmod(shared, 0o1777)
    made = private_directory(under / "generated")
    assert made == under / "generated"


def test_the_folder_itself_must_be_ours_alone(place):
    _, _, mine = place
    made = private_directory(mine / "generated")
    os.chmod(made, 0o1777)  # sticky does not help here: others could add modules
    with pytest.raises(InputError, match=r"can be written by others \(mode 1777\)"):
        private_directory(made)
