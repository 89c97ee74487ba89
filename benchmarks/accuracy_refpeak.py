"""The converged peak-stress reference of ``bench_accuracy.py --part refpeak`` (issue 20): the
raw P2 vertex von Mises peak of the thick plane model at one speed, refined locally at the
peak until Richardson's estimate is within 1 % (:func:`clutchfem.fe.peak_stress_converged`).

The model is the reference's plane model: thick, through-thickness order 6 (``order``), the
held steel ring drum of wall ``wall`` (2 mm, ASSUMED as the reference), pre-stress softening,
stresses in the small-strain measure (``bench_accuracy.lite``'s vM and the denominator of
its d_NL; the best path's finite-rotation measure reads ~2.3 % more at 14 000 rpm).  A helper
module of ``bench_accuracy.py`` and ``bench_refpeak_orders.py``, not a script.
"""

import math
import os
import time

import numpy as np

import clutchfem as cf
from clutchfem.core import EquilibriumError
from clutchfem.fe import peak_stress_converged, von_mises
from clutchfem.geometry import MeshSettings, get_concept

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


def peak_at_rpm(concept, vals, rpm, wall, softening="prestress", order=6):
    """``evaluate(cm) -> (peak [Pa], (x, y) [m])``: the raw P2 vertex von Mises peak at ``rpm``
    on the mesh ``cm`` of ``concept`` with the parameter values ``vals`` (module docstring)."""
    c = get_concept(concept)
    p = c.params().replace(**vals) if vals else c.params()
    op = cf.OperatingPoint(formulation="thick", thick_order=order, drum_wall=wall, softening=softening)

    def evaluate(cm):
        d = cf.Design(cm, op, params=p, name=c.name, concept=c)
        u = d.sweep([float(rpm)]).fields.displacement(0)
        vm = von_mises(d.model.stress(u))
        i = int(np.argmax(vm))
        return float(vm[i]), tuple(float(x) for x in d.model.stress.points[:2, i])
    return evaluate


def converged_peak(concept, vals, rpm, wall, tol=0.01) -> dict:
    """The converged peak of :func:`peak_at_rpm` from the best preset: {"vM_conv" [Pa], "error"
    its estimate [Pa], "order", "converged", "feature", "at" [m], "levels" [[peak, elements]],
    "time_s", "softening"}.  Where the pre-stress Ritz space misses equilibrium on a level, the
    whole sequence again with its per-speed reference ``prestress-exact`` (``analyze``'s own
    fallback; "prestress_failed" says why)."""
    t0, c, out = time.perf_counter(), get_concept(concept), {}
    p = c.params().replace(**vals) if vals else c.params()
    for soft in ("prestress", "prestress-exact"):
        try:
            r = peak_stress_converged(c, p, ms=MeshSettings.preset("best"),
                                      evaluate=peak_at_rpm(concept, vals, rpm, wall, soft), tol=tol)
            break
        except EquilibriumError as exc:
            if soft != "prestress":
                raise
            out["prestress_failed"] = str(exc)
    return {"vM_conv": r.peak, "error": r.error, "order": None if math.isnan(r.order) else r.order,
            "converged": r.converged, "feature": r.feature, "at": list(r.at),
            "levels": [[lv.peak, lv.elements] for lv in r.levels], "time_s": time.perf_counter() - t0,
            "softening": soft, **out}
