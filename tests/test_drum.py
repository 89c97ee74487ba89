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
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from clutchfem.drum import DrumWall, RingDrum, annulus_harmonic_compliance, lame_free_ring_expansion
from clutchfem.errors import ParameterError
from clutchfem.materials import get_material

RD = 0.0344


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
