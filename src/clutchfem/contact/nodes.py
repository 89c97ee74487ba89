"""Contact nodes: the P2 nodes of the ``contact`` boundary facing the drum circle, with their
exact initial gaps, normals, tangents, shoes and (lazily) tributary weights, for the 2-D and
the extruded 3-D model alike.

Node i at x_i has the exact initial gap g0_i = R_d - |x_i| and outward normal n_i = x_i/|x_i|
(the drum's, evaluated on the exact circle, so a coarse chord does not eat the 0.6 mm
clearance); on a one-sector model a node on cut_b is the rotated copy of one on cut_a and
is merged with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from ..core import MeshError, ParameterError, wrap_angle
from ..fe import FEModel3D, component_dofs, contact_area_weights, contact_weights


@dataclass(frozen=True, eq=False)
class ContactNodes:
    """The m candidate contact nodes of a model and the drum circle they face (read-only)."""

    drum_radius: float
    dof_x: np.ndarray  # (m,) x dof of each node
    dof_y: np.ndarray  # (m,) y dof
    xy: np.ndarray  # (2, m) positions [m]
    normal: np.ndarray  # (2, m) outward unit normals
    tangent: np.ndarray  # (2, m) e_theta (ccw)
    gap0: np.ndarray  # (m,) initial gaps [m]
    shoe: np.ndarray  # (m,) index of the shoe the node belongs to
    angle: np.ndarray  # (m,) polar angle [rad]
    ndofs: int
    _weights: object = None  # callable () -> (m,), evaluated once on first use

    @property
    def m(self) -> int:
        return len(self.gap0)

    @cached_property
    def weight(self) -> np.ndarray:
        """(m,) tributary length int phi_i ds [m] of each node (pressure = force / (h weight));
        computed on first use: only pressure output needs it."""
        return np.asarray(self._weights())

    @cached_property
    def shoes(self) -> list[int]:
        return sorted(set(self.shoe.tolist()))

    @cached_property
    def by_arc(self) -> np.ndarray:
        """Node indices sorted by shoe, then by polar angle unwrapped around the shoe."""
        ang = self.angle.copy()
        for s_ in self.shoes:
            sel = self.shoe == s_
            ang[sel] = wrap_angle(ang[sel], float(np.angle(np.exp(1j * ang[sel]).mean())))
        return np.lexsort((ang, self.shoe))

    @cached_property
    def normal_load(self) -> sp.csc_matrix:
        """N (ndofs x m): unit compressive force along -n_i at node i."""
        return self._load(-self.normal)

    @cached_property
    def tangent_load(self) -> sp.csc_matrix:
        """Tt (ndofs x m): unit force along -t_i at node i (friction direction for s = +1)."""
        return self._load(-self.tangent)

    def _load(self, vec: np.ndarray) -> sp.csc_matrix:
        m = self.m
        return sp.csc_matrix((np.concatenate([vec[0], vec[1]]),
                              (np.concatenate([self.dof_x, self.dof_y]), np.concatenate([np.arange(m)] * 2))),
                             shape=(self.ndofs, m))

    def normal_displacement(self, U: np.ndarray) -> np.ndarray:
        """B U: outward normal displacement at the nodes (rows) of U's column(s)."""
        U = np.asarray(U)
        if U.ndim == 1:
            return self.normal[0] * U[self.dof_x] + self.normal[1] * U[self.dof_y]
        return self.normal[0][:, None] * U[self.dof_x] + self.normal[1][:, None] * U[self.dof_y]


def check_drum_radius(drum_radius) -> None:
    if not (isinstance(drum_radius, (int, float)) and math.isfinite(drum_radius) and drum_radius > 0):
        raise ParameterError("drum_radius", drum_radius, "a radius > 0 m")


def contact_nodes(model, drum_radius: float) -> ContactNodes:
    """The contact nodes of ``model`` (a 2-D :class:`~clutchfem.fe.FEModel` or a 3-D
    :class:`~clutchfem.fe.FEModel3D`) facing a drum of inner radius ``drum_radius`` [m]: the
    ``contact`` group, per shoe from ``contact_<i>``."""
    if isinstance(model, FEModel3D):
        return _contact_nodes_3d(model, drum_radius)
    cm, basis = model.cm, model.basis
    check_drum_radius(drum_radius)
    b = cm.mesh.boundaries or {}
    if "contact" not in b:
        raise MeshError(f"{cm.source}: no 'contact' boundary group; cannot model the drum")
    facets = cm.boundary("contact")

    def x_dofs(fac):
        d = basis.get_dofs(np.asarray(fac))
        return np.concatenate([d.nodal["u^1"], d.facet["u^1"]])

    d = basis.get_dofs(facets)
    dx = np.concatenate([d.nodal["u^1"], d.facet["u^1"]])
    dy = np.concatenate([d.nodal["u^2"], d.facet["u^2"]])
    # the contact surface must face the drum: outward boundary normals point away from the axis
    check_facing(cm, facets)
    return build_contact_nodes(cm, cm, drum_radius, dx, dy, basis.doflocs, x_dofs,
                               lambda dx_all: contact_weights(cm, basis, facets)[dx_all], basis.N)


def _contact_nodes_3d(model, drum_radius: float) -> ContactNodes:
    """The extruded contact surface: every P2 node of the ``contact`` side faces (all
    levels), gaps on the exact circle, in-plane normals; on a sector, the cut_b copies of
    cut_a nodes merged (as in 2-D).  The weights are tributary *areas* divided by the part's
    axial thickness, so the drum's pressure = force / (thickness x weight) is force / area,
    as in 2-D."""
    cm, em, basis = model.cm, model.em, model.basis
    check_drum_radius(drum_radius)
    b = em.mesh.boundaries or {}
    if "contact" not in b:
        raise MeshError(f"{cm.source}: no 'contact' boundary group; cannot model the drum")
    facets = em.boundary("contact")
    dx, dy, _ = component_dofs(basis, facets)
    check_facing(cm, cm.boundary("contact"))
    h = model.thickness
    return build_contact_nodes(cm, em, drum_radius, dx, dy, basis.doflocs,
                               lambda fac: component_dofs(basis, np.asarray(fac))[0],
                               lambda dx_all: contact_area_weights(em, basis, facets)[dx_all] / h, basis.N)


def build_contact_nodes(cm, part, drum_radius: float, dx, dy, doflocs, x_dofs, weights_of,
                        ndofs: int) -> ContactNodes:
    """:class:`ContactNodes` from the x and y dofs of the contact surface of ``part`` (the
    2-D mesh ``cm`` itself, or its 3-D extrusion: ``part.mesh.boundaries`` and
    ``part.boundary(name)`` give its groups; ``doflocs`` has 2 or 3 rows; the normal is in
    the plane): gaps on the exact circle, the
    sector's cut_b copies merged, the shoe of each node from the ``contact_<i>`` groups.
    ``x_dofs(facets)``: the x dofs on some facets; ``weights_of(dx)``: tributary weights of
    the given x dofs (called lazily, when a pressure is asked for)."""
    order = np.argsort(dx)
    dx, dy = dx[order], dy[order]
    X = doflocs[:, dx]
    r = np.hypot(X[0], X[1])
    gap0 = drum_radius - r
    if np.any(gap0 < -1e-9 * drum_radius):
        worst = float(-gap0.min())
        raise MeshError(f"drum radius {drum_radius * 1e3:.4f} mm lies inside the part: contact nodes "
                        f"overlap the drum by up to {worst * 1e3:.4f} mm (drum radius must exceed "
                        f"{r.max() * 1e3:.4f} mm)")
    if np.any(gap0 <= 1e-9 * drum_radius):
        raise MeshError(f"drum radius {drum_radius * 1e3:.6g} mm equals the outer radius of the contact surface "
                        f"({r.max() * 1e3:.6g} mm): no clearance, the shoes touch the drum at rest and there is no "
                        "engagement speed; a centrifugal clutch needs a gap (the concepts allow 0.05..3 mm): give "
                        "a drum radius above the contact surface's")
    b = part.mesh.boundaries or {}
    shoe = -np.ones(len(dx), dtype=np.int64)
    for name, fac in b.items():
        if name.startswith("contact_"):
            shoe[np.isin(dx, x_dofs(fac))] = int(name.split("_")[1])
    if np.all(shoe < 0):
        shoe[:] = 0
    dx_all, merge = dx, None
    # one-sector model: a contact node on cut_b is the rotated copy of a node on cut_a (the
    # same node of the full part, u_b = R u_a).  Keep one of each pair, with both weights:
    # two copies would make G singular and split their force arbitrarily.
    if cm.sector_angle is not None and "cut_b" in b:
        copy = np.isin(dx, x_dofs(part.boundary("cut_b")))
        if copy.any():
            cs, sn = math.cos(cm.sector_angle), math.sin(cm.sector_angle)
            R = np.eye(len(X))
            R[:2, :2] = [[cs, sn], [-sn, cs]]  # rotation by -sector_angle about the axis
            back = R @ X[:, copy]
            keep = np.nonzero(~copy)[0]
            dist, j = cKDTree(X[:, keep].T).query(back.T)
            if dist.max() > 1e-8 * drum_radius:
                raise MeshError(f"{cm.source}: a contact node on cut_b has no partner on cut_a "
                                f"(mismatch {dist.max():.3g} m)")
            merge = (keep, j, copy)
            dx, dy, X, gap0, shoe = dx[keep], dy[keep], X[:, keep], gap0[keep], shoe[keep]
    xy = X[:2]
    n = xy / np.hypot(xy[0], xy[1])
    t = np.vstack([-n[1], n[0]])

    def weights() -> np.ndarray:
        w = weights_of(dx_all)
        if merge is not None:
            keep, j, copy = merge
            np.add.at(w, keep[j], w[copy])
            w = w[keep]
        return w

    return ContactNodes(drum_radius=float(drum_radius), dof_x=dx, dof_y=dy, xy=xy, normal=n, tangent=t,
                        gap0=np.maximum(gap0, 0.0), shoe=shoe, angle=np.arctan2(xy[1], xy[0]),
                        ndofs=ndofs, _weights=weights)


def check_facing(cm, facets: np.ndarray) -> None:
    mesh = cm.mesh
    p = mesh.p
    f = mesh.facets[:, facets]
    mid = 0.5 * (p[:, f[0]] + p[:, f[1]])
    elem = mesh.f2t[0, facets]
    cen = p[:, mesh.t[:, elem]].mean(axis=1)
    outward = mid - cen  # points out of the element, roughly along the facet normal
    radial = np.sum(outward * mid, axis=0) / np.linalg.norm(mid, axis=0)
    if np.mean(radial > 0) < 0.9:
        raise MeshError(f"{cm.source}: the 'contact' group faces inwards (its outward normals point "
                        "towards the axis); it must be the shoes' outer surface facing the drum")
