"""Issue 37: the one-at-a-time chart shows each parameter in its own unit (mm, deg) with its
declared limits, not as "parameter / its design value [-]" (a synthetic study: no mesh)."""

from __future__ import annotations

import pandas as pd

from clutchfem.core.values import param_bounds
from clutchfem.geometry import get_concept
from clutchfem.guidelines import GuidelineResult
from clutchfem.guidelines.elasticity import ANSWERS, oat_values
from clutchfem.report.guideline_charts import oat_chart
from support.pictures import agrees, rule

X0 = {"flexure_thickness": (0.0044, "m"), "clearance": (0.0006, "m"), "shoe_arc": (75.0, "deg")}
BASE = {"engagement_rpm": 3100.0, "slip_rpm": 9000.0, "torque_at_max_engine_torque_Nm": 2.5,
        "max_von_mises_MPa": 640.0, "shoe_mass_g": 21.0, "contact_arc_deg": 30.0}


def _result() -> GuidelineResult:
    table, oat = [], []
    for n, (x0, unit) in X0.items():
        for col, _ in ANSWERS:
            table.append({"parameter": n, "answer": col, "unit": unit, "x0": x0, "E": 0.5, "verdict": "stable",
                          "method": "central difference on morphed meshes", "value_at_x0": BASE[col]})
        xs = oat_values(x0, *param_bounds(get_concept("concept1").Params, n), 0.5, 5)  # as a study plans them
        for x in xs:
            f = x / x0
            rec = {"parameter": n, "unit": unit, "value": x, "relative": f, "status": "ok" if x < xs[-1] else "refused"}
            rec.update({col: (v * f ** 0.5 if f < 1.5 else None) for col, v in BASE.items()})
            oat.append(rec)
    return GuidelineResult("concept1", {}, 0.02, table, list(X0), pd.DataFrame(oat))


def test_each_parameter_in_its_unit_with_its_declared_limits(tmp_path):
    rec = rule(oat_chart(_result(), tmp_path / "one_at_a_time.png"))
    P = get_concept("concept1").Params
    panels = {a["xlabel"]: a for a in rec["axes"] if a["xlabel"]}
    assert set(panels) == {"flexure_thickness [mm]", "clearance [mm]", "shoe_arc [deg]"}
    assert not any("design value [-]" in a["xlabel"] for a in rec["axes"])
    for n, (x0, unit) in X0.items():
        ax = panels[f"{n} [{'mm' if unit == 'm' else unit}]"]
        scale = 1e3 if unit == "m" else 1.0
        lo, hi = param_bounds(P, n)
        assert f"design {x0 * scale:.4g}" in ax["title"]
        assert f">= {lo * scale:.4g}" in ax["title"] and f"<= {hi * scale:.4g}" in ax["title"], ax["title"]
        # the view spans the studied values (x0 (1 -+ 0.5), clipped to the limits) in the parameter's unit
        assert ax["xlim"][0] <= max(0.5 * x0, lo) * scale and ax["xlim"][1] >= min(1.5 * x0, hi) * scale
    near = panels["flexure_thickness [mm]"]  # its upper limit 6 mm bounds the study: drawn, the view beyond it
    assert near["xlim"][1] > param_bounds(P, "flexure_thickness")[1] * 1e3
    for col, label in ANSWERS:
        agrees(rec, label.replace("[", r"\[").replace("]", r"\]") + ": design point", BASE[col])
