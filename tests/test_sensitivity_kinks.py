"""Kinks of the contact answers in design sensitivities (issue 21): where a contact node
enters or leaves the zone inside the finite-difference step, the sensitivities say so, give
the one-sided slopes of both sides, and the linearised spreads take the steeper one."""

import math

import pytest

import clutchfem as cf
from clutchfem.analysis import CONTACT_SPEED_OF
from clutchfem.evaluation.sensitivity import Sensitivities, _kinks
from clutchfem.guidelines.elasticity import morphed_elasticity

COARSE = cf.MeshSettings(size="3mm")


def _row(slip, sets, morphed=1):
    return {"slip_rpm": slip, "torque_at_max_engine_torque_Nm": 3.0, "max_von_mises_Pa": 2e9, "safety_factor": 1.0,
            "contact_arc_deg": 5.0, "mesh_morphed": morphed, "contact_sets": sets}


def test_a_changed_contact_set_is_a_kink_with_both_one_sided_slopes():
    a = {"slip": [0, 90, 170], "torque": [0, 90], "peak": [0, 51]}
    b = {"slip": [0, 90], "torque": [0, 90], "peak": [0, 51]}
    rm, base, rp = _row(8000.0, a), _row(8010.0, b), _row(8030.0, b)
    central = {"slip_rpm": (8030.0 - 8000.0) / 2e-5, "torque_at_max_engine_torque_Nm": 0.0}
    k = _kinks(rm, base, rp, 1e-5, central)
    assert set(k) == {"slip_rpm"}  # the torque's and the peak's sets did not change (nor the fatigue's)
    assert k["slip_rpm"]["left"] == pytest.approx(10.0 / 1e-5) and k["slip_rpm"]["right"] == pytest.approx(20.0 / 1e-5)
    assert k["slip_rpm"]["jump"] == pytest.approx((20.0 - 10.0) / 15.0)
    assert k["slip_rpm"]["nodes"] == {"-": [0, 90, 170], "0": [0, 90], "+": [0, 90]}
    assert _kinks(rm, base, _row(8030.0, None), 1e-5, central) is None  # a row without sets: not comparable
    assert _kinks(_row(8000.0, b), base, rp, 1e-5, central) == {}
    c = {"slip": [0], "torque": [0, 90, 91], "peak": [0, 51]}  # the torque speed's set: torque, arc and fatigue
    rows = [_row(8000.0, b) | {"fatigue_safety_factor": 2.0}, _row(8000.0, b) | {"fatigue_safety_factor": 2.1},
            _row(8000.0, c) | {"fatigue_safety_factor": 2.3}]
    k = _kinks(*rows, 1e-5, {"torque_at_max_engine_torque_Nm": 1.0, "fatigue_safety_factor": 1e4, "slip_rpm": 1.0,
                             "contact_arc_deg": 1.0})
    assert set(k) == {"slip_rpm", "torque_at_max_engine_torque_Nm", "contact_arc_deg", "fatigue_safety_factor"}
    assert k["fatigue_safety_factor"]["speed"] == "torque" and k["fatigue_safety_factor"]["right"] == pytest.approx(2e4)


def test_spread_derivative_takes_the_steeper_side_with_the_central_sign():
    s = Sensitivities("concept4", {}, {"t": 1e-3}, {"t": 1e-5}, {"t": "m"},
                      {"t": {"slip_rpm": -1.5e6, "engagement_rpm": 2e6}}, {"t": "central, morphed"},
                      kinks={"t": {"slip_rpm": {"speed": "slip", "left": -1.0e6, "right": -2.0e6, "jump": -0.67,
                                                "nodes": {}}}})
    assert s.spread_derivative("t", "slip_rpm") == -2.0e6
    assert s.spread_derivative("t", "engagement_rpm") == 2e6  # no kink: the central difference
    assert s.spread_derivative("u", "slip_rpm") is None


@pytest.mark.slow
def test_sensitivities_report_the_contact_events_the_analyses_show():
    """With a 0.1 mm step on concept 4's coarse mesh, the kinks reported are exactly the
    answers whose contact set at their speed differs between the two sides, as independent
    analyses of the morphed designs show, and their one-sided slopes are those analyses'."""
    d = cf.Design.from_concept("concept4", mesh=COARSE)
    h = 1e-4
    s = cf.sensitivities(d, ["flexure_thickness"], workers=0, steps={"flexure_thickness": h})
    x0 = d.params.flexure_thickness
    ans = {o: cf.analyze(cf.morph(d, flexure_thickness=round(x0 + o, 12)), errors=False) for o in (-h, 0.0, h)}
    kinks = s.kinks.get("flexure_thickness", {})
    changed = {k for k, sps in CONTACT_SPEED_OF.items() for sp in sps
               if not ans[-h].contact_sets[sp] == ans[0.0].contact_sets[sp] == ans[h].contact_sets[sp]}
    assert set(kinks) == changed
    assert changed, "the 0.1 mm step on this mesh crosses at least one contact event (else the test checks nothing)"
    for key, k in kinks.items():
        attr = {"max_von_mises_Pa": "max_von_mises_Pa", "slip_rpm": "slip_rpm", "safety_factor": "safety_factor",
                "torque_at_max_engine_torque_Nm": "torque_at_max_engine_torque_Nm",
                "contact_arc_deg": "contact_arc_at_max_engine_torque_deg",
                "fatigue_safety_factor": "fatigue_safety_factor"}[key]
        a = {o: getattr(ans[o], attr) for o in ans}
        assert k["left"] == pytest.approx((a[0.0] - a[-h]) / h, rel=1e-6, abs=1e-9)
        assert k["right"] == pytest.approx((a[h] - a[0.0]) / h, rel=1e-6, abs=1e-9)
        d_spread = s.spread_derivative("flexure_thickness", key)
        assert abs(d_spread) >= abs(s.derivatives["flexure_thickness"][key]) - 1e-12
        assert math.isclose(abs(d_spread), max(abs(k["left"]), abs(k["right"]), abs(s.derivatives["flexure_thickness"][key])))
    assert "kink" in s.table()
    key = next(iter(kinks))  # a guideline's elasticity there gives both sides
    e = morphed_elasticity(s, s, "flexure_thickness", key)
    assert "contact node" in e["kink"]
    x, a = s.values["flexure_thickness"], s.base[key]
    assert e["E_left"] == pytest.approx(kinks[key]["left"] * x / a) and e["E_right"] == pytest.approx(kinks[key]["right"] * x / a)
    assert "kink" not in morphed_elasticity(s, s, "flexure_thickness", "engagement_rpm")
