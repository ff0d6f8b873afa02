"""Knot and link names for the panel, found by ``lkspace identify`` in a child process.

Identification (SnapPy, seconds) must not freeze Blender, and it cannot run in a thread:
SnapPy's exterior computations only work in a process's main thread (in another thread
they fail, and the name comes out ambiguous).  So the design is written to a scaffold
file and ``python -m lkspace identify FILE --json`` runs beside Blender, with Blender's
own Python; a timer (:func:`poll_jobs`) moves the answer to the object's
``lkspace.knot`` when it is ready, if the design has not changed meanwhile.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from typing import Any

import bpy
import numpy as np

from lkspace.errors import LkspaceError
from lkspace.io.files import write
from lkspace.model.scaffold import Scaffold


@dataclass
class Job:
    """A running identification: the design's state key, the child process and its folder."""

    key: str
    process: subprocess.Popen[str]
    folder: str


JOBS: dict[str, Job] = {}
"""Object name -> its running identification."""


def text_of(found: dict[str, Any]) -> str:
    """Return the panel's text for the JSON of ``lkspace identify``: the name, or why there is none."""
    if "error" in found:
        return f"not identified: {found['error'].get('message')}"
    if found.get("name") is None:
        return str(found.get("status", "unknown"))
    return str(found["name"]) + (" (mirror)" if found.get("mirror") else "")


def identify_now(scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray) -> str:
    """Identify in this process (blocking) and return the panel's text."""
    from lkspace.knots.recognition import identify

    try:
        return text_of(identify(scaffold, labels, nulls).to_dict())
    except LkspaceError as exc:
        return f"not identified: {exc}"


def start(name: str, key: str, scaffold: Scaffold, labels: np.ndarray, nulls: np.ndarray) -> None:
    """Start identifying object ``name``'s design (replacing a job already running for it)."""
    stop(name)
    folder = tempfile.mkdtemp(prefix="lkspace-identify-")
    path = os.path.join(folder, "design.json")
    write(scaffold.with_labels(labels, nulls), path)
    process = subprocess.Popen(
        [sys.executable, "-m", "lkspace", "identify", path, "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        env={**os.environ, "LKSPACE_PROGRESS": "0"},
    )
    JOBS[name] = Job(key, process, folder)
    if not bpy.app.timers.is_registered(poll_jobs):  # persistent: a file loaded meanwhile still reaps the job
        bpy.app.timers.register(poll_jobs, first_interval=0.5, persistent=True)


def stop(name: str) -> None:
    """Stop object ``name``'s identification, if one runs, and remove its folder."""
    job = JOBS.pop(name, None)
    if job is not None:
        if job.process.poll() is None:
            job.process.kill()
        job.process.communicate()
        shutil.rmtree(job.folder, ignore_errors=True)


def poll_jobs() -> float | None:
    """Timer: move finished identifications to their objects; stop polling when none is left."""
    for name, job in list(JOBS.items()):
        if job.process.poll() is None:
            continue
        out, _ = job.process.communicate()
        del JOBS[name]
        shutil.rmtree(job.folder, ignore_errors=True)
        try:
            text = text_of(json.loads(out.strip().splitlines()[-1]))
        except (IndexError, json.JSONDecodeError):
            text = "not identified: lkspace identify gave no answer"
        obj = bpy.data.objects.get(name)
        if obj is not None and obj.lkspace.key == job.key:
            obj.lkspace.knot = text
    for window in getattr(bpy.context.window_manager, "windows", []):
        for area in window.screen.areas:
            area.tag_redraw()
    return 0.5 if JOBS else None


def stop_all() -> None:
    """Stop every identification and the timer polling them (when the add-on is unregistered).

    The timer must go too: a Python timer still registered when the ``bpy`` module shuts
    down is freed after the interpreter, which crashes the process (exit status 139)
    whether or not a job was running.  Blender itself unregisters add-ons before it frees
    its timers; the add-on makes the ``bpy`` module do the same at exit.
    """
    for name in list(JOBS):
        stop(name)
    if bpy.app.timers.is_registered(poll_jobs):
        bpy.app.timers.unregister(poll_jobs)
