"""A simulation's result: named arrays on one time grid, exportable to CSV and NPZ.

Only what was computed is present: a path that was not asked for has no array, an output
nobody requested is not computed. Names used by :func:`ga_rotors.simulate.simulate`:

======== ========= ===================================================================
name     shape     meaning
======== ========= ===================================================================
t        (n,)      sample times (s)
w        (n, 3)    body angular velocity of the primary path (rad/s)
R        (n, 4)    rotor path: coefficients on clifford's blades (1, e12, e13, e23)
q        (n, 4)    quaternion path: (w, x, y, z)
euler    (m, 3)    Euler-angle path: integrated ZYZ angles (ψ, θ, φ), rad
energy   (n,)      kinetic energy ½ ω·Iω (J) of the primary path
L        (n, 3)    body-frame angular momentum Iω
L_space  (n, 3)    space-frame angular momentum q (Iω) q*
angles   (n, 3)    ZYZ angles (ψ, θ, φ) of the primary path's orientation (ga_rotors.euler)
======== ========= ===================================================================

An array can be shorter than ``t`` (``m < n``) when its path stopped early because its
state stopped being finite (the Euler-angle path hitting sin θ = 0 exactly); its first
``m`` rows are the valid samples, and ``meta["paths"][name]`` says when it ended. CSV
export leaves such cells empty, never NaN.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .errors import InputError
from .files import atomic_write, write_text

__all__ = ["Trajectory"]


class Trajectory:
    """Named arrays sampled on the grid ``t``.

    Parameters
    ----------
    arrays : dict of str -> ndarray
        Must contain ``t`` (1-D); every other array has at most ``len(t)`` rows.
    components : dict of str -> tuple of str, optional
        Column names of multi-column arrays (``R`` -> ``("1", "e12", "e13", "e23")``).
    meta : dict, optional
        How the data were made (integrator, step, body, per-path status).

    Examples
    --------
    >>> tr = Trajectory({"t": np.array([0.0, 0.5]), "w": np.zeros((2, 3))},
    ...                 {"w": ("1", "2", "3")})
    >>> tr.names
    ('t', 'w')
    >>> tr.w.shape
    (2, 3)
    >>> print(tr.to_csv().splitlines()[0])
    t,w_1,w_2,w_3
    """

    def __init__(self, arrays: dict, components: dict | None = None, meta: dict | None = None):
        if "t" not in arrays:
            raise InputError("arrays: a trajectory needs the sample times 't'")
        t = np.asarray(arrays["t"], dtype=np.float64)
        if t.ndim != 1:
            raise InputError(f"t: expected a 1-D array, got shape {t.shape}")
        self._arrays = {"t": t}
        for name, a in arrays.items():
            if name == "t":
                continue
            a = np.asarray(a, dtype=np.float64)
            if a.ndim == 0 or a.shape[0] > t.shape[0]:
                raise InputError(
                    f"{name}: expected at most {t.shape[0]} rows (len(t)), got shape {a.shape}"
                )
            self._arrays[name] = a
        self.components = {k: tuple(v) for k, v in (components or {}).items()}
        self.meta = dict(meta or {})

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the arrays present, in insertion order."""
        return tuple(self._arrays)

    def __getattr__(self, name: str) -> np.ndarray:
        arrays = self.__dict__.get("_arrays", {})
        if name in arrays:
            return arrays[name]
        raise AttributeError(
            f"trajectory has no array {name!r}; it has {', '.join(arrays) or 'none'} "
            "(only requested paths and outputs are computed)"
        )

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._arrays[name]
        except KeyError:
            raise KeyError(
                f"trajectory has no array {name!r}; it has {', '.join(self._arrays)}"
            ) from None

    def __contains__(self, name: str) -> bool:
        return name in self._arrays

    def __len__(self) -> int:
        return self._arrays["t"].shape[0]

    def __repr__(self) -> str:
        shapes = ", ".join(f"{k}{tuple(v.shape)}" for k, v in self._arrays.items())
        return f"Trajectory({shapes})"

    def columns(self) -> list[tuple[str, str, int | None]]:
        """(column header, array name, component index or None), in CSV order."""
        out = []
        for name, a in self._arrays.items():
            if a.ndim == 1:
                out.append((name, name, None))
                continue
            labels = self.components.get(name) or tuple(str(i) for i in range(a.shape[1]))
            if len(labels) != a.shape[1]:
                raise InputError(f"components of {name}: {len(labels)} labels for {a.shape[1]}")
            out.extend((f"{name}_{lab}", name, i) for i, lab in enumerate(labels))
        return out

    def to_csv(self, path=None) -> str | Path:
        """Write every array as CSV columns (``R_e12``, ``q_w``, ...), atomically.

        ``%.17g`` (17 significant digits: every float64 round-trips exactly); cells past
        the end of a shorter array are empty. Without ``path``, return the text.
        """
        cols = self.columns()
        n = len(self)
        table = np.empty((n, len(cols)))
        lengths = np.empty(len(cols), dtype=np.int64)
        for j, (_, name, comp) in enumerate(cols):
            a = self._arrays[name]
            lengths[j] = a.shape[0]
            table[: a.shape[0], j] = a if comp is None else a[:, comp]
        full = int(lengths.min()) if len(cols) else n
        fmt = ",".join(["%.17g"] * len(cols))
        lines = [",".join(c[0] for c in cols)]
        lines.extend(fmt % row for row in map(tuple, table[:full].tolist()))
        for r in range(full, n):
            lines.append(
                ",".join(f"{table[r, j]:.17g}" if r < lengths[j] else "" for j in range(len(cols)))
            )
        text = "\n".join(lines) + "\n"
        if path is None:
            return text
        return write_text(path, text)

    def to_npz(self, path) -> Path:
        """Write every array (and the component labels) to a ``.npz`` file, atomically.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> tr = Trajectory({"t": np.arange(3.0)})
        >>> p = tr.to_npz(pathlib.Path(tempfile.mkdtemp()) / "run.npz")
        >>> sorted(np.load(p).files)
        ['t']
        """
        payload = dict(self._arrays)
        for name, labels in self.components.items():
            if name in payload:
                payload[f"{name}__components"] = np.array(labels)

        def write(fh):
            np.savez(fh, **payload)

        return atomic_write(path, write)
