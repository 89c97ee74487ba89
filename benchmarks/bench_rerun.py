"""Rerun of a finished study against its first run (issue 24: a rerun of a finished 12-point
study took 4.7 s against 8.9 s for the first run). Wall time of `clutchfem study SPEC --out
OUT --json` run twice, as a user runs it (a fresh process each time, a fresh mesh cache).

    PYTHONPATH=src python benchmarks/bench_rerun.py 12 200
    PYTHONPATH=src python benchmarks/bench_rerun.py --crossover 1 2 3 4 6 8

``--crossover``: the first run of N points in process (``--workers 0``) against a local
cluster of 2 workers (``--workers 2``), the mesh cache warm for both (the points' meshes
built once beforehand), to choose how many points run in process (runner.IN_PROCESS_MAX).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

SPEC = """
[design]
concept = "concept4"
[design.set]
shoe_arc = "90deg"
[settings]
mesh_size = "2mm"
[errors]
sample = 0
[vary]
{vary}
"""


def vary(n: int) -> str:
    if n == 12:
        return ('method = "grid"\n[vary.params]\nflexure_thickness = {min = "1.6mm", max = "2.2mm", steps = 4}\n'
                'shoe_thickness = {values = ["5mm", "6mm", "7mm"]}\n')
    return (f'method = "lhs"\nsamples = {n}\nseed = 1\n[vary.params]\n'
            'flexure_thickness = {min = "1.6mm", max = "2.2mm"}\nshoe_thickness = {min = "5mm", max = "7mm"}\n')


def run(n: int) -> tuple[float, float]:
    with tempfile.TemporaryDirectory() as tmp:
        spec = Path(tmp) / f"s{n}.toml"
        spec.write_text(SPEC.format(vary=vary(n)))
        env = {**os.environ, "CLUTCHFEM_CACHE": str(Path(tmp) / "cache")}
        cmd = [sys.executable, "-m", "clutchfem.cli", "study", str(spec), "--out", str(Path(tmp) / "out"), "--json",
               "--no-charts"]
        times = []
        for _ in range(2):
            t0 = time.perf_counter()
            r = subprocess.run(cmd, env=env, capture_output=True, text=True)
            times.append(time.perf_counter() - t0)
            if r.returncode != 0:
                raise SystemExit(r.stderr[-2000:])
        return times[0], times[1]


def crossover(n: int) -> tuple[float, float]:
    with tempfile.TemporaryDirectory() as tmp:
        spec = Path(tmp) / f"s{n}.toml"
        spec.write_text(SPEC.format(vary=vary(n) if n in (12,) else
                                    f'method = "lhs"\nsamples = {n}\nseed = 2\n[vary.params]\n'
                                    'flexure_thickness = {min = "1.6mm", max = "2.2mm"}\n'))
        env = {**os.environ, "CLUTCHFEM_CACHE": str(Path(tmp) / "cache")}
        base = [sys.executable, "-m", "clutchfem.cli", "study", str(spec), "--json", "--no-charts"]
        subprocess.run(base + ["--out", str(Path(tmp) / "warm"), "--workers", "0"], env=env, capture_output=True,
                       check=True)  # meshes into the cache
        times = []
        for w in ("0", "2"):
            t0 = time.perf_counter()
            subprocess.run(base + ["--out", str(Path(tmp) / f"w{w}"), "--workers", w], env=env, capture_output=True,
                           check=True)
            times.append(time.perf_counter() - t0)
        return times[0], times[1]


if __name__ == "__main__":
    if sys.argv[1:2] == ["--crossover"]:
        for n in [int(a) for a in sys.argv[2:]] or [1, 2, 3, 4, 6, 8]:
            a, b = crossover(n)
            print(f"{n} points: in process {a:.1f} s, 2 local workers {b:.1f} s", flush=True)
        raise SystemExit(0)
    for n in [int(a) for a in sys.argv[1:]] or [12, 200]:
        first, second = run(n)
        print(f"{n} points: first run {first:.1f} s, rerun {second:.2f} s = {100 * second / first:.1f} % of the first",
              flush=True)
