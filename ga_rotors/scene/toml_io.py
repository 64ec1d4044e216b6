"""Resolved scene data written back as TOML text (reading is the standard library's tomllib).

The standard library reads TOML but does not write it; a resolved scene needs only
tables, sub-tables, arrays of tables and plain values, which :func:`dumps_toml` writes so
that ``tomllib.loads(dumps_toml(data)) == data`` for any resolved scene.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping

__all__ = ["dumps_toml"]

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _toml_key(k: str) -> str:
    return k if _BARE.match(k) else json.dumps(k)


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        return repr(float(v))
    if isinstance(v, str):
        if "\n" not in v:
            return json.dumps(v, ensure_ascii=False)
        # A multi-line basic string: readable in the file, the same value when parsed.
        body = "".join(c if c == "\n" else json.dumps(c, ensure_ascii=False)[1:-1] for c in v)
        return '"""\n' + body + '"""'

    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }"
    return "[" + ", ".join(_toml_value(x) for x in v) + "]"


def dumps_toml(data: Mapping) -> str:
    """Resolved scene data as TOML: tables, sub-tables and arrays of tables.

    Examples
    --------
    >>> print(dumps_toml({"time": {"duration": 1}, "effects": [{"type": "damping"}]}))
    [time]
    duration = 1.0
    <BLANKLINE>
    [[effects]]
    type = "damping"
    <BLANKLINE>
    """
    chunks = []

    def table(header: str, t: Mapping) -> None:
        plain = {k: v for k, v in t.items() if not isinstance(v, Mapping) or k == "rotor"}
        nested = {k: v for k, v in t.items() if k not in plain}
        if plain or not nested:
            chunks.append(f"{header}\n" + "".join(f"{_toml_key(k)} = {_toml_value(v)}\n"
                                                  for k, v in plain.items()))  # fmt: skip
        for k, v in nested.items():
            table(f"[{header[1:-1]}.{_toml_key(k)}]", v)

    for section, value in data.items():
        if isinstance(value, list):
            for entry in value:
                chunks.append(f"[[{section}]]\n" + "".join(
                    f"{_toml_key(k)} = {_toml_value(v)}\n" for k, v in entry.items()))  # fmt: skip
        else:
            table(f"[{_toml_key(section)}]", value)
    return "\n".join(chunks)
