"""The knot beside the curve, in headless Chromium through the installed ``lkspace studio``.

The diagram panel, common names, "find designs of type", catalog thumbnails and names,
and pinned designs: real clicks, every answer checked against the public API.
"""

import json

import pytest

import lkspace

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
pytest.importorskip("spherogram")

from lkspace.linktypes.common_names import common_name  # noqa: E402
from lkspace.linktypes.lookup import lookup  # noqa: E402
from tests.studio_harness import click_edge, labels_of, ready, running_studio  # noqa: E402

BORROMEAN = [1] * 6
"""The Borromean rings on the tetrahedron (L6a4)."""


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    """``lkspace studio`` on an identified tetrahedron catalog (it has the ``knot_name`` column)."""
    catalog = str(tmp_path_factory.mktemp("knots") / "tetra.parquet")
    lkspace.write_catalog("tetrahedron", catalog, label_set="-1..1", selection=lkspace.Selection(identify=True))
    with running_studio(catalog) as url:
        yield url, catalog


@pytest.fixture
def page(studio, browser):
    page = browser.new_page(viewport={"width": 1300, "height": 900})
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(studio[0] + "#s=tetrahedron&t=" + ",".join(map(str, BORROMEAN)))
    ready(page)
    yield page
    page.close()
    assert not errors, errors


def diagram_strands(page):
    page.wait_for_selector("#diagram svg", timeout=20000)
    return page.evaluate(
        "[...document.querySelectorAll('#diagram path')].map(p => [+p.dataset.strand, p.getAttribute('stroke')])"
    )


def test_diagram_panel_follows_edits_and_the_view(page):
    from lkspace.knots.naming import name_pd

    strands = diagram_strands(page)
    colours = page.evaluate("window.studio.colors()")
    assert sorted({k for k, _ in strands}) == [0, 1, 2]
    assert {c for _, c in strands} == set(colours)  # coloured as the 3D view colours the strands
    answer = page.evaluate("window.studio.diagram.answer")
    assert int(page.inner_text("#diagram-crossings")) == answer["crossings"] == len(answer["pd"])
    named = name_pd(answer["pd"], 3, floer=False)
    assert named.name == "L6a4" == lkspace.identify("tetrahedron", BORROMEAN).name
    # an edit: the diagram is redrawn for the new design
    svg = page.evaluate("window.studio.diagram.svg")
    click_edge(page, 0)
    page.keyboard.press("+")
    page.wait_for_function(f"window.studio.diagram.svg !== {svg!r} && window.studio.diagram.answer.components !== 3")
    labels = labels_of(page)
    expected = lkspace.trace("tetrahedron", labels).components
    assert labels[0] == 2 and page.evaluate("window.studio.diagram.answer.components") == expected
    assert sorted({k for k, _ in diagram_strands(page)}) == list(range(expected))
    # quick edits: the diagram shown is the last design's (answers for the earlier ones are dropped)
    for key in "++-+":
        page.keyboard.press(key)
    labels = labels_of(page)
    page.wait_for_function(
        f"(d => !d.pending && JSON.stringify(d.body.labels) === '{json.dumps(labels, separators=(',', ':'))}')"
        "(window.studio.diagram)",
        timeout=20000,
    )
    page.wait_for_timeout(500)  # any late answer would land now
    fresh = page.evaluate(
        """async () => { const d = window.studio.diagram, e = window.studio.view.camera.matrixWorld.elements;
        const view = [[e[0], e[1], e[2]], [e[4], e[5], e[6]], [e[8], e[9], e[10]]];
        const r = await fetch('/api/diagram', { method: 'POST', headers: { 'Content-Type': 'application/json' },
          body: JSON.stringify({ ...d.body, view }) });
        return (await r.json()).svg === d.svg; }"""
    )
    assert fresh and labels_of(page) == labels and labels[0] == 4
    expected = lkspace.trace("tetrahedron", labels).components
    assert page.evaluate("window.studio.diagram.answer.components") == expected
    # turning the 3D view redraws the diagram as seen from there (same design)
    svg = page.inner_html("#diagram")
    box = page.locator("#canvas").bounding_box()
    x, y = box["x"] + 12, box["y"] + box["height"] - 12  # a corner: a drag on an edge handle would scrub its label
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 150, y - 40, steps=8)
    page.mouse.up()
    page.wait_for_function(f"document.querySelector('#diagram').innerHTML !== {svg!r}", timeout=20000)
    assert page.evaluate("window.studio.diagram.answer.components") == expected
    # enlarge, and close again
    page.click("#diagram")
    assert page.is_visible("#diagram-big svg")
    page.keyboard.press("Escape")
    assert page.is_hidden("#diagram-big")


def test_simplified_diagram_is_drawn_as_the_tables_draw_it_and_stays_when_the_view_turns(page):
    diagram_strands(page)
    page.check("#diagram-simple")
    page.wait_for_function("window.studio.diagram.answer && window.studio.diagram.answer.view === 'simplified'")
    answer = page.evaluate("window.studio.diagram.answer")
    assert answer["components"] == 3 and 6 <= answer["crossings"] <= 8  # L6a4: 6 crossings, the fewest found
    assert int(page.inner_text("#diagram-crossings")) == answer["crossings"]
    assert "in the simplified diagram" in page.inner_text("#diagram-info")
    assert page.locator("#diagram svg.simplified path[data-component]").count() == 3
    svg = page.inner_html("#diagram")
    box = page.locator("#canvas").bounding_box()
    x, y = box["x"] + 12, box["y"] + box["height"] - 12
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 150, y - 40, steps=8)
    page.mouse.up()
    page.wait_for_timeout(800)  # a redraw for the new view would have been asked and answered by now
    assert page.inner_html("#diagram") == svg  # the simplified diagram does not depend on the view
    page.uncheck("#diagram-simple")
    page.wait_for_function("window.studio.diagram.answer.view === 'page'")
    assert page.locator("#diagram path[data-strand]").count() == 3


def test_common_name_of_the_borromean_rings(page):
    page.wait_for_selector("#knot-name", timeout=30000)
    assert page.inner_text("#knot-name") == "L6a4"
    assert page.inner_text("#common-name") == f"({common_name('L6a4')})" == "(Borromean rings)"


def test_lookup_trefoil_lists_designs_and_loads_one(page):
    expected = lookup("trefoil", limit=12).to_json()["designs"]
    page.fill("#find-name", "trefoil")
    page.press("#find-name", "Enter")
    page.wait_for_selector("#find-results li", timeout=30000)
    items = page.locator("#find-results li").all_inner_texts()
    assert len(items) == len(expected)
    for text, d in zip(items, expected, strict=True):
        assert text.startswith(d["chiral_name"]) and d["scaffold"] in text and " ".join(map(str, d["labels"])) in text
    # one on another scaffold than the one open: the scaffold switches, the name is the lookup's
    pick = next(i for i, d in enumerate(expected) if d["scaffold"] != "tetrahedron")
    d = expected[pick]
    page.click(f"#find-results li >> nth={pick}")
    page.wait_for_function(f"window.studio.state.key === {d['scaffold']!r}", timeout=30000)
    assert labels_of(page) == d["labels"]
    page.wait_for_selector("#knot-name", timeout=30000)
    found = lkspace.identify(d["scaffold"], d["labels"])
    assert page.inner_text("#knot-name") == found.name == d["type"] == "3_1"
    assert page.inner_text("#common-name") == f"({d['common_name']})" == f"({common_name('3_1', found.mirror)})"
    # a common name the atlas does not hold is said so
    page.fill("#find-name", "no such knot")
    page.click("#find-go")
    page.wait_for_function("document.querySelector('#find-status').textContent.includes('not a knot or link name')")
    assert page.locator("#find-results li").count() == 0


def test_catalog_rows_have_thumbnails_and_names(page, studio):
    page.wait_for_selector("#cat-table td.thumb svg", timeout=30000)
    rows = page.evaluate("window.studio.state.catalog.rows")
    first = page.evaluate(
        "[...document.querySelectorAll('#cat-table tr[data-i=\"0\"] td.thumb path')].map(p => +p.dataset.strand)"
    )
    assert sorted(first) == list(range(lkspace.trace("tetrahedron", rows[0]).components))
    # filter the Borromean rings by name: each row's name cell says the common name, each row has its picture
    page.select_option("#cat-col", "knot_name")
    page.fill("#cat-val", "L6a4")
    page.click("#cat-add")
    page.wait_for_function(
        "(c => c.filters.length === 1 && c.shown && c.shown.includes('L6a4') && c.rows.length > 0)(window.studio.state.catalog)",
        timeout=20000,
    )
    page.wait_for_selector("#cat-table td.knot-name span", timeout=30000)
    names = page.locator("#cat-table td.knot-name").all_inner_texts()
    assert names and all(n == "L6a4 (Borromean rings)" for n in names)
    page.wait_for_function(
        "[...document.querySelectorAll('#cat-table tr[data-i]')].every(tr => tr.querySelector('td.thumb svg'))",
        timeout=30000,
    )


def test_compare_pins_a_design_and_loads_it_back(page):
    page.wait_for_selector("#knot-name", timeout=30000)
    page.wait_for_selector("#diagram svg", timeout=20000)
    page.click("#compare-pin")
    card = page.locator(".pinned").first
    assert card.locator(".pinned-name").inner_text() == "L6a4"
    assert "Borromean rings" in card.inner_text() and "3 components" in card.inner_text()
    assert card.locator("svg path").count() >= 3
    # edit on: the pinned design stays as it was
    page.fill("#all-value", "0")
    page.click("#set-all")
    page.wait_for_function("window.studio.state.labels.every(t => t === 0)")
    page.wait_for_function("(e => e && e.textContent !== 'L6a4')(document.querySelector('#knot-name'))", timeout=30000)
    assert card.locator(".pinned-name").inner_text() == "L6a4"
    # load it back
    card.locator("button[data-act=load]").click()
    page.wait_for_function("window.studio.state.labels.every(t => t === 1)", timeout=20000)
    page.wait_for_function("document.querySelector('#knot-name')?.textContent === 'L6a4'", timeout=30000)
    assert labels_of(page) == BORROMEAN
