"""Loading scenes: from a file, or from the scenes bundled with ga_rotors by name.

The bundled scenes are TOML files in ``ga_rotors/scene/bundled/`` (``ga-rotors scenes``
lists them); a file is read as UTF-8 and parsed by :meth:`Scene.from_toml`, data only.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

from ..errors import SceneError
from .model import Scene
from .reader import suggest
from .toml_io import read_file

__all__ = ["bundled", "bundled_path", "load_scene"]


def _folder():
    return resources.files(__package__) / "bundled"


def bundled() -> dict[str, str]:
    """Bundled scene names -> their one-line descriptions.

    Examples
    --------
    >>> "heavy_top" in bundled()
    True
    """
    out = {}
    for entry in _files():
        data = tomllib.loads(entry.read_text(encoding="utf-8"))
        description = data.get("scene", {}).get("description", "")
        out[entry.name[:-5]] = description.strip().splitlines()[0] if description else ""
    return out


def _files() -> list:
    """The bundled scene files, by name."""
    files = sorted(_folder().iterdir(), key=lambda p: p.name)
    return [p for p in files if p.name.endswith(".toml")]


def bundled_path(name: str) -> Path:
    """The file of the bundled scene ``name``.

    Examples
    --------
    >>> bundled_path("heavy_top").name
    'heavy_top.toml'
    """
    return Path(str(_folder() / f"{name}.toml"))


#: Largest scene file read: scenes are a few kB; a file of gigabytes is not read whole.
MAX_FILE_BYTES = 10**7


def load_scene(path_or_name) -> Scene:
    """Load a scene file, or a bundled scene by name (``ga-rotors scenes`` lists them).

    Examples
    --------
    >>> load_scene("spinning_disk").name
    'spinning_disk'
    >>> load_scene("spining_disk")
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: spining_disk: no such file, and no bundled scene of that name ...
    >>> load_scene("a" * 5000)
    Traceback (most recent call last):
    ...
    ga_rotors.errors.SceneError: aaa...aaa (5000 characters): cannot read the file: File name ...
    """
    if isinstance(path_or_name, Scene):
        return path_or_name
    path = Path(path_or_name)
    try:
        is_file = path.is_file()
    except OSError as exc:  # a name too long for the system, a loop of links
        raise SceneError(str(path_or_name), "", f"cannot read the file: {exc.strerror}") from None
    except ValueError:  # an embedded NUL
        raise SceneError(str(path_or_name), "", "not a file name (it holds a NUL)") from None
    if not is_file:
        # the names only: parsing every bundled scene for its description took 2-3 ms,
        # paid before each sweep's chunks start
        names = [p.name[:-5] for p in _files()]
        name = str(path_or_name)
        if name in names:
            path = bundled_path(name)
        else:
            raise SceneError(
                name,
                "",
                f"no such file, and no bundled scene of that name{suggest(name, names)}; "
                f"bundled: {', '.join(names)}",
            )
    text = read_file(path, MAX_FILE_BYTES)
    return Scene.from_toml(text, file=str(path), base_dir=path.resolve().parent)
