"""What the studio answers: job states, job results and the views the page draws, each typed.

Small answers are frozen records with one ``to_json`` (:class:`~lkspace.studio.wire.Record`);
the large views the page reads key by key (a scaffold, a design, a diagram, a catalog page)
are ``TypedDict`` s built as they are sent.  Key order is the order the page has always
received.
"""

from __future__ import annotations

import base64
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal, NotRequired, TypeAlias, TypedDict

import numpy as np

from ..geometry.clearance import Closest, closest_json
from .wire import JsonAnswer

JobKind = Literal["identify", "relax", "solve", "clearance", "export"]
JobStatus = Literal["running", "done", "error", "cancelled"]


@dataclass(frozen=True)
class JobStarted:
    """The answer to a request starting a job: its id, or ``None`` with the reason none started."""

    job: int | None
    message: str | None = None

    def to_json(self) -> JsonAnswer:
        """Return the JSON form."""
        return {"job": self.job} if self.message is None else {"job": self.job, "message": self.message}


@dataclass(frozen=True)
class JobProgress:
    """What a worker's long step reports: its description, the work done (as text) and a note."""

    step: str
    done: str
    note: str

    def to_json(self) -> JsonAnswer:
        """Return the JSON form."""
        return {"step": self.step, "done": self.done, "note": self.note}


@dataclass(frozen=True)
class IdentifyAnswer:
    """An identify job's answer: the knot or link type as the page shows it.

    ``name``: the table name, or a split link's type ``split: A + B`` (pieces sorted, as the
    atlas and ``lookup`` name it); ``crossings``: crossings of the simplified diagram found;
    ``least_crossings``: the type's crossing number from the tables (the number in a prime
    table name: ``L6a4`` 6, ``3_1`` 3), ``None`` for a split link, a sum or an unnamed link.
    """

    name: str | None
    common_name: str | None
    status: str
    components: int
    linking_matrix: Sequence[Sequence[int]]
    mirror: bool | None
    split: bool | None
    crossings: int | None
    least_crossings: int | None = None

    def to_json(self) -> JsonAnswer:
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
            "least_crossings": self.least_crossings,
        }


TABLE_NAME = re.compile(r"m?(?:[KL](\d+)[an]\d+|(\d+)_\d+|(\d+)[an]_\d+)")
"""A prime table name: KnotInfo ``3_1``, ``11a_1``; LinkInfo ``L6a4``; HTLinkExteriors ``K15n1``; ``m`` for a mirror."""


def table_crossings(name: str | None) -> int | None:
    """Return the crossing number a prime table name states (``L6a4``: 6, ``m3_1``: 3, ``0_1``: 0), else ``None``."""
    found = TABLE_NAME.fullmatch(name or "")
    return None if found is None else int(next(g for g in found.groups() if g is not None))


@dataclass(frozen=True)
class Solved:
    """A solve job's answer: the solver's summary (:meth:`lkspace.SolveResult.to_dict`) with its designs."""

    summary: Mapping[str, object]
    solutions: tuple[tuple[list[int], int], ...]
    """``(labels, components)`` of every design found."""

    def to_json(self) -> JsonAnswer:
        """Return the JSON form."""
        designs = [{"labels": labels, "components": n} for labels, n in self.solutions]
        return {**self.summary, "solutions": designs}


@dataclass(frozen=True, eq=False)
class RelaxedCurves:
    """A relax job's answer: the relaxed curves ``(n, 3) float64`` each, the tube and the clearance."""

    curves: tuple[np.ndarray, ...]
    tube_radius: float
    min_distance: float
    closest: Closest | None

    def to_json(self) -> JsonAnswer:
        """Return the JSON form: ``points`` (base64 little-endian ``float64``), ``counts``, tube, clearance."""
        points = np.vstack(self.curves).astype("<f8").tobytes()
        return {
            "points": base64.b64encode(points).decode("ascii"),
            "counts": [len(c) for c in self.curves],
            "tube_radius": self.tube_radius,
            "min_distance": self.min_distance,
            "closest": closest_json(self.closest),
        }


@dataclass(frozen=True)
class Exported:
    """An export job's answer: the file's ``content`` and ``name`` (handed to the download, never polled)."""

    content: bytes
    name: str

    def to_json(self) -> JsonAnswer:
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

    def to_json(self) -> JsonAnswer:
        """Return the JSON form (``edge``, ``curves`` and ``message`` only when known)."""
        out: JsonAnswer = {"min_distance": self.min_distance, "min_separation": self.min_separation, "ok": self.ok}
        if self.curves is not None:
            out.update(edge=self.edge, curves=list(self.curves))
        if self.message is not None:
            out["message"] = self.message
        return out


JobResult: TypeAlias = IdentifyAnswer | Solved | RelaxedCurves | Exported | Clearance


@dataclass(frozen=True)
class JobState:
    """A job as the page polls it: ``state``, seconds ``elapsed``, the last ``progress``, ``result`` or ``error``."""

    id: int
    kind: JobKind
    state: JobStatus
    elapsed: float
    progress: JobProgress | None = None
    result: JobResult | None = None
    error: str | None = None

    def to_json(self) -> JsonAnswer:
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

    def to_json(self) -> JsonAnswer:
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

    def to_json(self) -> JsonAnswer:
        """Return the JSON form."""
        return {"thumbs": list(self.thumbs), "common_names": list(self.common_names)}


@dataclass(frozen=True)
class Stem:
    """``/api/filename``: the file name stem of a design."""

    stem: str

    def to_json(self) -> JsonAnswer:
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
    palette: tuple[str, ...]

    def to_json(self) -> JsonAnswer:
        """Return the JSON form."""
        return {
            "version": self.version,
            "builtins": list(self.builtins),
            "initial": self.initial,
            "exports": list(self.exports),
            "catalog": self.catalog,
            "max_upload": self.max_upload,
            "design": None if self.design is None else self.design.to_json(),
            "palette": list(self.palette),
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
    tone: list[int]
    slot: list[int]
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
