"""A bounded copy of a long run for its figure: every sample's extremes, at screen resolution.

A figure is a few hundred pixels wide; a run may have 10⁸ samples. :class:`ThinnedCopy`
takes the run piece by piece and keeps, for each of :data:`COLUMNS` equal slices of the
time span (about one pixel column each), the first and last sample of the slice and the
samples where each column of each array is smallest and largest in it: the min/max
envelope a line plot of all the samples would draw, spikes included, in at most
``COLUMNS × (2 + 2 × columns)`` rows whatever the length of the run. A run of at most
:data:`KEEP_ALL` samples is kept whole, so the figure of a short run is the figure of all
its samples.

A figure drawn from such a copy need not draw all its rows either: each of its lines needs
only its own envelope (:func:`envelope`: per slice, the first and last row and the rows of
the line's smallest and largest value), not the rows kept for the other arrays' extremes.
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from ..trajectory import Trajectory

__all__ = ["COLUMNS", "KEEP_ALL", "ThinnedCopy", "envelope"]

#: Slices of the time span; the figure's data area is about 900 pixels wide.
COLUMNS = 2048

#: Runs of at most this many samples are kept whole.
KEEP_ALL = 20_000


class ThinnedCopy:
    """The rows of a run a figure needs (see the module docstring).

    Parameters
    ----------
    t_start, t_end : float
        The run's time span (its first and last sample times).
    samples : int
        How many samples the run will have.

    Examples
    --------
    A million samples of a sine with one spike keep their envelope in a few thousand rows:

    >>> t = np.linspace(0.0, 10.0, 10**6)
    >>> y = np.sin(t)
    >>> y[123_457] = 5.0
    >>> copy = ThinnedCopy(0.0, 10.0, t.size)
    >>> for lo in range(0, t.size, 300_000):
    ...     copy.add(Trajectory({"t": t[lo : lo + 300_000], "y": y[lo : lo + 300_000]}))
    >>> thin = copy.trajectory()
    >>> len(thin) < 10_000, float(thin["y"].max()), bool(thin["y"].min() == y.min())
    (True, 5.0, True)
    """

    def __init__(self, t_start: float, t_end: float, samples: int, columns: int = COLUMNS):
        self.t_start, self.span = float(t_start), float(t_end) - float(t_start)
        self.columns = int(columns)
        self.keep_all = samples <= KEEP_ALL or not self.span > 0
        self.kept: list[Trajectory] = []

    def add(self, piece: Trajectory) -> None:
        """Keep the rows of ``piece`` the figure needs."""
        if self.keep_all or len(piece) == 0:
            self.kept.append(piece)
            return
        rows = self._rows(piece)
        arrays = {"t": piece.t[rows]}
        for name in piece.names:
            if name != "t":
                a = piece[name]
                arrays[name] = a[rows[rows < a.shape[0]]]
        self.kept.append(Trajectory(arrays, piece.components, piece.meta))

    def _rows(self, piece: Trajectory) -> np.ndarray:
        t = piece.t
        slices = _slices(t, self.t_start, self.span, self.columns)
        keep = np.zeros(t.shape[0], dtype=np.bool_)
        for name in piece.names:
            a = piece[name]
            if name != "t" and a.shape[0]:
                _extremes(
                    slices, np.ascontiguousarray(a.reshape(a.shape[0], -1), dtype=float), keep
                )
        _slice_ends(slices, keep)
        return np.flatnonzero(keep)

    def trajectory(self, meta: dict | None = None) -> Trajectory:
        """The kept rows as one Trajectory (``meta``: the run's final one, by default the
        last piece's).

        Examples
        --------
        >>> copy = ThinnedCopy(0.0, 1.0, 3)
        >>> copy.add(Trajectory({"t": np.array([0.0, 0.5, 1.0])}))
        >>> copy.trajectory().t.tolist()
        [0.0, 0.5, 1.0]
        """
        if len(self.kept) == 1:  # its orientations, if converted already, are shared
            return self.kept[0].extended({}, meta=meta)
        first = self.kept[0]
        arrays = {n: np.concatenate([p[n] for p in self.kept]) for n in first.names}
        return Trajectory(arrays, first.components, meta or self.kept[-1].meta)


def envelope(t: np.ndarray, y: np.ndarray, columns: int = COLUMNS, bounds=None) -> np.ndarray:
    """The rows of one line ``y(t)`` a plot of it needs: for each of ``columns`` equal
    slices of ``bounds`` (t_low, t_high; by default ``t``'s own span), its first and last
    row and the first rows holding the smallest and the largest ``y`` (a slice holding a
    NaN: its first row).

    Drawn through these rows, in order, a line covers in each slice what the line through
    every row covers: the same vertical extent, joined to the same neighbours; with a
    slice per pixel column, the same pixels.

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 10_001)
    >>> y = np.sin(40 * t)
    >>> rows = envelope(t, y, columns=100)
    >>> len(rows) <= 400, float(y[rows].max()) == float(y.max()), rows[0], rows[-1]
    (True, True, np.int64(0), np.int64(10000))
    """
    t = np.asarray(t, dtype=np.float64)
    keep = np.zeros(t.shape[0], dtype=np.bool_)
    if t.shape[0] == 0:
        return np.flatnonzero(keep)
    low, high = (float(t[0]), float(t[-1])) if bounds is None else map(float, bounds)
    span = high - low
    slices = _slices(t, low, span if span > 0 else 1.0, int(columns))
    _extremes(slices, np.ascontiguousarray(np.reshape(y, (t.shape[0], 1)), dtype=float), keep)
    _slice_ends(slices, keep)
    return np.flatnonzero(keep)


def _slices(t: np.ndarray, t_start: float, span: float, columns: int) -> np.ndarray:
    """Which of ``columns`` equal slices of [t_start, t_start + span] each time is in."""
    where = np.floor((t - t_start) / span * columns)
    return np.clip(where, 0, columns - 1).astype(np.int64)


# Times increase, so each slice is a run of consecutive rows; one compiled pass per array
# marks each run's extremes (about 10x the speed of numpy's reduceat per column, which
# made the thinning a tenth of a streamed run's output work).


@jit
def _slice_ends(slices, keep):
    """Mark the first and last row of each run of equal ``slices``."""
    n = slices.shape[0]
    for i in range(n):
        if i == 0 or slices[i] != slices[i - 1] or i == n - 1 or slices[i + 1] != slices[i]:
            keep[i] = True


@jit
def _extremes(slices, a, keep):
    """Mark, in each run of equal ``slices`` (rows of ``a``, which may have fewer rows than
    ``slices``: a path that stopped), the first row where each column of ``a`` is
    smallest and the first where it is largest; a run holding a NaN marks its first row
    (NaN is the extreme)."""
    n, m = a.shape
    lo, hi = np.empty(m, np.int64), np.empty(m, np.int64)
    low, high, nan = np.empty(m), np.empty(m), np.empty(m, np.bool_)
    start = 0
    while start < n:
        end = start + 1
        while end < n and slices[end] == slices[start]:
            end += 1
        for j in range(m):
            lo[j] = hi[j] = start
            low[j] = high[j] = a[start, j]
            nan[j] = a[start, j] != a[start, j]
        # row by row, as the values lie in memory (a column at a time was 1.7x the time);
        # a NaN compares false both ways, so it only sets its column's flag (a NaN first
        # value leaves its column's low and high NaN: the flag is set already)
        for i in range(start + 1, end):
            for j in range(m):
                v = a[i, j]
                if v < low[j]:
                    low[j], lo[j] = v, i
                elif v > high[j]:
                    high[j], hi[j] = v, i
                elif v != v:
                    nan[j] = True
        for j in range(m):
            if nan[j]:
                keep[start] = True
            else:
                keep[lo[j]] = True
                keep[hi[j]] = True
        start = end
