"""A labelled design as the page draws it: trace, strand curves (binary), clearance, exports.

Each strand of the answer lists the edges it passes (:func:`strand_edges`), which the page
lights when the strand is clicked.

Every answer comes from :func:`lkspace.trace` and :func:`lkspace.realize`; curves travel
as base64 ``float32`` arrays so a redraw of ~100,000 points costs a few milliseconds.
The redraw realizes without measuring the clearance (``embedding="later"``); the page asks for
the measurement (:func:`clearance`) right after, so a design appears at once and its
embedding verdict follows.  Asked with a ``relaxer`` (the studio's relax job), the curves
are the relaxed ones (:func:`lkspace.relax`), kept apart from the default ones in the cache.
"""

from __future__ import annotations

import os
import re
import tempfile
import threading
import time
from collections import ChainMap, OrderedDict
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from .. import PictureOptions, Realization, RealizeOptions, Scaffold, Trace, export, realize, trace
from ..errors import GeometryError, LabelError, TooLargeError, UsageError
from ..formats.registry import FORMATS
from ..geometry.clearance import check_embedding
from ..geometry.realization import StrandCurve, realize_reusing
from ..io.scaffold_json import format_scaffold_json
from ..model.validation import validate_labels, validate_nulls
from .answers import Clearance, DesignView, StrandView, page_labels
from .curves import curves_view
from .filenames import design_stem

MAX_STUDIO_POINTS = 600_000
"""Most curve points a redraw realizes, block copies included (as tubes, about 3 million vertices in the browser)."""

MAX_BLOCK = 64
"""Most lattice copies of a periodic block the page may ask for."""

DEFAULT_BLOCK_FACES = 1_200
"""Most faces of the block a periodic scaffold opens with (a redraw of about half a second)."""

MAX_BLOCK_FACES = 4_000
"""Most faces a periodic block may draw (copies × faces of the cell; past it the curves outgrow :data:`MAX_STUDIO_POINTS`)."""

EXPORTS = ("json", *(ext[1:] for ext in FORMATS), "oxdna")
"""Download formats: the scaffold file with labels, every format of the export registry, and DNA (a zip of
the oxDNA and oxView files, ``docs/dna.md``)."""

MAX_EXPORT_POINTS = 400_000
"""Most curve points of a downloaded file (tubes are 12 vertices a point)."""


def labels_from_page(scaffold: Scaffold, labels: Sequence[int] | None) -> np.ndarray:
    """``(n_edges,) int64`` from the page's labels (``None``: the scaffold's own, else zeros)."""
    if labels is None:
        if scaffold.labels is None:
            return np.zeros(scaffold.n_edges, np.int64)
        return scaffold.labels
    if len(labels) != scaffold.n_edges:
        raise LabelError(f"{scaffold.name}: expected {scaffold.n_edges} twist labels (one per edge), got {len(labels)}")
    try:
        array = np.array(labels, dtype=np.int64)
    except OverflowError:  # past int64: validate_labels names the edge and the range
        array = np.array(labels, dtype=object)
    return validate_labels(scaffold, array)


def parse_nulls(scaffold: Scaffold, sides: Sequence[int] | None) -> np.ndarray | None:
    """Null edge-sides ``(n_corners,) bool`` from the page's side indices (``None``: the scaffold's own)."""
    if sides is None:
        return scaffold.nulls
    if len(sides) > scaffold.n_corners:
        raise LabelError(f"nulls: {len(sides)} sides, but {scaffold.name} has {scaffold.n_corners}")
    if any(not 0 <= v < scaffold.n_corners for v in sides):  # before numpy: 10**30 fits no int64
        raise LabelError(f"nulls: side indices in 0..{scaffold.n_corners - 1}")
    return validate_nulls(scaffold, np.array(sides, dtype=np.int64))


def parse_block(scaffold: Scaffold, sizes: Sequence[int] | None) -> np.ndarray | None:
    """Lattice translations ``(n, dim)`` of the page's block sizes ``[A, B, C]`` (``None``: one cell).

    A block on a finite scaffold is refused (:class:`~lkspace.errors.UsageError`): it has no lattice to copy along.
    """
    if sizes is None:
        return None
    if not scaffold.periodic:
        raise UsageError("block: this scaffold is finite (no lattice to copy along); send no block")
    if len(sizes) != scaffold.dim:
        raise UsageError(f"block: give {scaffold.dim} sizes for a {scaffold.dim}D lattice")
    if not all(1 <= v <= MAX_BLOCK for v in sizes):
        raise UsageError(f"block: sizes must be integers in 1..{MAX_BLOCK}")
    copies = int(np.prod(sizes))
    if copies > MAX_BLOCK:
        raise TooLargeError(f"block: {copies} copies > {MAX_BLOCK}")
    if copies > 1 and copies * scaffold.n_faces > MAX_BLOCK_FACES:
        size, fits = ("x".join(map(str, s)) for s in (sizes, default_block(scaffold)))
        raise TooLargeError(
            f"block {size}: {copies} copies of {scaffold.n_faces:,} faces make {copies * scaffold.n_faces:,} faces"
            f" > {MAX_BLOCK_FACES:,} the studio draws at once; choose a smaller block, such as {fits}"
        )
    grids = np.meshgrid(*[np.arange(n) for n in sizes], indexing="ij")
    return np.column_stack([g.reshape(-1) for g in grids])


def default_block(scaffold: Scaffold) -> list[int]:
    """Return the block a periodic scaffold opens with: 2x2x2 (3x3 in 2D), smaller past :data:`DEFAULT_BLOCK_FACES` drawn."""
    side = 2 if scaffold.dim == 3 else 3
    while side > 1 and side**scaffold.dim * scaffold.n_faces > DEFAULT_BLOCK_FACES:
        side -= 1
    return [side] * scaffold.dim


def edge_named(scaffold: Scaffold, message: str) -> int | None:
    """Return the edge a geometry message names (``edge 3-7`` or ``edge 3-7[0,1,0]``), if any."""
    names = {scaffold.edge_name(e): e for e in range(scaffold.n_edges)}
    for found in re.findall(r"edge (\d+-\d+(?:\[[-\d,]+\])?)", message):
        if found in names:
            return names[found]
    return None


def nearest_edge(scaffold: Scaffold, point: np.ndarray) -> int:
    """Return the edge of the (unit-cell) scaffold nearest to ``point``."""
    pa, pb = scaffold.edge_points[:, 0], scaffold.edge_points[:, 1]
    v = pb - pa
    s = np.clip(np.sum((point - pa) * v, axis=1) / np.maximum(np.sum(v * v, axis=1), 1e-300), 0, 1)
    return int(np.argmin(np.linalg.norm(pa + s[:, None] * v - point, axis=1)))


def strand_edges(tr: Trace) -> list[list[int]]:
    """Return the scaffold edges each strand passes (owns a port of a side of), sorted, one list a strand."""
    edge_of_port = np.repeat(tr.scaffold.side_edge, 2)
    pairs = np.unique(np.column_stack([tr.port_strand, edge_of_port]), axis=0)
    starts = np.searchsorted(pairs[:, 0], np.arange(tr.components + 1))
    return [pairs[starts[k] : starts[k + 1], 1].tolist() for k in range(tr.components)]


class Cache:
    """The last few realizations, keyed by scaffold, labels, nulls, block and relaxed or not (for the clearance and reuse).

    With a default realization it keeps its curves by strand key
    (:func:`~lkspace.geometry.realization.realize_reusing`): the next design of the
    same scaffold builds only the strands these do not hold.
    """

    def __init__(self, size: int = 8) -> None:
        self._items: OrderedDict[bytes, Realization] = OrderedDict()
        self._strands: dict[bytes, tuple[str, dict[bytes, StrandCurve]]] = {}
        self._size = size
        self._lock = threading.Lock()

    @staticmethod
    def key(
        key: str, labels: np.ndarray, nulls: np.ndarray | None, block: np.ndarray | None, relaxed: bool = False
    ) -> bytes:
        """Return the cache key of a design (its default or its ``relaxed`` curves)."""
        parts = [key.encode(), labels.tobytes(), b"-" if nulls is None else nulls.tobytes()]
        return b"|".join([*parts, b"-" if block is None else block.tobytes(), b"relaxed" if relaxed else b"-"])

    def get(self, key: bytes) -> Realization | None:
        """Return the realization under ``key``, if kept."""
        with self._lock:
            return self._items.get(key)

    def put(
        self, key: bytes, real: Realization, scaffold: str = "", strands: dict[bytes, StrandCurve] | None = None
    ) -> None:
        """Keep ``real`` under ``key`` (forgetting the oldest past the size), and its curves by strand key."""
        with self._lock:
            self._items[key] = real
            self._items.move_to_end(key)
            if strands:
                self._strands[key] = (scaffold, strands)
            while len(self._items) > self._size:
                old, _ = self._items.popitem(last=False)
                self._strands.pop(old, None)

    def strands(self, scaffold: str) -> ChainMap[bytes, StrandCurve]:
        """Return the curves kept by strand key for the designs of ``scaffold`` (newest first)."""
        with self._lock:
            kept = [self._strands[k][1] for k in reversed(self._items) if self._strands.get(k, ("",))[0] == scaffold]
        return ChainMap(*kept)


def trace_view(tr: Trace) -> DesignView:
    """Return the trace's summary as the page shows it: components, strands (kind, length, period, edges, port)."""
    scaffold = tr.scaffold
    kinds, lengths = tr.strand_kinds, tr.strand_lengths.tolist()
    periods = tr.periods.tolist() if scaffold.periodic else [None] * tr.components
    ports = first_ports(tr.steps, tr.strand_starts)
    strands: list[StrandView] = [
        {
            "kind": kind,
            "length": length,
            "period": period if kind != "open" else None,
            "closed": kind == "loop",
            "edges": edges,
            "port": port,
        }
        for kind, length, period, edges, port in zip(kinds, lengths, periods, strand_edges(tr), ports, strict=True)
    ]
    out: DesignView = {
        "components": tr.components,
        "holds_together": tr.holds_together,
        "pieces": tr.n_pieces,
        "strands": strands,
        "labels": page_labels(tr.labels),
        "nulls": [] if tr.nulls is None else np.flatnonzero(tr.nulls).tolist(),
        "periodic": scaffold.periodic,
    }
    if scaffold.periodic:
        out["closed_loops"] = kinds.count("loop")
        out["infinite_threads"] = kinds.count("thread")
        out["lift_index"] = tr.holding.lift_index
    return out


def design(
    scaffold: Scaffold,
    labels: np.ndarray,
    nulls: np.ndarray | None,
    block: np.ndarray | None,
    cache: Cache,
    key: str,
    relaxer: Callable[[Realization], Realization] | None = None,
    have: frozenset[str] = frozenset(),
) -> DesignView:
    """Return the page's view of a design: the trace's summary and the strand curves (or the error, on its edge).

    With ``relaxer``, the curves are ``relaxer(realization)`` (kept in the cache); its
    errors (a refused scaffold, a relaxation stopped by a newer one) propagate.  Curves
    whose key is in ``have`` (the page holds them) travel without their points
    (:func:`~lkspace.studio.curves.curves_view`).
    """
    t0 = time.perf_counter()
    tr = trace(scaffold, labels, nulls)
    out = trace_view(tr)
    t1 = time.perf_counter()
    relaxed_key = Cache.key(key, tr.labels, nulls, block, True)
    real = cache.get(relaxed_key) if relaxer is not None else None
    if real is None:
        try:
            options = RealizeOptions(embedding="later", translations=block, trace=tr, max_points=MAX_STUDIO_POINTS)
            real, strands = realize_reusing(scaffold, tr, cache.strands(key), options)
        except (GeometryError, TooLargeError) as exc:
            out["failure"] = {"message": str(exc), "edge": edge_named(scaffold, str(exc))}
            out["timing"] = {"trace": t1 - t0, "realize": time.perf_counter() - t1}
            return out
        cache.put(Cache.key(key, tr.labels, nulls, block), real, key, strands)
        if relaxer is not None:
            real = relaxer(real)
            cache.put(relaxed_key, real)
    out["relaxed"] = relaxer is not None
    if relaxer is not None:  # the relaxation measured its curves (no distinct pieces near: infinite, sent as null)
        best, sep = real.min_distance, real.min_separation
        out["clearance"] = {
            "min_distance": best if np.isfinite(best) else None,
            "min_separation": sep,
            "ok": best >= sep,
        }
    out["curves"] = curves_view(real, have)
    out["timing"] = {"trace": t1 - t0, "realize": time.perf_counter() - t1}
    return out


def first_ports(steps: np.ndarray, starts: np.ndarray) -> list[int]:
    """Return the smallest port of every strand (``starts``: its steps' offsets), a name an edit elsewhere keeps."""
    return np.minimum.reduceat(steps, starts[:-1]).tolist() if len(starts) > 1 else []


def clearance(real: Realization) -> Clearance:
    """Measure the embedding of ``real``: ``min_distance`` against ``min_separation``, and where (the edge)."""
    best, where = check_embedding(real.curves, real.closed, real.min_separation, real.scale)
    if where is None:
        return Clearance(best, real.min_separation)
    point = np.asarray(where.point)
    if real.scaffold.lattice is not None and real.translations is not None:
        shift = real.scaffold.lattice.translate(real.translations[real.copy_of[where.curves[0]]][None])[0]
        point = point - shift
    edge = nearest_edge(real.scaffold, point)
    a, b = (int(c) for c in where.curves)
    found = Clearance(best, real.min_separation, edge, (a, b))
    if found.ok:
        return found
    message = (
        f"strands {a} and {b} come within {best:.3g} (< min_separation {real.min_separation:.3g}) near edge "
        f"{real.scaffold.edge_name(edge)}: the geometry would self-intersect"
    )
    return replace(found, message=message)


def export_bytes(scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray | None, fmt: str) -> tuple[bytes, str]:
    """Return the design written as ``fmt`` (one of :data:`EXPORTS`): ``(content, file name)``."""
    if fmt not in EXPORTS:
        raise UsageError(f"format {str(fmt)[:20]!r}: choose one of {', '.join(EXPORTS)}")
    name = f"{design_stem(scaffold.name, labels, [] if nulls is None else np.flatnonzero(nulls))}.{fmt}"
    if fmt == "json":
        return format_scaffold_json(scaffold, labels, nulls).encode(), name
    if fmt == "oxdna":
        from ..dna.build import build
        from ..dna.oxdna import zip_bytes

        if nulls is not None and nulls.any():
            raise UsageError("DNA export: null edge-sides are not supported (every strand is closed)")
        return zip_bytes(build(scaffold, labels), name[: -len(".oxdna")]), name + ".zip"
    with tempfile.TemporaryDirectory(prefix="lkspace-studio-") as folder:
        path = os.path.join(folder, name)
        real = realize(scaffold, labels, nulls, options=RealizeOptions(max_points=MAX_EXPORT_POINTS))
        export(real, path, options=PictureOptions(title=scaffold.name) if fmt == "png" else None)
        with open(path, "rb") as handle:
            return handle.read(), name
