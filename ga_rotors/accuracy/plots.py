"""Work-precision figures: one log–log PNG per case."""

from __future__ import annotations

import numpy as np

from .sweeps import Study

__all__ = ["plot"]


def plot(st: Study, path) -> None:
    """Log–log work-precision figure of one case: error, energy and momentum drift against
    wall time and against evaluations (solid: ga_rotors, dotted: compiled peers, dashed:
    casual peers); written atomically as PNG.

    Examples
    --------
    >>> import dataclasses, tempfile, pathlib
    >>> from ga_rotors.accuracy import cases, study
    >>> case = dataclasses.replace(cases()["asymmetric_far"], steps=(100, 200))
    >>> st = study(case, ["split2"], factor=2.0, repeats=1, peers=False)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     plot(st, pathlib.Path(d) / "fig.png")
    ...     (pathlib.Path(d) / "fig.png").stat().st_size > 1000
    True
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 2, figsize=(10, 10), sharex="col")
    methods = []
    for p in st.points:
        if p.method not in methods:
            methods.append(p.method)
    cmap = plt.get_cmap("tab20")
    for i, m in enumerate(methods):
        pts = sorted((p for p in st.points if p.method == m and not p.note),
                     key=lambda p: p.seconds)  # fmt: skip
        if not pts:
            continue
        style = {"ga_rotors": "-", "compiled": ":"}.get(pts[0].family, "--")
        for row, attr in enumerate(("error", "energy_drift", "momentum_drift")):
            y = np.array([max(getattr(p, attr), 1e-17) for p in pts])
            keep = np.isfinite(y) & (y <= 10.0)  # a drift beyond 10 only says "diverged"
            for col, xattr in enumerate(("seconds", "evaluations")):
                x = np.array([getattr(p, xattr) for p in pts])
                axes[row, col].loglog(
                    x[keep],
                    y[keep],
                    style,
                    marker=".",
                    ms=3,
                    lw=1,
                    color=cmap(i % 20),
                    label=m if row == col == 0 else None,
                )
    titles = ("orientation error (rad)", "relative energy drift", "relative momentum drift")
    for row, title in enumerate(titles):
        axes[row, 0].set_ylabel(title)
        for col in range(2):
            axes[row, col].grid(True, which="major", alpha=0.3)
    axes[2, 0].set_xlabel("wall time (s), median of warm repeats")
    axes[2, 1].set_xlabel("right-hand-side evaluations (splitting: Strang stages)")
    fig.suptitle(st.case.title, y=0.995, fontsize=10)
    fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.97), ncol=6, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    _save_atomically(fig, path)
    plt.close(fig)


def _save_atomically(fig, path) -> None:
    from pathlib import Path

    from ..files import atomic_write

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, lambda fh: fig.savefig(fh, format="png", dpi=60))
