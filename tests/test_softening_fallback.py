"""analyze falls back to the per-speed factorisation (softening prestress-exact) where the
pre-stress Ritz space misses equilibrium: a soft concept 4 design of the space-filling set
(concept4-lhs06, engaging near 1000 rpm) at 14 000 rpm."""

import pytest

import clutchfem as cf
from clutchfem.core import EquilibriumError
from clutchfem.loadcase.checks import RESIDUAL_FAIL

LHS06 = {"flexure_thickness": 0.002214, "flexure_length": 0.014487, "flexure_taper": 1.485,
         "flexure_angle": 26.647, "shoe_arc": 71.526, "thickness": 0.014108}


@pytest.fixture(scope="module")
def design():
    return cf.Design.from_concept("concept4", **LHS06, mesh=cf.MeshSettings(size="3mm"))


def test_ritz_space_misses_and_the_exact_one_holds(design):
    with pytest.raises(EquilibriumError, match="equilibrium residual"):
        design.sweep([14000])
    exact = design.with_softening("prestress-exact")
    assert exact.model is design.model  # the same model and factorisation of K
    res = exact.sweep([8000, 14000])
    assert float(res.curve["residual"].max()) < RESIDUAL_FAIL
    assert res.softening == "prestress-exact"


def test_analyze_falls_back_and_says_so(design):
    a = cf.analyze(design, errors=False)
    assert any("missed equilibrium" in n and "prestress-exact" in n for n in a.notes)
    assert a.inputs["operating_point"]["softening"] == "prestress-exact"
    assert a.inputs["model"]["softening"] == "prestress-exact"
    assert a.slip_rpm is not None and a.max_von_mises_Pa > 0



def test_prestress_exact_where_the_prestress_outweighs_the_softening_everywhere():
    """Concept 5's stretched beams: M - K_sigma1 is negative on every Ritz seed, so the free
    part never diverges.  The per-speed strategy's divergence estimate used to stop on an
    empty Krylov space (ValueError "need at least one array to concatenate"): now no limit."""
    d = cf.Design.from_concept("concept5", mesh=cf.MeshSettings(size=3e-3), fidelity="best",
                            formulation="plane-stress").with_softening("prestress-exact")
    case = d.case()
    assert case.omega_limit is None
    assert case.engagement_rpm > 0
