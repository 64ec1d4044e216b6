"""Exceptions and warnings that ga_rotors raises on purpose.

Every error a user can cause derives from :class:`GaRotorsError`; the command line
prints those as one line and exits non-zero, without a traceback. Errors about bad
arguments are also :class:`ValueError`, so ``except ValueError`` keeps working.
"""

from __future__ import annotations

__all__ = [
    "GaRotorsError",
    "GimbalLockWarning",
    "InputError",
    "IntegrationStoppedWarning",
    "PrecisionError",
    "SceneError",
    "StepLimitWarning",
    "echoed",
    "first_line",
]


class GaRotorsError(Exception):
    """Base class of the errors ga_rotors reports to users.

    Examples
    --------
    One ``except`` catches every error a user can cause:

    >>> from ga_rotors import quaternion
    >>> try:
    ...     quaternion.normalize([0.0, 0.0, 0.0, 0.0])
    ... except GaRotorsError as exc:
    ...     print(type(exc).__name__, "-", exc)
    InputError - q: expected nonzero values, got zero at index ()
    """


class InputError(GaRotorsError, ValueError):
    """An argument has the wrong shape, type or value; the message names it.

    The argument's name is data too: ``key`` (None when the message names no single
    argument) and ``detail``, what is wrong with it, so code that reports the error
    elsewhere (a scene names its own key) never parses the message.

    Parameters
    ----------
    detail : str
        What is wrong (the whole message when ``key`` is None).
    key : str, optional
        The argument at fault; the message is then ``"<key>: <detail>"``.

    Examples
    --------
    >>> from ga_rotors import quaternion
    >>> quaternion.normalize([1.0, 2.0, 3.0])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: q: expected ...
    >>> issubclass(InputError, ValueError)  # ``except ValueError`` keeps working
    True
    >>> exc = InputError("expected a positive number, got -1", key="step")
    >>> str(exc), exc.key, exc.detail
    ('step: expected a positive number, got -1', 'step', 'expected a positive number, got -1')
    """

    def __init__(self, detail: str, key: str | None = None):
        self.key = key
        self.detail = detail
        super().__init__(echoed(f"{key}: {detail}" if key else detail, MESSAGE_LIMIT))


class PrecisionError(GaRotorsError, ArithmeticError):
    """A computation cannot reach the accuracy it promises (an exact reference whose
    rounding-error bound exceeds the requested limit); raised instead of a degraded answer.

    Examples
    --------
    The heavy top's exact solution, asked for a time so far off that its rounding-error
    bound exceeds the default ``max_error``:

    >>> import math
    >>> from ga_rotors.reference.heavy_top import HeavyTop
    >>> tilted = (math.cos(0.25), 0.0, math.sin(0.25), 0.0)  # θ = 0.5 rad about y
    >>> top = HeavyTop((1.0, 1.0, 0.5), 1.0, tilted, (0.0, 0.0, 10.0))
    >>> top.state([1e8])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.PrecisionError: heavy top reference: rounding-error bound ... exceeds ...

    ``bound`` is that bound (rad) when the error is a bound beyond a limit (None otherwise):
    what a caller with its own limit, such as a scene, reports in its own terms.
    """

    def __init__(self, message: str, bound: float | None = None):
        super().__init__(message)
        self.bound = bound


class GimbalLockWarning(UserWarning):
    """Euler angles were extracted at (or within round-off of) a gimbal lock.

    The free angle is set by a documented rule (see ``docs/conventions.md``);
    the rotation the angles describe is still exact.

    Examples
    --------
    The identity in z-y'-z'' has θ = 0, where only ψ + φ is defined (φ is set to 0):

    >>> import warnings
    >>> from ga_rotors import euler
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     angles = euler.from_quaternion([1.0, 0.0, 0.0, 0.0], "ZYZ")
    >>> angles.tolist(), [w.category.__name__ for w in caught]
    ([0.0, 0.0, 0.0], ['GimbalLockWarning'])
    """


class IntegrationStoppedWarning(UserWarning):
    """A simulated path stopped before the end of the run: its state stopped being finite
    (the Euler-angle path at sin θ = 0, an explicit method blowing up, an implicit step
    with no solution or no convergence at this step size). The trajectory holds the
    samples up to then; ``meta["paths"][path]["ended_at"]`` says when.

    Examples
    --------
    The Euler-angle path cannot start at θ = 0 (sin θ = 0 divides its rates):

    >>> import warnings
    >>> from ga_rotors import shapes
    >>> from ga_rotors import simulate
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     tr = simulate(shapes.disk(2.0, 0.075), [1.0, 0, 0, 0], [0.02, 0.03, 15.7],
    ...                   duration=1.0, step=1e-3, paths=("rotor", "euler"),
    ...                   euler_angles=(0.0, 0.0, 0.0))
    >>> [w.category.__name__ for w in caught]
    ['IntegrationStoppedWarning']
    >>> tr.meta["paths"]["euler"]["complete"], tr.meta["paths"]["euler"]["ended_at"]
    (False, 0.0)
    >>> tr.meta["paths"]["rotor"]["complete"]
    True
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
    detail : str
        What is wrong with it.

    Examples
    --------
    >>> from ga_rotors.scene import Scene
    >>> try:
    ...     Scene({"body": {"moments": [1, 2, 3]}, "time": {"duration": -1.0}})
    ... except SceneError as exc:
    ...     print(exc.file, exc.key, isinstance(exc, InputError))
    <dict> time.duration True
    """

    def __init__(self, file: str, key: str, message: str):
        self.file = str(file)
        shown = echoed(self.file, FILE_LIMIT)  # a long path keeps its two ends
        where = f"{shown}: {_capped(key)}: " if key else f"{shown}: "
        ValueError.__init__(self, echoed(where + _capped(message), MESSAGE_LIMIT))
        self.key = key
        self.detail = message


#: Longest file name a scene error echoes whole.
FILE_LIMIT = 200

#: Longest message an error carries: beyond it the middle is left out (2,000 names of
#: effects made a 31 kB line), so an error is one readable line whatever it lists.
MESSAGE_LIMIT = 600

#: Longest run of non-blank characters a scene error echoes (a value, a key) before it is
#: cut: a 10,000-character name in a scene gives a readable line, not a screenful.
ECHO_LIMIT = 80


def first_line(exc: BaseException) -> str:
    """The first line of ``exc``'s message, or its type's name when it has none: what a
    one-line error keeps of a library's exception.

    Examples
    --------
    >>> first_line(ValueError("bad header\\nwhile reading block 3"))
    'bad header'
    >>> first_line(KeyError())
    'KeyError'
    """
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def echoed(text, limit: int | None = None) -> str:
    """``text`` as an error line echoes it: each control, format, surrogate or unassigned
    character (Unicode category C: ESC, BEL, line breaks, bidirectional overrides, an
    undecodable byte of a file name) as its Python escape, so nothing echoed can move the
    cursor, clear or retitle a terminal, or break the line; text of more than ``limit``
    characters cut in its middle, its length said.

    Examples
    --------
    >>> print(echoed("out\\x1b]0;owned\\x07/top\\n\\u202e"))
    out\\x1b]0;owned\\x07/top\\n\\u202e
    >>> echoed("θ = 0.5 rad"), echoed("/tmp/" + "a" * 5000, 80)[-21:]
    ('θ = 0.5 rad', 'aaa (5005 characters)')
    """
    import unicodedata

    text = "".join(repr(c)[1:-1] if unicodedata.category(c)[0] == "C" else c for c in str(text))
    if limit is None or len(text) <= limit:
        return text
    half = (limit - 3) // 2
    return f"{text[:half]}...{text[-half:]} ({len(text)} characters)"


def _capped(text: str) -> str:
    """``text`` :func:`echoed` (on one line, no control characters), with every run of
    non-blank characters longer than :data:`ECHO_LIMIT` cut in its middle."""
    import re

    return re.sub(
        rf"\S{{{ECHO_LIMIT + 1},}}", lambda m: echoed(m.group(), ECHO_LIMIT), echoed(text)
    )


class StepLimitWarning(UserWarning):
    """A fixed-step run starts past its integrator's declared step limit.

    Past it the method still returns numbers, but they degrade in a known way (a
    Runge–Kutta method damps the wobble, Lie–Euler amplifies it, a splitting loses the
    thin axis): the message names the integrator, the limit's quantity, its value and the
    limit, and what happens. See the step-limit table in ``docs/stability.md``.

    Examples
    --------
    RK4 at h = 2 s on a body whose wobble frequency is ν = 0.58 rad/s, for 1000 steps
    (checked before any loop runs):

    >>> import warnings
    >>> from ga_rotors.integrators import Problem, get
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     limit = get("rk4").check_step(Problem((1.0, 2.0, 3.0)), (1.0, 0.1, 0.1), 2.0, 1000)
    >>> limit.exceeded, [w.category.__name__ for w in caught]
    (True, ['StepLimitWarning'])
    >>> print(str(caught[0].message)[:48])
    step: rk4 cannot step 2N·|arg R(iy)e^(−iy)| = 11
    """
