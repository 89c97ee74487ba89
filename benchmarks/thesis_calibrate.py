"""The thesis case of docs/calibration.md: concept 1 measured at +25 % engagement and slip
speed relative to this tool's prediction (the thesis's own relative figure), calibrated over
mu, the flexure thickness and the clearance; which combinations explain it and which not.

    CLUTCHFEM_CACHE=/tmp/cache OPENBLAS_NUM_THREADS=1 PYTHONPATH=src python benchmarks/thesis_calibrate.py

The reduced model (concept 1, best path, the region of the priors: 32 designs fitted, 10 held
out) is built first if not cached (~40 FE designs, ~10 min on one core).
"""

from __future__ import annotations

import time

import clutchfem as cf
from clutchfem.calibration.inputs import parse_uncertain

PRIORS = ["mu=0.1:0.35", "flexure_thickness=+-0.1mm", "clearance=+-0.1mm"]


def run(design, model, measured, priors=PRIORS, title=""):
    t = time.perf_counter()
    c = cf.calibrate(design, measured, priors, model=model)
    print(f"\n== {title}: {', '.join(measured)} ({time.perf_counter() - t:.1f} s)")
    for ch in c.checks:
        print(f"  {ch['text']}: best fit within the priors {ch['best_fit']:.0f}, {ch['z_best']:+.1f} sigma, "
              f"explained: {ch['explained']}")
    for e in c.explanations:
        print("  -", e)
    for n in c.notes:
        print("  note:", n)
    return c


def main() -> None:
    design = cf.Design.from_concept("concept1", fidelity="best")
    U = [parse_uncertain(design, t) for t in PRIORS]
    model = cf.reduce(design, free=[u.name for u in U], ranges={u.name: (u.lo, u.hi) for u in U}, n=32, held_out=10,
                      workers=0, progress=False)
    print("region:", model.region.describe())
    print("own error (largest on 10 held-out):", {a: f"{100 * model.own_error(a):.2f} %" for a in
                                                  ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm")})
    u0 = model.region.unit_of(model.region.design_values(design))[None, :]
    e0 = float(model.models["engagement_rpm"].predict(u0)[0])
    s0 = float(model.models["slip_rpm"].predict(u0)[0])
    print(f"the tool's prediction of the drawn design: engagement {e0:.0f} rpm, slip {s0:.0f} rpm")
    meas = [f"engagement={1.25 * e0:.0f}rpm+-{0.02 * 1.25 * e0:.0f}rpm", f"slip={1.25 * s0:.0f}rpm+-{0.02 * 1.25 * s0:.0f}rpm"]
    run(design, model, meas, title="+25 % engagement and slip (2 % measurement uncertainty)")
    run(design, model, meas[1:], title="+25 % slip alone")
    run(design, model, [f"engagement={1.05 * e0:.0f}rpm+-{0.02 * e0:.0f}rpm", f"slip={1.25 * s0:.0f}rpm+-{0.025 * s0:.0f}rpm"],
        title="+5 % engagement, +25 % slip (concept 4's pattern)")
    # what it would take: the engagement reached at the priors' corners
    # the region's axes in order: mu, flexure_thickness, clearance (unit box; u0: the drawn design)
    for name, k in (("thickest flexure (+4 sigma)", {1: 1.0}), ("largest clearance (+4 sigma)", {2: 1.0}),
                    ("both", {1: 1.0, 2: 1.0})):
        uu = u0.copy()
        for i, v in k.items():
            uu[0, i] = v
        print(f"  the model at {name}: engagement {model.models['engagement_rpm'].predict(uu)[0] / e0 * 100 - 100:+.1f} %, "
              f"slip {model.models['slip_rpm'].predict(uu)[0] / s0 * 100 - 100:+.1f} %")
    for name, v in (("mu 0.1", 0.0), ("mu 0.35", 1.0)):
        uu = u0.copy()
        uu[0, 0] = v
        print(f"  the model at {name}: slip {model.models['slip_rpm'].predict(uu)[0] / s0 * 100 - 100:+.1f} %")


if __name__ == "__main__":
    main()
