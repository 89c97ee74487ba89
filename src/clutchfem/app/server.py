"""The app's server: one NiceGUI (FastAPI/uvicorn) process on 127.0.0.1 unless a host is
given, one page per browser tab, no file served but what a tab offers to download from its
own folder under the app's output folder."""

from __future__ import annotations

import tempfile
from pathlib import Path

from nicegui import ui

from ..core import InputError
from .page import build_page

__all__ = ["serve_app"]


def serve_app(host: str = "127.0.0.1", port: int = 8765, *, open_browser: bool = True, out: str | Path | None = None,
          title: str = "clutchfem") -> None:
    """Run the live design app until interrupted.

    Parameters
    ----------
    host : str
        The address to listen on (default 127.0.0.1: this machine only).
    port : int
        The TCP port.
    open_browser : bool
        Open a browser tab on the page.
    out : path, optional
        The folder of the tabs' files (reports, downloads); default: a new temporary folder.

    Returns
    -------
    None
        It returns when the server stops.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.serve_app  # doctest: +ELLIPSIS
    <function serve_app at ...>
    """
    if not (isinstance(port, int) and 1 <= port <= 65535):
        raise InputError(f"port {port!r}: a TCP port in 1..65535")
    root = Path(out) if out is not None else Path(tempfile.mkdtemp(prefix="clutchfem-app-"))
    root.mkdir(parents=True, exist_ok=True)
    ui.run(lambda: build_page(root), host=host, port=port, title=title, show=open_browser, reload=False,
           show_welcome_message=False, uvicorn_logging_level="warning", favicon="\u2699")
