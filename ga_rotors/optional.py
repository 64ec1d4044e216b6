"""Optional dependencies: import one, or say in one line which extra installs it.

The core package needs numpy, numba, scipy, clifford, sympy and matplotlib only. Results
in xarray's formats (``[results]``: xarray, h5netcdf, zarr) and sweeps on Dask
(``[dask]``) are extras; a command that needs a missing one fails with
:class:`MissingExtraError`, naming the ``pip install`` command, never with a traceback.
"""

from __future__ import annotations

import importlib

from .errors import GaRotorsError

__all__ = ["MissingExtraError", "require"]


class MissingExtraError(GaRotorsError, ImportError):
    """An optional dependency is not installed; the message names the install command.

    Examples
    --------
    >>> raise MissingExtraError("no_such_module", "results")
    Traceback (most recent call last):
    ...
    ga_rotors.optional.MissingExtraError: no_such_module is not installed; it comes with \
the results extra: pip install ".[results]" in the ga_rotors repository
    """

    def __init__(self, module: str, extra: str):
        self.module, self.extra = module, extra
        super().__init__(
            f"{module} is not installed; it comes with the {extra} extra: "
            f'pip install ".[{extra}]" in the ga_rotors repository'
        )


def require(module: str, extra: str):
    """Import ``module``, or raise :class:`MissingExtraError` naming ``extra``.

    Examples
    --------
    >>> require("json", "results").__name__
    'json'
    >>> require("no_such_module", "dask")
    Traceback (most recent call last):
    ...
    ga_rotors.optional.MissingExtraError: no_such_module is not installed; ...
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        if exc.name is not None and module.split(".")[0] != exc.name.split(".")[0]:
            raise  # the module is there but one of *its* imports broke: show that
        raise MissingExtraError(module, extra) from None
