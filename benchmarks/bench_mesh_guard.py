"""The high-order guard (mesh/highorder.py, issue 20) over presets, fillet factors and the
space-filling designs of bench_accuracy.py: the worst scaled Jacobian of every mesh, the
repairs made, and the free-spin peak von Mises at the element vertices against the peak at
the quadrature points (a nearly degenerate element reads several times the field's peak).

    PYTHONPATH=src .venv/bin/python benchmarks/bench_mesh_guard.py [--lhs]
"""

import argparse
import json
import logging
import os
import time
from pathlib import Path

import numpy as np

from clutchfem.core import get_material
from clutchfem.fe import FEModel
from clutchfem.geometry import MeshSettings, concepts, get_concept
from clutchfem.mesh import mesh_concept, scaled_jacobian

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

repairs: list[str] = []


class _Count(logging.Handler):
    def emit(self, record):
        if "curved elements repaired" in record.getMessage():
            repairs.append(record.getMessage())


logging.getLogger("clutchfem").addHandler(_Count())
logging.getLogger("clutchfem").setLevel(logging.INFO)


def refined(ms: MeshSettings) -> MeshSettings:
    return ms.replace(size=0.5 * ms.size, flexure_factor=0.5 * ms.flexure_factor, fillet_factor=0.5 * ms.fillet_factor)


def check(label, name, params, ms):
    c = get_concept(name)
    n0 = len(repairs)
    t0 = time.perf_counter()
    try:
        cm = mesh_concept(c, c.params(**params), ms, use_cache=False)
    except Exception as exc:  # noqa: BLE001 - a refusal is a result here
        print(f"| {label} | refused: {exc} | | | | |")
        return
    t = time.perf_counter() - t0
    sj = float(np.min(scaled_jacobian(cm.mesh)))
    m = FEModel(cm, get_material("51CrV4"))
    vm = m.von_mises(m.stress(m.u1))
    g = m.basis.interpolate(m.u1).grad
    lam, mu = m.lame
    exx, eyy, exy = g[0, 0], g[1, 1], 0.5 * (g[0, 1] + g[1, 0])
    vq = float(np.max(m.von_mises(np.array([2 * mu * exx + lam * (exx + eyy), 2 * mu * eyy + lam * (exx + eyy),
                                            2 * mu * exy]))))
    fix = repairs[n0].split("(")[1].split(";")[0] if len(repairs) > n0 else ""
    print(f"| {label} | {cm.n_elements} | {sj:.3f} | {fix} | {float(np.max(vm)) / vq:.3f} | {t:.2f} |", flush=True)


ap = argparse.ArgumentParser()
ap.add_argument("--lhs", action="store_true", help="also the 24 space-filling designs of bench_accuracy.py")
a = ap.parse_args()
print("| mesh | elements | worst scaled Jacobian | repaired (before -> after) | vertex / quadrature peak | mesh s |")
print("|---|---:|---:|---|---:|---:|")
for name in concepts():
    check(f"{name} fast", name, {}, MeshSettings())
    best = MeshSettings.preset("best")
    for ff in (0.5, 0.25, 0.125, 0.0625):
        check(f"{name} best, fillet factor {ff}", name, {}, best.replace(fillet_factor=ff))
    check(f"{name} best refined", name, {}, refined(best))
if a.lhs:
    seen = set()
    for line in Path(__file__).with_name("results_accuracy.jsonl").read_text().splitlines():
        r = json.loads(line)
        if "-lhs" in r["label"] and r["label"] not in seen:
            seen.add(r["label"])
            for lab, ms in (("best", MeshSettings.preset("best")), ("refined", refined(MeshSettings.preset("best")))):
                check(f"{r['label']} {lab}", r["concept"], r["params"], ms)
print(f"\n{len(repairs)} meshes repaired")
