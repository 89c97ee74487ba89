"""Three-dimensional linear elasticity of the spinning part: the 2-D mesh extruded through
the axial thickness into curved quadratic tetrahedra (scikit-fem ``MeshTet2``, P2).

Why 3-D
-------
The 2-D model assumes plane stress (s_zz = s_xz = s_yz = 0 everywhere: the thin limit) or
plane strain (e_zz = 0: the long-cylinder limit).  The clutch is an ~11 mm thick plate with
~2 mm thin flexures bent in their plane; neither limit is exact.  In the Saint-Venant
interior of a long flexure the beam bends with free anticlastic curvature (modulus E: the
plane-stress answer), but where it joins the hub and the shoe the thick neighbours restrain
the transverse strain e_zz over a length of about one axial thickness (plane-strain-like,
modulus E / (1 - nu^2)).  The 3-D model resolves this; ``benchmarks/bench_modelform.py``
measures how far each 2-D answer is from it.

Extrusion
---------
Every P2 triangle of the 2-D ``ClutchMesh`` becomes, per layer, a prism split into three
tetrahedra.  With the prism's vertices i < j < k (global 2-D numbers) at the bottom and
i' j' k' at the top, each quadrilateral side face (p, q, q', p'), p < q, is cut along the
diagonal p-q' (from the lower-numbered bottom vertex to the higher-numbered top vertex):
a rule that depends only on the two vertices of the shared edge, so neighbouring prisms cut
a shared face the same way (a conforming mesh).  The three tetrahedra are
(i, j, k, k'), (i, j, j', k'), (i, i', j', k').  In a full-thickness model the layers below
z = 0 take the mirror image of this split (the roles of bottom and top swapped; the shared
faces on z = 0 are triangles, so the halves still conform), so the mesh itself is
symmetric about the mid-plane and the half model is exactly its upper half.

The prism's geometry X(xi, eta, zeta) = x2(xi, eta) + z(zeta) e_z is quadratic in the
reference coordinates (x2 the curved P2 triangle map, z linear), and each tetrahedron is an
affine piece of the reference prism, so the P2 tetrahedra reproduce the curved extruded
prism *exactly* when every edge midpoint is X at the reference midpoint: the curved 2-D
edge midpoint for in-plane edges and for the diagonals of the side faces (at mid-layer
height), the straight midpoint for vertical edges.  No chord eats the 0.6 mm clearance.

Layers: ``layers`` through the modelled thickness, optionally graded towards the free face
z = h/2 (where the 3-D boundary layer of the in-plane stresses sits).

Mid-plane symmetry (``half=True``, the default)
-----------------------------------------------
The part, the bore clamp, the cyclic cuts, the centrifugal load (in-plane, z-independent),
the drum (a cylinder) and the full-slip friction (along e_theta) are all symmetric about
z = 0.  The linear problem has a unique solution, and its mirror image solves the same
problem, so the solution is symmetric: u_x, u_y even and u_z odd in z, hence u_z = 0 and
s_xz = s_yz = 0 on z = 0.  Modelling 0 <= z <= h/2 with u_z = 0 on z = 0 (the shear
tractions vanish there naturally) is therefore exact, not an approximation; the contact LCP
keeps a unique solution and so inherits the symmetry.  Operators are those of the physical
half: totals (forces, torques, mass) are ``symmetry_factor`` = 2 times the model's.  The
saving, measured on concept 4 (2 layers in the half, 4 in the full thickness, same mesh):
55725 vs 100305 unknowns, factorisation 1.6 s vs 6.7 s (CHOLMOD), assembly 2.0 s vs 4.1 s,
and the same centrifugal compliance to 2e-11 (``tests/test_fem3d.py`` checks the fields).

Operators (the 3-D twins of :mod:`clutchfem.fe.model`)
------------------------------------------------------
* ``K``  isotropic stiffness, lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu));
* ``M``  in-plane mass rho int (u_x v_x + u_y v_y): the spin-softening operator
  (the centrifugal load rho w^2 (x + u)_perp has no axial part);
* ``f1`` centrifugal load at w = 1 rad/s: rho int (x v_x + y v_y);
* ``T``  u = T a: clamped bore surface, u_z = 0 on the mid-plane (half model), cyclic
  u(cut_b) = R_z(2 pi / n) u(cut_a) (u_z copied).

Raw stresses (6 components, Voigt order xx, yy, zz, yz, xz, xy) at each tetrahedron's four
vertices; the P2 strain on a straight tetrahedron is linear, so its extremes sit at the
vertices and no averaging hides a peak.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from functools import cached_property
from typing import ClassVar

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTetP2, ElementVector, FacetBasis, LinearForm, MeshTet1, MeshTet2, asm

from ..core import Material, MeshError, ParamSet, SolverError, param
from ..mesh import ClutchMesh, cyclic_pairing, facet_numbers, named_boundary
from .model import ConstrainedOperators
from .stress import VertexStress3D, von_mises

__all__ = ["ExtrusionSettings", "ExtrudedMesh", "FEModel3D", "extrude", "build_fe_model_3d", "lame_3d"]

class ExtrusionSettings(ParamSet):
    """How the 2-D mesh is extruded through the axial thickness."""

    context: ClassVar[str] = "3-D extrusion"
    layers: int = param(2, "-", 1, 64, "element layers through the modelled thickness "
                        "(half the part with mid-plane symmetry)")
    half: bool = True
    grading: float = param(1.0, "-", 0.1, 1.0, "thickness of the layer at the free face / that "
                           "of the layer at the mid-plane (geometric grading; 1: uniform)")


@dataclass
class ExtrudedMesh:
    """A 2-D ``ClutchMesh`` extruded through the thickness (see module docstring).

    ``mesh`` carries boundaries ``bore``, ``contact``, ``contact_<i>``, ``cut_a``,
    ``cut_b`` (the side faces over the 2-D groups), ``top`` (z = h/2) and ``mid`` (z = 0,
    half model) or ``bottom`` (z = -h/2, full model); subdomains as in 2-D."""

    mesh: MeshTet2
    cm: ClutchMesh
    thickness: float
    layers: int
    half: bool
    z: np.ndarray  # (layers + 1,) vertex levels [m]
    vertex2d: np.ndarray  # (nverts3,) the 2-D vertex under each 3-D vertex
    level: np.ndarray  # (nverts3,) level index of each 3-D vertex

    @property
    def symmetry_factor(self) -> float:
        """Totals of the whole part / totals of the model (2 for the half model)."""
        return 2.0 if self.half else 1.0

    @property
    def sector_angle(self):
        return self.cm.sector_angle

    def boundary(self, name: str) -> np.ndarray:
        """The facets of boundary group ``name`` (:func:`clutchfem.mesh.named_boundary`)."""
        return named_boundary(self.mesh, name, f"extruded mesh of {self.cm.source}")


def _levels(h: float, layers: int, half: bool, grading: float) -> np.ndarray:
    """Vertex z levels: 0 .. h/2 (half) or -h/2 .. h/2, geometric grading towards the free
    face(s); ``grading`` = last / first layer thickness."""
    n = layers
    if half:
        r = grading ** (1.0 / max(n - 1, 1)) if n > 1 else 1.0
        w = r ** np.arange(n)
        return np.concatenate([[0.0], np.cumsum(w) / w.sum() * (h / 2)])
    if n % 2:  # odd: symmetric grading about a middle layer
        m = n // 2
        r = grading ** (1.0 / max(m, 1))
        w = r ** np.abs(np.arange(n) - m)
    else:
        m = n // 2
        r = grading ** (1.0 / max(m - 1, 1)) if m > 1 else 1.0
        half_w = r ** np.arange(m)
        w = np.concatenate([half_w[::-1], half_w])
    return np.concatenate([[0.0], np.cumsum(w) / w.sum() * h]) - h / 2


def extrude(cm: ClutchMesh, thickness: float | None = None,
            settings: ExtrusionSettings | None = None) -> ExtrudedMesh:
    """Extrude ``cm`` (curved ``MeshTri2``) into curved P2 tetrahedra (module docstring)."""
    s = settings or ExtrusionSettings()
    h = float(thickness if thickness is not None else (cm.thickness or 0.0))
    if not (h > 0 and math.isfinite(h)):
        raise SolverError("the axial thickness is unknown: give thickness (m) for a user mesh")
    m2 = cm.mesh
    nv = int(m2.nvertices)
    x2 = m2.doflocs  # vertices, then the (curved) midpoints of facets in m2.facets order
    z = _levels(h, s.layers, s.half, s.grading)
    nl = len(z)
    # vertices: level-major
    p3 = np.vstack([np.tile(x2[:, :nv], nl), np.repeat(z, nv)[None, :]])
    tri = np.sort(m2.t[:3], axis=0)  # i < j < k
    i, j, k = tri
    tets = []
    for lay in range(s.layers):
        o0, o1 = lay * nv, (lay + 1) * nv
        if not s.half and z[lay + 1] <= 1e-15 * h:  # below the mid-plane: the mirror image of
            o0, o1 = o1, o0  # the split above it, so the full mesh is symmetric about z = 0
        tets += [np.vstack([i + o0, j + o0, k + o0, k + o1]),
                 np.vstack([i + o0, j + o0, j + o1, k + o1]),
                 np.vstack([i + o0, i + o1, j + o1, k + o1])]
    t3 = np.hstack(tets)
    # positive orientation (skfem integrates |det J|, but keep the mesh tidy)
    a, b, c, d = (p3[:, t3[r]] for r in range(4))
    vol = np.einsum("ij,ij->j", np.cross(b - a, c - a, axis=0), d - a)
    flip = vol < 0
    t3[1, flip], t3[2, flip] = t3[2, flip].copy(), t3[1, flip].copy()
    lin = MeshTet1(np.ascontiguousarray(p3), np.ascontiguousarray(t3.astype(np.int64)))
    m3 = MeshTet2.from_mesh(lin)
    # exact curved edge midpoints
    nv3 = int(m3.nvertices)
    e = m3.edges
    va, vb = e[0] % nv, e[1] % nv
    la, lb = e[0] // nv, e[1] // nv
    mid = m3.doflocs.copy()
    inplane = va != vb
    f2 = facet_numbers(m2, va[inplane], vb[inplane])
    if (f2 < 0).any():  # (every in-plane edge of the extrusion is an edge of the 2-D mesh)
        raise MeshError(f"extrusion: {int((f2 < 0).sum())} in-plane edges are not edges of the 2-D mesh")
    cols = nv3 + np.nonzero(inplane)[0]
    mid[:2, cols] = x2[:, nv + f2]
    mid[2, cols] = 0.5 * (z[la[inplane]] + z[lb[inplane]])
    m3 = replace(m3, doflocs=mid)
    # boundaries: side faces over 2-D boundary groups; top/bottom/mid faces by level
    bf = m3.boundary_facets()
    fv = m3.facets[:, bf]
    lv = fv // nv
    vv = fv % nv
    horiz = (lv[0] == lv[1]) & (lv[1] == lv[2])
    bnd: dict[str, np.ndarray] = {}
    top = bf[horiz & (lv[0] == nl - 1)]
    low = bf[horiz & (lv[0] == 0)]
    bnd["top"] = top
    bnd["mid" if s.half else "bottom"] = low
    side = ~horiz
    sv = np.sort(vv[:, side], axis=0)
    # a vertical face has two distinct 2-D vertices: the 2-D edge (lowest, highest)
    e2 = facet_numbers(m2, sv[0], sv[2])
    if np.any(e2 < 0):
        raise MeshError(f"extrusion of {cm.source}: a side face matches no 2-D edge")
    face_of_f2 = {}
    for name, facets2 in (m2.boundaries or {}).items():
        mark = np.zeros(m2.facets.shape[1], dtype=bool)
        mark[np.asarray(facets2)] = True
        face_of_f2[name] = bf[side][mark[e2]]
    bnd.update(face_of_f2)
    m3 = m3.with_boundaries(bnd)
    if m2.subdomains:
        ne = m2.t.shape[1]
        sub = {}
        for name, el in m2.subdomains.items():
            el = np.asarray(el)
            sub[name] = np.concatenate([el + q * ne for q in range(3 * s.layers)])
        m3 = m3.with_subdomains(sub)
    vertex2d = np.arange(nv3) % nv
    level = np.arange(nv3) // nv
    return ExtrudedMesh(mesh=m3, cm=cm, thickness=h, layers=s.layers, half=s.half, z=z,
                        vertex2d=vertex2d, level=level)


def lame_3d(material: Material) -> tuple[float, float]:
    """Three-dimensional Lame pair (lambda, mu)."""
    E, nu = material.E, material.nu
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


class FEModel3D(ConstrainedOperators):
    """Assembled 3-D operators of one extruded part (module docstring).  The same interface
    as the 2-D :class:`clutchfem.fe.FEModel` (``cm, material, thickness, formulation,
    basis, K, f1, T, M, Kr, Mr, factor, solve, u1, stress, ndofs, timings``), so the contact,
    friction, spin-softening and sweep machinery runs on it unchanged; plus ``em`` (the
    extruded mesh) and ``symmetry_factor`` (totals / model); its contact nodes come from
    :func:`clutchfem.contact.contact_nodes`.

    ``slide_z``: extra faces with u_z = 0 (``('top',)`` turns the half model into plane
    strain: the verification of tests/test_fem3d.py)."""

    formulation = "3d"

    def __init__(self, cm: ClutchMesh, material: Material, thickness: float | None = None, *,
                 settings: ExtrusionSettings | None = None, solver=None,
                 slide_z: tuple[str, ...] = ()):
        t0 = time.perf_counter()
        self.cm = cm
        self.material = material
        self.settings = settings or ExtrusionSettings()
        self.solver = solver
        self.timings: dict[str, float] = {}
        self.em = extrude(cm, thickness, self.settings)
        self.thickness = self.em.thickness
        t1 = time.perf_counter()
        self.basis = Basis(self.em.mesh, ElementVector(ElementTetP2()), intorder=4)
        self._sb = self.basis.with_element(ElementTetP2())
        off = np.array([[0], [1], [2]])
        if not (np.array_equal(self.basis.nodal_dofs, 3 * self._sb.nodal_dofs + off)
                and np.array_equal(self.basis.edge_dofs, 3 * self._sb.edge_dofs + off)):  # pragma: no cover
            raise SolverError("unexpected scikit-fem dof layout for ElementVector(ElementTetP2)")
        lam, mu = self.lame
        rho = material.rho
        self.K = _stiffness(self._sb, lam, mu)

        @LinearForm
        def centrifugal(v, w):
            return rho * (w.x[0] * v[0] + w.x[1] * v[1])

        self.f1 = asm(centrifugal, self.basis)
        t2 = time.perf_counter()
        self.T = constraint_map_3d(self.em, self.basis, slide_z)
        self.timings.update({"extrude_s": t1 - t0, "assemble_s": t2 - t1,
                             "constraints_s": time.perf_counter() - t2})

    # -- material law -------------------------------------------------------------------
    @property
    def lame(self) -> tuple[float, float]:
        return lame_3d(self.material)

    @property
    def symmetry_factor(self) -> float:
        return self.em.symmetry_factor

    def boundary(self, name: str) -> np.ndarray:
        """Facets of boundary group ``name`` of the extruded mesh (the 2-D groups' side faces)."""
        return self.em.boundary(name)

    # -- operators ----------------------------------------------------------------------
    @cached_property
    def M(self) -> sp.csr_matrix:
        """In-plane mass rho int (u_x v_x + u_y v_y) (spin softening); on first use."""
        t0 = time.perf_counter()
        rho = self.material.rho

        @BilinearForm
        def mass(u, v, w):
            return rho * u * v

        M = sp.kron(asm(mass, self._sb), sp.diags([1.0, 1.0, 0.0]), format="csr")
        M.eliminate_zeros()
        self.timings["mass_s"] = time.perf_counter() - t0
        return M

    # -- post-processing ----------------------------------------------------------------
    @cached_property
    def stress(self) -> VertexStress3D:
        return VertexStress3D(self)

    def vertex_stresses(self, U: np.ndarray) -> np.ndarray:
        return self.stress(U)

    @property
    def vertex_points(self) -> np.ndarray:
        return self.stress.points

    def von_mises(self, s: np.ndarray) -> np.ndarray:
        return von_mises(s)

    def max_von_mises(self, u: np.ndarray) -> tuple[float, np.ndarray]:
        """(peak raw vertex von Mises stress [Pa], its position (3,))."""
        vm = von_mises(self.stress(u))
        k = int(np.argmax(vm))
        return float(vm[k]), self.stress.points[:, k]


def build_fe_model_3d(cm: ClutchMesh, material: Material, thickness: float | None = None,
                      settings: ExtrusionSettings | None = None, **kw) -> FEModel3D:
    """Extrude ``cm`` and assemble its 3-D model (:class:`FEModel3D`)."""
    return FEModel3D(cm, material, thickness, settings=settings, **kw)


def _stiffness(sb: Basis, lam: float, mu: float) -> sp.csr_matrix:
    """Isotropic stiffness on the vector P2 space of the scalar basis ``sb`` (dof 3 k + a),
    vectorised: with S_ab[k, l] = int d_a phi_k d_b phi_l (all elements at once),

        K[(k, a), (l, b)] = mu delta_ab sum_c S_cc[k, l] + mu S_ba[k, l] + lam S_ab[k, l],

    the entry of int 2 mu eps(u) : eps(v) + lam div u div v for u = phi_l e_b, v = phi_k e_a
    (S as one batched product A diag(dx) A', A = grad phi).
    Same matrix as ``asm`` of that form (checked in tests/test_fem3d.py), ~20x faster."""
    nb = sb.Nbfun
    G = np.stack([sb.basis[k][0].grad for k in range(nb)])  # (nb, 3, ne, nq)
    ne = G.shape[2]
    # A[e, (k, a), q] = d_a phi_k: S = A diag(dx) A' is one batched matrix product (the
    # 11-point tetrahedron rule has a negative weight: no square roots)
    A = G.transpose(2, 0, 1, 3).reshape(ne, 3 * nb, -1)
    S = ((A * sb.dx[:, None, :]) @ A.transpose(0, 2, 1)).reshape(ne, nb, 3, nb, 3)  # S[e, k, a, l, b]
    lap = S[:, :, 0, :, 0] + S[:, :, 1, :, 1] + S[:, :, 2, :, 2]
    Ke = lam * S + mu * S.transpose(0, 1, 4, 3, 2)
    for a in range(3):
        Ke[:, :, a, :, a] += mu * lap
    Ke = Ke.reshape(ne, 3 * nb, 3 * nb)  # rows 3 k + a
    ed = sb.element_dofs  # (nb, ne)
    dofs = (3 * ed.T[:, :, None] + np.arange(3)[None, None, :]).reshape(len(Ke), -1)
    r = np.repeat(dofs, 3 * nb, axis=1).ravel()
    c = np.tile(dofs, (1, 3 * nb)).ravel()
    N = 3 * sb.N
    return sp.coo_matrix((Ke.ravel(), (r, c)), shape=(N, N)).tocsr()


def geometric_stiffness_3d(model: "FEModel3D", u: np.ndarray) -> sp.csr_matrix:
    """Geometric stiffness of the (linear) pre-stress sigma(u): int sigma : (grad du' grad v)
    over the modelled volume, K[(k, c), (l, c)] = int sigma_ab d_a phi_k d_b phi_l."""
    sb = model._sb
    lam, mu = model.lame
    g = model.basis.interpolate(u).grad  # (3, 3, ne, nq): d u_i / d x_j
    eps = 0.5 * (g + g.transpose(1, 0, 2, 3))
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    sig = 2 * mu * eps + lam * tr[None, None] * np.eye(3)[:, :, None, None]
    nb = sb.Nbfun
    G = np.stack([sb.basis[k][0].grad for k in range(nb)])  # (nb, 3, ne, nq)
    SG = np.einsum("abeq,lbeq->aleq", sig * sb.dx[None, None], G)  # (3, nb, ne, nq)
    kg = np.einsum("kaeq,aleq->ekl", G, SG)  # (ne, nb, nb)
    Ke = np.zeros((len(kg), nb, 3, nb, 3))
    for c in range(3):
        Ke[:, :, c, :, c] = kg
    Ke = Ke.reshape(len(kg), 3 * nb, 3 * nb)
    ed = sb.element_dofs
    dofs = (3 * ed.T[:, :, None] + np.arange(3)[None, None, :]).reshape(len(Ke), -1)
    r = np.repeat(dofs, 3 * nb, axis=1).ravel()
    c_ = np.tile(dofs, (1, 3 * nb)).ravel()
    N = 3 * sb.N
    return sp.coo_matrix((Ke.ravel(), (r, c_)), shape=(N, N)).tocsr()


def component_dofs(basis: Basis, facets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    d = basis.get_dofs(facets)
    return tuple(np.asarray(d.all(f"u^{c}"), dtype=np.int64) for c in (1, 2, 3))


def constraint_map_3d(em: ExtrudedMesh, basis: Basis,
                      slide_z: tuple[str, ...] = ()) -> sp.csr_matrix:
    """Sparse T (ndofs x nindep), u = T a: clamped bore surface, u_z = 0 on the mid-plane
    (half model) and on the faces named in ``slide_z`` (e.g. ``('top',)``: the plane-strain
    verification), cyclic u(cut_b) = R_z u(cut_a) with u_z copied."""
    N = basis.N
    fixed = np.unique(basis.get_dofs(em.boundary("bore")).all())
    for name in (("mid",) if em.half else ()) + tuple(slide_z):
        fixed = np.union1d(fixed, component_dofs(basis, em.boundary(name))[2])
    rows, cols_, vals = [], [], []
    slaves = np.zeros(0, dtype=np.int64)
    links = []  # (slave dof, master dofs, coefficients)
    if em.sector_angle is not None:
        ax, ay, az = component_dofs(basis, em.boundary("cut_a"))
        bx, by, bz = component_dofs(basis, em.boundary("cut_b"))
        c, s = math.cos(em.sector_angle), math.sin(em.sector_angle)
        idx = cyclic_pairing(basis.doflocs[:, ax], basis.doflocs[:, bx], em.sector_angle,
                             scale=float(np.max(np.abs(basis.doflocs))),
                             what=f"{em.cm.source}: the extruded sector cut faces")
        bx, by, bz = bx[idx], by[idx], bz[idx]
        isf = np.zeros(N, dtype=bool)
        isf[fixed] = True
        clamp_xy = isf[ax] | isf[ay] | isf[bx] | isf[by]
        clamp_z = isf[az] | isf[bz]
        fixed = np.unique(np.concatenate([fixed, ax[clamp_xy], ay[clamp_xy], bx[clamp_xy],
                                          by[clamp_xy], az[clamp_z], bz[clamp_z]]))
        k = ~clamp_xy
        links += [(bx[k], [ax[k], ay[k]], [c, -s]), (by[k], [ax[k], ay[k]], [s, c])]
        kz = ~clamp_z
        links += [(bz[kz], [az[kz]], [1.0])]
        slaves = np.concatenate([bx[k], by[k], bz[kz]])
    dependent = np.zeros(N, dtype=bool)
    dependent[fixed] = True
    dependent[slaves] = True
    indep = np.nonzero(~dependent)[0]
    col = -np.ones(N, dtype=np.int64)
    col[indep] = np.arange(len(indep))
    rows, cols_, vals = [indep], [col[indep]], [np.ones(len(indep))]
    for sl, masters, coef in links:
        for mdofs, cf in zip(masters, coef):
            rows.append(sl)
            cols_.append(col[mdofs])
            vals.append(np.full(len(sl), cf))
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols_))),
                      shape=(N, len(indep)))
    if np.any(np.concatenate(cols_) < 0):
        raise MeshError(f"{em.cm.source}: a cyclic master dof is itself constrained")
    return T


def contact_area_weights(em: ExtrudedMesh, basis: Basis, facets: np.ndarray) -> np.ndarray:
    """int phi_i dA over the given side faces for every dof (length N; the x, y, z dofs of a
    node are equal): the tributary area of each P2 node, to turn forces into pressures."""
    fb = FacetBasis(em.mesh, basis.elem, facets=facets, intorder=6)

    @LinearForm
    def area(v, w):
        return v[0] + v[1] + v[2]

    return asm(area, fb)
