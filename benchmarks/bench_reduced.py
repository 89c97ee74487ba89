"""The reduced model (issue 36): its build, its accuracy on designs it was not built from, and
the cost of a live answer against the FE paths, in one run.

    python benchmarks/bench_reduced.py concept4 --span 0.2 --n 120 --held-out 30 --check 30 --workers 2

Prints (and with --json writes) per answer: the error of the live answer against the full best
path on the held-out designs of the build and on ``--check`` more designs drawn apart from
both (another Sobol seed), the share of them whose FE answer the live band holds; the build's
designs and time; the in-process cost of one live ``analyze``, of 10,000 designs in one
``predict`` call, and of ``analyze`` on the fast path (errors off, and with them) of the same
design, measured in this run.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time

import numpy as np

import clutchfem as cf
from clutchfem.evaluation import COLUMNS, ResultStore, run_points
from clutchfem.reduced import MAX_FE_BAND


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("concept")
    ap.add_argument("--span", type=float, default=0.2)
    ap.add_argument("--n", type=int, default=120)
    ap.add_argument("--held-out", type=int, default=30)
    ap.add_argument("--adaptive", type=float, default=None, help="share of the training designs picked adaptively "
                    "(default: the build's)")
    ap.add_argument("--check", type=int, default=0, help="more designs, FE against live (another seed)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    base = cf.Design.from_concept(a.concept, fidelity="live")
    t0 = time.perf_counter()
    kw = {} if a.adaptive is None else {"adaptive": a.adaptive}
    m = cf.reduce(base, span=a.span, n=a.n, held_out=a.held_out, workers=a.workers, progress=True, **kw)
    build_s = time.perf_counter() - t0
    out = {"concept": a.concept, "span": a.span, "region": m.region.describe(), "info": m.info,
           "accuracy_held_out": m.accuracy, "load_or_build_s": build_s}
    print(f"{a.concept} +-{100 * a.span:g} %: {m.region.describe()}")
    print(f"build: {m.info.get('fe_designs')} designs ({m.info.get('fe_ok')} answered; {m.info.get('n_train')} fitted, "
          f"{m.info.get('n_adaptive', 0)} of them adaptive), {m.info.get('build_s', 0):.0f} s "
          f"({m.info.get('workers')} workers); this call {build_s:.1f} s")
    _table("held-out designs of the build", m.accuracy)
    if a.check:
        out["accuracy_check"] = check(m, a.check, a.workers)
        _table(f"{a.check} more designs (seed 7)", out["accuracy_check"])
    out["cost"] = cost(m, a.concept)
    for k, v in out["cost"].items():
        print(f"  {k}: {v:.4g}")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(out, fh, indent=1, default=float)


def check(m, k: int, workers: int) -> dict:
    """``k`` designs of another Sobol seed through the full best path, against the live answers."""
    region = m.region
    pts = region.sample(k, seed=7, skip=1024)
    st = region.settings.study()
    with tempfile.TemporaryDirectory() as tmp:
        store = f"{tmp}/check.sqlite"
        res = run_points(pts, st, store, workers=workers, progress=True, source="bench_reduced check",
                         error_points=list(range(len(pts))))
        with ResultStore(store, COLUMNS) as rs:
            df = rs.frame(res.model_version, list(res.keys))
    rows = json.loads(df.to_json(orient="records"))
    saved = m.accuracy
    acc = m.measure(rows)
    m.accuracy = saved
    return acc


def _table(title: str, acc: dict) -> None:
    print(title + ":")
    for a_, v in acc.items():
        if a_ == "status":
            print(f"  status: FE answered {v['fe_answers']} of {v['n']}; told apart {100 * v['agree']:.0f} %")
            continue
        print(f"  {a_:32s} n={v['n']:3d}  mean {100 * v['mean_rel']:.3f} %  p95 {100 * v['p95_rel']:.3f} %  "
              f"max {100 * v['max_rel']:.3f} %  " + ("not given live (over 10 %)" if v.get("within") is None else
                                                  f"band holds FE {100 * v['within']:.0f} %"))
        if v.get("n_wide_fe_band"):
            narrow = v.get("max_rel_narrow_fe_band")
            print(f"  {'':32s} {v['n_wide_fe_band']} of them with an FE band over {100 * MAX_FE_BAND:g} %; max without "
                  f"them " + ("-" if narrow is None else f"{100 * narrow:.3f} %"))


def cost(m, concept: str) -> dict:
    """In-process seconds: one live analyze (median of 50 designs of the region), one
    predict of 10,000 designs, analyze on the fast path (errors off, and on) of one design."""
    pts = m.region.sample(50, seed=3, skip=4096)
    live = []
    for p in pts:
        d = cf.Design.from_concept(concept, fidelity="live", **p)
        t = time.perf_counter()
        an = cf.analyze(d)
        live.append(time.perf_counter() - t)
        assert an.answered_by in ("reduced model", "FE (fallback)")
    U = np.random.default_rng(0).random((10000, m.region.dim))
    t = time.perf_counter()
    m.predict(U)
    t10k = time.perf_counter() - t
    d = cf.Design.from_concept(concept, fidelity="fast", **pts[0])
    t = time.perf_counter()
    cf.analyze(d, errors=False)
    fast = time.perf_counter() - t
    d = cf.Design.from_concept(concept, fidelity="fast", **pts[0])
    t = time.perf_counter()
    cf.analyze(d)
    fast_err = time.perf_counter() - t
    med = statistics.median(live)
    return {"live_analyze_median_s": med, "live_analyze_max_s": max(live), "predict_10000_s": t10k,
            "fast_analyze_no_errors_s": fast, "fast_analyze_with_errors_s": fast_err,
            "fast_no_errors_over_live": fast / med, "fast_with_errors_over_live": fast_err / med}


if __name__ == "__main__":
    main()
