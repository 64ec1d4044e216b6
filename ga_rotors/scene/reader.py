"""Reading untrusted nested data (a parsed scene file) with errors that say where and what.

A :class:`Reader` carries the file name; each check takes the value and its dotted key
(``initial.orientation.units``, ``effects[1].torque``) and either returns the value in
canonical form (floats as ``float``, vectors as tuples) or raises
:class:`ga_rotors.errors.SceneError` naming the file, the key and what was expected.
Unknown keys and names get the closest valid spelling suggested.

Only the data's own types are inspected: nothing in it is ever evaluated.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable, Mapping

from ..errors import SceneError

__all__ = ["Reader", "join", "suggest"]


def join(prefix: str, name: str | int) -> str:
    """The dotted key of ``name`` inside ``prefix`` (``a.b``, ``a[2]``).

    Examples
    --------
    >>> join("", "body"), join("body", "mass"), join("effects", 2)
    ('body', 'body.mass', 'effects[2]')
    """
    if isinstance(name, int):
        return f"{prefix}[{name}]"
    return f"{prefix}.{name}" if prefix else name


def suggest(word: str, choices: Iterable[str]) -> str:
    """``" (did you mean 'x'?)"`` for the closest choice, or ``""``.

    Examples
    --------
    >>> suggest("duraton", ["duration", "start"])
    " (did you mean 'duration'?)"
    >>> suggest("zzz", ["duration"])
    ''
    """
    close = difflib.get_close_matches(str(word), list(choices), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _describe(value) -> str:
    if isinstance(value, bool):
        return f"boolean {str(value).lower()}"
    if isinstance(value, str):
        return f"string {value!r}"
    if isinstance(value, Mapping):
        return "a table"
    if isinstance(value, list | tuple):
        return f"an array of {len(value)} items"
    if isinstance(value, int) and abs(value).bit_length() > 256:
        # its digits are not echoed (Python refuses to write more than 4,300 of them)
        return f"an integer of {int(abs(value).bit_length() * 0.30103) + 1} digits"
    if isinstance(value, int | float):
        return repr(value)
    return type(value).__name__


class Reader:
    """Checks for one file's data; every error names ``file`` and the key.

    Examples
    --------
    >>> reader = Reader("spin.toml")
    >>> reader.number(2, "time.duration", positive=True)
    2.0
    >>> reader.number(-1, "time.duration", positive=True, unit="s")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: spin.toml: time.duration: expected a finite positive number ...
    """

    def __init__(self, file: str):
        self.file = str(file)

    def error(self, key: str, message: str) -> SceneError:
        return SceneError(self.file, key, message)

    # -------------------------------------------------------------- tables and keys

    def table(
        self, value, key: str, allowed: Iterable[str] | None = None, required: Iterable[str] = ()
    ) -> dict:
        """``value`` as a dict whose keys are all in ``allowed`` (any, when None) and
        include ``required``."""
        if not isinstance(value, Mapping):
            raise self.error(key, f"expected a table, got {_describe(value)}")
        allowed = value if allowed is None else list(allowed)
        for name in value:
            if name not in allowed:
                raise self.error(
                    join(key, name),
                    f"unknown key{suggest(name, allowed)}; expected one of {', '.join(allowed)}",
                )
        for name in required:
            if name not in value:
                raise self.error(join(key, name), "missing; this key is required")
        return dict(value)

    def one_of(self, value: Mapping, key: str, forms: Iterable[str]) -> str:
        """The single key of ``forms`` present in ``value`` (exactly one must be)."""
        forms = list(forms)
        present = [f for f in forms if f in value]
        if len(present) != 1:
            got = "none" if not present else " and ".join(present)
            raise self.error(key, f"expected exactly one of {', '.join(forms)}; got {got}")
        return present[0]

    # -------------------------------------------------------------- scalars

    def number(
        self,
        value,
        key: str,
        *,
        positive: bool = False,
        nonnegative: bool = False,
        unit: str = "",
    ) -> float:
        """A finite real number (TOML integer or float), optionally > 0 or ≥ 0."""
        what = "a finite number"
        if positive:
            what = "a finite positive number"
        elif nonnegative:
            what = "a finite number ≥ 0"
        if unit:
            what += f" ({unit})"
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(key, f"expected {what}, got {_describe(value)}")
        try:
            x = float(value)
        except OverflowError:  # an integer beyond float64 (TOML integers have any size)
            raise self.error(key, f"expected {what}, got {_describe(value)}, beyond "
                             "float64") from None  # fmt: skip
        if not math.isfinite(x) or (positive and x <= 0) or (nonnegative and x < 0):
            raise self.error(key, f"expected {what}, got {value!r}")
        return x

    def string(self, value, key: str, choices: Iterable[str] | None = None) -> str:
        """A string, optionally one of ``choices`` (with a suggestion when it is not)."""
        if not isinstance(value, str):
            raise self.error(key, f"expected a string, got {_describe(value)}")
        if choices is not None:
            choices = list(choices)
            if value not in choices:
                raise self.error(
                    key,
                    f"unknown value {value!r}{suggest(value, choices)}; "
                    f"expected one of {', '.join(choices)}",
                )
        return value

    def boolean(self, value, key: str) -> bool:
        if not isinstance(value, bool):
            raise self.error(key, f"expected true or false, got {_describe(value)}")
        return value

    # -------------------------------------------------------------- arrays

    def array(self, value, key: str) -> list:
        if not isinstance(value, list | tuple):
            raise self.error(key, f"expected an array, got {_describe(value)}")
        return list(value)

    def vector(self, value, key: str, size: int = 3, *, unit: str = "") -> tuple[float, ...]:
        """An array of exactly ``size`` finite numbers."""
        items = self.array(value, key)
        if len(items) != size:
            what = f"an array of {size} numbers" + (f" ({unit})" if unit else "")
            raise self.error(key, f"expected {what}, got {len(items)} items")
        return tuple(self.number(v, join(key, i)) for i, v in enumerate(items))

    def numbers(self, value, key: str) -> tuple[float, ...]:
        """An array of any length of finite numbers."""
        return tuple(self.number(v, join(key, i)) for i, v in enumerate(self.array(value, key)))

    def matrix(self, value, key: str, size: int = 3) -> tuple[tuple[float, ...], ...]:
        """A ``size`` × ``size`` array of arrays of finite numbers."""
        rows = self.array(value, key)
        if len(rows) != size:
            raise self.error(key, f"expected {size} rows of {size} numbers, got {len(rows)} rows")
        return tuple(self.vector(r, join(key, i), size) for i, r in enumerate(rows))

    def names(self, value, key: str, choices: Iterable[str]) -> list[str]:
        """An array of distinct strings, each one of ``choices``."""
        choices = list(choices)
        out: list[str] = []
        for i, item in enumerate(self.array(value, key)):
            name = self.string(item, join(key, i), choices)
            if name in out:
                raise self.error(join(key, i), f"{name!r} is listed twice")
            out.append(name)
        return out
