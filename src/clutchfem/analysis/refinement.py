"""Accuracy targets: one more mesh level for a main answer whose discretisation puts its
error band over the target (the error step, :func:`~.error_band.error_step`).

The error step reports each main answer with a band = discretisation + model form, the
discretisation being Richardson's estimate 2 |a_h - a_h/2| (p = 1) from the design mesh h and
the error step's finer mesh h/2 (:func:`~clutchfem.accuracy.refined_design`).  Where an
answer's band exceeds its target (:data:`ACCURACY_TARGET`, relative) *and* its model-form
terms alone fit in it (so the mesh is what puts it over), the design is meshed once more,
h/4 = ``refined_design`` of the h/2 design (shared by every answer that needs it; only the
answers that need it are computed there), and the answer is reported from that finest level
with discretisation 2 |a_h/2 - a_h/4| (the same rule, p = 1; 2 max(|a_h - a_h/2|, |a_h/2 -
a_h/4|) where the three levels do not converge monotonically).  Never more than that one
extra level, so the extra cost is bounded by one load case on a mesh ~4.5x the design's
elements (measured 3.2-4.5 s on six designs of concepts 1 and 4, ~50 k unknowns; h/8 would
take 25-50 s: ``benchmarks/bench_torque_levels.py``, BENCHMARKS.md section 13, stop 32); if
the target is still not met, the band is reported as it is, with a note saying so.  An answer within its target costs nothing and is
not touched (bit-identical).

Why p = 1 on the finer pair too: the orders observed over h, h/2, h/4 scatter (engagement
1.2-3.1, torque at 8000 rpm 0.8-2.8 on six designs; slip and torque also move by 0.01-0.04 %
per level with either sign, the contact discretisation's noise floor, 15-50x below where
this rule acts) and the reference's own in-plane refinement moves the torque as slowly, so
no higher order is assumed.  Measured on concept1-lhs10 (engages at 7501 rpm, so its torque at 8000 rpm carries
the engagement's mesh error amplified ~14x by w^2 - w0^2): torque 0.53636 / 0.53821 /
0.53891 N m on h / h/2 / h/4 (p = 1.4, monotone), band 1.01 % -> 0.58 % with the finest
level -0.36 % from the reference.

The peak stress is not refined here: it is extrapolated on its own disc
(:func:`~.error_band.corrected_peak`).  3-D designs (their in-plane term comes from the thick
twin) and user meshes (one level) are not refined either.
"""

from __future__ import annotations

import math
import time

from ..accuracy import refined_design
from ..clutch import EngineCurve
from ..core import ClutchfemError
from .torque import GRID_RPM_SENSITIVITY, FETorque, slip_step

#: the relative accuracy target of each main answer: the limits of issue 20 (engagement and
#: slip 0.5 %, torque at the rpm of maximum engine torque 1 %, peak von Mises 3 %), which are
#: what a designer sizes against (an engagement limit a x idle, a slip limit b x the rpm of
#: maximum engine torque, the torque margin, the safety factor).  The peak's is stated for
#: completeness: it is not refined by this rule (module docstring)
ACCURACY_TARGET = {"engagement_rpm": 0.005, "slip_rpm": 0.005, "torque_at_max_engine_torque_Nm": 0.01,
                   "max_von_mises_Pa": 0.03}
#: the answers the rule may refine once more
REFINABLE = ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm")


def needs_refinement(q: str, value: float | None, disc: float | None, model_form_abs: float,
                     targets: dict | None = None) -> bool:
    """Whether answer ``q`` (``value``, its discretisation ``disc`` and model form
    ``model_form_abs``, absolute) exceeds its target only because of its discretisation:
    band > target |value| >= model form."""
    t = (ACCURACY_TARGET if targets is None else targets).get(q)
    if q not in REFINABLE or t is None or value is None or disc is None or not math.isfinite(value) or value == 0:
        return False
    lim = t * abs(value)
    return disc + model_form_abs > lim >= model_form_abs


def level_answer(case, engine: EngineCurve, q: str) -> float | None:
    """Answer ``q`` (engagement, slip or torque at the rpm of maximum engine torque) of a
    mesh level's load case ``case``, as the error step computes it on every level: the
    engagement in closed form, the slip crossings bracketed every
    :data:`~.torque.GRID_RPM_SENSITIVITY` rpm and refined, the exact FE torque."""
    if q == "engagement_rpm":
        return case.engagement_rpm
    if q == "slip_rpm":
        return slip_step(case, engine, GRID_RPM_SENSITIVITY).rpm
    return float(FETorque(case)(float(engine.rpm_max_torque))[0])


class FinerLevel:
    """The h/4 level of a design, built on first use from the error step's h/2 design
    ``fine`` and computed lazily per answer (engagement, slip, torque at the rpm of maximum
    engine torque of ``engine``), each as the error step computes them on h/2.  ``error``:
    why the level has no answers (a refusal while meshing or solving it), else None."""

    def __init__(self, fine, engine: EngineCurve):
        self.fine, self.engine = fine, engine
        self.design = None
        self.values: dict = {}
        self.error: str | None = None
        self.time_s = 0.0
        self._case = None

    def get(self, q: str) -> float | None:
        if q in self.values or self.error is not None:
            return self.values.get(q)
        t0 = time.perf_counter()
        try:
            if self._case is None:
                self.design = refined_design(self.fine)
                self._case = self.design.case()
            self.values[q] = level_answer(self._case, self.engine, q)
        except ClutchfemError as exc:
            self.error = f"{type(exc).__name__}: {exc}"
        self.time_s += time.perf_counter() - t0
        return self.values.get(q)

    @property
    def elements(self) -> int | None:
        return None if self.design is None else int(self.design.cm.n_elements)


def refine_answer(q: str, unit: str, levels: tuple, factor: float, target: float, level: FinerLevel) -> dict:
    """(value, discretisation, note, correction) of answer ``q`` reported from the finest level:
    ``levels`` = (a_h, a_h/2, a_h/4) as computed (before the answer's other corrections, the
    factor ``factor``: 1 + d_NL for the torque, else 1); discretisation 2 |a_h/2 - a_h/4| x
    factor (Richardson, p = 1).  Where the three levels are not monotone (the changes switch
    sign: outside the asymptotic range, or at the contact discretisation's noise floor,
    ~0.01-0.04 % of torque and slip, measured) the finer pair's estimate is not trusted and
    the larger change is taken, 2 max(|a_h - a_h/2|, |a_h/2 - a_h/4|)."""
    a0, a1, a2 = levels
    monotone = (a1 - a0) * (a2 - a1) >= 0
    v, d = a2 * factor, 2.0 * (abs(a1 - a2) if monotone else max(abs(a1 - a2), abs(a0 - a1))) * abs(factor)
    fmt = (lambda x: f"{x:.5g}") if unit != "rpm" else (lambda x: f"{x:.1f}")
    note = (f"refined once more to meet the {100 * target:g} % target: {fmt(a0)} / {fmt(a1)} / {fmt(a2)} {unit} on the "
            f"design mesh / twice / four times as fine ({level.elements} elements, {level.time_s:.1f} s); reported "
            f"from the finest, discretisation " + ("2 |a_h/2 - a_h/4| (Richardson, p = 1)" if monotone else
                                                   "2 max(|a_h - a_h/2|, |a_h/2 - a_h/4|): the levels do not converge "
                                                   "monotonically, so the finer pair's estimate alone is not trusted"))
    fix = {"mesh_refinement": a2 / a0 - 1.0, "mesh_levels": [a0, a1, a2], "mesh_refinement_elements": level.elements,
           "mesh_refinement_time_s": level.time_s}
    return {"value": v, "discretisation": d, "note": note, "correction": fix}
