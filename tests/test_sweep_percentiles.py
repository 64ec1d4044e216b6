"""A sweep's summary in bounded memory: exact medians and percentiles read block by block,
equal to numpy's of the whole column to the bit."""

from __future__ import annotations

import itertools
import tracemalloc

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors.sweep.percentiles import percentiles

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)
values = st.lists(
    st.one_of(finite, st.just(np.nan), st.just(0.0), st.just(-0.0), st.just(5e-324)),
    min_size=0,
    max_size=60,
)


def _blocks(x, cuts):
    edges = sorted({0, x.size, *(c % (x.size + 1) for c in cuts)})
    return lambda: (x[a:b] for a, b in itertools.pairwise(edges))


def _numpy(x, qs):
    y = x[~np.isnan(x)]
    if not y.size:
        return np.nan, [np.nan] * len(qs), np.nan, 0
    return np.median(y), [np.percentile(y, q) for q in qs], y.max(), y.size


def _same(a, b):
    return (np.isnan(a) and np.isnan(b)) or a == b


@settings(max_examples=300, deadline=None)
@given(
    values,
    st.lists(st.integers(0, 100), max_size=5),
    st.lists(st.floats(0, 100), min_size=1, max_size=4),
)
def test_equal_to_numpys_median_and_percentile_of_the_whole_array(xs, cuts, qs):
    x = np.array(xs, dtype=np.float64)
    got = percentiles(_blocks(x, cuts), qs)
    want = _numpy(x, qs)
    assert _same(got[0], want[0]) and _same(got[2], want[2]) and got[3] == want[3]
    assert all(_same(g, w) for g, w in zip(got[1], want[1], strict=True)), (got, want)


@pytest.mark.parametrize(
    "case",
    [
        "all equal",  # every rank in one bin at every pass
        "neighbours in the last bits",  # values one ulp apart: the last pass decides
        "even count",  # the median is the mean of two values
        "one value",
        "all nan",
        "mixed signs and zeros",
    ],
)
def test_named_hard_cases(case):
    rng = np.random.default_rng(7)
    x = {
        "all equal": np.full(1001, 0.25),
        "neighbours in the last bits": np.nextafter(1.0, 2.0) ** rng.integers(0, 5, 999),
        "even count": rng.random(1000) * 1e-300,
        "one value": np.array([3.5]),
        "all nan": np.full(17, np.nan),
        "mixed signs and zeros": np.concatenate(
            [-rng.random(50), [0.0, -0.0] * 10, rng.random(50)]
        ),
    }[case]
    qs = [0, 1, 50, 95, 99.9, 100]
    got = percentiles(_blocks(x, [3, 100, 500]), qs)
    want = _numpy(x, qs)
    assert _same(got[0], want[0]) and _same(got[2], want[2]) and got[3] == want[3]
    assert all(_same(g, w) for g, w in zip(got[1], want[1], strict=True))


def test_it_holds_one_block_at_a_time():
    # 8·10⁶ values (64 MB) made block by block: traced memory stays a few blocks' worth
    # (a block, its keys and their temporaries, the counts of 65,536 bins per rank)
    def blocks():
        rng = np.random.default_rng(3)
        for _ in range(80):
            yield rng.random(100_000)

    tracemalloc.start()
    try:
        m, (p95,), top, n = percentiles(blocks, [95])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert n == 8_000_000 and 0.49 < m < 0.51 and 0.94 < p95 < 0.96 and top < 1
    assert peak < 16e6, peak  # about 10 MB; the values at once would be 64 MB


def test_the_summary_read_in_chunks_is_the_summary_read_at_once(tmp_path, monkeypatch):
    pytest.importorskip("zarr")
    pytest.importorskip("dask")
    from ga_rotors.sweep import open_sweep, run, run_sweep, summary

    text = """
[sweep]
scene = "spinning_disk"
samples = 1000
chunk = 128
seed = 5
times = [0.005, 0.01]

[set]
"time.duration" = 0.01

[[draw]]
key = "initial.angular_velocity.euler_rates[0]"
normal = [0.0, 3.0]
"""
    ds = open_sweep(run_sweep(text, tmp_path / "s.zarr", client="sync"))
    at_once = summary(ds)
    monkeypatch.setattr(run, "SUMMARY_IN_MEMORY", 0)
    assert summary(ds) == at_once
    a = np.degrees(ds["angle_from_nominal"].values[:, 1])
    assert f"0.01  {np.median(a):.4g}  {np.percentile(a, 95):.4g}  {a.max():.4g}" in at_once
