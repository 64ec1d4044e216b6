"""A digest of the paper's plotted data, stored in each figure so stale figures are found."""

from __future__ import annotations

import hashlib
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .runs import PaperRun

__all__ = ["data_digest"]


def _significant(a: np.ndarray, digits: int = 9) -> np.ndarray:
    """``a`` as integer mantissas of ``digits`` significant digits, with their exponents."""
    a = np.asarray(a, dtype=np.float64).ravel()
    with np.errstate(divide="ignore"):
        exponent = np.floor(np.log10(np.abs(a)))
    exponent = np.where(np.isfinite(exponent), exponent, 0.0)
    mantissa = np.round(a * 10.0 ** (digits - 1 - exponent))
    return np.concatenate([mantissa, exponent]).astype(np.int64)


def data_digest(runs: list[PaperRun]) -> str:
    """A digest of the plotted data, rounded to 9 significant digits.

    Stored in each PNG's metadata, so a test can tell whether committed figures still
    show what the code computes, without comparing pixels across matplotlib versions.
    Rounding keeps the digest independent of last-bit differences between machines.

    Examples
    --------
    >>> from ga_rotors.paper.runs import run_case
    >>> s = [run_case("disk", 15.0, steps=10)]
    >>> data_digest(s) == data_digest([run_case("disk", 15.0, steps=10)])
    True
    """
    h = hashlib.sha256()
    for s in runs:
        h.update(s.key.encode())
        for name in s.trajectory.names:
            h.update(name.encode())
            h.update(_significant(s.trajectory[name]).tobytes())
    return h.hexdigest()[:16]
