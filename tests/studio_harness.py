"""What the studio's browser tests share: the installed ``lkspace studio`` started as a user starts
it and stopped with Ctrl-C, Debian's Chromium driven by Playwright, and small page probes.

``window.studio`` (the page's own state) only tells a test where things are and what the page
holds; every answer is checked against the public API in the test process.
"""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import subprocess
import sys
from collections.abc import Iterator

import pytest

CHROMIUM = "/usr/bin/chromium"
ARGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def lkspace_command() -> list[str]:
    """The installed ``lkspace`` command (``python -m lkspace`` where it is not on PATH)."""
    exe = shutil.which("lkspace")
    return [exe] if exe else [sys.executable, "-m", "lkspace"]


def start_studio(*args: str) -> tuple[subprocess.Popen, str]:
    """``lkspace studio ARGS --no-browser --port 0``: the process and the URL it printed."""
    proc = subprocess.Popen(
        [*lkspace_command(), "studio", *args, "--no-browser", "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stdout.readline()
    match = re.search(r"(http://127\.0\.0\.1:\d+/)", line)
    assert match, f"no URL in {line!r}; stderr: {proc.stderr.read() if proc.poll() is not None else ''}"
    return proc, match.group(1)


def stop_studio(proc: subprocess.Popen) -> None:
    """Stop a studio with Ctrl-C: it must exit with status 130 and print no traceback."""
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)  # a hang detector
    assert proc.returncode == 130 and "Traceback" not in err, err


@contextlib.contextmanager
def running_studio(*args: str) -> Iterator[str]:
    """A studio started with ``args`` for the ``with`` block: yields its URL."""
    pytest.importorskip("starlette")
    pytest.importorskip("uvicorn")
    proc, url = start_studio(*args)
    try:
        yield url
    finally:
        stop_studio(proc)


@contextlib.contextmanager
def serving(studio) -> Iterator:
    """``studio`` served from a thread of this process for the ``with`` block: yields an httpx client."""
    import httpx

    from lkspace.studio.server import start_in_thread

    url, stop = start_in_thread(studio)
    try:
        with httpx.Client(base_url=url, timeout=60) as client:
            yield client
    finally:
        stop()


@contextlib.contextmanager
def chromium() -> Iterator:
    """Debian's Chromium, headless, under Playwright (skips the test where either is missing)."""
    sync_api = pytest.importorskip("playwright.sync_api")
    if not os.path.exists(CHROMIUM):
        pytest.skip(f"no Chromium at {CHROMIUM} (Debian package 'chromium')")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            yield browser
        finally:
            browser.close()


def ready(page) -> None:
    """Wait until the page has drawn its first design."""
    page.wait_for_function("window.studio && window.studio.state.ready", timeout=30000)


def redraws(page) -> int:
    """How many redraws the page has finished."""
    return page.evaluate("window.studio.state.latencies.length")


def wait_redraw(page, before: int) -> None:
    """Wait for a redraw after the ``before``-th."""
    page.wait_for_function(f"window.studio.state.latencies.length > {before}", timeout=20000)


def labels_of(page) -> list[int]:
    """The labels the page holds."""
    return [int(t) for t in page.evaluate("window.studio.state.labels")]


def click_edge(page, e: int):
    """Click edge ``e`` where it is on screen; return the edge the page selected."""
    pos = page.evaluate(f"window.studio.edgeScreen({e})")
    page.mouse.click(pos["x"], pos["y"])
    return page.evaluate("window.studio.state.selected")
