"""Sweep throughput: designs per minute of a 200-point concept-4 sweep on local Dask workers,
and where each design's time goes.

    .venv/bin/python benchmarks/bench_sweep_throughput.py [--points 200] [--scaling-points 60]
                                                          [--mesh-size 1.2e-3] [--steps 8]

1. **Per-step split, in process** (``--steps`` designs, no Dask, one BLAS thread): the
   designs' wall time split into mesh (geometry + gmsh + reading), assembly, solve
   (factorisation, unit load, spin-softening set-up) and the analysis steps of
   :func:`clutchfem.analysis.analyze` (timed by wrapping each step function of the
   module for this run only: slip, FE sweep, character, mu sensitivity, coupling, stress,
   whirl, mass properties).
2. **Scaling 1 -> 2 workers**: the first ``--scaling-points`` points on a local cluster of 1
   and then 2 process workers (fresh mesh cache each, so every design is meshed).
3. **The 200-point sweep** on 2 workers (fresh mesh cache, fresh store): designs per
   minute (compute: first submission to last row; and wall, with the cluster's start-up),
   and per design: mesh, assembly, solve, analysis (means over the rows, measured on the
   worker) and scheduling = workers x compute time / designs - mean worker time per design
   (the time a worker is not computing a design: dispatch round trips, result transfer,
   the store's commit in the client, idle at the end).
4. **Rerun with the mesh cache warm** (same 200 points, fresh store): what meshing costs.

The points: a Latin hypercube (seed 1) over flexure thickness 1.5-2.0 mm, shoe thickness
5-6.5 mm, shoe arc 80-100 deg and hub radius 11.5-12.5 mm (some are refused by concept 4's
geometry rules: they count as designs, at their own small cost).  The machine is shared:
the load average at the start is printed with the figures.
"""

from __future__ import annotations

import argparse
import functools
import os
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
[settings]
mesh_size = "{size}m"
[vary]
method = "lhs"
samples = {n}
seed = 1
[vary.params]
flexure_thickness = {{min = "1.5mm", max = "2.0mm"}}
shoe_thickness = {{min = "5mm", max = "6.5mm"}}
shoe_arc = {{min = "80deg", max = "100deg"}}
hub_radius = {{min = "11.5mm", max = "12.5mm"}}
"""

STEPS = ("slip_step", "fe_sweep", "engagement_step", "character_step", "mu_sensitivity_step", "coupling_step",
         "stress_step", "requirements_step", "whirl_step", "fatigue_step", "mesh_mass_properties")


def _spec(n: int, size: float):
    from clutchfem.studies import parse_spec

    return parse_spec(SPEC.format(n=n, size=size), source=f"bench-{n}")


def per_step(n: int, size: float) -> dict:
    """In-process split of ``n`` designs (see module docstring)."""
    from threadpoolctl import threadpool_limits

    import clutchfem.analysis.pipeline as A
    from clutchfem.evaluation import evaluate
    from clutchfem.evaluation.hashing import design_hash

    spent = {s: 0.0 for s in STEPS}
    originals = {s: getattr(A, s) for s in STEPS}

    def timed(name, fn):
        @functools.wraps(fn)
        def wrapper(*a, **k):
            t0 = time.perf_counter()
            try:
                return fn(*a, **k)
            finally:
                spent[name] += time.perf_counter() - t0
        return wrapper

    spec = _spec(max(n, 8), size)
    pts = spec.points()[:n]
    rows = []
    try:
        for s in STEPS:
            setattr(A, s, timed(s, originals[s]))
        with threadpool_limits(1):
            evaluate(pts[0], spec.settings, "warm-up")  # imports, first gmsh, JIT of nothing
            for s in spent:
                spent[s] = 0.0
            for p in pts:
                rows.append(evaluate(p, spec.settings, design_hash(p, spec.settings)))
    finally:
        for s in STEPS:
            setattr(A, s, originals[s])
    ok = [r for r in rows if r["status"] == "ok"]
    return {"designs": len(rows), "ok": len(ok), "spent": spent, "rows": rows}


def sweep(n: int, size: float, workers: int, cache: str, store_dir: Path) -> dict:
    from clutchfem.evaluation import COLUMNS, ResultStore, run_points

    os.environ["CLUTCHFEM_CACHE"] = cache  # inherited by the worker processes
    spec = _spec(n, size)
    store = store_dir / f"w{workers}-{n}-{os.path.basename(cache)}.sqlite"
    res = run_points(spec.points(), spec.settings, store, workers=workers, progress=False)
    with ResultStore(store, COLUMNS) as st:
        df = st.frame(res.model_version, res.keys)
    return {"res": res, "df": df}


def summarise(label: str, out: dict) -> dict:
    res, df = out["res"], out["df"]
    n = res.computed
    cols = ("t_mesh_s", "t_assembly_s", "t_solve_s", "t_analysis_s", "t_total_s", "t_cpu_s")
    ok = df[df["status"] == "ok"]
    mean_all = {c: float(df[c].fillna(0).mean()) for c in cols}
    sched = res.workers * res.compute_s / n - mean_all["t_total_s"] if n else float("nan")
    d = {"label": label, "designs": n, "ok": res.ok, "refused": res.refused, "failed": res.failed,
         "workers": res.workers, "wall_s": res.wall_s, "compute_s": res.compute_s,
         "per_min_compute": 60 * n / res.compute_s, "per_min_wall": 60 * n / res.wall_s,
         "startup_s": res.wall_s - res.compute_s, "sched_s": sched,
         "mean": mean_all, "mean_ok": {c: float(ok[c].mean()) for c in cols},
         "elements": float(ok["n_elements"].mean()), "cached": int(df["mesh_cached"].fillna(0).sum())}
    return d


def fmt_row(d: dict) -> str:
    m = d["mean"]
    return (f"| {d['label']} | {d['workers']} | {d['designs']} ({d['ok']} ok, {d['refused']} refused, "
            f"{d['failed']} failed) | {d['per_min_compute']:.0f} | {d['per_min_wall']:.0f} | "
            f"{1e3 * m['t_mesh_s']:.0f} | {1e3 * m['t_assembly_s']:.0f} | {1e3 * m['t_solve_s']:.0f} | "
            f"{1e3 * m['t_analysis_s']:.0f} | {1e3 * m['t_total_s']:.0f} | {1e3 * m['t_cpu_s']:.0f} | "
            f"{1e3 * d['sched_s']:.0f} | "
            f"{d['startup_s']:.1f} |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--scaling-points", type=int, default=60)
    ap.add_argument("--mesh-size", type=float, default=1.2e-3, help="global element size [m]")
    ap.add_argument("--steps", type=int, default=8, help="designs for the in-process per-step split")
    ap.add_argument("--skip-scaling", action="store_true")
    args = ap.parse_args(argv)
    print(f"load average at start: {os.getloadavg()}, cores: {len(os.sched_getaffinity(0))}, "
          f"python {sys.version.split()[0]}", flush=True)
    tmp = Path(tempfile.mkdtemp(prefix="bench-sweep-"))
    # 1. per-step split in process
    os.environ["CLUTCHFEM_CACHE"] = str(tmp / "cache-steps")
    ps = per_step(args.steps, args.mesh_size)
    rows = ps["rows"]
    tot = sum(r["t_total_s"] for r in rows)
    print(f"\n## 1. In process, one BLAS thread: {ps['designs']} designs ({ps['ok']} ok), mesh "
          f"{args.mesh_size * 1e3:g} mm, {tot / len(rows) * 1e3:.0f} ms per design "
          f"({60 * len(rows) / tot:.0f} designs/min on one core)\n")
    print("| part | ms per design | share |\n| --- | ---: | ---: |")
    parts = {"mesh (geometry, gmsh, read)": sum(r["t_mesh_s"] or 0 for r in rows),
             "assembly (K, load, constraints, mass)": sum(r["t_assembly_s"] or 0 for r in rows),
             "solve (factorisation, unit load, Ritz set-up)": sum(r["t_solve_s"] or 0 for r in rows)}
    for s in STEPS:
        parts[f"analyze: {s}"] = ps["spent"][s]
    for k, v in parts.items():
        print(f"| {k} | {1e3 * v / len(rows):.0f} | {100 * v / tot:.0f} % |")
    print("(the analyze steps include the contact solves and the lazy parts of the solve row: Ritz set-up, "
          "mass matrix; the rows overlap where a step triggers them)")
    # 2 + 3 + 4: on Dask
    results = []
    if not args.skip_scaling:
        for w in (1, 2):
            out = sweep(args.scaling_points, args.mesh_size, w, str(tmp / f"cache-scale-{w}"), tmp)
            results.append(summarise(f"{args.scaling_points} points, cold mesh cache", out))
            print(f"done: {results[-1]['label']} on {w} worker(s): {results[-1]['per_min_compute']:.0f} designs/min",
                  flush=True)
    out = sweep(args.points, args.mesh_size, 2, str(tmp / "cache-main"), tmp)
    results.append(summarise(f"{args.points} points, cold mesh cache", out))
    print(f"done: 200-point sweep: {results[-1]['per_min_compute']:.0f} designs/min", flush=True)
    (tmp / "warm").mkdir()
    warm = sweep(args.points, args.mesh_size, 2, str(tmp / "cache-main"), tmp / "warm")
    results.append(summarise(f"{args.points} points, warm mesh cache", warm))
    print(f"\n## 2-4. Local Dask cluster (process workers, 1 thread each), mesh {args.mesh_size * 1e3:g} mm, "
          f"load average now {os.getloadavg()}\n")
    print("| run | workers | designs | designs/min (compute) | designs/min (wall) | mesh ms | assembly ms | "
          "solve ms | analysis ms | worker wall ms | worker CPU ms | scheduling ms | start-up s |")
    print("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for d in results:
        print(fmt_row(d))
    if not args.skip_scaling:
        one, two = results[0], results[1]
        print(f"\nscaling 1 -> 2 workers ({args.scaling_points} points): {one['per_min_compute']:.0f} -> "
              f"{two['per_min_compute']:.0f} designs/min (x{two['per_min_compute'] / one['per_min_compute']:.2f}); "
              f"mean worker time per design {1e3 * one['mean']['t_total_s']:.0f} -> "
              f"{1e3 * two['mean']['t_total_s']:.0f} ms wall, CPU {1e3 * one['mean']['t_cpu_s']:.0f} -> "
              f"{1e3 * two['mean']['t_cpu_s']:.0f} ms (wall above CPU: waiting for a core on the shared machine)")
    print(f"\nmean elements per design: {results[-1]['elements']:.0f}; scratch folder {tmp}")


if __name__ == "__main__":
    main()
