"""Reading requests and writing answers: bodies read up to a limit, declared content types, JSON errors.

Every failure becomes ``{"error": {"type", "message"}}`` with a 4xx status (:func:`fail`); a
request addressed to a host that is not this machine's name is refused before any endpoint
runs (:class:`LocalHostOnly`).  Bodies a cross-site page could send without asking (text/plain,
forms) are refused before they are read: JSON endpoints take ``application/json``, file
uploads :data:`UPLOAD_TYPE`.
"""

from __future__ import annotations

import json
from typing import Any

from starlette.requests import Request
from starlette.responses import JSONResponse

from ..errors import LkspaceError, TooLargeError, UsageError
from .scaffolds import MAX_UPLOAD, UPLOAD_TYPE, NotAFile

MAX_JSON = 2_000_000
"""Largest JSON request body, in bytes."""


class BadRequest(UsageError):
    """A request the endpoints cannot read (not JSON, too large, fields missing)."""

    status = 400


class NotJson(BadRequest):
    """A POST without ``Content-Type: application/json`` (a cross-site form cannot send one without asking)."""

    status = 415


LOCAL_NAMES = ("127.0.0.1", "localhost", "::1")


class LocalHostOnly:
    """ASGI middleware: answer only requests addressed to this machine by name (DNS rebinding defence)."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        """Refuse (403, JSON) an HTTP request whose Host header is not a local name."""
        if scope["type"] == "http":
            host = dict(scope.get("headers") or []).get(b"host", b"").decode("latin-1")
            name = host[1:].split("]")[0] if host.startswith("[") else host.split(":")[0]
            if name not in LOCAL_NAMES:
                error = {
                    "error": {
                        "type": "HTTPError",
                        "message": f"host {name[:60]!r} refused: the studio answers 127.0.0.1",
                    }
                }
                await JSONResponse(error, status_code=403)(scope, receive, send)
                return
        await self.app(scope, receive, send)


def fail(exc: Exception) -> JSONResponse:
    """Return the JSON error answer to ``exc``."""
    if isinstance(exc, LkspaceError):
        status = getattr(exc, "status", 413 if isinstance(exc, TooLargeError) else 400 if exc.exit_code == 2 else 422)
        kind = type(exc).__name__
        message = " ".join(str(exc).split())
    else:
        status, kind = 500, "InternalError"
        message = f"internal error ({type(exc).__name__}: {exc})"
    return JSONResponse({"error": {"type": kind, "message": message}}, status_code=status)


async def body_of(request: Request, limit: int) -> bytes:
    """Return the request body, refused past ``limit`` bytes (before reading it all)."""
    declared = request.headers.get("content-length")
    if declared is not None and declared.isdigit() and int(declared) > limit:
        raise TooLargeError(f"request of {int(declared):,} bytes > {limit:,}")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise TooLargeError(f"request larger than {limit:,} bytes")
        chunks.append(chunk)
    return b"".join(chunks)


def content_type(request: Request) -> str:
    """Return the media type the request declares (lower case, no parameters)."""
    return request.headers.get("content-type", "").split(";")[0].strip().lower()


async def json_of(request: Request) -> dict[str, Any]:
    """Return the JSON object of the request body (``Content-Type: application/json`` required)."""
    if content_type(request) != "application/json":
        raise NotJson("send the request body as application/json")
    raw = await body_of(request, MAX_JSON)
    try:
        data = json.loads(raw or b"{}", parse_constant=lambda c: None)
    except (ValueError, RecursionError):
        raise BadRequest("request body: not valid JSON") from None
    if not isinstance(data, dict):
        raise BadRequest("request body: expected a JSON object")
    return data


async def file_of(request: Request) -> tuple[str, bytes]:
    """Return ``(name, bytes)`` of an uploaded file: raw body as :data:`UPLOAD_TYPE`, name in ``X-Filename``."""
    if content_type(request) != UPLOAD_TYPE:  # refused before the body is read
        raise NotAFile(f"send the file as {UPLOAD_TYPE} (the studio page does)")
    return request.headers.get("x-filename", ""), await body_of(request, MAX_UPLOAD)
