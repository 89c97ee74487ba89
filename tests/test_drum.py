"""Verification of the elastic drum, :mod:`clutchfem.drum`.

* Ring harmonics (curved Timoshenko beam) against a condensed scikit-fem annulus (plane
  stress, P2, curved, the same wall): per harmonic k, the inner wall's radial response to a
  radial cos k theta and a tangential sin k theta line load.  A 0.5 mm wall agrees to < 1e-3;
  the default 2 mm wall on R_d = 34.4 mm to < 1.5 % for the harmonics that carry the load
  pattern of three shoes (k = 3, 6, 9), the difference growing with k (the ring misses the
  local through-thickness squeeze of 2-D elasticity).
* Textbook ring (Roark, thin inextensible ring, two equal outward forces P on a diameter):
  the diameter along the loads grows by (pi/4 - 2/pi) P R^3 / EI and the one across them
  shrinks by (2/pi - 1/2) P R^3 / EI... with our sign: u_r(90 deg) = -(1/pi - 1/4) P R^3/EI.
* Cyclic condensation: the n-fold compliance equals the sum of the single-load compliance
  over the n rotated copies; C_rr is symmetric positive semi-definite.
* Spinning drum: the free rotating annulus's inner-wall expansion (Lame) tends to the thin
  ring's rho w^2 R^3 / E.
* In the contact problem (core ``LoadCase``, LCP matrix G + C_d, gaps opened by the spinning
  drum's expansion): the clamped annulus pressed on an elastic ring has the closed form
  N = (u_free - u_d - c) / (s_clutch + a_0 / (2 pi R_c)); the non-linear reference with the
  same drum tends to the linear answer like the strain.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from clutchfem.contact import DrumWall, RingDrum, annulus_harmonic_compliance, lame_free_ring_expansion
from clutchfem.core import Material, ParameterError, get_material

RD = 0.0344


@pytest.mark.slow
@pytest.mark.parametrize("t, ks, tol", [(0.5e-3, (0, 2, 3, 6), 1e-3), (2e-3, (0, 3, 6, 9), 1.5e-2)])
def test_ring_harmonics_match_fe_annulus(tmp_path, t, ks, tol):
    wall = DrumWall(wall_thickness=t)
    a, b = RingDrum(RD, wall).harmonics(ks)
    fe = annulus_harmonic_compliance(RD, wall, ks, size=t / 3, tmpdir=tmp_path)
    print(f"\nwall {t * 1e3:.1f} mm: k, a_k ring, FE / ring - 1, b_k ring, FE / ring - 1")
    for i, k in enumerate(ks):
        rb = fe[k][1] / b[i] - 1 if b[i] else float("nan")
        print(f"  {k:3d} {a[i]:.4e} {fe[k][0] / a[i] - 1:+.2e} {b[i]:+.4e} {rb:+.2e}")
        assert abs(fe[k][0] / a[i] - 1) < tol
        if b[i]:
            assert abs(fe[k][1] / b[i] - 1) < tol


def test_ring_matches_roark_diametral_pull():
    wall = DrumWall(wall_thickness=0.2e-3, shear=False)
    ring = RingDrum(RD, wall)
    Crr, Crt = ring.compliance(np.array([0.0, math.pi / 2]), n=2)
    ref = ring.Rc ** 3 / ring.EI
    along, across = Crr[0, 0] / ref, Crr[1, 0] / ref
    print(f"\nRoark diametral pull: u_r(0) {along:.6f} (pi/8 - 1/pi = {math.pi / 8 - 1 / math.pi:.6f}), "
          f"u_r(90) {across:.6f} (-(1/pi - 1/4) = {-(1 / math.pi - 0.25):.6f}) P R^3/EI")
    # extensibility adds O((t / R)^2 ~ 3e-5); the series is truncated at k = 800 (~1e-9)
    assert along == pytest.approx(math.pi / 8 - 1 / math.pi, rel=2e-4)
    assert across == pytest.approx(-(1 / math.pi - 0.25), rel=2e-4)
    # a radial-only pattern symmetric about each load: no radial response to the tangential
    # part at the load point itself
    assert abs(Crt[0, 0]) < 1e-12 * Crr[0, 0]


def test_cyclic_compliance_is_the_sum_over_copies():
    ring = RingDrum(RD)
    rng = np.random.default_rng(3)
    ang = rng.uniform(0.1, 1.9, 5)
    arc = np.full(5, 0.01)
    n = 3
    Crr3, Crt3 = ring.compliance(ang, n, arc)
    # single-load compliance with every copy listed (n = 1 with 3 x the nodes)
    allang = np.concatenate([ang + 2 * math.pi * p / n for p in range(n)])
    Crr1, Crt1 = ring.compliance(allang, 1, np.tile(arc, n))
    m = len(ang)
    S = sum(Crr1[:m, p * m:(p + 1) * m] for p in range(n))
    St = sum(Crt1[:m, p * m:(p + 1) * m] for p in range(n))
    # n = 1 keeps k = 1 out (bearing) as n = 3 does; the two sums differ only by their
    # truncation (k <= 400 vs k <= 1200): 1.9e-6 measured
    assert np.abs(S - Crr3).max() < 5e-6 * np.abs(Crr3).max()
    assert np.abs(St - Crt3).max() < 5e-6 * np.abs(Crt3).max()
    assert np.allclose(Crr3, Crr3.T, rtol=0, atol=1e-12 * np.abs(Crr3).max())
    assert np.linalg.eigvalsh(0.5 * (Crr3 + Crr3.T)).min() > -1e-12 * np.abs(Crr3).max()


def test_spinning_drum_expansion_thin_limit_and_held():
    steel = get_material("51CrV4")
    w = 1000.0
    thin = lame_free_ring_expansion(steel, RD, RD + 1e-5, w)
    assert thin == pytest.approx(steel.rho * w * w * RD ** 3 / steel.E, rel=1e-3)
    assert RingDrum(RD, DrumWall(state="held")).free_expansion(w) == 0.0
    assert RingDrum(RD, DrumWall(state="spinning")).free_expansion(w) > 0.0


def test_refuses_bad_input():
    with pytest.raises(ParameterError, match="wall_thickness"):
        DrumWall(wall_thickness=-1e-3)
    with pytest.raises(ParameterError, match="state"):
        DrumWall(state="rolling")
    with pytest.raises(ParameterError, match="wall_thickness"):
        RingDrum(0.01, DrumWall(wall_thickness=8e-3))
    with pytest.raises(ParameterError, match="drum_radius"):
        RingDrum(-1.0)


# ---------------------------------------------------------------------------------------
# the elastic drum in the contact problem (core LoadCase) and in the non-linear reference
# ---------------------------------------------------------------------------------------
A_IN, B_OUT, H = 6.5e-3, 33.8e-3, 11e-3


def _lame_annulus(mat, omega, rim_pressure, a=A_IN, b=B_OUT):
    """Plane-stress annulus, u(a) = 0, sigma_r(b) = -rim_pressure: u(b)."""
    E, nu, rho = mat.E, mat.nu, mat.rho
    D = E / (1 - nu * nu)
    C = rho * omega ** 2 / D
    f = [lambda r: r, lambda r: 1 / r, lambda r: -C * r ** 3 / 8]
    df = [lambda r: 1.0, lambda r: -1 / r ** 2, lambda r: -3 * C * r ** 2 / 8]
    sr = lambda i, r: D * (df[i](r) + nu * f[i](r) / r)  # noqa: E731
    A, B = np.linalg.solve([[f[0](a), f[1](a)], [sr(0, b), sr(1, b)]], [-f[2](a), -rim_pressure - sr(2, b)])
    return A * f[0](b) + B * f[1](b) + f[2](b)


@pytest.mark.parametrize("state", ["held", "spinning"])
def test_annulus_on_elastic_drum_closed_form(tmp_path, state):
    """A 30 degree sector of the clamped annulus pressed on an elastic drum (the whole rim
    touches; friction on): the LCP with G + C_d and the drum's free expansion gives the
    closed form N = (u_free(w) - u_d(w) - c) / (s_clutch + a_0 / (2 pi R_c)) (Lame for the
    annulus under rim pressure, the drum's k = 0 compliance a_0; the cyclic harmonics of the
    discrete nodal loads add ~1e-4), and the non-linear reference with the same drum agrees
    in the small-strain limit."""
    from clutchfem.contact import DrumContact, contact_nodes
    from clutchfem.core import rad_s_to_rpm
    from clutchfem.fe import FEModel
    from clutchfem.loadcase import LoadCase, sweep
    from support.shapes import load_annulus

    steel = get_material("51CrV4")
    c, mu, w = 0.2e-3, 0.3, 3.5e4
    Rd = B_OUT + c
    cm = load_annulus(tmp_path / "sec.msh", A_IN, B_OUT, 2e-3, thickness=H, sector_deg=30.0)
    fe = FEModel(cm, steel, H)
    nodes = contact_nodes(fe, Rd)
    # (a steel drum spinning at 3.5e4 rad/s would expand 2 mm, more than the clamped annulus,
    # and lose contact: the spinning case takes a drum 100 x lighter)
    drum_mat = steel if state == "held" else Material(name="light", E=steel.E, nu=0.3, rho=steel.rho / 100)
    ring = RingDrum(Rd, DrumWall(wall_thickness=2e-3, state=state, material=drum_mat))
    rigid = sweep(LoadCase(fe, DrumContact(nodes, mu, "ccw"), "off"), [rad_s_to_rpm(w)])
    res = sweep(LoadCase(fe, DrumContact(nodes, mu, "ccw", drum=ring, sectors=12), "off"), [rad_s_to_rpm(w)])
    u_free = _lame_annulus(steel, w, 0.0)
    s_c = -(_lame_annulus(steel, 0.0, 1.0) - _lame_annulus(steel, 0.0, 0.0)) / (2 * math.pi * B_OUT * H)
    a0 = ring.harmonics([0])[0][0]
    ud = ring.free_expansion(w)
    N_cf = (u_free - ud - c) / (s_c + a0 / (2 * math.pi * ring.Rc))
    N_rigid_cf = (u_free - c) / s_c
    N, Nr = float(res.curve["normal_force_N"][0]), float(rigid.curve["normal_force_N"][0])
    print(f"\nelastic drum ({state}): N {N:.6e} (closed form {N_cf:.6e}, {N / N_cf - 1:+.1e}); rigid drum "
          f"{Nr:.6e} ({Nr / N_rigid_cf - 1:+.1e}); drum softens the contact by {1 - N / Nr:.2%}")
    assert N == pytest.approx(N_cf, rel=5e-4)
    assert Nr == pytest.approx(N_rigid_cf, rel=5e-4)
    assert N < Nr
    assert N > 0


@pytest.mark.slow
def test_nonlinear_reference_with_elastic_drum_linear_limit(tmp_path):
    """The non-linear reference with an elastic drum (C_d in its bordered Newton system, the
    drum's free expansion in its gaps) tends to the linear path with the same physics (spin
    softening exact) in the small-strain limit: with E x s and the clearance / s the forces
    stay those of a steel clutch while the strains drop s-fold, and so must the difference
    (measured: 5.7e-2 at s = 1, 6e-3 at s = 10, 1.5e-3 at s = 40)."""
    from clutchfem.accuracy import NonlinearModel
    from clutchfem.contact import DrumContact, contact_nodes
    from clutchfem.core import rad_s_to_rpm
    from clutchfem.fe import FEModel
    from clutchfem.loadcase import LoadCase, sweep
    from support.shapes import load_annulus

    steel = get_material("51CrV4")
    mu, w = 0.3, 3.5e4
    cm = load_annulus(tmp_path / "sec.msh", A_IN, B_OUT, 2e-3, thickness=H, sector_deg=30.0)
    rows = []
    for scale in (10.0, 40.0):
        c = 0.2e-3 / scale
        Rd = B_OUT + c
        stiff = Material(name="steel x s", E=scale * steel.E, nu=0.3, rho=steel.rho)
        light = Material(name="light drum", E=scale * steel.E, nu=0.3, rho=steel.rho / 100)
        fe = FEModel(cm, stiff, H)
        nodes = contact_nodes(fe, Rd)
        for state, mat in (("held", stiff), ("spinning", light)):
            ring = RingDrum(Rd, DrumWall(wall_thickness=2e-3, state=state, material=mat))
            dc = DrumContact(nodes, mu, "ccw", drum=ring, sectors=12)
            lin = sweep(LoadCase(fe, dc, "exact"), [rad_s_to_rpm(w)])
            Nx = float(lin.curve["normal_force_N"][0])
            nl = NonlinearModel(fe, drum_radius=Rd, mu=mu, drum_compliance=dc.drum_compliance)
            nl.drum_free = np.full(nodes.m, ring.free_expansion(w))
            st = nl.sweep([w / 2, w])[-1]
            rows.append((scale, state, nl.normal_force(st), Nx, nl.normal_force(st) / Nx - 1))
    print("\nnon-linear reference with an elastic drum: scale, state, N non-linear, N linear")
    for r in rows:
        print("  %4.0f %-8s %.6e %.6e (%+.1e)" % r)
    d = {(r[0], r[1]): r[4] for r in rows}
    for state in ("held", "spinning"):
        assert abs(d[(40.0, state)]) < 2.5e-3
        assert 3.0 < d[(10.0, state)] / d[(40.0, state)] < 5.0  # O(strain)
