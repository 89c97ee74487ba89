"""The app's server: one NiceGUI (FastAPI/uvicorn) process on 127.0.0.1 unless a host is
given, one page per browser tab, no file served but what a tab offers to download from its
own folder under the app's output folder."""

from __future__ import annotations

import errno
import socket
import tempfile
from pathlib import Path

from nicegui import Client, app, ui
from starlette.requests import Request
from starlette.responses import PlainTextResponse, Response

from ..core import InputError
from . import limits
from .limits import UploadLimit
from .page import build_page

__all__ = ["serve_app"]


def serve_app(host: str = "127.0.0.1", port: int = 8765, *, open_browser: bool = True, out: str | Path | None = None,
              title: str = "clutchfem", started=None, max_tabs: int | None = None) -> None:
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
    title : str
        The page's title.
    max_tabs : int, optional
        The most tabs analysing at once (default :data:`~clutchfem.app.limits.MAX_SESSIONS`);
        a further tab gets a refusal page and no session.
    started : callable, optional
        Called once the port and the folder are checked, just before the server starts (the
        command line prints the address there: never for a port it cannot have).

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
    if isinstance(port, bool) or not (isinstance(port, int) and 1 <= port <= 65535):
        raise InputError(f"port {port!r}: a TCP port in 1..65535")
    if max_tabs is not None:
        if isinstance(max_tabs, bool) or not (isinstance(max_tabs, int) and 1 <= max_tabs <= 64):
            raise InputError(f"max_tabs {max_tabs!r}: an integer in 1..64 (the most tabs analysing at once)")
        limits.MAX_SESSIONS = max_tabs
    check_port(host, port)
    root = Path(out) if out is not None else Path(tempfile.mkdtemp(prefix="clutchfem-app-"))
    if root.exists() and not root.is_dir():
        raise InputError(f"out {root}: is a file, not a folder (the folder of the tabs' reports and downloads)")
    try:
        root.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"out {root}: cannot make the folder ({exc.strerror or exc})") from None
    if started is not None:
        started()
    register(root)
    ui.run(host=host, port=port, title=title, show=open_browser, reload=False,
           show_welcome_message=False, uvicorn_logging_level="warning", favicon="\u2699")


def register(root: Path) -> None:
    """The app's one page at ``/``, a plain 404 (no page, no session) for any other path, and
    the upload limit enforced on the server (:mod:`.limits`)."""

    @ui.page("/")
    def index(client: Client):
        page = build_page(root, client)
        return page if isinstance(page, Response) else None

    app.add_exception_handler(404, not_found)
    app.add_middleware(UploadLimit)


async def not_found(request: Request, exc: Exception) -> PlainTextResponse:
    """Any path but the page and NiceGUI's own: 404, nothing built."""
    return PlainTextResponse(f"404: {request.url.path} is no page of this app; the app is at /", status_code=404)


def check_port(host: str, port: int) -> None:
    """Refuse, before the server starts, a port another program listens on (or the address
    cannot be bound at all), naming it and the way out."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        try:
            s.bind((host, port))
        except OSError as exc:
            what = "is in use (another app, or another program)" if exc.errno in (errno.EADDRINUSE,) else \
                f"cannot be listened on ({exc.strerror or exc})"
            raise InputError(f"{host}:{port} {what}: give another --port (e.g. --port {port + 1})") from None
