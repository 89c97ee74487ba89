"""Verification of the geometrically non-linear reference, :mod:`clutchfem.nonlinear`.

Closed forms / accurate references
----------------------------------
**Spinning radial cantilever** (root on the axis, clamped, length L, depth t in the plane of
rotation, thickness h, A = t h, I = h t^3 / 12): the centrifugal tension is
N(x) = rho A w^2 (L^2 - x^2) / 2, and a small transverse (in-plane) tip load P deflects it
by v(x) with

    EI v'''' - (N v')' - rho A w^2 v = 0,   v(0) = v'(0) = 0, v''(L) = 0, EI v'''(L) = -P

(the last term: the in-plane centrifugal load follows the deflection, spin softening).  It
is solved with ``scipy.integrate.solve_bvp`` to 1e-10.  The non-linear FE state at speed w
plus P, minus the state without P, is the tangent response the ODE describes.  The linear
fast path (K - w^2 M, no stress stiffening) misses N entirely; with the geometric stiffness
of the linear pre-stress (K + w^2 (K_sigma1 - M)) it recovers the ODE's answer.

**Spinning annulus, St. Venant-Kirchhoff plane stress** (a <= R <= b, u(a) = 0): with
l_r = 1 + u', l_t = 1 + u / R, E_r = (l_r^2 - 1)/2, E_t = (l_t^2 - 1)/2,
S_r = D (E_r + nu E_t), S_t = D (E_t + nu E_r), D = E / (1 - nu^2), P_r = l_r S_r,
P_t = l_t S_t, radial equilibrium in the reference configuration with the centrifugal load
on the deformed position:

    (R P_r)' - P_t + rho w^2 (R + u) R = 0,   P_r(b) = 0 (free)  or  u(b) = c (drum).

Solved with ``solve_bvp`` to 1e-10 (state u, u').  Against the drum R_d = b + c the whole
rim touches; the contact force per unit reference length is -P_r(b), N = -P_r(b) 2 pi b h.
Its small-strain limit is the linear (spin-softened) Lame solution: the non-linear
correction must vanish like strain ~ w^2.

Run with ``pytest -s`` to see the measured tables.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from scipy.integrate import solve_bvp
from skfem import FacetBasis, LinearForm, asm

from clutchfem.accuracy import NonlinearModel, second_order_engagement
from clutchfem.core import Material
from clutchfem.fe import FEModel, geometric_stiffness
from support.shapes import load_annulus, load_cantilever

STEEL = Material(name="steel (verification)", E=210e9, nu=0.3, rho=7850.0)
A_IN, B_OUT, H = 6.5e-3, 33.8e-3, 11e-3


# ---------------------------------------------------------------------------------------
# references
# ---------------------------------------------------------------------------------------
def beam_tip(L, t, h, omega, P, mat=STEEL):
    """Tip deflection of the spinning cantilever ODE (module docstring)."""
    E, rho = mat.E, mat.rho
    A, EI = t * h, E * h * t ** 3 / 12
    N = lambda x: rho * A * omega ** 2 * (L * L - x * x) / 2  # noqa: E731
    dN = lambda x: -rho * A * omega ** 2 * x  # noqa: E731

    def f(x, y):
        v, v1, v2, v3 = y
        return np.vstack([v1, v2, v3, (dN(x) * v1 + N(x) * v2 + rho * A * omega ** 2 * v) / EI])

    def bc(ya, yb):
        return np.array([ya[0], ya[1], yb[2], EI * yb[3] - N(L) * yb[1] + P])

    x = np.linspace(0, L, 400)
    sol = solve_bvp(f, bc, x, np.zeros((4, len(x))), tol=1e-10, max_nodes=200000)
    assert sol.success
    return float(sol.sol(L)[0])


def svk_annulus(mat, omega, a=A_IN, b=B_OUT, rim=None):
    """(u(b), P_r(b)) of the St. Venant-Kirchhoff rotating annulus (module docstring);
    ``rim`` None: free rim, else u(b) = rim."""
    E, nu, rho = mat.E, mat.nu, mat.rho
    D = E / (1 - nu * nu)
    lam_s = D * nu  # plane-stress lambda*
    c1 = D  # lambda* + 2 mu

    def parts(R, u, v):
        lr, lt = 1 + v, 1 + u / R
        Er, Et = (lr * lr - 1) / 2, (lt * lt - 1) / 2
        Sr, St = c1 * Er + lam_s * Et, lam_s * Er + c1 * Et
        return lr, lt, Sr, St

    def rhs(w):
        def f(R, y):
            u, v = y
            lr, lt, Sr, St = parts(R, u, v)
            Pr, Pt = lr * Sr, lt * St
            dPr_dv = Sr + lr * c1 * lr
            dPr_dlt = lr * lam_s * lt
            dlt = v / R - u / R ** 2
            dv = (Pt - rho * w ** 2 * (R + u) * R - Pr - R * dPr_dlt * dlt) / (R * dPr_dv)
            return np.vstack([v, dv])
        return f

    def bc(ya, yb):
        if rim is None:
            lr, lt, Sr, _ = parts(b, yb[0], yb[1])
            return np.array([ya[0] / b, lr * Sr / D])  # dimensionless
        return np.array([ya[0] / b, (yb[0] - rim) / b])

    R = np.linspace(a, b, 400)
    y = np.zeros((2, len(R)))
    for frac in (0.25, 0.5, 0.75, 1.0):  # continuation in speed: each solution seeds the next
        sol = solve_bvp(rhs(frac * omega), bc, R, y, tol=1e-10, bc_tol=1e-10, max_nodes=200000)
        assert sol.success, sol.message
        R, y = sol.x, sol.y
    ub, vb = sol.sol(b)
    lr, lt, Sr, _ = parts(b, ub, vb)
    return float(ub), float(lr * Sr)


def rim_radial(fe, u, b=B_OUT):
    X = fe.basis.doflocs[:, 0::2]
    rim = np.abs(np.hypot(*X) - b) < 1e-9
    return float(np.mean((X[0] * u[0::2] + X[1] * u[1::2])[rim] / b))


@pytest.fixture(scope="module")
def sector(tmp_path_factory):
    d = tmp_path_factory.mktemp("nl")
    return load_annulus(d / "sec.msh", A_IN, B_OUT, 1.5e-3, thickness=H, sector_deg=30.0)


# ---------------------------------------------------------------------------------------
# tests
# ---------------------------------------------------------------------------------------
def test_tangent_is_the_derivative_of_the_residual(sector):
    """Central differences of the internal force (and of the contact force) match the
    assembled tangents to O(eps^2): the Newton iteration can converge quadratically."""
    fe = FEModel(sector, STEEL)
    nl = NonlinearModel(fe, drum_radius=B_OUT + 1e-4, mu=0.3)
    rng = np.random.default_rng(1)
    u = rng.standard_normal(fe.ndofs) * 1e-4
    du = rng.standard_normal(fe.ndofs) * 1e-4
    _, K = nl.kin.residual_and_tangent(u)
    errs = []
    for eps in (1e-2, 1e-3):
        rp, _ = nl.kin.residual_and_tangent(u + eps * du, tangent=False)
        rm, _ = nl.kin.residual_and_tangent(u - eps * du, tangent=False)
        errs.append(np.linalg.norm((rp - rm) / (2 * eps) - K @ du) / np.linalg.norm(K @ du))
    assert errs[1] < 1e-6 and errs[1] < errs[0] / 50
    lam = rng.uniform(0, 10, nl.nodes.m)
    _, Kc, D, _ = nl._contact_terms(u, lam)
    fp = nl._contact_terms(u + 1e-3 * du, lam, forces_only=True)
    fm = nl._contact_terms(u - 1e-3 * du, lam, forces_only=True)
    assert np.linalg.norm((fp - fm) / 2e-3 - Kc @ du) < 1e-6 * np.linalg.norm(Kc @ du)
    assert np.allclose(D @ lam, nl._contact_terms(u, lam, forces_only=True))


def test_zero_displacement_tangent_is_linear_stiffness(sector):
    fe = FEModel(sector, STEEL)
    nl = NonlinearModel(fe)
    _, K0 = nl.kin.residual_and_tangent(np.zeros(fe.ndofs))
    assert abs(K0 - fe.K).max() < 1e-12 * abs(fe.K).max()


def test_annulus_svk_free_spin_matches_ode(sector):
    """Large strain (a soft material at high speed: rim strain ~3 %): the FE reference matches
    the 1-D SVK solution, far closer than the linear answer does."""
    soft = Material(name="soft", E=2.1e9, nu=0.3, rho=7850.0)
    fe = FEModel(sector, soft)
    nl = NonlinearModel(fe)
    w = 6000.0
    st = nl.sweep([2000.0, 4000.0, w], contact=False)[-1]
    ub, _ = svk_annulus(soft, w)
    u_fe = rim_radial(fe, st.u) * 1.0
    A = (fe.Kr - w * w * fe.Mr).tocsc()
    u_lin = rim_radial(fe, fe.T @ spla.spsolve(A, fe.T.T @ (w * w * fe.f1)))
    print(f"\nSVK annulus, rim strain {ub / B_OUT:.3%}: u(b) ODE {ub:.6e}, FE {u_fe:.6e} "
          f"({u_fe / ub - 1:+.2e}), linear {u_lin:.6e} ({u_lin / ub - 1:+.2e}); "
          f"{st.iterations} Newton iterations at the last step")
    assert ub / B_OUT > 0.02
    assert abs(u_fe / ub - 1) < 2e-5
    assert abs(u_lin / ub - 1) > 100 * abs(u_fe / ub - 1)


def test_annulus_small_strain_limit_is_linear(sector):
    """Steel: the non-linear - linear (spin-softened) difference vanishes like w^2 (strain)."""
    fe = FEModel(sector, STEEL)
    nl = NonlinearModel(fe)
    rows = []
    for w in (2000.0, 4000.0, 8000.0):
        st = nl.solve(w, contact=False)
        A = (fe.Kr - w * w * fe.Mr).tocsc()
        ul = fe.T @ spla.spsolve(A, fe.T.T @ (w * w * fe.f1))
        d = rim_radial(fe, st.u) / rim_radial(fe, ul) - 1
        rows.append((w, d, rim_radial(fe, ul) / B_OUT))
    print("\nsmall-strain limit: w, u_nl / u_lin - 1, rim strain")
    for r in rows:
        print("  %.0f %+.3e %.2e" % r)
    orders = [math.log(rows[i + 1][1] / rows[i][1]) / math.log(2) for i in range(2)]
    print("  observed orders in w", ["%.3f" % q for q in orders])
    assert all(abs(q - 2) < 0.02 for q in orders)


@pytest.mark.slow
def test_annulus_on_drum_contact_force_matches_ode(sector):
    """The whole rim pressed on the exact circle R_d = b + c: total normal force vs the SVK
    ODE with u(b) = c (soft material, large strain), and the linear answer's error."""
    soft = Material(name="soft", E=2.1e9, nu=0.3, rho=7850.0)
    fe = FEModel(sector, soft)
    c = 0.6e-3
    nl = NonlinearModel(fe, drum_radius=B_OUT + c)
    w = 6000.0
    sts = nl.sweep([3000.0, 4500.0, w])
    st = sts[-1]
    assert st.lam.all()  # the whole rim touches
    _, Pr = svk_annulus(soft, w, rim=c)
    N_ode = -Pr * 2 * math.pi * B_OUT * H
    N_fe = nl.normal_force(st)
    r = np.hypot(*nl.positions(st.u))
    print(f"\ndrum contact (rim strain {c / B_OUT:.2%}): N ODE {N_ode:.6e} N, FE {N_fe:.6e} N "
          f"({N_fe / N_ode - 1:+.2e}); contact radius error {np.abs(r - B_OUT - c).max():.1e} m")
    assert abs(N_fe / N_ode - 1) < 1e-4
    assert np.abs(r - (B_OUT + c)).max() < 1e-12
    assert nl.torque(st) == 0.0


def test_spinning_beam_stress_stiffening(tmp_path):
    """Radial cantilever at Lambda = rho A w^2 L^4 / EI = 6 and 20: tip compliance under a
    transverse tip load relative to the non-spinning one, FE reference vs the beam ODE, the
    linear path (softening only) and the prestressed linear path."""
    L, t, h, P = 40e-3, 1e-3, 5e-3, 1e-3
    cm = load_cantilever(tmp_path / "beam.msh", L, t, 0.5e-3, depth=h)
    fe = FEModel(cm, STEEL)
    fb = FacetBasis(cm.mesh, fe.basis.elem, facets=cm.boundary("tip"), intorder=4)
    fP = asm(LinearForm(lambda v, w: P / t * v[1]), fb)  # shear traction, total P
    X = fe.basis.doflocs[:, 0::2]
    tip = 2 * int(np.nonzero((np.abs(X[0] - L) < 1e-12) & (np.abs(X[1]) < 1e-12))[0][0]) + 1
    nl = NonlinearModel(fe)
    u1 = fe.solve(fe.f1)
    Ks = geometric_stiffness(fe, u1)
    Ksr = (fe.T.T @ Ks @ fe.T).tocsc()
    d0 = fe.solve(fP)[tip]
    o0 = beam_tip(L, t, h, 0.0, P)
    rows = []
    for Lam in (6.0, 20.0):
        w = math.sqrt(Lam * STEEL.E * t ** 2 / (12 * STEEL.rho * L ** 4))
        s0 = nl.solve(w, contact=False)
        sP = nl.solve(w, u0=s0.u, contact=False, extra_load=fP)
        r_nl = (sP.u[tip] - s0.u[tip]) / d0
        r_ode = beam_tip(L, t, h, w, P) / o0
        lin = (fe.T @ spla.spsolve((fe.Kr - w * w * fe.Mr).tocsc(), fe.T.T @ fP))[tip] / d0
        pre = (fe.T @ spla.spsolve((fe.Kr + w * w * (Ksr - fe.Mr)).tocsc(), fe.T.T @ fP))[tip] / d0
        rows.append((Lam, w, r_ode, r_nl, lin, pre))
    print(f"\nspinning beam L/t = {L / t:.0f} (static FE / ODE - 1 = {d0 / o0 - 1:+.1e}): "
          "Lambda, w, tip compliance ratio ODE, FE non-linear, linear (softening only), prestressed")
    for r in rows:
        print("  %4.0f %7.1f  %.6f  %.6f  %+.4f  %.6f" % r)
    for Lam, w, r_ode, r_nl, lin, pre in rows:
        assert abs(r_nl - r_ode) < 5e-4  # beam vs 2-D continuum: O(t/L), measured 2.8e-4
        assert abs(pre - r_nl) < 2e-3 * r_nl  # prestressed linear: O(axial strain 5e-4)
        assert abs(lin - r_ode) > 0.3  # the linear fast path is qualitatively wrong here
    assert rows[1][4] < 0  # past the softened bending 'divergence' (Lambda ~ 12.4): sign flips


def test_second_order_engagement_closed_form():
    g0 = np.array([1e-3, 2e-3])
    un = np.array([1e-9, 1e-9])
    ut = np.array([0.0, 3e-8])
    r = np.array([0.03, 0.03])
    w, i = second_order_engagement(g0, un, ut, r)
    x = w * w
    assert i == 1 or math.isclose(x, 1e6)
    gi = g0 - x * un - x * x * ut ** 2 / (2 * r)
    assert gi.min() == pytest.approx(0.0, abs=1e-15)
    assert (gi >= -1e-15).all()


@pytest.mark.slow
def test_concept4_friction_contact_linear_limit():
    """Concept 4 against a drum 2 um outside its outermost node, at low speed (small
    displacements): the non-linear contact force equals the linear fast path's (exact
    softening) to O(strain ~1e-4), with and without friction, while friction itself changes
    the force by percents: the two codes agree on the friction direction and magnitude."""
    from clutchfem.contact import DrumContact
    from clutchfem.core import rad_s_to_rpm
    from clutchfem.geometry import MeshSettings, get_concept
    from clutchfem.loadcase import LoadCase, sweep
    from clutchfem.mesh import mesh_concept

    c = get_concept("concept4")
    # both codes on the same mesh: their agreement does not depend on it.  Measured on the
    # default 1.2 mm mesh / on 3 mm: N non-linear / linear - 1 = -1.97e-4 / -2.08e-4 (mu 0),
    # -3.78e-4 / -3.78e-4 (mu 0.165); torque -3.78e-4 / -3.78e-4; friction +62.5 % / +62.5 %;
    # 38 s / 2.6 s of CPU
    cm = mesh_concept(c, c.Params(), MeshSettings(size=3e-3))
    fe = FEModel(cm, STEEL)
    probe = NonlinearModel(fe, drum_radius=0.0344)
    Rd = float(np.hypot(*probe.nodes.xy).max()) + 2e-6
    w = 300.0
    rows = {}
    for mu in (0.0, 0.165):
        nl = NonlinearModel(fe, drum_radius=Rd, mu=mu)
        st = nl.sweep([w / 2, w])[-1]
        case = LoadCase(fe, DrumContact(nl.nodes, mu, "ccw"), "exact")
        ref = sweep(case, [rad_s_to_rpm(w)], stresses=False)
        rows[mu] = (nl.normal_force(st), float(ref.curve["normal_force_N"].iloc[0]),
                    nl.torque(st), float(ref.curve["torque_Nm"].iloc[0]))
    print("\nconcept4 linear limit at %.0f rad/s: mu, N non-linear, N linear, ratio - 1" % w)
    for mu, r in rows.items():
        print("  %.3f %.6e %.6e %+.2e" % (mu, r[0], r[1], r[0] / r[1] - 1))
    for r in rows.values():
        assert abs(r[0] / r[1] - 1) < 1e-3
    assert abs(rows[0.165][2] / rows[0.165][3] - 1) < 1e-3
    assert abs(rows[0.165][1] / rows[0.0][1] - 1) > 0.01  # friction matters (minus shoe)


@pytest.mark.slow
def test_concept4_prestress_fast_path_matches_nonlinear_reference():
    """Concept 4 (default): the fast path with the centrifugal pre-stress stiffness
    (``PrestressRitz``, one factorisation) equals its per-speed factorisation to 1e-6 and the
    non-linear reference's engagement speed and normal force at 8000 rpm to 3e-3 (measured
    1e-3 and 2e-4), while the plain spin-softened fast path is off by 1.4 % and 3 %."""
    from clutchfem.core import rpm_to_rad_s
    from clutchfem.loadcase import Design, LoadCase, sweep
    from clutchfem.softening import PrestressedModel, PrestressRitz

    d = Design.from_concept("concept4")
    fast = sweep(LoadCase(d.model, d.contact(), PrestressRitz()), [8000.0])
    ref = sweep(LoadCase(PrestressedModel(d.model), d.contact(), "exact"), [8000.0])
    plain = sweep(d.case(softening="ritz"), [8000.0])  # spin softening only
    assert fast.engagement_rpm == pytest.approx(ref.engagement_rpm, rel=1e-6)
    assert fast.curve["normal_force_N"][0] == pytest.approx(ref.curve["normal_force_N"][0], rel=1e-6)
    nl = NonlinearModel(d.model, drum_radius=d.drum_radius, mu=d.op.mu)
    w_nl, _ = nl.engagement(rpm_to_rad_s(plain.engagement_rpm))
    st = nl.sweep([w_nl * 1.02, rpm_to_rad_s(6000.0), rpm_to_rad_s(8000.0)])[-1]
    N_nl = nl.normal_force(st)
    e_nl = w_nl * 30 / math.pi
    print(f"\nconcept4: engagement non-linear {e_nl:.1f} rpm, prestress fast path "
          f"{fast.engagement_rpm:.1f} ({fast.engagement_rpm / e_nl - 1:+.1e}), plain "
          f"{plain.engagement_rpm:.1f} ({plain.engagement_rpm / e_nl - 1:+.1e}); N(8000) non-linear {N_nl:.2f} N, "
          f"prestress {fast.curve['normal_force_N'][0]:.2f}, plain {plain.curve['normal_force_N'][0]:.2f}")
    assert fast.engagement_rpm == pytest.approx(e_nl, rel=3e-3)
    assert fast.curve["normal_force_N"][0] == pytest.approx(N_nl, rel=3e-3)
    assert abs(plain.engagement_rpm / e_nl - 1) > 0.01
