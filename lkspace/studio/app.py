"""The studio's HTTP interface: a Starlette app of JSON endpoints and the static page.

Every endpoint answers JSON; bad input gets ``{"error": {"type", "message"}}`` with a 4xx
status and the server keeps running.  Request bodies are read up to a size limit; the
page names scaffolds by built-in name or by the id of one the server holds, never by a
path.
"""

from __future__ import annotations

import math
import os
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from starlette.applications import Starlette
from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from .. import __version__
from ..errors import GeometryError, LkspaceError, UsageError
from ..scaffolds import DEFAULT
from .browse import Browser
from .curves import parse_have
from .design_files import filename, open_upload, save_design
from .designs import EXPORTS, Cache, design, is_count, labels_from_page, parse_block, parse_nulls
from .diagrams import Thumbnails, diagram
from .jobs import Job, Jobs, relaxed
from .lanes import Lane
from .scaffolds import MAX_UPLOAD, Registry, builtin_choices, dumps
from .wire import BadRequest, LocalHostOnly, fail, file_of, json_of

if TYPE_CHECKING:
    from .. import Realization

STATIC = os.path.join(os.path.dirname(__file__), "static")
"""The page and its vendored three.js build (shipped in the wheel)."""

OBJECTIVES = (None, "min-abs", "min-nonzero")


@dataclass(eq=False)
class Studio:
    """What one studio serves: its scaffolds, realizations, jobs and (optionally) a catalog."""

    initial: str = DEFAULT
    registry: Registry = field(default_factory=Registry)
    cache: Cache = field(default_factory=Cache)
    jobs: Jobs = field(default_factory=Jobs)
    exports: Lane = field(default_factory=lambda: Lane("export"))
    browser: Browser | None = None
    local_only: bool = True
    thumbs: Thumbnails = field(default_factory=Thumbnails)
    design: dict[str, Any] | None = None
    """A design file opened on the command line (what ``/api/open-design`` answers), shown first."""


class Superseded(UsageError):
    """A relaxation or measurement stopped because a newer design asked for one (its answer would be stale)."""

    status = 409


Handler = Callable[[Studio, dict[str, Any]], Any]


def endpoint(
    handler: Handler, lane: Callable[[Studio], Lane] | None = None
) -> Callable[[Request], Awaitable[Response]]:
    """Wrap ``handler(studio, body)`` as a route answering JSON or an error.

    The handler runs in the thread pool that answers edits, or queued in ``lane(studio)`` (exports).
    """
    from starlette.concurrency import run_in_threadpool

    async def route(request: Request) -> Response:
        studio: Studio = request.app.state.studio
        try:
            body = await json_of(request) if request.method == "POST" else dict(request.query_params)
            body.update(request.path_params)
            if lane is None:
                result = await run_in_threadpool(handler, studio, body)
            else:
                result = await lane(studio).run(handler, studio, body)
        except Exception as exc:  # noqa: BLE001 - every failure is an answer; the server runs on
            return fail(exc)
        if isinstance(result, Response):
            return result
        return Response(dumps(result), media_type="application/json")

    return route


def design_args(studio: Studio, body: dict[str, Any]) -> tuple[Any, ...]:
    """``(held, labels, nulls, block)`` of a request naming a design."""
    held = studio.registry.get(body.get("key"))
    sc = held.scaffold
    return (
        held,
        labels_from_page(sc, body.get("labels")),
        parse_nulls(sc, body.get("nulls")),
        parse_block(sc, body.get("block")),
    )


def info(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return what the page needs first: built-in names, the scaffold to open, exports, the catalog."""
    return {
        "version": __version__,
        "builtins": builtin_choices(),
        "initial": studio.initial,
        "exports": list(EXPORTS),
        "catalog": studio.browser.info() if studio.browser else None,
        "max_upload": MAX_UPLOAD,
        "design": studio.design,
    }


def scaffold(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return the scaffold ``key``: geometry, edges, orbits, default labels."""
    return studio.registry.get(body.get("key")).view()


def orbits(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return the edge orbits of scaffold ``key`` under its rotations."""
    return studio.registry.get(body.get("key")).orbit_view()


def redraw(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Trace and realize a design (no clearance measurement); ``relax: true`` for the relaxed curves."""
    held, labels, nulls, block = design_args(studio, body)
    relax = body.get("relax", False)
    if not isinstance(relax, bool):
        raise BadRequest("relax: true or false")
    relaxer = (lambda real: relax_in_worker(studio, real)) if relax else None
    if not relax:
        studio.jobs.stop("clearance")  # the last design's measurement: its answer is stale, its CPU is this one's
    return design(held.scaffold, labels, nulls, block, studio.cache, held.key, relaxer, parse_have(body.get("have")))


def relax_in_worker(studio: Studio, real: Realization) -> Realization:
    """Return ``real`` relaxed by a worker (a newer relaxation cancels this one: :class:`Superseded`)."""
    state = studio.jobs.wait(studio.jobs.start("relax", real))
    if state["state"] == "cancelled":
        raise Superseded("relax stopped: a newer design asked to be relaxed")
    if state["state"] == "error":
        raise GeometryError(state["error"], usage=True)
    return relaxed(real, state["result"])


def measure(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return the embedding check of a design (from the realization the redraw kept)."""
    held, labels, nulls, block = design_args(studio, body)
    real = studio.cache.get(Cache.key(held.key, labels, nulls, block))
    if real is None:
        design(held.scaffold, labels, nulls, block, studio.cache, held.key)
        real = studio.cache.get(Cache.key(held.key, labels, nulls, block))
        if real is None:
            raise BadRequest("this design has no geometry to measure")
    state = studio.jobs.wait(studio.jobs.start("clearance", real))  # a worker: an edit meanwhile is never held up
    if state["state"] == "cancelled":
        raise Superseded("clearance stopped: a newer design was asked for")
    if state["state"] == "error":
        raise GeometryError(state["error"])
    return state["result"]


def identify(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Start identifying a design in a worker (cancelling the previous identification)."""
    held, labels, nulls, _ = design_args(studio, body)
    if held.scaffold.periodic:
        return {"job": None, "message": "periodic: an infinite structure, not a knot or link"}
    return {"job": studio.jobs.start("identify", held.scaffold, labels, nulls).id}


def solve(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Start a solve in a worker: ``components``, ``label_set``, ``no_zero``, ``fixes``, ``objective``, ``count``, ``time_limit``."""
    held = studio.registry.get(body.get("key"))
    components, count, limit = body.get("components"), body.get("count", 5), body.get("time_limit", 60)
    if (
        not isinstance(components, int)
        or isinstance(components, bool)
        or not 1 <= components <= held.scaffold.n_corners
    ):
        raise BadRequest(f"components: an integer in 1..{held.scaffold.n_corners}")
    if not isinstance(count, int) or isinstance(count, bool) or not 1 <= count <= 50:
        raise BadRequest("count: an integer in 1..50")
    if not isinstance(limit, int | float) or isinstance(limit, bool) or not (math.isfinite(limit) and 0 < limit <= 600):
        raise BadRequest("time_limit: seconds in (0, 600]")
    label_set = body.get("label_set", "-2..2")
    if not isinstance(label_set, str) or len(label_set) > 200:
        raise BadRequest("label_set: text like -2..2 or -1,1")
    if body.get("objective") not in OBJECTIVES:
        raise BadRequest("objective: none, min-abs or min-nonzero")
    fixes_in = body.get("fixes") or {}
    if not isinstance(fixes_in, dict) or len(fixes_in) > held.scaffold.n_edges:
        raise BadRequest("fixes: an object edge -> label")
    fixes = {}
    for edge, value in fixes_in.items():
        if not is_count(edge, 9) or not 0 <= int(edge) < held.scaffold.n_edges:
            raise BadRequest(f"fixes: edge {str(edge)[:20]!r} out of range 0..{held.scaffold.n_edges - 1}")
        if not isinstance(value, int) or isinstance(value, bool) or abs(value) > 10**6:
            raise BadRequest(f"fixes: label of edge {edge} must be an integer within ±10**6")
        fixes[int(edge)] = value
    from ..model.specs import parse_label_set

    parse_label_set(label_set)  # refused here, not in the worker
    options = {
        "label_set": label_set,
        "no_zero": bool(body.get("no_zero")),
        "fixes": fixes,
        "count": count,
        "objective": body.get("objective"),
        "time_limit": float(limit),
        "distinct_up_to": "none",
        "workers": 2,
    }
    return {"job": studio.jobs.start("solve", held.scaffold, {"components": components, **options}).id}


def job_of(studio: Studio, body: dict[str, Any]) -> Job:
    """Return the job ``id`` names (a 400 error if none)."""
    found = studio.jobs.get(int(body["id"]) if is_count(body.get("id")) else None)
    if found is None:
        raise BadRequest(f"no job {str(body.get('id'))[:20]!r}")
    return found


def job(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return the state of job ``id`` (progress, result or error)."""
    return job_of(studio, body).poll()


def cancel(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Cancel job ``id`` (terminating its worker)."""
    found = job_of(studio, body)
    found.cancel()
    return found.poll()


def catalog_query(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """One page of the catalog: ``filters``, ``sort``, ``descending``, ``offset``, ``limit``."""
    if studio.browser is None:
        raise BadRequest("no catalog: start the studio with a catalog (lkspace studio CATALOG.parquet)")
    b = body
    return studio.browser.query(
        b.get("filters"), b.get("sort"), b.get("descending", False), b.get("offset", 0), b.get("limit", 50)
    )


class NoSuchDesign(LkspaceError):
    """The atlas holds no design of the type asked for (404)."""

    status = 404


def type_lookup(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return the simplest designs of the type ``name`` in the shipped atlas (``limit``, ``scaffold``): ``lookup --json``."""
    from ..linktypes.lookup import TypeNotFound, lookup

    name, limit, on = body.get("name"), str(body.get("limit", 10)), body.get("scaffold")
    if not isinstance(name, str) or not name.strip() or len(name) > 200:
        raise BadRequest("name: a knot or link type, e.g. 5_2, m3_1 or Borromean rings")
    if not is_count(limit, 4) or not 1 <= int(limit) <= 1000:
        raise BadRequest("limit: an integer in 1..1000")
    if on is not None and (not isinstance(on, str) or len(on) > 200):
        raise BadRequest("scaffold: a built-in scaffold name")
    try:
        return lookup(name, limit=int(limit), scaffold=on).to_json()
    except TypeNotFound as exc:
        raise NoSuchDesign(str(exc)) from None


def knot_diagram(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return the 2D knot diagram of a design seen along ``view`` (:mod:`~lkspace.studio.diagrams`)."""
    held, labels, nulls, _ = design_args(studio, body)
    return diagram(held.scaffold, held.key, labels, nulls, studio.cache, body.get("view"))


def thumbnails(studio: Studio, body: dict[str, Any]) -> dict[str, Any]:
    """Return thumbnails of ``designs`` on scaffold ``key`` and the common names of their ``names``."""
    held = studio.registry.get(body.get("key"))
    return studio.thumbs.answer(held.scaffold, held.key, body.get("designs"), body.get("names"))


def download(studio: Studio, body: dict[str, Any]) -> Response:
    """Return the design as a file (``format``: one of :data:`~lkspace.studio.designs.EXPORTS`), written by a worker."""
    held, labels, nulls, _ = design_args(studio, body)
    content, name = studio.jobs.export(held.scaffold, labels, nulls, body.get("format"))
    kinds = {"json": "application/json", "png": "image/png", "glb": "model/gltf-binary"}
    media = kinds.get(str(body.get("format")), "application/octet-stream")
    return Response(content, media_type=media, headers={"Content-Disposition": f'attachment; filename="{name}"'})


async def upload(request: Request) -> Response:
    """Hold an uploaded ``.obj`` / ``.json`` scaffold (:func:`~lkspace.studio.wire.file_of`)."""
    from starlette.concurrency import run_in_threadpool

    studio: Studio = request.app.state.studio
    try:
        name, data = await file_of(request)
        held = await run_in_threadpool(studio.registry.upload, name or "upload.json", data)
        return Response(dumps(held.view()), media_type="application/json")
    except Exception as exc:  # noqa: BLE001 - every failure is an answer
        return fail(exc)


async def open_design(request: Request) -> Response:
    """Open an uploaded design file (:func:`~lkspace.studio.wire.file_of`): the page then loads the answer."""
    from starlette.concurrency import run_in_threadpool

    studio: Studio = request.app.state.studio
    try:
        name, data = await file_of(request)
        answer = await run_in_threadpool(open_upload, studio.registry, name, data)
        return Response(dumps(answer), media_type="application/json")
    except Exception as exc:  # noqa: BLE001 - every failure is an answer
        return fail(exc)


async def http_error(request: Request, exc: Exception) -> Response:
    """Unknown paths and methods: a JSON error too."""
    status = getattr(exc, "status_code", 500)
    return JSONResponse(
        {
            "error": {
                "type": "HTTPError",
                "message": f"{request.method} {request.url.path[:80]}: {getattr(exc, 'detail', '')}",
            }
        },
        status_code=status,
    )


async def page(request: Request) -> Response:
    """Return the studio page."""
    return FileResponse(os.path.join(STATIC, "index.html"), headers={"Cache-Control": "no-store"})


def create_app(studio: Studio | None = None) -> Any:
    """Return the ASGI app serving ``studio`` (a fresh one by default); local names only unless ``studio.local_only`` is off."""
    posts = {
        "scaffold": scaffold,
        "design": redraw,
        "orbits": orbits,
        "clearance": measure,
        "identify": identify,
        "solve": solve,
        "catalog": catalog_query,
        "diagram": knot_diagram,
        "thumbnails": thumbnails,
        "design-file": save_design,
        "filename": filename,
    }
    routes = [
        Route("/", page),
        Route("/favicon.ico", lambda request: Response(status_code=204)),
        Route("/api/info", endpoint(info)),
        Route("/api/lookup", endpoint(type_lookup)),
        Route("/api/upload", upload, methods=["POST"]),
        Route("/api/open-design", open_design, methods=["POST"]),
        Route("/api/job/{id}", endpoint(job)),
        Route("/api/job/{id}/cancel", endpoint(cancel), methods=["POST"]),
        Route("/api/export", endpoint(download, lambda studio: studio.exports), methods=["POST"]),
        *[Route(f"/api/{name}", endpoint(fn), methods=["POST"]) for name, fn in posts.items()],
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    app = Starlette(routes=routes, exception_handlers={HTTPException: http_error})
    app.router.redirect_slashes = False  # a path with a stray slash is unknown (JSON 404), not a redirect
    app.state.studio = studio = studio or Studio()
    return LocalHostOnly(app) if studio.local_only else app
