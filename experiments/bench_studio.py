"""Studio latency measured in the browser: performance.now() from the key press to the redrawn strands.

Starts a studio server (the same app as ``lkspace studio``) in a thread, drives headless
Chromium with real key presses on a selected edge and reads the page's own latency log
(``window.studio.state.latencies``: key handler -> answer from trace + realize -> tubes
built -> frame rendered).  Writes results/bench_studio.json and .md.

    python experiments/bench_studio.py [--repeats 12]

The machine is shared (2 cores, other jobs running): the median and the best of the
repeats are both reported.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time

import lkspace
from lkspace.studio.app import Studio
from lkspace.studio.server import start_in_thread

ARGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]
CASES = [  # (scaffold, target)
    ("truncated-octahedron", 0.150),
    ("honeycomb:cP@3x3x3", 0.150),
    ("tiling:square@10x10", 0.150),
    ("honeycomb:cP@7x7x7", 1.0),
    ("tiling:square@32x32", 1.0),
]
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def measure(page, url: str, name: str, repeats: int) -> dict:
    sc = lkspace.load(name)
    block = "&b=" + "x".join(["1"] * sc.dim) if sc.dim else ""
    page.goto(f"{url}#s={name}{block}")
    page.reload()
    page.wait_for_function(
        f"window.studio && window.studio.state.ready && window.studio.state.sc.name === '{name}'", timeout=120000
    )
    page.wait_for_timeout(500)
    for e in range(sc.n_edges):
        pos = page.evaluate(f"window.studio.edgeScreen({e})")
        page.mouse.click(pos["x"], pos["y"])
        if page.evaluate("window.studio.state.selected") is not None:
            break
    start = page.evaluate("window.studio.state.latencies.length")
    timings = []
    for i in range(repeats):
        n = page.evaluate("window.studio.state.latencies.length")
        page.keyboard.press("+" if i % 2 == 0 else "-")
        page.wait_for_function(f"window.studio.state.latencies.length > {n}", timeout=120000)
        timings.append(page.evaluate("window.studio.state.design.timing"))
        page.wait_for_timeout(150)  # let the clearance measurement after the redraw finish, as a user would
    lat = [ms / 1000 for ms in page.evaluate("window.studio.state.latencies")[start:]]
    points = page.evaluate(
        "window.studio.state.design.curves ? window.studio.state.design.curves.counts.reduce((a, b) => a + b, 0) : 0"
    )
    return {
        "scaffold": name,
        "faces": sc.n_faces,
        "edges": sc.n_edges,
        "curve_points": points,
        "median_s": statistics.median(lat),
        "best_s": min(lat),
        "worst_s": max(lat),
        "server_trace_median_s": statistics.median(t["trace"] for t in timings),
        "server_realize_median_s": statistics.median(t["realize"] for t in timings),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=12)
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    url, stop = start_in_thread(Studio())
    rows = []
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1200, "height": 800})
            for name, target in CASES:
                row = measure(page, url, name, args.repeats)
                row["target_s"] = target
                row["meets_target"] = row["median_s"] <= target
                rows.append(row)
                print(json.dumps(row))
            browser.close()
    finally:
        stop()
    out = {
        "what": "click-to-redrawn-strands latency in headless Chromium (performance.now in the page)",
        "machine": f"{platform.machine()}, {os.cpu_count()} cores shared with other jobs; software WebGL (--disable-gpu)",
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "repeats": args.repeats,
        "cases": rows,
    }
    os.makedirs(os.path.join(ROOT, "results"), exist_ok=True)
    with open(os.path.join(ROOT, "results", "bench_studio.json"), "w") as f:
        json.dump(out, f, indent=1)
    lines = [
        "# Studio latency in the browser",
        "",
        f"{out['what']}; {out['machine']}; {out['date']}; {args.repeats} edits each (+1/-1 on one edge).",
        "",
        "| scaffold | faces | curve points | median | best | worst | server trace | server realize | target |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        lines.append(
            f"| {r['scaffold']} | {r['faces']} | {r['curve_points']:,} | {r['median_s'] * 1000:.0f} ms | {r['best_s'] * 1000:.0f} ms "
            f"| {r['worst_s'] * 1000:.0f} ms | {r['server_trace_median_s'] * 1000:.0f} ms "
            f"| {r['server_realize_median_s'] * 1000:.0f} ms | {r['target_s'] * 1000:.0f} ms {'ok' if r['meets_target'] else 'MISSED'} |"
        )
    with open(os.path.join(ROOT, "results", "bench_studio.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
