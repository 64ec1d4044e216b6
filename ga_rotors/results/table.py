"""CSV for spreadsheets: one column per component, the unit in every header.

Headers read ``name_component [unit]`` (``t [s]``, ``w_1 [rad/s]``, ``q_w [1]``); values
are written as ``%.17g`` writes them (every float64 round-trips exactly), a block of rows
at a time by one compiled pass (:mod:`ga_rotors.results.decimal`: no Python object per
value), and written block by block, so memory beyond the arrays themselves stays at one
block. A path that stopped early leaves its cells empty after its last sample, never NaN.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError
from ..files import atomic_write
from .variables import describe

__all__ = ["BLOCK_ROWS", "csv_buffer_size", "csv_header", "csv_rows", "write_csv"]

#: Rows formatted per compiled call: about 600 KB of text for a heavy top's 16 columns,
#: which stays in the processor's cache while it is formatted and then copied into the
#: file (with 16,384 rows, 4.8 MB, the copy into the page cache cost 3-5x more: 0.45-0.73
#: against 0.15 s CPU for the 577 MB of a 1e7-step heavy top, under load).
BLOCK_ROWS = 2048


def csv_header(trajectory) -> list[str]:
    """Column headers with units, in the order :meth:`Trajectory.columns` gives.

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.zeros(2), "w": np.zeros((2, 3))}, {"w": ("1", "2", "3")})
    >>> csv_header(tr)
    ['t [s]', 'w_1 [rad/s]', 'w_2 [rad/s]', 'w_3 [rad/s]']

    An array the package does not know (one a user added) has no unit to show:

    >>> csv_header(Trajectory({"t": np.zeros(2), "x": np.zeros(2)}))
    ['t [s]', 'x']
    """
    out = []
    for header, name, _ in trajectory.columns():
        try:
            out.append(f"{header} [{describe(name)[0]}]")
        except InputError:
            out.append(header)
    return out


def _blocks(trajectory, rows: int, buffer=None, start: int = 0, stop: int | None = None):
    """The data rows ``start:stop`` as UTF-8 text, ``rows`` at a time
    (:func:`~.decimal.format_rows`; into ``buffer`` when given)."""
    from .decimal import format_rows

    # the columns of :meth:`Trajectory.columns`: each array's side by side, in its order,
    # so each array goes into a block in one copy (a piece of a long run is formatted a
    # block at a time, and per-column copies were a tenth of its CSV's cost)
    arrays, width = [], 0
    for name in trajectory.names:
        a = trajectory[name]
        arrays.append((width, a if a.ndim == 2 else a[:, None]))
        width += arrays[-1][1].shape[1]
    lengths = np.concatenate([np.full(a.shape[1], a.shape[0]) for _, a in arrays])
    n = len(trajectory) if stop is None else stop
    for lo in range(start, n, rows):
        hi = min(n, lo + rows)
        block = np.empty((hi - lo, width))
        for j, a in arrays:
            part = a[lo:hi]
            block[: part.shape[0], j : j + a.shape[1]] = part
            block[part.shape[0] :, j : j + a.shape[1]] = 0.0  # a stopped path: cells left empty
        yield format_rows(block, lengths, lo, out=buffer)


def csv_rows(trajectory, block_rows: int = BLOCK_ROWS, *, buffer=None, start=0, stop=None):
    """The data rows of ``trajectory`` as UTF-8 text, a block of ``block_rows`` at a time
    (no header: :func:`csv_header`); the rows of consecutive pieces of a run, joined, are
    the rows of the run whole.

    With ``buffer`` (a uint8 array of :func:`csv_buffer_size` bytes) each block is written
    into it and given as a memoryview, valid until the next block is asked for: for a
    writer that writes each block at once (:class:`~.streams.CsvStream`). ``start`` and
    ``stop``: only those rows (the text of consecutive row ranges, joined, is the text of
    all of them).

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> list(csv_rows(Trajectory({"t": np.array([0.0, 0.25])})))
    [b'0\\n0.25\\n']
    >>> list(csv_rows(Trajectory({"t": np.array([0.0, 0.25, 0.5])}), start=1, stop=2))
    [b'0.25\\n']
    """
    yield from _blocks(trajectory, block_rows, buffer, start, stop)


def csv_buffer_size(trajectory, block_rows: int = BLOCK_ROWS) -> int:
    """Bytes a block of ``block_rows`` rows of ``trajectory``'s columns may take as text.

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> csv_buffer_size(Trajectory({"t": np.zeros(2), "w": np.zeros((2, 3))}), 10)
    1050
    """
    from .decimal import MAX_CHARS

    return block_rows * (len(trajectory.columns()) * MAX_CHARS + 1)


def write_csv(trajectory, path=None, *, block_rows: int = BLOCK_ROWS) -> str | Path:
    """Write the trajectory as CSV with units in the headers, atomically.

    Without ``path``, return the text.

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> tr = Trajectory({"t": np.array([0.0, 0.5]), "energy": np.array([1.0, 1.0 / 3])})
    >>> print(write_csv(tr), end="")
    t [s],energy [J]
    0,1
    0.5,0.33333333333333331
    """
    header = ",".join(csv_header(trajectory)) + "\n"
    if path is None:
        return header + b"".join(_blocks(trajectory, block_rows)).decode()

    def write(fh):
        fh.write(header.encode())
        for text in csv_rows(trajectory, block_rows):
            fh.write(text)

    return atomic_write(path, write)
