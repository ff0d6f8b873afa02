"""The studio's HTTP boundary: JSON bodies read up to a limit, declared content types, answers and errors written.

What crosses the boundary is typed on both sides: every request body is read by the one
``from_json`` of its record (:mod:`~lkspace.studio.requests`), every answer and job state is a
record with one ``to_json`` or a ``TypedDict`` view (:mod:`~lkspace.studio.answers`), and
:func:`dumps` writes either.

Every failure becomes ``{"error": {"type", "message"}}`` with a 4xx status (:func:`fail`); a
request addressed to a host that is not this machine's name is refused before any endpoint
runs (:class:`LocalHostOnly`).  Bodies a cross-site page could send without asking (text/plain,
forms) are refused before they are read: JSON endpoints take ``application/json``, file
uploads :data:`UPLOAD_TYPE`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Protocol, TypeAlias, runtime_checkable

from ..errors import LkspaceError, TooLargeError, UsageError
from ..io.json_values import JsonObject

if TYPE_CHECKING:
    from starlette.requests import Request
    from starlette.responses import JSONResponse
    from starlette.types import ASGIApp, Receive, Scope, Send

JsonAnswer: TypeAlias = dict[str, object]
"""A JSON object as an answer writes it (``to_json``, :func:`error_json`): the output side.

Its values are whatever :func:`dumps` writes (sequences, ``TypedDict`` views, nested
answers), so it is wider than :data:`~lkspace.io.json_values.JsonObject`, the input side
that :func:`json_of` returns and every request's ``from_json`` reads (values as
:func:`json.loads` returns them, still to be checked)."""

MAX_JSON = 2_000_000
"""Largest JSON request body, in bytes."""

MAX_UPLOAD = 8_000_000
"""Largest uploaded scaffold file, in bytes."""

UPLOAD_TYPE = "application/octet-stream"
"""The content type an upload must declare: not one a cross-site form can send without asking."""


class BadRequest(UsageError):
    """A request the endpoints cannot read (not JSON, too large, fields missing)."""

    status = 400


class NotJson(BadRequest):
    """A POST without ``Content-Type: application/json`` (a cross-site form cannot send one without asking)."""

    status = 415


class BadUpload(BadRequest):
    """An uploaded file whose bytes are not a scaffold or design file (not UTF-8, not JSON, no faces; 400)."""


class NotAFile(UsageError):
    """An upload not sent as :data:`UPLOAD_TYPE` (a cross-site form could send text/plain or multipart; 415)."""

    status = 415


@runtime_checkable
class Record(Protocol):
    """An answer with its JSON form."""

    def to_json(self) -> JsonAnswer:
        """Return the JSON form."""


Answer: TypeAlias = Record | Mapping[str, object]
"""What an endpoint answers: a record, or a view the page reads as it is."""


def dumps(answer: Answer) -> str:
    """JSON text of an answer (numpy scalars made plain)."""
    data = answer.to_json() if isinstance(answer, Record) else answer
    return json.dumps(data, default=lambda v: v.item() if hasattr(v, "item") else str(v))


# ---- HTTP: bodies, content types, errors

LOCAL_NAMES = ("127.0.0.1", "localhost", "::1")


def error_json(kind: str, message: str) -> JsonAnswer:
    """Return the JSON of an error answer."""
    return {"error": {"type": kind, "message": message}}


class LocalHostOnly:
    """ASGI middleware: answer only requests addressed to this machine by name (DNS rebinding defence)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        """Refuse (403, JSON) an HTTP request whose Host header is not a local name."""
        from starlette.responses import JSONResponse

        if scope["type"] == "http":
            host = dict(scope.get("headers") or []).get(b"host", b"").decode("latin-1")
            name = host[1:].split("]")[0] if host.startswith("[") else host.split(":")[0]
            if name not in LOCAL_NAMES:
                message = f"host {name[:60]!r} refused: the studio answers 127.0.0.1"
                await JSONResponse(error_json("HTTPError", message), status_code=403)(scope, receive, send)
                return
        await self.app(scope, receive, send)


def fail(exc: Exception) -> JSONResponse:
    """Return the JSON error answer to ``exc``."""
    from starlette.responses import JSONResponse

    if isinstance(exc, LkspaceError):
        status = getattr(exc, "status", 413 if isinstance(exc, TooLargeError) else 400 if exc.exit_code == 2 else 422)
        kind = type(exc).__name__
        message = " ".join(str(exc).split())
    else:
        status, kind = 500, "InternalError"
        message = f"internal error ({type(exc).__name__}: {exc})"
    return JSONResponse(error_json(kind, message), status_code=status)


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


class NotFinite(BadRequest):
    """A request number that is not finite: ``NaN``, ``Infinity`` or one past ±1.8e308 (400)."""


def not_finite(text: str) -> float:
    """Refuse ``NaN`` / ``Infinity`` / ``-Infinity`` in a request body (Python reads them; JSON has no such numbers)."""
    raise NotFinite(f"request body: {text} is not a JSON number; send finite numbers")


def finite(text: str) -> float:
    """Return the JSON number ``text`` as a float; :class:`NotFinite` if it is past the largest double (``1e999``)."""
    value = float(text)
    if not math.isfinite(value):
        raise NotFinite(f"request body: {text[:30]} is past the largest number (±1.8e308); send finite numbers")
    return value


async def json_of(request: Request) -> JsonObject:
    """Return the JSON object of the request body (``Content-Type: application/json`` required)."""
    if content_type(request) != "application/json":
        raise NotJson("send the request body as application/json")
    raw = await body_of(request, MAX_JSON)
    try:
        data = json.loads(raw or b"{}", parse_constant=not_finite, parse_float=finite)
    except NotFinite:
        raise
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
