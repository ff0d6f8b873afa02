"""The studio driven in headless Chromium, started by the installed CLI as a user would.

Real clicks and keys on the page; ``window.studio`` only tells where an edge is on
screen and what the page holds, every answer is checked against the public API.
"""

import numpy as np
import pytest

import lkspace

from .studio_harness import click_edge, labels_of, ready, redraws, running_studio, wait_redraw


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    """``lkspace studio CATALOG``: yields its URL, the catalog and its folder; stopped with Ctrl-C."""
    folder = tmp_path_factory.mktemp("studio")
    catalog = str(folder / "tetra.parquet")
    lkspace.write_catalog("tetrahedron", catalog, label_set="-2..2")
    with running_studio(catalog) as url:
        yield url, catalog, folder


def test_edit_solve_browse_export_reload(studio, browser, tmp_path):
    url, catalog, _ = studio
    page = browser.new_page(viewport={"width": 1200, "height": 800})
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    ready(page)
    # the catalog's scaffold opens; switch to the cube: every label 1, four components
    n = redraws(page)
    page.select_option("#builtin", "cube")
    wait_redraw(page, n)
    page.wait_for_function("window.studio.state.sc.name === 'cube'")
    assert page.inner_text("#components") == "4" and len(page.evaluate("window.studio.colors()")) == 4
    # click an edge, press +: the component count and the strand colours change
    edge = click_edge(page, 3)
    assert edge is not None and page.inner_text("#edge-index") == str(edge)
    n = redraws(page)
    page.keyboard.press("+")
    wait_redraw(page, n)
    labels = labels_of(page)
    assert labels[edge] == 2 and labels.count(1) == 11
    assert page.inner_text("#components") == str(lkspace.trace("cube", labels).components) == "3"
    assert len(page.evaluate("window.studio.colors()")) == 3
    # type a value, then undo it
    n = redraws(page)
    page.fill("#label", "-1")
    page.press("#label", "Enter")
    wait_redraw(page, n)
    assert labels_of(page)[edge] == -1
    assert page.inner_text("#components") == str(lkspace.trace("cube", labels_of(page)).components)
    n = redraws(page)
    page.click("#undo")
    wait_redraw(page, n)
    assert labels_of(page)[edge] == 2
    # a twist too large to embed: the message names it and the edge is marked, the view is not blank
    n = redraws(page)
    page.fill("#label", "1000000000000000000")
    page.press("#label", "Enter")
    wait_redraw(page, n)
    assert page.evaluate("window.studio.state.design.failure.edge") == edge
    assert "self-intersect" in page.inner_text("#message")
    n = redraws(page)
    page.keyboard.press("Control+z")
    wait_redraw(page, n)
    assert labels_of(page)[edge] == 2 and page.is_hidden("#message")
    # a null face-side cuts a strand open
    side = int(page.get_attribute("#sides input >> nth=0", "data-side"))
    n = redraws(page)
    page.check("#sides input >> nth=0")
    wait_redraw(page, n)
    nulls = np.zeros(lkspace.load("cube").n_corners, bool)
    nulls[side] = True
    expected = lkspace.trace("cube", labels_of(page), nulls)
    assert page.inner_text("#components") == str(expected.components)
    assert page.evaluate("window.studio.state.design.strands.map(s => s.kind)") == expected.strand_kinds
    n = redraws(page)
    page.click("#undo")
    wait_redraw(page, n)
    # a whole edge orbit at once (the cube's rotations make all 12 edges one orbit)
    page.check("#orbit")
    page.wait_for_function("window.studio.state.orbits !== null", timeout=20000)
    n = redraws(page)
    page.keyboard.press("+")
    wait_redraw(page, n)
    assert labels_of(page) == [3] * 12
    assert page.inner_text("#components") == str(lkspace.trace("cube", 3).components)
    page.uncheck("#orbit")
    # hostile typing: a message in the page, the design unchanged
    page.fill("#label", "12abc")
    page.press("#label", "Enter")
    assert "integer" in page.inner_text("#message")
    # the knot/link name arrives from the background identification
    page.wait_for_function("document.querySelector('#knot-name') !== null", timeout=30000)
    # solve: one component, no zero; load the first result
    page.fill("#sv-n", "1")
    page.check("#sv-nozero")
    page.click("#sv-go")
    page.wait_for_selector("#sv-results li", timeout=30000)
    n = redraws(page)
    page.click("#sv-results li >> nth=0")
    wait_redraw(page, n)
    solved = labels_of(page)
    assert 0 not in solved and lkspace.trace("cube", solved).components == 1
    assert page.inner_text("#components") == "1"
    # shared link: the URL hash restores scaffold and labels in a new page
    other = browser.new_page(viewport={"width": 800, "height": 600})
    other.goto(page.url)
    ready(other)
    assert other.evaluate("window.studio.state.sc.name") == "cube" and labels_of(other) == solved
    other.close()
    # catalog: filter one-component designs, click a row, its labels load (the tetrahedron's)
    page.select_option("#cat-col", "components")
    page.fill("#cat-val", "1")
    page.click("#cat-add")
    shown = "JSON.stringify([c.filters, c.sort, c.desc, c.offset])"
    page.wait_for_function(
        f"(c => c.shown === {shown} && c.rows.length > 0)(window.studio.state.catalog)", timeout=20000
    )
    row = page.evaluate("window.studio.state.catalog.rows[0]")
    n = redraws(page)
    page.click("#cat-table tr[data-i='0']")
    wait_redraw(page, n)
    assert labels_of(page) == row  # a catalog row of the tetrahedron, on the tetrahedron
    page.wait_for_function("window.studio.state.sc.name === 'tetrahedron'")
    assert page.inner_text("#components") == "1" == str(lkspace.trace("tetrahedron", row).components)
    # download a GLB and read it back
    trimesh = pytest.importorskip("trimesh")
    with page.expect_download() as info:
        page.click("button[data-format='glb']")
    path = str(tmp_path / "design.glb")
    info.value.save_as(path)
    scene = trimesh.load(path)
    assert len(scene.geometry) == 1
    assert errors == []
    # uploads: a broken file gets a message in the page, a good one opens
    page.set_input_files(
        "#upload", files=[{"name": "broken.obj", "mimeType": "text/plain", "buffer": b"v 0 0\nf 1 9 3\n"}]
    )
    page.wait_for_function("!document.querySelector('#message').hidden", timeout=20000)
    assert "broken.obj" in page.inner_text("#message")
    obj = lkspace.io.obj.format_obj(lkspace.load("octahedron")).encode()
    n = redraws(page)
    page.set_input_files("#upload", files=[{"name": "octa.obj", "mimeType": "text/plain", "buffer": obj}])
    wait_redraw(page, n)
    assert page.evaluate("window.studio.state.sc.origin") == "upload octa.obj"
    assert page.inner_text("#components") == str(lkspace.trace("octahedron", 1).components)
    assert errors == []
    page.close()


def test_periodic_block(studio, browser):
    url, _, _ = studio
    page = browser.new_page(viewport={"width": 900, "height": 700})
    page.goto(url + "#s=honeycomb:cP&t=1,1,1&b=2x2x2")
    ready(page)
    assert page.inner_text("#components") == str(lkspace.trace("honeycomb:cP", 1).components) == "4"
    assert len(page.evaluate("window.studio.state.design.curves.counts")) == 4 * 8  # 4 threads x 8 cells
    assert "loops / threads" in page.inner_text("#summary")
    n = redraws(page)
    page.fill("#block", "3x1x1")
    page.press("#block", "Enter")
    page.dispatch_event("#block", "change")
    wait_redraw(page, n)
    assert len(page.evaluate("window.studio.state.design.curves.copy")) == 4 * 3
    n = redraws(page)
    page.select_option("#builtin", "honeycomb:cP@7x7x7")  # 1,029 faces a cell: opens as one cell, drawn
    page.wait_for_function(f"window.studio.state.latencies.length > {n}", timeout=120000)  # a big first build
    assert page.input_value("#block") == "1x1x1" and page.evaluate("window.studio.state.block") == [1, 1, 1]
    assert set(page.evaluate("window.studio.state.design.curves.copy")) == {0} and page.is_hidden("#message")
    page.close()


def test_relaxed_toggle_redraws_finite_and_periodic_designs(studio, browser):
    url, _, _ = studio
    labels = [0, 0, -1, -1]  # the Hopf link
    plain = lkspace.realize("dihedron:4", labels)
    tight = lkspace.relax(plain)
    page = browser.new_page(viewport={"width": 900, "height": 700})
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url + "#s=dihedron:4&t=0,0,-1,-1")
    ready(page)
    assert page.evaluate("window.studio.state.shown.counts") == [len(c) for c in plain.curves]
    page.check("#relaxed")
    page.wait_for_function("document.getElementById('relax-status').textContent.startsWith('relaxed')", timeout=60000)
    shown = page.evaluate("window.studio.state.shown")
    assert shown["counts"] == [len(c) for c in tight.curves] != [len(c) for c in plain.curves]
    assert shown["strand"] == plain.strand_of.tolist() and page.inner_text("#components") == "2"
    n = redraws(page)
    page.uncheck("#relaxed")
    wait_redraw(page, n)
    assert page.evaluate("window.studio.state.shown.counts") == [len(c) for c in plain.curves]
    assert page.inner_text("#relax-status") == ""
    page.close()
    page = browser.new_page(viewport={"width": 900, "height": 700})  # periodic: relaxed in its cell
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url + "#s=tiling:square&t=2,2&b=2x2")
    ready(page)
    page.check("#relaxed")
    page.wait_for_function("document.getElementById('relax-status').textContent.startsWith('relaxed')", timeout=120000)
    assert len(page.evaluate("window.studio.state.shown.counts")) == 4  # one ring per cell, every copy relaxed
    assert not errors
    page.close()
