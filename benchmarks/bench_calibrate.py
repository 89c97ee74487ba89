"""Calibration to measured parts (issue 39): coverage of the 95 % intervals on synthetic parts
measured by the full FE, the intervals' widths against the priors, the run time of one
calibration, emcee against the Laplace approximation, and the exact similarity of E and
density against the FE.

Synthetic parts: concept 1 on the fast path (3 mm mesh, so that a part costs about a second),
uncertain flexure thickness (+-0.1 mm, normal, +-3 sigma) and friction coefficient (uniform
0.1..0.35).  Each part's true thickness and mu are drawn from the priors, its engagement and
slip speeds computed by the full FE (the same path the reduced model was trained on, with the
error step) and a measurement noise added (25 rpm, 40 rpm); the calibration runs on the reduced
model of the region holding the priors (built once: 24 designs fitted, 10 held out).

    CLUTCHFEM_CACHE=/tmp/cache OPENBLAS_NUM_THREADS=1 PYTHONPATH=src python benchmarks/bench_calibrate.py [--parts 20]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

import clutchfem as cf
from clutchfem.calibration.inputs import parse_uncertain
from clutchfem.evaluation.point import evaluate

MESH = cf.MeshSettings(size="3mm")
PRIORS = ["flexure_thickness=+-0.1mm", "mu=0.1:0.35"]
U_ENG, U_SLIP = 25.0, 40.0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--parts", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    design = cf.Design.from_concept("concept1", mesh=MESH, fidelity="fast")
    U = [parse_uncertain(design, t) for t in PRIORS]
    t0 = time.perf_counter()
    model = cf.reduce(design, free=[u.name for u in U], ranges={u.name: (u.lo, u.hi) for u in U}, n=24, held_out=10,
                      workers=0, progress=False)
    print(f"reduced model: {model.info['fe_designs']} FE designs, {time.perf_counter() - t0:.1f} s (0 if cached); "
          "own error (largest on held-out) " + ", ".join(f"{a} {100 * model.own_error(a):.2f} %"
                                                         for a in ("engagement_rpm", "slip_rpm")))
    settings = model.region.settings.study()
    rng = np.random.default_rng(args.seed)
    rows, times = [], []
    for k in range(args.parts):
        truth = {"flexure_thickness": float(U[0].sample(rng, 1)[0]), "mu": float(U[1].sample(rng, 1)[0])}
        fe = evaluate({n: round(v, 9) for n, v in truth.items()}, settings, errors=True)
        if fe["status"] != "ok" or not fe.get("slip_rpm"):
            print(f"part {k}: the FE gives no slip speed ({fe['status']}): skipped")
            continue
        meas = [f"engagement={fe['engagement_rpm'] + rng.normal(0, U_ENG):.1f}rpm+-{U_ENG:g}rpm",
                f"slip={fe['slip_rpm'] + rng.normal(0, U_SLIP):.1f}rpm+-{U_SLIP:g}rpm"]
        t1 = time.perf_counter()
        c = cf.calibrate(design, meas, PRIORS, model=model, seed=k)
        times.append(time.perf_counter() - t1)
        row = {"part": k, "truth": truth, "consistent": c.consistent}
        for n in truth:
            p = c.posterior[n]
            row[n] = {"inside": p["ci95"][0] <= truth[n] <= p["ci95"][1], "identified": p["identified"],
                      "narrowed": p["narrowed"], "width": p["ci95"][1] - p["ci95"][0],
                      "prior_width": p["prior"]["ci95"][1] - p["prior"]["ci95"][0]}
        rows.append(row)
        print(json.dumps({"part": k, "t_mm": round(truth["flexure_thickness"] * 1e3, 4), "mu": round(truth["mu"], 4),
                          "post_t_mm": [round(x * 1e3, 4) for x in c.posterior["flexure_thickness"]["ci95"]],
                          "post_mu": [round(x, 4) for x in c.posterior["mu"]["ci95"]],
                          "inside": [row[n]["inside"] for n in truth], "consistent": c.consistent,
                          "s": round(times[-1], 2)}))
    for n in ("flexure_thickness", "mu"):
        ident = [r[n] for r in rows if r[n]["identified"]]
        cov = np.mean([r["inside"] for r in ident]) if ident else float("nan")
        sc, unit = (1e3, "mm") if n != "mu" else (1.0, "")
        print(f"{n}: identified in {len(ident)} of {len(rows)} parts; truth inside the 95 % interval in "
              f"{100 * cov:.0f} % of them (all parts: {100 * np.mean([r[n]['inside'] for r in rows]):.0f} %); "
              f"interval width median {np.median([r[n]['width'] for r in rows]) * sc:.4g} {unit} against the "
              f"prior's {rows[0][n]['prior_width'] * sc:.4g} {unit} (narrowed "
              f"{100 * np.median([r[n]['narrowed'] for r in rows]):.0f} % median)")
    allid = [r[n]["inside"] for r in rows for n in ("flexure_thickness", "mu") if r[n]["identified"]]
    print(f"coverage over identified inputs: {100 * np.mean(allid):.1f} % of {len(allid)}; consistent parts "
          f"{sum(r['consistent'] for r in rows)} of {len(rows)}; one calibration (2 measurements, 2 inputs, emcee "
          f"32 x 5000): median {np.median(times):.1f} s, max {max(times):.1f} s")
    # emcee against Laplace on the first part's measurements
    meas = [f"engagement={model.models['engagement_rpm'].predict(model.region.unit_of(rows[0]['truth']))[0]:.1f}"
            f"rpm+-{U_ENG:g}rpm",
            f"slip={model.models['slip_rpm'].predict(model.region.unit_of(rows[0]['truth']))[0]:.1f}rpm+-{U_SLIP:g}rpm"]
    a = cf.calibrate(design, meas, PRIORS, model=model, steps=5000)
    t1 = time.perf_counter()
    b = cf.calibrate(design, meas, PRIORS, model=model, method="laplace")
    tl = time.perf_counter() - t1
    for n in ("flexure_thickness", "mu"):
        pa, pb = a.posterior[n], b.posterior[n]
        print(f"emcee vs laplace, {n}: mean {pa['mean']:.6g} / {pb['mean']:.6g} (diff {abs(pa['mean'] - pb['mean']) / pa['sd']:.2f} sd), "
              f"sd {pa['sd']:.4g} / {pb['sd']:.4g}, ci95 {pa['ci95'][0]:.5g}..{pa['ci95'][1]:.5g} / "
              f"{pb['ci95'][0]:.5g}..{pb['ci95'][1]:.5g}")
    print(f"laplace: {tl:.2f} s; emcee (5000 steps): {a.info['sample_s']:.1f} s, acceptance {a.info['acceptance']:.2f}, "
          f"autocorrelation {a.info['autocorr_steps']:.0f} steps, {a.info['effective_samples']:.0f} effective samples")
    # E and density by exact similarity, against the FE
    from clutchfem.core.materials import Material

    m0 = cf.OperatingPoint().material
    base = cf.analyze(cf.Design.from_concept("concept1", mesh=MESH, fidelity="fast"))
    for E, rho in ((190e9, 7850.0), (210e9, 8100.0), (110e9, 4500.0)):
        mat = Material(name="scaled", E=E, nu=m0.nu, rho=rho, yield_strength=m0.yield_strength)
        a2 = cf.analyze(cf.Design.from_concept("concept1", mesh=MESH, fidelity="fast", material=mat))
        pred = base.engagement_rpm * np.sqrt(E / m0.E * m0.rho / rho)
        print(f"similarity E {E / 1e9:.0f} GPa, density {rho:.0f} kg/m^3: engagement FE {a2.engagement_rpm:.1f} rpm, "
              f"similarity {pred:.1f} rpm ({100 * (pred / a2.engagement_rpm - 1):+.4f} %); mass FE "
              f"{a2.part['mass_kg'] * 1e3:.3f} g, similarity {base.part['mass_kg'] * rho / m0.rho * 1e3:.3f} g")


if __name__ == "__main__":
    main()
