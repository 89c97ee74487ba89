"""How smooth the main answers are in a design parameter, per model (issue 21): concept 4's
defaults, ``flexure_thickness`` (or ``--name``) stepped on meshes *morphed* from the design's
own, for several contact models:

* ``rigid``: the default (rigid drum, exact node-to-circle contact);
* ``rigid, smoothed 1 um``: the same with the contact law smoothed on a 1 um gap scale
  (``contact_smoothing``, :func:`clutchfem.contact.smooth_lcp`);
* ``rigid, contact disc``: the contact zone meshed 20x finer (a refined disc of radius
  1.5 mm at 0.06 mm around the most loaded contact node);
* ``elastic drum 2 mm`` with and without a 2 um smoothing;
* ``best path``: ``fidelity="best"`` (thick plane model, 2 mm elastic drum, the best mesh
  preset; the linear model, as studies evaluate it).

For each answer it prints its kinks and the central-difference derivative at h = 1e-3, 1e-2
and 1e-1 mm with its scatter (max - min) / |median|, and the value noise (std of the
residual of a quadratic fit to 11 steps of 0.1 um, relative to the slope times that step:
round-off, not kinks).  Kinks: with s_i the slopes between neighbouring steps of 0.01 mm, the
second difference |s_(i+1) - 2 s_i + s_(i-1)| / |median s| (a slope jump J anywhere in the
three intervals shows as ~J; a smooth curvature cancels, leaving the third derivative times
h^2), its largest value next to a contact event (the loaded contact nodes at the answer's
speed differ between two neighbouring steps: the study rows' ``contact_sets``) and elsewhere.
(Until stop 32 this column was the first difference |s_(i+1) - s_i| / |median s|, which also
counts the answer's smooth curvature: the peak stress's "3 % jumps" on the best path were
mostly curvature.)

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_derivative_smoothness.py [--workers 2]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import platform
import time

import numpy as np

import clutchfem as cf
from clutchfem.core import rpm_to_rad_s
from clutchfem.core import values as V
from clutchfem.evaluation.batch import EvalSettings, evaluate_many, shared_cluster

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

KEYS = (("torque_at_max_engine_torque_Nm", "torque at max engine torque"), ("slip_rpm", "slip speed"),
        ("max_von_mises_Pa", "peak von Mises"), ("engagement_rpm", "engagement"))
#: the speed each answer is read at (Analysis.contact_sets' keys); the engagement has no contact
SPEED = {"torque_at_max_engine_torque_Nm": "torque", "slip_rpm": "slip", "max_von_mises_Pa": "peak"}
STEPS_MM = (1e-3, 1e-2, 1e-1)


def contact_point(design) -> tuple[float, float]:
    """(x, y) [m] of the most loaded contact node at the rpm of maximum engine torque."""
    an = cf.analyze(design)
    case = design.case()
    lam, _ = case.solve(rpm_to_rad_s(an.rpm_max_engine_torque))
    i = int(np.argmax(lam))
    xy = case.contact.nodes.xy
    return (float(xy[0, i]), float(xy[1, i])) if xy.shape[0] == 2 else (float(xy[i, 0]), float(xy[i, 1]))


def models(base) -> dict[str, tuple[dict, cf.MeshSettings]]:
    x, y = contact_point(base)
    disc = cf.MeshSettings(refine_x=x, refine_y=y, refine_radius=1.5e-3, refine_size=0.06e-3)
    return {"rigid": ({}, cf.MeshSettings()),
            "rigid, smoothed 1 um": ({"contact_smoothing": 1e-6}, cf.MeshSettings()),
            "rigid, contact disc": ({}, disc),
            "elastic drum 2 mm": ({"drum_wall": 2e-3}, cf.MeshSettings()),
            "elastic drum 2 mm, smoothed 2 um": ({"drum_wall": 2e-3, "contact_smoothing": 2e-6}, cf.MeshSettings()),
            "best path": ({"fidelity": "best"}, cf.MeshSettings.preset("best"))}


def scan(es, P, name, x0, offsets):
    pts = [{name: V.exact_text(P, name, V.round12(x0 + o))} for o in offsets]
    rows = evaluate_many(pts, es)
    bad = [r.get("message") for r in rows if r["status"] != "ok"]
    if bad:
        raise SystemExit(f"a design failed: {bad[0]}")
    out = {k: np.array([r[k] for r in rows], dtype=float) for k, _ in KEYS}
    out["sets"] = [r.get("contact_sets") or {} for r in rows]
    return out


def kinks(y, sets, speed):
    """(largest kink next to a contact event, largest elsewhere) of the answer ``y`` on the
    0.01 mm grid (module docstring), relative to its median slope."""
    s = np.diff(y) / 1e-2
    if not np.median(s):
        return float("nan"), float("nan")
    d2 = np.abs(s[2:] - 2 * s[1:-1] + s[:-2]) / abs(np.median(s))  # centred on slope i + 1
    event = np.array([speed is not None and sets[i].get(speed) != sets[i + 1].get(speed) for i in range(len(s))])
    near = np.array([event[i:i + 3].any() for i in range(len(d2))])  # slopes i, i + 1, i + 2
    at = d2[near].max() if near.any() else float("nan")
    off = d2[~near].max() if (~near).any() else float("nan")
    return at, off


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--name", default="flexure_thickness")
    ap.add_argument("--only", default=None, help="run one model (its name)")
    args = ap.parse_args()
    base = cf.Design.from_concept("concept4")
    P, name = type(base.params), args.name
    x0 = float(getattr(base.params, name))
    grid = np.round(np.arange(-10, 11) * 1e-5, 12)  # 0.01 mm steps over +-0.1 mm
    fine = np.array([-1e-6, 1e-6])
    noise = np.arange(-5, 6) * 1e-7
    print(f"machine: {platform.machine()}, python {platform.python_version()}, {time.strftime('%Y-%m-%d')}, "
          f"concept4 defaults, {name} = {x0 * 1e3:g} mm, morphed meshes, {args.workers} workers")
    print("\n| model | answer | contact events (0.01 mm steps) | largest kink at an event | largest kink elsewhere "
          "| dA/dx at h = 0.001 / 0.01 / 0.1 mm | scatter | value noise | time |")
    print("|---|---|---:|---:|---:|---|---:|---:|---:|")
    with shared_cluster(args.workers, None):
        for label, (op, ms) in models(base).items():
            if args.only and args.only != label:
                continue
            es = EvalSettings.from_design(cf.Design.from_concept("concept4", **op))
            es = dataclasses.replace(es, mesh=ms, morph=tuple(sorted(es.values().items())))
            t = time.perf_counter()
            g, f, z = scan(es, P, name, x0, grid), scan(es, P, name, x0, fine), scan(es, P, name, x0, noise)
            dt = time.perf_counter() - t
            for k, title in KEYS:
                y = g[k]
                sp = SPEED.get(k)
                at, off = kinks(y, g["sets"], sp)
                n_ev = sum(sp is not None and g["sets"][i].get(sp) != g["sets"][i + 1].get(sp) for i in range(len(y) - 1))
                d = [(f[k][1] - f[k][0]) / 2e-3, (y[11] - y[9]) / 2e-2, (y[20] - y[0]) / 2e-1]
                sc = (max(d) - min(d)) / abs(np.median(d)) if np.median(d) else float("nan")
                c = np.polyfit(noise, z[k], 2)
                nz = np.std(z[k] - np.polyval(c, noise)) / abs(c[1] * 1e-7) if c[1] else float("nan")
                unit = {"torque_at_max_engine_torque_Nm": "N m/mm", "max_von_mises_Pa": "MPa/mm"}.get(k, "rpm/mm")
                s = 1e-6 if k == "max_von_mises_Pa" else 1.0
                print(f"| {label} | {title} | {n_ev} | {at:.2%} | {off:.2%} | " + " / ".join(f"{v * s:.5g}" for v in d)
                      + f" {unit} | **{sc:.3%}** | {nz:.1e} | {dt:.0f} s |")


if __name__ == "__main__":
    main()
