"""The shortcuts that make a sweep cheap must not change its answer.

* lazy contact condensation (only the columns of nodes the LCP makes active) against the
  dense LCP on the full condensed matrix, at every speed of a sweep;
* the hand-written isoparametric vertex gradients against scikit-fem's own interpolation;
* a lazy column provider in the LCP against the dense matrix (hypothesis).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchfem.contact import lazy, solve_lcp
from clutchfem.core import get_material
from clutchfem.fe import FEModel
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.loadcase import Design, OperatingPoint
from clutchfem.mesh import mesh_concept

STEEL = get_material("51CrV4")


def design(cm, p, mu=0.165, **op):
    return Design(cm, OperatingPoint(mu=mu, material=STEEL, **op), params=p)


@pytest.fixture(scope="module")
def concept1_coarse():
    c = get_concept("concept1")
    p = c.params()
    return mesh_concept(c, p, MeshSettings(size=2.0e-3, model="sector")), p


@pytest.mark.slow
def test_lazy_condensation_equals_dense_lcp(concept1_coarse):
    cm, p = concept1_coarse
    d = design(cm, p, mu=0.3)
    res = d.sweep("0:14000:500")
    case = d.case()
    r = case.response
    nd = d.nodes
    assert res.engagement_rpm is not None
    # the saving is real: far fewer columns than contact nodes
    assert 0 < r.compliance.n_condensed < nd.m / 2
    # the dense reference: all m columns of K^-1 D
    D = case.contact.load
    W = d.model.solve(D.toarray())
    BW = nd.normal_displacement(W)
    engaged = 0
    for k, w in enumerate(res.omega):
        lam_k = res.lam[k]
        if not lam_k.any():
            continue
        engaged += 1
        c = r.coefficients(w)
        G = -(BW + (r.BPhi * c) @ r.PhiD)
        q = nd.gap0 - r.free_normal(w)
        lam, _ = solve_lcp(G, q)
        assert np.allclose(lam_k, lam, rtol=1e-8, atol=1e-10 * lam.max())
        # and the displacement assembled from the reduced basis equals the dense one
        u_dense = w ** 2 * d.model.u1 + W @ lam + r.Phi @ (c * (w ** 2 * r.Phi_f1 + r.PhiD @ lam))
        assert np.allclose(res.displacement(k), u_dense, rtol=1e-9, atol=1e-12 * np.abs(u_dense).max())
    assert engaged >= 5


def test_sweep_fields_from_reduced_basis(concept1_coarse):
    """Max displacement and max von Mises of the curve equal those of the per-speed fields."""
    cm, p = concept1_coarse
    d = design(cm, p)
    res = d.sweep("3000,8000,14000")
    for k in range(len(res.rpm)):
        u = res.displacement(k)
        vm = d.model.stress_at_vertices(u)
        vm = np.sqrt(vm[0] ** 2 - vm[0] * vm[1] + vm[1] ** 2 + 3 * vm[2] ** 2)
        assert res.curve["max_von_mises_Pa"][k] == pytest.approx(vm.max(), rel=1e-9)
        ux, uy = u[0::2], u[1::2]
        assert res.curve["max_displacement_m"][k] == pytest.approx(np.hypot(ux, uy).max(), rel=1e-12)


def test_vertex_stresses_match_skfem_on_curved_mesh(concept1_coarse):
    cm, p = concept1_coarse
    fe = FEModel(cm, STEEL, p.thickness)
    u = np.random.default_rng(1).normal(size=(fe.ndofs, 3))
    mine = fe.stress(u)
    for j in range(3):
        ref = fe.stress_at_vertices(u[:, j]).reshape(3, -1)
        assert np.allclose(mine[..., j], ref, rtol=1e-10, atol=1e-12 * np.abs(ref).max())


@settings(max_examples=40, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2 ** 32 - 1), m=st.integers(1, 30), skew=st.floats(0.0, 0.4))
def test_lazy_lcp_matches_dense(seed, m, skew):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(m, m))
    K = rng.normal(size=(m, m))
    G = 1e-8 * (A @ A.T / m + 0.05 * np.eye(m) + skew * (K - K.T) / np.sqrt(m))
    q = 1e-4 * rng.normal(size=m)
    asked: set[int] = set()

    def cols(idx):
        asked.update(int(i) for i in idx)
        return G[:, idx]

    lam_lazy, _ = solve_lcp(lazy(cols), q)
    lam, _ = solve_lcp(G, q)
    assert np.allclose(lam_lazy, lam, rtol=1e-8, atol=1e-12 * max(lam.max(initial=0.0), 1e-300))
    # the active-set path only asks for columns it activates (or all, on a Lemke fallback)
    assert set(np.nonzero(lam_lazy)[0]) <= asked


@pytest.mark.slow
@pytest.mark.parametrize("backend", ["superlu", "cholmod"])
def test_solver_backends_agree(concept1_coarse, backend, monkeypatch):
    """Every installed direct solver gives the same sweep (CHOLMOD is installed by
    `make setup` when it builds; SuperLU is always there), whether chosen by the environment
    variable (the default) or injected."""
    from clutchfem.fe import available

    if backend not in available():
        pytest.skip(f"{backend} not installed here")
    cm, p = concept1_coarse
    ref = design(cm, p).sweep("0:14000:1000")
    monkeypatch.setenv("CLUTCHFEM_SOLVER", backend)
    d = design(cm, p)
    assert d.model.factor.name == backend
    monkeypatch.delenv("CLUTCHFEM_SOLVER")
    injected = Design(cm, OperatingPoint(mu=0.165, material=STEEL), params=p, solver=backend)
    assert injected.model.factor.name == backend
    for r in (d.sweep("0:14000:1000"), injected.sweep("0:14000:1000")):
        assert r.engagement_rpm == pytest.approx(ref.engagement_rpm, rel=1e-9)
        assert np.allclose(r.curve["normal_force_N"], ref.curve["normal_force_N"], rtol=1e-7, atol=1e-9)
        assert np.allclose(r.curve["max_von_mises_Pa"], ref.curve["max_von_mises_Pa"], rtol=1e-7)


def test_cholmod_reuses_the_analysis_of_a_pattern_and_factors_bit_for_bit():
    """Matrices of one sparsity pattern (K - w^2 M at each speed) share one symbolic analysis:
    the factor is the one a fresh analysis gives, to the bit; a matrix of another pattern with
    the same size and entry count gets its own analysis, never the cached one."""
    import scipy.sparse as sp

    from clutchfem.fe import available, linsolve

    if "cholmod" not in available():
        pytest.skip("cholmod not installed here")
    from sksparse.cholmod import cholesky

    n = 400
    lap = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)).tocsc()
    lap2 = sp.kron(sp.eye(20), sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(20, 20))).tocsc()
    mass = sp.diags(np.linspace(1.0, 2.0, n)).tocsc()
    linsolve._SYMBOLIC.clear()
    b = np.random.default_rng(3).normal(size=n)
    for w2 in (0.0, 0.3, 0.7):
        A = (lap + lap2 + 1e-3 * sp.eye(n) - w2 * 1e-4 * mass).tocsc()
        f = linsolve._Cholmod(A)
        ref = cholesky(A, mode="simplicial")
        assert np.array_equal(f.solve(b), ref(b)) and np.array_equal(f._f.D(), ref.D())
    assert len(linsolve._SYMBOLIC) == 1  # one pattern, one analysis
    # same size and entry count, other pattern (a permuted band): its own analysis, its own answer
    perm = np.random.default_rng(5).permutation(n)
    B = ((lap + lap2 + 1e-3 * sp.eye(n)).tocsr()[perm][:, perm]).tocsc()
    assert B.nnz == A.nnz
    g = linsolve._Cholmod(B)
    assert np.allclose(B @ g.solve(b), b, atol=1e-9) and len(linsolve._SYMBOLIC) == 2


@pytest.mark.slow
def test_injected_solver_factory_is_used(concept1_coarse):
    """A user's own factory (here scipy's splu wrapped) is what factorises K."""
    import scipy.sparse.linalg as spla

    cm, p = concept1_coarse
    calls = []

    def my_solver(A):
        calls.append(A.shape)
        return spla.splu(A.tocsc())

    d = Design(cm, OperatingPoint(material=STEEL), params=p, solver=my_solver)
    r = d.sweep("0,9000")
    ref = design(cm, p).sweep("0,9000")
    assert len(calls) == 1 and calls[0][0] == calls[0][1]
    assert np.allclose(r.curve["normal_force_N"], ref.curve["normal_force_N"], rtol=1e-8)


@pytest.mark.parametrize("strategy", ["ritz", "prestress"])
def test_shared_space_extends_the_load_space_exactly(concept1_coarse, strategy):
    """seeds='all' built as the extension of a 'load' space (base_mu: only the tangential
    seeds back-solved) is the same space as built from scratch: principal-angle cosines 1,
    orthonormal in the strategy's inner product, and the same answers to 1e-8."""
    from dataclasses import replace

    from clutchfem.loadcase import LoadCase, sweep
    from clutchfem.softening import get_softening

    d = design(*concept1_coarse)
    soft = replace(get_softening(strategy), seeds="all")
    ext = replace(soft, base_mu=0.165)
    c = d.contact(0.3)
    Vs = np.hstack(soft._cached(d.model, c)[0])
    Ve = np.hstack(ext._cached(d.model, c)[0])
    inner = soft.inner(soft.operator_model(d.model))
    assert Ve.shape == Vs.shape
    assert np.abs(Ve.T @ (inner @ Ve) - np.eye(Ve.shape[1])).max() < 1e-7
    cos = np.linalg.svd(Vs.T @ (inner @ Ve), compute_uv=False)
    assert np.all(np.abs(cos - 1.0) < 1e-6)
    # the design's own load space was built on the way and is shared with its load case
    base_key = [k for k in d.model.__dict__["_ritz_cache"] if k[2] == "load" and k[0] == soft.name]
    assert base_key
    a = sweep(LoadCase(d.model, c, soft), [6000.0, 9000.0, 12000.0])
    b = sweep(LoadCase(d.model, c, ext), [6000.0, 9000.0, 12000.0])
    np.testing.assert_allclose(b.curve["normal_force_N"], a.curve["normal_force_N"], rtol=1e-8)


@pytest.mark.parametrize("kw", [{"base_mu": 0.2}, {"seeds": "all", "base_mu": -0.1},
                                {"seeds": "all", "base_mu": True}, {"seeds": "all", "base_mu": 1.5}])
def test_base_mu_is_checked(kw):
    from clutchfem.core import ParameterError
    from clutchfem.softening import Ritz

    with pytest.raises(ParameterError, match="base_mu"):
        Ritz(**kw)


@pytest.mark.slow
@pytest.mark.parametrize("what", ["sweep", "analyze"])
def test_a_finished_design_is_freed_without_the_garbage_collector(concept1_coarse, what):
    """No reference cycle holds a design's FE model (its matrices and factorisation): when the
    design and its results go, the model goes at once, not at some later garbage collection
    (in a study, memory and time would otherwise be charged to whichever design runs then)."""
    import gc
    import weakref

    from clutchfem.analysis import analyze

    gc.collect()
    gc.disable()
    try:
        d = design(*concept1_coarse)
        r = analyze(d, errors=False) if what == "analyze" else d.sweep("0:14000:500")
        model, factor = weakref.ref(d.model), weakref.ref(d.model.factor)
        del d, r
        assert model() is None and factor() is None
    finally:
        gc.enable()


def test_tune_malloc_is_idempotent_and_takes_on_glibc():
    import sys

    from clutchfem.core import tune_malloc

    first = tune_malloc()
    assert tune_malloc() is first
    if sys.platform.startswith("linux"):
        import platform

        assert first == (platform.libc_ver()[0] == "glibc")


def test_one_quantity_parser_for_every_unit():
    """--set, CLI options and the API read quantities through one parser (core.units): the
    field's own dimension only, converted exactly, refusals naming the accepted suffixes."""
    from clutchfem.core.units import UnitError, format_quantity, parse_quantity

    assert parse_quantity("9mm", "m") == 0.009  # exact decimal conversion, no float noise
    assert parse_quantity("400C", "C") == 400.0 and parse_quantity("673.15K", "C") == pytest.approx(400.0)
    assert parse_quantity("200GPa", "Pa") == 200e9 and parse_quantity("1250 N/mm2", "Pa") == 1250e6
    assert parse_quantity("2700rpm", "rpm") == 2700.0 and parse_quantity("3.4 N m", "N m") == 3.4
    assert parse_quantity("2.5 lbf ft", "N m") == pytest.approx(3.3895448708)
    for raw, unit in (("400mm", "C"), ("2deg", "m"), ("3 N m", "-"), ("12 parsecs", "m"), ("", "m")):
        with pytest.raises(UnitError):
            parse_quantity(raw, unit)
    assert format_quantity(0.019, "m") == "19 mm" and format_quantity(1.25e9, "Pa") == "1250 MPa"


def test_lazy_lcp_asks_only_for_what_an_elastic_drum_needs():
    """An elastic drum's compliance couples every node: pushing the deepest node leaves most
    of the shoe's free arc penetrating.  The lazy active-set iteration enters the deepest
    few per step (at least doubling), so it condenses far fewer columns than there are
    penetrating nodes, and reaches the dense solution."""
    m = 120
    s = np.linspace(0.0, 1.0, m)
    K = 1e-9 * (np.exp(-np.abs(s[:, None] - s[None, :]) / 0.05) + 0.2)  # coupled, positive definite
    q = -1e-4 * (0.2 + s ** 2)  # the whole arc penetrates, deepest at the tip
    asked: set[int] = set()

    def cols(idx):
        asked.update(int(i) for i in idx)
        return K[:, idx]

    lam_lazy, _ = solve_lcp(lazy(cols), q, np.eye(m, dtype=bool)[m - 1])
    lam, _ = solve_lcp(K, q)
    assert np.allclose(lam_lazy, lam, rtol=1e-8, atol=1e-12 * lam.max())
    assert np.count_nonzero(q < 0) == m and len(asked) < 0.6 * m
    print(f"\n{len(asked)} of {m} columns asked, {np.count_nonzero(lam)} active")
