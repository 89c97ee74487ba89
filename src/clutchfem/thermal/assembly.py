"""The FE operators of the slip-heat model: scalar P2 on the clutch mesh, the part as a plate
with the temperature uniform through its axial thickness h (:func:`build_heat_model`).

Field equation
--------------
    rho c h dT/dt = div(k h grad T) - 2 h_f (T - T_amb)                 in the part
    -k h dT/dn    = h_b h (T - T_crank)                                  on the bore
    -k h dT/dn    = h_e h (T - T_amb)                                    on free edges
    -k h dT/dn    = -gamma q h                                           on the contact patch

h_f: convection coefficient of each face (both faces: 2 h_f), h_b: conductance of the
bore joint to the crankshaft at T_crank, h_e: convection on the free edges (0 by default;
the loaded contact facets never convect: they touch the drum; the bore and the sector cuts
are no free edges), q = mu p v the friction heat flux, gamma the part's share.  Units: SI,
temperatures in deg C (the equation is linear, only differences matter).

Weak form with scalar P2 (scikit-fem ``ElementTriP2`` on the curved ``MeshTri2``, the
same mesh and node numbering as the elastic model):

    M dT/dt + (K + H) T = f + Q,
    M = int rho c h phi_i phi_j,   K = int k h grad phi_i . grad phi_j,
    H = int 2 h_f phi_i phi_j + oint_bore h_b h phi_i phi_j + oint_edges h_e h phi_i phi_j,
    f = int 2 h_f T_amb phi_i + oint_bore h_b h T_crank phi_i + oint_edges h_e h T_amb phi_i.

Q is the heat load (:mod:`.load`).  **Cyclic sector.**  For a one-sector model
(``cut_a``/``cut_b``) the temperature at a node of cut_b equals that at its partner on cut_a
(a scalar: no rotation of the value): T = P a with a sparse map P (all nodes x independent
nodes, :func:`cyclic_map`); the full part needs none.  Energies are reported for the whole
part (sector values x ``HeatModel.scale`` = n_total / n_model).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTriP2, FacetBasis, LinearForm, asm
from skfem.helpers import dot, grad

from ..core import InputError, MeshError, ParameterError
from ..mesh import ClutchMesh, cyclic_pairing
from .params import ThermalEnvironment, ThermalMaterial, finite_positive

__all__ = ["HeatModel", "build_heat_model", "cyclic_map", "heat_basis"]


def heat_basis(cm: ClutchMesh) -> Basis:
    """The scalar P2 basis of the heat model on ``cm`` (quadrature order 4)."""
    return Basis(cm.mesh, ElementTriP2(), intorder=4)


@dataclass
class HeatModel:
    """Assembled scalar-P2 operators of one part (module docstring): M, K, the Robin
    matrices H_face, H_bore, H_edge with their right sides, and the cyclic map P."""

    cm: ClutchMesh
    thickness: float
    material: ThermalMaterial
    env: ThermalEnvironment
    basis: Basis
    M: sp.csr_matrix
    K: sp.csr_matrix
    H: dict  # name -> (matrix, rhs vector) for 'face', 'bore', 'edge'
    P: sp.csr_matrix
    scale: float  # whole part / model (n_shoes_total / n_shoes_model for a sector)
    timings: dict = field(default_factory=dict)

    @property
    def N(self) -> int:
        return self.basis.N

    @property
    def A(self) -> sp.csr_matrix:
        return (self.K + sum(m for m, _ in self.H.values())).tocsr()

    @property
    def f(self) -> np.ndarray:
        return sum(b for _, b in self.H.values())

    def node_zone(self) -> dict[str, np.ndarray]:
        """Scalar P2 nodes of each subdomain (nodes of its elements)."""
        out = {}
        ed = self.basis.element_dofs
        for name, elems in (self.cm.mesh.subdomains or {}).items():
            out[name] = np.unique(ed[:, np.asarray(elems)])
        return out


def cyclic_map(cm: ClutchMesh, basis: Basis) -> sp.csr_matrix:
    """T = P a: identity, except that every node of cut_b takes the value of its partner on
    cut_a (rotated by the sector angle, :func:`clutchfem.mesh.cyclic_pairing`); the full
    part gets the identity."""
    N = basis.N
    if cm.sector_angle is None:
        return sp.identity(N, format="csr")
    b = cm.mesh.boundaries or {}
    if "cut_a" not in b or "cut_b" not in b:
        raise MeshError(f"{cm.source}: a sector model needs boundary groups 'cut_a' and 'cut_b'")
    a_dofs = np.unique(basis.get_dofs(cm.boundary("cut_a")).all())
    b_dofs = np.unique(basis.get_dofs(cm.boundary("cut_b")).all())
    j = cyclic_pairing(basis.doflocs[:, a_dofs], basis.doflocs[:, b_dofs], cm.sector_angle,
                       scale=float(np.max(np.abs(basis.doflocs))), what=f"{cm.source}: the sector cut lines")
    slave, master = b_dofs[j], a_dofs
    keep = slave != master
    slave, master = slave[keep], master[keep]
    dep = np.zeros(N, dtype=bool)
    dep[slave] = True
    indep = np.nonzero(~dep)[0]
    col = -np.ones(N, dtype=np.int64)
    col[indep] = np.arange(len(indep))
    if np.any(col[master] < 0):
        raise MeshError(f"{cm.source}: a cut_a node is also a cut_b node of another pair")
    rows = np.concatenate([indep, slave])
    cols = np.concatenate([col[indep], col[master]])
    return sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(N, len(indep)))


def build_heat_model(cm: ClutchMesh, thickness: float, material: ThermalMaterial,
                     env: ThermalEnvironment, *, no_edge_nodes=None) -> HeatModel:
    """Assemble the operators of the plate heat equation on ``cm`` (module docstring).
    ``no_edge_nodes``: scalar nodes whose boundary facets never convect (the loaded contact
    patch); the cut lines of a sector and the bore never count as free edges."""
    t0 = time.perf_counter()
    h = finite_positive("thickness", thickness, "an axial thickness > 0 m (<= 0.2 m)")
    if h > 0.2:
        raise ParameterError("thickness", thickness, "an axial thickness > 0 m (<= 0.2 m)")
    if not isinstance(material, ThermalMaterial):
        raise InputError(f"material must be a ThermalMaterial (got {type(material).__name__})")
    if not isinstance(env, ThermalEnvironment):
        raise InputError(f"env must be a ThermalEnvironment (got {type(env).__name__})")
    mesh = cm.mesh
    b = mesh.boundaries or {}
    if "bore" not in b:
        raise MeshError(f"{cm.source}: no 'bore' boundary group (the joint to the crankshaft)")
    basis = heat_basis(cm)
    k, rc = material.conductivity, material.density * material.specific_heat
    M = asm(BilinearForm(lambda u, v, w: rc * h * u * v), basis).tocsr()
    K = asm(BilinearForm(lambda u, v, w: k * h * dot(grad(u), grad(v))), basis).tocsr()
    hf, Ta = env.face_htc, env.ambient_temperature
    H = {"face": (asm(BilinearForm(lambda u, v, w: 2.0 * hf * u * v), basis).tocsr(),
                  asm(LinearForm(lambda v, w: 2.0 * hf * Ta * v), basis))}

    def robin(facets, coef, Tinf):
        if len(facets) == 0 or coef == 0.0:
            return sp.csr_matrix((basis.N, basis.N)), np.zeros(basis.N)
        fb = FacetBasis(mesh, ElementTriP2(), facets=np.asarray(facets), intorder=5)
        return (asm(BilinearForm(lambda u, v, w: coef * h * u * v), fb).tocsr(),
                asm(LinearForm(lambda v, w: coef * h * Tinf * v), fb))

    bore = cm.boundary("bore")
    H["bore"] = robin(bore, env.bore_conductance, env.crankshaft_temperature)
    exclude = set(bore.tolist())
    for cut in ("cut_a", "cut_b"):
        if cut in b:
            exclude |= set(np.asarray(b[cut]).tolist())
    edges = np.array([f for f in mesh.boundary_facets() if f not in exclude], dtype=np.int64)
    if no_edge_nodes is not None and len(edges):
        fd = basis.facet_dofs[0, edges]  # mid-edge node of each facet
        ends = mesh.facets[:, edges]
        hot = np.isin(fd, no_edge_nodes) | (np.isin(ends[0], no_edge_nodes) & np.isin(ends[1], no_edge_nodes))
        edges = edges[~hot]
    H["edge"] = robin(edges, env.edge_htc, Ta)
    P = cyclic_map(cm, basis)
    scale = float(cm.sector_copies)
    return HeatModel(cm=cm, thickness=h, material=material, env=env, basis=basis, M=M, K=K, H=H,
                     P=P, scale=float(scale), timings={"assemble_s": time.perf_counter() - t0})
