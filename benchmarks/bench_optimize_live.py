"""The optimiser on the reduced model (issue 36): concept 4's robust design searched on the
live answers of a small region and verified by the full FE.

(a) builds (or loads from the cache) the region around ``--set`` (default: the FE robust
    optimum of BENCHMARKS.md section 21) over a few free parameters: +-``--span`` of each,
    widened for a toleranced one by its tolerance box (+-4 sigma of a normal tolerance), so the
    robust search has +-span of room inside it; its build time and FE designs;
(b) ``optimize --tol ... --yield Y --fidelity live`` from there (:func:`clutchfem.robust_optimize`
    of a live design): time, live evaluations, FE designs, the design, its FE verification and
    the FE parts' agreement;
(c) ``--fe``: the same robust search on the FE (best path), for the time ratio (long: hours);
(d) ``--check N``: ``cf.tolerance(n=N)`` on the FE of the live result (N remeshed parts).

One JSON line per run in ``benchmarks/results_optimize_live.jsonl``.

    CLUTCHFEM_CACHE=/tmp/cache PYTHONPATH=src .venv/bin/python benchmarks/bench_optimize_live.py --workers 2
    ... benchmarks/bench_optimize_live.py --check 200 --workers 2      # + 200 FE parts of the result
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import clutchfem as cf
from clutchfem.core import values as V
from clutchfem.evaluation import EvalSettings
from clutchfem.reduced import find

#: the FE robust optimum of BENCHMARKS.md section 21 (best path, concept 4)
SET = ["hub_radius=9.04mm", "shoe_arc=100.8deg", "shoe_thickness=5.12mm", "flexure_length=16.87mm",
       "flexure_thickness=3.21mm", "flexure_taper=0.879", "flexure_angle=55.1deg", "fillet_radius=3.99mm",
       "clearance=0.33mm"]
FREE = "flexure_thickness,flexure_length,clearance,shoe_thickness"
TOL = ["flexure_thickness=+-0.05mm", "clearance=+-0.02mm"]
OUT = Path(__file__).with_name("results_optimize_live.jsonl")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--concept", default="concept4")
    ap.add_argument("--set", dest="set_", action="append", default=None)
    ap.add_argument("--free", default=FREE)
    ap.add_argument("--span", type=float, default=0.05)
    ap.add_argument("--tol", action="append", default=None)
    ap.add_argument("--yield", dest="yield_", type=float, default=0.99)
    ap.add_argument("--n", type=int, default=None, help="training designs (default 8 d + 8)")
    ap.add_argument("--held-out", type=int, default=10)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--check-parts", type=int, default=8, help="live result's parts also through the FE")
    ap.add_argument("--fe", action="store_true", help="(c) the same search on the FE, for the time ratio")
    ap.add_argument("--check", type=int, default=0, help="(d) cf.tolerance(n=N) on the FE of the result")
    ap.add_argument("--region-only", action="store_true", help="(a) only: build the region")
    ap.add_argument("--issue-fe", action="store_true", help="(e) first: the issue's FE command, timed")
    a = ap.parse_args()
    sets, tols_txt, free = a.set_ or SET, a.tol or TOL, a.free.split(",")
    design = cf.Design.from_concept(a.concept, fidelity="live", **dict(s.split("=", 1) for s in sets))
    P = type(design.params)
    tols = {}
    for t in tols_txt:
        n, v = t.split("=+-")
        tols[n] = V.from_text(P, n, v)
    ranges = {}
    for n in free:
        v = float(getattr(design.params, n))
        h = a.span * abs(v) + (tols[n] * 4.0 / 3.0 if n in tols else 0.0)
        lo, hi = V.param_bounds(P, n)
        ranges[n] = (max(v - h, lo), min(v + h, hi))
    rec = {"date": datetime.datetime.now().isoformat(timespec="seconds"), "host": platform.node(),
           "concept": a.concept, "set": sets, "free": free, "span": a.span, "tol": tols_txt, "yield": a.yield_}
    if a.issue_fe:
        rec["issue_fe"] = issue_fe(a.concept, tols_txt, a.yield_, a.workers)
        print(json.dumps(rec["issue_fe"], indent=1))
    # (a) the region
    n_train = a.n or 8 * len(free) + 8
    t0 = time.perf_counter()
    cached = find(design) is not None
    m = cf.reduce(design, free=free, ranges=ranges, n=n_train, held_out=a.held_out, workers=a.workers)
    rec["region"] = {"key": m.region.key(), "bounds": m.region.describe(), "cached_before": cached,
                     "build_s": m.info.get("build_s"), "wall_s": time.perf_counter() - t0,
                     "fe_designs": m.info.get("fe_designs"), "fe_ok": m.info.get("fe_ok"),
                     "accuracy_max_rel": {k: v.get("max_rel") for k, v in m.accuracy.items() if k != "status"}}
    print(json.dumps(rec["region"], indent=1))
    if a.region_only:
        return
    # (b) the robust search on the live model
    s = EvalSettings.from_design(design)
    t0 = time.perf_counter()
    r = cf.robust_optimize(s, {n: tols[n] for n in tols}, yield_target=a.yield_, free=free, fidelity="live",
                           check=a.check_parts, workers=a.workers, log=print)
    live = r.result.live
    rec["live"] = {"wall_s": time.perf_counter() - t0, "live_evaluations": live["live_evaluations"],
                   "fe_designs": live["fe_designs"], "set": r.result.set_args, "params": r.result.params_texts,
                   "mass_g": r.result.best.get("mass_kg", float("nan")) * 1e3, "verdict": live["verdict"],
                   "feasible": r.result.feasible, "yield": live["yield"], "fe_parts": live["fe_parts"],
                   "fe_answers": live.get("fe_answers"), "answers": live["answers"],
                   "on_region_bound": live["on_region_bound"], "rounds": len(live["rounds"]),
                   "message": r.result.message}
    print(json.dumps(rec["live"], indent=1, default=str))
    final = EvalSettings.from_design(cf.Design.from_concept(a.concept, fidelity="best", **dict(
        x.split("=", 1) for x in r.result.set_args)))
    # (c) the same on the FE
    if a.fe:
        t0 = time.perf_counter()
        rf = cf.robust_optimize(s, tols, yield_target=a.yield_, free=free, workers=a.workers, log=print)
        rec["fe"] = {"wall_s": time.perf_counter() - t0, "evaluations": rf.evaluations, "set": rf.result.set_args,
                     "mass_g": rf.result.best.get("mass_kg", float("nan")) * 1e3, "feasible": rf.result.feasible}
        rec["time_ratio_fe_over_live"] = rec["fe"]["wall_s"] / rec["live"]["wall_s"]
        print(json.dumps(rec["fe"], indent=1, default=str))
    # (d) the result's parts through the FE
    if a.check:
        t0 = time.perf_counter()
        tr = cf.tolerance(final, tols, n=a.check, shifts=False, targets=r.targets, workers=a.workers)
        o = tr.out_any
        rec["fe_check"] = {"n": a.check, "out_of_spec": o["k"], "share_in_spec": 1.0 - o["share"],
                           "ci95_in_spec": [1.0 - o["ci95"][1], 1.0 - o["ci95"][0]],
                           "wall_s": time.perf_counter() - t0}
        print(json.dumps(rec["fe_check"], indent=1))
    if "issue_fe" in rec:
        rec["issue_fe_over_live"] = {"region_cached": rec["issue_fe"]["wall_s"] / rec["live"]["wall_s"],
                                     "region_built": rec["issue_fe"]["wall_s"] / (rec["live"]["wall_s"]
                                                                                  + rec["region"]["wall_s"])}
        print(json.dumps(rec["issue_fe_over_live"]))
    with OUT.open("a") as fh:
        fh.write(json.dumps(rec, default=str) + "\n")


def issue_fe(concept: str, tols: list[str], yield_: float, workers: int) -> dict:
    """The issue's command on the FE (the default fidelity), a process timed from its start."""
    cmd = [sys.executable, "-m", "clutchfem.cli", "optimize", concept, *sum((["--tol", t] for t in tols), []),
           "--yield", f"{yield_:g}", "--workers", str(workers), "--json"]
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, env=os.environ.copy())
    out = {"command": " ".join(cmd[2:]), "wall_s": time.perf_counter() - t0, "exit": r.returncode}
    if r.returncode == 0:
        doc = json.loads(r.stdout)
        rob = doc.get("robust", {})
        out.update(mass_g=(doc["answers"].get("mass_kg") or float("nan")) * 1e3, feasible=doc.get("feasible"),
                   set=doc.get("set"), evaluations=rob.get("evaluations_total", doc.get("evaluations_total")),
                   predicted_yield=rob.get("predicted_yield"), rounds=rob.get("rounds"), answers=doc["answers"],
                   message=doc.get("message"), check_share_in_spec=rob.get("check_share_in_spec"))
    else:
        out["stderr"] = r.stderr[-2000:]
    return out


if __name__ == "__main__":
    main()
