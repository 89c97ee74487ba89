"""Peak stress refinement (issue 20; BENCHMARKS.md section 13): the free-spin peak von Mises
of concepts 1 and 4 at their defaults, refined locally (clutchfem.fe.peak_stress_converged)
from the best preset; prints the peak, its point, feature, error and the elements and time
of every level.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_peak.py [concept ...]
"""

import sys
import time

from clutchfem.core import get_material
from clutchfem.fe import peak_stress_converged
from clutchfem.geometry import MeshSettings, get_concept

RPM = 4000.0  # stress shown at 4000 rpm of free spin (section 12's speed)

for name in sys.argv[1:] or ["concept4", "concept1"]:
    c = get_concept(name)
    t0 = time.perf_counter()
    r = peak_stress_converged(c, c.params(), get_material("51CrV4"), MeshSettings.preset("best"))
    wall = time.perf_counter() - t0
    print(f"{name}: peak {r.at_rpm(RPM) / 1e6:.2f} MPa at {RPM:.0f} rpm free spin, +- {r.error / r.peak * 100:.3f} % "
          f"(order {r.order:.2f}), at ({r.at[0] * 1e3:.3f}, {r.at[1] * 1e3:.3f}) mm, {r.feature}; converged "
          f"{r.converged}; {wall:.1f} s in all (meshes not cached)")
    print("| level | refine size [mm] | elements | peak at 4000 rpm [MPa] | point [mm] | time [s] |")
    print("|---:|---:|---:|---:|---|---:|")
    for k, lv in enumerate(r.levels):
        print(f"| {k} | {lv.refine_size * 1e3:.4f} | {lv.elements} | {lv.peak * (RPM * 3.141592653589793 / 30) ** 2 / 1e6:.2f} "
              f"| ({lv.at[0] * 1e3:.3f}, {lv.at[1] * 1e3:.3f}) | {lv.time_s:.2f} |")
