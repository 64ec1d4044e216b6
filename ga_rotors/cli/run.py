"""Run a scene (a TOML file or a bundled scene's name) and write what it declares.

Integrates exactly the effects and orientation paths the scene declares, prints a closing
summary (invariant drift, the rotor/quaternion cross-check, the error against the exact
solution where one exists, and physics readouts such as nutation bounds or flip times),
and writes the scene's declared data files and figure into --out. The run is streamed:
integrated in pieces, each appended to the data files as it is computed, the summary
accumulated and the figure drawn from a thinned copy, so memory stays bounded whatever
the number of steps. The files move into --out only when the run is complete: a failed
or interrupted run leaves the previous ones. Bundled scenes: ga-rotors scenes. Schema:
docs/scenes.md.

A scene needing more than --max-steps integration steps (default 1e8, summed over paths)
or --max-disk GiB of files (default 20) is refused before it runs; a run of more than
1e6 steps prints its estimate first. A run that stops early (a path's state stopped being
finite) says INCOMPLETE on its first line and exits 3.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

from ..paper.reproduce import FORMATS  # as ga-rotors paper --format

__all__ = ["ProgressBar", "add_arguments", "run"]

DEFAULT_OUT = "results"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "scene", metavar="SCENE", help="a scene file (.toml) or a bundled scene's name"
    )
    parser.add_argument(
        "--out",
        metavar="DIR",
        default=None,
        help=f"output directory (default: ./{DEFAULT_OUT}/<scene name>)",
    )
    parser.add_argument(
        "--allow-user-code",
        metavar="DIR",
        nargs="?",
        const="",
        default=None,
        help="let the scene's user torques run: import them from DIR only (default: the "
        "scene file's folder); without it a scene runs no code (docs/scenes.md)",
    )
    parser.add_argument(
        "--max-steps",
        metavar="N",
        type=float,
        default=None,
        help="refuse a scene needing more integration steps, summed over paths (default 1e8)",
    )
    parser.add_argument(
        "--max-memory",
        metavar="GIB",
        type=float,
        default=None,
        help="refuse a scene whose run needs more memory (default 2 GiB; a streamed run "
        "holds one piece of samples at a time)",
    )
    parser.add_argument(
        "--max-disk",
        metavar="GIB",
        type=float,
        default=None,
        help="refuse a scene whose files need more disk (default 20 GiB)",
    )
    parser.add_argument(
        "--chunk-steps",
        metavar="N",
        type=int,
        default=None,
        help="steps per piece of the streamed run, each path (default 131072; memory grows "
        "with N, not with the run)",
    )
    parser.add_argument(
        "--format",
        choices=FORMATS,
        default=None,
        help="figure format: PNG at 150 dpi, or vector SVG or PDF for print (default: the "
        "scene's output.figure_format, png)",
    )
    bar = parser.add_mutually_exclusive_group()
    bar.add_argument(
        "--progress",
        dest="progress",
        action="store_true",
        default=None,
        help="always show progress (default: only on a terminal, once a run takes > 0.5 s)",
    )
    bar.add_argument(
        "--no-progress", dest="progress", action="store_false", help="never show progress"
    )


class ProgressBar:
    """``progress(done, total)`` callback drawing a bar on ``stream``.

    Shown only when enabled (by default: ``stream`` is a terminal) and only once the run
    has taken ``delay`` seconds, so short runs print nothing. On a terminal the bar is
    redrawn in place at most ten times a second; elsewhere (forced with ``--progress``)
    one line is printed per tenth of the run.

    Examples
    --------
    >>> import io
    >>> log = io.StringIO()
    >>> bar = ProgressBar(log, enabled=True, delay=0.0)
    >>> for done in (0, 50, 100):
    ...     bar(done, 100)
    >>> print(log.getvalue().strip())
    progress:   0.0% after ... s
    progress:  50.0% after ... s
    progress: 100.0% after ... s
    """

    def __init__(self, stream, enabled: bool | None = None, delay: float = 0.5, width: int = 30):
        self.stream = stream
        self.tty = bool(getattr(stream, "isatty", lambda: False)())
        self.enabled = self.tty if enabled is None else enabled
        self.delay = delay
        self.width = width
        self.start = time.monotonic()
        self.last = -1.0
        self.tenth = -1
        self.shown = False

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled or total <= 0:
            return
        now = time.monotonic()
        elapsed = now - self.start
        if elapsed < self.delay:
            return
        fraction = min(1.0, done / total)
        if self.tty:
            if now - self.last < 0.1 and done < total:
                return
            filled = round(self.width * fraction)
            bar = "#" * filled + "-" * (self.width - filled)
            self.stream.write(f"\r[{bar}] {100 * fraction:5.1f}%  {elapsed:6.1f} s")
        else:
            tenth = int(10 * fraction)
            if tenth == self.tenth:
                return
            self.tenth = tenth
            self.stream.write(f"progress: {100 * fraction:5.1f}% after {elapsed:.1f} s\n")
        self.stream.flush()
        self.last = now
        self.shown = True

    def close(self) -> None:
        """End the bar's line (if anything was drawn)."""
        if self.shown and self.tty:
            self.stream.write("\n")
            self.stream.flush()


def _user_code(args: argparse.Namespace, scene):
    """The opt-in of --allow-user-code: DIR, or the scene file's folder (ga_rotors.trust)."""
    import contextlib

    from ..errors import InputError
    from ..trust import allow_user_code

    if args.allow_user_code is None:
        return contextlib.nullcontext()
    folder = args.allow_user_code or scene.base_dir
    if folder is None:
        raise InputError("--allow-user-code: a bundled scene has no folder; name one: DIR")
    return allow_user_code(folder)


def budget_from_args(args: argparse.Namespace, default=None):
    """The budget from --max-steps / --max-memory / --max-disk, ``default``'s values
    (the scene budget's by default) where not given."""
    from ..scene.budget import DEFAULT, Budget

    default = DEFAULT if default is None else default
    steps = default.max_steps if args.max_steps is None else args.max_steps
    memory = default.max_memory_gib if args.max_memory is None else args.max_memory
    disk = default.max_disk_gib if args.max_disk is None else args.max_disk
    if steps != steps or memory != memory or disk != disk:  # NaN
        from ..errors import InputError

        raise InputError("--max-steps, --max-memory, --max-disk: expected numbers")
    return Budget(max_steps=steps, max_memory_gib=memory, max_disk_gib=disk)


#: Runs of more steps (all paths) print their estimate before they start.
SHOW_ESTIMATE_STEPS = 10**6


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..errors import GimbalLockWarning, IntegrationStoppedWarning, StepLimitWarning
    from ..files import checked_path
    from ..scene import load_scene, stream_scene
    from ..scene.budget import COMPILE_NOTICE_SECONDS, check
    from ..scene.formats import require_formats
    from ..warmup import scene_tasks, warm

    start = time.perf_counter()
    if args.out is not None:
        checked_path(args.out, "--out")  # an empty name, before anything is compiled
    scene = load_scene(args.scene)
    if args.format is not None:
        scene = scene.replace({"output.figure_format": args.format})
    budget = budget_from_args(args)
    estimate = check(scene, budget, streamed=True)
    if estimate.steps > SHOW_ESTIMATE_STEPS or estimate.compile_seconds >= COMPILE_NOTICE_SECONDS:
        print(f"{scene.name}: {estimate} (streamed)", file=sys.stderr)
    require_formats(scene)  # before the warm-up and the run: one line, nothing compiled
    if not any(e["type"] == "user" for e in scene.data["effects"]):
        # A scene's first run compiles, and says so where the progress bar shows; user
        # code is left to the run itself, which checks the opt-in and reports on one line.
        show = sys.stderr.isatty() if args.progress is None else args.progress
        warm(scene_tasks(scene), show=show)
    out = Path(args.out) if args.out is not None else Path(DEFAULT_OUT) / scene.name
    chunk = {}
    if args.chunk_steps is not None:
        if args.chunk_steps < 1:
            from ..errors import InputError

            raise InputError(f"--chunk-steps: expected a positive integer, got {args.chunk_steps}")
        chunk = {"chunk_steps": args.chunk_steps}
    bar = ProgressBar(sys.stderr, args.progress)
    own = (StepLimitWarning, GimbalLockWarning, IntegrationStoppedWarning)
    with warnings.catch_warnings(record=True) as caught, _user_code(args, scene):
        for category in own:
            warnings.simplefilter("always", category)
        try:
            written, rep = stream_scene(scene, out, progress=bar, budget=budget, **chunk)
        finally:
            bar.close()
    _warn(caught, own)  # after a run that failed, its one-line error says it all
    incomplete = "incomplete" in rep.values
    if scene.data["output"]["summary"]:
        print(rep)
    elif incomplete:
        print(rep.lines[0])
    took = time.perf_counter() - start
    if written:
        print(f"\nwrote {', '.join(p.name for p in written)} to {out}/ ({took:.1f} s)")
    else:
        print(f"\nno files declared (output.data, output.plots); done in {took:.1f} s")
    if incomplete:
        print("ga-rotors: error: the run is incomplete (see the first line)", file=sys.stderr)
        return 3
    saved = any(p.suffix == ".npz" for p in written)
    print(f'see it move: ga-rotors view {out if saved else args.scene}')
    return 0


def _warn(caught, own) -> None:
    """The run's warnings: the package's own about the scene, one line each (no source
    excerpt, no control character); any other as Python shows it."""
    from ..errors import echoed

    for w in caught:
        if issubclass(w.category, own):
            print(f"ga-rotors: warning: {echoed(w.message)}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
