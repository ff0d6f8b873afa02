"""The README's studio screenshot (docs/studio.png), taken in headless Chromium.

    python experiments/studio_screenshot.py

Opens a studio on a small tetrahedron catalog, loads the Borromean rings (every label 1),
waits for the knot name and writes a palette PNG under 150 KB.
"""

from __future__ import annotations

import io
import os
import tempfile

import lkspace
from lkspace.studio.app import Studio
from lkspace.studio.browse import Browser
from lkspace.studio.server import start_in_thread

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ARGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]


def main() -> None:
    from PIL import Image
    from playwright.sync_api import sync_playwright

    folder = tempfile.mkdtemp(prefix="lkspace-shot-")
    catalog = os.path.join(folder, "tetrahedron.parquet")
    lkspace.write_catalog("tetrahedron", catalog, label_set="-2..2")
    studio = Studio(browser=Browser(catalog))
    studio.initial = studio.registry.hold(lkspace.load("tetrahedron"), "built-in", "tetrahedron").key
    url, stop = start_in_thread(studio)
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1100, "height": 680})
            page.goto(url + "#s=tetrahedron&t=1,1,1,1,1,1")
            page.wait_for_function("window.studio && window.studio.state.ready", timeout=60000)
            page.wait_for_function("document.querySelector('#knot-name') !== null", timeout=60000)
            page.wait_for_function("window.studio.state.catalog.rows && window.studio.state.catalog.rows.length > 0")
            pos = page.evaluate("window.studio.edgeScreen(2)")
            page.mouse.click(pos["x"], pos["y"])
            page.wait_for_timeout(300)
            png = page.screenshot()
            browser.close()
    finally:
        stop()
    image = Image.open(io.BytesIO(png)).convert("RGB").quantize(colors=96)
    out = os.path.join(ROOT, "docs", "studio.png")
    image.save(out, optimize=True)
    print(out, os.path.getsize(out), "bytes")


if __name__ == "__main__":
    main()
