"""Knot and link identification of realized strands (extra ``[knots]``).

Pipeline: :func:`lkspace.geometry.realize` -> :func:`lkspace.diagram.project` (generic
projection, PD code) -> spherogram ``simplify('global')`` -> names.

Naming.  The Jones polynomial (regina, no Sage) of the simplified diagram, evaluated
exactly at ``sqrt(t) = 2/3`` and ``3/2`` (its mirror), is looked up in the KnotInfo
(knots up to 13 crossings) and LinkInfo (links up to 11 crossings, every orientation)
tables of ``database_knotinfo``.  Candidates are narrowed by the HOMFLY-PT polynomial
(regina, computed on our diagram and on the table's own PD code, so conventions agree)
and by SnapPy's ``identify()`` of the exterior.  A single remaining table entry is
accepted only if the hyperbolic volume agrees (zero for torus and satellite knots and
links, which ``identify()`` cannot name); otherwise ``name`` is ``None`` and the
invariants are returned.  Names: ``"0_1"``, Rolfsen ``"3_1"``..., Thistlethwaite
``"L2a1"``...; ``mirror`` says whether the structure is the table diagram's mirror image
(``None`` when the knot or link equals its mirror as far as HOMFLY-PT tells).
KnotInfo's ``3_1`` is the right-handed (positive) trefoil.
"""

from __future__ import annotations

import json
from fractions import Fraction
from functools import lru_cache

import numpy as np

from .diagram import DiagramError, project
from .errors import LkspaceError, require
from .geometry import GeometryParams, realize
from .mesh import Scaffold

PURPOSE = "knot identification"
HOMFLY_MAX_CROSSINGS = 40  # HOMFLY-PT (regina) of larger simplified diagrams is skipped
_X = Fraction(2, 3)


def _modules():
    spherogram = require("spherogram", "knots", PURPOSE)
    regina = require("regina", "knots", PURPOSE)
    require("snappy", "knots", PURPOSE)
    dki = require("database_knotinfo", "knots", PURPOSE)
    return spherogram, regina, dki


def _eval_table(poly: str, var: str, x: Fraction) -> Fraction | None:
    value = x * x if var == "t" else x
    try:
        return Fraction(eval(poly.replace("^", "**"), {"__builtins__": {}}, {var: value}))  # noqa: S307
    except Exception:  # noqa: BLE001 - a few table entries are blank
        return None


def laurent_value(laurent, x: Fraction) -> Fraction:
    """Exact value of a regina ``Laurent`` (in ``sqrt(t)``) at ``x``."""
    total = Fraction(0)
    if laurent.isZero():
        return total
    for e in range(laurent.minExp(), laurent.maxExp() + 1):
        c = int(str(laurent[e]))
        if c:
            total += c * x**e
    return total


def _cache_path(version: str) -> str:
    import os

    root = os.environ.get("LKSPACE_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "lkspace")
    return os.path.join(root, f"knot-tables-{version}-v1.pickle")


@lru_cache(maxsize=1)
def tables() -> dict:
    """Jones fingerprints of the KnotInfo and LinkInfo tables: ``{value: [entry, ...]}``.

    Built once from ``database_knotinfo`` (a few seconds) and kept in a pickle under
    ``$LKSPACE_CACHE`` (default ``~/.cache/lkspace``), keyed by the database version.
    """
    import os
    import pickle

    from .io.atomic import write_bytes

    _, _, dki = _modules()
    path = _cache_path(str(getattr(dki, "version", lambda: "0")()))
    if os.path.exists(path):
        try:
            with open(path, "rb") as fh:
                return pickle.load(fh)
        except Exception:  # noqa: BLE001 - a broken cache is rebuilt
            pass
    index = _build_tables(dki)
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        write_bytes(path, pickle.dumps(index, protocol=pickle.HIGHEST_PROTOCOL))
    except OSError:
        pass
    return index


def _build_tables(dki) -> dict:
    index: dict = {}

    def add(entry):
        index.setdefault(entry["fp"], []).append(entry)

    for row in dki.link_list():
        name = row.get("name")
        if not name or name == "Name" or not row.get("jones_polynomial"):
            continue
        fp = _eval_table(row["jones_polynomial"], "t", _X)
        if fp is None:
            continue
        add(
            {
                "name": name,
                "table_name": name,
                "components": 1,
                "pd": row.get("pd_notation"),
                "fp": fp,
                "crossings": int(row.get("crossing_number") or 0),
                "volume": _float(row.get("volume")),
            }
        )
    for row in dki.link_list(proper_links=True):
        name = row.get("name")
        if not name or name == "Name" or not row.get("jones_polynomial"):
            continue
        fp = _eval_table(row["jones_polynomial"], "x", _X)
        if fp is None:
            continue
        pd = row.get("pd_notation_vector")
        add(
            {
                "name": name.split("{")[0],
                "table_name": name,
                "components": int(row.get("components") or 0),
                "pd": pd.replace("{", "[").replace("}", "]") if pd else None,
                "fp": fp,
                "crossings": int(row.get("crossing_number") or 0),
                "volume": _float(row.get("volume")),
            }
        )
    return index


def _float(text) -> float | None:
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def _homfly(regina, pd, mirror=False) -> str:
    link = regina.Link.fromPD(pd)
    if mirror:
        link.changeAll()
    return str(link.homfly())


def _identify_names(link) -> tuple[list[str], float | None]:
    """SnapPy's names of the exterior (``[]`` if not hyperbolic) and its volume."""
    try:
        exterior = link.exterior()
        hyperbolic = exterior.solution_type() == "all tetrahedra positively oriented"
        volume = float(exterior.volume()) if hyperbolic else 0.0
        names = [str(m).split("(")[0] for m in exterior.identify()] if hyperbolic else []
        return names, volume
    except Exception:  # noqa: BLE001 - SnapPy may fail on a degenerate exterior
        return [], None


def name_diagram(pd: list, n_components: int) -> dict:
    """Name one non-split link diagram given by its PD code.

    Returns
    -------
    dict
        ``name`` (or ``None``), ``table_name``, ``mirror``, ``candidates`` and invariants
        ``crossings`` (simplified diagram), ``jones``, ``homfly``, ``volume``.
    """
    spherogram, regina, _ = _modules()
    out = {"name": None, "table_name": None, "mirror": None, "candidates": []}
    if not pd:
        out.update(crossings=0, jones="1", homfly=None, volume=0.0)
        if n_components == 1:
            out.update(name="0_1", table_name="0_1")
        return out
    rl = regina.Link.fromPD(pd)
    jones = rl.jones()
    out["crossings"] = len(pd)
    out["jones"] = str(jones)
    fp, fp_mirror = laurent_value(jones, _X), laurent_value(jones, 1 / _X)
    index = tables()
    cands = [(e, False) for e in index.get(fp, [])] + [(e, True) for e in index.get(fp_mirror, [])]
    cands = [(e, m) for e, m in cands if e["components"] == n_components and e["crossings"] <= len(pd)]
    homfly = str(rl.homfly()) if len(pd) <= HOMFLY_MAX_CROSSINGS else None
    if homfly is not None and cands:
        cands = [(e, m) for e, m in cands if e["pd"] and _homfly(regina, json.loads(e["pd"]), m) == homfly]
    link = spherogram.Link(pd)
    names, volume = _identify_names(link)
    out["volume"] = volume
    if len({e["name"] for e, _ in cands}) > 1 and names:
        cands = [(e, m) for e, m in cands if e["name"] in names or _knot_alias(e["name"]) in names]
    out["homfly"] = homfly
    out["candidates"] = sorted({e["table_name"] + (" (mirror)" if m else "") for e, m in cands})
    if len({e["name"] for e, _ in cands}) != 1:
        return out
    entry = cands[0][0]
    table_volume = entry["volume"] or 0.0
    if volume is None or abs(table_volume - volume) > 1e-4 * max(1.0, table_volume):
        out["note"] = f"volume {volume} differs from {entry['table_name']}'s {table_volume}"
        return out
    mirrors = {m for _, m in cands}
    out.update(name=entry["name"], table_name=entry["table_name"])
    out["mirror"] = mirrors.pop() if len(mirrors) == 1 else None
    if out["mirror"] is not None and n_components == 1:
        out["chiral_name"] = ("m" if out["mirror"] else "") + entry["name"]
    return out


def _knot_alias(name: str) -> str:
    """KnotInfo ``11a_1`` is SnapPy's ``K11a1``; Rolfsen names are shared."""
    import re

    m = re.fullmatch(r"(\d+)([an])_(\d+)", name)
    return f"K{m[1]}{m[2]}{m[3]}" if m else name


def _one_based(pd) -> list:
    """spherogram numbers PD edges from 0; KnotTheory and regina from 1."""
    return [[int(v) + 1 for v in x] for x in pd]


def name_pd(pd: list, n_components: int) -> dict:
    """Simplify and name the link of a PD code (1-based, KnotTheory convention).

    Split links are named piece by piece (``name`` stays ``None``, ``pieces`` lists
    them); a composite whose prime factors are all in the tables gets the name
    ``"3_1#4_1"`` (``prime: False``, ``factors``).
    """
    spherogram, _, _ = _modules()
    if not pd:
        out = {
            "name": "0_1" if n_components == 1 else None,
            "crossings": 0,
            "split": n_components > 1,
            "mirror": None,
            "jones": "1",
        }
        if n_components > 1:
            out["pieces"] = ["0_1"] * n_components
            out["note"] = f"unlink of {n_components} components"
        return out
    link = spherogram.Link(pd)
    n_free = n_components - len(link.link_components)
    link.simplify("global")
    pieces = link.split_link_diagram()
    n_free += link.unlinked_unknot_components
    if len(pieces) + n_free > 1:
        named = [name_pd(_one_based(p.PD_code()), len(p.link_components)) for p in pieces]
        out = {
            "name": None,
            "split": True,
            "crossings": sum(p.get("crossings", 0) for p in named),
            "pieces": [p["name"] for p in named] + ["0_1"] * n_free,
            "mirror": None,
        }
        out["note"] = "split link: " + " + ".join(str(p) for p in out["pieces"])
        return out
    simple = _one_based(link.PD_code())
    out = name_diagram(simple, n_components)
    out["split"] = False
    if out["name"] is None and simple:
        factors = link.copy().deconnect_sum()
        if len(factors) > 1:
            named = [name_diagram(_one_based(f.PD_code()), len(f.link_components)) for f in factors]
            out["factors"] = [f.get("chiral_name") or f["name"] for f in named]
            if all(f["name"] for f in named):
                out.update(name="#".join(sorted((f["name"] for f in named), key=_name_key)), prime=False, mirror=None)
                if all(f.get("chiral_name") or f["mirror"] is None for f in named) and n_components == 1:
                    out["chiral_name"] = "#".join(sorted(out["factors"], key=_name_key))
    if n_components == 1 and simple:
        try:
            hfk = link.knot_floer_homology()
            out["knot_floer"] = {k: hfk[k] for k in ("seifert_genus", "fibered", "tau", "total_rank", "L_space_knot")}
        except Exception:  # noqa: BLE001 - optional invariant
            pass
    return out


def _name_key(name: str):
    import re

    m = re.match(r"m?L?(\d+)", name)
    return (int(m[1]) if m else 0, name)


def identify_curves(curves, seed: int = 0) -> dict:
    """Identify the link formed by closed polylines ``curves`` (list of ``(n_k, 3)``).

    Returns
    -------
    dict
        ``components``, ``name``, ``linking_matrix``, ``projected_crossings`` and the
        results of :func:`name_pd` (invariants, see the module docstring).
    """
    diagram = project(curves, seed=seed)
    out = {
        "components": len(curves),
        "linking_matrix": diagram.linking_matrix().tolist(),
        "projected_crossings": diagram.n_crossings,
    }
    out.update(name_pd(diagram.pd, len(curves)))
    return out


def identify(scaffold: Scaffold, twists=None, nulls=None, params: GeometryParams | None = None, seed: int = 0) -> dict:
    """Knot/link type of ``scaffold`` labelled by ``twists`` (SPEC §2 ``identify``).

    Examples
    --------
    >>> from lkspace import load
    >>> r = identify(load("dihedron:3"), 1)
    >>> r["components"], r["name"], r["mirror"]
    (1, '3_1', False)
    """
    real = realize(scaffold, twists, nulls, params)
    if not real.closed.all():
        tr = real.trace
        reason = "open strands (null edge-sides)" if not tr.closed.all() else "infinite periodic threads"
        raise LkspaceError(f"{scaffold.name}: cannot identify a structure with {reason}")
    for attempt in range(3):  # a rare non-generic projection: turn again
        try:
            out = identify_curves(real.curves, seed=seed + attempt)
            break
        except DiagramError:
            if attempt == 2:
                raise
    out["min_distance"] = real.min_distance
    return out


_WORKER: dict = {}


def _init_worker(scaffold: Scaffold, seed: int) -> None:
    _WORKER["scaffold"], _WORKER["seed"] = scaffold, seed


def _identify_row(labels) -> dict:
    try:
        r = identify(_WORKER["scaffold"], np.asarray(labels, np.int64), seed=_WORKER["seed"])
        return {
            "knot_name": r["name"],
            "components": r["components"],
            "split": r.get("split"),
            "mirror": r.get("mirror"),
            "crossings": r.get("crossings"),
            "jones": r.get("jones"),
            "linking_matrix": json.dumps(r["linking_matrix"]),
            "error": None,
        }
    except LkspaceError as exc:
        return {
            "knot_name": None,
            "components": None,
            "split": None,
            "mirror": None,
            "crossings": None,
            "jones": None,
            "linking_matrix": None,
            "error": str(exc),
        }


COLUMNS = ["knot_name", "components", "split", "mirror", "crossings", "jones", "linking_matrix", "error"]


def identify_batch(scaffold: Scaffold, labels_2d, processes: int = 1, seed: int = 0, progress: bool | None = None):
    """Identify many designs of one scaffold: a ``pandas.DataFrame``, one row per design.

    Parameters
    ----------
    scaffold : Scaffold
    labels_2d : (n_designs, n_edges) int
    processes : int
        Worker processes (``1``: in this process).  Workers are forked and receive the
        scaffold once; rows travel in chunks.
    seed : int
        Seed of the generic projection.
    progress : bool, optional
        Show a progress bar on stderr (default: when stderr is a terminal).

    Returns
    -------
    pandas.DataFrame
        Columns ``knot_name`` (missing when unknown or split), ``components``, ``split``,
        ``mirror``, ``crossings`` (simplified diagram), ``jones``, ``linking_matrix`` (JSON
        text) and ``error`` (missing unless the design could not be identified, e.g.
        open strands), in the order of ``labels_2d``.

    Examples
    --------
    >>> from lkspace import load
    >>> identify_batch(load("dihedron:3"), [[1, 1, 1], [1, 0, 0]])["knot_name"].tolist()
    ['3_1', '0_1']
    """
    import sys

    import pandas as pd

    _modules()
    tables()  # loaded once, shared by forked workers
    labels_2d = np.asarray(labels_2d, np.int64).reshape(-1, scaffold.n_edges)
    if progress is None:
        progress = sys.stderr.isatty()
    _init_worker(scaffold, seed)
    chunk = max(1, min(64, len(labels_2d) // (4 * max(processes, 1)) or 1))
    if processes > 1 and len(labels_2d) > 1:
        import multiprocessing as mp

        pool = mp.get_context("fork").Pool(processes, initializer=_init_worker, initargs=(scaffold, seed))
        rows_iter = pool.imap(_identify_row, labels_2d, chunksize=chunk)
    else:
        pool = None
        rows_iter = map(_identify_row, labels_2d)
    try:
        if progress:
            from rich.console import Console
            from rich.progress import track

            rows = list(
                track(
                    rows_iter,
                    total=len(labels_2d),
                    description="identifying",
                    transient=True,
                    console=Console(stderr=True),
                )
            )
        else:
            rows = list(rows_iter)
    finally:
        if pool is not None:
            pool.close()
            pool.join()
    return pd.DataFrame(rows, columns=COLUMNS)
