import os
import sys

import numpy as np
import pytest
from hypothesis import settings

import lkspace

# The suite starts over a thousand fresh lkspace processes.  Where PYTHONDONTWRITEBYTECODE is
# set (as on the machine these tests were timed on) each of them compiled lkspace's modules from source
# again (0.1 s of CPU for `identify`, more for the studio); the bytecode goes to the
# checkout's __pycache__ folders, which git ignores.
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
sys.dont_write_bytecode = False

# no per-example deadline: on a loaded machine an example may take seconds (tests set their own sizes)
settings.register_profile("lkspace", deadline=None)
settings.load_profile("lkspace")


@pytest.fixture
def tetra():
    return lkspace.load("tetrahedron")


@pytest.fixture
def cube():
    return lkspace.load("cube")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


@pytest.fixture(scope="module")
def browser():
    """Debian's Chromium under Playwright, one per test module (skips where either is missing).

    Not one per session: a running Playwright keeps its event loop set in the main thread, so a later
    module's ``asyncio.run`` (httpx, anyio) would fail with "cannot be called from a running event loop".
    """
    from tests.studio_harness import chromium

    with chromium() as b:
        yield b


@pytest.fixture
def blender():
    """An empty Blender scene with the add-on registered (``bpy``: extra ``[blender]``); live off unless a test turns it on."""
    bpy = pytest.importorskip("bpy")
    import lkspace.blender.addon as addon

    bpy.ops.wm.read_factory_settings(use_empty=True)
    addon.register()
    bpy.context.scene.lkspace.live = False
    yield bpy.context
    addon.unregister()
