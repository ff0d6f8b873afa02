"""Benchmark: does an edit wait behind exports, and how many identify jobs does a burst leave?

Starts ``python -m lkspace studio cube --port 0 --no-browser`` (the lkspace of ``--source``,
put first on ``PYTHONPATH``, so an older checkout can be measured beside the working tree)
and, over loopback with httpx:

1. redraws the cube (``POST /api/design``, a new design each time) 15 times on an idle
   studio, and 15 more after step 2: the baseline latency;
2. sends 20 SVG exports of ``dihedron:3`` at once (about 1.5 s each alone) and redraws
   every 0.2 s while they run: the latency of an edit under the exports;
3. sends 50 identify requests at once (the dodecahedron, labels 2: about 10 s to name),
   then counts the identify jobs still running (their worker processes, children of the
   studio) right after the last answer;
4. sends 5 solves at once (``honeycomb:cP@4x4x4``, 7 components, a minute's search) and
   counts the solve workers running.

    git archive BASE | tar -x -C /tmp/base
    python experiments/bench_studio_jobs.py --source /tmp/base --label before
    python experiments/bench_studio_jobs.py --source . --label after

Results merge into ``results/studio_jobs.json`` under ``--label``; ``results/studio_jobs.md``
shows every label.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

import httpx
import psutil

RESULTS = Path(__file__).resolve().parents[1] / "results"


def start(source: Path) -> tuple[subprocess.Popen, str]:
    """Start the studio of ``source``; return the process and its URL."""
    env = {**os.environ, "PYTHONPATH": str(source.resolve())}
    proc = subprocess.Popen(
        [sys.executable, "-m", "lkspace", "studio", "cube", "--port", "0", "--no-browser"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=source,  # python -m puts the working folder first on the path
    )
    match = re.search(r"http://\S+/", proc.stdout.readline() if proc.stdout else "")
    if match is None:
        proc.kill()
        raise SystemExit("the studio did not start")
    return proc, match.group(0)


def redraw(client: httpx.Client, i: int) -> float:
    """Seconds for one redraw of the cube (a design not drawn before)."""
    labels = [1] * 12
    labels[i % 12] = 2 + i // 12
    t0 = time.perf_counter()
    r = client.post("/api/design", json={"key": "cube", "labels": labels})
    r.raise_for_status()
    return time.perf_counter() - t0


def in_parallel(n: int, fn) -> list:
    """Run ``fn(i)`` for i < n in n threads at once; return the results in order."""
    out: list = [None] * n

    def run(i: int) -> None:
        out[i] = fn(i)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


def workers(proc: subprocess.Popen) -> int:
    """Worker processes of the studio now: the live children of its fork server (a copy of which each worker is)."""
    count = 0
    for server in psutil.Process(proc.pid).children():
        try:
            if "forkserver" not in " ".join(server.cmdline()):
                continue
            for kid in server.children():
                if "resource_tracker" not in " ".join(kid.cmdline()) and kid.status() != psutil.STATUS_ZOMBIE:
                    count += 1
        except psutil.Error:
            continue
    return count


def measure(source: Path) -> dict:
    """Run the four steps against a fresh studio of ``source``."""
    proc, url = start(source)
    out: dict = {}
    try:
        with httpx.Client(base_url=url, timeout=900) as client:
            for i in range(3):
                redraw(client, 100 + i)
            export = {"key": "dihedron:3", "labels": [1, 1, 1], "format": "svg"}
            client.post("/api/export", json=export).raise_for_status()  # warm: matplotlib imported
            idle = [redraw(client, i) for i in range(15)]

            results: list = []
            t0 = time.perf_counter()
            exporter = threading.Thread(
                target=lambda: results.extend(
                    in_parallel(20, lambda i: client.post("/api/export", json=export).status_code)
                )
            )
            exporter.start()
            time.sleep(0.5)
            busy, i = [], 0
            while exporter.is_alive() and i < 60:
                busy.append(redraw(client, 20 + i))
                i += 1
                time.sleep(0.2)
            exporter.join()
            out["exports_s"] = round(time.perf_counter() - t0, 1)
            idle += [redraw(client, 100 + i) for i in range(15)]  # the machine's load drifts: idle before and after
            out["redraw_idle_ms"] = round(1000 * statistics.median(idle), 1)
            out["export_statuses"] = {str(s): results.count(s) for s in sorted(set(results))}
            out["redraws_under_exports"] = len(busy)
            out["redraw_under_exports_median_ms"] = round(1000 * statistics.median(busy), 1)
            out["redraw_under_exports_max_ms"] = round(1000 * max(busy), 1)
            out["slowdown_under_exports"] = round(statistics.median(busy) / statistics.median(idle), 2)

            body = {"key": "dodecahedron", "labels": [2] * 30}
            answers = in_parallel(50, lambda i: client.post("/api/identify", json=body))
            out["identify_statuses"] = {
                str(s): [a.status_code for a in answers].count(s) for s in {a.status_code for a in answers}
            }
            out["identify_workers_alive"] = workers(proc)
            ids = [a.json()["job"] for a in answers if a.status_code == 200]
            out["identify_jobs_running"] = sum(client.get(f"/api/job/{j}").json()["state"] == "running" for j in ids)

            solve = {"key": "honeycomb:cP@4x4x4", "components": 7, "count": 50, "objective": "min-abs"}
            answers = in_parallel(5, lambda i: client.post("/api/solve", json=solve))
            out["solve_statuses"] = {
                str(s): [a.status_code for a in answers].count(s) for s in {a.status_code for a in answers}
            }
            time.sleep(1)
            ids = [a.json()["job"] for a in answers if a.status_code == 200]
            out["solve_jobs_running"] = sum(client.get(f"/api/job/{j}").json()["state"] == "running" for j in ids)
            out["workers_alive_after_solves"] = workers(proc)
    finally:
        t0 = time.perf_counter()
        proc.send_signal(signal.SIGINT)
        try:
            proc.communicate(timeout=120)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
        out["ctrl_c_s"] = round(time.perf_counter() - t0, 2)
        out["exit_status"] = proc.returncode
    return out


ROWS = [
    ("redraw, idle studio (median of 15 before and 15 after the exports)", "redraw_idle_ms", "ms"),
    ("redraw while 20 SVG exports run (median)", "redraw_under_exports_median_ms", "ms"),
    ("redraw while 20 SVG exports run (worst)", "redraw_under_exports_max_ms", "ms"),
    ("redraw under exports / idle (medians)", "slowdown_under_exports", "×"),
    ("redraws measured during the exports", "redraws_under_exports", ""),
    ("20 exports: wall time", "exports_s", "s"),
    ("20 exports: answers", "export_statuses", ""),
    ("50 identify requests: answers", "identify_statuses", ""),
    ("identify jobs running after the 50", "identify_jobs_running", ""),
    ("worker processes alive after the 50", "identify_workers_alive", ""),
    ("5 solve requests: answers", "solve_statuses", ""),
    ("solve jobs running after the 5", "solve_jobs_running", ""),
    ("worker processes alive after the solves", "workers_alive_after_solves", ""),
    ("Ctrl-C to exit (with a solve running)", "ctrl_c_s", "s"),
    ("exit status", "exit_status", ""),
]


def table(runs: dict) -> str:
    """Markdown of every labelled run."""
    labels = list(runs)
    lines = [
        "# Studio jobs: edits never wait, jobs bounded",
        "",
        "`python experiments/bench_studio_jobs.py` (loopback, httpx, the `lkspace studio` command in a"
        " subprocess; 2 shared cores, timings noisy).",
        "Before: exports in the thread pool that answers edits, no bound on jobs. After: exports written by"
        " one worker process at a time (16 more in line, then 429), one identify / relax / solve at a time.",
        "Other engineers' jobs load the machine (load averages below): absolute latencies are the machine's;"
        " compare the ratio of a redraw under exports to an idle one, the job counts and Ctrl-C.",
        "",
        "| | " + " | ".join(labels) + " |",
        "|---|" + "---:|" * len(labels),
    ]
    for text, key, unit in ROWS:
        cells = []
        for label in labels:
            value = runs[label]["figures"].get(key)
            if isinstance(value, dict):
                cells.append(", ".join(f"{n} × {s}" for s, n in value.items()))
            else:
                cells.append(f"{value:,} {unit}".strip() if value is not None else "–")
        lines.append(f"| {text} | " + " | ".join(cells) + " |")
    lines.append("")
    for label in labels:
        run = runs[label]
        lines.append(f"- {label}: {run['when']}, load average {run['load']} at the start, commit {run['commit']}")
    return "\n".join(lines) + "\n"


def main() -> None:
    """Measure, merge into results/studio_jobs.json, write results/studio_jobs.md."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", type=Path, default=Path(__file__).resolve().parents[1])
    parser.add_argument("--label", default="after")
    parser.add_argument("--commit", default=None, help="the commit of --source (default: git rev-parse HEAD there)")
    args = parser.parse_args()
    load = [round(x, 1) for x in os.getloadavg()]
    commit = (
        args.commit
        or subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=args.source, capture_output=True, text=True
        ).stdout.strip()
    )
    figures = measure(args.source)
    print(json.dumps(figures, indent=1))
    path = RESULTS / "studio_jobs.json"
    runs = json.loads(path.read_text()) if path.exists() else {}
    runs[args.label] = {
        "figures": figures,
        "when": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "load": load,
        "commit": commit,
    }
    path.write_text(json.dumps(runs, indent=1) + "\n")
    (RESULTS / "studio_jobs.md").write_text(table(runs))


if __name__ == "__main__":
    main()
