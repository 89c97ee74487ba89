"""The command line run in the test's process, the way ``python -m clutchfem.cli`` runs it.

A ``clutchfem`` process costs ~2-3 s of interpreter start and imports before it parses its
first option.  Tests of what the command *says* (a refusal's exit code and message, no
traceback, the files it writes) run :func:`clutchfem.cli.main` here instead: the same entry
point (its usage-error lines for a standard error that is not a terminal, its log handler on
standard error), ``sys.argv`` as the process would have it, standard output and error
captured in text buffers (not terminals, as a pipe is not), and an exception that escapes
written to standard error as Python writes it, with exit code 1.

Tests about the process itself stay real processes: exit codes on signals, Ctrl-C, kill -9,
what a start imports, and a JSON standard output that must hold nothing else (a library that
writes to file descriptor 1, as gmsh does, is only seen there).
"""

from __future__ import annotations

import contextlib
import io
import logging
import os
import signal
import subprocess
import sys
import traceback
from unittest import mock


def cli_in_process(*args: str, env: dict | None = None, ok: bool = False) -> subprocess.CompletedProcess:
    """Run ``clutchfem ARGS`` in this process; the result as :func:`subprocess.run` gives
    it (``returncode``, ``stdout``, ``stderr``).  ``env``: variables set for the run;
    ``ok``: assert that it exited with 0 (its standard error in the message)."""
    from clutchfem.cli import main

    out, err = io.StringIO(), io.StringIO()
    log = logging.getLogger("clutchfem")
    handlers, level = list(log.handlers), log.level
    sigint, argv = signal.getsignal(signal.SIGINT), sys.argv
    code = 0
    # the process-wide allocator settings main() makes for its own process are not this
    # test worker's business.  main() takes it as ``clutchfem.tune_malloc``, a lazy public name
    # the package keeps once resolved: patched there too (patching clutchfem.core alone let the
    # first in-process run leave the stand-in in clutchfem's namespace for the rest of the
    # worker's tests, e.g. test_docs_site's check of every public name's docstring)
    import clutchfem

    clutchfem.tune_malloc  # noqa: B018 -- resolved (and kept) before the patch, so that it restores the real one
    with mock.patch.dict(os.environ, env or {}), mock.patch("clutchfem.tune_malloc", lambda: False), \
            mock.patch("clutchfem.core.tune_malloc", lambda: False), \
            contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        sys.argv = ["clutchfem", *map(str, args)]
        try:
            code = exit_code_of(main)
        finally:
            sys.argv = argv
            signal.signal(signal.SIGINT, sigint)
            for h in log.handlers[:]:
                if h not in handlers:
                    log.removeHandler(h)
            log.setLevel(level)
    r = subprocess.CompletedProcess(["clutchfem", *map(str, args)], code, out.getvalue(), err.getvalue())
    if ok:
        assert r.returncode == 0, r.stderr[-3000:] + r.stdout[-3000:]
    return r


def exit_code_of(run) -> int:
    """``run()`` as the end of a process: its exit code (``sys.exit``'s; 0 when it returns), a
    ``SystemExit("message")`` printed to standard error with 1, an exception that escapes
    written to standard error as Python writes it, with 1."""
    try:
        run()
    except SystemExit as exc:
        if exc.code is None or isinstance(exc.code, int):
            return exc.code or 0
        print(exc.code, file=sys.stderr)  # SystemExit("message"): Python prints it and exits with 1
        return 1
    except Exception:  # what escapes a process: its traceback on standard error, exit code 1
        traceback.print_exc(file=sys.stderr)
        return 1
    return 0
