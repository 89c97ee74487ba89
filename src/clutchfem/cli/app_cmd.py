"""``clutchfem app``: the live design app in the browser."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .. import ClutchfemError
from .common import err, fail


def app(
    port: int = typer.Option(8765, "--port", help="TCP port"),
    host: str = typer.Option("127.0.0.1", "--host", help="address to listen on (default: this machine only; "
                             "0.0.0.0: every network the machine is on)"),
    no_browser: bool = typer.Option(False, "--no-browser", help="do not open a browser tab"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for the tabs' files (reports, downloads; "
                                       "default: a new temporary folder)"),
    max_tabs: int = typer.Option(8, "--max-tabs", help="the most tabs analysing at once (each holds up to ~150 MB "
                                 "during an analysis; a further tab gets a refusal page)"),
):
    """Live design in the browser: every parameter a slider, the answers with their bands,
    the torque-speed chart and the part at a speed, after each change; compare, studies and
    downloads."""
    from .. import serve_app

    try:
        if host not in ("127.0.0.1", "localhost", "::1"):
            err.print(f"[yellow]listening on {host}:{port}: anyone who can reach this address can run analyses "
                      "and download their files[/]")
        serve_app(host, port, open_browser=not no_browser, out=out, max_tabs=max_tabs,
                  started=lambda: err.print(f"clutchfem app on http://{host if host != '0.0.0.0' else '127.0.0.1'}:"
                                            f"{port} (Ctrl-C stops it)"))
    except ClutchfemError as exc:
        fail(exc)
