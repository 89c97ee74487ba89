"""Guideline (thesis 4.4): "a 0.2-0.5 mm shift of the flexure changes stiffness and stress a
lot" -- how much, per 0.1 mm, from the FE model, on the study engine.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python examples/guideline_flexure_shift.py [--out DIR] [--workers N]

The thesis reports that moving the flexure by 0.2-0.5 mm changed the stiffness a lot, and
concludes that tight tolerances are needed; nobody quantified it.  Four manufacturing
deviations of that size, each on its own, everything else at the concept's defaults:

* concept 4, the beam moved radially outwards at the hub (``hub_radius`` + d);
* concept 4, one edge of the beam moved by d (``flexure_thickness`` + d);
* concept 1, the flexure moved radially outwards (``flexure_offset`` + d, d >= 0: the
  default sits on the shoe's inner edge);
* concept 1, one edge of the flexure moved by d (``flexure_thickness`` + d).

For each: the effective flexure stiffness k_eff = F_f / c (the flexure's force at
engagement F_f = m R_Tp w_e^2 per shoe over the clearance c it closes), the static
engagement speed and the peak von Mises stress at the engine's maximum speed, at d = 0 and
their change per 0.1 mm (least-squares slope over the shifts) and over the largest shift.
Which deviations matter and which do not is what the model says; the script only prints it.

With CLUTCHFEM_EXAMPLE_SMALL=1 (tests/test_examples.py): a coarse mesh (3 mm), shifts
-0.2, 0, +0.2 mm, computed in this process (no Dask cluster).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

import clutchfem as cf

SMALL = os.environ.get("CLUTCHFEM_EXAMPLE_SMALL") == "1"
#: (label, concept, parameter, shifts allowed below the default?)
DEVIATIONS = (
    ("concept 4: beam moved radially at the hub", "concept4", "hub_radius", True),
    ("concept 4: one beam edge moved (thickness)", "concept4", "flexure_thickness", True),
    ("concept 1: flexure moved radially", "concept1", "flexure_offset", False),
    ("concept 1: one flexure edge moved (thickness)", "concept1", "flexure_thickness", True),
)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=Path("out/examples"))
    ap.add_argument("--workers", type=int, default=None,
                    help="local Dask process workers (default: one per core; small mode: 0, in this process)")
    ap.add_argument("--mesh-size", type=float, default=None, help="global element size [m] (default 1.2e-3)")
    args = ap.parse_args(argv)
    size = args.mesh_size or (3e-3 if SMALL else 1.2e-3)
    workers = args.workers if args.workers is not None else (0 if SMALL else None)
    shifts_mm = [-0.2, 0.0, 0.2] if SMALL else [-0.5, -0.4, -0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.4, 0.5]
    args.out.mkdir(parents=True, exist_ok=True)
    store = args.out / "guideline_flexure_shift.sqlite"
    fig = Figure(figsize=(15.0, 4.6))
    axes = fig.subplots(1, 3)
    print("A 0.2-0.5 mm shift of the flexure (thesis 4.4), per 0.1 mm, FE model "
          f"(mesh {size * 1e3:g} mm, 51CrV4, mu 0.165):")
    for k, (label, concept, name, both_ways) in enumerate(DEVIATIONS):
        p0 = cf.get_concept(concept).Params()
        x0, clearance = getattr(p0, name), p0.clearance
        d_mm = [d for d in shifts_mm if both_ways or d >= 0]
        values = [float(f"{x0 + d * 1e-3:.9g}") for d in d_mm]
        df = cf.run_grid(cf.Design.from_concept(concept, mesh=cf.MeshSettings(size=size)), {name: values}, store=store,
                         workers=workers).frame
        for d, (_, r) in zip(d_mm, df.iterrows()):
            if r["status"] != "ok":
                print(f"  {label}: shift {d:+.1f} mm: {r['status']} ({r['message']})")
        sel = (df["status"] == "ok").to_numpy() & df["engagement_rpm"].notna().to_numpy()
        d = np.asarray(d_mm)[sel]
        ok = df[sel]
        if len(ok) < 2 or 0.0 not in d:
            print(f"  {label}: too few answered designs")
            continue
        k_eff = ok["spring_force_N"].to_numpy(float) / (clearance * 1e3)
        eng = ok["engagement_rpm"].to_numpy(float)
        vm = ok["max_von_mises_MPa"].to_numpy(float)
        i0 = int(np.nonzero(d == 0.0)[0][0])
        slope = {n: 0.1 * np.polyfit(d, y, 1)[0] for n, y in (("k", k_eff), ("eng", eng), ("vm", vm))}
        j = int(np.argmax(np.abs(d)))
        print(f"  {label} ({name} = {x0 * 1e3:g} mm at d = 0):")
        print(f"    at d = 0: k_eff {k_eff[i0]:.1f} N/mm, engagement {eng[i0]:.0f} rpm, peak stress {vm[i0]:.0f} MPa")
        print(f"    per 0.1 mm: k_eff {slope['k']:+.2f} N/mm ({100 * slope['k'] / k_eff[i0]:+.1f} %), engagement "
              f"{slope['eng']:+.0f} rpm ({100 * slope['eng'] / eng[i0]:+.1f} %), peak stress {slope['vm']:+.1f} MPa "
              f"({100 * slope['vm'] / vm[i0]:+.1f} %)")
        print(f"    at d = {d[j]:+.1f} mm: k_eff {100 * (k_eff[j] / k_eff[i0] - 1):+.1f} %, engagement "
              f"{eng[j] - eng[i0]:+.0f} rpm, peak stress {vm[j] - vm[i0]:+.0f} MPa")
        if name == "flexure_thickness":  # the numbers printed, checked: a thicker flexure is stiffer
            assert slope["k"] > 0 and slope["eng"] > 0, (label, slope)
        for ax, y in zip(axes, (100 * (k_eff / k_eff[i0] - 1), eng, vm)):
            ax.plot(d, y, "-o", color=f"C{k}", label=label)
    for ax, what in zip(axes, ("k_eff change [%]", "static engagement [rpm]", "peak von Mises at max rpm [MPa]")):
        ax.set_xlabel("shift d [mm]")
        ax.set_ylabel(what)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"flexure shifts of 0.1-0.5 mm (FE, mesh {size * 1e3:g} mm; each deviation alone)", fontsize=10)
    fig.tight_layout()
    path = args.out / "guideline_flexure_shift.png"
    fig.savefig(path, dpi=110)
    print(f"\nwrote {path}")
    print(f"wrote {store}")


if __name__ == "__main__":
    main()
