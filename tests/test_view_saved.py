"""ga_rotors.view.saved: a saved result read for the viewer a block at a time, thinned."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from ga_rotors.errors import InputError
from ga_rotors.scene import load_scene
from ga_rotors.view import View, saved

SCENE = load_scene("heavy_top")


def _result(tmp_path, n=5000, q_rows=None, **changes):
    """A result of ``n`` rows beside its scene: t, ω (largest |ω| at row 1234 and |L| at
    row 4321 when n > 4321: they differ as I₃ < I⊥), a quaternion path of ``q_rows`` rows."""
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 1.0, n)
    w = rng.uniform(-1.0, 1.0, (n, 3))
    if n > 4321:
        w[1234] = (0.0, 0.0, 7.5)  # the largest |ω|; |L| = 7.5 I₃
        w[4321] = (5.0, 5.0, 0.0)  # |ω| = 7.07 only, but the largest |L| = 7.07 I⊥ (I⊥ > 1.07 I₃)
    q = rng.normal(size=(q_rows or n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    arrays = {"t": t, "w": w, "q": q} | changes
    (tmp_path / "r.scene.toml").write_text(SCENE.to_toml(), encoding="utf-8")
    np.savez(tmp_path / "r.npz", **arrays)
    return arrays


@pytest.fixture
def small_limits(monkeypatch):
    monkeypatch.setattr(saved, "VIEW_ROWS", 100)
    monkeypatch.setattr(saved, "BLOCK_BYTES", 4000)  # blocks of 125-500 rows


def test_a_result_within_view_rows_is_read_whole(tmp_path):
    arrays = _result(tmp_path, n=300)
    _, tr = saved.load_result(tmp_path)
    for name, a in arrays.items():
        assert np.array_equal(tr[name] if name != "q" else tr.q, a)


def test_a_large_result_keeps_even_rows_and_those_the_page_needs(tmp_path, small_limits):
    moments = np.asarray(SCENE.body.moments)
    assert moments[0] > 1.07 * moments[2]  # the largest |L| (row 4321) is not the largest |ω|
    arrays = _result(tmp_path, q_rows=3000)  # the path stopped at row 2999
    _, tr = saved.load_result(tmp_path / "r.npz")
    t = np.asarray(tr.t)
    rows = np.searchsorted(arrays["t"], t)
    assert np.array_equal(arrays["t"][rows], t)
    assert {0, 1234, 2999, 4321, 4999} <= set(rows.tolist())
    assert 100 <= rows.size <= 105
    assert np.array_equal(tr.w, arrays["w"][rows])
    assert np.array_equal(tr.q, arrays["q"][rows[rows < 3000]])
    # The page: |ω| and |L| scales of the whole run, the path's end where it ended.
    page = View.from_scene(SCENE, tr).data
    from ga_rotors.view.page import payload as page_payload

    payload = page_payload(page)
    omega, L = payload["vectors"]
    assert omega["max"] == pytest.approx(np.linalg.norm(arrays["w"], axis=1).max(), rel=1e-15)
    assert L["max"] == pytest.approx(np.linalg.norm(arrays["w"] * moments, axis=1).max(), rel=1e-15)
    assert payload["paths"][0]["endedAt"] == pytest.approx(arrays["t"][2999], rel=1e-15)


def test_every_row_is_checked_not_only_the_kept_ones(tmp_path, small_limits):
    w = np.zeros((5000, 3))
    w[2345, 1] = np.nan  # not a kept row
    _result(tmp_path, w=w)
    with pytest.raises(InputError, match=r"r\.npz: w: expected finite numbers"):
        saved.load_result(tmp_path)


def test_memory_stays_bounded_by_the_blocks(tmp_path, monkeypatch):
    monkeypatch.setattr(saved, "VIEW_ROWS", 1000)
    monkeypatch.setattr(saved, "BLOCK_BYTES", 1 << 20)
    n = 400_000  # t, ω, q: 25.6 MB
    t = np.arange(n, dtype=np.float64)
    (tmp_path / "r.scene.toml").write_text(SCENE.to_toml(), encoding="utf-8")
    np.savez(tmp_path / "r.npz", t=t, w=np.ones((n, 3)), q=np.tile([1.0, 0, 0, 0], (n, 1)))
    del t
    tracemalloc.start()
    try:
        _, tr = saved.load_result(tmp_path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert tr.t.size == 1000
    assert peak < 6 << 20, peak


def test_column_major_and_big_endian_arrays_read_the_same(tmp_path, small_limits):
    arrays = _result(tmp_path)
    np.savez(tmp_path / "r.npz", t=arrays["t"].astype(">f8"), w=np.asfortranarray(arrays["w"]),
             q=arrays["q"])  # fmt: skip
    _, tr = saved.load_result(tmp_path)
    rows = np.searchsorted(arrays["t"], tr.t)
    assert np.array_equal(tr.w, arrays["w"][rows]) and np.array_equal(tr.t, arrays["t"][rows])


def test_a_large_column_major_array_is_one_line(tmp_path, small_limits, monkeypatch):
    monkeypatch.setattr(saved, "WHOLE_BYTES", 1000)
    arrays = _result(tmp_path)
    np.savez(tmp_path / "r.npz", **(arrays | {"w": np.asfortranarray(arrays["w"])}))
    with pytest.raises(InputError, match=r"r\.npz: w: stored column-major and over 0 MB"):
        saved.load_result(tmp_path)


@pytest.mark.parametrize("cut", [100, 30_000, -8])
def test_a_cut_archive_is_one_line(tmp_path, cut):
    _result(tmp_path)
    data = (tmp_path / "r.npz").read_bytes()
    (tmp_path / "r.npz").write_bytes(data[:cut])
    with pytest.raises(InputError, match=r"r\.npz: not a readable \.npz result") as caught:
        saved.load_result(tmp_path)
    assert "\n" not in str(caught.value)


def test_an_object_array_is_refused_without_unpickling(tmp_path):
    arrays = _result(tmp_path, n=10)
    np.savez(tmp_path / "r.npz", **arrays, extra=np.array([{"a": 1}], dtype=object))
    with pytest.raises(InputError, match=r"r\.npz: extra: expected finite real numbers, got obj"):
        saved.load_result(tmp_path)


def test_an_empty_t_beside_long_arrays_is_one_line(tmp_path, small_limits):
    arrays = _result(tmp_path)
    np.savez(tmp_path / "r.npz", **(arrays | {"t": np.zeros(0)}))
    with pytest.raises(InputError, match=r"r\.npz: t: expected at least one sample") as caught:
        saved.load_result(tmp_path)
    assert "\n" not in str(caught.value)


def test_a_header_claiming_countless_empty_rows_is_not_read_row_by_row(tmp_path, small_limits):
    # 10¹⁵ rows of nothing: a loop over its blocks would run for minutes.
    arrays = _result(tmp_path)
    np.savez(tmp_path / "r.npz", **arrays, extra=np.empty((10**15, 0)))
    with pytest.raises(InputError, match=r"^extra: expected at most \d+ rows \(len\(t\)\)"):
        saved.load_result(tmp_path)  # at once: longer than t
