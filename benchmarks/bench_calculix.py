"""Peer comparison with CalculiX (ccx 2.20, Debian ``calculix-ccx``; a benchmark-only tool,
never a runtime dependency): the same linear free-spin problem on the same mesh.

Problems (concept 4, default parameters, the *full* 360 degree mesh so that no cyclic
constraint is involved; bore clamped; centrifugal load at w = 1000 rad/s; no spin
softening -- CalculiX's linear static step has none either):

* plane stress: clutchfem P2 triangles (FEModel) vs ccx CPS6 (same nodes, same curved
  mid-side nodes, thickness 11 mm);
* plane strain: FEModel(formulation='plane-strain') vs ccx CPE6;
* 3-D: the extruded half model (P2 tetrahedra, mid-plane symmetry) vs ccx C3D10 on the
  very same tetrahedra with u_z = 0 on z = 0.

ccx's CPS6 is *not* a plane-stress element at 11 mm: it is expanded into one layer of 15-node
wedges with free faces, which on ~0.7 mm in-plane elements locks towards plane strain; a
0.2 mm thick CPS6 run shows that it tends to clutchfem's plane stress as h -> 0.

Reported: max nodal displacement difference / max displacement, the engagement speed from
each code's field with clutchfem's closed form (w0^2 = min gap0 / (n . u1)), and the wall
time of one solve in each code (ccx: the whole run, input parsing and output included;
clutchfem: assembly + factorisation + solve).  Run:

    PYTHONPATH=src python benchmarks/bench_calculix.py
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from clutchfem.contact import contact_nodes
from clutchfem.core import get_material, rad_s_to_rpm
from clutchfem.fe import ExtrusionSettings, FEModel, FEModel3D
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.mesh import mesh_concept

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

OMEGA = 1000.0


def _write_inp(path: Path, X: np.ndarray, cells: np.ndarray, etype: str, fixed: dict, mat, h: float | None):
    with open(path, "w") as f:
        f.write("*NODE, NSET=Nall\n")
        for i, x in enumerate(X.T):
            z = x[2] if len(x) == 3 else 0.0
            f.write(f"{i + 1}, {x[0]:.13e}, {x[1]:.13e}, {z:.13e}\n")  # ccx reads <= 20 chars a field
        f.write(f"*ELEMENT, TYPE={etype}, ELSET=Eall\n")
        for k, c in enumerate(cells):
            f.write(f"{k + 1}, " + ", ".join(str(int(n) + 1) for n in c) + "\n")
        for name, (nodes, dofs) in fixed.items():
            f.write(f"*NSET, NSET={name}\n")
            for j in range(0, len(nodes), 12):
                f.write(", ".join(str(int(n) + 1) for n in nodes[j:j + 12]) + "\n")
        f.write("*BOUNDARY\n")
        for name, (nodes, dofs) in fixed.items():
            f.write(f"{name}, {dofs[0]}, {dofs[1]}\n")
        f.write(f"*MATERIAL, NAME=STEEL\n*ELASTIC\n{mat.E:.10g}, {mat.nu:.10g}\n*DENSITY\n{mat.rho:.10g}\n")
        f.write("*SOLID SECTION, ELSET=Eall, MATERIAL=STEEL\n" + (f"{h:.10g}\n" if h else "\n"))
        f.write("*STEP\n*STATIC\n*DLOAD\n")
        f.write(f"Eall, CENTRIF, {OMEGA ** 2:.10g}, 0., 0., 0., 0., 0., 1.\n")
        f.write("*NODE PRINT, NSET=Nall\nU\n*END STEP\n")


def _read_dat(path: Path, n: int, dim: int) -> np.ndarray:
    U = np.zeros((3, n))
    with open(path) as f:
        lines = f.readlines()
    start = next(i for i, l in enumerate(lines) if "displacements" in l)
    for l in lines[start + 1:]:
        p = l.split()
        if len(p) == 4:
            try:
                U[:, int(p[0]) - 1] = [float(v) for v in p[1:]]
            except ValueError:
                continue
    return U[:dim]


def _run_ccx(job: Path) -> float:
    t0 = time.perf_counter()
    r = subprocess.run(["ccx", "-i", job.stem], cwd=job.parent, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0 or "ERROR" in r.stdout:
        raise RuntimeError(r.stdout[-2000:])
    return dt


def _engagement(nodes, u1):
    un = nodes.normal_displacement(u1)
    ok = un > 0
    return rad_s_to_rpm(math.sqrt(float(np.min(nodes.gap0[ok] / un[ok]))))


def compare_2d(cm, p, mat, formulation: str, etype: str, work: Path) -> dict:
    t0 = time.perf_counter()
    fe = FEModel(cm, mat, p.thickness, formulation=formulation)
    u = fe.solve(OMEGA ** 2 * fe.f1)
    t_cf = time.perf_counter() - t0
    b = fe.basis
    # scalar P2 node numbering: x dof of node k is 2 k (checked by FEModel's layout assertion)
    X = b.doflocs[:, 0::2]
    ed = b.element_dofs[0::2] // 2  # (6, ne): vertices, then mid-edges 01, 12, 20 (as CPS6)
    cells = ed.T.copy()
    a, b_, c = (X[:, cells[:, k]] for k in range(3))
    cw = ((b_[0] - a[0]) * (c[1] - a[1]) - (b_[1] - a[1]) * (c[0] - a[0])) < 0
    cells[cw] = cells[cw][:, [0, 2, 1, 5, 4, 3]]  # counter-clockwise for ccx
    bore = np.unique(b.get_dofs(cm.boundary("bore")).all() // 2)
    job = work / f"ps_{etype}.inp"
    _write_inp(job, X, cells, etype, {"Nbore": (bore, (1, 2))}, mat, p.thickness)
    t_ccx = _run_ccx(job)
    U = _read_dat(job.with_suffix(".dat"), X.shape[1], 2)
    Uc = np.vstack([u[0::2], u[1::2]])
    nodes = contact_nodes(fe, p.drum_radius)
    u1_ccx = np.zeros_like(u)
    u1_ccx[0::2], u1_ccx[1::2] = U[0] / OMEGA ** 2, U[1] / OMEGA ** 2
    return {"problem": f"{formulation} ({etype})", "dofs": fe.ndofs,
            "max|du|/max|u|": float(np.abs(U - Uc).max() / np.abs(Uc).max()),
            "eng_clutchfem_rpm": _engagement(nodes, u / OMEGA ** 2), "eng_ccx_rpm": _engagement(nodes, u1_ccx),
            "t_clutchfem_s": t_cf, "t_ccx_s": t_ccx}


def compare_3d(cm, p, mat, layers: int, work: Path) -> dict:
    t0 = time.perf_counter()
    fe = FEModel3D(cm, mat, p.thickness, settings=ExtrusionSettings(layers=layers))
    u = fe.solve(OMEGA ** 2 * fe.f1)
    t_cf = time.perf_counter() - t0
    print("clutchfem 3-D timings:", {k: round(v, 2) for k, v in fe.timings.items()})
    b = fe.basis
    X = b.doflocs[:, 0::3]
    cells = (b.element_dofs[0::3] // 3).T.copy()  # skfem TetP2 order = C3D10 order
    a, b_, c, d = (X[:, cells[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->j", np.cross(b_ - a, c - a, axis=0), d - a)
    neg = vol < 0
    cells[neg] = cells[neg][:, [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]]
    bore = np.unique(b.get_dofs(fe.em.boundary("bore")).all() // 3)
    mid = np.unique(b.get_dofs(fe.em.boundary("mid")).all() // 3)
    job = work / "c3d10.inp"
    _write_inp(job, X, cells, "C3D10", {"Nbore": (bore, (1, 3)), "Nmid": (mid, (3, 3))}, mat, None)
    t_ccx = _run_ccx(job)
    U = _read_dat(job.with_suffix(".dat"), X.shape[1], 3)
    Uc = np.vstack([u[0::3], u[1::3], u[2::3]])
    nodes = contact_nodes(fe, p.drum_radius)
    u1_ccx = np.zeros_like(u)
    for k in range(3):
        u1_ccx[k::3] = U[k] / OMEGA ** 2
    return {"problem": f"3-D, {layers} layers (C3D10)", "dofs": fe.ndofs,
            "max|du|/max|u|": float(np.abs(U - Uc).max() / np.abs(Uc).max()),
            "eng_clutchfem_rpm": _engagement(nodes, u / OMEGA ** 2), "eng_ccx_rpm": _engagement(nodes, u1_ccx),
            "t_clutchfem_s": t_cf, "t_ccx_s": t_ccx}


def main():
    if shutil.which("ccx") is None:
        print("ccx (CalculiX) not found: apt-get install calculix-ccx (benchmarks only)")
        return
    c = get_concept("concept4")
    p = c.Params()
    cm = mesh_concept(c, p, MeshSettings(model="full"))
    mat = get_material("51CrV4")
    work = Path(tempfile.mkdtemp(prefix="ccx_"))
    rows = [compare_2d(cm, p, mat, "plane-stress", "CPS6", work),
            compare_2d(cm, p, mat, "plane-strain", "CPE6", work),
            compare_3d(cm, p, mat, 2, work)]
    # ccx's CPS6 is expanded into one layer of 15-node wedges with free faces: at 11 mm on
    # ~0.7 mm in-plane elements that layer locks towards plane strain; it becomes plane stress
    # only as the thickness -> 0 (u does not depend on h in plane stress: compare at 0.2 mm)
    thin = type("P", (), {"thickness": 0.2e-3, "drum_radius": p.drum_radius})()
    r = compare_2d(cm, thin, mat, "plane-stress", "CPS6", work)
    r["problem"] = "plane-stress (CPS6), h = 0.2 mm"
    rows.insert(1, r)
    cols = ["problem", "dofs", "max|du|/max|u|", "eng_clutchfem_rpm", "eng_ccx_rpm", "t_clutchfem_s", "t_ccx_s"]
    print("\n### CalculiX 2.20 vs clutchfem, concept 4 full part, linear free spin (w = 1000 rad/s)\n")
    print("| " + " | ".join(cols) + " |\n|" + "|".join("---" for _ in cols) + "|")
    for r in rows:
        print("| " + " | ".join(f"{r[k]:.6g}" if not isinstance(r[k], str) else r[k] for k in cols) + " |")


if __name__ == "__main__":
    main()
