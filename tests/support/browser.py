"""The live app in a subprocess and Debian's Chromium under Playwright, shared by the
browser test, the latency benchmark and the README screenshot script."""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run"]


def free_port() -> int:
    """A TCP port free on 127.0.0.1 now."""
    with socket.socket() as so:
        so.bind(("127.0.0.1", 0))
        return so.getsockname()[1]


@contextlib.contextmanager
def app_server(out: Path, timeout: float = 60.0, args: tuple[str, ...] = ()):
    """``clutchfem app`` on a free port writing into ``out`` (with further ``args``); yields
    its URL, stops it after.

    NiceGUI's own test mode keys on PYTEST_* variables: they are left out of its environment."""
    port = free_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTEST")}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])
    out.mkdir(parents=True, exist_ok=True)
    log = open(out / "app.log", "wb")  # a file, not a pipe nobody reads: a chatty server never blocks
    proc = subprocess.Popen([sys.executable, "-m", "clutchfem.cli", "app", "--port", str(port), "--no-browser",
                             "--out", str(out), *args], env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        t0 = time.time()
        while True:
            if proc.poll() is not None or time.time() - t0 > timeout:
                proc.kill()
                raise RuntimeError("the app did not start: " + (out / "app.log").read_text(errors="replace")[-2000:])
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.3)
        yield f"http://127.0.0.1:{port}/"
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()


def launch_chromium(playwright):
    """Debian's Chromium, headless, without its background services."""
    return playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
