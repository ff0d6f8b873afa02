"""What the page sends: one frozen record per request body, each with one validating ``from_json``.

A body that is not of the record's shape is refused in ``from_json``, with a one-line message
naming the field (a :class:`~lkspace.errors.UsageError`, :class:`~lkspace.studio.wire.BadRequest`
or :class:`~lkspace.errors.LabelError`, answered 4xx), so the endpoints only ever see
well-typed values.  What a request means on a scaffold (a label list as long as its edges, a
side index in range, a block that fits) is checked where the scaffold is known
(:mod:`~lkspace.studio.designs`, :mod:`~lkspace.studio.app`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from ..errors import LabelError, LkspaceError, UsageError
from ..io.json_values import JsonObject
from .wire import BadRequest

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
FormObjective = Literal["min-abs", "min-nonzero"]
"""The objectives the solve form offers (``None``: any design); :func:`lkspace.solve` checks its own again."""

View = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]
"""The page's camera axes ``(right, up, back)``."""


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


def page_id(data: Mapping[str, object]) -> str:
    """Return the ``page`` field: the id a page sends (``X-Lkspace-Page``) so its jobs are its own ("" when absent)."""
    page = data.get("page", "")
    if not isinstance(page, str) or not re.fullmatch(r"[A-Za-z0-9_-]{0,64}", page):
        raise BadRequest("page: an id of at most 64 letters, digits, - or _ (the page makes one when it opens)")
    return page


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
    """A design: scaffold ``key``, ``labels`` (``None``: its own), null ``nulls`` sides, ``block``, asking ``page`` (:func:`page_id`)."""

    key: str
    labels: tuple[int, ...] | None = None
    nulls: tuple[int, ...] | None = None
    block: tuple[int, ...] | None = None
    page: str = ""

    @classmethod
    def from_json(cls, data: JsonObject) -> DesignRequest:
        """Read the request body (``/api/clearance``, ``/api/identify``, ``/api/filename``)."""
        return cls(
            scaffold_key(data),
            label_list(data.get("labels")),
            integer_list(data.get("nulls"), LabelError("nulls: expected a list of side indices (integers)")),
            integer_list(data.get("block"), UsageError("block: a list of sizes, one per lattice direction")),
            page_id(data),
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
        if have is not None and not (isinstance(have, list) and all(isinstance(v, str) and len(v) <= 32 for v in have)):
            raise UsageError("have: expected a list of curve keys (strings from an earlier answer)")
        if have is not None and len(have) > MAX_HAVE:
            raise UsageError(f"have: {len(have):,} curve keys > {MAX_HAVE:,}; send the keys of the curves drawn")
        keys = frozenset(v for v in have or () if isinstance(v, str))  # every one is, checked above
        return cls(DesignRequest.from_json(data), flag(data, "relax"), keys)


@dataclass(frozen=True)
class DiagramRequest:
    """``/api/diagram``: a design, the page's ``view`` (``None``: the generic rotation), or ``simplified``."""

    design: DesignRequest
    view: View | None = None
    simplified: bool = False

    @classmethod
    def from_json(cls, data: JsonObject) -> DiagramRequest:
        """Read the request body."""
        return cls(DesignRequest.from_json(data), view_axes(data.get("view")), flag(data, "simplified"))


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
    objective: FormObjective | None = None
    count: int = 5
    time_limit: float = 60.0
    page: str = ""

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
            raise BadRequest("time_limit: seconds of wall-clock time in (0, 600]")
        label_set = data.get("label_set", "-2..2")
        if not isinstance(label_set, str) or len(label_set) > 200:
            raise BadRequest("label_set: text like -2..2 or -1,1")
        parse_label_set(label_set)  # refused here, not in the worker
        objective: FormObjective | None
        match data.get("objective"):
            case None:
                objective = None
            case "min-abs" | "min-nonzero" as chosen:
                objective = chosen
            case _:
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
            page_id(data),
        )

    def options(self) -> dict[str, object]:
        """Return the query's keyword arguments of :func:`lkspace.solve` (``count`` and ``time_limit`` go to its options)."""
        return {
            "components": self.components,
            "label_set": self.label_set,
            "no_zero": self.no_zero,
            "fixes": dict(self.fixes),
            "objective": self.objective,
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
            match op:
                case "==" | "!=" | "<" | "<=" | ">" | ">=" | "contains":
                    triples.append((column, op, value))
                case _:
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
