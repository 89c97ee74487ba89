"""Sparse direct solvers on the concept-4 stiffness: factorisation and the multi-RHS solve
that condenses the contact problem (G = B K^-1 D, one column per contact node).

* back-ends: scipy SuperLU as used by clutchfem.linsolve (MMD on A + A', symmetric mode),
  SuperLU with COLAMD, and CHOLMOD (scikit-sparse) when ``import sksparse.cholmod`` works,
  supernodal (CHOLMOD's own choice for these matrices) and simplicial (clutchfem's choice
  up to linsolve.SIMPLICIAL_MAX_N unknowns);
* right-hand sides: all m columns at once, blocks of 16 / 64, one at a time;
* BLAS threads x machine load: every configuration runs in a fresh process with
  OPENBLAS_NUM_THREADS unset (library default = all cores) or 1, on an otherwise idle
  machine or next to one busy-looping process (what a second pytest worker or a second job
  does on a 2-core machine).

    .venv/bin/python benchmarks/bench_solvers.py [--factors 1,0.5,0.25] [--repeat 3]

Times are the minimum over ``--repeat`` runs; for the all-columns solve the maximum is shown
too, because the BLAS-thread contention it suffers from is intermittent.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


def build(f: float):
    import numpy as np
    import scipy.sparse as sp

    from clutchfem.contact import contact_nodes
    from clutchfem.core import get_material
    from clutchfem.fe import FEModel
    from clutchfem.geometry import MeshSettings, get_concept
    from clutchfem.mesh import mesh_concept

    c = get_concept("concept4")
    p = c.params()
    d = MeshSettings()
    ms = MeshSettings(size=d.size * f, flexure_factor=d.flexure_factor * f, fillet_factor=d.fillet_factor * f)
    cm = mesh_concept(c, p, ms)
    fe = FEModel(cm, get_material("51CrV4"))
    nd = contact_nodes(fe, p.drum_radius)
    m = nd.m
    D = sp.csc_matrix((np.concatenate([-nd.normal[0], -nd.normal[1]]),
                       (np.concatenate([nd.dof_x, nd.dof_y]), np.concatenate([np.arange(m)] * 2))),
                      shape=(fe.ndofs, m))
    R = np.asfortranarray((fe.T.T @ D).toarray())
    return cm, fe.Kr.tocsc(), R


def timeit(fn, repeat, worst=None):
    """Minimum time over ``repeat`` runs (the maximum is appended to ``worst`` if given)."""
    ts = []
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    if worst is not None:
        worst.append(max(ts))
    return min(ts), out


def worker(f: float, repeat: int, backends: list[str]) -> dict:
    import numpy as np
    import scipy.sparse.linalg as spla

    cm, A, R = build(f)
    res = {"f": f, "elements": cm.n_elements, "n": A.shape[0], "nnz": int(A.nnz), "m": R.shape[1], "rows": []}
    facs = {}
    if "superlu" in backends:
        facs["SuperLU MMD(A+A') sym"] = lambda: spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                                                          options={"SymmetricMode": True})
        facs["SuperLU COLAMD"] = lambda: spla.splu(A, permc_spec="COLAMD")
    if "cholmod" in backends:
        from sksparse.cholmod import cholesky

        facs["CHOLMOD supernodal (its own choice here)"] = lambda: cholesky(A)
        facs["CHOLMOD simplicial (clutchfem, n <= 100k)"] = lambda: cholesky(A, mode="simplicial")
    for name, make in facs.items():
        tf, F = timeit(make, repeat)
        solve = F.solve if hasattr(F, "solve") else F
        fill = int(F.L.nnz + F.U.nnz) if hasattr(F, "U") else int(F.L().nnz)
        row = {"backend": name, "factor_s": tf, "fill": fill}
        m = R.shape[1]
        w = []
        row["all_s"], X = timeit(lambda: solve(R), repeat, w)
        row["all_max_s"] = w[0]
        for blk in (16, 64):
            row[f"blk{blk}_s"], _ = timeit(lambda: np.hstack([solve(R[:, j:j + blk]) for j in range(0, m, blk)]),
                                           repeat)
        row["one_s"], _ = timeit(lambda: np.column_stack([solve(R[:, j]) for j in range(m)]), max(1, repeat - 1))
        row["resid"] = float(np.abs(A @ X - R).max() / np.abs(R).max())
        res["rows"].append(row)
    return res


def run_config(f, repeat, backends, threads, load):
    env = dict(os.environ)
    env.pop("OPENBLAS_NUM_THREADS", None)
    if threads:
        env["OPENBLAS_NUM_THREADS"] = str(threads)
    burner = None
    if load:
        burner = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    try:
        out = subprocess.run([sys.executable, __file__, "--worker", str(f), "--repeat", str(repeat),
                              "--backends", ",".join(backends)], env=env, capture_output=True, text=True,
                             check=True)
    finally:
        if burner is not None:
            burner.kill()
            burner.wait()
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--factors", default="1,0.5,0.25")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--worker", type=float, default=None)
    ap.add_argument("--backends", default=None)
    a = ap.parse_args()
    if a.worker is not None:
        print(json.dumps(worker(a.worker, a.repeat, a.backends.split(","))))
        return
    backends = ["superlu"]
    try:
        import sksparse.cholmod  # noqa: F401
        backends.append("cholmod")
        print("CHOLMOD: available")
    except Exception as exc:  # ImportError or a broken shared library
        print(f"CHOLMOD: unavailable ({type(exc).__name__}: {exc})")
    print(f"load average at start: {os.getloadavg()}")
    hdr = (f"{'elements':>8} {'n':>7} {'m':>4} {'threads':>7} {'load':>4}  {'backend':<22} {'factor s':>8} "
           f"{'fill':>9} {'all m s':>8} {'(max)':>7} {'blk16 s':>8} {'blk64 s':>8} {'one-by-one s':>12} {'resid':>8}")
    print(hdr)
    for f in [float(x) for x in a.factors.split(",")]:
        configs = [(None, False), (1, False), (None, True), (1, True)] if f >= 0.5 else [(None, False), (1, False)]
        for threads, load in configs:
            r = run_config(f, a.repeat, backends, threads, load)
            for row in r["rows"]:
                print(f"{r['elements']:>8} {r['n']:>7} {r['m']:>4} {threads or 'all':>7} {('busy' if load else 'idle'):>4}  "
                      f"{row['backend']:<22} {row['factor_s']:>8.3f} {row['fill']:>9} {row['all_s']:>8.3f} {row['all_max_s']:>7.2f} "
                      f"{row['blk16_s']:>8.3f} {row['blk64_s']:>8.3f} {row['one_s']:>12.3f} {row['resid']:>8.1e}",
                      flush=True)
    print(f"load average at end: {os.getloadavg()}")


if __name__ == "__main__":
    main()
