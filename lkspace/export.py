"""Write realized strands to files: ``.obj``, ``.ply``, ``.glb`` and ``.png``.

* ``.obj`` — one object per strand: polylines (``l``) or, with ``tubes=True``, tube meshes.
* ``.ply`` — ASCII PLY with per-vertex colours (one colour per strand): polylines as
  ``edge`` elements, or tube meshes as ``face`` elements.
* ``.glb`` — glTF 2.0 binary written with numpy and struct: one tube mesh (and node) per
  strand, each with its own material colour; opens in Blender, three.js, trimesh.
* ``.png`` — a matplotlib (Agg) picture: shaded tubes, one colour per strand, the input
  mesh drawn faintly.

Every file is written to a temporary name and renamed when complete.
"""

from __future__ import annotations

import json
import os
import struct

import numpy as np

from .errors import LkspaceError, require
from .geometry import Realization, resample
from .io.atomic import atomic_path, write_bytes, write_text

FORMATS = (".obj", ".ply", ".glb", ".png")

PALETTE = np.array(
    [
        [0.89, 0.10, 0.11],
        [0.12, 0.47, 0.71],
        [0.20, 0.63, 0.17],
        [1.00, 0.50, 0.00],
        [0.42, 0.24, 0.60],
        [0.09, 0.75, 0.81],
        [0.90, 0.67, 0.00],
        [0.65, 0.34, 0.16],
        [0.97, 0.51, 0.75],
        [0.40, 0.40, 0.40],
        [0.55, 0.80, 0.20],
        [0.00, 0.30, 0.55],
    ]
)


class ExportError(LkspaceError, ValueError):
    """An output path or format that cannot be written."""


def colors(n: int) -> np.ndarray:
    """(n, 3) float64 distinct colours in ``[0, 1]`` (a fixed palette, then golden-ratio hues)."""
    if n <= len(PALETTE):
        return PALETTE[:n].copy()
    import colorsys

    extra = [colorsys.hsv_to_rgb((0.618034 * k) % 1.0, 0.75, 0.9) for k in range(n - len(PALETTE))]
    return np.vstack([PALETTE, np.array(extra)])


def _frames(points: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rotation-minimizing frames ``(tangent, normal, binormal)``, each ``(n, 3)``."""
    nxt = np.roll(points, -1, axis=0) if closed else np.vstack([points[1:], 2 * points[-1] - points[-2]])
    prv = np.roll(points, 1, axis=0) if closed else np.vstack([2 * points[0] - points[1], points[:-1]])
    tan = nxt - prv
    tan /= np.maximum(np.linalg.norm(tan, axis=1, keepdims=True), 1e-300)
    n = len(points)
    normal = np.empty_like(points)
    helper = np.eye(3)[np.argmin(np.abs(tan[0]))]
    v = np.cross(tan[0], helper)
    normal[0] = v / np.linalg.norm(v)
    for i in range(1, n):  # parallel transport (double reflection)
        v1 = points[i] - points[i - 1]
        c1 = v1 @ v1
        if c1 < 1e-300:
            normal[i] = normal[i - 1]
            continue
        r_l = normal[i - 1] - (2 / c1) * (v1 @ normal[i - 1]) * v1
        t_l = tan[i - 1] - (2 / c1) * (v1 @ tan[i - 1]) * v1
        v2 = tan[i] - t_l
        c2 = v2 @ v2
        normal[i] = r_l - (2 / c2) * (v2 @ r_l) * v2 if c2 > 1e-300 else r_l
    binormal = np.cross(tan, normal)
    if closed and n > 2:  # spread the closing twist along the curve
        angle = np.arctan2(np.cross(normal[-1], normal[0]) @ tan[0], normal[-1] @ normal[0])
        phi = angle * np.arange(n) / n
        c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
        normal, binormal = c * normal + s * binormal, -s * normal + c * binormal
    return tan, normal, binormal


def tube(points: np.ndarray, closed: bool, radius: float, sides: int = 12):
    """Tube mesh around a polyline.

    Returns
    -------
    vertices : (n * sides + caps, 3) float64
    normals : same shape, unit outward normals
    faces : (n_faces, 3) int64 triangles, counter-clockwise seen from outside
    """
    points = np.asarray(points, np.float64)
    n = len(points)
    _, normal, binormal = _frames(points, closed)
    ang = 2 * np.pi * np.arange(sides) / sides
    ring = np.cos(ang)[None, :, None] * normal[:, None] + np.sin(ang)[None, :, None] * binormal[:, None]
    verts = (points[:, None] + radius * ring).reshape(-1, 3)
    norms = ring.reshape(-1, 3)
    i = np.arange(n if closed else n - 1)
    j = np.arange(sides)
    i0 = i[:, None] * sides + j[None, :]
    i1 = ((i[:, None] + 1) % n) * sides + j[None, :]
    j1 = (j[None, :] + 1) % sides
    i0n = i[:, None] * sides + j1
    i1n = ((i[:, None] + 1) % n) * sides + j1
    faces = np.concatenate([np.stack([i0, i0n, i1], -1).reshape(-1, 3), np.stack([i0n, i1n, i1], -1).reshape(-1, 3)])
    if not closed:  # flat caps
        t0 = points[1] - points[0]
        t1 = points[-1] - points[-2]
        c0, c1 = len(verts), len(verts) + 1
        verts = np.vstack([verts, points[0], points[-1]])
        norms = np.vstack([norms, -t0 / np.linalg.norm(t0), t1 / np.linalg.norm(t1)])
        cap0 = np.column_stack([np.full(sides, c0), j1[0], j])
        cap1 = np.column_stack([np.full(sides, c1), (n - 1) * sides + j, (n - 1) * sides + j1[0]])
        faces = np.vstack([faces, cap0, cap1])
    return verts, norms, faces.astype(np.int64)


def _tubes(real: Realization, radius: float | None, sides: int, spacing: float | None = None):
    radius = real.tube_radius if radius is None else radius
    out = []
    for curve, closed in zip(real.curves, real.closed, strict=False):
        pts = curve if spacing is None else resample(curve, bool(closed), spacing)[0]
        out.append(tube(pts, bool(closed), radius, sides))
    return out


def write_obj(real: Realization, path, tubes: bool = False, radius: float | None = None, sides: int = 12) -> None:
    """Polylines (``l``) or tube meshes, one ``o strand_k`` object per curve."""
    lines = [f"# lkspace strands of {real.scaffold.name}: {real.n_curves} curve(s)"]
    base = 1
    if tubes:
        for k, (v, _, f) in enumerate(_tubes(real, radius, sides)):
            lines.append(f"o strand_{k}")
            lines.extend(f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in v)
            lines.extend(f"f {a + base} {b + base} {c + base}" for a, b, c in f)
            base += len(v)
    else:
        for k, (curve, closed) in enumerate(zip(real.curves, real.closed, strict=False)):
            lines.append(f"o strand_{k}")
            lines.extend(f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in curve)
            idx = list(range(base, base + len(curve))) + ([base] if closed else [])
            lines.append("l " + " ".join(map(str, idx)))
            base += len(curve)
    write_text(path, "\n".join(lines) + "\n")


def write_ply(real: Realization, path, tubes: bool = False, radius: float | None = None, sides: int = 12) -> None:
    """ASCII PLY, vertex colours per strand; ``edge`` polylines or tube ``face`` triangles."""
    cols = (colors(real.n_curves) * 255).round().astype(int)
    verts, vcols, elems = [], [], []
    base = 0
    if tubes:
        for k, (v, _, f) in enumerate(_tubes(real, radius, sides)):
            verts.append(v)
            vcols.append(np.repeat(cols[k][None], len(v), 0))
            elems.append(f + base)
            base += len(v)
    else:
        for k, (curve, closed) in enumerate(zip(real.curves, real.closed, strict=False)):
            n = len(curve)
            verts.append(curve)
            vcols.append(np.repeat(cols[k][None], n, 0))
            a = np.arange(n if closed else n - 1)
            elems.append(np.column_stack([a, (a + 1) % n]) + base)
            base += n
    v = np.vstack(verts)
    c = np.vstack(vcols)
    e = np.vstack(elems)
    kind = "face" if tubes else "edge"
    header = [
        "ply",
        "format ascii 1.0",
        f"comment lkspace strands of {real.scaffold.name}",
        f"element vertex {len(v)}",
        "property float x",
        "property float y",
        "property float z",
        "property uchar red",
        "property uchar green",
        "property uchar blue",
        f"element {kind} {len(e)}",
    ]
    header += ["property list uchar int vertex_indices"] if tubes else ["property int vertex1", "property int vertex2"]
    header.append("end_header")
    body = [f"{x:.6f} {y:.6f} {z:.6f} {r} {g} {b}" for (x, y, z), (r, g, b) in zip(v, c, strict=False)]
    body += [("3 " if tubes else "") + " ".join(map(str, row)) for row in e]
    write_text(path, "\n".join(header + body) + "\n")


def glb_bytes(real: Realization, radius: float | None = None, sides: int = 12) -> bytes:
    """glTF 2.0 binary: one mesh, node and material per strand."""
    blobs, views, accessors, meshes, nodes, materials = [], [], [], [], [], []
    offset = 0

    def add_view(data: bytes, target: int) -> int:
        nonlocal offset
        pad = (-len(data)) % 4
        blobs.append(data + b"\0" * pad)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
        offset += len(data) + pad
        return len(views) - 1

    for k, ((v, nrm, f), rgb) in enumerate(zip(_tubes(real, radius, sides), colors(real.n_curves), strict=False)):
        v32 = v.astype(np.float32)
        pos = add_view(v32.tobytes(), 34962)
        accessors.append(
            {
                "bufferView": pos,
                "componentType": 5126,
                "count": len(v32),
                "type": "VEC3",
                "min": v32.min(0).tolist(),
                "max": v32.max(0).tolist(),
            }
        )
        nv = add_view(nrm.astype(np.float32).tobytes(), 34962)
        accessors.append({"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
        iv = add_view(f.astype(np.uint32).reshape(-1).tobytes(), 34963)
        accessors.append({"bufferView": iv, "componentType": 5125, "count": int(f.size), "type": "SCALAR"})
        materials.append(
            {
                "name": f"strand_{k}",
                "doubleSided": False,
                "pbrMetallicRoughness": {
                    "baseColorFactor": [*map(float, rgb), 1.0],
                    "metallicFactor": 0.1,
                    "roughnessFactor": 0.6,
                },
            }
        )
        meshes.append(
            {
                "name": f"strand_{k}",
                "primitives": [
                    {
                        "attributes": {"POSITION": 3 * k, "NORMAL": 3 * k + 1},
                        "indices": 3 * k + 2,
                        "material": k,
                        "mode": 4,
                    }
                ],
            }
        )
        nodes.append({"name": f"strand_{k}", "mesh": k})
    binary = b"".join(blobs)
    doc = {
        "asset": {"version": "2.0", "generator": "lkspace"},
        "scene": 0,
        "scenes": [{"name": real.scaffold.name, "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(binary)}],
    }
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * ((-len(text)) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (
        struct.pack("<4sII", b"glTF", 2, total)
        + struct.pack("<I4s", len(text), b"JSON")
        + text
        + struct.pack("<I4s", len(binary), b"BIN\0")
        + binary
    )


def write_glb(real: Realization, path, radius: float | None = None, sides: int = 12) -> None:
    write_bytes(path, glb_bytes(real, radius, sides))


def render_png(
    real: Realization,
    path,
    show_mesh: bool = True,
    radius: float | None = None,
    size: int = 900,
    elev: float | None = None,
    azim: float = -58.0,
    title: str | None = None,
) -> None:
    """A shaded picture of the tubes (one colour per strand), the input mesh faint behind.

    Lattice translates of one strand (a periodic block) share its colour.

    ``elev`` defaults to 24 degrees, or 55 for a flat scaffold seen from above.
    """
    require("matplotlib", "render", "PNG export")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    radius = real.tube_radius if radius is None else radius
    pts = np.vstack(real.curves)
    extent = np.ptp(pts, axis=0)
    if elev is None:
        elev = 55.0 if extent[2] < 0.25 * extent.max() else 24.0
    fig = plt.figure(figsize=(size / 100, size / 100), dpi=100)
    ax = fig.add_subplot(projection="3d", computed_zorder=False)
    ax.view_init(elev=elev, azim=azim)
    e, a = np.radians(elev), np.radians(azim)
    view = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    light = view + np.array([0.3, -0.2, 0.6])
    light /= np.linalg.norm(light)
    sc = real.scaffold
    if show_mesh:
        base = [sc.corner_positions[s:t] for s, t in zip(sc.face_starts[:-1], sc.face_starts[1:], strict=True)]
        shifts = (
            sc.lattice.translate(real.translations)
            if sc.periodic and real.translations is not None
            else np.zeros((1, 3))
        )
        polys = [p + d for d in shifts for p in base]
        ax.add_collection3d(
            Poly3DCollection(
                polys, facecolors=(0.6, 0.65, 0.75, 0.07), edgecolors=(0.35, 0.35, 0.4, 0.35), linewidths=0.6
            )
        )
    spacing = 1.2 * radius
    all_tris, all_cols = [], []
    palette = colors(int(real.strand_of.max()) + 1)[real.strand_of]  # translates share their strand's colour
    for (v, nrm, f), rgb in zip(_tubes(real, radius, 10, spacing), palette, strict=True):
        fn = nrm[f].mean(axis=1)
        fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-12)
        lam = np.clip(fn @ light, 0, 1)
        spec = np.clip(fn @ ((light + view) / np.linalg.norm(light + view)), 0, 1) ** 24
        shade = np.clip(rgb[None] * (0.35 + 0.65 * lam[:, None]) + 0.35 * spec[:, None], 0, 1)
        facing = fn @ view > -0.2
        all_tris.append(v[f[facing]])
        all_cols.append(shade[facing])
    tris = np.concatenate(all_tris)
    cols = np.concatenate(all_cols)
    depth = tris.mean(axis=1) @ view
    order = np.argsort(depth)  # far first: painter's algorithm
    ax.add_collection3d(Poly3DCollection(tris[order], facecolors=cols[order], edgecolors=cols[order], linewidths=0.25))
    lo, hi = pts.min(0) - 2 * radius, pts.max(0) + 2 * radius
    center, half = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(center[0] - half, center[0] + half)
    ax.set_ylim(center[1] - half, center[1] + half)
    ax.set_zlim(center[2] - half, center[2] + half)
    ax.set_box_aspect((1, 1, 1), zoom=1.3)
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=13)
    fig.subplots_adjust(0, 0, 1, 1)
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, format="png", dpi=100)
    plt.close(fig)


def export(
    real: Realization,
    path,
    tubes: bool = False,
    radius: float | None = None,
    show_mesh: bool = True,
    title: str | None = None,
) -> str:
    """Write ``real`` to ``path``; the format follows the extension (:data:`FORMATS`)."""
    ext = os.path.splitext(os.fspath(path))[1].lower()
    if ext not in FORMATS:
        raise ExportError(f"{path}: unknown output format {ext or '(none)'!r}; use one of {', '.join(FORMATS)}")
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise ExportError(f"{path}: directory {directory} does not exist")
    if ext == ".obj":
        write_obj(real, path, tubes, radius)
    elif ext == ".ply":
        write_ply(real, path, tubes, radius)
    elif ext == ".glb":
        write_glb(real, path, radius)
    else:
        render_png(real, path, show_mesh, radius, title=title)
    return ext[1:]
