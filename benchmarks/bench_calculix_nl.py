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
   * clutchfem: the tool's contact path on the 3-D model (LCP on the exact drum circle, gap
     along the initial normal, prestress softening, rigid drum, mu = 0): normal force per
     shoe, the nodes in contact (lam > 0) and their arc, shoe-tip radial displacement; and
     its 3-D answer times (1 + d_NL) with d_NL from the 2-D total-Lagrangian reference on the
     same 2-D mesh (exact circle, load on the deformed position): the tool's non-linear best
     estimate.
   * ccx (default): the geometrically non-linear problem (NLGEOM, CENTRIF as above) with
     clutchfem's contact set *held on the drum*, frictionless: first along the initial
     radius (u_r = g0 in a cylindrical ``*TRANSFORM``, tangential and axial motion free),
     then ``CIRCLE_ITERATIONS`` times on the exact circle along the normal at the solved
     position (a rectangular ``*TRANSFORM`` per node, n_f . u = R_d - n_f . X).  The first is
     *not* frictionless: a node that slides u_t ~ 0.8 mm along the drum is pushed along a
     direction u_t / R_d ~ 1.3 deg off the drum's normal, a fictitious friction (mu ~ 0.02)
     that moves the normal force by ~3 % (printed, to show it); the second is the peer.  The
     contact forces are ccx's reactions on the held nodes along the current normal; their
     tangential part / normal part is printed (~0 when frictionless).  Complementarity is
     checked on ccx's field: every held node pushed (``min_lam_ccx_N``), every other node's
     gap open, exact R_d - |X + u| (``min_open_gap_ccx_um``) and g0 - n . u
     (``min_open_lingap_ccx_um``).  If both hold, clutchfem's contact set is the non-linear
     problem's too, and the forces compare like for like.
   * ccx's own contact search (``--contact-search``): the drum as one layer of 8-node bricks
     (R_d, 2 mm wall, ``DRUM_DIVISIONS`` around: chord sag 0.08 um), all nodes fixed,
     ``*CONTACT PAIR`` with the shoes' C3D10 contact faces as slave, linear penalty.  On this
     mesh it did not converge (2026-11-26): SURFACE TO SURFACE at 1e17 N/m^3 chattered (2900-
     3700 contact elements, 20 iterations without convergence in the 5000 rpm increment),
     NODE TO SURFACE at 1e15 N/m^3 stalled (largest residual ~2e4 N over 14 iterations): the
     corner nodes of a 6-node triangle carry no share of a uniform pressure, the known
     weakness of penalty contact on quadratic tetrahedra.  Kept as an option, not reported.
   Friction is left out: clutchfem's friction is the full-slip (kinetic) state of a slipping
   clutch, a static ccx step with ``*FRICTION`` would stick; the peer of full slip needs the
   drum turned through a prescribed rotation in contact (a further step, not done).

Run (needs ccx on PATH; ``make bench-peer`` installs it and runs this):

    PYTHONPATH=src python benchmarks/bench_calculix_nl.py [--layers 1]
"""

from __future__ import annotations

import argparse
import math
import os
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

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

RPMS = (4000.0, 8000.0)
RPM_CONTACT = 8000.0
DRUM_DIVISIONS = 1440
DRUM_WALL = 2e-3
CIRCLE_ITERATIONS = 2
PENALTY = 1e15  # N/m^3: 1 GPa contact pressure at 1e-6 m overclosure


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


def write_deck(path: Path, model, X, cells, mat, w2_steps: list[float], drum: dict | None,
               active: tuple | None = None):
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
            f.write("*CONTACT PAIR, INTERACTION=SI1, TYPE=NODE TO SURFACE\nSslave, Smaster\n")
            f.write(f"*SURFACE INTERACTION, NAME=SI1\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                    f"{PENALTY:.6g}\n")
        nset(f, "Nout", drum["out"] if drum is not None else np.arange(n))
        f.write("*BOUNDARY\n" + "\n".join(fixed) + "\n")
        if active is not None:  # the contact set held: n . u = value along n (tangent, z free)
            nodes_a, g0, dirs = active
            nset(f, "Nact", nodes_a)
            if dirs is None:  # the initial radial direction (cylindrical system)
                f.write("*TRANSFORM, NSET=Nact, TYPE=C\n0., 0., 0., 0., 0., 1.\n")
            else:  # a direction of its own per node (rectangular system, local x = n)
                for j, k in enumerate(nodes_a):
                    nx, ny = dirs[:, j]
                    f.write(f"*NSET, NSET=H{j}\n{int(k) + 1}\n*TRANSFORM, NSET=H{j}, TYPE=R\n"
                            f"{nx:.12e}, {ny:.12e}, 0., {-ny:.12e}, {nx:.12e}, 0.\n")
            f.write("*BOUNDARY\n" + "".join(f"{int(k) + 1}, 1, 1, {g:.13e}\n" for k, g in zip(nodes_a, g0)))
        f.write(f"*MATERIAL, NAME=STEEL\n*ELASTIC\n{mat.E:.10g}, {mat.nu:.10g}\n*DENSITY\n{mat.rho:.10g}\n")
        f.write("*SOLID SECTION, ELSET=Epart, MATERIAL=STEEL\n")
        if drum is not None:
            f.write("*SOLID SECTION, ELSET=Edrum, MATERIAL=STEEL\n")
        t = np.linspace(0.0, 1.0, len(w2_steps) + 1)
        amp = [0.0] + [w / w2_steps[-1] for w in w2_steps]
        f.write("*AMPLITUDE, NAME=A1\n" + "\n".join(f"{a:.10g}, {b:.12g}" for a, b in zip(t, amp)) + "\n")
        dt = 1.0 / len(w2_steps)
        if drum is None:  # one increment a speed, each printed
            f.write(f"*STEP, NLGEOM, INC=1000\n*STATIC, DIRECT\n{dt:.10g}, 1.0\n")
        else:  # contact: automatic increments (cut back where the contact set changes)
            f.write(f"*STEP, NLGEOM, INC=1000\n*STATIC\n{dt:.10g}, 1.0, 1e-5, {dt:.10g}\n")
        f.write(f"*DLOAD, AMPLITUDE=A1\nEpart, CENTRIF, {w2_steps[-1]:.12g}, 0., 0., 0., 0., 0., 1.\n")
        f.write("*NODE PRINT, NSET=Nout, GLOBAL=YES\nU\n")
        if drum is not None:
            f.write("*NODE PRINT, NSET=Ndrum\nRF\n")
        if active is not None:
            f.write("*NODE PRINT, NSET=Nact, GLOBAL=YES\nRF\n")
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
            if " for set " in line and "time" in line:  # a block header: ours or another's
                cur = None
                if what in line:
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
    """Radial displacement n . u [m] of contact node k in the (3, n) field U (along the
    initial normal: the closure of the tool's linear gap)."""
    i = nodes.dof_x[k] // 3
    return float(nodes.normal[0, k] * U[0, i] + nodes.normal[1, k] * U[1, i])


def radius_change(nodes, U, k):
    """|X + u| - |X| [m] of contact node k: the closure of the exact gap."""
    i = nodes.dof_x[k] // 3
    x = nodes.xy[:, k]
    return float(np.hypot(x[0] + U[0, i], x[1] + U[1, i]) - np.hypot(*x))


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
        row = {"rpm": rpm, "u_tip_ccx_um": 1e6 * radial(nodes, U, tip), "dr_tip_ccx_um": 1e6 * radius_change(nodes, U, tip)}
        for name, us in fields.items():
            Uc = by_node(us[j])
            row[f"du_{name}"] = float(np.abs(Uc - U).max() / np.abs(U).max())
            row[f"u_tip_{name}_um"] = 1e6 * radial(nodes, Uc, tip)
        row["dr_tip_prestress_um"] = 1e6 * radius_change(nodes, by_node(fields["prestress"][j]), tip)
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


def held_forces(model, nodes, ia, w) -> dict[str, float]:
    """Total normal force [N] of the model (not scaled) with the contact nodes ``ia`` held at
    n . u = g0 (frictionless), per load model, by exact solves: u = u_f - A^-1 B lam,
    B' u = g0."""
    T = model.T.tocsr()
    G = {"linear": None, "softening": -model.M, "prestress": geometric_stiffness(model, model.u1) - model.M}
    B = sp.csc_matrix((np.concatenate([nodes.normal[0, ia], nodes.normal[1, ia]]),
                       (np.concatenate([nodes.dof_x[ia], nodes.dof_y[ia]]), np.tile(np.arange(len(ia)), 2))),
                      shape=(model.ndofs, len(ia)))
    Br = (T.T @ B).toarray()
    out = {}
    for name, g in G.items():
        A = model.K if g is None else model.K + w * w * g
        Ar = (T.T @ A @ T).tocsc()
        F = factorize(sp.csc_matrix(0.5 * (Ar + Ar.T)))
        uf = F.solve(T.T @ (w * w * model.f1))
        lam = np.linalg.solve(Br.T @ F.solve(Br), Br.T @ uf - nodes.gap0[ia])
        out[name] = float(lam.sum())
    return out


def part_contact(d, X, cells, work: Path, search: bool = False) -> tuple[list[dict], dict]:
    """Rigid drum, mu = 0, RPM_CONTACT.  Default: ccx solves the non-linear problem with
    clutchfem's contact set held on the drum (u_r = g0 in a cylindrical system, tangential
    and axial motion free: frictionless), and complementarity is checked a posteriori
    (every held node pushed, not pulled; every free node's exact gap open).  ``search``:
    ccx's own contact search (``*CONTACT PAIR`` against a meshed drum; did not converge on
    this mesh, module docstring)."""
    if search:
        return part_contact_search(d, X, cells, work)
    model, nodes = d.model, d.nodes
    n = X.shape[1]
    w8 = rpm_to_rad_s(RPM_CONTACT)
    t0 = time.perf_counter()
    r = d.sweep([RPM_CONTACT], stresses=False)
    lam, _ = d.case().solve(w8)
    u_cf = by_node(r.fields.displacement(0))
    t_cf = time.perf_counter() - t0
    act = lam > 0
    idx = nodes.dof_x // 3
    speeds = [4000.0, 5000.0, 6000.0, 7000.0, RPM_CONTACT]
    job = work / "contact_held.inp"
    write_deck(job, model, X, cells, model.material, [rpm_to_rad_s(v) ** 2 for v in speeds], None,
               active=(idx[act], nodes.gap0[act], None))
    t_ccx = run_ccx(job)
    U = read_blocks(job.with_suffix(".dat"), "displacements", n)[-1][1]
    RF = read_blocks(job.with_suffix(".dat"), "forces", n)[-1][1]
    # contact force of the drum on held node i: the support's reaction, along -n_i
    lam_ccx = np.zeros(nodes.m)
    ia = np.nonzero(act)[0]
    lam_ccx[ia] = -(RF[0, idx[ia]] * nodes.normal[0, ia] + RF[1, idx[ia]] * nodes.normal[1, ia])
    N_radial = float(lam_ccx.sum() * model.symmetry_factor)
    # held along a fixed radial direction, a node that slides u_t along the drum is pushed
    # along a direction u_t / R_d off the drum's normal: a fictitious friction.  Hold it on
    # the exact circle instead, along the normal at its solved position (twice: fixed point)
    t_circle = 0.0
    for it in range(CIRCLE_ITERATIONS):
        P = X[:2, idx[ia]] + U[:2, idx[ia]]
        nf = P / np.hypot(*P)
        val = nodes.drum_radius - (nf[0] * X[0, idx[ia]] + nf[1] * X[1, idx[ia]])
        jc = work / f"contact_circle{it}.inp"
        write_deck(jc, model, X, cells, model.material, [rpm_to_rad_s(v) ** 2 for v in speeds], None,
                   active=(idx[ia], val, nf))
        t_circle += run_ccx(jc)
        U = read_blocks(jc.with_suffix(".dat"), "displacements", n)[-1][1]
        RF = read_blocks(jc.with_suffix(".dat"), "forces", n)[-1][1]
    P = X[:2, idx[ia]] + U[:2, idx[ia]]
    nc = P / np.hypot(*P)
    lam_ccx[ia] = -(RF[0, idx[ia]] * nc[0] + RF[1, idx[ia]] * nc[1])
    tang = float(np.sum(RF[0, idx[ia]] * -nc[1] + RF[1, idx[ia]] * nc[0]) / max(np.sum(lam_ccx), 1e-300))
    g_ccx = nodes.drum_radius - np.hypot(X[0, idx] + U[0, idx], X[1, idx] + U[1, idx])
    sym = model.symmetry_factor
    # the same held set, linear (no NLGEOM: ccx's linear step has no spin softening) against
    # clutchfem's three load models solved exactly (no Ritz basis) with that set
    jl = work / "contact_held_linear.inp"
    write_deck(jl, model, X, cells, model.material, [w8 * w8], None, active=(idx[act], nodes.gap0[act], None))
    jl.write_text(jl.read_text().replace("*STEP, NLGEOM, INC=1000", "*STEP"))
    t_lin = run_ccx(jl)
    RFl = read_blocks(jl.with_suffix(".dat"), "forces", n)[-1][1]
    held = {"ccx NLGEOM, held along the initial radius": N_radial, "ccx linear": float(-(RFl[0, idx[ia]] * nodes.normal[0, ia] + RFl[1, idx[ia]] * nodes.normal[1, ia]).sum()
                                * sym), "ccx NLGEOM, held on the circle": float(lam_ccx.sum() * sym)}
    held.update({f"clutchfem {k}": v * sym for k, v in held_forces(model, nodes, ia, w8).items()})
    rows = []
    for s_ in nodes.shoes:
        sel = nodes.shoe == s_
        ks = np.nonzero(sel)[0]
        tip_k = ks[np.argmax([radial(nodes, u_cf, k) for k in ks])]
        rows.append({"shoe": int(s_), "N_cf_N": float(lam[sel].sum() * sym), "N_ccx_N": float(lam_ccx[sel].sum() * sym),
                     "held_nodes": int((sel & act).sum()), "arc_nodes_deg": arc_deg(nodes.angle[sel & act]),
                     "u_tip_cf_um": 1e6 * radial(nodes, u_cf, tip_k), "u_tip_ccx_um": 1e6 * radial(nodes, U, tip_k),
                     "min_lam_ccx_N": float(lam_ccx[sel & act].min()) if (sel & act).any() else 0.0,
                     "min_open_gap_ccx_um": float(1e6 * g_ccx[sel & ~act].min()),
                     "min_open_lingap_ccx_um": float(1e6 * min(nodes.gap0[k] - radial(nodes, U, k)
                                                               for k in np.nonzero(sel & ~act)[0]))})
    summ = {"N_cf_N": float(r.curve["normal_force_N"].iloc[0]), "N_ccx_N": float(lam_ccx.sum() * sym),
            "arc_cf_tool_deg": float(r.curve["contact_arc_deg"].iloc[0]),
            "arc_cf_tool_error_deg": float(r.curve["contact_arc_error_deg"].iloc[0]),
            "du_field": float(np.abs(u_cf - U).max() / np.abs(U).max()),
            "held_exact_gap_um": float(1e6 * np.abs(g_ccx[act]).max()), "held": held,
            "t_cf_s": t_cf, "t_ccx_s": t_ccx + t_circle, "t_ccx_linear_s": t_lin, "tangential_over_normal": tang}
    return rows, summ


def part_contact_search(d, X, cells, work: Path) -> tuple[list[dict], dict]:
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
    ap.add_argument("--contact-search", action="store_true",
                    help="ccx's own *CONTACT PAIR search against a meshed rigid drum (did not converge here)")
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
        rows, s = part_contact(d, X, cells, work, a.contact_search)
        print(f"\n### Rigid drum, frictionless, {RPM_CONTACT:.0f} rpm: ccx NLGEOM "
              + ("with its own contact search" if a.contact_search else "with clutchfem's contact set held on the "
                 f"drum (on the exact circle: |gap| <= {s['held_exact_gap_um']:.4f} um, tangential / normal force "
                 f"{s['tangential_over_normal']:.1e})")
              + " vs clutchfem 3-D prestress LCP\n")
        print(table(rows))
        print(f"\ntotal N: clutchfem {s['N_cf_N']:.2f} N (x (1 + d_NL): {s['N_cf_N'] * (1 + dnl['N']):.2f} N), ccx "
              f"{s['N_ccx_N']:.2f} N: {s['N_cf_N'] / s['N_ccx_N'] - 1:+.2e} / "
              f"{s['N_cf_N'] * (1 + dnl['N']) / s['N_ccx_N'] - 1:+.2e}; tool's arc {s['arc_cf_tool_deg']:.2f} "
              f"+- {s['arc_cf_tool_error_deg']:.2f} deg; max|du|/max|u| {s['du_field']:.2e}")
        if "held" in s:
            print("\nthe same held set, total N [N]: " + ", ".join(f"{k} {v:.2f}" for k, v in s["held"].items()))
        print(f"times: ccx {s['t_ccx_s']:.1f} s (NLGEOM), {s.get('t_ccx_linear_s', 0.0):.1f} s (linear); clutchfem "
              f"sweep point + LCP {s['t_cf_s']:.1f} s", flush=True)
    print(f"\nwhole run {time.perf_counter() - t_all:.0f} s")


if __name__ == "__main__":
    main()
