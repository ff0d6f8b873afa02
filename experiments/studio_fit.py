"""How much of the canvas a fitted design fills: the studio's fit against the bounding-sphere fit it replaced.

    python experiments/studio_fit.py        # -> results/studio_fit.md

For a few scaffolds and window shapes (desktop and a 390x844 phone), the page fits the
design, then every 3rd tube vertex is projected to the screen: the share of the canvas
width and height the design spans, the larger of the two being what "fills" means.  The
old fit (camera at the bounding sphere's radius / sin(fov/2)) is put in the same page
by setting the camera the way it did.
"""

from __future__ import annotations

import os

from lkspace.studio.app import Studio
from lkspace.studio.server import start_in_thread

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ARGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]
CASES = ["cube", "tetrahedron", "dodecahedron", "honeycomb:cP@3x3x3"]
WINDOWS = [(1200, 800), (390, 844), (1600, 600)]

SPREAD = """(old) => { const v = window.studio.view;
  if (old) { // the former fit: the bounding sphere's radius over sin(fov/2), from the same direction
    const g = v.groups.strands.children[0].geometry; g.computeBoundingBox(); const b = g.boundingBox;
    const c = b.max.clone().add(b.min).multiplyScalar(0.5), r = b.max.clone().sub(b.min).length() / 2;
    const dist = r / Math.sin(v.camera.fov * Math.PI / 360), d = [0.55, 0.45, 0.7], n = Math.hypot(...d);
    v.camera.position.set(c.x + d[0] / n * dist, c.y + d[1] / n * dist, c.z + d[2] / n * dist);
    v.controls.target.copy(c); v.controls.update(); v.render();
  } else v.fit();
  const r = v.canvas.getBoundingClientRect(), pos = v.groups.strands.children[0].geometry.getAttribute('position');
  let x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (let i = 0; i < pos.count; i += 3) { const s = v.screenOf([pos.getX(i), pos.getY(i), pos.getZ(i)]);
    x0 = Math.min(x0, s.x); x1 = Math.max(x1, s.x); y0 = Math.min(y0, s.y); y1 = Math.max(y1, s.y); }
  return [(x1 - x0) / r.width, (y1 - y0) / r.height, Math.min(x0 - r.left, r.right - x1, y0 - r.top, r.bottom - y1)]; }"""


def main() -> None:
    from playwright.sync_api import sync_playwright

    url, stop = start_in_thread(Studio())
    rows = []
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            for width, height in WINDOWS:
                page = browser.new_page(viewport={"width": width, "height": height})
                for name in CASES:
                    page.goto("about:blank")
                    page.goto(f"{url}#s={name}")
                    page.wait_for_function("window.studio && window.studio.state.ready", timeout=60000)
                    page.wait_for_function("window.studio.view.groups.strands.children.length > 0")
                    size = page.evaluate(
                        "[window.studio.view.canvas.clientWidth, window.studio.view.canvas.clientHeight]"
                    )
                    old, new = page.evaluate(SPREAD, True), page.evaluate(SPREAD, False)
                    rows.append((f"{width}x{height}", f"{size[0]}x{size[1]}", name, old, new))
                page.close()
            browser.close()
    finally:
        stop()
    lines = [
        "# The studio's fit: share of the canvas the design spans",
        "",
        "`python experiments/studio_fit.py` (headless Chromium).  Width and height spanned by the",
        "projected tube vertices, as a share of the canvas; *fills* is the larger of the two;",
        "*margin* the smallest gap to a canvas edge in pixels (negative: cut off).",
        "",
        "| window | canvas | scaffold | old fit: fills (w, h) | new fit: fills (w, h) | new margin px |",
        "|---|---|---|---|---|---|",
    ]
    for window, canvas, name, old, new in rows:
        lines.append(
            f"| {window} | {canvas} | {name} | {max(old[:2]):.0%} ({old[0]:.0%}, {old[1]:.0%}) "
            f"| {max(new[:2]):.0%} ({new[0]:.0%}, {new[1]:.0%}) | {new[2]:.0f} |"
        )
    text = "\n".join(lines) + "\n"
    os.makedirs(os.path.join(ROOT, "results"), exist_ok=True)
    with open(os.path.join(ROOT, "results", "studio_fit.md"), "w") as handle:
        handle.write(text)
    print(text)


if __name__ == "__main__":
    main()
