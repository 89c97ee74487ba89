"""Command line: a thin layer over the Python API (parse, call, print).

One module per subcommand; :mod:`.common` holds the shared plumbing.
"""

from __future__ import annotations

import typer

from .analyze_cmd import analyze
from .demo_cmd import demo
from .geometry_cmd import geometry
from .slip_heat_cmd import slip_heat
from .solve_cmd import solve
from .study_cmd import guidelines, study
from .targets_cmd import compensate, optimize, report, tolerance
from .validate_cmd import validate

app = typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode=None,
                  help="clutchfem: design one-piece compliant centrifugal clutches (FEM + plus/minus shoe model).")
for _cmd in (geometry, solve, analyze, validate, demo, study, guidelines, optimize, tolerance, compensate, report):
    app.command()(_cmd)
app.command("slip-heat")(slip_heat)


def main() -> None:
    """Entry point: progress notes (clutchfem's INFO log) on stderr; Ctrl-C stops with exit
    code 130 and one line, not a traceback (gmsh, while meshing, exits with 130 itself)."""
    import logging
    import sys

    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(message)s"))
    log = logging.getLogger("clutchfem")
    log.addHandler(handler)
    log.setLevel(logging.INFO)
    import signal

    def interrupted(signum, frame):  # one line, exit 130, finally-blocks still run
        print("\ninterrupted (Ctrl-C): unfinished work is not written", file=sys.stderr)
        raise SystemExit(130)

    signal.signal(signal.SIGINT, interrupted)
    from ..core import tune_malloc

    tune_malloc()  # this process is clutchfem's: freed arrays stay for the next design
    app()


__all__ = ["app", "main"]
