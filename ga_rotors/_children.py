"""Child processes that never outlive the command that started them.

ga_rotors starts children in two places: the drawing processes of ``ga-rotors paper``
(a standard :class:`~concurrent.futures.ProcessPoolExecutor`) and the time-limited peer
measurements of the accuracy study. Both come from :func:`context`: forked from a clean
server process (``forkserver``; ``spawn`` where there is none), never from the calling
process and its threads. Each child runs :func:`exit_with_parent` first: a standard pool's
worker waits on a queue whose write end it holds itself, so when the command is killed
(SIGKILL, no chance to shut the pool down) the worker would wait forever, holding the
command's pipes open; with it, the worker exits as soon as the command is gone.
"""

from __future__ import annotations

import multiprocessing
import os
import threading

__all__ = ["context", "exit_with_parent"]


def context():
    """The multiprocessing context children are started with (forkserver, else spawn).

    Examples
    --------
    >>> context().get_start_method() in ("forkserver", "spawn")
    True
    """
    methods = multiprocessing.get_all_start_methods()
    return multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")


def exit_with_parent() -> None:
    """In a child: end this process as soon as the process that started it has ended.

    multiprocessing hands every child a sentinel of its parent (for ``forkserver``, of
    the process that asked the server for it, not of the server), which becomes ready
    when the parent is gone; a daemon thread waits on it. In the parent itself it does
    nothing.

    Examples
    --------
    >>> exit_with_parent()  # in the main process: nothing to watch
    """
    parent = multiprocessing.parent_process()
    if parent is None:
        return

    def watch():
        parent.join()
        os._exit(1)

    threading.Thread(target=watch, name="ga_rotors-exit-with-parent", daemon=True).start()
