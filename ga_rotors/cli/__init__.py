"""The ``ga-rotors`` command: one module per sub-command in this package.

Each sub-command lives in its own module, named in :data:`COMMANDS`, which exposes
``add_arguments(parser)`` and ``run(args) -> int``. A new command is a module here plus
one line in :data:`COMMANDS`. Command modules import only the standard library (and
light parts of ga_rotors) at top level, so ``ga-rotors --help`` and light commands start
fast; heavy imports happen inside ``run``.

``ga-rotors --version`` prints the installed distribution's version (from its metadata,
set once in pyproject.toml). A bare ``ga-rotors`` prints the usage and the command list
on stdout and exits 0.

Errors a user can cause (:class:`ga_rotors.errors.GaRotorsError`) are printed as one line
on stderr with exit code 2, never as a traceback. Ctrl-C at any moment after ``main``
starts, importing a command's modules included, ends with one line and exit 130, and a
command that writes leaves its previous output. An interrupt that lands where Python cannot
raise it (a callback such as llvmlite's object cache while numba compiles, a ``__del__``)
is dropped there and delivered again as soon as the callback has returned, so the command
stops rather than finishing; where a library turns it into another error, the handler has
recorded it, and a command that goes on to finish still exits 130.
"""

from __future__ import annotations

import _thread
import argparse
import importlib
import signal
import sys
import threading
import time

from ..errors import GaRotorsError

__all__ = ["COMMANDS", "build_parser", "main", "version"]

#: sub-command name -> module implementing it (one line per command).
COMMANDS: dict[str, str] = {
    "paper": "ga_rotors.cli.paper",
    "demo": "ga_rotors.cli.demo",
    "verify": "ga_rotors.cli.verify",
    "prove": "ga_rotors.cli.prove",
    "bench": "ga_rotors.cli.bench",
    "run": "ga_rotors.cli.run",
    "scenes": "ga_rotors.cli.scenes",
    "show": "ga_rotors.cli.show",
    "cache": "ga_rotors.cli.cache",
    "sweep": "ga_rotors.cli.sweep",
    "view": "ga_rotors.cli.view",
}


def version() -> str:
    """The version of the installed ``ga-rotors`` distribution (set once, in pyproject.toml).

    Read from the package metadata; a source tree that was never installed has none and
    reports ``unknown (not installed)``.

    Examples
    --------
    >>> from importlib.metadata import version as installed
    >>> version() == installed("ga-rotors")
    True
    """
    from .. import __version__

    return __version__


class _Version(argparse.Action):
    """``--version``, read from the metadata only when asked: importlib.metadata costs more
    to import (0.03-0.3 s) than everything else ``ga-rotors --help`` loads."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog} {version()}")
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    """The ``ga-rotors`` argument parser: one sub-parser per entry of :data:`COMMANDS`.

    Each parsed namespace carries the command's ``run`` as ``args._run``.

    Examples
    --------
    >>> args = build_parser().parse_args(["verify", "--details", "12", "N9"])
    >>> args.command, args.details, args._run.__module__
    ('verify', ['12', 'N9'], 'ga_rotors.cli.verify')
    """
    parser = argparse.ArgumentParser(
        prog="ga-rotors",
        description="Rotations in geometric algebra: rotors, quaternions, rigid bodies.",
    )
    parser.add_argument("--version", action=_Version, help="print the version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, modname in COMMANDS.items():
        module = importlib.import_module(modname)
        doc = (module.__doc__ or "").strip().splitlines()
        p = sub.add_parser(
            name,
            help=doc[0] if doc else None,
            description=(module.__doc__ or "").strip() or None,
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``ga-rotors`` console script.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``ga-rotors`` (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status: the command's, 2 for an error the user caused (printed as one
        line on stderr, no traceback), 130 when interrupted, 143 on SIGTERM (after
        clean-up: a command that writes leaves its previous output); 0 for a bare
        ``ga-rotors``, which prints the usage and the command list.

    Examples
    --------
    >>> main(["scenes"])
    damped_top ...
    0
    >>> import contextlib, io
    >>> err = io.StringIO()
    >>> with contextlib.redirect_stderr(err):
    ...     status = main(["show", "no_such_scene"])
    >>> status, err.getvalue().split(";")[0]
    (2, 'ga-rotors: error: no_such_scene: no such file, and no bundled scene of that name')
    """
    _INTERRUPTED.clear()
    # The handlers go in inside the try: an interrupt right after SIGINT's is installed
    # is then one line and 130 too.
    previous = _handler(signal.SIGTERM), _handler(signal.SIGINT), sys.unraisablehook
    try:
        sys.unraisablehook = _unraisable
        _on_sigterm(_terminated)
        _on_sigint(_interrupted)
        status = _main(argv)
    except GaRotorsError as exc:
        if _INTERRUPTED:
            return _interrupt_status()
        print(f"ga-rotors: error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file the command was pointed at, and the system refused it
        if _INTERRUPTED:
            return _interrupt_status()
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"ga-rotors: error: {_one_line(where + str(exc.strerror or exc))}",
              file=sys.stderr)  # fmt: skip
        return 2
    except KeyboardInterrupt:
        return _interrupt_status()
    except _Terminated:
        print("ga-rotors: terminated (SIGTERM); no output was changed", file=sys.stderr)
        return 143
    except Exception:
        if _INTERRUPTED:  # Ctrl-C inside a library that raised something else for it
            return _interrupt_status()
        raise
    finally:
        _on_sigterm(previous[0])
        _on_sigint(previous[1])
        sys.unraisablehook = previous[2]
    if _INTERRUPTED:  # the interrupt was swallowed, and the command went on to finish
        return _interrupt_status()
    return status


def _main(argv) -> int:
    parser = build_parser()  # imports every command's module: interruptible like the rest
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    return int(args._run(args) or 0)


def _one_line(text) -> str:
    """What an error message prints: one line, no control character, bounded."""
    from ..errors import MESSAGE_LIMIT, echoed

    return echoed(text, MESSAGE_LIMIT)


#: Set by the SIGINT handler: a Ctrl-C arrived during this ``main``.
_INTERRUPTED: list = []


def _interrupted(signum, frame):
    _INTERRUPTED.append(signum)
    raise KeyboardInterrupt


def _unraisable(info) -> None:
    """Python's report of an exception it had to drop (raised in a callback), except the
    interrupt, which the handler has recorded and the command reports in one line (a
    Ctrl-C inside numba's compiler callback printed a traceback before that line). The
    dropped interrupt is raised again at the next point Python can raise it: without that
    the command went on and wrote its whole output after Ctrl-C."""
    if isinstance(info.exc_value, KeyboardInterrupt) and _INTERRUPTED:
        if threading.current_thread() is threading.main_thread():
            _HOOK_DONE[0] = False
            _thread.start_new_thread(_interrupt_again, ())
            _HOOK_DONE[0] = True  # a plain store: the handler cannot run in here after it
        return
    sys.__unraisablehook__(info)


#: Set as the last step of :func:`_unraisable`, for :func:`_interrupt_again`.
_HOOK_DONE = [True]


def _interrupt_again() -> None:
    # Called in the main thread, the handler would raise inside the hook (dropped again):
    # from this thread, once the hook is done, it runs at the main thread's next step.
    while not _HOOK_DONE[0]:
        time.sleep(0.001)
    _thread.interrupt_main()


def _interrupt_status() -> int:
    print("ga-rotors: interrupted", file=sys.stderr)
    return 130


class _Terminated(BaseException):
    """SIGTERM as an exception, so that clean-up (staging folders, temporary files) runs:
    Python's default for SIGTERM ends the process at once, leaving them behind."""


def _terminated(signum, frame):
    raise _Terminated


def _on_sigterm(handler):
    """Install ``handler`` for SIGTERM (main thread only); return the previous one."""
    return _on_signal(signal.SIGTERM, handler)


def _on_sigint(handler):
    """Install ``handler`` for SIGINT (main thread only); return the previous one."""
    return _on_signal(signal.SIGINT, handler)


def _handler(signum):
    """The handler installed for ``signum`` now (None where none can be installed)."""
    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.getsignal(signum)


def _on_signal(signum, handler):
    if handler is None or threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signum, handler)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
