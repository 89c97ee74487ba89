"""The whole part from a one-sector model for field output: rotated copies of its nodes, nodal
fields and element-vertex stresses (2-D triangle6 and 3-D tetra10), their zone ids, and the
ParaView collection (``.pvd``) of a time series.

A cyclic sector stands for the whole ring: copy c is the sector rotated by c times the
sector angle about the z axis (the axis of rotation), positions and vectors rotated, stress
tensors transformed, s' = R s R^T; the copies' shared cut-line (cut-face) nodes are merged.
Stresses at a node: the element-vertex values *averaged* over the elements at the node
(corners; a mid-edge node the mean of its edge's corners: the P2 strain is linear along a
straight edge), and the *largest* element-vertex von Mises at the node (unaveraged: its
maximum over the part is the sweep table's peak).
"""

from __future__ import annotations

import math
from xml.sax.saxutils import quoteattr

import numpy as np
from scipy.spatial import cKDTree

#: zone ids of the ``zone_id`` cell array
ZONES = {"hub": 0, "flexure": 1, "shoe": 2}

#: mid-edge nodes of a quadratic cell: their corners, in VTK's (and meshio's) order of the
#: cell's nodes after its corners (triangle6: 3 4 5; tetra10: 4 .. 9, scikit-fem's edge order
#: of ``RefTet`` too)
CELL_EDGES = {3: ((0, 1), (1, 2), (2, 0)), 4: ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))}


def zone_ids(mesh) -> tuple[np.ndarray, np.ndarray]:
    """(zone id, shoe id) of every element of the mesh (2-D, or 3-D with the 2-D subdomain
    names) from its subdomains ``hub``, ``flexure_<i>``, ``shoe_<i>`` (-1 where none applies)."""
    ne = mesh.t.shape[1]
    zone = -np.ones(ne, dtype=np.int64)
    shoe = -np.ones(ne, dtype=np.int64)
    for name, elems in (mesh.subdomains or {}).items():
        kind, _, idx = name.partition("_")
        if kind in ZONES:
            zone[np.asarray(elems)] = ZONES[kind]
            if idx.isdigit():
                shoe[np.asarray(elems)] = int(idx)
    return zone, shoe


class RingMesh:
    """The whole part from a one-sector model (or the model itself): ``copies`` rotated by
    ``angle`` [rad] about the z axis, cut-line nodes merged.  ``pts`` (n, 3) (z = 0 for a 2-D
    model); ``node[c]`` maps the sector's nodes to the ring's for copy c."""

    def __init__(self, pts: np.ndarray, cells: np.ndarray, angle: float | None, copies: int):
        self.angle = float(angle or 0.0)
        self.copies = copies if angle else 1
        pts = np.asarray(pts, dtype=float)
        n = len(pts)
        z = pts[:, 2] if pts.shape[1] > 2 else np.zeros(n)
        allp = np.vstack([self._rot(c) @ pts[:, :2].T for c in range(self.copies)]).reshape(self.copies, 2, n)
        flat = np.column_stack([allp.transpose(0, 2, 1).reshape(-1, 2), np.tile(z, self.copies)])
        tol = 1e-9 * max(float(np.abs(pts).max()), 1e-300)
        rep = np.arange(len(flat))
        if self.copies > 1:
            for i, j in cKDTree(flat).query_pairs(tol):
                rep[max(i, j)] = min(rep[max(i, j)], min(i, j))
            while True:  # chains of merges point at the smallest index
                nxt = rep[rep]
                if np.array_equal(nxt, rep):
                    break
                rep = nxt
        keep, ring_id = np.unique(rep, return_inverse=True)
        self.points = flat[keep]
        self.node = ring_id.reshape(self.copies, n)
        self.cells = np.vstack([self.node[c][cells] for c in range(self.copies)])
        self.n = len(keep)

    def _rot(self, c: int) -> np.ndarray:
        a = c * self.angle
        return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])

    def vector(self, v: np.ndarray) -> np.ndarray:
        """(n_ring, 3) of a sector's (n, 2) or (n, 3) nodal vector field, rotated per copy
        (z component unchanged; 0 for an in-plane field)."""
        out = np.zeros((self.n, 3))
        for c in range(self.copies):
            out[self.node[c], :2] = v[:, :2] @ self._rot(c).T
            if v.shape[1] > 2:
                out[self.node[c], 2] = v[:, 2]
        return out

    def scalar(self, s: np.ndarray, how: str = "first") -> np.ndarray:
        """(n_ring,) of a sector's nodal scalar (``how``: 'first' copy's value or the 'max')."""
        out = np.full(self.n, -np.inf if how == "max" else 0.0)
        for c in range(self.copies):
            if how == "max":
                with np.errstate(invalid="ignore"):  # a NaN (no value there) stays NaN
                    np.maximum.at(out, self.node[c], s)
            else:
                out[self.node[c]] = s
        return out

    def tensor(self, s: np.ndarray, c: int) -> np.ndarray:
        """Stress rotated into copy c: in-plane (3, k) (xx, yy, xy) or 3-D Voigt (6, k)
        (xx, yy, zz, yz, xz, xy; zz unchanged, the shears (xz, yz) rotate as a vector)."""
        a = c * self.angle
        cs, sn = math.cos(a), math.sin(a)
        sxx, syy, sxy = (s[0], s[1], s[2]) if s.shape[0] == 3 else (s[0], s[1], s[5])
        inplane = (cs * cs * sxx + sn * sn * syy - 2 * cs * sn * sxy,
                   sn * sn * sxx + cs * cs * syy + 2 * cs * sn * sxy,
                   cs * sn * (sxx - syy) + (cs * cs - sn * sn) * sxy)
        if s.shape[0] == 3:
            return np.array(inplane)
        yz, xz = s[3], s[4]
        return np.array([inplane[0], inplane[1], s[2], sn * xz + cs * yz, cs * xz - sn * yz, inplane[2]])


def ring_stresses(ring: RingMesh, sv: np.ndarray, cells: np.ndarray, von_mises) -> tuple[np.ndarray, np.ndarray]:
    """(averaged stress (k, n_ring), largest element-vertex von Mises (n_ring,)) on the ring
    from a sector's element-vertex stresses ``sv`` (k, ne, nv): k = 3 in-plane components on
    triangles (nv = 3) or 6 Voigt components on tetrahedra (nv = 4); corners averaged over the
    elements of every copy at the node, mid-edge nodes the mean of their edge's corners."""
    k_, _, nv = sv.shape
    acc = np.zeros((k_, ring.n))
    cnt = np.zeros(ring.n)
    vmax = np.full(ring.n, -np.inf)
    vm_vertex = von_mises(sv)  # (ne, nv): invariant under the rotation
    for c in range(ring.copies):
        corners = ring.node[c][cells[:, :nv]].ravel()
        rs = ring.tensor(sv.reshape(k_, -1), c)
        np.add.at(cnt, corners, 1.0)
        for k in range(k_):
            np.add.at(acc[k], corners, rs[k])
        np.maximum.at(vmax, corners, vm_vertex.ravel())
    acc[:, cnt > 0] /= cnt[cnt > 0]
    for c in range(ring.copies):
        cl = ring.node[c][cells]
        for k, (i, j) in enumerate(CELL_EDGES[nv]):
            acc[:, cl[:, nv + k]] = 0.5 * (acc[:, cl[:, i]] + acc[:, cl[:, j]])
            # the mid-edge von Mises of the element's own (linear) stress: never above its corners'
            mid = von_mises(0.5 * (sv[:, :, i] + sv[:, :, j]))
            np.maximum.at(vmax, cl[:, nv + k], mid)
    return acc, vmax


def pvd_text(entries) -> str:
    """A ParaView collection (``.pvd``) of (timestep, file name) entries: the time series."""
    rows = "\n".join(f'    <DataSet timestep="{t:.12g}" group="" part="0" file={quoteattr(name)}/>'
                     for t, name in entries)
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f"  <Collection>\n{rows}\n  </Collection>\n</VTKFile>\n")
