"""List the bundled scenes; run one with ga-rotors run NAME, print it with ga-rotors show NAME.

The scenes are TOML files shipped in ga_rotors/scene/bundled/; their schema
is in docs/scenes.md. With --figures DIR every bundled scene is run and its figure written
to DIR/<name>.png (how docs/figures/scenes/ is made), or .svg / .pdf with --format.
"""

from __future__ import annotations

import argparse

from ..paper.reproduce import FORMATS  # as ga-rotors paper and run --format

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--figures",
        metavar="DIR",
        default=None,
        help="run every bundled scene and write its figure to DIR/<name>.png",
    )
    parser.add_argument(
        "--format",
        choices=FORMATS,
        default="png",
        help="with --figures: PNG at 150 dpi (default), or vector SVG or PDF for print",
    )


def run(args: argparse.Namespace) -> int:
    from ..scene import bundled

    names = bundled()
    if args.figures is None:
        if args.format != "png":
            from ..errors import InputError

            raise InputError("--format: only with --figures DIR (the figures' format)")
        width = max(map(len, names))
        for name, description in names.items():
            print(f"{name:<{width}}  {description}")
        return 0
    from ..errors import InputError
    from ..files import checked_path, output_set, shown_path
    from ..scene import load_scene, run_scene
    from ..scene.figures import render

    out = checked_path(args.figures, "--figures")  # "" is no name, not the current folder
    if not out.is_dir():
        raise InputError(f"{shown_path(out)} is not a directory", key="--figures")
    written = []
    with output_set(out, "--figures") as stage:  # every figure, or the previous ones
        for name in names:
            scene = load_scene(name)
            if not scene.data["output"]["plots"]:
                continue
            figure = render(scene, run_scene(scene), args.format)
            (stage / f"{name}.{args.format}").write_bytes(figure)
            written.append((out / f"{name}.{args.format}", len(figure)))
    for path, size in written:
        print(f"wrote {path} ({size // 1024} KiB)")
    return 0
