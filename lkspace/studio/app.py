"""The studio's HTTP interface: a Starlette app of JSON endpoints and the static page.

Every endpoint answers JSON; bad input gets ``{"error": {"type", "message"}}`` with a 4xx
status and the server keeps running.  Request bodies are read up to a size limit; the
page names scaffolds by built-in name or by the id of one the server holds, never by a
path.
"""

from __future__ import annotations

import os
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias, TypeVar

import numpy as np
from starlette.applications import Starlette
from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp

from .. import __version__
from ..errors import GeometryError, LkspaceError, ScaffoldError, UsageError
from ..formats.colors import PALETTE, hex_colors
from ..io.json_values import JsonObject
from ..scaffolds import DEFAULT
from .answers import (
    Clearance,
    DesignView,
    DiagramView,
    Info,
    JobStarted,
    JobState,
    OpenedDesign,
    OrbitView,
    RelaxedCurves,
    ScaffoldView,
    Thumbs,
)
from .browse import Browser
from .design_files import filename, open_upload, save_design
from .designs import EXPORTS, Cache, design, labels_from_page, parse_block, parse_nulls
from .diagrams import Thumbnails, diagram
from .jobs import Job, Jobs, relaxed
from .lanes import Lane
from .requests import (
    CatalogRequest,
    DesignFileRequest,
    DesignRequest,
    DiagramRequest,
    ExportRequest,
    JobRequest,
    LookupRequest,
    RedrawRequest,
    ScaffoldRequest,
    SolveRequest,
    ThumbnailsRequest,
)
from .scaffolds import Held, Registry, builtin_choices
from .wire import (
    MAX_UPLOAD,
    Answer,
    BadRequest,
    BadUpload,
    JsonAnswer,
    LocalHostOnly,
    dumps,
    error_json,
    fail,
    file_of,
    json_of,
)

if TYPE_CHECKING:
    from .. import Realization

STATIC = os.path.join(os.path.dirname(__file__), "static")
"""The page and its vendored three.js build (shipped in the wheel)."""


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
    design: OpenedDesign | None = None
    """A design file opened on the command line (what ``/api/open-design`` answers), shown first."""


class Superseded(UsageError):
    """A relaxation or measurement stopped because a newer design asked for one (its answer would be stale)."""

    status = 409


R = TypeVar("R")
Reply: TypeAlias = Answer | Response


def endpoint(
    handler: Callable[[Studio, R], Reply],
    read: Callable[[JsonObject], R],
    lane: Callable[[Studio], Lane] | None = None,
) -> Callable[[Request], Awaitable[Response]]:
    """Wrap ``handler(studio, read(body))`` as a route answering JSON or an error.

    ``read`` is the request record's ``from_json``; a GET's body is its query parameters, and
    path parameters and the page id (header ``X-Lkspace-Page``, as ``page``) join the body.  The handler runs in the thread pool that answers edits,
    or queued in ``lane(studio)`` (exports).
    """
    from starlette.concurrency import run_in_threadpool

    async def route(request: Request) -> Response:
        studio: Studio = request.app.state.studio
        try:
            body: JsonObject = await json_of(request) if request.method == "POST" else dict(request.query_params)
            body.update(request.path_params)
            if "x-lkspace-page" in request.headers:
                body["page"] = request.headers["x-lkspace-page"]
            parsed = read(body)
            if lane is None:
                result = await run_in_threadpool(handler, studio, parsed)
            else:
                result = await lane(studio).run(handler, studio, parsed)
        except Exception as exc:  # noqa: BLE001 - every failure is an answer; the server runs on
            return fail(exc)
        if isinstance(result, Response):
            return result
        return Response(dumps(result), media_type="application/json")

    return route


@dataclass(frozen=True, eq=False)
class HeldDesign:
    """A request's design read on its scaffold: the scaffold held, labels, nulls and block translations."""

    held: Held
    labels: np.ndarray
    nulls: np.ndarray | None
    block: np.ndarray | None

    @classmethod
    def of(cls, studio: Studio, request: DesignRequest) -> HeldDesign:
        """Check the request's design on its scaffold (lengths, ranges, block size)."""
        held = studio.registry.get(request.key)
        sc = held.scaffold
        labels = labels_from_page(sc, request.labels)
        return cls(held, labels, parse_nulls(sc, request.nulls), parse_block(sc, request.block))


def no_body(data: JsonObject) -> None:
    """Read a request that takes no fields (any are ignored)."""


def info(studio: Studio, _: None) -> Info:
    """Return what the page needs first: built-in names, the scaffold to open, exports, the catalog, the strand colours."""
    return Info(
        version=__version__,
        builtins=tuple(builtin_choices()),
        initial=studio.initial,
        exports=EXPORTS,
        catalog=studio.browser.info() if studio.browser else None,
        max_upload=MAX_UPLOAD,
        design=studio.design,
        palette=tuple(hex_colors(PALETTE)),
    )


def scaffold(studio: Studio, request: ScaffoldRequest) -> ScaffoldView:
    """Return the scaffold ``key``: geometry, edges, orbits, default labels."""
    return studio.registry.get(request.key).view()


def orbits(studio: Studio, request: ScaffoldRequest) -> OrbitView:
    """Return the edge orbits of scaffold ``key`` under its rotations."""
    return studio.registry.get(request.key).orbit_view()


def redraw(studio: Studio, request: RedrawRequest) -> DesignView:
    """Trace and realize a design (no clearance measurement); ``relax: true`` for the relaxed curves."""
    d = HeldDesign.of(studio, request.design)
    page = request.design.page
    relaxer = (lambda real: relax_in_worker(studio, real, page)) if request.relax else None
    if not request.relax:
        studio.jobs.stop("clearance", page)  # the page's last measurement: its answer is stale, its CPU is this one's
    cache, key = studio.cache, d.held.key
    return design(d.held.scaffold, d.labels, d.nulls, d.block, cache, key, relaxer, request.have)


def relax_in_worker(studio: Studio, real: Realization, page: str = "") -> Realization:
    """Return ``real`` relaxed by a worker (a newer relaxation of ``page`` cancels this one: :class:`Superseded`)."""
    state = studio.jobs.wait(studio.jobs.start("relax", real, page=page))
    if state.state == "cancelled":
        raise Superseded("relax stopped: a newer design asked to be relaxed")
    if not isinstance(state.result, RelaxedCurves):
        raise GeometryError(state.error or "relax stopped", usage=True)
    return relaxed(real, state.result)


def measure(studio: Studio, request: DesignRequest) -> Clearance:
    """Return the embedding check of a design (from the realization the redraw kept)."""
    d = HeldDesign.of(studio, request)
    key = Cache.key(d.held.key, d.labels, d.nulls, d.block)
    real = studio.cache.get(key)
    if real is None:
        design(d.held.scaffold, d.labels, d.nulls, d.block, studio.cache, d.held.key)
        real = studio.cache.get(key)
        if real is None:
            raise BadRequest("this design has no geometry to measure")
    state = studio.jobs.wait(
        studio.jobs.start("clearance", real, page=request.page)
    )  # a worker: an edit meanwhile is never held up
    if state.state == "cancelled":
        raise Superseded("clearance stopped: a newer design was asked for")
    if not isinstance(state.result, Clearance):
        raise GeometryError(state.error or "clearance stopped")
    return state.result


def identify(studio: Studio, request: DesignRequest) -> JobStarted:
    """Start identifying a design in a worker (cancelling the previous identification)."""
    d = HeldDesign.of(studio, request)
    if d.held.scaffold.periodic:
        return JobStarted(None, "periodic: an infinite structure, not a knot or link")
    return JobStarted(studio.jobs.start("identify", d.held.scaffold, d.labels, d.nulls, page=request.page).id)


def solve(studio: Studio, request: SolveRequest) -> JobStarted:
    """Start a solve in a worker: ``components``, ``label_set``, ``no_zero``, ``fixes``, ``objective``, ``count``, ``time_limit``."""
    sc = studio.registry.get(request.key).scaffold
    if not 1 <= request.components <= sc.n_corners:
        raise BadRequest(f"components: an integer in 1..{sc.n_corners}")
    if len(request.fixes) > sc.n_edges:
        raise BadRequest("fixes: an object edge -> label")
    for edge, _ in request.fixes:
        if not 0 <= edge < sc.n_edges:
            raise BadRequest(f"fixes: edge {str(edge)[:20]!r} out of range 0..{sc.n_edges - 1}")
    return JobStarted(studio.jobs.start("solve", sc, request, page=request.page).id)


def job_of(studio: Studio, request: JobRequest) -> Job:
    """Return the job ``id`` names (a 400 error if none)."""
    found = studio.jobs.get(request.id)
    if found is None:
        raise BadRequest(f"no job {str(request.id)[:20]!r}")
    return found


def job(studio: Studio, request: JobRequest) -> JobState:
    """Return the state of job ``id`` (progress, result or error)."""
    return job_of(studio, request).poll()


def cancel(studio: Studio, request: JobRequest) -> JobState:
    """Cancel job ``id`` (terminating its worker)."""
    found = job_of(studio, request)
    found.cancel()
    return found.poll()


def catalog_query(studio: Studio, request: CatalogRequest) -> Answer:
    """One page of the catalog: ``filters``, ``sort``, ``descending``, ``offset``, ``limit``."""
    if studio.browser is None:
        raise BadRequest("no catalog: start the studio with a catalog (lkspace studio CATALOG.parquet)")
    return studio.browser.query(request)


class NoSuchDesign(LkspaceError):
    """The atlas holds no design of the type asked for (404)."""

    status = 404


def type_lookup(studio: Studio, request: LookupRequest) -> JsonAnswer:
    """Return the simplest designs of the type ``name`` in the shipped atlas (``limit``, ``scaffold``): ``lookup --json``."""
    from ..linktypes.lookup import TypeNotFound, lookup

    try:
        return dict(lookup(request.name, limit=request.limit, scaffold=request.scaffold).to_json())
    except TypeNotFound as exc:
        raise NoSuchDesign(str(exc)) from None


def knot_diagram(studio: Studio, request: DiagramRequest) -> DiagramView:
    """Return the 2D knot diagram of a design seen along ``view``, or simplified (:mod:`~lkspace.studio.diagrams`)."""
    d = HeldDesign.of(studio, request.design)
    return diagram(d.held.scaffold, d.held.key, d.labels, d.nulls, studio.cache, request.view, request.simplified)


def thumbnails(studio: Studio, request: ThumbnailsRequest) -> Thumbs:
    """Return thumbnails of ``designs`` on scaffold ``key`` and the common names of their ``names``."""
    held = studio.registry.get(request.key)
    return studio.thumbs.answer(held.scaffold, held.key, request)


MEDIA = {"json": "application/json", "png": "image/png", "glb": "model/gltf-binary", "oxdna": "application/zip"}
"""Content types of the downloads that have one (others: ``application/octet-stream``)."""


def download(studio: Studio, request: ExportRequest) -> Response:
    """Return the design as a file (``format``: one of :data:`~lkspace.studio.designs.EXPORTS`), written by a worker."""
    d = HeldDesign.of(studio, request.design)
    content, name = studio.jobs.export(d.held.scaffold, d.labels, d.nulls, request.format)
    media = MEDIA.get(request.format, "application/octet-stream")
    return Response(content, media_type=media, headers={"Content-Disposition": f'attachment; filename="{name}"'})


async def upload(request: Request) -> Response:
    """Hold an uploaded ``.obj`` / ``.json`` scaffold (:func:`~lkspace.studio.wire.file_of`); bytes that are not one: 400."""
    from starlette.concurrency import run_in_threadpool

    studio: Studio = request.app.state.studio
    try:
        name, data = await file_of(request)
        held = await run_in_threadpool(studio.registry.upload, name or "upload.json", data)
        return Response(dumps(held.view()), media_type="application/json")
    except ScaffoldError as exc:  # the bytes sent are not a scaffold file: the body's fault (400)
        return fail(BadUpload(str(exc)))
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
    except ScaffoldError as exc:  # the bytes sent are not a design file: the body's fault (400)
        return fail(BadUpload(str(exc)))
    except Exception as exc:  # noqa: BLE001 - every failure is an answer
        return fail(exc)


async def http_error(request: Request, exc: Exception) -> Response:
    """Unknown paths and methods: a JSON error too."""
    status = getattr(exc, "status_code", 500)
    message = f"{request.method} {request.url.path[:80]}: {getattr(exc, 'detail', '')}"
    return JSONResponse(error_json("HTTPError", message), status_code=status)


async def page(request: Request) -> Response:
    """Return the studio page."""
    return FileResponse(os.path.join(STATIC, "index.html"), headers={"Cache-Control": "no-store"})


def create_app(studio: Studio | None = None) -> ASGIApp:
    """Return the ASGI app serving ``studio`` (a fresh one by default); local names only unless ``studio.local_only`` is off."""
    posts = [
        Route("/api/scaffold", endpoint(scaffold, ScaffoldRequest.from_json), methods=["POST"]),
        Route("/api/design", endpoint(redraw, RedrawRequest.from_json), methods=["POST"]),
        Route("/api/orbits", endpoint(orbits, ScaffoldRequest.from_json), methods=["POST"]),
        Route("/api/clearance", endpoint(measure, DesignRequest.from_json), methods=["POST"]),
        Route("/api/identify", endpoint(identify, DesignRequest.from_json), methods=["POST"]),
        Route("/api/solve", endpoint(solve, SolveRequest.from_json), methods=["POST"]),
        Route("/api/catalog", endpoint(catalog_query, CatalogRequest.from_json), methods=["POST"]),
        Route("/api/diagram", endpoint(knot_diagram, DiagramRequest.from_json), methods=["POST"]),
        Route("/api/thumbnails", endpoint(thumbnails, ThumbnailsRequest.from_json), methods=["POST"]),
        Route("/api/design-file", endpoint(save_design, DesignFileRequest.from_json), methods=["POST"]),
        Route("/api/filename", endpoint(filename, DesignRequest.from_json), methods=["POST"]),
    ]
    routes = [
        Route("/", page),
        Route("/favicon.ico", lambda request: Response(status_code=204)),
        Route("/api/info", endpoint(info, no_body)),
        Route("/api/lookup", endpoint(type_lookup, LookupRequest.from_json)),
        Route("/api/upload", upload, methods=["POST"]),
        Route("/api/open-design", open_design, methods=["POST"]),
        Route("/api/job/{id}", endpoint(job, JobRequest.from_json)),
        Route("/api/job/{id}/cancel", endpoint(cancel, JobRequest.from_json), methods=["POST"]),
        Route(
            "/api/export", endpoint(download, ExportRequest.from_json, lambda studio: studio.exports), methods=["POST"]
        ),
        *posts,
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    app = Starlette(routes=routes, exception_handlers={HTTPException: http_error})
    app.router.redirect_slashes = False  # a path with a stray slash is unknown (JSON 404), not a redirect
    app.state.studio = studio = studio or Studio()
    return LocalHostOnly(app) if studio.local_only else app
