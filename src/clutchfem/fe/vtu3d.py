"""One ``.vtu`` frame of the 3-D model's fields (issue 20): the quadratic tetrahedra (VTK
``tetra10``) of the extruded model, mirrored about the mid-plane to the full thickness and
rotated into the whole ring, with its displacement, stresses, contact and zone ids.

What a frame holds (SI units, the names say them):

* the mesh: the model's P2 tetrahedra (:class:`clutchfem.fe.FEModel3D`: the 2-D mesh extruded
  through half the thickness).  **Mirrored by default**: the half model (0 <= z <= h/2, exact
  by the mid-plane symmetry) is reflected about z = 0, so the file shows the whole thickness
  -h/2 .. h/2 (``full_thickness=False``: the modelled half only); a one-sector model is then
  rotated into the whole ring like the 2-D output (:class:`clutchfem.fe.RingMesh`).  Nodes on
  z = 0 and on the cut faces are shared, not doubled.  Every cell is positively oriented
  (a mirrored or sorted tetrahedron has its corners 1 and 2 and their edges swapped);
* node order: VTK's (and meshio's) ``tetra10`` -- corners 0..3, then the mid-edge nodes of
  edges 01, 12, 02, 03, 13, 23 -- which is scikit-fem's ``ElementTetP2`` dof order (the
  edges of ``RefTet``); the writer builds each cell from scikit-fem's own edge table
  (``mesh.t2e``) and checks every mid-edge node against its corners, so a change on either
  side is an error, not a wrong picture;
* point data: ``displacement_m`` (x, y, z; u_z odd in z: flipped in the mirrored half),
  the 6 stress components ``sxx_Pa``, ``syy_Pa``, ``szz_Pa``, ``syz_Pa``, ``sxz_Pa``,
  ``sxy_Pa`` (s_yz, s_xz odd in z) and ``von_mises_Pa`` from the tetrahedron-vertex stresses
  averaged over the elements at a node, ``von_mises_max_Pa`` the largest unaveraged vertex
  value at a node (its maximum over the part is the sweep table's ``max_von_mises_Pa``);
  ``contact_pressure_Pa`` (force / tributary area) and ``gap_m`` at the contact nodes, 0
  elsewhere; the pressure is NaN at the corners of the quadratic contact faces, whose
  consistent share of a pressure is zero (no tributary area: a value there would be made up);
* cell data: ``zone_id`` (0 hub, 1 flexure, 2 shoe, -1 none), ``shoe_id``, ``sector_id`` (the
  copy of the sector) and ``half_id`` (0 the modelled half z >= 0, 1 its mirror image).
"""

from __future__ import annotations

import meshio
import numpy as np

from ..core import SolverError
from .ring import CELL_EDGES, RingMesh, ring_stresses, zone_ids
from .stress import von_mises

#: VTK tetra10 node order with corners 1 and 2 swapped (their edges 01 <-> 02, 13 <-> 23 with them)
FLIP10 = np.array([0, 2, 1, 3, 6, 5, 4, 7, 9, 8])
#: the sign of each Voigt stress component (xx, yy, zz, yz, xz, xy) in the mirror image z -> -z
MIRROR_STRESS = np.array([1.0, 1.0, 1.0, -1.0, -1.0, 1.0])
#: names of the 6 Voigt components in the file
STRESS_NAMES = ("sxx_Pa", "syy_Pa", "szz_Pa", "syz_Pa", "sxz_Pa", "sxy_Pa")


def tetra10_cells(basis) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3), cells (ne, 10)) of the vector P2 tetrahedron basis in VTK's ``tetra10``
    order (module docstring): node k is the scalar dof k (vector dofs 3 k + c), at the mesh's
    exact node position."""
    mesh = basis.mesh
    ed = np.asarray(basis.element_dofs)
    if ed.shape[0] != 30 or np.any(ed[0::3] % 3) or np.any(ed[1::3] != ed[0::3] + 1):
        raise SolverError("unexpected scikit-fem dof layout for the 3-D field output (not ElementVector(ElementTetP2))")
    nodes = ed[0::3] // 3  # (10, ne) in scikit-fem's local order
    pts = np.asarray(mesh.doflocs).T  # exact (the basis's own positions carry the map's round-off)
    if pts.shape[0] != basis.N // 3 or not np.allclose(pts.T, basis.doflocs[:, 0::3], rtol=0,
                                                       atol=1e-12 * float(np.abs(pts).max())):
        raise SolverError("3-D field output: the mesh's nodes are not the basis's dofs")
    nv = int(mesh.nvertices)
    cells = np.empty((mesh.t.shape[1], 10), dtype=np.int64)
    cells[:, :4] = mesh.t.T
    if not np.array_equal(nodes[:4], mesh.t):
        raise SolverError("3-D field output: the corner dofs are not the mesh's vertices")
    # the mid-edge node of VTK's edge (a, b): scikit-fem's edge with those corners
    edges = np.sort(mesh.edges, axis=0)
    for k, (a, b) in enumerate(CELL_EDGES[4]):
        lo = np.minimum(mesh.t[a], mesh.t[b])
        hi = np.maximum(mesh.t[a], mesh.t[b])
        local = [q for q in range(6) if np.array_equal(np.sort(edges[:, mesh.t2e[q]], axis=0), np.vstack([lo, hi]))]
        if len(local) != 1:
            raise SolverError(f"3-D field output: VTK edge {a}{b} is no scikit-fem edge of the elements")
        cells[:, 4 + k] = nodes[4 + local[0]]
        if np.any(cells[:, 4 + k] != nv + mesh.t2e[local[0]]):
            raise SolverError("3-D field output: an edge dof is not its edge's node")
    return pts, cells


def orient(pts: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Whether each tetra10 cell has a negative volume (corners (0, 1, 2, 3) left-handed)."""
    a, b, c, d = (pts[cells[:, r]] for r in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) < 0


class Frames3D:
    """The ``.vtu`` frames of a 3-D sweep result ``res`` (module docstring); ``cm`` the design's
    ClutchMesh (sector angle and copies), ``full_thickness``: mirror the half model."""

    def __init__(self, res, cm=None, full_thickness: bool = True):
        self.res = res
        basis = res.fields.fe_basis
        mesh = basis.mesh
        pts, cells = tetra10_cells(basis)
        self.n = len(pts)
        self.ne = len(cells)
        scale = float(np.abs(pts).max())
        half = "mid" in (mesh.boundaries or {})
        self.mirrored = bool(full_thickness and half)
        if self.mirrored:
            on_mid = np.abs(pts[:, 2]) <= 1e-9 * scale
            image = np.arange(self.n)
            image[~on_mid] = self.n + np.arange(int((~on_mid).sum()))
            pts = np.vstack([pts, pts[~on_mid] * [1.0, 1.0, -1.0]])
            cells = np.vstack([cells, image[cells]])
            self.image = image
        flip = orient(pts, cells)
        cells[flip] = cells[flip][:, FLIP10]
        self.flip = flip
        self.cells = cells
        # every mid-edge node near the middle of its corners (a wrong order is off by ~half an edge)
        for k, (a, b) in enumerate(CELL_EDGES[4]):
            mid = 0.5 * (pts[cells[:, a]] + pts[cells[:, b]])
            length = np.linalg.norm(pts[cells[:, a]] - pts[cells[:, b]], axis=1)
            if np.any(np.linalg.norm(pts[cells[:, 4 + k]] - mid, axis=1) > 0.25 * length):
                raise SolverError("3-D field output: a mid-edge node is far from its edge (node order)")
        angle = getattr(cm, "sector_angle", None)
        self.ring = RingMesh(pts, cells, angle, getattr(cm, "sector_copies", 1) if angle else 1)
        zone, shoe = zone_ids(mesh)
        halves = 2 if self.mirrored else 1
        cp = self.ring.copies
        self.cell_data = {"zone_id": [np.tile(zone, halves * cp)], "shoe_id": [np.tile(shoe, halves * cp)],
                          "sector_id": [np.repeat(np.arange(cp), halves * self.ne)],
                          "half_id": [np.tile(np.repeat(np.arange(halves), self.ne), cp)]}

    def _full(self, v: np.ndarray, odd: bool = False) -> np.ndarray:
        """A model nodal array (n, ...) on the mirrored nodes (odd: the sign flips)."""
        if not self.mirrored:
            return v
        keep = self.image >= self.n
        return np.concatenate([v, -v[keep] if odd else v[keep]])

    def stresses(self, u: np.ndarray) -> np.ndarray:
        """Element-vertex stresses (6, ne_full, 4) [Pa] of displacement ``u``, in the cells'
        (mirrored, re-oriented) corner order."""
        sv = self.res.fields.stress(u).reshape(6, self.ne, 4)
        if self.mirrored:
            sv = np.concatenate([sv, sv * MIRROR_STRESS[:, None, None]], axis=1)
        sv[:, self.flip] = sv[:, self.flip][:, :, [0, 2, 1, 3]]
        return sv

    def mesh(self, k: int) -> meshio.Mesh:
        """The frame of sweep speed index ``k``."""
        res, ring = self.res, self.ring
        u = res.displacement(k)
        uz = self._full(u[2:3 * self.n:3], odd=True)
        uxy = self._full(np.column_stack([u[0:3 * self.n:3], u[1:3 * self.n:3]]))
        s, vmax = ring_stresses(ring, self.stresses(u), self.cells, von_mises)
        press = np.zeros(self.n)
        gap = np.zeros(self.n)
        if res.contact is not None:
            node = res.contact.nodes.dof_x // 3
            if res.lam[k].any():
                press[node] = res.contact.pressure(res.lam[k], res.thickness)
            if res.gaps.size:
                gap[node] = res.gaps[k]
        point_data = {"displacement_m": ring.vector(np.column_stack([uxy, uz]))}
        point_data.update({name: s[i] for i, name in enumerate(STRESS_NAMES)})
        point_data.update({"von_mises_Pa": von_mises(s), "von_mises_max_Pa": vmax,
                           "contact_pressure_Pa": ring.scalar(self._full(press), "max"), "gap_m": ring.scalar(self._full(gap))})
        return meshio.Mesh(ring.points, [("tetra10", ring.cells)], point_data=point_data, cell_data=self.cell_data)
