"""Peak stress refined where it governs (fe/peak.py): the convergence rate of the local
refinement at a fillet against Kirsch's closed form, Richardson's estimate, and the
converged peak of concept 4.

Kirsch (plate with a circular hole of radius a under uniaxial tension S along x, infinite
plate; Timoshenko & Goodier, Theory of Elasticity, 3rd ed., sec. 35), polar (r, theta):

    s_rr = S/2 (1 - a^2/r^2) + S/2 (1 - 4 a^2/r^2 + 3 a^4/r^4) cos 2 theta
    s_tt = S/2 (1 + a^2/r^2) - S/2 (1 + 3 a^4/r^4) cos 2 theta
    s_rt = -S/2 (1 + 2 a^2/r^2 - 3 a^4/r^4) sin 2 theta

so von Mises at (0, a) is 3 S (Kt = 3).  The quarter plate [0, 8a]^2 minus the hole has
symmetry conditions on x = 0 and y = 0 and the exact Kirsch traction on x = 8a and
y = 8a: the FE solution converges to Kirsch's field itself (no finite-width error).
"""

import math
import os
import tempfile

import gmsh
import meshio
import numpy as np
import pytest
from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, FacetBasis, LinearForm, asm, condense, solve
from skfem.helpers import ddot, sym_grad, trace
from skfem.io.meshio import from_meshio

from clutchfem.accuracy import extrapolated_peak
from clutchfem.core import ParameterError, get_material
from clutchfem.fe import p2_vertex_gradients, peak_stress_converged, richardson, von_mises
from clutchfem.geometry import MeshSettings, disc_size_field, get_concept, gmsh_session

A, L, S, E, NU = 1e-3, 8e-3, 100e6, 210e9, 0.3
LAM, MU = E * NU / (1 - NU ** 2), E / (2 * (1 + NU))


def _kirsch(x, y):
    r2 = x * x + y * y
    r = np.sqrt(r2)
    c, s = x / r, y / r
    c2, s2, q = c * c - s * s, 2 * s * c, A * A / r2
    srr = S / 2 * (1 - q) + S / 2 * (1 - 4 * q + 3 * q * q) * c2
    stt = S / 2 * (1 + q) - S / 2 * (1 + 3 * q * q) * c2
    srt = -S / 2 * (1 + 2 * q - 3 * q * q) * s2
    return (srr * c * c + stt * s * s - 2 * srt * s * c, srr * s * s + stt * c * c + 2 * srt * s * c,
            (srr - stt) * s * c + srt * (c * c - s * s))


def _mesh(size: float):
    """Quarter plate, 2 mm elements, a disc of radius a/2 at the hole's peak point (0, a)
    meshed at ``size`` by the same size field as MeshSettings.refine_* (geometry.disc_size_field)."""
    with gmsh_session("kirsch"):
        occ = gmsh.model.occ
        occ.cut([(2, occ.addRectangle(0, 0, 0, L, L))], [(2, occ.addDisk(0, 0, 0, A, A))])
        occ.synchronize()
        gmsh.model.mesh.field.setAsBackgroundMesh(disc_size_field(0.0, A, 0.5 * A, size, L / 4))
        gmsh.option.setNumber("Mesh.MeshSizeMax", L / 4)
        for k in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(k, 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(2)
        fd, tmp = tempfile.mkstemp(suffix=".msh")
        os.close(fd)
        gmsh.write(tmp)
    try:
        m = meshio.read(tmp)
    finally:
        os.unlink(tmp)
    return from_meshio(meshio.Mesh(m.points[:, :2], [c for c in m.cells if c.type == "triangle6"]))


def _peak_von_mises(size: float) -> tuple[float, np.ndarray]:
    m = _mesh(size)
    b = Basis(m, ElementVector(ElementTriP2()), intorder=4)
    K = asm(BilinearForm(lambda u, v, w: 2 * MU * ddot(sym_grad(u), sym_grad(v))
                         + LAM * trace(sym_grad(u)) * trace(sym_grad(v))), b)
    f = np.zeros(b.N)
    for axis in (0, 1):
        fb = FacetBasis(m, b.elem, facets=m.facets_satisfying(lambda x, a=axis: np.isclose(x[a], L)), intorder=6)

        def traction(v, w, a=axis):
            sxx, syy, sxy = _kirsch(w.x[0], w.x[1])
            tx, ty = (sxx, sxy) if a == 0 else (sxy, syy)
            return tx * v[0] + ty * v[1]

        f += asm(LinearForm(traction), fb)
    sym = [b.get_dofs(lambda x, a=a: np.isclose(x[a], 0.0)) for a in (0, 1)]
    D = np.concatenate([sym[0].nodal["u^1"], sym[0].facet["u^1"], sym[1].nodal["u^2"], sym[1].facet["u^2"]])
    u = solve(*condense(K, f, D=D))
    Gx, Gy, ex, ey, _ = p2_vertex_gradients(b)
    exx, eyy = np.einsum("evk,ek->ev", Gx, u[ex]), np.einsum("evk,ek->ev", Gy, u[ey])
    gxy = np.einsum("evk,ek->ev", Gy, u[ex]) + np.einsum("evk,ek->ev", Gx, u[ey])
    vm = von_mises(np.array([2 * MU * exx + LAM * (exx + eyy), 2 * MU * eyy + LAM * (exx + eyy), MU * gxy]))
    i = np.unravel_index(int(np.argmax(vm)), vm.shape)
    return float(vm[i]), m.p[:, m.t[i[1], i[0]]]


@pytest.mark.slow
def test_local_refinement_at_a_hole_converges_at_p2_rate_to_kirsch():
    """Local sizes a/16, a/32, a/64 (measured 2026-11-26: errors 5.5e-4, 1.4e-4, 3.3e-5 of
    3 S; observed orders 1.98, 2.07; a/4 and a/8 are pre-asymptotic, orders 0.7 and 1.3).
    P2 vertex stresses at a smooth boundary converge as h^2 (section 12: 1.86-2.27): the
    band 1.7-2.5 allows the unstructured meshes' not-exactly-halved sizes."""
    sizes = [A / 16, A / 32, A / 64]
    vals, at = zip(*(_peak_von_mises(s) for s in sizes))
    err = [abs(v / (3 * S) - 1) for v in vals]
    print("\nKirsch, vertex von Mises / 3 S - 1:", ", ".join(f"{v / (3 * S) - 1:+.2e}" for v in vals))
    assert all(np.allclose(x, [0.0, A], atol=1e-12) for x in at)  # the peak is at (0, a)
    orders = [math.log2(err[i] / err[i + 1]) for i in range(2)]
    assert all(1.7 <= p <= 2.5 for p in orders), orders
    assert err[-1] < 1e-4
    # Richardson's estimate from the three levels holds the true error, within 3x of it
    est, p = richardson(list(vals))
    true = abs(vals[-1] - 3 * S)
    assert true <= est <= 3 * true and 1.7 <= p <= 2.5
    # the best path's two-level extrapolation (accuracy.extrapolated_peak) holds its error
    ext, ext_err = extrapolated_peak(vals[0], vals[1])
    assert abs(ext - 3 * S) <= ext_err and abs(ext - 3 * S) < abs(vals[1] - 3 * S)


def test_richardson_exact_for_a_power_law_and_honest_when_not_monotone():
    v = [1.0 - 0.5 ** 2 * k for k in (1, 0.25, 0.0625)]  # v(h) = 1 - c h^2, h = 1, 1/2, 1/4
    est, p = richardson(v)
    assert p == pytest.approx(2.0) and est == pytest.approx(abs(1.0 - v[-1]))
    est, p = richardson([1.0, 1.1, 1.05])
    assert math.isnan(p) and est == pytest.approx(0.1)


@pytest.mark.slow
def test_concept4_peak_converged_in_its_notch_fillet():
    """Concept 4 at its defaults, best preset: the free-spin peak sits on the R 0.8 mm fillet
    at (26.94, -1.35) mm (where the slot meets the rim), and local refinement converges it
    (942.7 / 952.2 / 953.7 / 953.9 MPa at 4000 rpm, 2026-11-26), where refining every
    fillet arc alone did not (BENCHMARKS.md section 13)."""
    c = get_concept("concept4")
    r = peak_stress_converged(c, c.params(), MeshSettings.preset("best"), material=get_material("51CrV4"))
    assert r.converged and r.error <= 0.01 * r.peak
    assert "fillet R 0.80 mm" in r.feature
    assert np.hypot(r.at[0] - 26.94e-3, r.at[1] + 1.35e-3) < 0.1e-3
    # the best preset's own peak reads low by ~1.2 % (its discretisation error at this point)
    assert 0.0 < 1.0 - r.levels[0].peak / r.peak < 0.03
    # extrapolated from levels 0 and 1 (the best path's correction), the peak is within its
    # stated error of the converged one (955.3 +- 3.2 against 953.9 +- 0.05 MPa, 2026-11-26)
    ext, ext_err = extrapolated_peak(r.levels[0].peak, r.levels[1].peak)
    assert abs(ext - r.peak) <= ext_err + r.error
    assert r.levels[-1].elements < 20_000


@pytest.mark.parametrize("bad", [{"tol": 0.0}, {"tol": "1%"}, {"tol": True}, {"max_levels": 2}, {"material": None}])
def test_peak_refinement_refuses_bad_settings(bad):
    c = get_concept("concept4")
    kw = {"material": get_material("51CrV4"), **bad}
    with pytest.raises(ParameterError, match=next(iter(bad))):
        peak_stress_converged(c, c.params(), **kw)
