"""Topology of a quadratic triangle mesh that several stages share: its P2 nodes, the nodes
of every facet, the facet of a vertex pair, the triangle6 cells, connected element sets,
their area and perimeter.

Node numbering: the scalar P2 nodes of scikit-fem's ``ElementTriP2`` on a ``MeshTri2`` --
the mesh vertices first (their own numbers), then one mid-edge node per facet
(``nvertices + facet``).  A vector P2 dof d of the elastic model (dof 2 i + component)
belongs to node d // 2.  Cells are in VTK's triangle6 order (3 corners, then the mid-edges
01, 12, 20), which is scikit-fem's order too.  Every function takes the scikit-fem mesh
(``ClutchMesh.mesh``).
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from skfem import Basis, ElementTriP2, MeshTri2

#: P2 bases of the last meshes asked for (a mesh is immutable: its basis is built once)
_P2_BASES: dict[int, tuple] = {}


def facet_numbers(mesh, a, b) -> np.ndarray:
    """The facet number of each edge (``a[i]``, ``b[i]``) given by its two vertex numbers in
    either order, -1 where ``mesh`` has no such facet (vectorised: one sort of the facets' keys
    and a binary search; a vertex number of -1 finds none).

    Examples
    --------
    >>> import numpy as np
    >>> from skfem import MeshTri
    >>> from clutchfem.mesh import facet_numbers
    >>> m = MeshTri()                                   # the unit square in two triangles
    >>> f = facet_numbers(m, m.facets[1], m.facets[0])  # every facet, its ends swapped
    >>> bool((f == np.arange(m.facets.shape[1])).all()), facet_numbers(m, [0], [0]).tolist()
    (True, [-1])
    """
    n = int(mesh.p.shape[1]) + 1
    fs = np.sort(mesh.facets, axis=0).astype(np.int64)
    keys = fs[0] * n + fs[1]
    order = np.argsort(keys)
    a, b = np.asarray(a, dtype=np.int64), np.asarray(b, dtype=np.int64)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    want = lo * n + hi
    pos = np.clip(np.searchsorted(keys[order], want), 0, len(keys) - 1)
    found = (lo >= 0) & (keys[order][pos] == want)
    return np.where(found, order[pos], -1).astype(np.int64)


def p2_basis(mesh: MeshTri2) -> Basis:
    """The scalar P2 basis of ``mesh`` (one-point quadrature: for its nodes and dof maps, not
    for assembly), cached for the last four meshes."""
    hit = _P2_BASES.get(id(mesh))
    if hit is None or hit[0] is not mesh:
        if len(_P2_BASES) >= 4:
            _P2_BASES.pop(next(iter(_P2_BASES)))
        hit = _P2_BASES[id(mesh)] = (mesh, Basis(mesh, ElementTriP2(), intorder=1))
    return hit[1]


def is_quadratic(mesh: MeshTri2) -> bool:
    """The mesh carries its P2 nodes (a quadratic MeshTri2: vertices, then one per facet)."""
    return mesh.doflocs.shape[1] == mesh.nvertices + mesh.facets.shape[1]


def facet_nodes(mesh: MeshTri2) -> np.ndarray:
    """(3, nfacets) P2 node ids of every facet: its two corners and its mid-edge node."""
    mid = mesh.nvertices + np.arange(mesh.facets.shape[1]) if is_quadratic(mesh) else p2_basis(mesh).facet_dofs[0]
    return np.vstack([mesh.facets, mid])


def p2_nodes(mesh: MeshTri2) -> np.ndarray:
    """(2, n) positions of the P2 nodes (corners keep the mesh's vertex numbers)."""
    return mesh.doflocs if is_quadratic(mesh) else p2_basis(mesh).doflocs


def p2_cells(mesh: MeshTri2) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3), cells (ne, 6)) of the quadratic triangle mesh for .vtu output: every P2
    node once (z = 0), cells in VTK's triangle6 order (module docstring)."""
    b = p2_basis(mesh)
    xy = b.doflocs
    return np.column_stack([xy.T, np.zeros(xy.shape[1])]), b.element_dofs.T.copy()


def element_components(mesh: MeshTri2, elems: np.ndarray) -> list[np.ndarray]:
    """Connected components (through shared edges) of a set of elements, each sorted."""
    elems = np.unique(np.asarray(elems, dtype=np.int64))
    inner = np.nonzero(mesh.f2t[1] >= 0)[0]
    a, b = mesh.f2t[0, inner], mesh.f2t[1, inner]
    sel = np.isin(a, elems) & np.isin(b, elems)
    ia, ib = np.searchsorted(elems, a[sel]), np.searchsorted(elems, b[sel])
    n = len(elems)
    _, label = connected_components(coo_matrix((np.ones(len(ia)), (ia, ib)), shape=(n, n)), directed=False)
    return [elems[label == k] for k in np.unique(label)]


def element_set_area(mesh: MeshTri2, elems: np.ndarray) -> float:
    """Area of the straight triangles through the vertices of ``elems`` [m^2]."""
    p, t = mesh.p, mesh.t[:, elems]
    a, b, c = p[:, t[0]], p[:, t[1]], p[:, t[2]]
    return float(0.5 * np.abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).sum())


def element_set_perimeter(mesh: MeshTri2, elems: np.ndarray) -> float:
    """Length of the (straight) edges of ``elems`` that border no other element of the set [m]."""
    f = mesh.t2f[:, elems].ravel()
    uniq, cnt = np.unique(f, return_counts=True)
    edge = uniq[cnt == 1]
    a, b = mesh.p[:, mesh.facets[0, edge]], mesh.p[:, mesh.facets[1, edge]]
    return float(np.linalg.norm(b - a, axis=0).sum())
