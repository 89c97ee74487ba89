"""Start-up cost of the faces: ``import clutchfem`` (the public API, imported lazily),
``clutchfem --help`` (the command line answers without loading the FE stack) and the first
use of ``cf.analyze`` (the FE stack itself), and the time to the first line a design command
shows on a terminal (``clutchfem analyze concept4 ...`` in a pseudo-terminal: its spinner,
which starts before the FE stack is loaded).  Minimum and median of N fresh interpreters.

    .venv/bin/python benchmarks/bench_import.py [--n 9]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import subprocess
import sys
import time

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


def _time(cmd: list[str], n: int) -> list[float]:
    out = []
    for _ in range(n):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        out.append(time.perf_counter() - t0)
    return out


def _visible(data: bytes) -> bool:
    """Whether terminal output ``data`` holds a visible character (not only control sequences:
    rich hides the cursor before it draws anything)."""
    import re

    text = re.sub(rb"\x1b\[[0-9;?]*[ -/]*[@-~]|\x1b[@-_]", b"", data)
    return any(32 < b < 127 or b >= 0xC0 for b in text)


def _first_output(cmd: list[str], n: int) -> list[float]:
    """Seconds from the start of ``cmd`` to the first visible character on a pseudo-terminal
    (then killed)."""
    import pty
    import select

    out = []
    for _ in range(n):
        leader, follower = pty.openpty()
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=follower, stderr=follower)
        os.close(follower)
        seen, got = b"", float("inf")
        while time.perf_counter() - t0 < 30.0:
            ready, _, _ = select.select([leader], [], [], 30.0)
            if not ready:
                break
            try:
                seen += os.read(leader, 4096)
            except OSError:
                break
            if _visible(seen):
                got = time.perf_counter() - t0
                break
        out.append(got)
        proc.kill()
        proc.wait()
        os.close(leader)
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=9)
    args = ap.parse_args(argv)
    py = sys.executable
    base = _time([py, "-c", "pass"], args.n)
    rows = [("python -c pass (the interpreter alone)", base),
            ("python -c 'import clutchfem'", _time([py, "-c", "import clutchfem"], args.n)),
            ("python -c 'import clutchfem as cf; cf.Design' (the FE stack)",
             _time([py, "-c", "import clutchfem as cf; cf.Design"], args.n)),
            ("clutchfem --help", _time([py, "-m", "clutchfem.cli", "--help"], args.n)),
            ("clutchfem analyze concept4: its first line on a terminal",
             _first_output([py, "-m", "clutchfem.cli", "analyze", "concept4"], args.n)),
            ("clutchfem solve concept4: its first line on a terminal",
             _first_output([py, "-m", "clutchfem.cli", "solve", "concept4"], args.n))]
    print(f"machine: {platform.machine()} {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"{time.strftime('%Y-%m-%d %H:%M')}, load {os.getloadavg()[0]:.1f}")
    for name, t in rows:
        print(f"{name:<65} min {min(t):.3f} s, median {statistics.median(t):.3f} s")
    print(f"import clutchfem beyond the interpreter: {min(rows[1][1]) - min(base):.3f} s (min)")


if __name__ == "__main__":
    main()
