"""``clutchfem validate``: reproduce the source papers' numbers."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Optional

import typer

from ..errors import ClutchfemError
from .common import console, fail


def validate(
    json_: bool = typer.Option(False, "--json", help="print a JSON list of records"),
    out: Path = typer.Option(Path("out/validation"), "--out", help="folder for figures"),
    docs: Optional[Path] = typer.Option(None, "--docs", help="write the Markdown report here (e.g. docs/validation.md)"),
):
    """Reproduce the source papers' numbers (spring clutch, chain impact, shaft whirl, thesis)."""
    from ..validation import runner

    try:
        records = runner.run_all()
        if docs is not None:
            runner.write_report(out, docs)
        if json_:
            print(json.dumps([r.to_json() for r in records]))
        else:
            console.print(runner.rich_table(records))
    except ClutchfemError as exc:
        fail(exc)
