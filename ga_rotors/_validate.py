"""Argument checking shared by every public function.

Messages name the argument and say what was expected, so a user can fix the call
without reading the source. Batched hot paths may skip the up-front finiteness scan
(``finite=False``) and check finiteness inside their compiled loop instead, which
costs about 1 ns per element instead of a second pass over memory.
"""

from __future__ import annotations

import numpy as np

from .errors import InputError

#: Largest | |q| - 1 | accepted where a unit quaternion or rotor is required.
#: Inputs within it are renormalised before use; inputs beyond it are rejected.
#: 1e-6 is far above the drift of float64 arithmetic (about 1e-16 per operation,
#: ~1e-12 after a million compositions) and far below any genuine modelling error.
UNIT_TOLERANCE = 1e-6


def as_float_array(x, name: str, *, last: int | None = None, finite: bool = True) -> np.ndarray:
    """``x`` as a float64 array, checked.

    Parameters
    ----------
    x : array_like
        Real numbers (ints, floats, bools). Strings, complex numbers and ragged
        nested sequences are rejected.
    name : str
        The argument's name, used in error messages.
    last : int, optional
        Required length of the last axis (4 for quaternions, 3 for vectors).
    finite : bool
        Reject NaN and infinities.

    Examples
    --------
    >>> as_float_array([1, 0, 0, 0], "q", last=4)
    array([1., 0., 0., 0.])
    >>> as_float_array([1, 0, 0], "q", last=4)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: q: expected an array of shape (..., 4), got shape (3,)
    """
    if type(x) is np.ndarray:
        raw = x
    elif isinstance(x, np.ma.MaskedArray) and np.ma.is_masked(x):
        raise InputError("expected real numbers, got a masked array with masked values", key=name)
    else:  # an ndarray subclass (np.matrix: indexing one gives 2-d rows) becomes an ndarray
        try:
            raw = np.asarray(x)
        except (ValueError, TypeError, OverflowError):  # ragged nesting, odd sequences
            raise InputError(
                f"expected an array of real numbers, got {type(x).__name__} "
                "(ragged nesting or non-numeric items)",
                key=name,
            ) from None
    if raw.dtype.kind not in "fiub":
        if raw.dtype.kind == "c":
            raise InputError("expected real numbers, got complex values", key=name)
        if raw.dtype.kind == "O":
            raise InputError(
                f"expected an array of real numbers, got {type(x).__name__} "
                "(ragged nesting or non-numeric items)",
                key=name,
            )
        raise InputError(f"expected real numbers, got {raw.dtype} values", key=name)
    a = raw.astype(np.float64, copy=False)
    if last is not None and (a.ndim == 0 or a.shape[-1] != last):
        raise InputError(f"expected an array of shape (..., {last}), got shape {a.shape}", key=name)
    if finite:
        check_finite(a, name)
    return a


def check_finite(a: np.ndarray, name: str) -> None:
    """Raise :class:`InputError` naming the first NaN or infinite entry of ``a``."""
    if not np.isfinite(a).all():
        bad = np.argwhere(~np.isfinite(np.atleast_1d(a)))[0]
        where = tuple(int(i) for i in bad)
        value = np.atleast_1d(a)[where]
        raise InputError(f"contains {value} at index {where}; expected finite numbers", key=name)


def require_unit(
    q: np.ndarray, name: str, tol: float = UNIT_TOLERANCE, what: str = "quaternions"
) -> np.ndarray:
    """Return ``q`` renormalised, or raise if some ``| |q| - 1 | > tol``.

    ``what`` names the kind of argument in the message ("rotors" for a rotor's
    coefficients, whose norm is the quaternion's).

    Examples
    --------
    >>> require_unit(np.array([1.0, 0.0, 0.0, 1e-9]), "q")
    array([1.e+00, 0.e+00, 0.e+00, 1.e-09])
    >>> require_unit(np.array([2.0, 0.0, 0.0, 0.0]), "q")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: q: expected unit quaternions (| |q| - 1 | <= 1e-06), got norm 2 ...
    """
    norms = np.sqrt(np.einsum("...i,...i->...", q, q))
    if norms.ndim == 0 and abs(float(norms) - 1.0) <= tol:
        return q / norms  # one quaternion within tolerance: the same division, less Python
    dev = np.abs(norms - 1.0)
    if dev.size and not (dev.max() <= tol):
        where = np.unravel_index(int(np.argmax(dev)), dev.shape)
        raise InputError(
            f"expected unit {what} (| |{name}| - 1 | <= {tol:g}), got norm "
            f"{norms[where]:.6g} at index {tuple(int(i) for i in where)}; "
            f"normalise it first (ga_rotors.{'rotor' if what == 'rotors' else 'quaternion'}"
            ".normalize)",
            key=name,
        )
    return q / norms[..., None]
