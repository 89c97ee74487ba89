"""Mesh morphing: a design whose parameters changed but whose curves did not gets the nodes
of a reference design's mesh moved onto its geometry, instead of a new mesh.

Why.  A new mesh for every design changes the mesh topology with the parameters, so every
answer carries a small, non-smooth noise (~0.05 % in engagement, ~0.5 % in peak stress
between neighbouring designs): finite-difference derivatives at small steps are noise, and
a gradient-based optimiser cannot work.  A morphed mesh keeps the reference's connectivity,
so the answers are smooth functions of the parameters (``benchmarks/bench_morph.py``).

How (:func:`morph_to`):

1. **Curves** (:func:`~clutchfem.geometry.curve_frame`): the reference's every node that lies
   on a curve of the model -- the boundary, the zone interfaces inside the part (shoe,
   flexure, hub) and the sector cut lines, the P2 mid-edge nodes included -- is given its
   curve and its normalised parameter s on it (once per reference).  The new design is built
   (the same OCC operations, no meshing) and its **topology signature** is compared with the
   reference's: the same surfaces bounded by the same curves in the same order, the same
   curve types and end points, the same physical groups.  A different signature (a curve
   added or dropped) refuses the morph.
2. **Boundary move**: each such node goes to the point at the same s on its new curve (lines
   and arcs: the same share of their length).  The nodes of cut line ``cut_b`` are then set to
   their ``cut_a`` partners rotated by the sector angle, so the cyclic pairing stays exact.
3. **Interior move**: the displacement of the curve nodes is extended into each surface by
   a Laplace solve on the reference mesh (P2, one sparse factorisation per reference, two
   back-substitutions per design) with Jacobian-based stiffening: each element's
   conductivity is (mean area / its area), so small elements (fillets, the flexure) move
   nearly rigidly and large ones take up the change (Stein, Tezduyar & Benney 2003, J. Appl.
   Mech. 70: 58-63, chi = 1).
4. **Quality** (:func:`clutchfem.mesh.quality.assess`), the remesh criterion: every element's
   shape distortion s1/s2 <= 2.5 (:data:`~clutchfem.mesh.quality.MAX_DISTORTION`) and scaled
   Jacobian >= half of min(0.2, its reference value).  Measured (``benchmarks/bench_morph.py``,
   BENCHMARKS.md, "Robust design", ``tests/test_mesh_morph.py`` on every concept): within it, a
   morphed design's answers agree with the same design meshed from scratch inside the
   discretisation error reported for the morphed design.  A refused morph is a
   :class:`MorphRefused`: :func:`morph_or_mesh` then meshes the design from scratch (the
   caller decides whether that design becomes the next reference).

The morphed mesh carries the reference's groups (bore, contact, contact_i, cut_a/cut_b,
zones) and the new design's OCC-exact mass properties, pivots and contact arcs, so the whole
pipeline runs on it unchanged; ``ClutchMesh.morph`` records the reference and the quality.
"""

from __future__ import annotations

import dataclasses
import json
import math
import time

import cachetools
import numpy as np
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriP0, ElementTriP2, asm
from skfem.helpers import dot, grad

from ..core import MeshError
from ..geometry import Concept, ConceptParams, MeshSettings, curve_frame, get_concept
from .clutch_mesh import ClutchMesh
from .convert import meshio_to_skfem, read_cached_msh
from .cyclic import cyclic_pairing
from .generate import mesh_concept
from .quality import MorphQuality, assess, scaled_jacobian
from .topology import facet_nodes

#: morph references kept per process (each holds a mesh, its curve map and a factorisation)
CACHE_SIZE = 4


class MorphRefused(MeshError):
    """A design that cannot be morphed from the reference (another topology, or elements
    that would be too distorted): mesh it from scratch."""


@dataclasses.dataclass
class MorphReference:
    """A reference design prepared for morphing (module docstring): its mesh, the curve and
    normalised parameter of every node on a curve, the topology signature, the cut-line
    pairing and the factorised interior (Laplace) problem."""

    concept: Concept
    params: ConceptParams
    settings: MeshSettings
    cm: ClutchMesh
    curve_nodes: dict
    curve_s: dict
    signature: tuple
    pairs: tuple | None
    fixed: np.ndarray
    free: np.ndarray
    solve_free: object
    k_free_fixed: object
    ref_sj: np.ndarray
    setup_s: float

    @property
    def key(self) -> str:
        return reference_key(self.concept, self.params, self.settings)


def reference_key(concept: Concept, p: ConceptParams, ms: MeshSettings) -> str:
    """The cache key of a reference: concept, every parameter and the mesh settings."""
    return json.dumps({"c": concept.name, "p": p.model_dump(mode="json"), "m": ms.model_dump(mode="json")},
                      sort_keys=True)


def morph_reference(concept: Concept | str, p: ConceptParams, ms: MeshSettings | None = None) -> MorphReference:
    """The reference design ``p`` of ``concept`` prepared for morphing (meshed through the
    mesh cache; the last :data:`CACHE_SIZE` references are kept in this process)."""
    concept = get_concept(concept) if isinstance(concept, str) else concept
    return _prepared(concept, p, ms or MeshSettings())


# least recently used out; keyed by reference_key (the parameters are compared by value)
@cachetools.cached(cachetools.LRUCache(maxsize=CACHE_SIZE), key=reference_key)
def _prepared(concept: Concept, p: ConceptParams, ms: MeshSettings) -> MorphReference:
    t0 = time.perf_counter()
    cm = mesh_concept(concept, p, ms)
    curve_nodes = _curve_nodes(cm)
    frame = curve_frame(concept, p, ms, project={t: cm.mesh.doflocs[:, n] for t, n in curve_nodes.items()})
    fixed = np.unique(np.concatenate(list(curve_nodes.values())))
    free, solve_free, k_ff = _laplace(cm, fixed)
    pairs = None
    b = cm.mesh.boundaries or {}
    if cm.sector_angle is not None and "cut_a" in b and "cut_b" in b:
        fn = facet_nodes(cm.mesh)
        na, nb = np.unique(fn[:, b["cut_a"]]), np.unique(fn[:, b["cut_b"]])
        x = cm.mesh.doflocs
        j = cyclic_pairing(x[:, na], x[:, nb], cm.sector_angle, scale=float(np.abs(x).max()),
                           what=f"{concept.name}: the reference's sector cut lines")
        pairs = (na, nb[j])
    return MorphReference(concept=concept, params=p, settings=ms, cm=cm, curve_nodes=curve_nodes,
                          curve_s=frame.params, signature=frame.signature, pairs=pairs, fixed=fixed, free=free,
                          solve_free=solve_free, k_free_fixed=k_ff, ref_sj=scaled_jacobian(cm.mesh),
                          setup_s=time.perf_counter() - t0)


def _curve_nodes(cm: ClutchMesh) -> dict:
    """curve tag -> the P2 nodes on it (each node once: a corner shared by two curves goes to
    the curve with the lower tag), from the line elements of the cached ``.msh``."""
    if cm.msh_path is None:
        raise MeshError(f"{cm.source}: a morph reference needs a mesh generated from its concept (the mesh cache)")
    m = read_cached_msh(cm.msh_path)
    tags = sorted({int(lab[0]) for cb, lab in zip(m.cells, m.cell_data["gmsh:geometrical"])
                   if cb.type in ("line", "line3") and len(lab)})
    per = meshio_to_skfem(m, {str(t): {t} for t in tags}, {}, "gmsh:geometrical", cm.source)
    if per.doflocs.shape != cm.mesh.doflocs.shape or not np.array_equal(per.facets, cm.mesh.facets):
        raise MeshError(f"{cm.source}: the cached mesh file does not match the mesh read from it")
    fn = facet_nodes(per)
    seen: set = set()
    out = {}
    for t in tags:
        nodes = [int(n) for n in np.unique(fn[:, per.boundaries[str(t)]]) if int(n) not in seen]
        seen.update(nodes)
        if nodes:
            out[t] = np.array(nodes, dtype=np.int64)
    return out


@BilinearForm
def _stiffened_laplace(u, v, w):
    return w.k * dot(grad(u), grad(v))


def _laplace(cm: ClutchMesh, fixed: np.ndarray):
    """(free nodes, solver of K_ff, K_f,fixed) of the Jacobian-stiffened P2 Laplace problem."""
    mesh = cm.mesh
    basis = Basis(mesh, ElementTriP2(), intorder=4)
    area = np.abs(Basis(mesh, ElementTriP0(), intorder=1).mapping.detDF(np.array([[1 / 3], [1 / 3]]))[:, 0])
    k = np.mean(area) / area
    K = asm(_stiffened_laplace, basis, k=np.repeat(k[:, None], basis.X.shape[1], axis=1)).tocsr()
    n = K.shape[0]
    if n != mesh.doflocs.shape[1]:
        raise MeshError(f"{cm.source}: the P2 nodes of the mesh and of its basis differ ({mesh.doflocs.shape[1]} vs {n})")
    free = np.setdiff1d(np.arange(n), fixed)
    lu = spla.splu(K[free][:, free].tocsc())
    return free, lu.solve, K[free][:, fixed].tocsr()


def morph_to(ref: MorphReference, p: ConceptParams) -> ClutchMesh:
    """The reference's mesh moved onto design ``p`` (module docstring); raises
    :class:`MorphRefused` with the reason when the topology differs or the quality fails."""
    t0 = time.perf_counter()
    if type(p) is not type(ref.params):
        raise MorphRefused(f"design of {type(p).__name__} cannot be morphed from a {ref.concept.name} reference")
    frame = curve_frame(ref.concept, p, ref.settings, evaluate=ref.curve_s, expect=ref.signature)
    if frame.signature != ref.signature:
        raise MorphRefused(f"{ref.concept.name}: the design's curves differ from the reference's "
                           f"({_difference(ref.signature, frame.signature)})")
    x0 = ref.cm.mesh.doflocs
    x = x0.copy()
    for tag, nodes in ref.curve_nodes.items():
        x[:, nodes] = frame.points[tag]
    built = frame.built
    if ref.pairs is not None:
        a, b = ref.pairs
        th = built.sector_angle
        c, s = math.cos(th), math.sin(th)
        x[:, b] = np.array([[c, -s], [s, c]]) @ x[:, a]
    d_fixed = x[:, ref.fixed] - x0[:, ref.fixed]
    for k in range(2):
        x[k, ref.free] = x0[k, ref.free] + ref.solve_free(-(ref.k_free_fixed @ d_fixed[k]))
    mesh = dataclasses.replace(ref.cm.mesh, doflocs=x)
    q = assess(ref.cm.mesh, mesh, ref.ref_sj)
    if not q.ok:
        raise MorphRefused(f"{ref.concept.name}: {q.reason}")
    info = {"morphed": True, "reference": ref.params.model_dump(mode="json"), "quality": q.to_json(),
            "max_node_move_m": float(np.max(np.hypot(*(x - x0)))), "seconds": time.perf_counter() - t0}
    return dataclasses.replace(ref.cm, mesh=mesh, n_shoes_total=built.n_shoes_total,
                               n_shoes_model=built.n_shoes_model, sector_angle=built.sector_angle,
                               params=p.model_dump(), mass=built.mass, pivots=list(built.pivots),
                               contact_arcs=list(built.contact_arcs), drum_radius=p.drum_radius,
                               thickness=p.thickness, msh_path=None, cached=False,
                               mesh_time_s=info["seconds"], morph=info)


def _difference(a: tuple, b: tuple) -> str:
    names = ("surfaces and their curve loops", "curves (types, end points)", "physical groups", "shoes in the model",
             "arrangement")
    diff = [n for n, x, y in zip(names, a, b) if x != y]
    na, nb = len(a[1]), len(b[1])
    return ", ".join(diff) + (f"; {na} curves in the reference, {nb} in the design" if na != nb else "")


def morph_or_mesh(concept: Concept | str, p: ConceptParams, ms: MeshSettings | None = None, *,
                  reference: ConceptParams | None = None) -> ClutchMesh:
    """Design ``p`` morphed from ``reference`` (default: ``p`` itself), or meshed from scratch
    (through the mesh cache) when the morph is refused; ``ClutchMesh.morph`` says which, and
    why."""
    concept = get_concept(concept) if isinstance(concept, str) else concept
    ms = ms or MeshSettings()
    ref = morph_reference(concept, reference if reference is not None else p, ms)
    try:
        return morph_to(ref, p)
    except MorphRefused as exc:
        cm = mesh_concept(concept, p, ms)
        cm.morph = {"morphed": False, "reference": ref.params.model_dump(mode="json"), "reason": str(exc)}
        return cm


def quality_of(cm: ClutchMesh) -> MorphQuality | None:
    """The morph quality recorded on a morphed mesh (None for a mesh made from scratch)."""
    q = (cm.morph or {}).get("quality")
    return MorphQuality(**q) if q else None

