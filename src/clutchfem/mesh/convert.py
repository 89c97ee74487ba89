"""meshio -> scikit-fem: a triangle mesh read by meshio becomes a ``MeshTri2`` with named
boundaries and subdomains, checked for inverted, folded or degenerate elements.

scikit-fem's own meshio reader does not turn order-2 ``line3`` boundary cells into
boundary tags, so the boundary facets are matched here from the two end vertices of every
labelled boundary cell.  A P1 mesh is lifted to straight-sided P2.
"""

from __future__ import annotations

import contextlib
import io
import warnings
from pathlib import Path

import meshio
import numpy as np
from skfem import Basis, ElementTriP0, MeshTri1, MeshTri2

from ..core import MeshError
from .topology import facet_numbers


def read_msh(path: Path) -> meshio.Mesh:
    """meshio.read without its stray prints on stdout (its gmsh reader prints an empty line
    per file, which breaks the CLI's tables and JSON output); real messages become warnings."""
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        m = meshio.read(path)
    if buf.getvalue().strip():
        warnings.warn(f"meshio ({path}): {buf.getvalue().strip()}", stacklevel=2)
    return m


#: gmsh element type -> (meshio cell type, nodes per element) of the files the mesh cache writes
_CACHE_TYPES = {15: ("vertex", 1), 1: ("line", 2), 8: ("line3", 3), 2: ("triangle", 3), 9: ("triangle6", 6)}


def read_cached_msh(path: Path) -> meshio.Mesh:
    """A mesh cache file (:func:`clutchfem.mesh.mesh_concept`'s: gmsh's ASCII msh 4.1, every
    element with its entity tag, no physical groups) as :func:`read_msh` reads it -- the same
    points, cells and ``gmsh:geometrical`` labels, parsed by the same number parser -- in a
    fifth of the time: each section is parsed in one call instead of three per entity block
    (meshio's reader was a quarter of a coarse mesh's making and all of a cache hit's).  A
    file of any other form is read by :func:`read_msh`."""
    data = Path(path).read_bytes()
    try:
        if not data.startswith(b"$MeshFormat\n4.1 0 8\n"):
            raise ValueError("not an ASCII msh 4.1 file")
        ent = _section(data, b"Entities", float)
        n_ent, k = ent[:4].astype(int), 4
        for dim, count in enumerate(n_ent):  # no entity may carry a physical tag (meshio would label by it)
            for _ in range(count):
                k += 4 if dim == 0 else 7
                if int(ent[k]) != 0:
                    raise ValueError("physical tags")
                k += 1 if dim == 0 else 2 + int(ent[k + 1])
        nodes = _section(data, b"Nodes", float)
        n_blocks, n_nodes = int(nodes[0]), int(nodes[1])
        points, tags, k, at = np.empty((n_nodes, 3)), np.empty(n_nodes, dtype=int), 4, 0
        for _ in range(n_blocks):
            if int(nodes[k + 2]) != 0:
                raise ValueError("parametric nodes")
            n = int(nodes[k + 3])
            tags[at:at + n] = nodes[k + 4:k + 4 + n]
            points[at:at + n] = nodes[k + 4 + n:k + 4 + 4 * n].reshape(n, 3)
            k, at = k + 4 + 4 * n, at + n
        if at != n_nodes or k != len(nodes):
            raise ValueError("node count")
        elems = _section(data, b"Elements", np.int64)
        inv = np.full(int(tags.max()) + 1, -1, dtype=int)
        inv[tags - 1] = np.arange(n_nodes)
        cells, labels, k = [], [], 4
        for _ in range(int(elems[0])):
            tag, kind, n = int(elems[k + 1]), int(elems[k + 2]), int(elems[k + 3])
            name, per = _CACHE_TYPES[int(kind)]
            block = elems[k + 4:k + 4 + n * (1 + per)].reshape(n, 1 + per)
            cells.append((name, inv[block[:, 1:] - 1]))
            labels.append(np.full(n, tag, int))
            k += 4 + n * (1 + per)
        if k != len(elems):
            raise ValueError("element count")
    except (ValueError, KeyError, IndexError):
        return read_msh(path)
    return meshio.Mesh(points, cells, cell_data={"gmsh:geometrical": labels})


def _section(data: bytes, name: bytes, dtype) -> np.ndarray:
    """The numbers of the file's ``$name`` section, parsed as ``dtype`` (ValueError: none)."""
    a = data.index(b"\n$" + name + b"\n") + len(name) + 3
    text = data[a:data.index(b"\n$End" + name, a)].decode("ascii")
    return np.fromstring(text, dtype=dtype, sep=" ")


def meshio_to_skfem(m: meshio.Mesh, curve_groups: dict[str, set[int]],
                    surface_groups: dict[str, set[int]], key: str, source: str) -> MeshTri2:
    """Convert a meshio mesh of triangles (order 1 or 2) into a ``MeshTri2`` with named
    boundaries and subdomains.

    ``key`` is the meshio cell-data key that labels cells (``gmsh:physical`` for user
    files, ``gmsh:geometrical`` for our own cached models); ``curve_groups`` and
    ``surface_groups`` map a group name to the set of labels it contains (a label may sit
    in several groups, e.g. ``contact`` and ``contact_0``).
    """
    pts = np.asarray(m.points, dtype=float)
    if pts.shape[1] == 3:
        scale = max(float(np.ptp(pts[:, :2], axis=0).max()), 1e-300)
        if np.abs(pts[:, 2]).max() > 1e-9 * scale:
            raise MeshError(f"{source}: the mesh is not planar (z varies up to "
                            f"{np.abs(pts[:, 2]).max():.3g} m); expected a 2-D part in the x-y plane")
        pts = pts[:, :2]
    tri_type = "triangle6" if "triangle6" in m.cells_dict else ("triangle" if "triangle" in m.cells_dict else None)
    if tri_type is None:
        raise MeshError(f"{source}: no triangle elements found (cell types: {sorted(m.cells_dict)}); "
                        "expected a 2-D triangle mesh")
    t_all = np.vstack([c.data for c in m.cells if c.type == tri_type])
    if tri_type == "triangle6":
        # keep only the triangles' nodes: a gmsh file also holds nodes no triangle uses
        # (circle-arc centres, points of curves saved on their own), which MeshTri2 would
        # carry along as extra 'nodes'
        used = np.unique(t_all)
        t_all = np.searchsorted(used, t_all)
        pts = pts[used]
        line_map = used
        uniq = np.unique(t_all[:, :3])
        mesh = MeshTri2(np.ascontiguousarray(pts.T), np.ascontiguousarray(t_all.T))
    else:
        uniq = np.unique(t_all)
        line_map = None
        t = np.searchsorted(uniq, t_all).T
        mesh = MeshTri2.from_mesh(MeshTri1(np.ascontiguousarray(pts[uniq].T), np.ascontiguousarray(t)))
    labels = m.cell_data.get(key)
    sub: dict[str, np.ndarray] = {}
    bnd: dict[str, np.ndarray] = {}
    if labels is not None:
        tri_lab = np.concatenate([np.asarray(labels[i]) for i, c in enumerate(m.cells) if c.type == tri_type])
        for name, labs in surface_groups.items():
            sub[name] = np.nonzero(np.isin(tri_lab, list(labs)))[0].astype(np.int64)
        # boundaries: match every labelled line/line3 cell to a facet by its end vertices
        line_blocks = [(c.data, np.asarray(labels[i])) for i, c in enumerate(m.cells)
                       if c.type in ("line", "line3")]
        if line_blocks:
            raw = np.vstack([d[:, :2] for d, _ in line_blocks])
            if line_map is not None:  # file node numbers -> compacted numbers (-1: not a triangle node)
                pos = np.clip(np.searchsorted(line_map, raw), 0, len(line_map) - 1)
                raw = np.where(line_map[pos] == raw, pos, -1)
            ends = np.where(raw >= 0, np.searchsorted(uniq, raw), -1)
            lab = np.concatenate([lv for _, lv in line_blocks])
            facet = facet_numbers(mesh, ends[:, 0], ends[:, 1])
            for name, labs in curve_groups.items():
                sel = np.isin(lab, list(labs))
                if np.any(facet[sel] < 0):
                    raise MeshError(f"{source}: {int(np.sum(facet[sel] < 0))} cells of boundary group "
                                    f"'{name}' do not match any triangle edge")
                bnd[name] = np.unique(facet[sel])
    if bnd:
        mesh = mesh.with_boundaries(bnd)
    if sub:
        mesh = mesh.with_subdomains(sub)
    check_orientation(mesh, source)
    return mesh


def check_orientation(mesh: MeshTri2, source: str) -> None:
    """Refuse degenerate, inverted or folded elements.

    Two checks: (1) inside every element the Jacobian determinant keeps one sign and does not
    vanish (a curved P2 element whose mid-edge node is too far out fails this); (2) the two
    elements that share an interior edge lie on opposite sides of it (a flipped element in a
    fold fails this).  Elements may be oriented either way (gmsh keeps the orientation of
    mirrored surfaces), so the global sign is not checked.
    """
    basis = Basis(mesh, ElementTriP0(), intorder=4)
    detJ = basis.mapping.detDF(basis.X)
    scale = np.median(np.abs(detJ))
    pos = (detJ > 1e-10 * scale).all(axis=1)
    neg = (detJ < -1e-10 * scale).all(axis=1)
    bad = ~(pos | neg)
    p, t, f2t, facets = mesh.p, mesh.t, mesh.f2t, mesh.facets
    inner = np.nonzero(f2t[1] >= 0)[0]
    a, b = p[:, facets[0, inner]], p[:, facets[1, inner]]

    def side(elems):
        c = p[:, t[:, elems]].mean(axis=1)
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    folded = side(f2t[0, inner]) * side(f2t[1, inner]) >= 0
    nbad = int(bad.sum()) + int(folded.sum())
    if nbad:
        raise MeshError(f"{source}: {nbad} inverted, folded or degenerate element(s) (Jacobian "
                        "changes sign or vanishes, or neighbours overlap); fix or regenerate the mesh")
