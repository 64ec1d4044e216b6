"""Print a scene resolved with all its defaults, as TOML, and what it resolves to.

SCENE is a scene file or a bundled scene's name (ga-rotors scenes lists them). The output
is itself a valid scene file (every key explicit); the closing comment lines give the
derived values: principal moments (about the pivot, with gravity), the initial orientation
and body angular velocity in radians, the step count and the exact solution that applies.
Nothing is simulated and no user-torque module is imported.
"""

from __future__ import annotations

import argparse

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "scene", metavar="SCENE", help="a scene file (.toml) or a bundled scene's name"
    )


def run(args: argparse.Namespace) -> int:
    from ..scene import load_scene

    scene = load_scene(args.scene)
    print(f"# {scene.name}: resolved from {scene.file}\n")
    print(scene.to_toml())
    print(scene.describe())
    return 0
