"""The rows of a DNA catalog: every buildable design of a mesh at one scale, and their check.

At ``nm_per_unit`` each edge allows the labels within ``window`` half turns of its natural
twist (:func:`~lkspace.dna.search.window_labels`, at least 1).  A design is kept when its
strands run antiparallel on every edge, which depends only on its labels mod 2: the
buildable parity patterns are an affine subspace (:mod:`lkspace.dna.parity`), each
confirmed by :func:`~lkspace.dna.model.orient`.  Each pattern is one residue class; its
rows are the product of every edge's window labels of that parity, one row per label
assignment (``orbit_size`` 1), in the order "parity vector in edge order, then labels in
edge order".  :func:`check_dna_rows` recomputes them for ``lkspace verify``; the catalog
itself is written by :mod:`lkspace.catalog.dna_catalog`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from ..design.batch import BATCH_PORTS, holds_batch, trace_batch
from ..design.space import DesignSpace
from ..design.walk import DesignBlock
from ..dna.model import BP_PER_TURN, check_buildable, orient
from ..dna.parity import parity_patterns, parity_system
from ..dna.search import natural_twist, window_labels
from ..errors import CatalogError, LabelError, LkspaceError, TooLargeError
from ..io.scaffold_json import scaffold_from_dict
from ..model.scaffold import Scaffold
from ..strands.tracing import trace
from .batches import gather_blocks
from .columns import INT64_MAX
from .metadata import CatalogMetadata, DnaSetting, Filters
from .options import Selection
from .schema import ROW_GROUP, expected_schema
from .settings import catalog_metadata

if TYPE_CHECKING:
    import pyarrow as pa

    from .verify import CatalogParts

MAX_DNA_ROWS = 1_000_000
"""Most assignments a DNA catalog lists (the buildable ones of every parity pattern), and most patterns."""

CHUNK = 1 << 16
"""Patterns per numpy call when they are counted."""

_smaller = "a DNA catalog lists; use a smaller `window` or a smaller mesh"

DNA_RULE = "every buildable assignment of the windows, in order of (t mod 2 per edge, then t per edge); see docs/dna.md"


@dataclass(frozen=True, eq=False)
class DnaSpace:
    """The buildable designs of a mesh at one scale: the windows and the buildable parity patterns.

    Attributes
    ----------
    space : DesignSpace
        The scaffold with the labels of all windows, symmetry ``none`` (for tracing and codes).
    setting : DnaSetting
    patterns : tuple of int
        The buildable parity patterns the windows reach (:mod:`lkspace.dna.parity`), ascending.
    """

    space: DesignSpace
    setting: DnaSetting
    patterns: tuple[int, ...]

    @property
    def scaffold(self) -> Scaffold:
        """The mesh."""
        return self.space.scaffold

    @cached_property
    def options(self) -> list[list[list[int]]]:
        """Per edge, per parity (0, 1): its window labels of that parity."""
        return [[[t for t in range(lo, hi + 1) if t % 2 == r] for r in (0, 1)] for lo, hi in self.setting.labels]

    @cached_property
    def counts(self) -> np.ndarray:
        """(n_edges, 2) int64: how many window labels of each parity every edge has."""
        return np.array([[len(o) for o in per_edge] for per_edge in self.options], np.int64).reshape(-1, 2)

    @cached_property
    def table(self) -> np.ndarray:
        """(n_edges, 2, max_labels) int8: per edge and parity its window labels (zero-padded)."""
        out = np.zeros((*self.counts.shape, max(1, int(self.counts.max()))), np.int8)
        for e, per_edge in enumerate(self.options):
            for r, labels in enumerate(per_edge):
                out[e, r, : len(labels)] = labels
        return out

    @property
    def assignments(self) -> int:
        """Assignments of the windows (buildable or not)."""
        return math.prod(hi - lo + 1 for lo, hi in self.setting.labels)

    def parities(self, patterns: Sequence[int]) -> np.ndarray:
        """(len(patterns), n_edges) int64: the parity vectors of ``patterns``."""
        n_e = self.scaffold.n_edges
        text = "".join(format(p, f"0{n_e}b") for p in patterns).encode()
        return (np.frombuffer(text, np.uint8).reshape(len(patterns), n_e) - ord("0")).astype(np.int64)

    def expand(self, parities: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Return ``(labels (m, n_edges) int8, row_class (m,) int64)``: every window assignment of each parity vector.

        Each class's rows are lexicographic in edge order (edge 0 slowest).
        """
        n_c, n_e = parities.shape
        e = np.arange(n_e)
        radix = self.counts[e, parities]  # (n_c, n_edges)
        sizes = radix.prod(axis=1)
        row_class = np.repeat(np.arange(n_c), sizes)
        local = np.arange(len(row_class)) - np.repeat(np.cumsum(sizes) - sizes, sizes)
        labels = np.empty((len(row_class), n_e), np.int8)
        for edge in range(n_e - 1, -1, -1):
            n = radix[row_class, edge]
            labels[:, edge] = self.table[edge, parities[row_class, edge], local % n]
            local //= n
        return labels, row_class

    def sizes(self, patterns: Sequence[int]) -> np.ndarray:
        """(len(patterns),) int64: the window assignments of each parity pattern."""
        parities = self.parities(patterns)
        return self.counts[np.arange(parities.shape[1]), parities].prod(axis=1)


def dna_space(
    scaffold: Scaffold,
    nm_per_unit: float,
    window: float = 1.0,
    bp_per_turn: float = BP_PER_TURN,
    max_designs: int = MAX_DNA_ROWS,
) -> DnaSpace:
    """Return the :class:`DnaSpace` of ``scaffold`` at ``nm_per_unit``; refuse one past ``max_designs`` assignments."""
    check_buildable(scaffold, np.ones(scaffold.n_edges, np.int64))
    windows = window_labels(scaffold, nm_per_unit, window, bp_per_turn)
    for e, opts in enumerate(windows):
        if not opts:
            natural = natural_twist(scaffold, nm_per_unit, bp_per_turn)[e]
            raise LabelError(
                f"{scaffold.name}: edge {e} ({scaffold.edge_name(e)}) has no label of at least 1 within {window:g} of its "
                f"natural twist {natural:.2f} at {nm_per_unit:g} nm per unit; use a larger scale or `window`"
            )
    setting = DnaSetting(float(nm_per_unit), float(window), float(bp_per_turn), tuple((w[0], w[-1]) for w in windows))
    union = sorted({t for w in windows for t in w})
    space = DesignSpace(scaffold, np.asarray(union, np.int64), "none")
    if space.n_classes > INT64_MAX:
        raise TooLargeError(
            f"{scaffold.name}: {space.n_classes:,} residue classes, past the int64 codes of a catalog's "
            "residue_class; use a smaller `window` or a smaller mesh"
        )
    fixed = {e: w[0] % 2 for e, w in enumerate(windows) if len(w) == 1}
    listed = parity_patterns(parity_system(scaffold), fixed)
    at = f"{scaffold.name} at {nm_per_unit:g} nm per unit (window {window:g})"
    if listed.count > max_designs:
        raise TooLargeError(f"{at}: {listed.count:,} parity patterns, more than the {max_designs:,} {_smaller}")
    found = DnaSpace(space, setting, ())
    # orient() judges: its buildable patterns form an affine space too, so when it accepts the
    # generators (every pattern is an odd sum of them) it accepts every pattern listed
    if all(_antiparallel(found, p) for p in listed.generators()):
        patterns = list(listed)
    else:  # not expected (tests/test_dna_catalog.py); trust orient() pattern by pattern
        patterns = [p for p in listed if _antiparallel(found, p)]
    total = sum(int(found.sizes(patterns[i : i + CHUNK]).sum()) for i in range(0, len(patterns), CHUNK))
    if total > max_designs:
        raise TooLargeError(f"{at}: {total:,} buildable assignments, more than the {max_designs:,} {_smaller}")
    return replace(found, patterns=tuple(patterns))


def _antiparallel(space: DnaSpace, pattern: int) -> bool:
    """Whether the strands of ``pattern`` orient antiparallel (:func:`~lkspace.dna.model.orient`, the judge)."""
    parities = space.parities([pattern])[0]
    labels = space.table[np.arange(len(parities)), parities, 0].astype(np.int64)
    try:
        orient(trace(space.scaffold, labels))
    except LabelError:
        return False
    return True


def dna_blocks(space: DnaSpace, components: int | None = None) -> Iterator[DesignBlock]:
    """Yield the buildable designs of ``space`` (with ``components`` strands), a run of patterns at a time.

    A run holds at most :data:`~lkspace.design.batch.BATCH_PORTS` ports x patterns of trace
    arrays, as the design walk's batches do.
    """
    ds, n_e = space.space, space.scaffold.n_edges
    batch = max(1, BATCH_PORTS // (2 * space.scaffold.n_corners))
    index = ds.residue_table.lookup[np.arange(n_e)[None, :], space.parities([0, (1 << n_e) - 1])]
    weights = np.array([math.prod(ds.residue_table.n_res[e + 1 :].tolist()) for e in range(n_e)], np.int64)
    for start in range(0, len(space.patterns), batch):
        residues = space.parities(space.patterns[start : start + batch])
        traces = trace_batch(ds, residues)
        keep = np.ones(len(residues), bool) if components is None else traces.components == components
        if not keep.any():
            continue
        residues, traces = residues[keep], traces.select(keep)
        labels, row_class = space.expand(residues)
        codes = index[0, :] * (1 - residues) @ weights + index[1, :] * residues @ weights
        holds = holds_batch(ds, traces, labels, row_class)
        yield DesignBlock(codes, traces.slim(), row_class, labels, np.ones(len(labels), np.int64), holds)


def dna_batches(
    space: DnaSpace, components: int | None = None, max_designs: int | None = None
) -> Iterator[pa.RecordBatch]:
    """Record batches (designs schema) of the buildable designs, about ``ROW_GROUP`` rows each."""
    yield from gather_blocks(dna_blocks(space, components), space.scaffold, max_designs, ROW_GROUP)


def dna_metadata(space: DnaSpace, components: int | None, max_designs: int | None) -> CatalogMetadata:
    """Return the ``lkspace`` metadata of a DNA catalog: the usual keys and ``dna``."""
    meta = catalog_metadata(space.space, Selection(components=components, max_designs=max_designs))
    return replace(meta, assignments=space.assignments, canonical_rule=DNA_RULE, dna=space.setting)


def check_dna_rows(parts: CatalogParts) -> None:
    """Recompute the DNA catalog ``parts`` from its settings; raise unless its rows are exactly those designs."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    settings, path = parts.footer.settings, parts.path
    dna = settings.dna
    assert dna is not None
    info = settings.scaffold
    try:
        if info.data is None:
            raise CatalogError("not stored")
        scaffold = scaffold_from_dict(info.data, info.name)
        if info.content_hash != scaffold.content_hash():
            raise CatalogError("its content hash differs")
        space = dna_space(scaffold, dna.nm_per_unit, dna.window, dna.bp_per_turn)
    except LkspaceError as exc:
        raise CatalogError(f"{path}: the DNA catalog's scaffold or scale does not give its designs: {exc}") from None
    if space.setting != dna:
        raise CatalogError(f"{path}: damaged: its dna windows are not the ones its scaffold has at its scale")
    filters = settings.filters if isinstance(settings.filters, Filters) else Filters()
    components, max_designs = filters.components, filters.max_designs
    try:
        again = dna_metadata(space, components, max_designs).to_json()
    except LkspaceError as exc:
        raise CatalogError(f"{path}: damaged: its filters are not ones lkspace writes: {exc}") from None
    if settings.to_json() != again or parts.footer.shard is not None:  # counts, rule, tolerance: edited and sealed
        raise CatalogError(
            f"{path}: damaged: its recorded settings (counts, filters, shard) are not the ones its scaffold and scale give"
        )
    expected = pa.Table.from_batches(
        list(dna_batches(space, components, max_designs)), schema=expected_schema(settings)
    )
    names = expected.schema.names
    found = pa.concat_tables([pq.read_table(f, columns=names) for f in parts.files]).cast(expected.schema)
    _compare(path, expected, found, dna)


def _compare(path: str, expected: pa.Table, found: pa.Table, dna: DnaSetting) -> None:
    """Raise naming the first row of ``found`` that is not the row ``expected`` holds there."""
    at = f"at {dna.nm_per_unit:g} nm per unit (window {dna.window:g})"
    want = [tuple(x) for x in expected.column("labels").to_pylist()]
    have = [tuple(x) for x in found.column("labels").to_pylist()]
    wanted = set(want)
    for i, labels in enumerate(have):
        if labels not in wanted:
            shown = ",".join(map(str, labels))
            raise CatalogError(f"{path}: row {i}: labels {shown} are not a buildable design {at} (damaged)")
    present = set(have)
    missing = [labels for labels in want if labels not in present]
    if missing:
        shown = ",".join(map(str, missing[0]))
        raise CatalogError(f"{path}: the buildable design {shown} {at} is missing ({len(missing):,} missing; damaged)")
    if have != want:
        first = next(i for i, (a, b) in enumerate(zip(have, want, strict=True)) if a != b)
        raise CatalogError(f"{path}: row {first}: rows out of order or repeated (damaged)")
    for name in expected.schema.names:
        if not found.column(name).equals(expected.column(name)):
            a, b = found.column(name).to_pylist(), expected.column(name).to_pylist()
            first = next(i for i, (x, y) in enumerate(zip(a, b, strict=True)) if x != y)
            raise CatalogError(f"{path}: row {first}: {name} is not what its design gives (damaged)")
