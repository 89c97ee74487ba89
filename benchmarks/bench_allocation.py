"""Tolerance allocation and the mass-yield trade-off (issue 21): the allocation at concept 4's
robust design (BENCHMARKS.md section 18) for several yields, with and without the
model-error bands; the trade-off along the straight path from the pattern search's deterministic optimum
(122.3 g) to the robust design (129.1 g) and a little beyond; a Monte Carlo check through
remeshed designs (``tolerance``) of the predicted yield at one point of the path.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_allocation.py [--n 200] [--alpha 0.5] [--workers 1]
        [--union-check 500]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import clutchfem as cf
from clutchfem.core import ParameterError
from clutchfem.core import values as V
from clutchfem.evaluation import EvalSettings
from clutchfem.geometry import get_concept

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

TOLS = {"flexure_thickness": "0.05mm", "clearance": "0.02mm"}
DET = ("hub_radius=11.84mm", "shoe_arc=87.1deg", "shoe_thickness=7.01mm", "flexure_length=19mm",
       "flexure_thickness=1.75mm", "flexure_taper=1.3", "flexure_angle=32.3deg", "fillet_radius=2.06mm",
       "clearance=0.231mm")
ROB = ("hub_radius=11.84mm", "shoe_arc=97.6deg", "shoe_thickness=6.5mm", "flexure_length=18.44mm",
       "flexure_thickness=1.75mm", "flexure_taper=1.3", "flexure_angle=34.6deg", "fillet_radius=3.55mm",
       "clearance=0.231mm")


def say(*a):
    print(*a, flush=True)


def num(v) -> str:
    return "-" if v is None else f"{v:.3f}"


def path_point(alpha: float) -> tuple[str, ...]:
    """x = x_det + alpha (x_rob - x_det), every parameter, as exact --set texts."""
    P = get_concept("concept4").Params
    a = P.parse_assignments(list(DET))
    b = P.parse_assignments(list(ROB))
    out = []
    for k in a:
        v = a[k] + alpha * (b[k] - a[k])
        res = V.resolution(P, k)
        out.append(f"{k}={V.exact_text(P, k, V.round12(round(v / res) * res))}")
    return tuple(out)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--alpha", type=float, default=0.5)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--alphas", default="0,0.25,0.5,0.75,1,1.25")
    ap.add_argument("--skip-check", action="store_true")
    ap.add_argument("--only-check", action="store_true")
    ap.add_argument("--union-check", type=int, default=0, help="Monte Carlo parts at the robust design's optimal-split "
                    "widths for 99 %, bands left out (0: none)")
    args = ap.parse_args()
    say(f"machine: {platform.machine()}, python {platform.python_version()}, {args.workers} workers; "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    rob = EvalSettings(concept="concept4", base=ROB)
    if not args.only_check:
        trade_offs(rob, args)
    if not args.skip_check:
        check(args)
    if args.union_check:
        union_check(rob, args)


def union_check(rob, args):
    """4. Monte Carlo of the allocation itself: the optimal-split widths for Y = 0.99 (bands
    left out, as the Monte Carlo draws no model error) at the robust design."""
    a = cf.allocate_tolerances(rob, TOLS, model_error=False, workers=args.workers)
    r = a.at(0.99, model_error=False)
    w = {d["name"]: d["allocated_union"] for d in r["dims"]}
    say(f"optimal-split widths for 99 % [m]: {w}; joint-normal prediction {cf_joint(a, w):.4%}")
    t = time.perf_counter()
    res = cf.tolerance(rob, w, n=args.union_check, shifts=False, workers=args.workers)
    o = res.out_of_spec["any"]
    lo, hi = o["ci95"]
    say(f"  MC: {o['n'] - o['k']} of {o['n']} analysed parts in spec = {1 - o['share']:.2%} (Wilson 95 %: "
        f"{1 - hi:.2%} .. {1 - lo:.2%}); {time.perf_counter() - t:.0f} s; statuses {res.statuses}")


def cf_joint(a, w):
    from clutchfem.tolerances import joint_yield

    return joint_yield(a.linearisation, w)


def trade_offs(rob, args):
    # 1. the allocation at the robust design: one linearisation, every yield
    t = time.perf_counter()
    a = cf.allocate_tolerances(rob, TOLS, yield_target=0.99, workers=args.workers)
    say(f"allocation at the robust design: {time.perf_counter() - t:.0f} s; notes {a.notes}")
    say(f"  derivatives [per m]: {a.derivatives}")
    for me in (True, False):
        say(f"model error {'in' if me else 'out'}:")
        for y in (0.9, 0.95, 0.99, 0.999):
            r = a.at(y, model_error=me)
            dims = "; ".join(f"{d['name']} +-{(d['allocated'] or 0) * 1e3:.4f} mm (x{d['ratio'] or 0:.3f}, alone "
                             f"+-{(d['alone'] or 0) * 1e3:.4f} mm, optimal split +-{(d['allocated_union'] or 0) * 1e3:.4f}"
                             f" mm)" for d in r["dims"])
            say(f"  Y = {y}: {r['message']}; scale {r['scale']} (joint normal: {r.get('scale_joint')}; optimal split {r.get('scale_union')}); binds "
                f"{r['scale_binds']}; {dims}; joint yield at the allocated widths {r.get('allocated_yield')}")
        r = a.at(0.99, model_error=me)
        say(f"  predicted yield at the given widths {r['predicted_yield']:.4%} (joint normal; product over the targets "
            f"{r['predicted_yield_independent']:.4%}); at the allocated widths {r.get('allocated_yield')}; perfect part "
            f"{r['perfect_part_yield']:.4%}; ranking {r['ranking']}; model share {r.get('model_share')}")
        for c, c0 in zip(r["constraints"], a.constraints):
            say(f"    {c['name']}: value {c0['value']:.5g}, slack {c['slack']:.4g}, sigma model {c['sigma_model']:.4g}, "
                f"sigma given {c['sigma_given']:.4g} {c0['unit']}, multiplier {c.get('multiplier')}")
        say("    shares at the given widths: " + ", ".join(f"{d['name']} {d.get('share')}" for d in r["dims"])
            + "; binds: " + ", ".join(f"{d['name']} {d.get('binds')}" for d in r["dims"]))
    # 2. the trade-off along the path
    alphas = [float(x) for x in args.alphas.split(",")]
    designs = []
    for al in alphas:
        try:
            es = EvalSettings(concept="concept4", base=path_point(al))
            es.params()
            designs.append((al, es))
        except ParameterError as exc:
            say(f"  alpha {al}: refused by the concept's rules: {exc}")
    t = time.perf_counter()
    rows = cf.yield_front([es for _, es in designs], TOLS, yields=(0.9, 0.95, 0.99, 0.999), workers=args.workers)
    say(f"trade-off, model error in ({time.perf_counter() - t:.0f} s):")
    for (al, es), r in zip(designs, rows):
        sc = ", ".join(f"{y}: {num(v)} / {num(r['scale_joint'][y])}" for y, v in r["scale"].items())
        say(f"  alpha {al}: mass {r['mass_kg'] * 1e3:.2f} g, predicted yield {r['predicted_yield']:.4%} (product "
            f"{r['predicted_yield_independent']:.4%}; tolerances "
            f"only {r['predicted_yield_tolerances_only']:.4%}), perfect part {r['perfect_part_yield']:.4%}, pareto "
            f"{r['pareto']}; scale per yield (Bonferroni / joint) {{{sc}}}; slack " + ", ".join(f"{k} {v:.4g}" for k, v in r["slack"].items())
            + "; sigma " + ", ".join(f"{k} {v:.4g}" for k, v in r["sigma_given"].items()))


def check(args):
    """3. Monte Carlo check of one point's predicted yield (tolerances only: the MC draws no
    model error)."""
    es = EvalSettings(concept="concept4", base=path_point(args.alpha))
    say("check point --set " + " ".join(es.base))
    a = cf.allocate_tolerances(es, TOLS, model_error=False, workers=args.workers)
    say(f"  predicted (tolerances only): joint normal {a.predicted_yield:.4%}, product over the targets "
        f"{a.predicted_yield_independent:.4%}")
    t = time.perf_counter()
    r = cf.tolerance(es, TOLS, n=args.n, shifts=False, workers=args.workers)
    o = r.out_of_spec["any"]
    lo, hi = o["ci95"]
    say(f"  MC at alpha {args.alpha}: {o['n'] - o['k']} of {o['n']} analysed parts in spec = {1 - o['share']:.2%} "
        f"(Wilson 95 %: {1 - hi:.2%} .. {1 - lo:.2%}); {time.perf_counter() - t:.0f} s; statuses {r.statuses}")
    for k, v in r.out_of_spec.items():
        say(f"    out of spec, {k}: {v['k']} of {v['n']}")


if __name__ == "__main__":
    main()
