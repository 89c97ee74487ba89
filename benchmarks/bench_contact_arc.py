"""Contact arc between nodes (issue 25): the ends of :mod:`clutchfem.contact.arc` on the
default mesh against the same design with a contact mesh ten times finer, and their
smoothness in speed.

For each concept: the default mesh swept every ``--step`` rpm from just above engagement to
14 000 rpm, the reference (``MeshSettings(contact_factor=0.05)``: node spacing ~0.05 deg)
every 10th of those speeds.  Printed per kappa (:data:`clutchfem.contact.arc.EDGE_COMPLIANCE`):
the error of the start and end angles against the reference (mean, rms, largest; in degrees
and in node spacings of the default mesh), the share of ends within the stated error
(:data:`~clutchfem.contact.arc.END_ERROR` spacings), and the largest change of the arc from
one speed to the next; the same for the old staircase (nodes in contact + half a spacing).
Prints the Markdown table kept in BENCHMARKS.md.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_contact_arc.py [--step 25]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time
from datetime import date

import numpy as np

import clutchfem.contact.arc as arcmod
from clutchfem.contact import contact_ends
from clutchfem.geometry import MeshSettings
from clutchfem.loadcase import Design

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


def staircase(nodes, lam: np.ndarray) -> np.ndarray:
    """The old rule: first to last node in contact, plus half a node spacing at each end."""
    sel = np.nonzero(nodes.shoe == 0)[0]
    ang = nodes.angle[sel]
    ang = np.angle(np.exp(1j * (ang - np.angle(np.exp(1j * ang).mean())))) + np.angle(np.exp(1j * ang).mean())
    o = np.argsort(ang)
    a, idx = ang[o], sel[o]
    gaps = np.diff(a)
    out = np.full((lam.shape[0], 2), np.nan)
    for k in range(lam.shape[0]):
        on = np.nonzero(lam[k, idx] > 0)[0]
        if len(on):
            lo = a[on[0]] - (0.5 * gaps[on[0] - 1] if on[0] > 0 else 0.0)
            hi = a[on[-1]] + (0.5 * gaps[on[-1]] if on[-1] < len(a) - 1 else 0.0)
            out[k] = lo, hi
    return out


def run(name: str, step: float) -> dict:
    coarse = Design.from_concept(name)
    fine = Design.from_concept(name, mesh=MeshSettings(contact_factor=0.05))
    w0 = max(coarse.case().engagement_rpm, fine.case().engagement_rpm)
    rpm = np.arange(math.ceil((w0 + 1.0) / step) * step, 14000.0 + 1e-9, step)
    t = time.perf_counter()
    rc, rf = coarse.sweep(rpm, stresses=False), fine.sweep(rpm[::10], stresses=False)
    spacing = float(np.median(np.abs(np.diff(np.sort(coarse.case().contact.nodes.angle[
        coarse.case().contact.nodes.shoe == 0])))))
    return {"coarse": rc, "fine": rf, "rpm": rpm, "spacing": spacing, "seconds": time.perf_counter() - t}


def ends(res, kappa: float) -> np.ndarray:
    arcmod.EDGE_COMPLIANCE = kappa
    return contact_ends(res.contact.nodes, res.lam, res.gaps, res.thickness, res.contact_modulus, 0)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--step", type=float, default=25.0)
    args = ap.parse_args()
    kappa0 = arcmod.EDGE_COMPLIANCE
    print(f"machine: {platform.machine()}, Python {platform.python_version()}, {date.today()}; "
          f"`OPENBLAS_NUM_THREADS=1 python benchmarks/bench_contact_arc.py --step {args.step:g}`\n")
    print("| concept | ends | ends: rms error [deg] | largest [deg] | largest [spacings] | "
          f"within {arcmod.END_ERROR} spacings | arc: mean error [deg] | largest [deg] | "
          f"largest step of the arc per {args.step:g} rpm [deg] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in ("concept1", "concept4"):
        r = run(name, args.step)
        ref = ends(r["fine"], kappa0)[:, :2]
        h = r["spacing"]
        rows = [(f"kappa = {k:.3g}" + (" (used)" if k == kappa0 else ""), ends(r["coarse"], k)[:, :2])
                for k in (1 / 3, 0.5, 2 / 3, 1.0)]
        rows.append(("whole nodes + half spacing (before)", staircase(r["coarse"].contact.nodes, r["coarse"].lam)))
        for label, e in rows:
            err = np.degrees(e[::10] - ref)
            ok = np.isfinite(err).all(axis=1)
            arc_err = err[ok, 1] - err[ok, 0]
            err = err[ok].ravel()
            arc = np.degrees(np.nan_to_num(e[:, 1] - e[:, 0]))
            hd = math.degrees(h)
            print(f"| {name} | {label} | {math.sqrt(np.mean(err ** 2)):.3f} | "
                  f"{np.abs(err).max():.3f} | {np.abs(err).max() / hd:.2f} | "
                  f"{np.mean(np.abs(err) <= arcmod.END_ERROR * hd + 1e-12):.0%} | {arc_err.mean():+.3f} | "
                  f"{np.abs(arc_err).max():.3f} | {np.abs(np.diff(arc)).max():.3f} |")
        print(f"<!-- {name}: node spacing {math.degrees(h):.3f} deg, {len(r['rpm'])} speeds "
              f"{r['rpm'][0]:.0f}..{r['rpm'][-1]:.0f} rpm, sweeps {r['seconds']:.1f} s -->")
    arcmod.EDGE_COMPLIANCE = kappa0


if __name__ == "__main__":
    main()
