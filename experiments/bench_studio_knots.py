"""Cost of the studio's knot diagram and catalog thumbnails, measured over HTTP on a live server.

The diagram is asked after every redraw (from the realization the redraw kept), so its
cost adds to nothing the designer waits for but must stay well under a redraw; a catalog
page asks the thumbnails of its 25 rows at once.  Writes ``results/bench_studio_knots.md``.
"""

from __future__ import annotations

import os
import statistics
import time

import httpx
import numpy as np

import lkspace
from lkspace.studio.app import Studio
from lkspace.studio.server import start_in_thread

CASES = ["tetrahedron", "cube", "icosahedron", "truncated-octahedron", "kaleidocycle:12", "book:60", "dihedron:200"]
OUT = os.path.join(os.path.dirname(__file__), "..", "results", "bench_studio_knots.md")


def main() -> None:
    """Measure and write the table."""
    url, stop = start_in_thread(Studio())
    rows = []
    rng = np.random.default_rng(0)
    with httpx.Client(base_url=url, timeout=120) as client:
        for name in CASES:
            sc = lkspace.load(name)
            labels = rng.integers(-1, 2, sc.n_edges).tolist()
            body = {"key": name, "labels": labels}
            design = client.post("/api/design", json=body).json()  # the redraw, keeping the realization
            points = sum(design["curves"]["counts"])
            walls, server = [], []
            for _ in range(5):
                t0 = time.perf_counter()
                d = client.post("/api/diagram", json=body).json()
                walls.append(time.perf_counter() - t0)
                server.append(d["seconds"])
            rows.append(
                (
                    name,
                    sc.n_faces,
                    points,
                    d["crossings"],
                    len(d["svg"]),
                    statistics.median(server),
                    statistics.median(walls),
                )
            )
        sc = lkspace.load("tetrahedron")
        designs = [rng.integers(-2, 3, sc.n_edges).tolist() for _ in range(25)]
        t0 = time.perf_counter()
        client.post("/api/thumbnails", json={"key": "tetrahedron", "designs": designs})
        cold = time.perf_counter() - t0
        t0 = time.perf_counter()
        thumbs = client.post("/api/thumbnails", json={"key": "tetrahedron", "designs": designs}).json()["thumbs"]
        warm = time.perf_counter() - t0
    stop()
    lines = [
        "# Studio knot diagrams and thumbnails",
        "",
        "`python experiments/bench_studio_knots.py`: a live server, random labels in -1..1, median of 5 requests",
        "(the realization is the one the redraw kept; a loaded 2-core machine, timings noisy).",
        "",
        "| scaffold | faces | curve points | crossings drawn | SVG bytes | server | request |",
        "|---|---|---|---|---|---|---|",
        *(
            f"| {n} | {f} | {p:,} | {c:,} | {b:,} | {s * 1000:.1f} ms | {w * 1000:.1f} ms |"
            for n, f, p, c, b, s, w in rows
        ),
        "",
        f"Thumbnails of one catalog page (25 tetrahedron designs, labels -2..2): {cold * 1000:.0f} ms drawn, "
        f"{warm * 1000:.0f} ms kept; {sum(map(len, thumbs)) / 1024:.0f} KiB of SVG.",
        "",
    ]
    with open(OUT, "w") as handle:
        handle.write("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
