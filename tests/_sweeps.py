"""Sweeps interrupted as a user interrupts them: Ctrl-C while chunks are being handed over."""

from __future__ import annotations


def run_until_interrupted(source, out, after: int = 1, **run) -> None:
    """Run the sweep ``source`` into ``out`` (``run``: run_sweep's other arguments) and
    press Ctrl-C once ``after`` chunks count as done; check that run_sweep raised it."""
    import pytest

    from ga_rotors.sweep import run_sweep

    def interrupt(done, total):
        if done == after:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(source, out, progress=interrupt, **run)
