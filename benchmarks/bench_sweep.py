"""Speed sweep benchmark: what a designer waits for, and what accuracy it buys.

1. Default sweep of the default concept 4 (0:14000:250 rpm, mu = 0.165, stresses at every
   speed, default mesh, default 'modal' spin softening): wall time after the imports, split
   into setup (assembly, factorisation, modes, contact condensation) and sweep (engagement,
   contact at every speed, fields, stresses).  Meshing (from the cache) is timed separately.
2. The cost of one no-contact static solve of the same mesh, the minimal one (assembly of K
   and the centrifugal load only, constraints, factorisation, one solve: no mass matrix), and
   the ratio full sweep / static solve, in wall time and in CPU time (process time, one BLAS
   thread: less sensitive to other jobs on a shared machine).
3. Mesh-size table: uniform refinement factor f (global size 1.2 mm * f, flexure and fillet
   factors scaled with f), elements, dofs, contact nodes, time, error of engagement rpm and
   torque at 8000 rpm against a reference (finest mesh, spin_softening='exact').
4. Spin softening: 'ritz' (load-dependent Ritz, depth 1..6) / 'off' against 'exact' on the
   default mesh.
5. ``analyze`` (every answer: slip, character, mu +-30 %, coupling, stresses, whirl, fatigue)
   against one full sweep with stresses on the same speeds, both from the mesh in memory (FE
   model built in both): the ratio that says what the answers cost on top of the sweep;
   timed in blocks (each repeated back to back) and interleaved (sweep, analyze, ...).

    .venv/bin/python benchmarks/bench_sweep.py [--concept concept4] [--ref-factor 0.25] [--repeat 3]
        [--parts 1,2,3,4,5]

Times are the minimum over ``--repeat`` runs (the machine is shared; the median is printed
too).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np
from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, LinearForm, asm
from skfem.helpers import ddot, sym_grad, trace

from clutchfem.analysis import analyze, bracket_grid, check_speeds
from clutchfem.clutch import EngineCurve
from clutchfem.core import get_material
from clutchfem.fe import FEModel, constraint_map, factorize
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.loadcase import Design, OperatingPoint
from clutchfem.mesh import mesh_concept
from clutchfem.softening import Ritz

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

RPM = "0:14000:250"
MU = 0.165


def settings(f: float) -> MeshSettings:
    d = MeshSettings()
    return MeshSettings(size=d.size * f, flexure_factor=d.flexure_factor * f,
                        fillet_factor=d.fillet_factor * f)


def run(cm, p, mat, softening="ritz", rpm=RPM, stresses=True, clock=time.perf_counter):
    """(design, result, setup time, sweep time): setup = FE model (assembly, constraints);
    the sweep includes the factorisation, Ritz vectors, condensation, contact and fields."""
    t0 = clock()
    d = Design(cm, OperatingPoint(mu=MU, material=mat), params=p)
    t1 = clock()
    r = d.sweep(rpm, softening=softening, stresses=stresses)
    t2 = clock()
    return d, r, t1 - t0, t2 - t1


def static_solve(cm, p, mat):
    """The minimal no-contact static solve: K and f1, constraints, factorisation, one solve."""
    lam, mu = mat.lame_plane_stress()
    h, rho = p.thickness, mat.rho
    basis = Basis(cm.mesh, ElementVector(ElementTriP2()), intorder=4)

    @BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return h * (2.0 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev))

    @LinearForm
    def centrifugal(v, w):
        return h * rho * (w.x[0] * v[0] + w.x[1] * v[1])

    K = asm(stiffness, basis)
    f = asm(centrifugal, basis)
    T = constraint_map(cm, basis)
    return T @ factorize((T.T @ K @ T).tocsc()).solve(T.T @ f)


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
    ap.add_argument("--parts", default="1,2,3,4,5", help="which parts to run (comma separated)")
    ap.add_argument("--no-tune-malloc", action="store_true",
                    help="leave glibc's allocator as it is (the CLI and the sweep workers tune it)")
    a = ap.parse_args()
    if not a.no_tune_malloc:
        from clutchfem.core import tune_malloc

        print(f"allocator tuned as in the CLI and the sweep workers: {tune_malloc()}")
    try:
        run_parts = {int(x) for x in a.parts.split(",")}
    except ValueError:
        run_parts = set()
    if not run_parts or not run_parts <= {1, 2, 3, 4, 5}:
        ap.error(f"--parts {a.parts!r}: comma-separated part numbers from 1 to 5")
    c = get_concept(a.concept)
    p = c.params()
    mat = get_material("51CrV4")

    t0 = time.perf_counter()
    cm = mesh_concept(c, p, MeshSettings())
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    cm = mesh_concept(c, p, MeshSettings())
    t_cache = time.perf_counter() - t0
    if 1 in run_parts:
        # -- 1. default sweep -----------------------------------------------------------------
        print(f"== 1. default sweep: {c.name}, {RPM} rpm, mu = {MU}, stresses, spin softening 'modal'")
        print(f"mesh: {cm.n_elements} P2 elements; gmsh generation {cm.mesh_time_s:.3f} s (first call "
              f"{first:.3f} s), load from cache {t_cache:.3f} s (excluded below)")
        setups, sweeps, totals, cpu = [], [], [], []
        for _ in range(a.repeat):
            d, r, ts, tw = run(cm, p, mat)
            setups.append(ts)
            sweeps.append(tw)
            totals.append(ts + tw)
            _, _, cs, cw = run(cm, p, mat, clock=time.process_time)
            cpu.append(cs + cw)
        fe, resp = d.model, d.case().response
        print(f"solver back-end {fe.factor.name}, dofs {fe.ndofs}, reduced {fe.Kr.shape[0]}, contact "
              f"nodes {d.nodes.m} (condensed: {resp.compliance.n_condensed}), Ritz vectors {resp.Phi.shape[1]}, "
              f"speeds {len(r.curve)}, engagement {r.engagement_rpm:.1f} rpm, torque(8000) {torque_at(r):.4f} N m")
        print(f"wall time (min / median of {a.repeat}): setup {min(setups):.3f} / "
              f"{statistics.median(setups):.3f} s, sweep {min(sweeps):.3f} / {statistics.median(sweeps):.3f} s, "
              f"total {min(totals):.3f} / {statistics.median(totals):.3f} s; CPU time total {min(cpu):.3f} s")
        tm = r.timings
        tm = {**tm, "condense_s": resp.compliance.seconds}
        parts = ["assemble_s", "constraints_s", "mass_s", "factorize_s", "solve_u1_s", "case_setup_s",
                 "engagement_s", "contact_s", "condense_s", "post_s"]
        print("breakdown (last run): " + ", ".join(f"{k[:-2]} {tm[k] * 1e3:.1f} ms" for k in parts if k in tm)
              + "  (case_setup: mass, factorisation, u1, Ritz vectors; condense is part of contact; "
              "post: fields and stresses)")

    if 2 in run_parts:
        # -- 2. one static solve ----------------------------------------------------------------
        st, st_cpu, st_fe = [], [], []
        for _ in range(a.repeat):
            t0, c0 = time.perf_counter(), time.process_time()
            static_solve(cm, p, mat)
            st.append(time.perf_counter() - t0)
            st_cpu.append(time.process_time() - c0)
            t0 = time.perf_counter()
            fe = FEModel(cm, mat)
            fe.solve(fe.f1)
            st_fe.append(time.perf_counter() - t0)
        print(f"\n== 2. one no-contact static solve (K and f1 assembly, constraints, factorisation, solve): "
              f"wall {min(st):.3f} s, CPU {min(st_cpu):.3f} s  (clutchfem's FEModel + u1: {min(st_fe):.3f} s)")
        print(f"full sweep / static solve: wall {min(totals) / min(st):.2f}, CPU {min(cpu) / min(st_cpu):.2f}")

    if 3 in run_parts:
        # -- 3. mesh table ----------------------------------------------------------------------
        print(f"\n== 3. mesh size vs time vs error (reference: f = {a.ref_factor}, spin_softening='exact')")
        cm_ref = mesh_concept(c, p, settings(a.ref_factor))
        t0 = time.perf_counter()
        dref, ref, ts, tw = run(cm_ref, p, mat, softening="exact", rpm=[8000.0], stresses=False)
        t_ref = time.perf_counter() - t0
        e_ref, T_ref = ref.engagement_rpm, torque_at(ref)
        print(f"reference: {cm_ref.n_elements} elements, {dref.model.ndofs} dofs, {dref.nodes.m} "
              f"contact nodes, engagement {e_ref:.3f} rpm, torque(8000) {T_ref:.5f} N m ({t_ref:.1f} s)")
        rows = []
        factors = [float(x) for x in a.factors.split(",")] + [a.ref_factor]
        for f in factors:
            t0 = time.perf_counter()
            cmf = mesh_concept(c, p, settings(f))
            t_mesh = time.perf_counter() - t0
            best = None
            for _ in range(1 if f < 0.5 else a.repeat):
                df, rf, ts, tw = run(cmf, p, mat)
                best = (ts, tw) if best is None or ts + tw < sum(best) else best
            rows.append((f, cmf.mesh_settings["size"] * 1e3, cmf.n_elements, df.model.ndofs, df.nodes.m,
                         t_mesh, best[0], best[1], best[0] + best[1],
                         rf.engagement_rpm - e_ref, 100 * (rf.engagement_rpm / e_ref - 1),
                         100 * (torque_at(rf) / T_ref - 1)))
        table(["f", "size mm", "elements", "dofs", "m", "mesh s", "setup s", "sweep s", "total s",
               "d_eng rpm", "d_eng %", "d_T8000 %"], rows,
              ["{:g}", "{:.2f}", "{:d}", "{:d}", "{:d}", "{:.2f}", "{:.3f}", "{:.3f}", "{:.3f}", "{:+.2f}",
               "{:+.3f}", "{:+.3f}"])
        print("(d_* against the reference; the last row is the reference mesh with 'modal' softening; "
              "'mesh s' includes gmsh generation on a cold cache)")

    if 4 in run_parts:
        # -- 4. spin softening --------------------------------------------------------------------
        print("\n== 4. spin softening on the default mesh (errors against 'exact')")
        res = {}
        variants = [("exact", "exact"), ("off", "off")] + [(f"ritz depth {d}", Ritz(depth=d)) for d in (1, 2, 3, 4, 6)]
        from clutchfem.core import SolverError

        refused = {}
        for name, soft in variants:
            t0 = time.perf_counter()
            try:
                dk, rk, _, _ = run(cm, p, mat, softening=soft)
            except SolverError as exc:  # the sweep's own residual check refuses a too coarse space
                refused[name] = str(exc)
                continue
            res[name] = (rk, time.perf_counter() - t0, dk.case(softening=soft).response)
        ex = res["exact"][0]
        cx = ex.curve.set_index("rpm")
        hi = cx.index >= 6000
        rows = []
        for name in refused:
            print(f"{name}: refused by the sweep's residual check ({refused[name][:80]}...)")
        for name, _ in variants:
            if name not in res:
                continue
            rk, tk, resp = res[name]
            c_ = rk.curve.set_index("rpm")
            dN = (c_.loc[hi, "normal_force_N"] / cx.loc[hi, "normal_force_N"] - 1).abs().max()
            rows.append((name, getattr(resp, "Phi", np.zeros((0, 0))).shape[1], tk, rk.engagement_rpm,
                         100 * (rk.engagement_rpm / ex.engagement_rpm - 1),
                         100 * (torque_at(rk) / torque_at(ex) - 1), 100 * dN, float(rk.curve["residual"].max())))
        table(["softening", "vectors", "time s", "engagement rpm", "d_eng %", "d_T8000 %", "max|dN| >= 6000 rpm %",
               "max residual"],
              rows, ["{}", "{:d}", "{:.3f}", "{:.2f}", "{:+.2e}", "{:+.2e}", "{:.2e}", "{:.1e}"])
        print("(default: depth 3)")

    if 5 in run_parts:
        # -- 5. analyze vs one full sweep ---------------------------------------------------------
        engine = EngineCurve.default()
        speeds = check_speeds(None, engine)

        def design():
            return Design(cm, OperatingPoint(mu=MU, material=mat), params=p)

        def t_sweep():
            t0 = time.perf_counter()
            design().sweep(speeds, stresses=True)
            return time.perf_counter() - t0

        def t_analyze(errors=False):
            t0 = time.perf_counter()
            out = analyze(design(), engine=engine, errors=errors)
            return time.perf_counter() - t0, out

        # (a) in blocks (timeit-style: each operation repeated back to back), (b) interleaved
        # sweep / analyze: the operation before changes the allocator's and the caches' state
        # (large temporaries), which moves an analysis by ~5 %
        blk_sw = [t_sweep() for _ in range(a.repeat)]
        blk_an = [t_analyze()[0] for _ in range(a.repeat)]
        int_sw, int_an = [], []
        for _ in range(a.repeat):
            int_sw.append(t_sweep())
            int_an.append(t_analyze()[0])
        t_err, an = zip(*[t_analyze(errors=True) for _ in range(max(1, a.repeat // 2))])
        an = an[-1]
        print(f"\n== 5. analyze vs one full sweep with stresses ({len(speeds)} speeds, default softening "
              f"'{OperatingPoint().softening}', FE model built in both; slip crossings bracketed on "
              f"{len(bracket_grid(engine))} speeds; min of {a.repeat})")
        for label, sw, ana in (("in blocks", blk_sw, blk_an), ("interleaved", int_sw, int_an)):
            print(f"{label:11s}: full sweep {min(sw):.3f} s, analyze without the error estimate {min(ana):.3f} s: "
                  f"ratio {min(ana) / min(sw):.2f}, analyze - sweep = {1e3 * (min(ana) - min(sw)):.0f} ms "
                  f"(medians {statistics.median(sw):.3f} / {statistics.median(ana):.3f} s)")
        print(f"analyze with the error estimate (a mesh twice as fine) {min(t_err):.3f} s (ratio "
              f"{min(t_err) / min(blk_sw):.2f} to the sweep in blocks); slip {an.slip_rpm:.1f} rpm, torque(8000) "
              f"{an.torque_at_max_engine_torque_Nm:.4f} N m")

if __name__ == "__main__":
    main()
