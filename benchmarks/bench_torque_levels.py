"""Convergence of the main answers over three mesh levels of the best path (issue 20, the
accuracy target): h (the best preset), h/2 (the error step's finer mesh,
:func:`clutchfem.accuracy.refined_design` with the disc at the peak, as ``analyze`` builds
it) and h/4 (``refined_design`` of that), for engagement, slip and the torque at the rpm of
maximum engine torque (8000 rpm; the peak stress is extrapolated on its own disc, not here).

Per answer: the three values, the observed order p = log2(|a_h - a_h/2| / |a_h/2 - a_h/4|),
whether the changes are monotone (same sign), and whether the finer pair's estimate
2 |a_h/2 - a_h/4| (Richardson, p = 1) bounds |a_h/4 - a_ref|, the reference of
``benchmarks/results_accuracy.jsonl`` ("reference" rows, key "ref"; the torque compared
after the design's non-linearity correction (1 + d_NL), as ``analyze`` reports it).  Time per
level: the answers' own FE work (load case, engagement, slip on the 250 rpm bracket, torque).

Run (from a source snapshot; ~1 min a design with --eighth, idle):

    PYTHONPATH=src OPENBLAS_NUM_THREADS=1 python benchmarks/bench_torque_levels.py \
        --eighth --only concept1-lhs10,concept1,concept4,concept1-lhs01,concept1-lhs02,concept4-lhs02
    PYTHONPATH=src OPENBLAS_NUM_THREADS=1 python benchmarks/bench_torque_levels.py --cost \
        --only concept1-lhs10,concept1,concept4     # analyze's cost: from each snapshot of an A/B
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

from bench_accuracy import ENGINE, RPM_T, designs, load

import clutchfem as cf
from clutchfem.accuracy import refined_design
from clutchfem.analysis import slip_step
from clutchfem.analysis.torque import GRID_RPM_SENSITIVITY, FETorque
from clutchfem.core import tune_malloc

KEYS = {"eng": "engagement_rpm", "slip": "slip_rpm", "T": "torque_at_max_engine_torque_Nm"}


def level_answers(d) -> dict:
    """Engagement [rpm], slip [rpm], torque at RPM_T [N m] of one design (as the error step's
    finer mesh computes them) and the time [s]."""
    t0 = time.perf_counter()
    case = d.case()
    eng = case.engagement_rpm
    slip = slip_step(case, ENGINE, GRID_RPM_SENSITIVITY).rpm
    T = float(FETorque(case)(RPM_T)[0])
    return {"eng": eng, "slip": slip, "T": T, "dofs": int(d.model.ndofs), "elements": int(d.cm.n_elements),
            "time_s": time.perf_counter() - t0}


def measure(concept: str, vals: dict, eighth: bool = False) -> dict:
    d0 = cf.Design.from_concept(concept, fidelity="best", **vals)
    an = cf.analyze(d0)
    et = an.errors["torque_at_max_engine_torque_Nm"]
    dnl = (et.get("corrections") or {}).get("geometric_nonlinearity", 0.0)
    d1 = refined_design(d0, peak_at=tuple(an.max_stress_location_m))
    d2 = refined_design(d1)
    ds = [cf.Design.from_concept(concept, fidelity="best", **vals), d1, d2]  # (h: a fresh design, timed)
    if eighth:
        ds.append(refined_design(d2))
    levels = [level_answers(d) for d in ds]
    return {"levels": levels, "d_nl_T": dnl, "model_form_T": et["model_form"],
            "reported": {k: {"value": an.errors[q]["value"], "discretisation": an.errors[q]["discretisation"],
                             "model_form": an.errors[q]["model_form"],
                             "total": an.errors[q]["total"]} for k, q in KEYS.items()}}


def rows(label: str, m: dict, ref: dict | None) -> list[str]:
    """Table rows of one design: per answer the levels (the torque times (1 + d_NL)), the
    changes, the observed orders, the finer pair's estimate 2 |a_h/2 - a_h/4| against the
    discretisation error of a_h/4 (|a_h/4 - a_inf|, a_inf extrapolated from h/4 and h/8 at
    their observed order, where h/8 was computed) and the new total band (that estimate +
    the reported model form) against the reference."""
    out = []
    lv = m["levels"]
    for k, unit, f in (("eng", "rpm", "{:.2f}"), ("slip", "rpm", "{:.2f}"), ("T", "N m", "{:.5f}")):
        xs = [x[k] for x in lv]
        if any(x is None for x in xs):
            out.append(f"| {label} | {k} [{unit}] | no answer on a level | | | | | | | | | |")
            continue
        s = 1.0 + m["d_nl_T"] if k == "T" else 1.0
        xs = [x * s for x in xs]
        ch = [b - a for a, b in zip(xs, xs[1:])]
        ps = [math.log2(abs(a) / abs(b)) if a and b else float("nan") for a, b in zip(ch, ch[1:])]
        mono = "yes" if all(a * b > 0 for a, b in zip(ch, ch[1:])) else "NO"
        est = 2 * abs(ch[1])
        x2 = xs[2]
        if len(xs) == 4 and ps[1] > 0 and ch[1] * ch[2] > 0:
            e_true = abs(ch[2]) * 2 ** ps[1] / (2 ** ps[1] - 1)  # |a_h/4 - a_inf|
            disc = f"{100 * e_true / abs(x2):.3f} % ({'yes' if e_true <= est else 'NO'})"
        elif len(xs) == 4:
            disc = f">= {100 * abs(ch[2]) / abs(x2):.3f} % ({'yes' if abs(ch[2]) <= est else 'NO'}, not monotone)"
        else:
            disc = "-"
        mf = m["reported"][k]["total"] - (m["reported"][k]["discretisation"] or 0.0)
        r = None if ref is None else ref.get(k)
        if r:
            err = x2 - r
            band = est + mf
            holds = f"{100 * err / r:+.3f} % / {100 * band / abs(x2):.3f} % ({'yes' if abs(err) <= band else 'NO'})"
        else:
            holds = "-"
        vals = " | ".join(f.format(x) for x in xs) + (" | -" if len(xs) == 3 else "")
        chg = " / ".join(f"{100 * c / x:+.3f}" for c, x in zip(ch, xs))
        pt = " / ".join(f"{p:.2f}" for p in ps)
        out.append(f"| {label} | {k} [{unit}] | {vals} | {chg} % | {pt} | {mono} | {100 * est / abs(x2):.3f} % | "
                   f"{disc} | {holds} |")
    return out


def cost(only: list[str], repeat: int) -> None:
    """analyze's cost on the best path with its error step (the default): CPU and wall minima
    over ``repeat`` runs after one warm-up, and the main answers and bands (for an A/B of two
    source snapshots: run this from each)."""
    tune_malloc()
    by_label = {lab: (c, v) for lab, c, v in designs("all")}
    for label in only:
        concept, vals = by_label[label]
        an = cf.analyze(cf.Design.from_concept(concept, fidelity="best", **vals))
        wall = cpu = math.inf
        for _ in range(repeat):
            t0, c0 = time.perf_counter(), time.process_time()
            an = cf.analyze(cf.Design.from_concept(concept, fidelity="best", **vals))
            wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
        print(label, json.dumps({"wall": wall, "cpu": cpu, **{q: an.errors[q]["value"] for q in KEYS.values()},
                                 "bands": {q: an.errors[q]["total"] for q in KEYS.values()}}), flush=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", default="concept1-lhs10,concept1,concept4,concept1-lhs01,concept1-lhs02,concept4-lhs02")
    ap.add_argument("--out", default="", help="append each design's measurement (JSON lines) here")
    ap.add_argument("--eighth", action="store_true", help="also h/8 (the check of the h/4 level's estimate)")
    ap.add_argument("--cost", action="store_true", help="analyze's cost (best, errors on) instead of the levels")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    only = [x for x in args.only.split(",") if x]
    if args.cost:
        cost(only, args.repeat)
        return 0
    refs = load()
    table = ["| design | answer | h | h/2 | h/4 | h/8 | changes between levels | p | monotone | "
             "estimate 2 |a_h/2 - a_h/4| | a_h/4's disc. error (bounded) | a_h/4 - ref / new band (holds) |",
             "|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|"]
    times = ["| design | level | elements | dofs | time [s] |", "|---|---|---:|---:|---:|"]
    by_label = {lab: (c, v) for lab, c, v in designs("all")}
    for label in only:
        concept, vals = by_label[label]
        t0 = time.perf_counter()
        m = measure(concept, vals, args.eighth)
        if args.out:
            with open(args.out, "a") as fh:
                fh.write(json.dumps({"label": label, **m}) + "\n")
        ref = refs.get(label, {}).get("reference", {}).get("ref")
        table += rows(label, m, ref)
        for name, lv in zip(("h", "h/2", "h/4", "h/8"), m["levels"]):
            times.append(f"| {label} | {name} | {lv['elements']} | {lv['dofs']} | {lv['time_s']:.1f} |")
        print(f"{label}: {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
    print("\n".join(table))
    print()
    print("\n".join(times))
    return 0


if __name__ == "__main__":
    sys.exit(main())
