"""The 3-D path's own discretisation error (issue 20): a layers term (Richardson against one
layer more) and an in-plane term (the thick plane model's relative change on a mesh twice as
fine), both computed, not assumed; their sum is the discretisation reported by ``solve``."""

from __future__ import annotations

import pytest

import clutchfem as cf
from clutchfem.accuracy import layers_design, layers_error, refined_design, sweep_errors, thick_twin

COARSE = cf.MeshSettings(size="6mm", flexure_factor=1.0, contact_factor=0.5, fillet_factor=1.0)


def test_layers_richardson_is_exact_for_a_first_order_sequence():
    a, c = 4000.0, 90.0  # a_n = a + c / n: the error of a_2 is c / 2
    assert layers_error(a + c / 2, 2, a + c / 3, 3) == pytest.approx(c / 2, rel=1e-12)
    assert layers_error(a + c / 1, 1, a + c / 2, 2) == pytest.approx(c, rel=1e-12)
    assert layers_error(a + c / 16, 16, a + c / 15, 15) == pytest.approx(c / 16, rel=1e-12)  # n - 1 at the top
    assert layers_error(a, 2, None, 3) is None


@pytest.mark.slow
def test_solve_errors_of_a_3d_design_sum_the_measured_terms():
    d = cf.Design.from_concept("concept4", formulation="3d", layers=1, mesh=COARSE)
    res = d.sweep([9000.0])
    errs = sweep_errors(d, res)
    # the terms, computed here independently
    d2 = layers_design(d)
    assert d2.op.layers == 2 and d2.model.ndofs > d.model.ndofs
    r2 = d2.sweep([9000.0])
    tw = thick_twin(d)
    fine = refined_design(tw)
    assert tw.model.formulation == "thick" and fine.cm.n_elements > 2 * tw.cm.n_elements
    rt, rf = tw.sweep([9000.0]), fine.sweep([9000.0])
    for q, col in (("torque_Nm", "torque_Nm"), ("max_von_mises_Pa", "max_von_mises_Pa")):
        v, v2 = float(res.curve[col].iloc[0]), float(r2.curve[col].iloc[0])
        e = errs[q]
        assert e["discretisation_layers"] == pytest.approx(2 * abs(v - v2), rel=1e-9)  # n + 1 = 2 x the change
        t, f = float(rt.curve[col].iloc[0]), float(rf.curve[col].iloc[0])
        assert e["discretisation_in_plane"] == pytest.approx(abs(v) * 2 * abs(t - f) / abs(t), rel=1e-9)
        assert e["discretisation"] == pytest.approx(e["discretisation_layers"] + e["discretisation_in_plane"])
        assert e["discretisation_layers"] > 0 and e["discretisation_in_plane"] > 0
        assert any("layers 1 vs 2" in n for n in e["notes"])
    e = errs["engagement_rpm"]
    assert e["discretisation_layers"] == pytest.approx(2 * abs(res.engagement_rpm - r2.engagement_rpm), rel=1e-9)
