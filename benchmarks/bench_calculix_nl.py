"""Peer check kept current (issue 20): CalculiX 2.20 (Debian ``calculix-ccx``, installed by
``make bench-peer``; never a runtime or test dependency) against clutchfem on the *same* 3-D
mesh, geometrically non-linear free spin and rigid-drum contact, in one run.

The model (both codes, node for node)
-------------------------------------
Concept 4 at its default parameters, the full 360 degree part (no cyclic constraint in
either code), the ``best`` preset mesh (6 mm global, flexures 0.5 t_f, fillets 0.25 r,
contact surface 1.5 mm: coarse on purpose, 2 shared cores) extruded into ``LAYERS`` layers of
curved P2 tetrahedra through half the 11 mm thickness; ccx gets the very same C3D10 (same
nodes, same curved mid-side nodes), bore clamped, u_z = 0 on the mid-plane (exact mid-plane
symmetry), 51CrV4 (E 210 GPa, nu 0.3, rho 7850).

1. Free spin, geometrically non-linear
   * ccx: ``*STEP, NLGEOM`` / ``*STATIC, DIRECT`` / ``*DLOAD ... CENTRIF``: total-Lagrangian
     large-displacement statics, linear elastic law on Green-Lagrange strain and PK2 stress
     (St. Venant-Kirchhoff), the centrifugal load rho w^2 (X + u)_perp evaluated at the
     *deformed* Gauss point position over the reference volume (ccx 2.20 ``e_c3d.f``: with
     NLGEOM the body-force point is xl + vold): the load follows the deformation, which is
     spin softening, and the stress stiffening comes from NLGEOM itself.  w^2 is stepped up
     (``*AMPLITUDE``) through the speeds below; every increment is printed.
   * clutchfem: its 3-D path (:class:`clutchfem.fe.FEModel3D`) at each speed with the three
     load models the tool knows: ``linear`` (K u = w^2 f1: no spin softening), ``softening``
     ((K - w^2 M) u = w^2 f1: the load on the deformed position, linear strains) and
     ``prestress`` ((K + w^2 (K_sigma1 - M)) u = w^2 f1: plus the geometric stiffness of
     the centrifugal pre-stress, the linearisation of the non-linear problem about the
     linear field and the tool's default softening).  Only ``prestress`` contains the same
     physics as NLGEOM to first order; the rest (O(u^2) in the strain beyond K_sigma, the
     pre-stress's own dependence on w beyond w^2) is what the tool's 2-D total-Lagrangian
     reference (:class:`clutchfem.accuracy.NonlinearModel`) adds, measured per design in 2-D
     as d_NL and applied to the 3-D answer (``benchmarks/bench_accuracy.py``); that
     composition is checked here too (engagement, column ``3-D prestress x (1 + d_NL)``).
   Compared: max nodal |u_cf - u_ccx| / max |u_ccx| and the radial displacement of the shoe
   tip (the contact node of largest radial displacement at 4000 rpm) at each speed, and the
   engagement speed: ccx's from its exact gaps R_d - |X + u| on the contact nodes (secant in
   w^2 between two printed speeds bracketing clutchfem's answer), clutchfem's from its own
   path (gap along the initial normal, prestress softening).

2. Contact with a rigid drum, frictionless, at 8000 rpm
   * ccx: the drum as one layer of 8-node bricks (inner radius R_d = 34.4 mm, 2 mm wall,
     ``DRUM_DIVISIONS`` around: chord sag R_d (1 - cos(pi/n)), 0.08 um), every drum node
     fixed (a rigid drum), ``*CONTACT PAIR, TYPE=SURFACE TO SURFACE`` (penalty, linear
     pressure-overclosure of slope ``PENALTY``: 1e-8 m overclosure per 1 GPa), slave the
     shoes' contact faces, master the drum's inner faces; NLGEOM, w^2 stepped up from 0.
     Normal force: the radial reaction of the drum nodes (times 2: the half thickness),
     per shoe by the nearest shoe; contact arc: the angular extent of the slave nodes whose
     exact gap R_d - |X + u| is <= 0 (overclosed).
   * clutchfem: the tool's contact path on the 3-D model (LCP on the exact drum circle, gap
     along the initial normal, prestress softening, rigid drum, mu = 0): normal force, per
     shoe, contact arc (angular extent of the nodes with lam > 0), shoe-tip radial
     displacement; and its 3-D answer times (1 + d_NL) with d_NL from the 2-D
     total-Lagrangian reference on the same 2-D mesh (exact circle, load on the deformed
     position): the tool's non-linear best estimate.
   Friction is left out: clutchfem's friction is the full-slip (kinetic) state of a slipping
   clutch, a static ccx step with ``*FRICTION`` would stick; the peer of full slip needs the
   drum turned through a prescribed rotation in contact (a further step, not done).

Run (needs ccx on PATH; ``make bench-peer`` installs it and runs this):

    PYTHONPATH=src python benchmarks/bench_calculix_nl.py [--layers 1]
"""

from __future__ import annotations

import argparse
import math
import platform
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

import clutchfem as cf
from clutchfem.accuracy import NonlinearModel
from clutchfem.core import rad_s_to_rpm, rpm_to_rad_s
from clutchfem.fe import factorize, geometric_stiffness
from clutchfem.geometry import MeshSettings

RPMS = (4000.0, 8000.0)
RPM_CONTACT = 8000.0
DRUM_DIVISIONS = 1440
DRUM_WALL = 2e-3
PENALTY = 1e17  # N/m^3: 1 GPa contact pressure at 1e-8 m overclosure


# ---------------------------------------------------------------------------------------
# the mesh and the ccx deck
# ---------------------------------------------------------------------------------------
def tets(model):
    """(X (3, n), C3D10 connectivity (ne, 10), 0-based) of the 3-D model's P2 nodes."""
    b = model.basis
    X = b.doflocs[:, 0::3]
    cells = (b.element_dofs[0::3] // 3).T.copy()  # skfem TetP2 order = C3D10 order
    a, b_, c, d = (X[:, cells[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->j", np.cross(b_ - a, c - a, axis=0), d - a)
    neg = vol < 0
    cells[neg] = cells[neg][:, [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]]
    return X, cells


def slave_faces(model, cells):
    """(element, ccx face number) of every contact side face of the extruded mesh.
    C3D10 faces (ccx): S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1 (vertex sets)."""
    em = model.em.mesh
    fac = model.boundary("contact")
    faces = {1: {0, 1, 2}, 2: {0, 1, 3}, 3: {1, 2, 3}, 4: {0, 2, 3}}
    out = []
    for f in fac:
        e = int(em.f2t[0, f]) if em.f2t[0, f] >= 0 else int(em.f2t[1, f])
        verts = set(int(v) for v in em.facets[:, f])
        cv = cells[e, :4]
        loc = {k for k in range(4) if int(cv[k]) in verts}
        out.append((e, next(s for s, v in faces.items() if v == loc)))
    return out


def nset(f, name, nodes):
    f.write(f"*NSET, NSET={name}\n")
    nodes = np.asarray(nodes, dtype=int)
    for j in range(0, len(nodes), 12):
        f.write(", ".join(str(int(n) + 1) for n in nodes[j:j + 12]) + "\n")


def write_deck(path: Path, model, X, cells, mat, w2_steps: list[float], drum: dict | None):
    """The ccx input: the part, optionally the rigid drum and the contact pair, one NLGEOM
    step whose w^2 goes through ``w2_steps`` (one increment each, each printed)."""
    n = X.shape[1]
    b = model.basis
    bore = np.unique(b.get_dofs(model.boundary("bore")).all() // 3)
    mid = np.unique(b.get_dofs(model.boundary("mid")).all() // 3)
    with open(path, "w") as f:
        f.write("*NODE, NSET=Nall\n")
        for i, x in enumerate(X.T):
            f.write(f"{i + 1}, {x[0]:.13e}, {x[1]:.13e}, {x[2]:.13e}\n")
        f.write("*ELEMENT, TYPE=C3D10, ELSET=Epart\n")
        for k, c in enumerate(cells):
            f.write(f"{k + 1}, " + ", ".join(str(int(v) + 1) for v in c) + "\n")
        nset(f, "Nbore", bore)
        nset(f, "Nmid", mid)
        fixed = ["Nbore, 1, 3", "Nmid, 3, 3"]
        if drum is not None:
            dn0 = n + 1
            f.write("*NODE, NSET=Ndrum\n")
            for i, x in enumerate(drum["X"].T):
                f.write(f"{dn0 + i}, {x[0]:.13e}, {x[1]:.13e}, {x[2]:.13e}\n")
            e0 = len(cells) + 1
            f.write("*ELEMENT, TYPE=C3D8, ELSET=Edrum\n")
            for k, c in enumerate(drum["cells"]):
                f.write(f"{e0 + k}, " + ", ".join(str(int(v) + dn0) for v in c) + "\n")
            fixed.append("Ndrum, 1, 3")
            f.write("*SURFACE, NAME=Smaster\n")
            for k in range(len(drum["cells"])):
                f.write(f"{e0 + k}, S6\n")
            f.write("*SURFACE, NAME=Sslave\n")
            for e, s in drum["slave"]:
                f.write(f"{e + 1}, S{s}\n")
            f.write("*CONTACT PAIR, INTERACTION=SI1, TYPE=SURFACE TO SURFACE\nSslave, Smaster\n")
            f.write(f"*SURFACE INTERACTION, NAME=SI1\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                    f"{PENALTY:.6g}\n")
        nset(f, "Nout", drum["out"] if drum is not None else np.arange(n))
        f.write("*BOUNDARY\n" + "\n".join(fixed) + "\n")
        f.write(f"*MATERIAL, NAME=STEEL\n*ELASTIC\n{mat.E:.10g}, {mat.nu:.10g}\n*DENSITY\n{mat.rho:.10g}\n")
        f.write("*SOLID SECTION, ELSET=Epart, MATERIAL=STEEL\n")
        if drum is not None:
            f.write("*SOLID SECTION, ELSET=Edrum, MATERIAL=STEEL\n")
        t = np.linspace(0.0, 1.0, len(w2_steps) + 1)
        amp = [0.0] + [w / w2_steps[-1] for w in w2_steps]
        f.write("*AMPLITUDE, NAME=A1\n" + "\n".join(f"{a:.10g}, {b:.12g}" for a, b in zip(t, amp)) + "\n")
        dt = 1.0 / len(w2_steps)
        f.write(f"*STEP, NLGEOM, INC=1000\n*STATIC, DIRECT\n{dt:.10g}, 1.0\n")
        f.write(f"*DLOAD, AMPLITUDE=A1\nEpart, CENTRIF, {w2_steps[-1]:.12g}, 0., 0., 0., 0., 0., 1.\n")
        f.write("*NODE PRINT, NSET=Nout\nU\n")
        if drum is not None:
            f.write("*NODE PRINT, NSET=Ndrum\nRF\n")
        f.write("*END STEP\n")


def run_ccx(job: Path) -> float:
    t0 = time.perf_counter()
    r = subprocess.run(["ccx", "-i", job.stem], cwd=job.parent, capture_output=True, text=True,
                       env={"OMP_NUM_THREADS": "1", "CCX_NPROC_STIFFNESS": "1", "PATH": "/usr/bin:/bin"})
    dt = time.perf_counter() - t0
    if r.returncode != 0 or "*ERROR" in r.stdout:
        raise RuntimeError(r.stdout[-3000:])
    return dt


def read_blocks(path: Path, what: str, n: int) -> list[tuple[float, np.ndarray]]:
    """[(time, (3, n) values by 0-based node)] of every ``what`` block of a .dat file (node
    numbers beyond n are left out)."""
    out = []
    cur = None
    with open(path) as f:
        for line in f:
            if what in line and "time" in line:
                cur = np.zeros((3, n))
                out.append((float(line.split()[-1]), cur))
                continue
            if cur is None:
                continue
            p = line.split()
            if len(p) == 4:
                try:
                    k = int(p[0]) - 1
                    v = [float(x) for x in p[1:]]
                except ValueError:
                    continue
                if 0 <= k < n:
                    cur[:, k] = v
    return out


# ---------------------------------------------------------------------------------------
# clutchfem's side
# ---------------------------------------------------------------------------------------
def free_fields(model, omegas) -> dict[str, list[np.ndarray]]:
    """u(w) of the three load models (module docstring) at each speed [rad/s]."""
    T = model.T.tocsr()
    K, M, f1 = model.K, model.M, model.f1
    Ks = geometric_stiffness(model, model.u1)
    out = {}
    for name, G in (("linear", None), ("softening", -M), ("prestress", Ks - M)):
        us = []
        for w in omegas:
            A = K if G is None else K + w * w * G
            Ar = (T.T @ A @ T).tocsc()
            Ar = 0.5 * (Ar + Ar.T)
            us.append(T @ factorize(sp.csc_matrix(Ar)).solve(T.T @ (w * w * f1)))
        out[name] = us
    return out


def by_node(u):
    return np.vstack([u[0::3], u[1::3], u[2::3]])


def engagement_ccx(nodes, X, blocks, w2s, pair):
    """Engagement speed [rad/s] of ccx's field: the exact min gap R_d - |X + u| over the
    contact nodes, secant in w^2 between the printed speeds ``pair`` (indices)."""
    idx = nodes.dof_x // 3
    g = []
    for k in pair:
        U = blocks[k][1]
        x = X[0, idx] + U[0, idx]
        y = X[1, idx] + U[1, idx]
        g.append(float(np.min(nodes.drum_radius - np.hypot(x, y))))
    (a, b), (ga, gb) = (w2s[pair[0]], w2s[pair[1]]), g
    return math.sqrt(a - ga * (b - a) / (gb - ga)), g


def radial(nodes, U, k):
    """Radial displacement [m] of contact node k in the (3, n) field U."""
    i = nodes.dof_x[k] // 3
    return float(nodes.normal[0, k] * U[0, i] + nodes.normal[1, k] * U[1, i])


def part_free(d, X, cells, work: Path) -> tuple[list[dict], dict]:
    model, nodes = d.model, d.nodes
    case = d.case()
    t0 = time.perf_counter()
    w_eng_cf = case.engagement[0]
    t_eng = time.perf_counter() - t0
    speeds = [RPMS[0], rad_s_to_rpm(w_eng_cf) * 0.997, rad_s_to_rpm(w_eng_cf) * 1.003, 6000.0, RPMS[1]]
    w2s = [rpm_to_rad_s(r) ** 2 for r in speeds]
    job = work / "free_nl.inp"
    write_deck(job, model, X, cells, model.material, w2s, None)
    t_ccx = run_ccx(job)
    blocks = read_blocks(job.with_suffix(".dat"), "displacements", X.shape[1])
    if len(blocks) != len(speeds):
        raise RuntimeError(f"ccx printed {len(blocks)} increments, expected {len(speeds)}")
    t0 = time.perf_counter()
    omegas = [rpm_to_rad_s(r) for r in RPMS]
    fields = free_fields(model, omegas)
    t_cf = time.perf_counter() - t0
    k4 = speeds.index(RPMS[0])
    # the shoe tip: the contact node of largest radial displacement (ccx, 4000 rpm)
    ur = np.array([radial(nodes, blocks[k4][1], k) for k in range(nodes.m)])
    tip = int(np.argmax(ur))
    rows = []
    for j, rpm in enumerate(RPMS):
        U = blocks[speeds.index(rpm)][1]
        row = {"rpm": rpm, "u_tip_ccx_um": 1e6 * radial(nodes, U, tip)}
        for name, us in fields.items():
            Uc = by_node(us[j])
            row[f"du_{name}"] = float(np.abs(Uc - U).max() / np.abs(U).max())
            row[f"u_tip_{name}_um"] = 1e6 * radial(nodes, Uc, tip)
        rows.append(row)
    w_eng_ccx, g = engagement_ccx(nodes, X, blocks, w2s, (1, 2))
    eng = {"eng_cf_prestress_rpm": rad_s_to_rpm(w_eng_cf), "eng_ccx_rpm": rad_s_to_rpm(w_eng_ccx),
           "t_ccx_s": t_ccx, "t_cf_fields_s": t_cf, "t_cf_engagement_s": t_eng, "tip_angle_deg":
           math.degrees(float(nodes.angle[tip])), "increments": len(speeds)}
    return rows, eng


def nonlinear_delta(concept_kw) -> dict:
    """d_NL of engagement and of the normal force at RPM_CONTACT: the 2-D total-Lagrangian
    reference / the 2-D prestressed linear path - 1, on the same 2-D mesh, rigid drum, mu 0."""
    d2 = cf.Design.from_concept("concept4", formulation="plane-stress", **concept_kw)
    case = d2.case()
    nl = NonlinearModel(d2.model, drum_radius=d2.drum_radius, mu=0.0)
    w_lin = case.engagement[0]
    w_nl, _ = nl.engagement(w_lin)
    w8 = rpm_to_rad_s(RPM_CONTACT)
    st = nl.sweep([1.02 * w_nl, w8])[-1]
    N_lin = float(d2.sweep([RPM_CONTACT], stresses=False).curve["normal_force_N"].iloc[0])
    return {"eng": w_nl / w_lin - 1, "N": nl.normal_force(st) / N_lin - 1}


def drum_mesh(R: float, wall: float, h2: float, nth: int) -> dict:
    """One layer of 8-node bricks R <= r <= R + wall, 0 <= z <= h2, ``nth`` around; the
    inner face is ccx face S6 (4-8-5-1), its outward normal pointing at the axis."""
    th = np.linspace(0.0, 2 * math.pi, nth, endpoint=False)
    X = np.zeros((3, 4 * nth))
    for j, t in enumerate(th):
        for k, (r, z) in enumerate(((R, 0.0), (R + wall, 0.0), (R, h2), (R + wall, h2))):
            X[:, 4 * j + k] = (r * math.cos(t), r * math.sin(t), z)
    cells = []
    for j in range(nth):
        a, b = 4 * j, 4 * ((j + 1) % nth)
        cells.append([a, a + 1, b + 1, b, a + 2, a + 3, b + 3, b + 2])
    return {"X": X, "cells": np.array(cells)}


def arc_deg(angles: np.ndarray) -> float:
    """Angular extent [deg] of a set of polar angles of one shoe (0 for fewer than 2)."""
    if len(angles) < 2:
        return 0.0
    a = np.unwrap(np.sort(angles))
    return math.degrees(float(a.max() - a.min()))


def part_contact(d, X, cells, work: Path) -> tuple[list[dict], dict]:
    model, nodes = d.model, d.nodes
    n = X.shape[1]
    t0 = time.perf_counter()
    r = d.sweep([RPM_CONTACT], stresses=False)
    lam, _ = d.case().solve(rpm_to_rad_s(RPM_CONTACT))
    u_cf = by_node(r.fields.displacement(0))
    t_cf = time.perf_counter() - t0
    drum = drum_mesh(d.drum_radius, DRUM_WALL, model.thickness / 2, DRUM_DIVISIONS)
    drum["slave"] = slave_faces(model, cells)
    drum["out"] = np.unique(nodes.dof_x // 3)
    speeds = [4000.0, 5000.0, 6000.0, 7000.0, RPM_CONTACT]
    job = work / "contact_nl.inp"
    write_deck(job, model, X, cells, model.material, [rpm_to_rad_s(s) ** 2 for s in speeds], drum)
    t_ccx = run_ccx(job)
    U = read_blocks(job.with_suffix(".dat"), "displacements", n)[-1][1]
    rf_blocks = read_blocks(job.with_suffix(".dat"), "forces", n + drum["X"].shape[1])
    RF = rf_blocks[-1][1][:, n:]
    DX = drum["X"]
    rr = np.hypot(DX[0], DX[1])
    fr = -(RF[0] * DX[0] + RF[1] * DX[1]) / rr  # force of the part on the drum, radial
    idx = nodes.dof_x // 3
    gx, gy = X[0, idx] + U[0, idx], X[1, idx] + U[1, idx]
    g_ccx = nodes.drum_radius - np.hypot(gx, gy)
    # each drum node to the shoe of the angularly nearest contact node
    ang_d = np.arctan2(DX[1], DX[0])
    dang = np.abs(np.angle(np.exp(1j * (ang_d[:, None] - nodes.angle[None, :]))))
    shoe_d = nodes.shoe[np.argmin(dang, axis=1)]
    sym = model.symmetry_factor
    rows = []
    for s in nodes.shoes:
        sel = nodes.shoe == s
        ks = np.nonzero(sel)[0]
        tip_k = ks[np.argmax([radial(nodes, u_cf, k) for k in ks])]
        rows.append({"shoe": int(s), "N_cf_N": float(lam[sel].sum() * sym),
                     "N_ccx_N": float(fr[shoe_d == s].sum() * sym),
                     "arc_nodes_cf_deg": arc_deg(nodes.angle[sel & (lam > 0)]),
                     "arc_nodes_ccx_deg": arc_deg(nodes.angle[sel & (g_ccx <= 0)]),
                     "u_tip_cf_um": 1e6 * radial(nodes, u_cf, tip_k), "u_tip_ccx_um": 1e6 * radial(nodes, U, tip_k),
                     "max_overclosure_ccx_um": float(1e6 * max(0.0, -g_ccx[sel].min()))})
    summ = {"N_cf_N": float(r.curve["normal_force_N"].iloc[0]), "N_ccx_N": float(fr.sum() * sym),
            "arc_cf_tool_deg": float(r.curve["contact_arc_deg"].iloc[0]),
            "arc_cf_tool_error_deg": float(r.curve["contact_arc_error_deg"].iloc[0]),
            "du_field": float(np.abs(u_cf - U[:, :n]).max() / np.abs(U).max()),
            "t_cf_s": t_cf, "t_ccx_s": t_ccx, "slave_faces": len(drum["slave"])}
    return rows, summ


def table(rows: list[dict], fmt=".5g") -> str:
    cols = list(rows[0])
    out = ["| " + " | ".join(cols) + " |", "|" + "|".join("---" for _ in cols) + "|"]
    for r in rows:
        out.append("| " + " | ".join(f"{r[c]:{fmt}}" if isinstance(r[c], float) else str(r[c]) for c in cols) + " |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--layers", type=int, default=1, help="tetrahedron layers through half the thickness")
    ap.add_argument("--part", choices=["all", "free", "contact"], default="all")
    a = ap.parse_args()
    if shutil.which("ccx") is None:
        print("ccx (CalculiX) not found: `make bench-peer` installs Debian calculix-ccx (benchmarks only)")
        return
    t_all = time.perf_counter()
    ms = MeshSettings.preset("best", model="full", contact_factor=0.1)
    kw = {"mesh": ms, "drum_wall": 0.0, "mu": 0.0, "softening": "prestress"}
    t0 = time.perf_counter()
    d = cf.Design.from_concept("concept4", formulation="3d", layers=a.layers, **kw)
    X, cells = tets(d.model)
    t_build = time.perf_counter() - t0
    work = Path(tempfile.mkdtemp(prefix="ccx_nl_"))
    print(f"concept 4, full part, 'best' mesh (contact factor 0.1), {a.layers} layer(s) in the half thickness: "
          f"{len(cells)} C3D10, {X.shape[1]} nodes, {d.model.ndofs} dofs; clutchfem model + case built in "
          f"{t_build:.1f} s; {platform.node()}, {time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC; work {work}",
          flush=True)
    t0 = time.perf_counter()
    dnl = nonlinear_delta(kw)
    t_dnl = time.perf_counter() - t0
    print(f"2-D total-Lagrangian / 2-D prestress - 1 (same 2-D mesh, rigid drum, mu 0): engagement "
          f"{dnl['eng']:+.3e}, N({RPM_CONTACT:.0f}) {dnl['N']:+.3e} ({t_dnl:.1f} s)", flush=True)
    if a.part in ("all", "free"):
        rows, eng = part_free(d, X, cells, work)
        print(f"\n### Free spin, geometrically non-linear: ccx NLGEOM ({eng['increments']} increments) vs "
              "clutchfem's 3-D load models\n")
        print(table(rows))
        e_ref = eng["eng_cf_prestress_rpm"] * (1 + dnl["eng"])
        print(f"\nengagement: clutchfem 3-D prestress {eng['eng_cf_prestress_rpm']:.2f} rpm, x (1 + d_NL) "
              f"{e_ref:.2f} rpm; ccx NLGEOM (exact gaps) {eng['eng_ccx_rpm']:.2f} rpm: "
              f"{eng['eng_cf_prestress_rpm'] / eng['eng_ccx_rpm'] - 1:+.2e} / {e_ref / eng['eng_ccx_rpm'] - 1:+.2e}")
        print(f"times: ccx {eng['t_ccx_s']:.1f} s (whole NLGEOM run); clutchfem 3 load models x {len(RPMS)} speeds "
              f"{eng['t_cf_fields_s']:.1f} s, engagement {eng['t_cf_engagement_s']:.1f} s; shoe tip at "
              f"{eng['tip_angle_deg']:.1f} deg", flush=True)
    if a.part in ("all", "contact"):
        rows, s = part_contact(d, X, cells, work)
        print(f"\n### Rigid drum, frictionless, {RPM_CONTACT:.0f} rpm: ccx NLGEOM surface-to-surface penalty "
              f"({s['slave_faces']} slave faces) vs clutchfem 3-D prestress LCP\n")
        print(table(rows))
        print(f"\ntotal N: clutchfem {s['N_cf_N']:.2f} N (x (1 + d_NL): {s['N_cf_N'] * (1 + dnl['N']):.2f} N), ccx "
              f"{s['N_ccx_N']:.2f} N: {s['N_cf_N'] / s['N_ccx_N'] - 1:+.2e} / "
              f"{s['N_cf_N'] * (1 + dnl['N']) / s['N_ccx_N'] - 1:+.2e}; tool's arc {s['arc_cf_tool_deg']:.2f} "
              f"+- {s['arc_cf_tool_error_deg']:.2f} deg; max|du|/max|u| {s['du_field']:.2e}")
        print(f"times: ccx {s['t_ccx_s']:.1f} s; clutchfem sweep point + LCP {s['t_cf_s']:.1f} s", flush=True)
    print(f"\nwhole run {time.perf_counter() - t_all:.0f} s")


if __name__ == "__main__":
    main()
