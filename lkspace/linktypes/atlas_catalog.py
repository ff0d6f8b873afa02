"""The atlas of a catalog that ``enumerate --identify`` wrote: its ``knot_name`` column summed into types."""

from __future__ import annotations

import os

import numpy as np

from ..errors import CatalogError
from .atlas import TypeEntry, sort_types
from .examples import EXAMPLES
from .records import AtlasResult, DesignRecord


def atlas_of_catalog(path: str) -> AtlasResult:
    """Sum a catalog identified by ``enumerate --identify`` (its ``knot_name`` column) into atlas types.

    Rows without a name are grouped as ``split (N components)``, ``not in the tables (N
    components)`` (named by key only: no table type has their invariants) or ``unknown (N
    components)``; a type's ``crossings`` is the fewest its designs' simplified diagrams
    keep; its examples are the few simplest designs of each chirality.  The work is columnar (pandas ``groupby``), so big catalogs sum quickly.
    """
    import pandas as pd

    from ..catalog.reader import read_catalog
    from ..knots.key_names import NOT_IN_TABLES

    cat = read_catalog(path)
    frame = cat.frame
    if "knot_name" not in frame.columns:
        raise CatalogError(
            f"{path}: no knot_name column: its designs are not named; write it with `identify=True`, or give a mesh"
        )
    comps = frame["components"].to_numpy(np.int64)
    names = frame["knot_name"].astype(object).where(frame["knot_name"].notna(), None).to_numpy()
    split = frame["split"].fillna(False).to_numpy(bool) if "split" in frame.columns else np.zeros(len(frame), bool)
    status = frame["identify_status"] if "identify_status" in frame.columns else pd.Series([""] * len(frame))
    beyond = status.fillna("").str.startswith(NOT_IN_TABLES.status).to_numpy(bool)
    fallback = np.where(split, "split", np.where(beyond, "not in the tables", "unknown"))
    keys = [n if n is not None else f"{f} ({c} components)" for n, f, c in zip(names, fallback, comps, strict=True)]
    mirror = frame["mirror"] if "mirror" in frame.columns else pd.Series([None] * len(frame))
    chir = np.where(
        mirror.isna().to_numpy(), "undetermined", np.where(mirror.fillna(False).to_numpy(bool), "mirror", "table")
    )
    a = np.abs(cat.labels.astype(np.int64))
    rows = pd.DataFrame(
        {
            "key": keys,
            "components": comps,
            "orbit": frame["orbit_size"].to_numpy(np.int64),
            "sum_abs": a.sum(axis=1),
            "nonzero": (a != 0).sum(axis=1),
            "max_abs": a.max(axis=1) if a.shape[1] else 0,
            "chirality": chir,
            "crossings": frame["crossings"].astype("Int64") if "crossings" in frame.columns else pd.NA,
        }
    )
    ordered = rows.sort_values(["sum_abs", "nonzero", "max_abs"], kind="stable")
    simplest = ordered.groupby("key").head(1)
    examples = ordered.groupby(["key", "chirality"]).head(EXAMPLES)
    types: dict[str, TypeEntry] = {}
    sums = rows.groupby("key").agg(
        designs=("orbit", "size"),
        assignments=("orbit", "sum"),
        components=("components", "first"),
        crossings=("crossings", "min"),
    )
    counts = rows.groupby(["key", "chirality"]).size()
    for key, row in sums.iterrows():
        entry = TypeEntry(
            str(key),
            int(row["components"]),
            crossings=None if pd.isna(row["crossings"]) else int(row["crossings"]),
            designs=int(row["designs"]),
            assignments=int(row["assignments"]),
        )
        for side in entry.chirality:
            entry.chirality[side] = int(counts.get((key, side), 0))
        types[str(key)] = entry
    for i, row in simplest.iterrows():
        entry = types[str(row["key"])]
        entry.simplest = [int(x) for x in cat.labels[int(i)]]
        entry.cost = (int(row["sum_abs"]), int(row["nonzero"]), int(row["max_abs"]))
    sides = {"table": False, "mirror": True, "undetermined": None}
    for i, row in examples.iterrows():  # the few simplest of each chirality, as lookup shows them
        entry = types[str(row["key"])]
        crossings = None if pd.isna(row["crossings"]) else int(row["crossings"])
        record = DesignRecord(entry.name, entry.components, None, sides[row["chirality"]], crossings, None)
        cost = (int(row["sum_abs"]), int(row["nonzero"]), int(row["max_abs"]))
        entry.examples.add(cat.labels[int(i)], cost, record)
    listed = tuple(t.record() for t in sort_types(types))
    return AtlasResult(
        cat.scaffold.name,
        cat.footer.settings.label_set,
        len(frame),
        sum(t.assignments for t in listed),
        listed,
        from_catalog=os.path.abspath(path),
    )
