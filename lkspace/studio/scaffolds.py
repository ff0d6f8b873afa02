"""The scaffolds a studio page may use, and what the page draws of them.

The page names a scaffold by a built-in name or by the id of one the server holds: a
file named on the command line or an upload (parsed from its bytes; never a path the
page sends).  Ids are content hashes, so a shared link names the same scaffold as long
as a studio holds it.
"""

from __future__ import annotations

import os
import threading
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .. import Scaffold
from .. import scaffolds as builtins
from ..errors import ScaffoldError, TooLargeError, UsageError
from ..io.obj import parse_obj
from ..io.scaffold_json import scaffold_from_dict
from ..io.sources import load
from ..io.text import parse_json
from .answers import OrbitView, ScaffoldView
from .designs import default_block
from .wire import MAX_UPLOAD

MAX_FACES = 20_000
"""Most faces of a scaffold the studio opens (a supercell past it is refused before it is built)."""

MAX_ORBIT_EDGES = 400
"""Most edges of a scaffold whose edge orbits the studio computes (the symmetry search grows fast)."""

MAX_CELLS = 4096
"""Most unit cells of a supercell name accepted from the page."""

MAX_HELD = 32
"""Uploaded scaffolds kept at once (the oldest is forgotten first)."""

MAX_NAME = 200
"""Longest built-in name accepted from the page."""


@dataclass(frozen=True, eq=False)
class Held:
    """A scaffold the page may use: ``key`` (a built-in name or ``id:<hash>``) and where it came from."""

    key: str
    scaffold: Scaffold
    origin: str

    @cached_property
    def orbits(self) -> list[list[int]]:
        """Edge orbits under the rotation group (each a sorted list of edge indices).

        The orbits of ``--invariant rotations`` (:mod:`lkspace.symmetry.edge_orbits`): a symmetric
        edit gives every edge of the orbit the same label, a design fixed by all rotations.
        """
        from ..symmetry.edge_orbits import invariant_edge_orbits

        try:
            orbit = invariant_edge_orbits(self.scaffold, "rotations").orbit
        except Exception:  # noqa: BLE001 - a scaffold without a usable group: every edge alone
            return [[e] for e in range(self.scaffold.n_edges)]
        return [np.flatnonzero(orbit == o).tolist() for o in range(int(orbit.max()) + 1 if len(orbit) else 0)]

    def orbit_view(self) -> OrbitView:
        """Return the edge orbits and each edge's orbit (asked for when the page first edits an orbit)."""
        if self.scaffold.n_edges > MAX_ORBIT_EDGES:
            raise TooLargeError(
                f"{self.scaffold.name}: {self.scaffold.n_edges:,} edges > {MAX_ORBIT_EDGES} for orbit editing "
                "(the symmetry search would take minutes)"
            )
        orbit_of = np.zeros(self.scaffold.n_edges, np.int64)
        for i, orbit in enumerate(self.orbits):
            orbit_of[orbit] = i
        return {"orbits": self.orbits, "orbit_of": orbit_of.tolist()}

    def view(self) -> ScaffoldView:
        """Return what the page draws and edits: geometry, edges, default labels (JSON-ready)."""
        sc = self.scaffold
        out: ScaffoldView = {
            "key": self.key,
            "name": sc.name,
            "origin": self.origin,
            "n_vertices": sc.n_vertices,
            "n_edges": sc.n_edges,
            "n_faces": sc.n_faces,
            "n_corners": sc.n_corners,
            "dim": sc.dim,
            "vertices": np.round(sc.vertices, 6).tolist(),
            "corner_positions": np.round(sc.corner_positions, 6).reshape(-1).tolist(),
            "face_starts": sc.face_starts.tolist(),
            "face_centroids": np.round(sc.face_centroids, 6).reshape(-1).tolist(),
            "corner_face": sc.corner_face.tolist(),
            "side_edge": sc.side_edge.tolist(),
            "edge_points": np.round(sc.edge_points, 6).reshape(-1).tolist(),
            "edge_names": [sc.edge_name(e) for e in range(sc.n_edges)],
            "edge_degrees": sc.edge_degrees.tolist(),
            "labels": None if sc.labels is None else [int(t) for t in sc.labels],
            "nulls": None if sc.nulls is None else np.flatnonzero(sc.nulls).tolist(),
        }
        if sc.lattice is not None:
            out["lattice"] = np.asarray(sc.lattice.basis).tolist()
            out["block"] = default_block(sc)  # the block the page opens with: it fits the studio's bound
        return out


def check_builtin_name(name: object) -> str:
    """Return ``name`` if it can only mean a built-in scaffold; raise :class:`UsageError` otherwise."""
    if not isinstance(name, str) or not name or len(name) > MAX_NAME:
        raise UsageError(f"scaffold name must be a non-empty string of at most {MAX_NAME} characters")
    if any(c in name for c in "/\\\0") or ".." in name or not builtins.is_builtin_name(name):
        raise UsageError(f"{name[:60]!r} is not a built-in scaffold name (files are opened on the command line)")
    if "@" in name:
        sizes = name.partition("@")[2].lower().split("x")
        try:
            copies = int(np.prod([int(s) for s in sizes], dtype=object))
        except ValueError:
            raise UsageError(f"{name!r}: supercell sizes like @2x2x2 expected") from None
        if copies > MAX_CELLS:
            raise TooLargeError(f"{name!r}: {copies:,} cells > {MAX_CELLS:,} for the studio")
    return name


class Registry:
    """The scaffolds of one studio: built-ins by name (built once), files and uploads by id."""

    def __init__(self) -> None:
        self._held: dict[str, Held] = {}
        self._pinned: set[str] = set()
        self._lock = threading.Lock()

    def _keep(self, held: Held, pinned: bool = False) -> Held:
        if held.scaffold.n_faces > MAX_FACES:
            raise TooLargeError(f"{held.scaffold.name}: {held.scaffold.n_faces:,} faces > {MAX_FACES:,} for the studio")
        with self._lock:
            self._held[held.key] = held
            if pinned:
                self._pinned.add(held.key)
            loose = [k for k in self._held if k not in self._pinned]
            for key in loose[: max(0, len(loose) - MAX_HELD)]:
                del self._held[key]
        return held

    def get(self, key: str) -> Held:
        """Return the scaffold named ``key``: a built-in name or the id of one held here."""
        if isinstance(key, str) and key in self._held:
            return self._held[key]
        if isinstance(key, str) and key.startswith("id:"):
            raise UsageError(f"scaffold {key[:40]!r} is not held by this studio (reload it or upload the file)")
        name = check_builtin_name(key)
        return self._keep(Held(name, builtins.builtin(name), "built-in"), pinned=name == builtins.DEFAULT)

    def open_file(self, path: str) -> Held:
        """Hold the scaffold of a file named on the command line (read once, here)."""
        scaffold = load(path)
        return self._keep(Held(f"id:{scaffold.content_hash()[:16]}", scaffold, os.path.basename(path)), pinned=True)

    def hold(self, scaffold: Scaffold, origin: str, key: str | None = None, pinned: bool = True) -> Held:
        """Hold ``scaffold`` (from the command line, a catalog's metadata or a design file) under ``key`` or its content id."""
        return self._keep(Held(key or f"id:{scaffold.content_hash()[:16]}", scaffold, origin), pinned=pinned)

    def upload(self, filename: str, data: bytes) -> Held:
        """Parse an uploaded ``.obj`` or ``.json`` scaffold of at most :data:`MAX_UPLOAD` bytes and hold it."""
        if len(data) > MAX_UPLOAD:
            raise TooLargeError(f"upload of {len(data):,} bytes > {MAX_UPLOAD:,} (MAX_UPLOAD)")
        name = os.path.basename(filename.replace("\\", "/"))[:MAX_NAME] or "upload"
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            raise ScaffoldError(f"{name}: not a text file (UTF-8 expected)") from None
        ext = os.path.splitext(name)[1].lower()
        if ext == ".obj":
            scaffold = parse_obj(text, name)
        elif ext == ".json":
            scaffold = scaffold_from_dict(parse_json(text, name), name)
        else:
            raise UsageError(f"{name}: upload a .obj or .json scaffold file")
        if scaffold.n_faces > 1 and scaffold.edge_degrees.max() == 1:
            scaffold = parse_obj(text, name, True) if ext == ".obj" else scaffold  # one vertex copy per face: weld
        return self._keep(Held(f"id:{scaffold.content_hash()[:16]}", scaffold, f"upload {name}"))


def builtin_choices() -> list[str]:
    """Built-in names offered in the page's menu (families with a small parameter)."""
    names = [n.replace(":N", ":3").replace(":K", ":3") for n in builtins.builtin_names()]
    return names + ["honeycomb:cP@3x3x3", "tiling:square@10x10", "honeycomb:cP@7x7x7", "tiling:square@32x32"]
