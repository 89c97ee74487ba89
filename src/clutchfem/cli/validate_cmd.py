"""``clutchfem validate``: reproduce the source papers' numbers."""

from __future__ import annotations

import time
import warnings
from pathlib import Path
from typing import Optional

import typer

from .. import ClutchfemError, InputError
from .common import check_out_dir, console, err, fail, working


def validate(
    json_: bool = typer.Option(False, "--json", help="print a JSON list of records"),
    out: Path = typer.Option(Path("out/validation"), "--out",
                             help="folder for figures and validation.json (with --docs)"),
    docs: Optional[Path] = typer.Option(None, "--docs", help="write the Markdown report here (e.g. docs/validation.md)"),
):
    """Reproduce the source papers' numbers (spring clutch, chain impact, overhung-disc shaft,
    thesis): every module of clutchfem.validation that defines records()."""
    from .. import dumps
    from .. import validate as run_validation

    t0 = time.perf_counter()
    try:
        if docs is not None:  # refused before any work: a folder, a file in a file, no permission
            check_out_dir(out)
            if docs.is_dir():
                raise InputError(f"--docs {docs}: is a folder; give the Markdown file to write (e.g. "
                                 "docs/validation.md)")
            check_out_dir(docs.parent, "--docs")
        with working("validate") as stage:
            stage("every validation case (analytic, thesis, CalculiX where installed)")
            run = run_validation(out=out if docs is not None else None, docs=docs)  # every module runs once
        if json_:
            print(dumps([r.to_json() for r in run.records]))
        else:
            console.print(run.table())
        for w in run.warnings:
            warnings.warn(w, UserWarning, stacklevel=1)
            err.print(f"[yellow]warning:[/] {w}")
        if not json_:
            where = f"; report {docs}, figures in {out}" if docs is not None else ""
            console.print(f"{len(run.records)} records in {time.perf_counter() - t0:.1f} s{where}")
    except ClutchfemError as exc:
        fail(exc)
