"""CSV for spreadsheets: one column per component, the unit in every header.

Headers read ``name_component [unit]`` (``t [s]``, ``w_1 [rad/s]``, ``q_w [1]``); values
are ``%.17g`` (every float64 round-trips exactly). Rows are formatted a block at a time,
one C-level ``%`` over the whole block instead of a Python call per row or per value, and
written block by block, so memory beyond the arrays themselves stays at one block. A
path that stopped early leaves its cells empty after its last sample, never NaN.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError
from ..files import atomic_write
from .variables import describe

__all__ = ["BLOCK_ROWS", "csv_header", "csv_rows", "write_csv"]

#: Rows formatted per ``%`` call (a few MB of text).
BLOCK_ROWS = 16_384


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


def _blocks(trajectory, rows: int):
    """Text of the data rows, ``rows`` at a time."""
    cols = trajectory.columns()
    n = len(trajectory)
    lengths = [trajectory[name].shape[0] for _, name, _ in cols]
    full = min(lengths) if cols else n
    ncol = len(cols)
    row_fmt = ",".join(["%.17g"] * ncol) + "\n"
    for lo in range(0, n, rows):
        hi = min(n, lo + rows)
        block = np.empty((hi - lo, ncol))
        for j, (_, name, comp) in enumerate(cols):
            a = trajectory[name][lo:hi]
            block[: a.shape[0], j] = a if comp is None else a[:, comp]
        m = max(0, min(hi, full) - lo)  # rows of the block where every column is present
        text = (row_fmt * m) % tuple(block[:m].ravel().tolist()) if m else ""
        for r in range(m, hi - lo):  # the ragged tail of a path that ended early
            cells = [f"{block[r, j]:.17g}" if lo + r < lengths[j] else "" for j in range(ncol)]
            text += ",".join(cells) + "\n"
        yield text


def csv_rows(trajectory, block_rows: int = BLOCK_ROWS):
    """The data rows of ``trajectory`` as UTF-8 text, a block of ``block_rows`` at a time
    (no header: :func:`csv_header`); the rows of consecutive pieces of a run, joined, are
    the rows of the run whole.

    Examples
    --------
    >>> import numpy as np
    >>> from ga_rotors.trajectory import Trajectory
    >>> list(csv_rows(Trajectory({"t": np.array([0.0, 0.25])})))
    [b'0\\n0.25\\n']
    """
    for text in _blocks(trajectory, block_rows):
        yield text.encode()


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
        return header + "".join(_blocks(trajectory, block_rows))

    def write(fh):
        fh.write(header.encode())
        for text in csv_rows(trajectory, block_rows):
            fh.write(text)

    return atomic_write(path, write)
