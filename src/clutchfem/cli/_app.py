"""The typer app of :mod:`clutchfem.cli`: its commands, the root options and :func:`main`
(loaded by :func:`clutchfem.cli.main` after its start-up line)."""

from __future__ import annotations

import logging
import signal
import sys
from typing import Annotated, Optional

import typer
from typer import rich_utils
from typer._click.exceptions import ClickException  # typer vendors click (its BadParameter's base)

from .. import __version__
from . import clear_early
from .analyze_cmd import analyze
from .app_cmd import app as app_command
from .cache_cmd import cache
from .calibrate_cmd import calibrate
from .compensate_cmd import compensate
from .demo_cmd import demo
from .export_cmd import export
from .geometry_cmd import geometry
from .life_cmd import life
from .optimize_cmd import optimize
from .reduce_cmd import reduce
from .report_cmd import report
from .slip_heat_cmd import slip_heat
from .solve_cmd import solve
from .study_cmd import guidelines, study
from .tolerance_cmd import tolerance
from .validate_cmd import validate

app = typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode="rich",
                  help="clutchfem: design one-piece compliant centrifugal clutches (FEM + plus/minus shoe model).\n\n"
                       "A design is a CONCEPT with --set overrides (clutchfem geometry --list) or --mesh FILE; "
                       "every quantity takes a unit suffix (2.4mm, 80deg, 2700rpm, 200GPa).")

#: (command, name, panel, example)
_COMMANDS = [
    (geometry, "geometry", "Design", "clutchfem geometry concept4 --set flexure_thickness=2mm --out out/c4"),
    (analyze, "analyze", "Design", "clutchfem analyze concept4 --set flexure_thickness=2mm --out out/c4"),
    (solve, "solve", "Design", "clutchfem solve concept1 --rpm 0:14000:250 --vtk --out out/c1"),
    (report, "report", "Design", "clutchfem report concept4 --out out/c4-report"),
    (slip_heat, "slip-heat", "Design", "clutchfem slip-heat concept2 --cycles 3 --pause 20s --out out/heat"),
    (life, "life", "Design", "clutchfem life concept4 --starts 100000 --duty duty.toml --out out/life"),
    (optimize, "optimize", "Design to targets", "clutchfem optimize concept4 --out out/opt"),
    (tolerance, "tolerance", "Design to targets",
     "clutchfem tolerance concept4 --tol flexure_thickness=+-0.05mm --tol clearance=+-0.02mm --n 100"),
    (compensate, "compensate", "Design to targets", "clutchfem compensate concept4 --rpm 8000 --out out/comp"),
    (calibrate, "calibrate", "Design to targets",
     "clutchfem calibrate concept1 --measured engagement=4191rpm+-25rpm --measured slip=7512rpm+-40rpm "
     "--uncertain mu=0.1:0.35 --uncertain flexure_thickness=+-0.1mm"),
    (export, "export", "Design to targets",
     "clutchfem export concept4 --process wire-edm --dxf part.dxf --step part.step --drawing part.pdf"),
    (reduce, "reduce", "Studies", "clutchfem reduce concept4 --workers 2   (then: clutchfem analyze concept4 --fidelity live)"),
    (study, "study", "Studies", "clutchfem study --example > study.toml && clutchfem study study.toml"),
    (guidelines, "guidelines", "Studies", "clutchfem guidelines concept4 --params flexure_thickness,shoe_arc"),
    (validate, "validate", "Checks", "clutchfem validate --docs docs/validation.md --out docs/img/validation"),
    (demo, "demo", "Checks", "clutchfem demo --out out/demo"),
    (app_command, "app", "Design", "clutchfem app  (then open http://127.0.0.1:8765)"),
    (cache, "cache", "Checks", "clutchfem cache --clear"),
]
for _fn, _name, _panel, _example in _COMMANDS:
    app.command(_name, rich_help_panel=_panel, epilog=f"Example: {_example}")(_fn)


def _version(value: bool) -> None:
    if value:
        print(f"clutchfem {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: Annotated[Optional[bool], typer.Option(
        "--version", callback=_version, is_eager=True, help="print the version and exit")] = None) -> None:
    """clutchfem: design one-piece compliant centrifugal clutches (FEM + plus/minus shoe model)."""


def main() -> None:
    """Entry point: progress notes (clutchfem's INFO log) on stderr; Ctrl-C stops with exit
    code 130 and one line, not a traceback (gmsh, while meshing, exits with 130 itself)."""
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(message)s"))
    handler.addFilter(lambda record: clear_early() or True)  # a note replaces the start-up line
    log = logging.getLogger("clutchfem")
    log.addHandler(handler)
    log.setLevel(logging.INFO)

    stopped = []

    def interrupted(signum, frame):  # one line, exit 130, finally-blocks still run
        stopped.append(signum)
        print("\ninterrupted (Ctrl-C): unfinished work is not written", file=sys.stderr)
        raise SystemExit(130)

    signal.signal(signal.SIGINT, interrupted)
    from .. import tune_malloc

    tune_malloc()  # this process is clutchfem's: freed arrays stay for the next design
    try:
        _run()
    except Exception:
        # Ctrl-C while a library imports (scipy wraps what its import raised in an
        # ImportError): the interrupt it was, not a traceback
        if stopped:
            raise SystemExit(130) from None
        raise


def _set_hint(exc: ClickException) -> None:
    """``--set a=1 b=2`` (several parameters after one ``--set``) is refused by the parser as
    "unexpected extra argument(s)": say how to give them."""
    msg = getattr(exc, "message", "")
    if "unexpected extra argument" in msg and "=" in msg:
        exc.message = (f"{msg}: each concept parameter takes its own --set "
                       "(--set flexure_thickness=2mm --set clearance=0.3mm)")


def _run() -> None:
    """The app, with usage errors as one line when standard error is not a terminal."""
    if sys.stderr.isatty():
        try:
            code = app(standalone_mode=False)
        except ClickException as exc:
            _set_hint(exc)
            rich_utils.rich_format_error(exc)
            raise SystemExit(exc.exit_code) from None
        except typer.Abort:
            print("aborted", file=sys.stderr)
            raise SystemExit(1) from None
        raise SystemExit(code if isinstance(code, int) else 0)
    # standard error is a file or a pipe: a usage error is one `error:` line (typer draws a
    # box wrapped at 80 columns, and a script reading the first line got "Usage: ...")
    try:
        code = app(standalone_mode=False)
    except ClickException as exc:
        _set_hint(exc)
        ctx = getattr(exc, "ctx", None)
        where = f" (see {ctx.command_path} --help)" if ctx is not None else ""
        print(f"error: {exc.format_message()}{where}", file=sys.stderr)
        raise SystemExit(exc.exit_code) from None
    except typer.Abort:
        print("aborted", file=sys.stderr)
        raise SystemExit(1) from None
    raise SystemExit(code if isinstance(code, int) else 0)


__all__ = ["app", "main"]
