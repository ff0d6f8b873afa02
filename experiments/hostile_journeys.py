"""Replay hostile and broken user journeys against the installed ``lkspace`` command.

Each case runs ``lkspace ...`` as a fresh subprocess in its own empty folder (inputs
written first), with a wall-clock limit and a 4 GB address-space cap, and is classified:

- ``clean``: an expected error, exit 1 or 2, exactly one stderr line ``lkspace: error: ...``
  and nothing new left in the folder (``-o`` targets, temporary files);
- ``ok``: an expected success (exit 0);
- ``traceback``: a Python traceback, exit 70 (internal error) or death by a signal;
- ``memory``: the run ran out of memory (under the cap) before saying what was wrong;
- ``hang``: the time limit was reached;
- ``silent``: exit 0 where an error was due;
- ``messy``: an error with a wrong exit code, several lines, or files left behind.

The cases are the journeys of the "every user journey hardened" issue: malformed scaffold
files, huge numbers, FIFOs, devices and symlinks as paths, built-ins with absurd
parameters, options out of range.  Results go to ``results/hostile_journeys.{json,md}``.

Run (with the venv whose ``lkspace`` is to be checked first on PATH)::

    python experiments/hostile_journeys.py [--timeout 60] [--label after]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import stat
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

RESULTS = Path(__file__).resolve().parents[1] / "results"
CUBE_OBJ = "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 1) for z in (0, 1)) + (
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n"
)
QUAD_OBJ = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
TETRA_JSON = {
    "format": "lkspace-scaffold",
    "version": 1,
    "vertices": [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]],
    "faces": [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
}


def unwelded_cube() -> str:
    """A cube OBJ with one vertex copy per face, as modelling tools export it."""
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines: list[str] = []
    faces_out: list[str] = []
    for face in faces:
        start = len(lines) + 1
        lines += [f"v {' '.join(map(str, corners[i]))}" for i in face]
        faces_out.append("f " + " ".join(str(start + k) for k in range(4)))
    return "\n".join(lines + faces_out) + "\n"


def tetra_json(**changes: object) -> str:
    """The tetrahedron scaffold JSON with some fields replaced (``None`` removes a field)."""
    data = {**TETRA_JSON, **changes}
    return json.dumps({k: v for k, v in data.items() if v is not None})


@dataclass
class Case:
    """One journey: its arguments, the files to create first, and the outcome due."""

    name: str
    args: list[str]
    expect: str = "error"  # "error" or "ok"
    files: dict[str, str] = field(default_factory=dict)
    fifo: str | None = None
    device: str | None = None  # a character device (like /dev/null) made at this name in the folder
    symlink: tuple[str, str] | None = None
    keep: tuple[str, ...] = ()  # outputs allowed to exist afterwards (for "ok" cases)


def cases() -> list[Case]:
    """The journeys replayed, grouped as in the issue."""
    big = str(2**63)
    return [
        # broken journeys
        Case("solve a single quad", ["solve", "q.obj", "-n", "1"], "ok", {"q.obj": QUAD_OBJ}),
        Case("solve an unwelded cube", ["solve", "u.obj", "-n", "1"], "ok", {"u.obj": unwelded_cube()}),
        Case(
            "spanning-tree sample of square@8x8",
            [
                "enumerate",
                "tiling:square@8x8",
                "--mode",
                "spanning-trees",
                "--sample",
                "3",
                "--symmetry",
                "none",
                "-o",
                "x.parquet",
            ],
            "ok",
            keep=("x.parquet",),
        ),  # fmt: skip
        Case("info on an unwelded cube", ["info", "u.obj"], "ok", {"u.obj": unwelded_cube()}),
        Case("info on a welded unwelded cube", ["info", "u.obj", "--weld"], "ok", {"u.obj": unwelded_cube()}),
        # scaffold JSON
        Case("JSON edges not a list", ["info", "s.json"], files={"s.json": tetra_json(edges=5)}),
        Case("JSON radial_orders garbage", ["info", "s.json"], files={"s.json": tetra_json(radial_orders=[[0]])}),
        Case("JSON lattice garbage", ["info", "s.json"], files={"s.json": tetra_json(lattice="x")}),
        Case("JSON lattice 2x2 for 3D", ["info", "s.json"], files={"s.json": tetra_json(lattice=[[1, 0], [0, 1]])}),
        Case(
            "JSON 1e400 coordinate",
            ["info", "s.json"],
            files={"s.json": tetra_json().replace("[1, 1, 1]", "[1e400, 1, 1]")},
        ),  # fmt: skip
        Case("JSON 10^30 index", ["info", "s.json"], files={"s.json": tetra_json(faces=[[0, 1, 10**30]])}),
        Case("JSON deep nesting", ["info", "s.json"], files={"s.json": "[" * 100_000 + "]" * 100_000}),
        Case("JSON version true", ["info", "s.json"], files={"s.json": tetra_json(version=True)}),
        Case("JSON not UTF-8", ["info", "s.json"], files={"s.json": "\udcff"}),
        # OBJ
        Case("OBJ with BOM", ["info", "b.obj"], "ok", {"b.obj": "\ufeff" + CUBE_OBJ}),
        Case(
            "OBJ with 1e308 coordinates",
            ["info", "h.obj"],
            "error",
            {"h.obj": CUBE_OBJ.replace("v 1", "v 1e308").replace("v 0", "v -1e308")},
        ),  # fmt: skip
        Case("OBJ with inf", ["info", "i.obj"], files={"i.obj": CUBE_OBJ.replace("v 1 1 1", "v inf 1 1")}),
        Case("a FIFO as input", ["info", "p.obj"], fifo="p.obj"),
        Case("a folder as input", ["info", "."]),
        # labels and label sets
        Case("twist 10^30", ["trace", "cube", "--twist", str(10**30)]),
        Case("twist 2^63", ["trace", "cube", "--twist", big]),
        Case("twist 2^63-1 on book:3", ["trace", "book:3", "--twist", str(2**63 - 1)], "ok"),
        Case("export twist 2^63-1 on book:3", ["export", "book:3", "--twist", str(2**63 - 1), "-o", "b.obj"]),
        Case("label set up to 10^30", ["enumerate", "cube", "--labels", f"0..{10**30}", "-o", "c.parquet"]),
        Case("label set -100..100 on the cube", ["enumerate", "cube", "--labels", "-100..100", "-o", "c.parquet"]),
        Case("twist file {'twists': 5}", ["trace", "cube", "--twist", "t.json"], files={"t.json": '{"twists": 5}'}),
        # built-in parameters
        Case("dihedron:999999999999", ["info", "dihedron:999999999999"]),
        Case("book:999999999999", ["info", "book:999999999999"]),
        Case("honeycomb:cP@1000x1000x1000", ["info", "honeycomb:cP@1000x1000x1000"]),
        # outputs
        Case("-o into a missing folder", ["scaffold", "cube", "-o", "nope/c.obj"]),
        Case("-o empty", ["export", "cube", "--twist", "1", "-o", ""]),
        Case("-o under a file", ["export", "cube", "--twist", "1", "-o", "f.txt/x.obj"], files={"f.txt": "x"}),
        Case("-o a device", ["enumerate", "tetrahedron", "-o", "dev.parquet"], device="dev.parquet"),
        Case("-o t.csv", ["enumerate", "tetrahedron", "-o", "t.csv"], "either", keep=("t.csv",)),
        Case("-o t.json", ["enumerate", "tetrahedron", "-o", "t.json"]),
        Case(
            "-o a symlink",
            ["export", "cube", "--twist", "1", "-o", "link.obj"],
            "ok",
            symlink=("real.obj", "link.obj"),
            keep=("link.obj", "real.obj"),
        ),  # fmt: skip
        Case("--jobs 10^30", ["enumerate", "cube", "--jobs", str(10**30), "-o", "c.parquet"]),
        # options
        Case("--tube-radius nan", ["export", "cube", "--twist", "1", "--tube-radius", "nan", "-o", "c.obj"]),
        Case("--tube-radius -1", ["export", "cube", "--twist", "1", "--tube-radius", "-1", "-o", "c.obj"]),
        Case("--normal-offset nan", ["export", "cube", "--twist", "1", "--normal-offset", "nan", "-o", "c.obj"]),
        Case("solve --time-limit nan", ["solve", "cube", "-n", "1", "--time-limit", "nan"]),
        # budgets
        Case("identify dihedron:3 twist 100000", ["identify", "dihedron:3", "--twist", "100000"]),
        Case("identify a periodic scaffold", ["identify", "honeycomb:cP", "--twist", "1"], "either"),
    ]


def run(case: Case, timeout: float) -> dict[str, object]:
    """Run ``case`` in a fresh folder; return its outcome and what was seen."""
    with tempfile.TemporaryDirectory() as folder:
        for name, text in case.files.items():
            Path(folder, name).write_bytes(text.encode("utf-8", "surrogateescape"))
        if case.fifo:
            os.mkfifo(Path(folder, case.fifo))
        if case.device:  # never a real /dev node: a broken writer would replace it
            os.mknod(Path(folder, case.device), 0o666 | stat.S_IFCHR, os.makedev(1, 3))
        if case.symlink:
            Path(folder, case.symlink[0]).write_text("old\n")
            os.symlink(case.symlink[0], Path(folder, case.symlink[1]))
        before = set(os.listdir(folder))
        env = {**os.environ, "LKSPACE_PROGRESS": "0"}
        start = time.perf_counter()
        try:
            proc = subprocess.run(
                ["lkspace", *case.args], cwd=folder, capture_output=True, text=True, timeout=timeout, env=env,
                preexec_fn=_cap_memory,
            )  # fmt: skip
        except subprocess.TimeoutExpired:
            return {"case": case.name, "outcome": "hang", "seconds": timeout}
        seconds = time.perf_counter() - start
        left = sorted(set(os.listdir(folder)) - before - set(case.keep))
        symlink_kept = case.symlink is None or os.path.islink(Path(folder, case.symlink[1]))
        device_kept = case.device is None or stat.S_ISCHR(os.lstat(Path(folder, case.device)).st_mode)
    err_lines = [line for line in proc.stderr.splitlines() if line.strip() and "warning:" not in line]
    if "Traceback" in proc.stderr or proc.returncode == 70 or proc.returncode < 0:
        outcome = "traceback"
    elif "out of memory" in proc.stderr:
        outcome = "memory"
    elif proc.returncode == 0:
        outcome = "ok" if case.expect in ("ok", "either") and symlink_kept and device_kept else "silent"
    elif case.expect == "ok":
        outcome = "messy"
    else:
        one_line = len(err_lines) == 1 and err_lines[0].startswith("lkspace: error:")
        outcome = "clean" if proc.returncode in (1, 2) and one_line and not left else "messy"
    return {
        "case": case.name,
        "args": case.args,
        "outcome": outcome,
        "exit": proc.returncode,
        "seconds": round(seconds, 2),
        "stderr": proc.stderr.strip().splitlines()[-1:] if proc.stderr.strip() else [],
        "left_behind": left,
    }


def _cap_memory() -> None:
    cap = 4 * 2**30
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))


def main() -> None:
    """Run every case and write the results."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--label", default="after")
    args = parser.parse_args()
    rows = []
    for case in cases():
        row = run(case, args.timeout)
        rows.append(row)
        print(f"{row['outcome']:>9}  {row.get('seconds', 0):6.2f} s  {case.name}: {row.get('stderr', '')}", flush=True)
    tally: dict[str, int] = {}
    for row in rows:
        tally[str(row["outcome"])] = tally.get(str(row["outcome"]), 0) + 1
    RESULTS.mkdir(exist_ok=True)
    out = RESULTS / "hostile_journeys.json"
    data = json.loads(out.read_text()) if out.exists() else {}
    data[args.label] = {"tally": tally, "cases": rows}
    out.write_text(json.dumps(data, indent=1) + "\n")
    lines = ["# Hostile journeys", "", "| label | " + " | ".join(OUTCOMES) + " |", "|---" * (len(OUTCOMES) + 1) + "|"]
    for label, result in data.items():
        lines.append(f"| {label} | " + " | ".join(str(result["tally"].get(k, 0)) for k in OUTCOMES) + " |")
    lines += ["", f"Cases of the last run ({args.label}):", "", "| case | outcome | exit | s | last stderr line |"]
    lines.append("|---|---|---|---|---|")
    for row in rows:
        last = " ".join(row.get("stderr", [])).replace("|", "\\|")[:140]  # type: ignore[arg-type]
        lines.append(
            f"| {row['case']} | {row['outcome']} | {row.get('exit', '')} | {row.get('seconds', '')} | {last} |"
        )
    (RESULTS / "hostile_journeys.md").write_text("\n".join(lines) + "\n")
    print(json.dumps(tally))


OUTCOMES = ("clean", "ok", "traceback", "memory", "hang", "silent", "messy")

if __name__ == "__main__":
    main()
