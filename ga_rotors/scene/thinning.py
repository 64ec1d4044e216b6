"""A bounded copy of a long run for its figure: every sample's extremes, at screen resolution.

A figure is a few hundred pixels wide; a run may have 10⁸ samples. :class:`ThinnedCopy`
takes the run piece by piece and keeps, for each of :data:`COLUMNS` equal slices of the
time span (about one pixel column each), the first and last sample of the slice and the
samples where each column of each array is smallest and largest in it: the min/max
envelope a line plot of all the samples would draw, spikes included, in at most
``COLUMNS × (2 + 2 × columns)`` rows whatever the length of the run. A run of at most
:data:`KEEP_ALL` samples is kept whole, so the figure of a short run is the figure of all
its samples.
"""

from __future__ import annotations

import numpy as np

from ..trajectory import Trajectory

__all__ = ["COLUMNS", "KEEP_ALL", "ThinnedCopy"]

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
        where = np.floor((t - self.t_start) / self.span * self.columns)
        slices = np.clip(where, 0, self.columns - 1).astype(np.int64)
        # times increase, so each slice is a run of consecutive rows: reduceat per run
        starts = np.flatnonzero(np.diff(slices, prepend=-1))
        keep = [starts, np.append(starts[1:] - 1, t.shape[0] - 1)]  # each slice's ends
        for name in piece.names:
            a = piece[name]
            if name == "t" or a.shape[0] == 0:
                continue
            n = a.shape[0]
            runs = starts[starts < n]
            sizes = np.diff(np.append(runs, n))
            run_of = np.repeat(np.arange(runs.shape[0]), sizes)
            for column in a.reshape(n, -1).T:
                for reduce in (np.minimum, np.maximum):  # NaN, if any, is the extreme
                    extreme = np.repeat(reduce.reduceat(column, runs), sizes)
                    hits = np.flatnonzero((column == extreme) | (extreme != extreme))
                    first = np.concatenate([[True], run_of[hits][1:] != run_of[hits][:-1]])
                    keep.append(hits[first])  # the first row of each run reaching it
        return np.unique(np.concatenate(keep))

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
