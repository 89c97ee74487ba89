"""Command line: a thin face over the Python API (parse, call, print).

One grammar for every command that takes a design: ``clutchfem COMMAND CONCEPT [--set
name=value ...]`` or ``clutchfem COMMAND --mesh FILE``; every quantity option takes a unit
suffix (``--drum-radius 34.4mm``); every file written is listed (``wrote PATH`` on stderr)
and carries the design's label.  One module per command, :mod:`.options` the shared
options, :mod:`.common` the plumbing, :mod:`._app` the typer app.

This package's own module is light (the typer app, its commands and their imports load in
:func:`main`): on a terminal, the first line a command shows (``clutchfem analyze ...``)
is written before they load, within a fraction of a second of the command (issue 37); the
command's spinner or its first output replaces it.
"""

from __future__ import annotations

import atexit
import sys

__all__ = ["clear_early", "early_line", "main"]  # and ``app`` (the typer app, loaded on use)

#: whether the start-up line is on the terminal (not yet replaced)
_EARLY = [False]


def early_line(argv: list[str]) -> bool:
    """Write ``clutchfem COMMAND ...`` on a terminal's standard error at once (no newline: the
    spinner or the command's first output replaces it, :func:`clear_early`); nothing for a
    pipe or a file, ``--help``, ``--version`` or ``--json``.  Returns whether it was written."""
    try:
        tty = sys.stderr.isatty()
    except (AttributeError, ValueError):
        tty = False
    if not tty or len(argv) < 2 or argv[1].startswith("-") or any(
            a in ("--help", "-h", "--version", "--json") for a in argv[2:]):
        return False
    sys.stderr.write(f"clutchfem {argv[1]} ...\r")
    sys.stderr.flush()
    _EARLY[0] = True
    atexit.register(clear_early)
    return True


def clear_early() -> None:
    """Erase the start-up line of :func:`early_line` if it is still there (before a spinner or
    any output)."""
    if _EARLY[0]:
        _EARLY[0] = False
        try:
            sys.stderr.write("\r\x1b[2K")
            sys.stderr.flush()
        except (OSError, ValueError):
            pass


def main() -> None:
    """Entry point (``clutchfem``): the start-up line on a terminal, then the typer app
    (:func:`clutchfem.cli._app.main`)."""
    early_line(sys.argv)
    from ._app import main as run

    run()


def __getattr__(name: str):
    if name == "app":
        from ._app import app

        return app
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
