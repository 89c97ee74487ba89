"""The 3-D path's own discretisation error (issue 20; BENCHMARKS.md section 13, "3-D path"):
concept 4 at its defaults on the best-estimate operating point with ``formulation="3d"``
(P2 tetrahedra through half the thickness, 2 mm elastic ring drum, pre-stress softening),
the four main answers of ``analyze`` (engagement, slip, torque at the rpm of maximum engine
torque, peak von Mises at the engine's maximum speed) and the wall time of
``analyze(errors=False)`` for

* ``--layers`` 1, 2, 3 on the in-plane levels of ``--levels`` (``coarse``: the best preset
  1.5 times as coarse (its global size may not pass 10 mm), ``best``: the preset, ``fine``: twice as fine, as
  :func:`clutchfem.accuracy.refined_design` refines): the layers term's Richardson order and
  its estimate against the change measured;
* the thick plane model (order 4, ``fidelity="best"``) on the same levels: its relative
  in-plane change against the 3-D model's on the same meshes (the in-plane term of
  :func:`clutchfem.accuracy.discretisation_3d` is the thick model's);
* ``--errors``: the wall time of ``analyze(errors=True)`` at 2 layers on ``best`` (the
  3-D error step's cost) and the band it reports.

One JSON line per run in ``benchmarks/results_3d_error.jsonl``; ``--table`` prints the
Markdown of BENCHMARKS.md from it.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_3d_error.py --levels coarse,best --layers 1,2,3
    PYTHONPATH=src .venv/bin/python benchmarks/bench_3d_error.py --errors
    PYTHONPATH=src .venv/bin/python benchmarks/bench_3d_error.py --table
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import resource
import time
from pathlib import Path

import clutchfem as cf

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

RESULTS = Path(__file__).with_name("results_3d_error.jsonl")
ANSWERS = ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_Pa")
SCALE = {"coarse": 1.5, "best": 1.0, "fine": 0.5}  # coarse: the global size is at most 10 mm


def level(name: str) -> cf.MeshSettings:
    ms = cf.MeshSettings.preset("best")
    f = SCALE[name]
    return ms.replace(size=ms.size * f, flexure_factor=ms.flexure_factor * f, fillet_factor=ms.fillet_factor * f)


def run(form: str, lvl: str, layers: int | None, errors: bool = False) -> dict:
    kw = {"formulation": "3d", "layers": layers} if form == "3d" else {}
    t0 = time.perf_counter()
    d = cf.Design.from_concept("concept4", fidelity="best", mesh=level(lvl), **kw)
    a = cf.analyze(d, errors=errors)
    row = {"form": form, "level": lvl, "layers": layers, "errors": errors, "time_s": time.perf_counter() - t0,
           "elements_2d": int(d.cm.n_elements), "dofs": int(d.model.ndofs),
           "peak_rss_GB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6,
           "when": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes"),
           "machine": platform.node() + " " + platform.processor()}
    for q in ANSWERS:
        row[q] = getattr(a, q)
    if errors:
        row["errors"] = {q: {k: a.errors[q].get(k) for k in ("discretisation", "discretisation_layers",
                                                             "discretisation_in_plane", "model_form", "total")}
                         for q in ANSWERS}
    with RESULTS.open("a") as f:
        f.write(json.dumps(row) + "\n")
    print(json.dumps(row), flush=True)
    return row


def table() -> None:
    rows = [json.loads(x) for x in RESULTS.read_text().splitlines() if x.strip()]
    plain = {(r["form"], r["level"], r["layers"]): r for r in rows if not r["errors"]}
    units = {"engagement_rpm": ("engagement [rpm]", 1, ".1f"), "slip_rpm": ("slip [rpm]", 1, ".1f"),
             "torque_at_max_engine_torque_Nm": ("torque [N m]", 1, ".4f"),
             "max_von_mises_Pa": ("peak vM [MPa]", 1e-6, ".1f")}
    print("| model | in-plane level (2-D elements) | layers | unknowns | " +
          " | ".join(u[0] for u in units.values()) + " | analyze [s] |")
    print("|---|---|---:|---:|" + "---:|" * len(units) + "---:|")
    for (form, lvl, lay), r in sorted(plain.items(), key=lambda kv: (kv[0][0], -SCALE[kv[0][1]], kv[0][2] or 0)):
        vals = " | ".join(f"{r[q] * s:{f}}" for q, (_, s, f) in units.items())
        print(f"| {form} | {lvl} ({r['elements_2d']}) | {lay or '-'} | {r['dofs']} | {vals} | {r['time_s']:.1f} |")
    print()
    # layers: observed order and the estimate of the error of n layers from n + 1 (p = 1)
    for lvl in SCALE:
        a = [plain.get(("3d", lvl, n)) for n in (1, 2, 3)]
        if all(a):
            print(f"layers on {lvl}: " + "; ".join(
                f"{q}: change 1->2 {a[1][q] - a[0][q]:+.4g}, 2->3 {a[2][q] - a[1][q]:+.4g}, estimate of n=2 "
                f"(3 x |a2 - a3|) {3 * abs(a[1][q] - a[2][q]):.3g}" for q in units))
    # in plane: the 3-D change between two levels against the thick model's (relative)
    levels = [lv for lv in SCALE if ("thick", lv, None) in plain]
    for lo, hi in zip(levels, levels[1:]):
        for lay in (1, 2, 3):
            if ("3d", lo, lay) in plain and ("3d", hi, lay) in plain:
                r0, r1, t0, t1 = plain[("3d", lo, lay)], plain[("3d", hi, lay)], plain[("thick", lo, None)], \
                    plain[("thick", hi, None)]
                print(f"in plane {lo}->{hi}, 3-D {lay} layers vs thick (relative change, %): " + "; ".join(
                    f"{q} {100 * (r1[q] / r0[q] - 1):+.3f} / {100 * (t1[q] / t0[q] - 1):+.3f}" for q in units))
    for r in rows:
        if r["errors"]:
            print(f"analyze(errors=True) {r['form']} {r['level']} {r['layers']} layers: {r['time_s']:.1f} s; "
                  + "; ".join(f"{q}: disc {e['discretisation']:.4g} (layers {e['discretisation_layers']}, in plane "
                              f"{e['discretisation_in_plane']}), total {e['total']:.4g}" for q, e in r["errors"].items()))


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", default="coarse,best")
    ap.add_argument("--layers", default="1,2,3")
    ap.add_argument("--errors", action="store_true")
    ap.add_argument("--table", action="store_true")
    ap.add_argument("--no-thick", action="store_true")
    o = ap.parse_args()
    if o.table:
        table()
    elif o.errors:
        run("3d", "best", 2, errors=True)
    else:
        for lv in o.levels.split(","):
            if not o.no_thick:
                run("thick", lv, None)
            for n in (int(x) for x in o.layers.split(",")):
                run("3d", lv, n)
