"""Peak stress refinement (issue 20; BENCHMARKS.md section 13): the peak von Mises of
concepts 1 and 4 at their defaults refined locally (clutchfem.fe.peak_stress_converged)
from the best preset; prints the peak, its point, feature, error and the elements and time
of every level, for

* ``free``: the free spin (plane stress, per unit omega^2, shown at 4000 rpm);
* ``fast14k`` / ``best14k``: the answer analyze reports, the peak at 14 000 rpm with the
  drum contact, of the fast model (plane stress, rigid drum) and the best one (thick plane
  model, 2 mm elastic drum), each on the refined meshes.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_peak.py [--cases free,fast14k,best14k] [concept ...]
"""

import argparse
import math
import os
import time

from clutchfem import Design, OperatingPoint
from clutchfem.core import get_material
from clutchfem.fe import peak_stress_converged
from clutchfem.geometry import MeshSettings, get_concept

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

RPM = 4000.0  # free spin shown at 4000 rpm (section 12's speed)


def at_14k(name: str, fidelity: str):
    op = OperatingPoint(fidelity=fidelity)

    def evaluate(cm):
        d = Design.from_concept(name, operating=op, mesh=MeshSettings(**cm.mesh_settings))
        row = d.sweep([14000.0]).curve.iloc[0]
        return float(row.max_von_mises_Pa), (float(row.max_vm_x_m), float(row.max_vm_y_m))
    return evaluate


ap = argparse.ArgumentParser()
ap.add_argument("concepts", nargs="*", default=["concept4", "concept1"])
ap.add_argument("--cases", default="free,fast14k,best14k")
a = ap.parse_args()
for name in a.concepts:
    c = get_concept(name)
    for case in a.cases.split(","):
        kw = ({"material": get_material("51CrV4")} if case == "free"
              else {"evaluate": at_14k(name, case.removesuffix("14k"))})
        scale = (RPM * math.pi / 30) ** 2 if case == "free" else 1.0
        t0 = time.perf_counter()
        r = peak_stress_converged(c, c.params(), MeshSettings.preset("best"), **kw)
        wall = time.perf_counter() - t0
        where = f"{RPM:.0f} rpm free spin" if case == "free" else "14000 rpm, " + case.removesuffix("14k") + " model"
        print(f"\n{name} {case}: peak {r.peak * scale / 1e6:.2f} MPa at {where}, +- {r.error * scale / 1e6:.2f} MPa "
              f"({r.error / r.peak * 100:.3f} %, observed order {r.order:.2f}), at ({r.at[0] * 1e3:.3f}, "
              f"{r.at[1] * 1e3:.3f}) mm, {r.feature}; converged {r.converged}; {wall:.1f} s in all")
        print("| level | refine size [mm] | elements | peak [MPa] | point [mm] | time [s] |")
        print("|---:|---:|---:|---:|---|---:|")
        for k, lv in enumerate(r.levels):
            print(f"| {k} | {lv.refine_size * 1e3:.4f} | {lv.elements} | {lv.peak * scale / 1e6:.2f} "
                  f"| ({lv.at[0] * 1e3:.3f}, {lv.at[1] * 1e3:.3f}) | {lv.time_s:.2f} |", flush=True)
