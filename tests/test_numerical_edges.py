"""Numerical stress test (issue 12): the solver driven to its edges gives a correct answer
or a clear refusal, never a silent wrong number.  The cases are in
:mod:`support.solver_edges` (tests/support) (shared with ``benchmarks/bench_stress.py``, whose table is in
BENCHMARKS.md); here every outcome is checked against its reference and the invariants."""

from __future__ import annotations

import numpy as np
import pytest

from support import solver_edges as S

pytestmark = pytest.mark.stress


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("stress")
    out = (S.slender_flexure() + S.sliver_elements(tmp) + S.mesh_sizes() + S.near_divergence() + S.clearances(tmp)
           + S.friction() + S.moving_contact() + S.never_engages())
    print("\n" + "\n".join(" | ".join(map(str, o.row())) for o in out))
    return out


def _answers(outcomes, case):
    return [o for o in outcomes if o.case == case and o.outcome == "answer"]


@pytest.mark.slow
def test_every_case_answers_or_refuses_clearly(outcomes):
    for o in outcomes:
        assert o.outcome in ("answer", "refused"), o
        if o.outcome == "refused":
            assert len(o.message) > 30 and ("speed" in o.message or "size" in o.message), o.message


@pytest.mark.slow
def test_answers_satisfy_the_invariants(outcomes):
    for o in outcomes:
        if o.outcome != "answer":
            continue
        res = o.extra["result"]
        c = res.curve
        assert o.max_residual < 1e-3 and o.max_torque_balance < 1e-3, o.row()
        assert np.all(res.lam >= 0), o.case  # compressive contact forces only
        assert np.all(c["torque_Nm"] >= 0) and np.all(c["normal_force_N"] >= 0), o.case
        touching = c["rpm"][c["normal_force_N"] > 0]
        if len(touching):  # contact only at or above the engagement speed
            assert res.engagement_rpm is not None and touching.min() >= res.engagement_rpm * (1 - 1e-9), o.case
        if "max_von_mises_Pa" in c and c["max_von_mises_Pa"].notna().all():
            assert np.all(c["max_von_mises_Pa"] >= 0)


@pytest.mark.slow
def test_checks_against_references(outcomes):
    tol = {"closed-form engagement (Lame, no softening)": 3e-4,  # straight-sided P2 chords
           "engagement vs Lame closed form": 1e-5,
           "engagement vs 0.6 mm mesh": 1e-3,
           "normal force vs exact softening": 1e-6,
           "warm vs cold contact solves": 1e-9,
           "torque in the engine range (must be 0)": 0.0}
    seen = set()
    for o in outcomes:
        if o.outcome == "answer" and o.reference:
            assert o.error <= tol[o.reference], o.row()
            seen.add(o.reference)
    assert seen == set(tol)


@pytest.mark.slow
def test_expected_refusals(outcomes):
    by = {(o.case, o.inputs): o for o in outcomes}
    refused = [o for o in outcomes if o.outcome == "refused"]
    # past divergence (both softenings), past the mesh-size limit, clearances that need speeds past divergence
    assert any("divergence" in o.message for o in refused if o.case == "near divergence")
    assert all(o.outcome == "refused" for o in outcomes if o.case == "near divergence"
               and (" 1 x" in o.inputs or "1.5 x" in o.inputs))
    assert all(o.outcome == "answer" for o in outcomes if o.case == "near divergence"
               and ("0.999 x" in o.inputs or "0.5 x" in o.inputs))
    assert any("elements" in o.message for o in refused if o.case == "mesh size")
    assert len(by) == len(outcomes)


@pytest.mark.slow
def test_slivers_only_worsen_the_conditioning(outcomes):
    sl = _answers(outcomes, "sliver elements")
    assert len(sl) == 5
    eng = [o.engagement_rpm for o in sl]
    assert max(eng) / min(eng) - 1 < 1e-6  # same answer down to a 0.05 deg sliver
    conds = [o.condition for o in sl]
    assert conds[-1] > 100 * conds[0]  # ... reported through the condition estimate


@pytest.mark.slow
def test_friction_character_and_slender_flexure(outcomes):
    fr = {o.inputs: o.extra["N_ratio"] for o in _answers(outcomes, "friction")}
    assert fr["concept1 minus, mu 1"] < fr["concept1 minus, mu 0.165"] < 1.0 < fr["concept1 plus, mu 0.165"] \
        < fr["concept1 plus, mu 1"]
    (sf,) = _answers(outcomes, "slender flexure")
    assert sf.engagement_rpm < sf.extra["divergence_rpm"]
    (mv,) = _answers(outcomes, "moving contact")
    assert mv.extra["nodes_opening"] > 0  # contact really opened somewhere along the arc
    (ne,) = _answers(outcomes, "never engages")
    assert ne.extra["status"] == "never engages" and ne.extra["slip_rpm"] is None
