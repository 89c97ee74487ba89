"""The app's limits, enforced by the server (not by the browser): the number of live tabs,
the size of an uploaded file, the answer to a path that is no page.

A browser is not needed to reach the server: a page request (``GET /``) builds the page's
widgets only; the tab's session, its folder and its analysis start when the page's websocket
connects (a real page in a browser); at most :data:`MAX_PENDING` pages wait for it, each at
most :data:`PENDING_S` (a further request gets a 503).  At most :data:`MAX_SESSIONS` tabs
are live at once (a further one gets a refusal page, no session); a closed tab's tasks are cancelled, its session and folder
dropped.  An upload larger than its limit is refused with HTTP 413 before its body is read
(:class:`UploadLimit`, on the request's declared length and on the bytes as they arrive).
"""

from __future__ import annotations

import re

__all__ = ["MAX_SESSIONS", "MAX_PENDING", "PENDING_S", "MAX_CSV_BYTES", "MAX_PART_BYTES", "UploadLimit", "upload_limits"]

#: the most tabs analysing at once (each holds one design's meshes and answers: ~150 MB at
#: the peak of an analysis on the best path): the server stays under BASE + MAX x 150 MB
MAX_SESSIONS = 8
#: the most pages built and waiting for their websocket (each ~0.5 MB of widgets, no session)
MAX_PENDING = 32
#: a page not connected after this long is dropped [s]
PENDING_S = 15.0
#: largest uploaded engine CSV [bytes]
MAX_CSV_BYTES = 1 << 20
#: largest uploaded part (.msh / STEP) [bytes]
MAX_PART_BYTES = 20 << 20
#: the multipart envelope around a file (boundaries, headers) [bytes]
ENVELOPE_BYTES = 16 << 10

#: the upload routes of the live pages and their limits [bytes] (registered by the page)
upload_limits: dict[str, int] = {}
_UPLOAD = re.compile(r"^/_nicegui/client/[^/]+/upload/[^/]+$")


class UploadLimit:
    """ASGI middleware: a POST to an upload route larger than the route's limit (or to an
    upload route no live page registered) is answered 413 (404) before its body is read; a
    body without a declared length is counted as it arrives and cut off at the limit.

    Parameters
    ----------
    app : ASGI application
        The application it wraps.

    Examples
    --------
    >>> from clutchfem.app.limits import UploadLimit
    >>> UploadLimit(None).app is None
    True
    """

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope.get("type") != "http" or scope.get("method") != "POST" or not _UPLOAD.match(scope.get("path", "")):
            return await self.app(scope, receive, send)
        path = scope["path"]
        limit = upload_limits.get(path)
        if limit is None:
            return await _answer(send, 404, "no such upload: open the app's page (/) in a browser")
        cap = limit + ENVELOPE_BYTES
        headers = dict(scope.get("headers") or [])
        declared = headers.get(b"content-length")
        if declared is not None:
            try:
                n = int(declared)
            except ValueError:
                return await _answer(send, 400, "content-length is not a number")
            if n > cap:
                return await _answer(send, 413, _too_large(limit))
        seen, refused, answered = 0, False, False

        async def counted():  # the bytes as they arrive: past the cap, the client "went"
            nonlocal seen, refused
            if refused:
                return {"type": "http.disconnect"}
            msg = await receive()
            if msg.get("type") == "http.request":
                seen += len(msg.get("body", b""))
                if seen > cap:
                    refused = True
                    return {"type": "http.disconnect"}
            return msg

        async def guarded(msg):  # once refused, the route's own answer (an error) becomes the 413
            nonlocal answered
            if not refused:
                return await send(msg)
            if not answered:
                answered = True
                await _answer(send, 413, _too_large(limit))

        try:
            await self.app(scope, counted, guarded)
        except Exception:
            if not refused:
                raise
        if refused and not answered:
            await _answer(send, 413, _too_large(limit))


def _too_large(limit: int) -> str:
    return f"refused: the file is larger than the limit of {limit / 1024:.0f} kB for this upload"


async def _answer(send, status: int, text: str) -> None:
    body = text.encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"text/plain; charset=utf-8"),
                            (b"content-length", str(len(body)).encode()), (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})
