"""Exceptions and warnings that ga_rotors raises on purpose.

Every error a user can cause derives from :class:`GaRotorsError`; the command line
prints those as one line and exits non-zero, without a traceback. Errors about bad
arguments are also :class:`ValueError`, so ``except ValueError`` keeps working.
"""

from __future__ import annotations


class GaRotorsError(Exception):
    """Base class of the errors ga_rotors reports to users."""


class InputError(GaRotorsError, ValueError):
    """An argument has the wrong shape, type or value; the message names it."""


class PrecisionError(GaRotorsError, ArithmeticError):
    """A computation cannot reach the accuracy it promises (an exact reference whose
    rounding-error bound exceeds the requested limit); raised instead of a degraded answer."""


class GimbalLockWarning(UserWarning):
    """Euler angles were extracted at (or within round-off of) a gimbal lock.

    The free angle is set by a documented rule (see ``docs/conventions.md``);
    the rotation the angles describe is still exact.
    """


class IntegrationStoppedWarning(UserWarning):
    """A simulated path stopped before the end of the run: its state stopped being finite
    (the Euler-angle path at sin θ = 0, an explicit method blowing up, an implicit step
    with no solution or no convergence at this step size). The trajectory holds the
    samples up to then; ``meta["paths"][path]["ended_at"]`` says when.
    """


class SceneError(InputError):
    """A scene file (or scene dictionary) is invalid.

    The message names the file, the key as a dotted path (``initial.orientation.units``,
    ``effects[2].type``) and what was expected, e.g.::

        heavy_top.toml: time.duration: expected a finite positive number of seconds, got -1

    Attributes
    ----------
    file : str
        The scene's file name (``<dict>`` for a scene built in Python).
    key : str
        Dotted path of the offending key (empty when the whole file is at fault).
    """

    def __init__(self, file: str, key: str, message: str):
        self.file = str(file)
        self.key = key
        where = f"{self.file}: {key}: " if key else f"{self.file}: "
        super().__init__(where + message)


class StepLimitWarning(UserWarning):
    """A fixed-step run starts past its integrator's declared step limit.

    Past it the method still returns numbers, but they degrade in a known way (a
    Runge–Kutta method damps the wobble, Lie–Euler amplifies it, a splitting loses the
    thin axis): the message names the integrator, the limit's quantity, its value and the
    limit, and what happens. See the step-limit table in ``docs/stability.md``.
    """
