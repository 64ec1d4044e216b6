"""TOML files from anyone, read with guards; resolved scene data written back as TOML text.

Reading: :func:`read_file` takes a regular file of bounded size (never a device, a FIFO
or a file of gigabytes) and :func:`parse_toml` parses its text with the standard
library's ``tomllib`` (data only, nothing evaluated), refusing nesting beyond
:data:`MAX_NESTING`; every refusal is one :class:`~ga_rotors.errors.SceneError` line
naming the file. Scene files and sweep files both come through here.

Writing: the standard library reads TOML but does not write it; a resolved scene needs
only tables, sub-tables, arrays of tables and plain values, which :func:`dumps_toml`
writes so that ``tomllib.loads(dumps_toml(data)) == data`` for any resolved scene.
"""

from __future__ import annotations

import json
import os
import re
import stat
import tomllib
from collections.abc import Mapping

from ..errors import SceneError

__all__ = ["MAX_NESTING", "check_nesting", "dumps_toml", "parse_toml", "read_file"]

#: Deepest nesting of tables and arrays a file may have (a scene needs four levels).
MAX_NESTING = 32


def read_file(path, limit: int, what: str = "scene") -> str:
    """The UTF-8 text of ``path``, a regular file of at most ``limit`` bytes.

    Opened without blocking (a FIFO with no writer does not hang), checked on the open
    file (a symlink to ``/dev/zero`` is a character device, refused before any read),
    and never read past ``limit`` (a file that grows while read is refused too).

    Examples
    --------
    >>> read_file("/dev/null", 100)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: /dev/null: not a regular file (a character device); ...
    """
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except (OSError, ValueError) as exc:
        raise SceneError(str(path), "", f"cannot read the file: {exc}") from None
    with os.fdopen(fd, "rb") as f:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise SceneError(
                str(path), "", f"not a regular file ({_kind(mode)}); a {what} file is a text file"
            )
        size = os.fstat(fd).st_size
        data = b"" if size > limit else _read_up_to(f, size, limit)
    if size > limit or len(data) > limit:
        size = max(size, len(data))
        raise SceneError(str(path), "", f"{size:,} bytes; a {what} file is at most {limit:,}")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SceneError(str(path), "", f"cannot read the file: {exc}") from None


def _read_up_to(f, size: int, limit: int) -> bytes:
    """The bytes of ``f``, whose size was ``size`` when opened, and at most ``limit + 1``
    of them (one more than the limit shows a file that grew past it while read).

    Read as ``size + 1`` bytes first, not ``limit + 1``: a buffered ``read(n)`` allocates
    n bytes before it reads, so every scene file read would cost the limit in memory."""
    data = f.read(size + 1)
    if len(data) > size:  # grown since it was opened (or a size the kernel does not know)
        data += f.read(limit + 1 - len(data))
    return data


def _kind(mode: int) -> str:
    kinds = ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"),
             (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO"),
             (stat.S_ISSOCK, "a socket"))  # fmt: skip
    return next((name for test, name in kinds if test(mode)), "not a file")


def parse_toml(text: str, file: str) -> dict:
    """The data of the TOML ``text`` (``file`` names it in errors), at most
    :data:`MAX_NESTING` levels deep.

    Examples
    --------
    >>> parse_toml("a = [[1], [2]]", "x.toml")
    {'a': [[1], [2]]}
    >>> parse_toml("a = " + "[" * 40 + "]" * 40, "x.toml")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: x.toml: arrays or tables nested too deeply
    """
    try:  # a byte-order mark (editors on Windows save one) is not the text's
        data = tomllib.loads(text.removeprefix("\ufeff"))
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(file, "", f"not valid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses once per level of nesting
        raise SceneError(file, "", _TOO_DEEP) from None
    except ValueError as exc:  # an integer past Python's digit limit (4,300 digits)
        raise SceneError(file, "", f"not valid TOML: {str(exc).split(':')[0]}") from None
    check_nesting(data, file)
    return data


_TOO_DEEP = "arrays or tables nested too deeply"


def check_nesting(data, file: str) -> None:
    """The one-line refusal of data nested more than :data:`MAX_NESTING` levels deep, for
    data that did not come through :func:`parse_toml` too (a scene built in Python, whose
    copy would recurse as deep: 2,000 levels of table headers gave a RecursionError).

    Examples
    --------
    >>> deep = {}
    >>> node = deep
    >>> for _ in range(2000):
    ...     node["a"] = node = {}
    >>> check_nesting(deep, "deep.toml")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: deep.toml: arrays or tables nested too deeply
    """
    if _depth(data) > MAX_NESTING:
        raise SceneError(file, "", _TOO_DEEP)


def _depth(data) -> int:
    """How deep tables and arrays nest in ``data`` (a walk without recursion)."""
    deepest, todo = 0, [(data, 1)]
    while todo:
        value, depth = todo.pop()
        items = value.values() if isinstance(value, Mapping) else value
        if isinstance(value, Mapping | list | tuple):
            deepest = max(deepest, depth)
            if depth <= MAX_NESTING:
                todo.extend((v, depth + 1) for v in items
                             if isinstance(v, Mapping | list | tuple))  # fmt: skip
    return deepest


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
