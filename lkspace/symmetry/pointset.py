"""Isometries of a finite point set, found in time and memory linear in its size.

The vertices are first put in a standard position: divided by their largest coordinate
(no overflow for coordinates near ``1e308``, no underflow for tiny ones), centred on their
centroid (which every isometry of the set fixes) and scaled to RMS radius 1.  Positions
closer than :data:`WELD` are one **site** (an OBJ with one vertex copy per face has
several vertices per site).  A candidate motion must move every site to within the
search's tolerance ``Sites.tolerance`` (:mod:`lkspace.symmetry.tolerance`, in these
units) of a site of its class, one-to-one.  Every site gets an invariant class (radius, number of
vertex copies, and caller-given invariants such as degrees) that any symmetry keeps.

Candidates: an isometry fixing the centroid is fixed by the images of two sites ``a``,
``b`` that are not collinear with the centroid (and the sign of the third axis), so ``a``
is taken from the smallest class and ``b`` from a small class, and the images ``a'``,
``b'`` run over their classes with ``|a' - b'| = |a - b|`` (found by nearest-point queries).  Each
candidate is probed on a few sites, then every site is matched with the KD-tree
(:mod:`lkspace.symmetry.nearest`: numpy for a few sites, scipy's KD-tree for many; within :data:`SLACK` tolerances, since a frame fixed by
two rounded sites is a little off far from them): the candidate is kept when it maps the
sites one-to-one onto sites of their own class and, refit on all sites (3 x 3
Procrustes), moves none by more than the tolerance.
Collinear sites (a line through the centroid) have the four motions that fix or flip
the line.  Memory: O(sites) per candidate; time: O(candidates) + O(motions x sites log sites).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..errors import TooLargeError
from ..model.scaffold import unique_rows
from ..runtime.progress import task
from .nearest import NearestPoints, components

WELD = 1e-6
"""Distance (in units of the RMS radius about the centroid) below which two positions are one site."""

SLACK = 4.0
"""Candidates are matched to sites within ``SLACK`` tolerances, then refit and checked within one."""

MAX_FRAME_CANDIDATES = 5_000_000
"""Most candidate frames ``(a', b')`` the search tries; past it, :class:`~lkspace.errors.TooLargeError`.

Reached only by point sets with huge classes of alike sites (e.g. ``10^4`` sites on one circle)."""

CHUNK = 4096
"""Candidate frames probed together (one batch of numpy work and one progress step)."""

N_PROBES = 12
"""Sites each candidate is tried on before the full match."""


@dataclass(frozen=True)
class Sites:
    """Distinct positions of a vertex set in standard position.

    Attributes
    ----------
    points : (n_sites, 3) float64
        Site positions, centroid at 0, RMS radius 1.
    of_vertex : (n_vertices,) int64
        Site of each vertex.
    classes : (n_sites,) int64
        Invariant class of each site (equal for sites a symmetry may exchange).
    tolerance : float
        How far (same units) a motion may move a site from the site it is matched with.
    """

    points: np.ndarray
    of_vertex: np.ndarray
    classes: np.ndarray
    tolerance: float

    @property
    def n_sites(self) -> int:
        """Number of distinct positions."""
        return len(self.points)


def standard_position(vertices: np.ndarray) -> np.ndarray:
    """Return ``(n, 3) float64``: ``vertices`` centred on their centroid and scaled to RMS radius 1.

    Examples
    --------
    >>> x = standard_position(np.array([[1e300, 0, 0], [-1e300, 0, 0], [0, 1e300, 0], [0, -1e300, 0]]))
    >>> np.round(np.sqrt((x**2).sum(axis=1)), 6).tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    v = np.asarray(vertices, np.float64)
    scale = float(np.abs(v).max())
    x = v / scale if scale > 0 else v.copy()
    x -= x.mean(axis=0)
    rms = float(np.sqrt(np.mean(np.einsum("ij,ij->i", x, x))))
    return x / rms if rms > 0 else x


def first_seen_order(ids: np.ndarray) -> np.ndarray:
    """Renumber ``ids (n,)`` as ``(n,) int64`` 0, 1, ... in the order each id first occurs."""
    _, first, inverse = np.unique(ids, return_index=True, return_inverse=True)
    rank = np.empty(len(first), np.int64)
    rank[np.argsort(first)] = np.arange(len(first))
    return rank[inverse.reshape(-1)]


def gap_clusters(values: np.ndarray, tol: float) -> np.ndarray:
    """Return ``(n,) int64`` cluster ids of ``values``: sorted values closer than ``tol`` chain together."""
    order = np.argsort(values, kind="stable")
    new = np.r_[True, np.diff(values[order]) > tol]
    ids = np.empty(len(values), np.int64)
    ids[order] = np.cumsum(new) - 1
    return ids


def find_sites(x: np.ndarray, invariants: list[np.ndarray], tolerance: float = WELD) -> Sites:
    """Weld positions ``x`` (standard position) into sites; class them by radius and ``invariants``.

    ``invariants`` are ``(n_vertices,)`` float arrays kept by every symmetry (e.g. vertex
    degrees, exact); a site's value is the sum over its vertices.  Radii closer than ten
    ``tolerance`` chain into one class (a rounded mesh keeps its classes whole).
    """
    x_all = x
    x, copy_of = np.unique(x_all, axis=0, return_inverse=True)  # exact copies first: pairs stay linear
    of_vertex = components(len(x), NearestPoints(x).pairs(WELD))
    of_vertex = first_seen_order(of_vertex[copy_of.reshape(-1)])  # sites of the copies, numbered in vertex order
    x = x_all
    n_sites = int(of_vertex.max()) + 1
    copies = np.bincount(of_vertex, minlength=n_sites).astype(np.float64)
    points = np.zeros((n_sites, 3))
    np.add.at(points, of_vertex, x)
    points /= copies[:, None]
    columns = [gap_clusters(np.sqrt(np.einsum("ij,ij->i", points, points)), 10 * tolerance), copies]
    for inv in invariants:
        columns.append(gap_clusters(np.bincount(of_vertex, weights=inv, minlength=n_sites), 10 * WELD))
    _, classes = unique_rows(np.column_stack(columns).astype(np.int64))
    return Sites(points=points, of_vertex=of_vertex, classes=classes, tolerance=tolerance)


def frame(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Return ``(..., 3, 3)``: orthonormal frames (columns) from ``a`` and ``b`` (Gram-Schmidt)."""
    e1 = a / np.linalg.norm(a, axis=-1, keepdims=True)
    e2 = b - np.sum(b * e1, axis=-1, keepdims=True) * e1
    e2 /= np.linalg.norm(e2, axis=-1, keepdims=True)
    return np.stack([e1, e2, np.cross(e1, e2)], axis=-1)


def procrustes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Orthogonal ``Q (3, 3)`` minimizing ``|x Q^T - y|`` (only a 3 x 3 SVD)."""
    u, _, wt = np.linalg.svd(y.T @ x)
    return u @ wt


def refit(x: np.ndarray, pi: np.ndarray, q: np.ndarray, normal: np.ndarray, tolerance: float) -> np.ndarray | None:
    """Refit ``q`` on all sites (Procrustes), keeping its handedness; ``None`` if it moves a site past ``tolerance``.

    For coplanar sites the fit leaves the side of the plane open: ``normal`` (the direction
    of least spread) is mirrored when the fit's determinant differs from ``q``'s.
    """
    fit = procrustes(x, x[pi])
    if np.linalg.det(fit) * np.linalg.det(q) < 0:
        fit = fit @ (np.eye(3) - 2 * np.outer(normal, normal))
    if miss(x, pi, fit) > tolerance:
        return None
    return fit


def miss(x: np.ndarray, pi: np.ndarray, q: np.ndarray) -> float:
    """Largest distance between a site ``x[i]`` moved by ``q`` and the site ``x[pi[i]]`` it is matched with."""
    d = rotate(x, q) - x[pi]
    return float(np.sqrt(np.einsum("ij,ij->i", d, d).max()))


def line_motions(direction: np.ndarray) -> list[np.ndarray]:
    """Return the four motions of a line through 0 along unit ``direction``: keep or flip it, proper or not."""
    helper = np.eye(3)[int(np.argmin(np.abs(direction)))]
    normal = np.cross(direction, helper)
    normal /= np.linalg.norm(normal)
    mirror_n = np.eye(3) - 2 * np.outer(normal, normal)
    mirror_u = np.eye(3) - 2 * np.outer(direction, direction)
    return [np.eye(3), mirror_n, mirror_u, -mirror_n]


class Matcher:
    """Match images of the sites back onto the sites (KD-tree, class-preserving, one-to-one)."""

    def __init__(self, sites: Sites) -> None:
        self.sites = sites
        self.tree = NearestPoints(sites.points)

    def match(self, q: np.ndarray) -> np.ndarray | None:
        """Return ``(n_sites,) int64``, the site each site goes to under ``q``, or ``None``."""
        pts, classes = self.sites.points, self.sites.classes
        dist, idx = self.tree.nearest(rotate(pts, q), SLACK * self.sites.tolerance)
        if not np.all(np.isfinite(dist)):
            return None
        if not np.array_equal(classes[idx], classes):
            return None
        if np.any(np.bincount(idx, minlength=len(pts)) != 1):
            return None
        return idx.astype(np.int64)

    def probe(self, qs: np.ndarray, probes: np.ndarray) -> np.ndarray:
        """(m,) bool: which ``qs (m, 3, 3)`` map every probe site onto a site of its class."""
        if not len(qs):  # a batch whose candidates were all found already
            return np.zeros(0, dtype=bool)
        pts, classes = self.sites.points, self.sites.classes
        images = np.einsum("mij,pj->mpi", qs, pts[probes])
        dist, idx = self.tree.nearest(images.reshape(-1, 3), SLACK * self.sites.tolerance)
        ok = np.isfinite(dist).reshape(len(qs), -1)
        idx = np.minimum(idx, len(pts) - 1).reshape(len(qs), -1)
        ok &= classes[idx] == classes[probes][None, :]
        return np.all(ok, axis=1)


def anchors(sites: Sites) -> tuple[int, int | None]:
    """Return sites ``a`` (smallest class off the centroid) and ``b`` (small class, far from the line 0-a)."""
    pts, classes, tol = sites.points, sites.classes, sites.tolerance
    radii = np.sqrt(np.einsum("ij,ij->i", pts, pts))
    sizes = np.bincount(classes)
    off = radii > max(tol, WELD)
    a = int(np.flatnonzero(off)[np.argmin(sizes[classes[off]] * 1.0)])
    sines = np.linalg.norm(np.cross(pts / np.maximum(radii, WELD)[:, None], pts[a] / radii[a]), axis=1)
    best = float(sines.max())
    if best <= 1e3 * WELD or float(np.max(sines * radii)) <= tol:
        return a, None  # collinear sites (within the tolerance of the line through 0 and a)
    good = sines >= min(0.2, 0.5 * best)
    cls = np.flatnonzero(good)[np.argmin(sizes[classes[good]] * 1.0)]
    members = np.flatnonzero((classes == classes[cls]) & good)
    b = int(members[np.argmin(np.linalg.norm(pts[members] - pts[a], axis=1))])
    return a, b


def rotate(x: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``x (n, 3)`` moved by ``q``: ``x @ q.T`` (written as ``(q @ x.T).T``, much faster for tall ``x``)."""
    return (q @ x.T).T


class SiteSearch:
    """Candidate motions of the sites, each with an exact key, and their verification.

    A motion is known by its key ``(a', b', proper)``: the images of the anchor sites
    ``a`` and ``b`` and its handedness fix it (for collinear sites ``b = a``).
    """

    def __init__(self, sites: Sites) -> None:
        self.sites = sites
        self.matcher = Matcher(sites)
        self.a, self.b = anchors(sites)
        pts, n = sites.points, sites.n_sites
        order = np.argsort(np.bincount(sites.classes)[sites.classes], kind="stable")
        self.probes = order[np.linspace(0, n - 1, min(n, N_PROBES)).astype(np.int64)]
        self.normal = np.linalg.eigh(pts.T @ pts)[1][:, 0]  # the plane's normal when the sites are coplanar

    @property
    def b_or_a(self) -> int:
        """The second anchor (``a`` again for collinear sites)."""
        return self.a if self.b is None else self.b

    def key(self, pi: np.ndarray, proper: bool) -> int:
        """Exact key of the motion inducing site permutation ``pi``."""
        return self.key_of(pi[[self.a, self.b_or_a]], proper)

    def key_of(self, images: np.ndarray, proper: bool) -> int:
        """Exact key of the motion sending the anchors to ``images`` (2,)."""
        return (int(images[0]) * self.sites.n_sites + int(images[1])) * 2 + int(proper)

    def batches(self) -> Iterator[tuple[np.ndarray | None, np.ndarray]]:
        """Yield ``(keys or None, qs (m, 3, 3))``: every motion of the sites is among the candidates."""
        if self.b is None:
            direction = self.sites.points[self.a] / np.linalg.norm(self.sites.points[self.a])
            yield None, np.array(line_motions(direction))
            return
        yield from self.frame_candidates()

    def frame_candidates(self) -> Iterator[tuple[np.ndarray | None, np.ndarray]]:
        """Candidates sending ``a, b`` to sites ``a', b'`` of their classes at the same distance."""
        a, b = self.a, self.b
        assert b is not None, "frames need two anchors"
        pts, classes, n = self.sites.points, self.sites.classes, self.sites.n_sites
        images_a = np.flatnonzero(classes == classes[a])
        images_b = np.flatnonzero(classes == classes[b])
        d = float(np.linalg.norm(pts[a] - pts[b]))
        tree_b = NearestPoints(pts[images_b])
        slack = SLACK * self.sites.tolerance
        counts = np.array([len(m) for m in tree_b.balls(pts[images_a], d + slack)], np.int64)
        total = 2 * int(np.sum(counts))
        if total > MAX_FRAME_CANDIDATES:
            raise TooLargeError(
                f"the symmetry search would try {total} candidate motions (more than {MAX_FRAME_CANDIDATES}): "
                f"{len(images_a)} vertices look alike; use `symmetry='none'`",
            )
        base_t = frame(pts[a], pts[b]).T
        flip = np.diag([1.0, 1.0, -1.0])
        per_block = max(1, CHUNK // max(1, int(np.max(counts, initial=1))))
        with task("symmetry search (candidate motions)", total=total) as step:
            for start in range(0, len(images_a), per_block):
                block = images_a[start : start + per_block]
                near = tree_b.balls(pts[block], d + slack)
                pa = np.repeat(block, [len(m) for m in near])
                step.advance(2 * len(pa))
                if not len(pa):
                    continue
                pb = images_b[np.concatenate([np.asarray(m, np.int64) for m in near])]
                keep = np.abs(np.linalg.norm(pts[pa] - pts[pb], axis=1) - d) <= slack
                pa, pb = pa[keep], pb[keep]
                if len(pa):
                    frames = frame(pts[pa], pts[pb])
                    keys = (pa * n + pb) * 2
                    yield np.concatenate([keys + 1, keys]), np.concatenate([frames @ base_t, frames @ flip @ base_t])

    def probe(self, qs: np.ndarray) -> np.ndarray:
        """(m,) bool: which candidates map the probe sites onto sites of their classes."""
        return self.matcher.probe(qs, self.probes)

    def verify(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """``(Q, pi)``: ``q`` refit on all sites and the site permutation, or ``None`` if ``q`` is no symmetry."""
        pi = self.matcher.match(q)
        if pi is None:
            return None
        if self.b is not None:
            fit = refit(self.sites.points, pi, q, self.normal, self.sites.tolerance)
            return None if fit is None else (fit, pi)
        return (q, pi) if miss(self.sites.points, pi, q) <= self.sites.tolerance else None
