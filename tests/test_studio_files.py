"""Save, open and share in the studio, driven in headless Chromium through the installed CLI.

Design files saved and opened back, shared links, the PNG of the view, the WebM animations,
download names, the phone layout and the fit.  Files are captured as real downloads.
"""

import base64
import io
import json
import math
import pathlib

import numpy as np
import pytest

from lkspace.studio.filenames import design_stem

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
Image = pytest.importorskip("PIL.Image")

from .studio_harness import ready, running_studio, start_studio, stop_studio  # noqa: E402


@pytest.fixture(scope="module")
def studio():
    with running_studio("cube") as url:
        yield url


@pytest.fixture
def page(browser, studio):
    context = browser.new_context(viewport={"width": 1200, "height": 800}, accept_downloads=True)
    pg = context.new_page()
    pg.goto(studio)
    ready(pg)
    yield pg
    identified(pg)  # no worker starting when the studio is stopped
    context.close()


def state(page):
    return page.evaluate(
        """() => { const s = window.studio.state, v = window.studio.view;
        return { key: s.key, labels: s.labels, nulls: [...s.nulls].sort((a, b) => a - b), block: s.block,
                 position: v.camera.position.toArray(), target: v.controls.target.toArray(),
                 message: document.getElementById('message').hidden ? '' : document.getElementById('message').textContent }; }"""
    )


def settle(page, labels):
    """Wait until the page shows ``labels`` (its redraw answered)."""
    page.wait_for_function(
        f"JSON.stringify(window.studio.state.labels) === '{json.dumps(labels, separators=(',', ':'))}'"
    )
    page.wait_for_function("document.getElementById('busy').hidden")


def identified(page):
    """Wait until the page's identify job is over (Ctrl-C while a worker starts is another matter)."""
    page.wait_for_function(
        "document.getElementById('knot-name') !== null || !/waiting|running/.test(document.getElementById('identify').textContent)",
        timeout=90000,
    )


def click_edge(page, e):
    p = page.evaluate(f"window.studio.edgeScreen({e})")
    page.mouse.click(p["x"], p["y"])
    page.wait_for_function(f"window.studio.state.selected === {e}")


def make_design(page):
    """Edit through the page: every label 2, edge 3 to 3, one null side, the camera dragged."""
    page.fill("#all-value", "2")
    page.click("#set-all")
    click_edge(page, 3)
    page.click("#plus")
    page.locator("#sides input").first.check()
    labels = [2] * 12
    labels[3] = 3
    settle(page, labels)
    box = page.locator("#canvas").bounding_box()
    x, y = box["x"] + box["width"] * 0.3, box["y"] + box["height"] * 0.8
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 120, y - 60, steps=8)
    page.mouse.up()
    page.wait_for_timeout(400)  # the moved camera goes into the link after 250 ms
    return labels


def download(page, selector, timeout=30000):
    with page.expect_download(timeout=timeout) as info:
        page.click(selector)
    d = info.value
    return d.suggested_filename, pathlib.Path(d.path()).read_bytes()


def wait_for_camera(page, position, tol=1e-6):
    """Wait (120 s at most: the page redraws the design first, slow on a loaded machine) until its camera stands at ``position``."""
    page.wait_for_function(
        f"window.studio.view.camera.position.toArray().every((x, i) => Math.abs(x - {json.dumps(list(position))}[i]) <= {tol})",
        timeout=120000,
    )


def close(a, b, tol):
    return all(math.isclose(x, y, abs_tol=tol) for x, y in zip(a, b, strict=True))


def test_save_change_open_back(page, tmp_path):
    labels = make_design(page)
    saved = state(page)
    assert saved["nulls"] and saved["position"] != [0, 0, 0]
    name, content = download(page, "#save-design")
    assert name == design_stem("cube", labels, saved["nulls"]) + ".design.json"
    data = json.loads(content)
    assert data["format"] == "lkspace-design" and data["scaffold"] == "cube" and data["labels"] == labels
    assert close(data["view"]["position"], saved["position"], 1e-9)
    # change everything: another scaffold, another camera
    page.select_option("#builtin", "tetrahedron")
    page.wait_for_function("window.studio.state.key === 'tetrahedron' && window.studio.state.ready")
    path = tmp_path / name
    path.write_bytes(content)
    page.set_input_files("#open-design", str(path))
    settle(page, labels)
    wait_for_camera(page, saved["position"])  # set once the scaffold has loaded, just after the labels show
    back = state(page)
    assert back["key"] == "cube" and back["nulls"] == saved["nulls"] and not back["message"]
    assert close(back["position"], saved["position"], 1e-6) and close(back["target"], saved["target"], 1e-6)
    # the scaffold file input tells a design from a scaffold too
    page.select_option("#builtin", "octahedron")
    page.wait_for_function("window.studio.state.key === 'octahedron'")
    page.set_input_files("#upload", str(path))
    settle(page, labels)
    assert state(page)["key"] == "cube"
    # a broken design file: one message, the page keeps its design
    bad = tmp_path / "bad.design.json"
    bad.write_text(json.dumps({**data, "labels": labels[:5]}))
    page.set_input_files("#open-design", str(bad))
    page.wait_for_function("!document.getElementById('message').hidden")
    assert "expected 12 twist labels (one per edge of cube), got 5" in state(page)["message"]
    assert state(page)["labels"] == labels


def test_cli_opens_design_file_and_still_opens_scaffold_files(page, tmp_path):
    labels = make_design(page)
    saved = state(page)
    name, content = download(page, "#save-design")
    path = tmp_path / name
    path.write_bytes(content)
    proc, url = start_studio(str(path))
    try:
        other = page.context.new_page()
        other.goto(url)
        ready(other)
        settle(other, labels)
        got = state(other)
        assert got["nulls"] == saved["nulls"] and close(got["position"], saved["position"], 1e-6)
        identified(other)
    finally:
        stop_studio(proc)
    scaffold_name, scaffold = download(page, "#exports [data-format=json]")  # a scaffold file, not a design
    assert scaffold_name == design_stem("cube", labels, saved["nulls"]) + ".json"
    (tmp_path / scaffold_name).write_bytes(scaffold)
    proc, url = start_studio(str(tmp_path / scaffold_name))
    try:
        other = page.context.new_page()
        other.goto(url)
        ready(other)
        settle(other, labels)
        assert other.evaluate("window.studio.state.key").startswith("id:")
        identified(other)
    finally:
        stop_studio(proc)


def test_shared_link_reopens_the_same_picture(page, browser):
    labels = make_design(page)
    saved = state(page)
    link = page.url
    assert "&v=" in link and len(link) < 200
    other = browser.new_context(viewport={"width": 1200, "height": 800}).new_page()
    other.goto(link)
    ready(other)
    settle(other, labels)
    got = state(other)
    dist = float(np.linalg.norm(np.subtract(saved["position"], saved["target"])))
    assert got["nulls"] == saved["nulls"] and not got["message"]
    assert close(got["position"], saved["position"], dist * 1e-4) and close(got["target"], saved["target"], dist * 1e-4)
    page.keyboard.press("Escape")  # the selected edge's halo and a hovered handle are not part of the design
    page.mouse.move(0, 0)
    page.wait_for_timeout(200)
    a = Image.open(io.BytesIO(page.locator("#canvas").screenshot())).convert("L")
    b = Image.open(io.BytesIO(other.locator("#canvas").screenshot())).convert("L")
    # the same picture up to the strands' colours: the edited page's follow its edits, the link's are fresh
    drawn_a, drawn_b = np.asarray(a) < 245, np.asarray(b) < 245
    assert drawn_a.mean() > 0.02 and (drawn_a != drawn_b).mean() < 0.01
    again = browser.new_context(viewport={"width": 1200, "height": 800}).new_page()
    again.goto(link)
    ready(again)
    settle(again, labels)
    assert again.evaluate("window.studio.colors()") == other.evaluate("window.studio.colors()")  # a link: one colouring
    again.context.close()
    other.context.close()


@pytest.mark.parametrize(
    ("link", "words"),
    [
        ("#s=id:0123456789abcdef&t=1,2,3", "is not held by this studio"),
        ("#s=../../etc/passwd", "is not a built-in scaffold name"),
        ("#s=tetrahedron&t=1,1,1", "3 labels for the 6 edges of tetrahedron"),
        ("#s=tetrahedron&t=1,x,1,1,1,1", "labels: integers expected"),
        ("#s=tetrahedron&t=1,1,1,1,1,1&n=99", "nulls: side indices in 0..11 expected"),
        ("#s=tetrahedron&v=1,2,nope", "view: 6 or 9 numbers expected"),
    ],
)
def test_bad_or_stale_link_opens_with_a_message(browser, studio, link, words):
    pg = browser.new_page(viewport={"width": 1000, "height": 700})
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(studio + link)
    ready(pg)
    pg.wait_for_function("!document.getElementById('message').hidden", timeout=20000)
    s = state(pg)
    assert words in s["message"] and s["message"].startswith("link:")
    assert s["key"] in ("cube", "tetrahedron") and len(s["labels"]) in (12, 6) and not errors
    assert pg.evaluate("window.studio.state.design.curves !== undefined")  # a drawn design, not a broken page
    pg.close()


def test_png_of_the_view(page):
    make_design(page)
    size = page.evaluate("[document.getElementById('canvas').width, document.getElementById('canvas').height]")
    canvas = page.evaluate("document.getElementById('canvas').toDataURL('image/png')")
    name, png = download(page, "#png-view")
    shown_state = state(page)
    assert name == design_stem("cube", shown_state["labels"], shown_state["nulls"]) + "_view.png"
    image = Image.open(io.BytesIO(png)).convert("RGB")
    assert list(image.size) == size
    pixels = np.asarray(image, float)
    assert pixels.std() > 10 and (pixels.sum(axis=2) < 600).mean() > 0.02  # strands drawn, not a blank white
    shown = np.asarray(Image.open(io.BytesIO(base64.b64decode(canvas.split(",")[1]))).convert("RGB"), float)
    assert np.abs(shown - pixels).mean() < 1  # the canvas as it is on screen
    page.check("#png-2x")
    name2, png2 = download(page, "#png-view")
    assert name2 == name.replace("_view.png", "_view-2x.png")
    assert list(Image.open(io.BytesIO(png2)).size) == [2 * size[0], 2 * size[1]]
    assert page.evaluate("document.getElementById('canvas').width") == size[0]  # back to its own size


def webm_ok(page, data):
    """A WebM file the browser decodes, of the canvas's size."""
    if data[:4] != b"\x1a\x45\xdf\xa3" or b"webm" not in data[:64]:
        return False
    size = page.evaluate(
        """async (b64) => { const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
        const video = document.createElement('video'); video.muted = true;
        video.src = URL.createObjectURL(new Blob([bytes], { type: 'video/webm' }));
        await new Promise((ok, bad) => { video.onloadedmetadata = ok; video.onerror = () => bad(new Error('not decodable')); });
        return [video.videoWidth, video.videoHeight]; }""",
        base64.b64encode(data).decode(),
    )
    return size == page.evaluate("[document.getElementById('canvas').width, document.getElementById('canvas').height]")


def bounded_and_cancellable(page):
    """A twist over too many labels is refused in one message; a turntable under way stops on cancel."""
    page.fill("#an-range", "-50..50")
    page.click("#an-twist")
    page.wait_for_function("!document.getElementById('message').hidden")
    assert "at most 41 labels" in state(page)["message"]
    page.click("#an-turn")
    page.wait_for_function("document.getElementById('an-status').textContent.includes('frame')")
    page.click("#an-cancel")
    page.wait_for_function("document.getElementById('an-status').textContent === 'cancelled'", timeout=30000)


def test_twist_animation_and_a_cancelled_turntable(page):
    make_design(page)
    before = state(page)
    click_edge(page, 5)
    page.fill("#an-range", "0..1")
    name, data = download(page, "#an-twist", timeout=90000)
    assert webm_ok(page, data) and name.endswith("_twist-e5_0..1.webm") and name.startswith("cube_")
    assert state(page)["labels"] == before["labels"]
    bounded_and_cancellable(page)
    after = state(page)
    assert close(after["position"], before["position"], 1e-9) and after["labels"] == before["labels"]  # put back


@pytest.mark.slow  # 121 frames in software rendering, then the 3-step twist: half a minute
def test_turntable_and_twist_animations(page):
    make_design(page)
    before = state(page)
    name, data = download(page, "#an-turn", timeout=90000)
    assert webm_ok(page, data) and name.endswith("_turntable.webm") and name.startswith("cube_")
    after = state(page)
    assert close(after["position"], before["position"], 1e-9)  # the camera is put back
    click_edge(page, 5)
    page.fill("#an-range", "-1..1")
    name, data = download(page, "#an-twist", timeout=90000)
    assert webm_ok(page, data) and name.endswith("_twist-e5_-1..1.webm")
    assert state(page)["labels"] == before["labels"]
    bounded_and_cancellable(page)


def test_phone_layout_every_panel_reachable(browser, studio):
    context = browser.new_context(viewport={"width": 390, "height": 844}, has_touch=True)
    pg = context.new_page()
    pg.goto(studio)
    ready(pg)
    pg.wait_for_timeout(500)
    pg.screenshot(path="/tmp/studio_phone.png")
    assert pg.evaluate("document.documentElement.scrollWidth") <= 390  # nothing off the side
    canvas = pg.locator("#canvas").bounding_box()
    assert canvas["width"] >= 380 and canvas["height"] >= 300
    for tab, panel in [("left", "#left"), ("right", "#right")]:
        pg.click(f"#tabs [data-panel={tab}]")
        assert pg.locator(panel).is_visible()
        for control in pg.locator(f"{panel} button, {panel} input:not([type=file]), {panel} select").all():
            if not control.is_visible():
                continue
            control.scroll_into_view_if_needed()
            box = control.bounding_box()
            assert 0 <= box["x"] and box["x"] + box["width"] <= 390 and box["y"] + box["height"] <= 845
            hit = control.evaluate(
                "(el) => { const r = el.getBoundingClientRect(), x = r.left + r.width / 2, y = r.top + r.height / 2; "
                "const top = document.elementFromPoint(x, y); return top === el || el.contains(top) || top.contains(el); }"
            )
            assert hit  # on screen and not covered: a tap reaches it
    pg.click("#tabs [data-panel=right]")
    assert not pg.locator("#left").is_visible() and pg.locator("#summary").is_visible()
    pg.screenshot(path="/tmp/studio_phone_read.png")
    pg.click("#tabs [data-panel=left]")
    pg.locator("#png-view").scroll_into_view_if_needed()
    pg.screenshot(path="/tmp/studio_phone_export.png")
    assert pg.locator("#save-design").is_visible()
    context.close()


def test_desktop_layout_and_fit_fills_the_canvas(page):
    page.screenshot(path="/tmp/studio_desktop.png")
    assert not page.locator("#tabs").is_visible()
    assert round(page.locator("#left").bounding_box()["width"]) == 250
    assert round(page.locator("#right").bounding_box()["width"]) == 260
    for width, height in [(1200, 800), (900, 500), (700, 900)]:
        page.set_viewport_size({"width": width, "height": height})
        page.wait_for_timeout(300)
        page.click("#fit")
        spread = page.evaluate(
            """() => { const v = window.studio.view, r = v.canvas.getBoundingClientRect();
            let x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
            for (const mesh of v.groups.strands.children) { // one tube mesh a curve
              const pos = mesh.geometry.getAttribute('position');
              for (let i = 0; i < pos.count; i += 7) { const s = v.screenOf([pos.getX(i), pos.getY(i), pos.getZ(i)]);
                x0 = Math.min(x0, s.x); x1 = Math.max(x1, s.x); y0 = Math.min(y0, s.y); y1 = Math.max(y1, s.y); } }
            return [(x1 - x0) / r.width, (y1 - y0) / r.height, x0 - r.left, r.right - x1, y0 - r.top, r.bottom - y1]; }"""
        )
        assert max(spread[0], spread[1]) > 0.75, spread  # the design fills the canvas in its tighter direction
        assert min(spread[2:]) > 0, spread  # and all of it is in view
