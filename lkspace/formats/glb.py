"""``.glb`` strands: glTF 2.0 binary written with numpy and struct.

One mesh, node and material per strand (opens in Blender, three.js, trimesh).
"""

from __future__ import annotations

import json
import struct

import numpy as np

from ..geometry.realization import Realization
from .colors import curve_colors
from .options import GlbOptions
from .tubes import tube_meshes


def glb_bytes(real: Realization, options: GlbOptions) -> bytes:
    """Return the glTF 2.0 binary of the tubes: one mesh, node and material per strand."""
    blobs, views, accessors, meshes, nodes, materials = [], [], [], [], [], []
    offset = 0

    def add_view(data: bytes, target: int) -> int:
        nonlocal offset
        pad = (-len(data)) % 4
        blobs.append(data + b"\0" * pad)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
        offset += len(data) + pad
        return len(views) - 1

    for k, ((v, nrm, f), rgb) in enumerate(
        zip(tube_meshes(real, options.tube_radius, options.sides), curve_colors(real), strict=False)
    ):
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
