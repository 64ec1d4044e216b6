"""Work-precision figures: one log–log PNG per case, 150 dpi, as a palette PNG.

Line plots need few colours, so the figure is stored as a 256-colour palette PNG
(:func:`ga_rotors.paper.figures.palette_png`): a third of the RGB file's size at the
same resolution, the anti-aliased text kept sharp.
"""

from __future__ import annotations

import numpy as np

from .sweeps import Study

__all__ = ["plot"]


def plot(st: Study, path) -> None:
    """Log–log work-precision figure of one case: error, energy and momentum drift against
    wall time and against evaluations (solid: ga_rotors, dotted: compiled peers, dashed:
    casual peers); written atomically as a 150 dpi palette PNG.

    Examples
    --------
    >>> import dataclasses, tempfile, pathlib, PIL.Image
    >>> from ga_rotors.accuracy import cases, study
    >>> case = dataclasses.replace(cases()["asymmetric_far"], steps=(100, 200))
    >>> st = study(case, ["split2"], factor=2.0, repeats=1, peers=False)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     plot(st, pathlib.Path(d) / "fig.png")
    ...     with PIL.Image.open(pathlib.Path(d) / "fig.png") as image:
    ...         image.mode, image.size, [round(x) for x in image.info["dpi"]]
    ('P', (1500, 1650), [150, 150])
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 2, figsize=(10, 11), sharex="col")
    methods = []
    for p in st.points:
        if p.method not in methods:
            methods.append(p.method)
    # ga_rotors' methods take tab20's colours in turn; the peers (dotted: compiled, dashed:
    # casual) take tab20b's, a palette tab20 does not share, so no peer has the colour of
    # one of ours (dp8 and njit_dop853 lie on each other).
    ours = [m for m in methods if _family(st, m) == "ga_rotors"]
    colours = {m: plt.get_cmap("tab20")(k % 20) for k, m in enumerate(ours)}
    peers = [m for m in methods if m not in colours]
    # tab20b in four shades of five hues: the darkest and the middle shade of each first
    order = (0, 4, 8, 12, 16, 2, 6, 10, 14, 18, 1, 5, 9, 13, 17, 3, 7, 11, 15, 19)
    colours |= {m: plt.get_cmap("tab20b")(order[k % 20]) for k, m in enumerate(peers)}
    for m in methods:
        # From coarse to fine (step counts up, tolerances down), so a line doubles back
        # only where a finer run was timed faster: timing noise, shown as it was measured.
        pts = sorted((p for p in st.points if p.method == m and not p.note),
                     key=lambda p: p.setting if p.setting >= 1 else 1 / p.setting)  # fmt: skip
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
                    ms=4,
                    lw=1.3,
                    color=colours[m],
                    label=m if row == col == 0 else None,
                )
    titles = ("orientation error (rad)", "relative energy drift", "relative momentum drift")
    for row, title in enumerate(titles):
        axes[row, 0].set_ylabel(title, fontsize=11)
        for col in range(2):
            axes[row, col].grid(True, which="major", alpha=0.3)
            axes[row, col].tick_params(labelsize=10)
    axes[2, 0].set_xlabel("wall time (s), median of warm repeats", fontsize=11)
    axes[2, 1].set_xlabel("right-hand-side evaluations (splitting: Strang stages)", fontsize=11)
    fig.suptitle(f"{st.case.title}\nsolid: ga_rotors; dotted: compiled peers; dashed: casual "
                 "peers", y=0.995, fontsize=12)  # fmt: skip
    fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.955), ncol=5, fontsize=9.5,
               frameon=False)  # fmt: skip
    fig.tight_layout(rect=(0, 0, 1, 0.885))
    _save_atomically(fig, path, st.case.title)
    plt.close(fig)


def _family(st: Study, method: str) -> str:
    return next(p.family for p in st.points if p.method == method)


#: Resolution of the figures (issue 14: legible, not 60 dpi).
DPI = 150


def _save_atomically(fig, path, title: str) -> None:
    from pathlib import Path

    from ..files import atomic_write
    from ..paper.figures import palette_png

    png = palette_png(fig, f"ga_rotors work-precision study: {title}", dpi=DPI)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, lambda fh: fh.write(png))
