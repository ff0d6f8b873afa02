"""Everything that crosses the studio's HTTP boundary: typed requests, answers and job states, and the JSON errors.

Each request body is a frozen record with one validating ``from_json``: a body that is not
of the record's shape is refused there, with a one-line message naming the field (a
:class:`~lkspace.errors.UsageError` or :class:`~lkspace.errors.LabelError`, answered 4xx by
:func:`fail`), so the endpoints only ever see well-typed values.  What a request means on
a scaffold (a label list as long as its edges, a side index in range) is checked by the
module that knows the scaffold (:mod:`~lkspace.studio.designs`).  Each answer is a record
with one ``to_json`` (or, for the large views the page reads key by key, a ``TypedDict``);
:func:`dumps` writes either.

Every failure becomes ``{"error": {"type", "message"}}`` with a 4xx status (:func:`fail`); a
request addressed to a host that is not this machine's name is refused before any endpoint
runs (:class:`LocalHostOnly`).  Bodies a cross-site page could send without asking (text/plain,
forms) are refused before they are read: JSON endpoints take ``application/json``, file
uploads :data:`UPLOAD_TYPE`.
"""

from __future__ import annotations

import base64
import json
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, NotRequired, Protocol, TypeAlias, TypedDict, runtime_checkable

import numpy as np

from ..errors import LabelError, LkspaceError, TooLargeError, UsageError

if TYPE_CHECKING:
    from starlette.requests import Request
    from starlette.responses import JSONResponse

JsonObject: TypeAlias = dict[str, object]
"""A JSON object as it arrives (values still to be checked) or as an answer writes it."""

MAX_JSON = 2_000_000
"""Largest JSON request body, in bytes."""

MAX_UPLOAD = 8_000_000
"""Largest uploaded scaffold file, in bytes."""

UPLOAD_TYPE = "application/octet-stream"
"""The content type an upload must declare: not one a cross-site form can send without asking."""

MAX_HAVE = 50_000
"""Most curve keys a request may say the page holds."""

MAX_THUMBS = 50
"""Most designs in one thumbnail request."""

MAX_LIMIT = 200
"""Most catalog rows in one page."""

MAX_FILTERS = 16
"""Most filters of one catalog query."""

OPS = ("==", "!=", "<", "<=", ">", ">=", "contains")
"""Catalog filter operators."""

Op = Literal["==", "!=", "<", "<=", ">", ">=", "contains"]
Objective = Literal["min-abs", "min-nonzero"]
JobKind = Literal["identify", "relax", "solve", "clearance", "export"]
JobStatus = Literal["running", "done", "error", "cancelled"]
View = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
"""The page's camera axes ``(right, up, back)``."""


class BadRequest(UsageError):
    """A request the endpoints cannot read (not JSON, too large, fields missing)."""

    status = 400


class NotJson(BadRequest):
    """A POST without ``Content-Type: application/json`` (a cross-site form cannot send one without asking)."""

    status = 415


class NotAFile(UsageError):
    """An upload not sent as :data:`UPLOAD_TYPE` (a cross-site form could send text/plain or multipart; 415)."""

    status = 415


# ---- reading fields (each refusal names its field)


def is_integer(value: object) -> bool:
    """Whether ``value`` is a JSON integer (``true`` and ``false`` are not)."""
    return isinstance(value, int) and not isinstance(value, bool)


def is_count(value: object, digits: int = 18) -> bool:
    """Return whether ``value`` is a non-negative integer written in at most ``digits`` ASCII digits."""
    return (
        isinstance(value, str | int)
        and not isinstance(value, bool)
        and bool(re.fullmatch(rf"[0-9]{{1,{digits}}}", str(value)))
    )


def integer_in(data: Mapping[str, object], name: str, default: int, low: int, high: int, message: str) -> int:
    """Return the integer field ``name`` (``default`` when absent) if in ``low..high``; :class:`BadRequest` otherwise."""
    value = data.get(name, default)
    if not isinstance(value, int) or isinstance(value, bool) or not low <= value <= high:
        raise BadRequest(message)
    return value


def flag(data: Mapping[str, object], name: str) -> bool:
    """Return the ``true`` / ``false`` field ``name`` (false when absent or null)."""
    value = data.get(name)
    if value is None:
        return False
    if not isinstance(value, bool):
        raise BadRequest(f"{name}: true or false")
    return value


def scaffold_key(data: Mapping[str, object]) -> str:
    """Return the ``key`` field: a built-in scaffold name or the id of one the studio holds."""
    key = data.get("key")
    if not isinstance(key, str) or not key:
        raise UsageError("key: a scaffold name (a built-in one, like 'cube', or the id the studio gave one)")
    return key


def label_list(value: object, name: str = "labels") -> tuple[int, ...] | None:
    """Return the page's labels (integers, or decimal strings for exact int64), ``None`` when absent."""
    if value is None:
        return None
    if not isinstance(value, list):
        raise LabelError(f"{name}: expected a list with one integer per edge")
    items: list[int] = []
    for i, v in enumerate(value):
        if isinstance(v, str) and re.fullmatch(r"[+-]?\d{1,25}", v.strip()):
            v = int(v)
        if not is_integer(v):
            raise LabelError(f"{name}: item {i}: {str(v)[:30]!r} is not an integer")
        items.append(v)
    return tuple(items)


def integer_list(value: object, error: LkspaceError) -> tuple[int, ...] | None:
    """Return a list of integers (``None`` when absent); raise ``error`` for anything else."""
    if value is None:
        return None
    if not isinstance(value, list) or not all(is_integer(v) for v in value):
        raise error
    return tuple(value)


def view_axes(value: object) -> View | None:
    """Return the page's camera axes ``[right, up, back]`` (three numbers each within ±10**6), ``None`` when absent."""
    if value is None:
        return None
    if not (
        isinstance(value, list)
        and len(value) == 3
        and all(isinstance(v, list) and len(v) == 3 for v in value)
        and all(isinstance(x, int | float) and not isinstance(x, bool) and abs(x) <= 1e6 for v in value for x in v)
    ):
        raise UsageError("view: three directions [right, up, back], each three numbers within ±10**6")
    right, up, back = (tuple(float(x) for x in v) for v in value)
    return ((right[0], right[1], right[2]), (up[0], up[1], up[2]), (back[0], back[1], back[2]))


# ---- requests


@dataclass(frozen=True)
class ScaffoldRequest:
    """``/api/scaffold``, ``/api/orbits``: a scaffold ``key``."""

    key: str

    @classmethod
    def from_json(cls, data: JsonObject) -> ScaffoldRequest:
        """Read the request body."""
        return cls(scaffold_key(data))


@dataclass(frozen=True)
class DesignRequest:
    """A design: scaffold ``key``, ``labels`` (``None``: the scaffold's own), null ``nulls`` sides, periodic ``block``."""

    key: str
    labels: tuple[int, ...] | None = None
    nulls: tuple[int, ...] | None = None
    block: tuple[int, ...] | None = None

    @classmethod
    def from_json(cls, data: JsonObject) -> DesignRequest:
        """Read the request body (``/api/clearance``, ``/api/identify``, ``/api/filename``)."""
        return cls(
            scaffold_key(data),
            label_list(data.get("labels")),
            integer_list(data.get("nulls"), LabelError("nulls: expected a list of side indices (integers)")),
            integer_list(data.get("block"), UsageError("block: a list of sizes, one per lattice direction")),
        )


@dataclass(frozen=True)
class RedrawRequest:
    """``/api/design``: a design, ``relax`` for the relaxed curves, the curve keys the page ``have``."""

    design: DesignRequest
    relax: bool = False
    have: frozenset[str] = frozenset()

    @classmethod
    def from_json(cls, data: JsonObject) -> RedrawRequest:
        """Read the request body."""
        have = data.get("have")
        if have is not None and (
            not isinstance(have, list) or not all(isinstance(v, str) and len(v) <= 32 for v in have)
        ):
            raise UsageError("have: expected a list of curve keys (strings from an earlier answer)")
        if have is not None and len(have) > MAX_HAVE:
            raise UsageError(f"have: {len(have):,} curve keys > {MAX_HAVE:,}; send the keys of the curves drawn")
        return cls(DesignRequest.from_json(data), flag(data, "relax"), frozenset(have or ()))


@dataclass(frozen=True)
class DiagramRequest:
    """``/api/diagram``: a design and the page's ``view`` (``None``: the generic rotation)."""

    design: DesignRequest
    view: View | None = None

    @classmethod
    def from_json(cls, data: JsonObject) -> DiagramRequest:
        """Read the request body."""
        return cls(DesignRequest.from_json(data), view_axes(data.get("view")))


@dataclass(frozen=True)
class ExportRequest:
    """``/api/export``: a design and the file ``format`` (checked against the export formats when written)."""

    design: DesignRequest
    format: str

    @classmethod
    def from_json(cls, data: JsonObject) -> ExportRequest:
        """Read the request body."""
        fmt = data.get("format")
        if not isinstance(fmt, str):
            raise UsageError("format: one of the export formats /api/info lists")
        return cls(DesignRequest.from_json(data), fmt)


@dataclass(frozen=True)
class DesignFileRequest:
    """``/api/design-file``: a design and the page's camera ``view`` (the design file's own reader checks it)."""

    design: DesignRequest
    view: Mapping[str, tuple[float, float, float]] | None = None

    @classmethod
    def from_json(cls, data: JsonObject) -> DesignFileRequest:
        """Read the request body."""
        from ..io.design_json import read_view

        return cls(DesignRequest.from_json(data), read_view(data.get("view"), "view"))


@dataclass(frozen=True)
class SolveRequest:
    """``/api/solve``: the query of :func:`lkspace.solve` the page's form sends."""

    key: str
    components: int
    label_set: str = "-2..2"
    no_zero: bool = False
    fixes: tuple[tuple[int, int], ...] = ()
    objective: Objective | None = None
    count: int = 5
    time_limit: float = 60.0

    @classmethod
    def from_json(cls, data: JsonObject) -> SolveRequest:
        """Read the request body (the components' upper bound and the fixed edges are the scaffold's to check)."""
        from ..model.specs import parse_label_set

        key = scaffold_key(data)
        components = data.get("components")
        if not isinstance(components, int) or isinstance(components, bool):
            raise BadRequest("components: an integer (how many strands the designs have)")
        count = integer_in(data, "count", 5, 1, 50, "count: an integer in 1..50")
        limit = data.get("time_limit", 60)
        if (
            not isinstance(limit, int | float)
            or isinstance(limit, bool)
            or not (math.isfinite(limit) and 0 < limit <= 600)
        ):
            raise BadRequest("time_limit: seconds in (0, 600]")
        label_set = data.get("label_set", "-2..2")
        if not isinstance(label_set, str) or len(label_set) > 200:
            raise BadRequest("label_set: text like -2..2 or -1,1")
        parse_label_set(label_set)  # refused here, not in the worker
        objective = data.get("objective")
        if objective is not None and objective not in ("min-abs", "min-nonzero"):
            raise BadRequest("objective: none, min-abs or min-nonzero")
        return cls(
            key,
            components,
            label_set,
            flag(data, "no_zero"),
            fixes_of(data.get("fixes")),
            objective,
            count,
            float(limit),
        )

    def options(self) -> JsonObject:
        """Return the keyword arguments of :func:`lkspace.solve` (the studio's fixed ones included)."""
        return {
            "components": self.components,
            "label_set": self.label_set,
            "no_zero": self.no_zero,
            "fixes": dict(self.fixes),
            "count": self.count,
            "objective": self.objective,
            "time_limit": self.time_limit,
            "distinct_up_to": "none",
            "workers": 2,
        }


def fixes_of(value: object) -> tuple[tuple[int, int], ...]:
    """Return the fixed labels ``((edge, label), ...)`` of the solve form's ``fixes`` object (edge -> label)."""
    if value is None:
        return ()
    if not isinstance(value, dict) or len(value) > 10**6:
        raise BadRequest("fixes: an object edge -> label")
    fixes = []
    for edge, label in value.items():
        if not is_count(edge, 9):
            raise BadRequest(f"fixes: edge {str(edge)[:20]!r} is not an edge number")
        if not is_integer(label) or abs(label) > 10**6:
            raise BadRequest(f"fixes: label of edge {edge} must be an integer within ±10**6")
        fixes.append((int(edge), int(label)))
    return tuple(fixes)


@dataclass(frozen=True)
class JobRequest:
    """``/api/job/{id}``, ``/api/job/{id}/cancel``: a job ``id``."""

    id: int

    @classmethod
    def from_json(cls, data: JsonObject) -> JobRequest:
        """Read the path's job id."""
        value = data.get("id")
        if not is_count(value):
            raise BadRequest(f"no job {str(value)[:20]!r}")
        return cls(int(str(value)))


Filter = tuple[str, Op, object]
"""A catalog filter ``(column, op, value)``; the value is checked against the column's type."""


@dataclass(frozen=True)
class CatalogRequest:
    """``/api/catalog``: ``filters``, ``sort`` (a column), ``descending``, ``offset``, ``limit``."""

    filters: tuple[Filter, ...] = ()
    sort: str | None = None
    descending: bool = False
    offset: int = 0
    limit: int = 50

    @classmethod
    def from_json(cls, data: JsonObject) -> CatalogRequest:
        """Read the request body (the columns are the catalog's to check)."""
        filters = data.get("filters")
        if filters is not None and (not isinstance(filters, list) or len(filters) > MAX_FILTERS):
            raise UsageError(f"filters: expected a list of at most {MAX_FILTERS} [column, op, value] triples")
        triples: list[Filter] = []
        for item in filters or []:
            if not (isinstance(item, list) and len(item) == 3):
                raise UsageError("filters: each filter is [column, op, value]")
            column, op, value = item
            if not isinstance(column, str):
                raise UsageError(f"filter column {str(column)[:40]!r}: not a column name")
            if op == "==" or op == "!=" or op == "<" or op == "<=" or op == ">" or op == ">=" or op == "contains":
                triples.append((column, op, value))
            else:
                raise UsageError(f"filter op {str(op)[:10]!r}: choose one of {' '.join(OPS)}")
        sort = data.get("sort")
        if sort is not None and not isinstance(sort, str):
            raise UsageError(f"sort column {str(sort)[:40]!r}: not a column")
        offset = data.get("offset", 0)
        if not is_integer(offset) or not isinstance(offset, int) or offset < 0:
            raise UsageError("offset: expected an integer >= 0")
        limit = data.get("limit", 50)
        if not is_integer(limit) or not isinstance(limit, int) or not 1 <= limit <= MAX_LIMIT:
            raise UsageError(f"limit: expected an integer in 1..{MAX_LIMIT}")
        return cls(tuple(triples), sort, flag(data, "descending"), offset, limit)


@dataclass(frozen=True)
class LookupRequest:
    """``/api/lookup?name=&limit=&scaffold=``: the simplest designs of a type in the shipped atlas."""

    name: str
    limit: int = 10
    scaffold: str | None = None

    @classmethod
    def from_json(cls, data: JsonObject) -> LookupRequest:
        """Read the query parameters."""
        name, limit, on = data.get("name"), str(data.get("limit", 10)), data.get("scaffold")
        if not isinstance(name, str) or not name.strip() or len(name) > 200:
            raise BadRequest("name: a knot or link type, e.g. 5_2, m3_1 or Borromean rings")
        if not is_count(limit, 4) or not 1 <= int(limit) <= 1000:
            raise BadRequest("limit: an integer in 1..1000")
        if on is not None and (not isinstance(on, str) or len(on) > 200):
            raise BadRequest("scaffold: a built-in scaffold name")
        return cls(name, int(limit), on)


@dataclass(frozen=True)
class ThumbnailsRequest:
    """``/api/thumbnails``: label lists ``designs`` on scaffold ``key`` and their table ``names`` (or ``None``)."""

    key: str
    designs: tuple[tuple[int, ...], ...]
    names: tuple[str | None, ...]

    @classmethod
    def from_json(cls, data: JsonObject) -> ThumbnailsRequest:
        """Read the request body (a name that is not a string has no common name: ``None``)."""
        designs, names = data.get("designs"), data.get("names")
        if not isinstance(designs, list) or len(designs) > MAX_THUMBS or not all(isinstance(d, list) for d in designs):
            raise UsageError(f"designs: a list of at most {MAX_THUMBS} label lists")
        if names is not None and (not isinstance(names, list) or len(names) != len(designs)):
            raise UsageError("names: a list with one name (or null) per design")
        labels = tuple(label_list(d, f"designs[{i}]") or () for i, d in enumerate(designs))
        named = tuple(n[:200] if isinstance(n, str) and n else None for n in names or [None] * len(designs))
        return cls(scaffold_key(data), labels, named)


# ---- answers


@runtime_checkable
class Record(Protocol):
    """An answer with its JSON form."""

    def to_json(self) -> JsonObject:
        """Return the JSON form."""


@dataclass(frozen=True)
class JobStarted:
    """The answer to a request starting a job: its id, or ``None`` with the reason none started."""

    job: int | None
    message: str | None = None

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {"job": self.job} if self.message is None else {"job": self.job, "message": self.message}


@dataclass(frozen=True)
class Progress:
    """What a worker's long step reports: its description, the work done (as text) and a note."""

    step: str
    done: str
    note: str

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {"step": self.step, "done": self.done, "note": self.note}


@dataclass(frozen=True)
class Identified:
    """An identify job's answer: the knot or link type as the page shows it."""

    name: str | None
    common_name: str | None
    status: str
    components: int
    linking_matrix: Sequence[Sequence[int]]
    mirror: bool | None
    split: bool | None
    crossings: int | None

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {
            "name": self.name,
            "common_name": self.common_name,
            "status": self.status,
            "components": self.components,
            "linking_matrix": self.linking_matrix,
            "mirror": self.mirror,
            "split": self.split,
            "crossings": self.crossings,
        }


@dataclass(frozen=True)
class Solved:
    """A solve job's answer: the solver's summary (:meth:`lkspace.SolveResult.to_dict`) with its designs."""

    summary: Mapping[str, object]
    solutions: tuple[tuple[list[int], int], ...]
    """``(labels, components)`` of every design found."""

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        designs = [{"labels": labels, "components": n} for labels, n in self.solutions]
        return {**self.summary, "solutions": designs}


@dataclass(frozen=True, eq=False)
class RelaxedCurves:
    """A relax job's answer: the relaxed curves ``(n, 3) float64`` each, the tube and the clearance."""

    curves: tuple[np.ndarray, ...]
    tube_radius: float
    min_distance: float
    closest: Mapping[str, object]

    def to_json(self) -> JsonObject:
        """Return the JSON form: ``points`` (base64 little-endian ``float64``), ``counts``, tube, clearance."""
        points = np.vstack(self.curves).astype("<f8").tobytes()
        return {
            "points": base64.b64encode(points).decode("ascii"),
            "counts": [len(c) for c in self.curves],
            "tube_radius": self.tube_radius,
            "min_distance": self.min_distance,
            "closest": self.closest,
        }


@dataclass(frozen=True)
class Exported:
    """An export job's answer: the file's ``content`` and ``name`` (handed to the download, never polled)."""

    content: bytes
    name: str

    def to_json(self) -> JsonObject:
        """Return the JSON form (the name and size; the bytes travel as the download)."""
        return {"name": self.name, "bytes": len(self.content)}


@dataclass(frozen=True)
class Clearance:
    """The embedding check of a design: closest approach against ``min_separation``, and where (edge, curves)."""

    min_distance: float
    min_separation: float
    edge: int | None = None
    curves: tuple[int, int] | None = None
    message: str | None = None

    @property
    def ok(self) -> bool:
        """Whether the strands keep ``min_separation`` apart."""
        return self.min_distance >= self.min_separation

    def to_json(self) -> JsonObject:
        """Return the JSON form (``edge``, ``curves`` and ``message`` only when known)."""
        out: JsonObject = {"min_distance": self.min_distance, "min_separation": self.min_separation, "ok": self.ok}
        if self.curves is not None:
            out.update(edge=self.edge, curves=list(self.curves))
        if self.message is not None:
            out["message"] = self.message
        return out


JobResult: TypeAlias = Identified | Solved | RelaxedCurves | Exported | Clearance


@dataclass(frozen=True)
class JobState:
    """A job as the page polls it: ``state``, seconds ``elapsed``, the last ``progress``, ``result`` or ``error``."""

    id: int
    kind: JobKind
    state: JobStatus
    elapsed: float
    progress: Progress | None = None
    result: JobResult | None = None
    error: str | None = None

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {
            "id": self.id,
            "kind": self.kind,
            "state": self.state,
            "elapsed": self.elapsed,
            "progress": {} if self.progress is None else self.progress.to_json(),
            "result": None if self.result is None else self.result.to_json(),
            "error": self.error,
        }


@dataclass(frozen=True)
class OpenedDesign:
    """A design file opened: the held scaffold's ``key`` and what the page loads (labels, nulls, block, view)."""

    key: str
    labels: tuple[int, ...]
    nulls: tuple[int, ...]
    block: tuple[int, ...] | None
    view: Mapping[str, tuple[float, float, float]] | None
    name: str

    def to_json(self) -> JsonObject:
        """Return the JSON form (labels past 2**53 as decimal strings: exact in JavaScript)."""
        return {
            "key": self.key,
            "labels": page_labels(self.labels),
            "nulls": list(self.nulls),
            "block": None if self.block is None else list(self.block),
            "view": None if self.view is None else {k: list(v) for k, v in self.view.items()},
            "name": self.name,
        }


def page_labels(labels: Sequence[int] | np.ndarray) -> list[int | str]:
    """Labels as the page reads them: integers, or decimal strings past 2**53 (exact in JavaScript)."""
    return [str(int(t)) if abs(int(t)) > 2**53 else int(t) for t in labels]


@dataclass(frozen=True)
class Thumbs:
    """``/api/thumbnails``: one SVG per design and the common names of their table names."""

    thumbs: tuple[str, ...]
    common_names: tuple[str | None, ...]

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {"thumbs": list(self.thumbs), "common_names": list(self.common_names)}


@dataclass(frozen=True)
class Stem:
    """``/api/filename``: the file name stem of a design."""

    stem: str

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {"stem": self.stem}


class CatalogInfo(TypedDict):
    """The catalog as ``/api/info`` describes it (rows and columns once read)."""

    path: str
    scaffold: str | None
    label_set: object
    symmetry: object
    ready: bool
    error: str | None
    rows: NotRequired[int]
    columns: NotRequired[list[str]]
    load_seconds: NotRequired[float]


class CatalogPage(TypedDict):
    """One page of catalog rows (``ready`` false while the catalog is read: then its info only)."""

    ready: bool
    total: NotRequired[int]
    offset: NotRequired[int]
    columns: NotRequired[list[str]]
    rows: NotRequired[list[list[object]]]
    labels: NotRequired[list[list[int]]]
    seconds: NotRequired[float]


@dataclass(frozen=True)
class Info:
    """``/api/info``: what the page needs first."""

    version: str
    builtins: tuple[str, ...]
    initial: str
    exports: tuple[str, ...]
    catalog: CatalogInfo | None
    max_upload: int
    design: OpenedDesign | None

    def to_json(self) -> JsonObject:
        """Return the JSON form."""
        return {
            "version": self.version,
            "builtins": list(self.builtins),
            "initial": self.initial,
            "exports": list(self.exports),
            "catalog": self.catalog,
            "max_upload": self.max_upload,
            "design": None if self.design is None else self.design.to_json(),
        }


class ScaffoldView(TypedDict):
    """What the page draws and edits of a scaffold (flat ``float`` lists: three per point)."""

    key: str
    name: str
    origin: str
    n_vertices: int
    n_edges: int
    n_faces: int
    n_corners: int
    dim: int
    vertices: list[list[float]]
    corner_positions: list[float]
    face_starts: list[int]
    face_centroids: list[float]
    corner_face: list[int]
    side_edge: list[int]
    edge_points: list[float]
    edge_names: list[str]
    edge_degrees: list[int]
    labels: list[int] | None
    nulls: list[int] | None
    lattice: NotRequired[list[list[float]]]
    block: NotRequired[list[int]]


class OrbitView(TypedDict):
    """The edge orbits of a scaffold under its rotations, and each edge's orbit."""

    orbits: list[list[int]]
    orbit_of: list[int]


class StrandView(TypedDict):
    """One strand of a design: ``loop``, ``open`` or ``thread``, its length, period, edges and first port."""

    kind: str
    length: int
    period: int | None
    closed: bool
    edges: list[int]
    port: int


class CurvesView(TypedDict):
    """The strand curves: a key each, the points (base64 ``float32``) of those the page does not hold."""

    keys: list[str]
    points: str
    sent: list[bool]
    counts: list[int]
    closed: list[bool]
    strand: list[int]
    copy: list[int]
    radius: float
    scale: float


class Failure(TypedDict):
    """Why a design has no curves, and the edge the message names (if any)."""

    message: str
    edge: int | None


class RelaxedClearance(TypedDict):
    """The clearance the relaxation measured (``None``: no distinct pieces near)."""

    min_distance: float | None
    min_separation: float
    ok: bool


class DesignView(TypedDict):
    """``/api/design``: the trace's summary, the strands, and the curves (or the failure, on its edge)."""

    components: int
    holds_together: bool
    pieces: int
    strands: list[StrandView]
    labels: list[int | str]
    nulls: list[int]
    periodic: bool
    closed_loops: NotRequired[int]
    infinite_threads: NotRequired[int]
    lift_index: NotRequired[int | None]
    failure: NotRequired[Failure]
    relaxed: NotRequired[bool]
    clearance: NotRequired[RelaxedClearance]
    curves: NotRequired[CurvesView]
    timing: NotRequired[dict[str, float]]


class DiagramView(TypedDict):
    """``/api/diagram``: the SVG and its crossings, PD code and linking matrix (or why there is none)."""

    svg: str | None
    message: NotRequired[str]
    crossings: NotRequired[int]
    components: NotRequired[int]
    view: NotRequired[str]
    pd: NotRequired[object]
    linking_matrix: NotRequired[list[list[int]] | None]
    writhe: NotRequired[int]
    seconds: NotRequired[float]


Answer: TypeAlias = Record | Mapping[str, object]
"""What an endpoint answers: a record, or a view the page reads as it is."""


def dumps(answer: Answer) -> str:
    """JSON text of an answer (numpy scalars made plain)."""
    data = answer.to_json() if isinstance(answer, Record) else answer
    return json.dumps(data, default=lambda v: v.item() if hasattr(v, "item") else str(v))


# ---- HTTP: bodies, content types, errors

LOCAL_NAMES = ("127.0.0.1", "localhost", "::1")


def error_json(kind: str, message: str) -> JsonObject:
    """Return the JSON of an error answer."""
    return {"error": {"type": kind, "message": message}}


class LocalHostOnly:
    """ASGI middleware: answer only requests addressed to this machine by name (DNS rebinding defence)."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
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


async def json_of(request: Request) -> JsonObject:
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
