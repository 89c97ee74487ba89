"""Verification model of the ring drum: a plane-stress scikit-fem annulus, meshed with gmsh,
whose harmonic compliances the curved-beam ring model (:mod:`.ring`) is checked against.

The annulus R_d <= r <= R_d + t of width b (P2, curved elements) is free; rigid-body modes
are removed by Lagrange multipliers (the loads are self-equilibrated for k != 1).  It is
loaded on its inner surface by the radial traction cos k theta and, separately, the
tangential traction sin k theta (per unit inner length); the cos k theta amplitude of the
inner wall's radial displacement, least-squares fitted on the node angles, is converted to
the ring's convention (load per unit centroid length, R_d / (R_d + t/2)).  It includes what
the ring leaves out (the local through-thickness squeeze under the load), which is why it
is the reference (tests/test_drum.py).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import gmsh
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, FacetBasis, LinearForm, asm
from skfem.helpers import ddot, sym_grad, trace

from ..geometry import gmsh_session
from ..mesh import load_user_geometry
from .ring import DrumWall

__all__ = ["annulus_harmonic_compliance"]


def annulus_harmonic_compliance(radius: float, wall: DrumWall, ks, size: float | None = None,
                                tmpdir=None) -> dict:
    """Verification model: a plane-stress P2 annulus R_d <= r <= R_d + t of width b
    (scikit-fem, curved elements), free, loaded on its inner surface by the radial traction
    cos k theta and, separately, the tangential traction sin k theta (per unit inner length);
    rigid-body modes removed by Lagrange multipliers (the loads are self-equilibrated for
    k != 1).  Returns per k the cos k theta amplitude of the inner wall's radial displacement,
    converted to the ring's convention (load per unit centroid length):
    {k: (a_k, b_k)} comparable with :meth:`~clutchfem.contact.RingDrum.harmonics`."""
    t, b = wall.wall_thickness, wall.width
    a_in, a_out = radius, radius + t
    size = size or t / 3
    d = Path(tmpdir or tempfile.mkdtemp())
    path = d / f"drum_{a_in:.6g}_{t:.6g}_{size:.6g}.msh"
    with gmsh_session("drum"):
        occ = gmsh.model.occ
        outer = occ.addDisk(0, 0, 0, a_out, a_out)
        inner = occ.addDisk(0, 0, 0, a_in, a_in)
        (surf,), _ = occ.cut([(2, outer)], [(2, inner)])
        occ.synchronize()
        bore, rim = [], []
        for _, c in gmsh.model.getBoundary([surf], oriented=False):
            xmin, ymin, _, xmax, ymax, _ = gmsh.model.getBoundingBox(1, abs(c))
            (bore if max(xmax, ymax) < 0.5 * (a_in + a_out) else rim).append(abs(c))
        gmsh.model.addPhysicalGroup(1, bore, name="bore")
        gmsh.model.addPhysicalGroup(1, rim, name="contact")
        gmsh.model.addPhysicalGroup(2, [surf[1]], name="solid")
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
        gmsh.model.mesh.generate(2)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        gmsh.write(str(path))
    cm = load_user_geometry(path, thickness=b)
    mesh = cm.mesh
    m = wall.material
    lam, mu = m.lame_plane_stress()
    basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=4)

    @BilinearForm
    def stiff(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return b * (2 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev))

    K = asm(stiff, basis).tocsr()
    X = basis.doflocs
    N = basis.N
    # rigid modes: x-, y-translation, rotation
    Rm = np.zeros((N, 3))
    Rm[0::2, 0] = 1.0
    Rm[1::2, 1] = 1.0
    Rm[0::2, 2] = -X[1, 0::2]
    Rm[1::2, 2] = X[0, 1::2]
    Rm /= np.linalg.norm(Rm, axis=0)
    A = sp.bmat([[K, sp.csr_matrix(Rm)], [sp.csr_matrix(Rm.T), None]], format="csc")
    lu = spla.splu(A)
    fb = FacetBasis(mesh, basis.elem, facets=cm.boundary("bore"), intorder=8)
    loads = []
    ks = [int(k) for k in ks]
    for k in ks:
        @LinearForm
        def radial(v, w, k=k):
            th = np.arctan2(w.x[1], w.x[0])
            return np.cos(k * th) * (np.cos(th) * v[0] + np.sin(th) * v[1])

        @LinearForm
        def tangential(v, w, k=k):
            th = np.arctan2(w.x[1], w.x[0])
            return np.sin(k * th) * (-np.sin(th) * v[0] + np.cos(th) * v[1])

        loads += [asm(radial, fb), asm(tangential, fb)]
    F = np.column_stack(loads)
    U = lu.solve(np.vstack([F, np.zeros((3, F.shape[1]))]))[:N]
    # radial displacement of the inner-wall nodes, projected on cos k theta
    dd = basis.get_dofs(cm.boundary("bore"))
    ix = np.concatenate([dd.nodal["u^1"], dd.facet["u^1"]])
    iy = ix + 1
    th = np.arctan2(X[1, ix], X[0, ix])
    order = np.argsort(th)
    th = th[order]
    out = {}
    scale = radius / (radius + t / 2)  # per unit inner length -> per unit centroid length
    for q, k in enumerate(ks):
        res = []
        for col in (2 * q, 2 * q + 1):
            u = U[:, col]
            ur = (np.cos(th) * u[ix[order]] + np.sin(th) * u[iy[order]])
            # least-squares amplitude of cos k theta on the (non-uniform) node angles
            basis_f = np.column_stack([np.cos(k * th), np.sin(k * th)] + ([np.ones_like(th)] if k else []))
            coef = np.linalg.lstsq(basis_f if k else np.ones((len(th), 1)), ur, rcond=None)[0]
            res.append(coef[0] / scale)
        out[k] = tuple(res)
    return out
