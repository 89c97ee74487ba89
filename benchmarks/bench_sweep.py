"""Speed sweep benchmark: what a designer waits for, and what accuracy it buys.

1. Default sweep of the default concept 4 (0:14000:250 rpm, mu = 0.165, stresses at every
   speed, default mesh, default 'modal' spin softening): wall time after the imports, split
   into setup (assembly, factorisation, modes, contact condensation) and sweep (engagement,
   contact at every speed, fields, stresses).  Meshing (from the cache) is timed separately.
2. The cost of one no-contact static solve of the same mesh (assembly + factorisation + one
   solve) and the ratio full sweep / static solve.
3. Mesh-size table: uniform refinement factor f (global size 1.2 mm * f, flexure and fillet
   factors scaled with f), elements, dofs, contact nodes, time, error of engagement rpm and
   torque at 8000 rpm against a reference (finest mesh, spin_softening='exact').
4. Spin softening: 'modal' / 'off' against 'exact' on the default mesh.

    .venv/bin/python benchmarks/bench_sweep.py [--concept concept4] [--ref-factor 0.25] [--repeat 3]

Times are the minimum over ``--repeat`` runs (the machine is shared; the median is printed
too).
"""

from __future__ import annotations

import argparse
import statistics
import time

from clutchfem.fem import build_fe_model
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.materials import get_material
from clutchfem.mesh import mesh_concept
from clutchfem.solver import ClutchSolver

RPM = "0:14000:250"
MU = 0.165


def settings(f: float) -> MeshSettings:
    d = MeshSettings()
    return MeshSettings(size=d.size * f, flexure_factor=d.flexure_factor * f,
                        fillet_factor=d.fillet_factor * f)


def run(cm, p, mat, softening="modal", rpm=RPM, stresses=True):
    t0 = time.perf_counter()
    s = ClutchSolver(cm, mat, drum_radius=p.drum_radius, mu=MU, spin_softening=softening)
    t1 = time.perf_counter()
    r = s.sweep(rpm, stresses=stresses)
    t2 = time.perf_counter()
    return r, t1 - t0, t2 - t1


def torque_at(r, rpm=8000.0):
    c = r.curve.set_index("rpm")
    return float(c.loc[rpm, "torque_Nm"])


def table(headers, rows, fmts):
    w = [max(len(h), *(len(f.format(r[i])) for r in rows)) for i, (h, f) in enumerate(zip(headers, fmts))]
    print("  ".join(h.rjust(n) for h, n in zip(headers, w)))
    for r in rows:
        print("  ".join(f.format(v).rjust(n) for v, f, n in zip(r, fmts, w)))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--concept", default="concept4")
    ap.add_argument("--ref-factor", type=float, default=0.25)
    ap.add_argument("--factors", default="4,2,1,0.5")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    c = get_concept(a.concept)
    p = c.params()
    mat = get_material("51CrV4")

    # -- 1. default sweep -----------------------------------------------------------------
    t0 = time.perf_counter()
    cm = mesh_concept(c, p, MeshSettings())
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    cm = mesh_concept(c, p, MeshSettings())
    t_cache = time.perf_counter() - t0
    print(f"== 1. default sweep: {c.name}, {RPM} rpm, mu = {MU}, stresses, spin softening 'modal'")
    print(f"mesh: {cm.n_elements} P2 elements; gmsh generation {cm.mesh_time_s:.3f} s (first call "
          f"{first:.3f} s), load from cache {t_cache:.3f} s (excluded below)")
    setups, sweeps, totals = [], [], []
    for _ in range(a.repeat):
        r, ts, tw = run(cm, p, mat)
        setups.append(ts)
        sweeps.append(tw)
        totals.append(ts + tw)
    s = r.solver
    print(f"dofs {s.fe.ndofs}, reduced {s.fe.Kr.shape[0]}, contact nodes {s.nodes.m}, speeds "
          f"{len(r.curve)}, engagement {r.engagement_rpm:.1f} rpm, torque(8000) {torque_at(r):.4f} N m")
    print(f"wall time (min / median of {a.repeat}): setup {min(setups):.3f} / "
          f"{statistics.median(setups):.3f} s, sweep {min(sweeps):.3f} / {statistics.median(sweeps):.3f} s, "
          f"total {min(totals):.3f} / {statistics.median(totals):.3f} s")
    tm = r.timings
    parts = ["assemble_s", "constraints_s", "factorize_s", "solve_u1_s", "modes_s", "condense_s",
             "engagement_s", "contact_s", "fields_s", "post_s"]
    print("breakdown (last run): " + ", ".join(f"{k[:-2]} {tm[k] * 1e3:.1f} ms" for k in parts if k in tm))

    # -- 2. one static solve ----------------------------------------------------------------
    st = []
    for _ in range(a.repeat):
        t0 = time.perf_counter()
        fe = build_fe_model(cm, mat)
        fe.solve(fe.f1)
        st.append(time.perf_counter() - t0)
    print(f"\n== 2. one no-contact static solve (assembly + factorisation + solve): "
          f"{min(st):.3f} s; full sweep / static = {min(totals) / min(st):.1f}")

    # -- 3. mesh table ----------------------------------------------------------------------
    print(f"\n== 3. mesh size vs time vs error (reference: f = {a.ref_factor}, spin_softening='exact')")
    cm_ref = mesh_concept(c, p, settings(a.ref_factor))
    t0 = time.perf_counter()
    ref, ts, tw = run(cm_ref, p, mat, softening="exact", rpm=[8000.0], stresses=False)
    t_ref = time.perf_counter() - t0
    e_ref, T_ref = ref.engagement_rpm, torque_at(ref)
    print(f"reference: {cm_ref.n_elements} elements, {ref.solver.fe.ndofs} dofs, {ref.solver.nodes.m} "
          f"contact nodes, engagement {e_ref:.3f} rpm, torque(8000) {T_ref:.5f} N m ({t_ref:.1f} s)")
    rows = []
    factors = [float(x) for x in a.factors.split(",")] + [a.ref_factor]
    for f in factors:
        t0 = time.perf_counter()
        cmf = mesh_concept(c, p, settings(f))
        t_mesh = time.perf_counter() - t0
        best = None
        for _ in range(1 if f < 0.5 else a.repeat):
            rf, ts, tw = run(cmf, p, mat)
            best = (ts, tw) if best is None or ts + tw < sum(best) else best
        rows.append((f, cmf.mesh_settings["size"] * 1e3, cmf.n_elements, rf.solver.fe.ndofs, rf.solver.nodes.m,
                     t_mesh, best[0], best[1], best[0] + best[1],
                     rf.engagement_rpm - e_ref, 100 * (rf.engagement_rpm / e_ref - 1),
                     100 * (torque_at(rf) / T_ref - 1)))
    table(["f", "size mm", "elements", "dofs", "m", "mesh s", "setup s", "sweep s", "total s",
           "d_eng rpm", "d_eng %", "d_T8000 %"], rows,
          ["{:g}", "{:.2f}", "{:d}", "{:d}", "{:d}", "{:.2f}", "{:.3f}", "{:.3f}", "{:.3f}", "{:+.2f}",
           "{:+.3f}", "{:+.3f}"])
    print("(d_* against the reference; the last row is the reference mesh with 'modal' softening; "
          "'mesh s' includes gmsh generation on a cold cache)")

    # -- 4. spin softening --------------------------------------------------------------------
    print("\n== 4. spin softening on the default mesh (errors against 'exact')")
    res = {}
    for k in ("exact", "modal", "off"):
        t0 = time.perf_counter()
        rk, _, _ = run(cm, p, mat, softening=k)
        res[k] = (rk, time.perf_counter() - t0)
    ex = res["exact"][0]
    rows = []
    for k in ("exact", "modal", "off"):
        rk, tk = res[k]
        c_ = rk.curve.set_index("rpm")
        cx = ex.curve.set_index("rpm")
        hi = c_.index >= 6000
        dN = (c_.loc[hi, "normal_force_N"] / cx.loc[hi, "normal_force_N"] - 1).abs().max()
        rows.append((k, tk, rk.engagement_rpm, 100 * (rk.engagement_rpm / ex.engagement_rpm - 1),
                     100 * (torque_at(rk) / torque_at(ex) - 1), 100 * dN))
    table(["softening", "time s", "engagement rpm", "d_eng %", "d_T8000 %", "max|dN| >= 6000 rpm %"], rows,
          ["{}", "{:.3f}", "{:.2f}", "{:+.2e}", "{:+.2e}", "{:.2e}"])


if __name__ == "__main__":
    main()
