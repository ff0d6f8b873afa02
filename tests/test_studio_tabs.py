"""The studio in Chromium as issue 35 used it: two tabs on one studio, a phone, clicks at edge midpoints,
the read-out right after an edit and the name line's crossing number."""

import pytest

import lkspace

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")

from .studio_harness import ready, running_studio  # noqa: E402

BORROMEAN = "#s=tetrahedron&t=1,1,1,1,1,1"  # L6a4: 6 crossings
SLOW = "#s=dodecahedron&t=" + ",".join(["2"] * 30)  # about 10 s to name


@pytest.fixture(scope="module")
def studio():
    with running_studio("cube") as url:
        yield url


def named(page, timeout=90000):
    page.wait_for_function(
        "document.querySelector('#knot-name') !== null || /: (cancelled|error)/.test(document.getElementById('identify').textContent)",
        timeout=timeout,
    )
    return page.inner_text("#identify")


def test_two_tabs_each_get_their_own_name(browser, studio):
    context = browser.new_context(viewport={"width": 1200, "height": 800})
    a, b = context.new_page(), context.new_page()
    a.goto(studio + SLOW)
    ready(a)
    # A's identify running (or, on a fast machine with the shipped kernels, already done: the check below still holds)
    a.wait_for_function(
        "/running/.test(document.getElementById('identify').textContent) || document.querySelector('#knot-name') !== null",
        timeout=60000,
    )
    b.goto(studio + BORROMEAN)  # its identify starts while tab A's runs
    ready(b)
    assert "L6a4" in named(b)
    text = named(a)  # before, tab B's identify cancelled A's for good: "identify: cancelled"
    assert "cancelled" not in text and a.inner_text("#knot-name") == "unknown"  # 12 components, beyond the tables
    context.close()


def test_the_name_line_gives_the_crossing_number_of_the_type(browser, studio):
    page = browser.new_page(viewport={"width": 1200, "height": 800})
    page.goto(studio + BORROMEAN)
    ready(page)
    named(page)
    found = lkspace.identify("tetrahedron", [1] * 6)
    assert found.name == "L6a4"
    # the type's crossing number, from the tables, whatever the simplified diagram kept (it had 8
    # crossings with the spherogram of earlier runs, 6 with 2.4.1: the name line must not follow it)
    assert page.inner_text("#knot-crossings") == "6 crossings"
    page.close()


def test_an_edit_clears_the_last_designs_name_at_once(browser, studio):
    page = browser.new_page(viewport={"width": 1200, "height": 800})
    page.goto(studio + BORROMEAN)
    ready(page)
    named(page)
    pos = page.evaluate("window.studio.edgeScreen(0)")
    page.mouse.click(pos["x"], pos["y"])
    assert page.evaluate("window.studio.state.selected") == 0
    page.keyboard.press("+")  # the redraw is on its way: nothing of L6a4 may stay on the read-out
    text = page.inner_text("#identify")
    assert "L6a4" not in text and "waiting" in text, text
    pending, now = page.evaluate(
        "[document.getElementById('right').classList.contains('pending'), document.getElementById('identify').innerText]"
    )  # read together: the redraw may already be done (a cube's takes 25 ms), then the read-out is the new design's
    assert pending or "L6a4" not in now, now
    page.wait_for_function("!document.getElementById('right').classList.contains('pending')", timeout=20000)
    assert "L6a4" not in named(page)
    page.close()


@pytest.mark.parametrize("scaffold", ["cube", "tetrahedron", "octahedron"])
def test_a_click_at_an_edge_midpoint_selects_that_edge(browser, studio, scaffold):
    page = browser.new_page(viewport={"width": 1200, "height": 800})
    page.goto(f"{studio}#s={scaffold}")
    ready(page)
    n = lkspace.load(scaffold).n_edges
    picked = []
    for e in range(n):  # a strand crosses every edge at its midpoint: the click means the edge
        pos = page.evaluate(f"window.studio.edgeScreen({e})")
        page.mouse.click(pos["x"], pos["y"])
        picked.append(page.evaluate("window.studio.state.selected"))
        page.keyboard.press("Escape")
    assert picked == list(range(n))
    page.close()


def test_a_phone_gets_the_phone_layout(browser, studio):
    context = browser.new_context(
        viewport={"width": 390, "height": 844}, is_mobile=True, has_touch=True, device_scale_factor=3
    )
    page = context.new_page()
    page.goto(studio)
    ready(page)
    assert page.evaluate("window.innerWidth") == 390  # without the viewport tag a phone lays the page out at 980 px
    assert page.evaluate("document.documentElement.scrollWidth") <= 390
    canvas = page.locator("#canvas").bounding_box()
    assert 380 <= canvas["width"] <= 390 and canvas["height"] >= 300
    assert page.locator("#tabs").is_visible()
    for tab in ("left", "right"):
        page.tap(f"#tabs [data-panel={tab}]")
        wide = page.evaluate(
            f"[...document.querySelectorAll('#{tab} *')].filter((el) => el.getBoundingClientRect().right > 391).map((el) => el.id || el.tagName)"
        )
        assert wide == [], wide
    page.tap("#tabs [data-panel=left]")
    pos = page.evaluate("window.studio.edgeScreen(2)")
    page.touchscreen.tap(pos["x"], pos["y"])
    assert page.evaluate("window.studio.state.selected") == 2
    before = page.evaluate("window.studio.state.latencies.length")
    page.locator("#plus").scroll_into_view_if_needed()
    page.tap("#plus")
    page.wait_for_function(f"window.studio.state.latencies.length > {before}", timeout=20000)
    assert page.evaluate("window.studio.state.labels[2]") == 2
    context.close()
