"""``lkspace studio`` on the command line: start-up stays light, the URL is printed, --host warns, errors are one line."""

import re
import signal
import subprocess
import sys

import pytest

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
httpx = pytest.importorskip("httpx")


def test_help_does_not_import_the_web_stack():
    code = (
        "import sys; from lkspace.cli import main; main(['--help']); main(['studio', '--help']);"
        " print(sorted(m for m in ('starlette', 'uvicorn', 'pyarrow', 'lkspace.studio.app') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert "studio" in out.stdout and out.stdout.strip().splitlines()[-1] == "[]"


def test_serves_a_file_from_the_command_line_warns_on_host_and_stops_on_ctrl_c(tmp_path):
    mesh = tmp_path / "tetra.obj"
    subprocess.run([sys.executable, "-m", "lkspace", "scaffold", "tetrahedron", "-o", str(mesh)], check=True)
    proc = subprocess.Popen(
        [sys.executable, "-m", "lkspace", "studio", str(mesh), "--no-browser", "--port", "0", "--host", "0.0.0.0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        url = re.search(r"http://\S+/", proc.stdout.readline()).group(0)
        info = httpx.get(url + "api/info", timeout=30).json()
        assert info["initial"].startswith("id:")  # the file, held by content id: the page never sends its path
        design = httpx.post(url + "api/design", json={"key": info["initial"], "labels": [1] * 6}, timeout=30).json()
        assert design["components"] == 3
    finally:
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)  # a hang detector
    assert proc.returncode == 130
    assert "lkspace: warning: listening on 0.0.0.0" in err and "Traceback" not in err


@pytest.mark.parametrize(
    ("args", "code", "text"),
    [
        (["no-such-scaffold"], 2, "neither a file nor a built-in"),
        (["cube", "--port", "99999"], 2, "99999"),
    ],
)
def test_bad_usage_is_one_line(args, code, text):
    out = subprocess.run(
        [sys.executable, "-m", "lkspace", "studio", *args, "--no-browser"], capture_output=True, text=True, timeout=60
    )
    assert out.returncode == code and text in out.stderr and "Traceback" not in out.stderr


def test_a_port_in_use_is_one_line():
    import socket

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen(1)
        port = taken.getsockname()[1]
        out = subprocess.run(
            [sys.executable, "-m", "lkspace", "studio", "cube", "--no-browser", "--port", str(port)],
            capture_output=True,
            text=True,
            timeout=60,
        )
    assert out.returncode == 2 and f"cannot listen on 127.0.0.1:{port}" in out.stderr
    assert out.stderr.count("\n") == 1


@pytest.mark.parametrize("rounds", [8, pytest.param(25, marks=pytest.mark.slow)])
def test_ctrl_c_stops_the_studio_with_its_jobs_after_long_use(rounds):
    """The installed command, 8 rounds of design and clearance requests from 4 threads (25: a few hundred
    requests), identify / solve / relax / exports running: Ctrl-C ends it all."""
    import shutil
    import threading
    import time

    psutil = pytest.importorskip("psutil")
    command = [shutil.which("lkspace") or pytest.fail("the lkspace command is not installed")]
    proc = subprocess.Popen(
        [*command, "studio", "cube", "--no-browser", "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        url = re.search(r"http://\S+/", proc.stdout.readline()).group(0)
        with httpx.Client(base_url=url, timeout=120) as client:

            def edits(seed):
                for i in range(rounds):
                    labels = [1] * 12
                    labels[(seed + i) % 12] = 2 + i % 3
                    assert client.post("/api/design", json={"key": "cube", "labels": labels}).status_code == 200
                    # 409: a newer design's measurement stopped this one (its answer would be stale)
                    assert client.post("/api/clearance", json={"key": "cube", "labels": labels}).status_code in (
                        200,
                        409,
                    )

            threads = [threading.Thread(target=edits, args=(k,)) for k in range(4)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            identify = client.post("/api/identify", json={"key": "dodecahedron", "labels": [2] * 30}).json()["job"]
            solve = {"key": "honeycomb:cP@4x4x4", "components": 7, "count": 50, "objective": "min-abs"}
            solving = client.post("/api/solve", json=solve).json()["job"]

            def ask(path, body):
                try:
                    client.post(f"/api/{path}", json=body)
                except httpx.HTTPError:
                    pass  # cut short by Ctrl-C

            pending = [("design", {"key": "icosahedron", "labels": [1] * 30, "relax": True})]
            pending += [("export", {"key": "tetrahedron", "labels": [1] * 6, "format": "svg"})] * 3
            for path, body in pending:
                threading.Thread(target=ask, args=(path, body), daemon=True).start()
            time.sleep(1)
            states = [client.get(f"/api/job/{j}").json()["state"] for j in (identify, solving)]
            assert states[1] == "running", states
            assert states[0] in ("running", "done"), states  # a name may come from the cache at once
            family = psutil.Process(proc.pid).children(recursive=True)
            assert len(family) >= 2  # the fork server and the solve's worker at least
            started = time.monotonic()
            proc.send_signal(signal.SIGINT)
            _, err = proc.communicate(timeout=60)
            seconds = time.monotonic() - started
    finally:
        if proc.poll() is None:  # no hang here either: the workers hold the studio's stderr open
            for p in [*psutil.Process(proc.pid).children(recursive=True), proc]:
                p.kill()
            proc.communicate(timeout=60)
    assert proc.returncode == 130 and "Traceback" not in err, err
    print(f"Ctrl-C to exit: {seconds:.2f} s")
    psutil.wait_procs(family, timeout=5)
    assert [p.pid for p in family if p.is_running() and p.status() != psutil.STATUS_ZOMBIE] == []
