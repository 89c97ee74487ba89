"""Robust design to targets, the acceptance run of issue 21: from concept 4's defaults with
flexure_thickness +-0.05 mm and clearance +-0.02 mm (normal at +-3 sigma), yield 0.99 and the
default targets, ``robust_optimize`` (model-error bands included; if that is infeasible, also
without them), then an independent Monte Carlo check through remeshed designs (``tolerance``,
``--n`` parts) of the robust design and of the deterministic optimum given in ``--det``.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_robust.py [--n 1000] [--workers 2]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import clutchfem as cf
from clutchfem.evaluation import EvalSettings

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

TOLS = {"flexure_thickness": "0.05mm", "clearance": "0.02mm"}
#: today's deterministic optimum (docs/design_to_targets.md, 122.3 g)
DET = ("hub_radius=11.84mm", "shoe_arc=87.1deg", "shoe_thickness=7.01mm", "flexure_length=19mm",
       "flexure_thickness=1.75mm", "flexure_taper=1.3", "flexure_angle=32.3deg", "fillet_radius=2.06mm",
       "clearance=0.231mm")

#: the gradient method's deterministic optimum (105.4 g, benchmarks/bench_optimize.py)
DET_GRADIENT = ("clearance=0.4081mm", "fillet_radius=2.2883mm", "hub_radius=11.7258mm", "shoe_arc=109.9851deg",
                "shoe_thickness=4.1725mm", "flexure_length=20.2743mm", "flexure_thickness=2.3956mm",
                "flexure_taper=0.868482", "flexure_angle=35.9993deg")


def say(*a):
    print(*a, flush=True)


def check(settings, n, workers, what):
    t = time.perf_counter()
    r = cf.tolerance(settings, TOLS, n=n, shifts=False, workers=workers)
    o = r.out_any  # a part the concept's rules refuse (cannot be built as drawn) counts out of spec
    lo, hi = o["ci95"]
    say(f"  check of {what}: {n} remeshed parts, {o['n'] - o['k']} of {o['n']} in spec = {1 - o['share']:.2%} "
        f"(Wilson 95 %: {1 - hi:.2%} .. {1 - lo:.2%}); {time.perf_counter() - t:.0f} s")
    for k, v in r.out_of_spec.items():
        say(f"    out of spec, {k}: {v['k']} of {v['n']}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--skip-det", action="store_true")
    ap.add_argument("--n-det", type=int, default=None, help="parts of the deterministic optima's checks "
                    "(default: --n)")
    ap.add_argument("--method", default="pattern", help="optimize's method inside the robust rounds")
    ap.add_argument("--max-evals", type=int, default=300, help="each round's optimisation budget (designs)")
    ap.add_argument("--rounds", type=int, default=None, help="shifted rounds at most (default: robust_optimize's)")
    args = ap.parse_args()
    say(f"machine: {platform.machine()}, python {platform.python_version()}, {args.workers} workers; "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    d = cf.Design.from_concept("concept4")
    for model_error in (True, False):
        t = time.perf_counter()
        r = cf.robust_optimize(d, TOLS, yield_target=0.99, model_error=model_error, workers=args.workers,
                               method=args.method, max_evals=args.max_evals,
                               **({"rounds": args.rounds} if args.rounds else {}),
                               log=lambda s: say("   ", s) if s.startswith("round") else None)
        res = r.result
        say(f"robust (model error {'in' if model_error else 'out'}): feasible {res.feasible}, mass "
            f"{res.best.get('mass_kg', float('nan')) * 1e3:.1f} g, predicted yield {r.predicted_yield:.4f}, "
            f"{r.evaluations} designs, {time.perf_counter() - t:.0f} s")
        say("  margins: " + ", ".join(f"{k} {v:.4g}" for k, v in r.margins.items()))
        say("  answers: " + ", ".join(f"{k} {res.best.get(k)}" for k in ("engagement_rpm_with_ripple", "slip_rpm",
                                                                           "safety_factor")))
        say("  --set " + " ".join(res.set_args))
        if res.feasible:
            check(dataclasses_replace(r), args.n, args.workers, "the robust design")
            break
    if not args.skip_det:
        n_det = args.n_det or args.n
        check(EvalSettings(concept="concept4", base=DET_GRADIENT), n_det, args.workers,
              "the gradient method's deterministic optimum (105.4 g)")
        check(EvalSettings(concept="concept4", base=DET), n_det, args.workers,
              "the pattern search's deterministic optimum (122.3 g)")


def dataclasses_replace(r):
    import dataclasses
    return dataclasses.replace(r.result.settings, base=tuple(r.result.set_args))


if __name__ == "__main__":
    main()
