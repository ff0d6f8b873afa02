"""The strand tubes in the browser: after every edit the page draws exactly the server's curves, rebuilds only
the new ones, and each strand keeps its colour (in the view and in the Read panel's strand table); the copies
of a ring take a colour per tone of their cells.

The studio is started by the installed CLI; the keys are pressed in headless Chromium; the curves are
checked against :func:`lkspace.realize`.
"""

import numpy as np
import pytest

import lkspace
from lkspace.formats.colors import PALETTE, colour_slots, curve_colors, curve_tones, hex_colors
from lkspace.geometry.params import RealizeOptions

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
from lkspace.studio.curves import curve_key  # noqa: E402
from tests.studio_harness import running_studio  # noqa: E402

NAME = "honeycomb:cP@3x3x3"
BLOCK = [[0, 0, 0], [1, 0, 0]]  # the page's block 2x1x1: two lattice copies of every thread


@pytest.fixture(scope="module")
def url():
    """``lkspace studio honeycomb:cP@3x3x3 --no-browser --port 0``: yields its URL; stopped with Ctrl-C."""
    with running_studio(NAME) as url:
        yield url


SEEN = """() => {
  const s = window.studio.state, v = window.studio.view.strands;
  return {
    labels: s.labels.map(Number), curves: s.design.curves, strands: s.design.strands,
    drawn: window.studio.view.groups.strands.children.map((m) => ({ key: m.userData.key, color: '#' + m.material.color.getHexString(), mark: m.userData.mark ?? null })),
    colors: s.design.strands.map((_, k) => v.colorOf(k)),
    swatches: [...document.querySelectorAll('#strands .swatch')].map((e) => e.style.backgroundColor),
  };
}"""


def rgb(color):
    return "rgb({}, {}, {})".format(*(int(color[i : i + 2], 16) for i in (1, 3, 5)))


@pytest.mark.parametrize("keys", ["+-+", pytest.param("++-+--", marks=pytest.mark.slow)])  # a redraw a key
def test_edits_redraw_the_new_strands_only_and_keep_colours(url, browser, keys):
    sc = lkspace.load(NAME)
    page = browser.new_page(viewport={"width": 1200, "height": 800})
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(f"{url}#s={NAME}&b=2x1x1")
    page.wait_for_function("window.studio && window.studio.state.ready", timeout=60000)
    for e in range(sc.n_edges):  # select an edge whose edits change some strands
        pos = page.evaluate(f"window.studio.edgeScreen({e})")
        page.mouse.click(pos["x"], pos["y"])
        if page.evaluate("window.studio.state.selected") is not None:
            break
    before, rebuilt, kept = None, 0, 0
    for key in keys:
        page.evaluate("window.studio.view.groups.strands.children.forEach((m, i) => { m.userData.mark = i; })")
        n = page.evaluate("window.studio.state.latencies.length")
        page.keyboard.press(key)
        page.wait_for_function(f"window.studio.state.latencies.length > {n}", timeout=60000)
        seen = page.evaluate(SEEN)
        real = lkspace.realize(
            sc, seen["labels"], options=RealizeOptions(embedding="later", translations=np.array(BLOCK))
        )
        keys = [curve_key(c, cl) for c, cl in zip(real.curves, real.closed, strict=True)]
        # exactly the server's curves are drawn, one mesh each, in the colour of their strand
        assert sorted(d["key"] for d in seen["drawn"]) == sorted(keys) == sorted(seen["curves"]["keys"])
        color_of = {d["key"]: d["color"] for d in seen["drawn"]}
        assert seen["curves"]["tone"] == curve_tones(real).tolist()  # the tone of a ring's cell, 0 for the rest
        units = {(s, t): color_of[k] for k, s, t in zip(keys, real.strand_of.tolist(), curve_tones(real).tolist())}
        assert [color_of[k] for k in keys] == [units[s, t] for s, t in zip(real.strand_of, curve_tones(real))]
        assert all(units[s, 0] == seen["colors"][s] for s, _ in units)  # a strand's colour is its copy's in cell 0
        for s in set(real.strand_of.tolist()):  # the copies of a ring in cells of different tones differ
            assert len({c for (r, _), c in units.items() if r == s}) == len({t for r, t in units if r == s})
        assert seen["swatches"] == [rgb(c) for c in seen["colors"]]  # the Read panel uses the same colours
        # a curve drawn before keeps its mesh; the others are new
        old = [d for d in seen["drawn"] if d["mark"] is not None]
        rebuilt += len(seen["drawn"]) - len(old)
        kept += len(old)
        assert sum(seen["curves"]["sent"]) <= len(seen["drawn"]) - len(old)  # points travel for new curves only
        # a strand named by the same smallest port keeps its colour
        now = {s["port"]: c for s, c in zip(seen["strands"], seen["colors"], strict=True)}
        if before is not None:
            common = set(now) & set(before)
            assert common and all(now[q] == before[q] for q in common)
        before = now
    assert rebuilt > 0 and kept > rebuilt  # every edit changed some strands, most stayed as they were
    assert len(set(seen["colors"])) > 1 and not errors, errors
    page.close()


@pytest.mark.parametrize(
    ("name", "fragment", "block"),
    [
        ("tiling:square", "&t=2,2&b=2x2", [[0, 0], [1, 0], [0, 1], [1, 1]]),  # chainmail: one ring, four tones
        (NAME, "&b=2x1x1", BLOCK),
        ("cube", "&t=0,1,0,0,0,0,0,0,0,0,0,-1", None),
    ],
)
def test_a_page_drawn_afresh_is_coloured_as_export_colours_it(browser, name, fragment, block):
    """Fresh strands take their export colour slot (a ring's tones took the colours in the order its curves came)."""
    with running_studio(name) as url:
        page = browser.new_page(viewport={"width": 1000, "height": 700})
        page.goto(f"{url}#s={name}{fragment}")
        page.wait_for_function(
            "window.studio && window.studio.state.ready && window.studio.state.design", timeout=60000
        )
        seen = page.evaluate(SEEN)
        page.close()
    sc = lkspace.load(name)
    translations = None if block is None else np.array(block)
    real = lkspace.realize(sc, seen["labels"], options=RealizeOptions(embedding="later", translations=translations))
    keys = [curve_key(c, cl) for c, cl in zip(real.curves, real.closed, strict=True)]
    assert seen["curves"]["slot"] == [
        dict(zip(keys, colour_slots(real).tolist(), strict=True))[k] for k in seen["curves"]["keys"]
    ]
    color_of = {d["key"]: d["color"] for d in seen["drawn"]}
    exported = hex_colors(curve_colors(real, PALETTE))
    assert [color_of[k] for k in keys] == [c.lower() for c in exported]
    assert len(set(exported)) > 2


SEAM = """async () => {
  const { tubeArrays } = await import('/static/tubes.js');
  const n = 200, p = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) { // a trefoil: its rotation-minimizing frame comes back turned
    const t = 2 * Math.PI * i / n;
    p.set([(2 + Math.cos(3 * t)) * Math.cos(2 * t), (2 + Math.cos(3 * t)) * Math.sin(2 * t), Math.sin(3 * t)], 3 * i);
  }
  const { normal } = tubeArrays(p, true, 0.1, 8);
  const jump = (i, j) => Math.max(...[...Array(8).keys()].map((s) => Math.hypot(
    normal[3 * (i * 8 + s)] - normal[3 * (j * 8 + s)], normal[3 * (i * 8 + s) + 1] - normal[3 * (j * 8 + s) + 1],
    normal[3 * (i * 8 + s) + 2] - normal[3 * (j * 8 + s) + 2])));
  const inner = Math.max(...[...Array(n - 1).keys()].map((i) => jump(i, i + 1)));
  return { seam: jump(n - 1, 0), inner };
}"""


def test_closed_tubes_have_no_seam(url, browser):
    """The last ring of a closed tube meets the first as any two neighbours meet (no pinch)."""
    page = browser.new_page()
    page.goto(url)
    got = page.evaluate(SEAM)
    page.close()
    assert got["inner"] < 0.2 and got["seam"] < 1.5 * got["inner"], got
