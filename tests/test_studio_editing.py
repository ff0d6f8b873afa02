"""Direct manipulation in the studio: edge handles, strand picking, keys, scrubbing, orbit edits.

The page is driven in headless Chromium (the studio started by the installed CLI, real clicks,
drags and keys); ``window.studio`` only tells where things are on screen and what the page
holds.  Every answer is checked against the public API on the Python side.
"""

import numpy as np
import pytest

import lkspace
from lkspace.studio.designs import Cache, design
from lkspace.symmetry.group import symmetry_group
from tests.studio_harness import running_studio

FRACTIONS = (0.5, 0.35, 0.65, 0.2, 0.8)  # points along a handle tried in turn (a strand may cover its midpoint)


def traced_edges(tr):
    """The edges each strand of ``tr`` passes: the edge of the side each of its steps leaves by."""
    side_edge = tr.scaffold.side_edge
    starts = tr.strand_starts
    return [sorted(set(side_edge[tr.steps[starts[k] : starts[k + 1]] // 2].tolist())) for k in range(tr.components)]


@pytest.mark.parametrize(
    ("name", "labels", "block"),
    [("cube", 1, None), ("cube", [2, 1, 1, -1, 0, 1, 1, 1, 3, 1, 1, 1], None), ("honeycomb:cP@3x3x3", 1, [1, 1, 1])],
)
def test_design_lists_the_edges_each_strand_passes(name, labels, block):
    scaffold = lkspace.load(name)
    tr = lkspace.trace(scaffold, labels)
    grid = None if block is None else np.zeros((1, 3), np.int64)
    out = design(scaffold, tr.labels, None, grid, Cache(), name)
    assert [s["edges"] for s in out["strands"]] == traced_edges(tr)
    assert all(s["edges"] for s in out["strands"])


@pytest.fixture(scope="module")
def studio():
    """``lkspace studio cube --no-browser --port 0``: yields its URL; stopped with Ctrl-C (exit 130)."""
    with running_studio("cube") as url:
        yield url


def open_page(browser, url, errors, size=(1100, 800)):
    page = browser.new_page(viewport={"width": size[0], "height": size[1]})
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    page.wait_for_function("window.studio && window.studio.state.ready", timeout=60000)
    return page


def redraws(page):
    return page.evaluate("window.studio.state.latencies.length")


def wait_redraw(page, before):
    page.wait_for_function(f"window.studio.state.latencies.length > {before}", timeout=30000)


def labels_of(page):
    return [int(t) for t in page.evaluate("window.studio.state.labels")]


def selected(page):
    return page.evaluate("window.studio.state.selected")


def rod_point(page, e, f):
    """Pixel (rounded, as a mouse sees it) of the point at fraction ``f`` along edge ``e``'s handle."""
    p = page.evaluate(
        """([e, f]) => { const h = window.studio.handles, a = h.a, b = h.b;
        return window.studio.view.screenOf([0, 1, 2].map((k) => a[3 * e + k] + f * (b[3 * e + k] - a[3 * e + k]))); }""",
        [e, f],
    )
    return round(p["x"]), round(p["y"])


def click_rod(page, e):
    """Click along edge ``e``'s handle until the page selects it; return the pixel that did (or None)."""
    for f in FRACTIONS:
        x, y = rod_point(page, e, f)
        page.mouse.click(x, y)
        if selected(page) == e:
            return x, y
    return None


def pickable(page, edges):
    """Edges of ``edges`` the page's picker (the one the click handler calls) cannot reach at any point along their handle."""
    return page.evaluate(
        """([edges, fractions]) => edges.filter((e) => !fractions.some((f) => {
          const h = window.studio.handles, a = h.a, b = h.b;
          const p = window.studio.view.screenOf([0, 1, 2].map((k) => a[3 * e + k] + f * (b[3 * e + k] - a[3 * e + k])));
          const r = window.studio.view.canvas.getBoundingClientRect();
          return p.x > r.left && p.x < r.right && p.y > r.top && p.y < r.bottom && h.pick(Math.round(p.x), Math.round(p.y)) === e; }))""",
        [edges, list(FRACTIONS)],
    )


def test_handles_keys_scrub_and_help_on_the_cube(studio, browser):
    errors = []
    page = open_page(browser, studio + "#s=cube", errors)
    page.screenshot(path="/tmp/studio_editing_cube.png")
    # every edge handle can be clicked; the selected one is drawn thick, with its label at its midpoint
    for e in range(12):
        assert click_rod(page, e) is not None, f"edge {e}: no point of its handle selects it"
        assert page.inner_text("#edge-index") == str(e)
        label = page.locator(f"#edge-labels span[data-edge='{e}']:not([hidden])")
        assert label.inner_text() == "1" and "sel" in label.get_attribute("class")
    # empty space clears the selection
    page.mouse.click(300, 780)
    assert selected(page) is None and page.inner_text("#edge-info") == "click an edge"
    # hover: the handle under the mouse is lit and its label shown
    x, y = rod_point(page, 5, 0.3)
    page.mouse.move(x, y)
    page.wait_for_function("window.studio.handles.hovered !== null", timeout=5000)
    hovered = page.evaluate("window.studio.handles.hovered")
    assert page.locator(f"#edge-labels span[data-edge='{hovered}']:not([hidden])").count() == 1
    # N / P step through the edges (wrapping), digits set the label, Shift+digit the negative one
    page.keyboard.press("n")
    assert selected(page) == 0
    page.keyboard.press("n")
    page.keyboard.press("n")
    page.keyboard.press("p")
    assert selected(page) == 1
    page.keyboard.press("p")
    page.keyboard.press("p")
    assert selected(page) == 11
    n = redraws(page)
    page.keyboard.press("2")
    wait_redraw(page, n)
    assert labels_of(page) == [1] * 11 + [2]
    assert page.inner_text("#components") == str(lkspace.trace("cube", labels_of(page)).components)
    n = redraws(page)
    page.keyboard.press("Shift+Digit3")
    wait_redraw(page, n)
    assert labels_of(page)[11] == -3
    n = redraws(page)
    page.keyboard.press("0")
    wait_redraw(page, n)
    assert labels_of(page)[11] == 0
    assert page.locator("#edge-labels span[data-edge='11']").inner_text() == "0"
    # Enter: type any label in the field, Enter sets it and hands the keys back to the view
    page.keyboard.press("Enter")
    assert page.evaluate("document.activeElement.id") == "label"
    n = redraws(page)
    page.keyboard.type("-12")
    page.keyboard.press("Enter")
    wait_redraw(page, n)
    assert labels_of(page)[11] == -12
    page.wait_for_function("document.activeElement.id !== 'label'", timeout=5000)
    page.keyboard.press("n")
    assert selected(page) == 0
    # scrub: drag a handle up three steps (12 px a step): +3, one undo step for the whole drag
    before = labels_of(page)
    x, y = click_rod(page, 7)
    page.mouse.move(x, y)
    page.mouse.down()
    for dy in range(4, 44, 4):
        page.mouse.move(x, y - dy)
    page.mouse.up()
    page.wait_for_function(f"window.studio.state.labels[7] == {before[7] + 3}", timeout=30000)
    page.wait_for_function("document.getElementById('busy').hidden", timeout=30000)
    after = labels_of(page)
    assert after[7] == before[7] + 3 and [t for i, t in enumerate(after) if i != 7] == before[:7] + before[8:]
    assert page.evaluate("window.studio.view.controls.enabled")  # the drag did not orbit, and orbiting is back
    n = redraws(page)
    page.keyboard.press("Control+z")
    wait_redraw(page, n)
    assert labels_of(page) == before
    # ? shows the help overlay (every key listed); Escape closes it and keeps the selection, then clears it
    assert page.is_hidden("#help")
    page.keyboard.press("?")
    assert page.is_visible("#help")
    text = page.inner_text("#help")
    for key in ("N / P", "0 … 9", "Shift + 1 … 9", "Enter", "O", "Escape", "drag an edge"):
        assert key in text
    page.screenshot(path="/tmp/studio_editing_help.png")
    page.keyboard.press("Escape")
    assert page.is_hidden("#help") and selected(page) == 7
    page.click("#help-button")
    assert page.is_visible("#help")
    page.click("#help-button")
    assert page.is_hidden("#help")
    page.keyboard.press("Escape")
    assert selected(page) is None
    assert errors == []
    page.close()


def strand_pixel(page):
    """Pixels of curve points, nearest the camera first, each with the strand its curve draws."""
    return page.evaluate(
        """() => { const S = window.studio.state, v = window.studio.view, c = S.shown;
        const bin = atob(c.points), b = new Uint8Array(bin.length); for (let i = 0; i < bin.length; i++) b[i] = bin.charCodeAt(i);
        const p = new Float32Array(b.buffer), out = []; let start = 0;
        c.counts.forEach((n, k) => { for (let i = start + 1; i < start + n - 1; i += 2) { const s = v.screenOf([p[3*i], p[3*i+1], p[3*i+2]]);
          if (s.z < 1) out.push({ x: Math.round(s.x), y: Math.round(s.y), z: s.z, strand: c.strand[k] }); } start += n; });
        return out.sort((a, b) => a.z - b.z).slice(0, 40); }"""
    )


@pytest.mark.parametrize(
    "name", ["cube", "honeycomb:cP@2x2x2", pytest.param("honeycomb:cP@3x3x3", marks=pytest.mark.slow)]
)  # a periodic block of lattice copies too
def test_strand_click_lights_its_component_and_edges(studio, browser, name):
    errors = []
    labels = [2, 1, 1, -1, 0, 1, 1, 1, 3, 1, 1, 1] if name == "cube" else None
    url = studio + f"#s={name}" + (f"&t={','.join(map(str, labels))}" if labels else "&b=2x1x1")
    page = open_page(browser, url, errors)
    labels = labels_of(page)
    expected = traced_edges(lkspace.trace(name, labels))
    for point in strand_pixel(page):  # the nearest curve point not under an edge handle
        page.mouse.click(point["x"], point["y"])
        if page.evaluate("window.studio.strands.strand") is not None:
            break
        page.keyboard.press("Escape")
    lit = page.evaluate("window.studio.strands.strand")
    assert lit == point["strand"], "a click on the front-most strand lights that strand"
    lit_edges = page.evaluate("[...window.studio.handles.strandEdges].sort((a, b) => a - b)")
    assert lit_edges == expected[lit]
    # N / P walk the lit strand's edges
    page.keyboard.press("n")
    assert selected(page) == expected[lit][0]
    page.keyboard.press("p")
    page.keyboard.press("p")
    assert selected(page) == expected[lit][-2]
    page.screenshot(path=f"/tmp/studio_editing_strand_{name.replace(':', '_').replace('@', '_')}.png")
    # empty space clears the strand and the selection
    page.mouse.click(300, 780)
    assert (
        page.evaluate("window.studio.strands.strand") is None
        and page.evaluate("window.studio.handles.strandEdges") is None
    )
    assert selected(page) is None
    # an edit clears the lit strand (its strands change)
    page.mouse.click(point["x"], point["y"])
    assert page.evaluate("window.studio.strands.strand") is not None
    page.keyboard.press("n")
    n = redraws(page)
    page.keyboard.press("+")
    wait_redraw(page, n)
    assert page.evaluate("window.studio.strands.strand") is None
    assert errors == []
    page.close()


def test_orbit_edits_set_exactly_the_orbit(studio, browser):
    errors = []
    page = open_page(browser, studio + "#s=truncated-octahedron", errors)
    scaffold = lkspace.load("truncated-octahedron")
    perms, _ = symmetry_group(scaffold).action("rotations")
    orbit = sorted(set(perms[:, 0].tolist()))
    assert 1 < len(orbit) < scaffold.n_edges
    before = labels_of(page)
    page.keyboard.press("n")  # edge 0
    page.keyboard.press("o")
    assert page.is_checked("#orbit")
    page.wait_for_function("window.studio.state.orbits", timeout=30000)
    assert sorted(page.evaluate("window.studio.handles.orbitOf(0)")) == orbit  # the orbit is lit
    lit = page.evaluate(
        "[...document.querySelectorAll('#edge-labels span.lit:not([hidden]), #edge-labels span.sel:not([hidden])')].map(s => +s.dataset.edge)"
    )
    assert sorted(lit) == orbit
    n = redraws(page)
    page.keyboard.press("2")
    wait_redraw(page, n)
    after = labels_of(page)
    assert [e for e in range(scaffold.n_edges) if after[e] != before[e]] == orbit and {after[e] for e in orbit} == {2}
    # a scrub applies to the orbit too
    x, y = click_rod(page, 0)
    page.mouse.move(x, y)
    page.mouse.down()
    for dy in range(3, 18, 3):
        page.mouse.move(x, y - dy)
    page.mouse.up()
    page.wait_for_function("window.studio.state.labels[0] == 3", timeout=30000)
    page.wait_for_function("document.getElementById('busy').hidden", timeout=30000)
    after = labels_of(page)
    assert {after[e] for e in orbit} == {3} and all(
        after[e] == before[e] for e in range(scaffold.n_edges) if e not in orbit
    )
    # O again: orbit editing off, one edge at a time
    page.keyboard.press("o")
    assert not page.is_checked("#orbit")
    n = redraws(page)
    page.keyboard.press("5")
    wait_redraw(page, n)
    assert [e for e, (a, b) in enumerate(zip(labels_of(page), after)) if a != b] == [0]
    assert errors == []
    page.close()


def check_picking_on_big_scaffolds(studio, browser, side, cells, clicks):
    """The square tiling ``side``x``side`` seen from above: every edge reachable by the picker, ``clicks``
    sampled edges by real clicks; honeycomb:cP@``cells``^3 (most edges inside) from close by: ``clicks`` sampled edges."""
    errors = []
    n = 2 * side * side
    page = open_page(browser, studio + f"#s=tiling:square@{side}x{side}&b=1x1", errors)
    page.evaluate(
        """() => { const v = window.studio.view, p = window.studio.state.sc.edge_points, c = [0, 1, 2].map((k) => {
          let lo = Infinity, hi = -Infinity; for (let i = k; i < p.length; i += 3) { lo = Math.min(lo, p[i]); hi = Math.max(hi, p[i]); }
          return (lo + hi) / 2; });
        v.controls.target.set(...c); v.camera.position.set(c[0], c[1], c[2] + 100); v.camera.far = 1000; v.camera.updateProjectionMatrix();
        v.controls.update(); v.render(); }"""
    )  # from above: every edge in sight
    assert pickable(page, list(range(n))) == []
    for e in np.random.default_rng(1).choice(n, clicks, replace=False).tolist():
        assert click_rod(page, e) is not None, f"edge {e}"
    shown = page.evaluate("document.querySelectorAll('#edge-labels span:not([hidden])').length")
    assert 1 <= shown <= 400  # labels culled, the selected one always among them
    page.close()
    n = 3 * cells**3
    page = open_page(browser, studio + f"#s=honeycomb:cP@{cells}x{cells}x{cells}&b=1x1x1", errors)
    for e in np.random.default_rng(2).choice(n, clicks, replace=False).tolist():
        page.evaluate(
            """(e) => { const v = window.studio.view, h = window.studio.handles, a = h.a, b = h.b;
            const m = [0, 1, 2].map((k) => (a[3 * e + k] + b[3 * e + k]) / 2), d = [0, 1, 2].map((k) => b[3 * e + k] - a[3 * e + k]);
            const side = Math.abs(d[0]) > 0.1 ? [0, 0.5, 0.5] : Math.abs(d[1]) > 0.1 ? [0.5, 0, 0.5] : [0.5, 0.5, 0];
            v.controls.target.set(...m); v.camera.position.set(m[0] + side[0], m[1] + side[1], m[2] + side[2]);
            v.camera.near = 0.01; v.camera.updateProjectionMatrix(); v.controls.update(); v.render(); }""",
            e,
        )
        assert click_rod(page, e) is not None, f"edge {e}"
    page.close()
    assert errors == []


def test_picking_on_big_scaffolds(studio, browser):
    # 512 edges (over the 400 whose labels are all drawn) swept by the picker, 2 clicked, and 2 of the
    # 192 of honeycomb:cP@4x4x4; 375 there and 4 clicks each: test_picking_on_bigger_scaffolds; the 2,048-
    # and 1,029-edge scaffolds take minutes in software rendering: test_picking_on_the_biggest_scaffolds
    check_picking_on_big_scaffolds(studio, browser, 16, 4, 2)


@pytest.mark.slow
def test_picking_on_bigger_scaffolds(studio, browser):
    check_picking_on_big_scaffolds(studio, browser, 16, 5, 4)


@pytest.mark.slow
def test_picking_on_the_biggest_scaffolds(studio, browser):
    check_picking_on_big_scaffolds(studio, browser, 32, 7, 8)  # 2,048 and 1,029 edges


def test_picking_never_the_lattice_copies(studio, browser):
    # a block of lattice copies: a click on a copy's handle position picks nothing (copies are drawn, not edited)
    errors = []
    page = open_page(browser, studio + "#s=honeycomb:cP&b=3x1x1", errors)
    assert pickable(page, [0, 1, 2]) == []
    for e in range(3):
        x, y = page.evaluate(
            """(e) => { const sc = window.studio.state.sc, p = sc.edge_points, L = sc.lattice;
            const s = window.studio.view.screenOf([0, 1, 2].map((k) => (p[6 * e + k] + p[6 * e + 3 + k]) / 2 + 2 * L[0][k]));
            return [Math.round(s.x), Math.round(s.y)]; }""",
            e,
        )
        page.mouse.click(x, y)
        assert selected(page) is None, f"the copy of edge {e} two cells over was picked"
    assert errors == []
    page.close()
