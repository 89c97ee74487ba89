"""Guideline (thesis 4.4): "a heavier shoe engages earlier and slips at a lower rpm" -- with
numbers from the FE model, on the study engine.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python examples/guideline_shoe_mass.py [--out DIR] [--workers N]

Three ways to add shoe mass, each with everything else at the concept's defaults:

* concept 1, radial shoe thickness (the flexure stays where it is, the shoe grows inwards);
* concept 4, shoe arc (the shoe grows at its tip; the beam is unchanged);
* concept 4, radial shoe thickness: here the beam's shoe end sits on the shoe's inner
  surface, so a thicker shoe also moves and shortens the lever the beam works on: mass is
  not the only thing that changes (the guideline may then not hold: see what it prints).

For each series the script fits engagement and slip speed against shoe mass (least squares,
straight line) and prints the change per gram and whether the guideline holds (both slopes
negative), computed from the model's numbers, not asserted.  The requirement factors
a = 1.3, b = 1.0 and the engine curve's shape are ASSUMED defaults.

With CLUTCHFEM_EXAMPLE_SMALL=1 (tests/test_examples.py): a coarse mesh (3 mm), three values
per series, computed in this process (no Dask cluster).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

import clutchfem as cf

SMALL = os.environ.get("CLUTCHFEM_EXAMPLE_SMALL") == "1"

#: (label, concept, parameter, values in the parameter's unit)
SERIES_FULL = (
    ("concept 1, shoe thickness", "concept1", "shoe_thickness", [4.5e-3, 5e-3, 5.5e-3, 6e-3, 6.5e-3, 7e-3, 7.5e-3]),
    ("concept 4, shoe arc", "concept4", "shoe_arc", [70.0, 75.0, 80.0, 85.0, 90.0, 95.0, 100.0, 105.0, 110.0]),
    ("concept 4, shoe thickness", "concept4", "shoe_thickness", [5.0e-3, 5.25e-3, 5.5e-3, 5.75e-3, 6e-3, 6.25e-3]),
)
SERIES_SMALL = (
    ("concept 1, shoe thickness", "concept1", "shoe_thickness", [5e-3, 6e-3, 7e-3]),
    ("concept 4, shoe arc", "concept4", "shoe_arc", [80.0, 90.0, 100.0]),
    ("concept 4, shoe thickness", "concept4", "shoe_thickness", [5.5e-3, 6e-3, 6.25e-3]),
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
    args.out.mkdir(parents=True, exist_ok=True)
    store = args.out / "guideline_shoe_mass.sqlite"
    series = SERIES_SMALL if SMALL else SERIES_FULL
    fig = Figure(figsize=(12.0, 4.8))
    ax_e, ax_s = fig.subplots(1, 2)
    lines = []
    for k, (label, concept, name, values) in enumerate(series):
        df = cf.run_grid(cf.Design.from_concept(concept, mesh=cf.MeshSettings(size=size)), {name: values}, store=store,
                         workers=workers).frame
        ok = df[df["status"] == "ok"]
        for _, r in df[df["status"] != "ok"].iterrows():
            print(f"  {label}: {name} = {r[name]:g}: {r['status']} ({r['message']})")
        m, e, s = (ok[c].to_numpy(float) for c in ("shoe_mass_g", "engagement_rpm", "slip_rpm"))
        have = np.isfinite(m) & np.isfinite(e) & np.isfinite(s)
        m, e, s = m[have], e[have], s[have]
        if len(m) < 2:
            print(f"{label}: fewer than two answered designs, no trend")
            continue
        de, ds = np.polyfit(m, e, 1)[0], np.polyfit(m, s, 1)[0]
        holds = de < 0 and ds < 0
        unit = "mm" if name.endswith("thickness") else "deg"
        shown = [v * 1e3 if unit == "mm" else v for v in ok[name]]
        lines.append(f"{label} ({shown[0]:g}..{shown[-1]:g} {unit}: shoe mass {m.min():.1f}..{m.max():.1f} g): "
                     f"engagement {e[0]:.0f} -> {e[-1]:.0f} rpm, slip {s[0]:.0f} -> {s[-1]:.0f} rpm; "
                     f"per +1 g of shoe: engagement {de:+.0f} rpm, slip {ds:+.0f} rpm -> guideline "
                     + ("HOLDS" if holds else "DOES NOT HOLD here"))
        if concept == "concept1":  # the numbers printed, checked: concept 1's heavier shoe engages earlier
            assert de < 0 and ds < 0, (label, de, ds)
        ax_e.plot(m, e, "-o", color=f"C{k}", label=label)
        ax_s.plot(m, s, "-o", color=f"C{k}", label=label)
    print("\nA heavier shoe engages earlier and slips at a lower rpm (thesis 4.4):")
    for line in lines:
        print("  " + line)
    for ax, what in ((ax_e, "static engagement [rpm]"), (ax_s, "slip speed, drum held [rpm]")):
        ax.set_xlabel("shoe mass [g]")
        ax.set_ylabel(what)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"heavier shoe: engagement and slip (FE, mesh {size * 1e3:g} mm, 51CrV4, mu 0.165, "
                 "engine curve ASSUMED)", fontsize=10)
    fig.tight_layout()
    path = args.out / "guideline_shoe_mass.png"
    fig.savefig(path, dpi=110)
    print(f"\nwrote {path}")
    print(f"wrote {store}")


if __name__ == "__main__":
    main()
