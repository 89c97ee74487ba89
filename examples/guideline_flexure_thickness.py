"""Guideline (thesis 4.4): "a thicker flexure engages later, with lower stress" -- with
numbers from the FE model, on the study engine.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python examples/guideline_flexure_thickness.py [--out DIR] [--workers N]

The flexure thickness of concepts 1 and 4 is swept around its default (concept 4: the
thickness at the beam's hub end, the taper ratio kept), everything else at the defaults.
Printed per +0.1 mm of flexure (least-squares slope over the sweep): the change of the
static engagement speed, of the effective flexure stiffness k_eff = F_f / c (the flexure's
force at engagement, F_f = m R_Tp w_e^2 per shoe, over the clearance c it closes) and of the
peak von Mises stress at the engine's maximum speed (where the safety factor is read).  The
verdict ("holds" when engagement rises and the peak stress falls over the sweep) is computed
from the model's numbers; the script asserts that engagement and stiffness rise with the
thickness (the numbers it prints).  The requirement factors, the engine curve's shape and
mu = 0.165 are ASSUMED defaults.

With CLUTCHFEM_EXAMPLE_SMALL=1 (tests/test_examples.py): a coarse mesh (3 mm), three values
per concept, computed in this process (no Dask cluster).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

import clutchfem as cf

SMALL = os.environ.get("CLUTCHFEM_EXAMPLE_SMALL") == "1"
#: (concept, flexure thicknesses [m])
SERIES_FULL = (("concept1", np.arange(1.8e-3, 2.81e-3, 0.1e-3)), ("concept4", np.arange(1.5e-3, 2.11e-3, 0.05e-3)))
SERIES_SMALL = (("concept1", [2.0e-3, 2.2e-3, 2.4e-3]), ("concept4", [1.65e-3, 1.75e-3, 1.85e-3]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=Path("out/examples"))
    ap.add_argument("--workers", type=int, default=None,
                    help="local Dask process workers (default: one per core; small mode: 0, in this process)")
    ap.add_argument("--mesh-size", type=float, default=None, help="global element size [m] (default 1.2e-3)")
    args = ap.parse_args(argv)
    size = args.mesh_size or (3e-3 if SMALL else 1.2e-3)
    workers = args.workers if args.workers is not None else (0 if SMALL else None)
    args.out.mkdir(parents=True, exist_ok=True)
    store = args.out / "guideline_flexure_thickness.sqlite"
    fig = Figure(figsize=(15.0, 4.6))
    axes = fig.subplots(1, 3)
    print("A thicker flexure engages later, with lower stress (thesis 4.4):")
    for k, (concept, values) in enumerate(SERIES_SMALL if SMALL else SERIES_FULL):
        values = [float(f"{v:.6g}") for v in values]
        c = cf.get_concept(concept)
        clearance = c.Params().clearance
        df = cf.run_grid(cf.Design.from_concept(concept, mesh=cf.MeshSettings(size=size)), {"flexure_thickness": values}, store=store,
                         workers=workers).frame
        for _, r in df[df["status"] != "ok"].iterrows():
            print(f"  {concept}: flexure_thickness = {r['flexure_thickness'] * 1e3:g} mm: {r['status']} "
                  f"({r['message']})")
        ok = df[(df["status"] == "ok") & df["engagement_rpm"].notna()]
        if len(ok) < 2:
            print(f"  {concept}: fewer than two answered designs, no trend")
            continue
        t = ok["flexure_thickness"].to_numpy(float) * 1e3  # mm
        eng = ok["engagement_rpm"].to_numpy(float)
        k_eff = ok["spring_force_N"].to_numpy(float) / (clearance * 1e3)  # N/mm
        vm = ok["max_von_mises_MPa"].to_numpy(float)
        per = {name: 0.1 * np.polyfit(t, y, 1)[0] for name, y in (("eng", eng), ("k", k_eff), ("vm", vm))}
        monotone_vm = bool(np.all(np.diff(vm) < 0))
        holds = per["eng"] > 0 and per["vm"] < 0
        print(f"  {concept}: t_f {t[0]:.2f}..{t[-1]:.2f} mm: engagement {eng[0]:.0f} -> {eng[-1]:.0f} rpm, "
              f"k_eff {k_eff[0]:.0f} -> {k_eff[-1]:.0f} N/mm, peak von Mises at max rpm {vm[0]:.0f} -> "
              f"{vm[-1]:.0f} MPa")
        print(f"    per +0.1 mm of flexure: engagement {per['eng']:+.0f} rpm, k_eff {per['k']:+.1f} N/mm "
              f"({100 * per['k'] / np.mean(k_eff):+.1f} %), peak stress {per['vm']:+.1f} MPa -> guideline "
              + ("HOLDS" if holds else "DOES NOT HOLD here")
              + ("" if monotone_vm else " (the peak stress is not monotonic over the sweep)"))
        # the numbers printed, checked: a thicker flexure is stiffer and engages later (both
        # concepts, coarse and fine mesh alike); the stress verdict is what the model says
        assert per["eng"] > 0 and per["k"] > 0, (concept, per)
        for ax, y in zip(axes, (eng, k_eff, vm)):
            ax.plot(t, y, "-o", color=f"C{k}", label=concept)
    for ax, what in zip(axes, ("static engagement [rpm]", "k_eff = F_f / c per shoe [N/mm]",
                               "peak von Mises at max rpm [MPa]")):
        ax.set_xlabel("flexure thickness [mm]")
        ax.set_ylabel(what)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"thicker flexure (FE, mesh {size * 1e3:g} mm, 51CrV4, mu 0.165, engine curve ASSUMED)",
                 fontsize=10)
    fig.tight_layout()
    path = args.out / "guideline_flexure_thickness.png"
    fig.savefig(path, dpi=110)
    print(f"\nwrote {path}")
    print(f"wrote {store}")


if __name__ == "__main__":
    main()
