"""Mesh morphing against meshing from scratch (issue 21): for every concept and each of its
real-valued parameters changed by +-``--rel`` (relative; lengths at least ``--min-step``),
the morphed design's answers, the same design meshed from scratch, and the discretisation
errors reported for both (``analyze``'s error step: each design against the same design on a
mesh twice as fine, made from scratch).  Prints, per concept, the largest |morphed -
remeshed| / the discretisation error reported for the morphed design, of each answer, the morph quality (shape
distortion, scaled Jacobian), the refusals and the times; ``--detail`` prints every row.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_morph.py [--rel 0.05] [--concepts concept4]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time

import numpy as np

from clutchfem.analysis import analyze
from clutchfem.geometry import MeshSettings, concepts, get_concept
from clutchfem.loadcase import Design
from clutchfem.mesh import MorphRefused, mesh_concept, morph_reference, morph_to

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

ANSWERS = (("engagement_rpm", "engagement", "rpm", 1.0), ("slip_rpm", "slip", "rpm", 1.0),
           ("torque_at_max_engine_torque_Nm", "torque", "N m", 1.0), ("max_von_mises_Pa", "stress", "MPa", 1e-6))


def answers(cm, p, c, errors=False):
    a = analyze(Design(cm, params=p, name=c.name, concept=c), errors=errors)
    vals = {k: getattr(a, k) for k, *_ in ANSWERS}
    disc = {k: (a.errors.get(k) or {}).get("discretisation") for k, *_ in ANSWERS} if errors else {}
    return vals, disc


def changes(c, p, rel, min_step):
    P = type(p)
    for n, f in P.model_fields.items():
        if f.annotation is not float or n.startswith("table_c") or n in ("drum_radius", "thickness"):
            continue
        if n in ("clearance_tip", "eccentricity", "eccentric_angle"):
            continue
        v = getattr(p, n)
        step = max(abs(v) * rel, min_step if P.unit(n) == "m" else 0.0)
        if step == 0.0:
            continue
        for s in (-1, 1):
            try:
                yield n, s * step, p.replace(**{n: v + s * step})
            except Exception:  # noqa: BLE001 - a refused design is skipped (and said)
                print(f"  {c.name}: {n} {s * step:+.3g} refused by the concept's rules")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rel", type=float, default=0.05)
    ap.add_argument("--min-step", type=float, default=0.05e-3)
    ap.add_argument("--concepts", default=",".join(concepts()))
    ap.add_argument("--detail", action="store_true")
    args = ap.parse_args()
    print(f"machine: {platform.machine()} {platform.processor()}, python {platform.python_version()}; "
          f"changes +-{args.rel:.0%} (lengths >= {args.min_step * 1e3:g} mm)")
    print("| concept | designs morphed / refused | max distortion | min scaled Jacobian | " +
          " | ".join(f"max abs(morph - remesh) / disc. error ({lab})" for _, lab, _, _ in ANSWERS) +
          " | morph s (median) | remesh s (median, cold cache) |")
    print("|" + "---|" * (6 + len(ANSWERS)))
    for name in args.concepts.split(","):
        c = get_concept(name)
        p = c.params()
        ms = MeshSettings()
        ref = morph_reference(c, p, ms)
        worst = {k: 0.0 for k, *_ in ANSWERS}
        n_ok, refused, dist, sj, tm, tr = 0, [], [], [], [], []
        for n, dv, q in changes(c, p, args.rel, args.min_step):
            t = time.perf_counter()
            try:
                cm = morph_to(ref, q)
            except MorphRefused as exc:
                refused.append(f"{n} {dv:+.3g}: {exc}")
                continue
            tm.append(time.perf_counter() - t)
            t = time.perf_counter()
            cr = mesh_concept(c, q, ms, use_cache=False)
            tr.append(time.perf_counter() - t)
            vm, disc = answers(cm, q, c, errors=True)
            vr, disc_r = answers(cr, q, c, errors=True)
            n_ok += 1
            dist.append(cm.morph["quality"]["max_distortion"])
            sj.append(cm.morph["quality"]["min_scaled_jacobian"])
            row = []
            for k, lab, unit, sc in ANSWERS:
                a, b, d = vm[k], vr[k], disc.get(k)
                if a is None or b is None or not d or not (math.isfinite(a) and math.isfinite(b)):
                    row.append(f"{lab} -")
                    continue
                r = abs(a - b) / d
                worst[k] = max(worst[k], r)
                dr = disc_r.get(k)
                row.append(f"{lab} {a * sc:.6g}/{b * sc:.6g} (diff {abs(a - b) * sc:.3g}, {r:.3f} of the morphed "
                           f"design's disc. error {d * sc:.3g}" + (f", {abs(a - b) / dr:.3f} of the remeshed one's)" if dr
                                                                   else ")"))
            if args.detail:
                print(f"  {name} {n} {dv:+.3g}: dist {dist[-1]:.2f} sj {sj[-1]:.3f}; " + "; ".join(row))
        print(f"| {name} | {n_ok} / {len(refused)} | {max(dist, default=float('nan')):.2f} | "
              f"{min(sj, default=float('nan')):.3f} | " + " | ".join(f"{worst[k]:.3f}" for k, *_ in ANSWERS) +
              f" | {np.median(tm) if tm else float('nan'):.3f} | {np.median(tr) if tr else float('nan'):.3f} |")
        for r in refused:
            print(f"  refused: {name} {r}")


if __name__ == "__main__":
    main()
