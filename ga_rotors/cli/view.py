"""Write an interactive page of a run: ga-rotors view SCENE_OR_RESULT.

SCENE_OR_RESULT is a scene (a .toml file or a bundled scene's name: the scene is run
first) or a saved result of ga-rotors run (its directory, or its .npz file, next to the
<name>.scene.toml the run wrote). The page is one light, self-contained HTML file that works
offline: the body drawn from its geometry with its pivot, its axes, ω and L, the rotor's
bivector plane, the symmetry axis' trace on the unit sphere, a legend, a time slider with
play/pause, and live rotor, quaternion and Euler-angle readouts for every orientation path
of the run.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "source",
        metavar="SCENE_OR_RESULT",
        help="a scene (.toml or bundled name) or a result directory / .npz of ga-rotors run",
    )
    parser.add_argument(
        "--out",
        metavar="FILE",
        default=None,
        help="the page to write (default: <name>.view.html, next to a result or in ./)",
    )
    parser.add_argument(
        "--duration",
        metavar="SECONDS",
        type=float,
        default=None,
        help="run a scene for this long instead of its time.duration",
    )


def run(args: argparse.Namespace) -> int:
    from ..errors import InputError, StepLimitWarning
    from ..scene import load_scene
    from ..view import View
    from ..view.saved import load_result

    source = Path(args.source)
    if source.suffix == ".npz" or source.is_dir():
        if args.duration is not None:
            raise InputError("--duration: applies to a scene, not to a saved result")
        scene, trajectory = load_result(source)
        where = source if source.is_dir() else source.parent
    else:
        scene = load_scene(args.source)
        if args.duration is not None:
            scene = scene.replace({"time.duration": args.duration})
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", StepLimitWarning)
            from ..scene import run_scene

            trajectory = run_scene(scene)
        for w in caught:
            if issubclass(w.category, StepLimitWarning):
                print(f"ga-rotors: warning: {w.message}", file=sys.stderr)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        where = Path(".")
    out = Path(args.out) if args.out is not None else where / f"{scene.name}.view.html"
    View.from_scene(scene, trajectory).save(out)
    print(f"wrote {out} (open it in a browser; it works offline)")
    return 0
