"""The generic build pipeline: a concept and its parameters -> a tagged, size-fielded gmsh model.

:func:`build_model` draws the concept (:meth:`~.concept.Concept.build`, canonical frame), then,
the same for every concept: cuts the bore, cuts one sector (``MeshSettings.model =
"sector"``) with periodic (rotated) matching of its two cut lines, partitions the material
into shoe / flexure / hub zones, classifies the boundary curves (clamped bore, per-shoe
contact surface, cut lines), adds the physical groups and the mesh size fields, and takes
the OCC-exact mass properties of every zone.  The minus arrangement is the canonical
(plus) model mirrored y -> -y: the OCC model stays canonical and the mesh is reflected by
the caller after meshing (:attr:`BuiltModel.mirrored`); everything :class:`BuiltModel`
reports is already in the final frame.  Meshing itself (second order, the high-order
fix-up, the cache) is the mesh stage's (:mod:`clutchfem.mesh`).
"""

from __future__ import annotations

import hashlib
import inspect
import math
from dataclasses import dataclass
from pathlib import Path

import gmsh
import numpy as np

from ..core import GeometryError, wrap_angle
from . import occ as G
from .concept import Concept, ConceptParams, MeshSettings

occ = gmsh.model.occ
#: the modules of the generic geometry code that shape every mesh; with the concept's own
#: file they make the mesh cache key (:func:`source_files`)
SHAPING_MODULES = ("concept.py", "build.py", "curves.py", "occ.py", "sketch.py", "profile.py")


def source_files() -> list[Path]:
    """The files of the generic geometry code that shape every mesh (:data:`SHAPING_MODULES`):
    a change to any of them must not serve a cached mesh."""
    here = Path(__file__).resolve().parent
    return [here / name for name in SHAPING_MODULES]


#: the meshing pipeline's files that shape every mesh as well (:mod:`clutchfem.mesh`: generation,
#: the high-order guard, meshio -> scikit-fem), relative to the package: named here so that a
#: design's identity (:func:`clutchfem.loadcase.model_version`) is computed without importing
#: the mesh stage (a live design is never meshed)
MESH_PIPELINE = ("mesh/generate.py", "mesh/convert.py", "mesh/highorder.py")


def source_hash(concept) -> str:
    """Hash of every source that shapes the mesh of ``concept``: the concept's module file and
    those of its base classes loaded from geometries/, the generic geometry code
    (:func:`source_files`) and the meshing pipeline (:data:`MESH_PIPELINE`)."""
    h = hashlib.sha256()
    files = {inspect.getfile(cls) for cls in type(concept).__mro__
             if cls.__module__.startswith("clutchfem_geometries.")}
    files |= {str(f) for f in source_files()}
    package = Path(__file__).parent.parent
    files |= {str(package / rel) for rel in MESH_PIPELINE}
    for f in sorted(files):
        h.update(Path(f).read_bytes())
    return h.hexdigest()[:16]


@dataclass
class BuiltModel:
    """Facts about the gmsh model in memory after :func:`build_model` (final frame)."""

    concept: str
    n_shoes_total: int
    n_shoes_model: int
    sector_angle: float | None
    sector_start: float | None
    mirrored: bool
    entity_groups: dict[str, list[int]]
    """physical group name -> gmsh entity tags (curves for 1D names, surfaces for 2D)"""
    group_dims: dict[str, int]
    mass: dict
    pivots: list[tuple[float, float]]
    contact_arcs: list[tuple[float, float]]
    """per shoe (root angle, tip angle) of the contact surface in the final frame (rad)"""


def _curve_samples(tag: int, n: int = 7) -> np.ndarray:
    lo, hi = gmsh.model.getParametrizationBounds(1, tag)
    ts = np.linspace(lo[0], hi[0], n)
    xyz = np.asarray(gmsh.model.getValue(1, tag, ts)).reshape(-1, 3)
    return xyz[:, :2]


def build_model(concept: Concept, p: ConceptParams, ms: MeshSettings) -> BuiltModel:
    """Draw, cut, partition, tag and size-field the concept in the *current* gmsh model.

    All OCC work (sector wedge, partition, curve classification, exact mass properties) is
    done in the canonical (plus) frame.  For the minus arrangement the OCC model stays
    canonical and the *mesh* is reflected (y -> -y) after meshing by the caller
    (``BuiltModel.mirrored``); everything returned here (groups, mass, pivots, arcs) is
    already in the final frame.  (Mirroring the OCC model instead gave mass properties off
    by up to 4e-4 and renumbered entities.)  The caller owns gmsh initialisation."""
    n = p.n_shoes
    Theta = p.sector_angle
    shapes = concept.build(p)
    material = G.cut(shapes.material, [G.disk(p.bore_radius)])
    shoe_zones, flex_zones = shapes.shoe_zones, shapes.flexure_zones
    sector = ms.model == "sector"
    cut_angles = None
    if sector:
        lo, hi = shapes.sector_start, shapes.sector_start + Theta
        big = 4.0 * p.drum_radius
        kept = []
        for tags in (material, shoe_zones, flex_zones):
            new = []
            for t in tags:
                out, _ = occ.intersect([(2, t)], [(2, G.annular_sector(0.0, big, lo, hi))])
                new += [tt for d, tt in out if d == 2]
            kept.append(new)
        material, shoe_zones, flex_zones = kept
        cut_angles = (lo, hi)
    n_model = 1 if sector else n
    # partition the material by the zones; drop zone pieces outside the material
    obj = [(2, t) for t in material]
    out, out_map = occ.fragment(obj, [(2, t) for t in shoe_zones + flex_zones])
    mat_pieces = {t for m in out_map[: len(obj)] for d, t in m if d == 2}
    zone_pieces = [[t for d, t in m if d == 2] for m in out_map[len(obj):]]
    extra = [(2, t) for d, t in out if d == 2 and t not in mat_pieces]
    if extra:
        occ.remove(extra, recursive=True)
    occ.synchronize()
    surfaces = sorted(mat_pieces)
    if not surfaces:
        raise GeometryError(f"{concept.name}: the geometry has no material left", p)

    # zones: shoe before flexure before hub; zones kept by a sector wedge renumber from 0
    n_shoe_z = len(shoe_zones)
    zone_of: dict[int, tuple[str, int]] = {}
    for k, pieces in enumerate(zone_pieces):
        kind, idx = ("shoe", k) if k < n_shoe_z else ("flexure", k - n_shoe_z)
        for t in pieces:
            if t in mat_pieces and (t not in zone_of or (zone_of[t][0] == "flexure" and kind == "shoe")):
                zone_of[t] = (kind, idx)
    groups: dict[str, list[int]] = {"solid": surfaces}
    if len({i for k, i in zone_of.values() if k == "shoe"}) != n_model:
        raise GeometryError(f"{concept.name}: expected {n_model} shoe(s) in the model "
                            "(does the sector cut cross a shoe?)", p)
    for t, (kind, idx) in zone_of.items():
        groups.setdefault(f"{kind}_{idx}", []).append(t)
    groups["hub"] = [t for t in surfaces if t not in zone_of]

    # classify boundary curves (canonical frame; the sector holds shoe 0)
    root, tip = concept.shoe_arc(p)
    bnd = gmsh.model.getBoundary([(2, t) for t in surfaces], combined=True, oriented=False)
    curves = sorted({abs(t) for d, t in bnd if d == 1})
    tol = 1e-6 * p.drum_radius
    cuts: dict[str, list[tuple[float, int]]] = {"a": [], "b": []}
    groups["bore"] = []
    contact_by_shoe: dict[int, list[int]] = {}
    for c in curves:
        xy = _curve_samples(c)
        r = np.hypot(xy[:, 0], xy[:, 1])
        th = np.arctan2(xy[:, 1], xy[:, 0])
        if np.all(np.abs(r - p.bore_radius) < tol):
            groups["bore"].append(c)
            continue
        if cut_angles is not None:
            side = [k for k, ang in zip("ab", cut_angles) if np.all(np.abs(wrap_angle(th, ang) - ang) * r < tol)]
            if side:
                cuts[side[0]].append((float(np.mean(r)), c))
                continue
        for i in range(n_model):
            th_can = wrap_angle(th - i * Theta, 0.5 * (root + tip))
            inside = np.all((th_can >= root - 1e-9) & (th_can <= tip + 1e-9))
            if inside and np.all(np.abs(r - p.outer_radius(th_can, root, tip)) < tol):
                contact_by_shoe.setdefault(i, []).append(c)
                break
    if not groups["bore"]:
        raise GeometryError(f"{concept.name}: no bore curve found at r = {p.bore_radius} m", p)
    for j in range(n_model):
        if j not in contact_by_shoe:
            raise GeometryError(f"{concept.name}: shoe {j} has no contact surface on its profile", p)
        groups[f"contact_{j}"] = contact_by_shoe[j]
    groups["contact"] = [c for j in range(n_model) for c in contact_by_shoe[j]]
    mass = _mass_properties(groups, n_model)
    px, py = concept.pivot(p)
    pivots = [(px * math.cos(i * Theta) - py * math.sin(i * Theta),
               px * math.sin(i * Theta) + py * math.cos(i * Theta)) for i in range(n_model)]
    arcs = [(root + i * Theta, tip + i * Theta) for i in range(n_model)]

    if cut_angles is not None:
        if not cuts["a"] or len(cuts["a"]) != len(cuts["b"]):
            raise GeometryError(f"{concept.name}: sector cut lines do not match "
                                f"({len(cuts['a'])} vs {len(cuts['b'])} curves)", p)
        lower, upper = [c for _, c in sorted(cuts["a"])], [c for _, c in sorted(cuts["b"])]
        cs, sn = math.cos(Theta), math.sin(Theta)
        affine = [cs, -sn, 0, 0, sn, cs, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
        gmsh.model.mesh.setPeriodic(1, upper, lower, affine)  # upper = lower rotated by +Theta
        groups["cut_a"], groups["cut_b"] = lower, upper

    mirrored = p.arrangement == "minus"
    if mirrored:  # final frame = canonical reflected y -> -y (the mesh is reflected later)
        for props in mass.values():
            cx, cy = props["centroid"]
            props["centroid"] = (cx, -cy)
        pivots = [(x, -y) for x, y in pivots]
        arcs = [(-a, -b) for a, b in arcs]
        if cut_angles is not None:
            # cut_a is always the line at the lower angle: after reflection that is 'upper'
            cut_angles = (-cut_angles[1], -cut_angles[0])
            groups["cut_a"], groups["cut_b"] = groups["cut_b"], groups["cut_a"]

    dims = {}
    for name, tags in groups.items():
        dim = 1 if name in ("bore", "contact", "cut_a", "cut_b") or name.startswith("contact_") else 2
        dims[name] = dim
        if tags:
            gmsh.model.addPhysicalGroup(dim, tags, name=name)
    _size_fields(p, ms, groups, -1.0 if mirrored else 1.0)
    return BuiltModel(concept=concept.name, n_shoes_total=n, n_shoes_model=n_model,
                      sector_angle=Theta if sector else None,
                      sector_start=cut_angles[0] if cut_angles else None, mirrored=mirrored,
                      entity_groups=groups, group_dims=dims, mass=mass, pivots=pivots,
                      contact_arcs=arcs)


def _size_fields(p: ConceptParams, ms: MeshSettings, groups: dict[str, list[int]], ysign: float = 1.0) -> None:
    f = gmsh.model.mesh.field
    h = ms.size
    fields = []
    if ms.refine_radius > 0 and ms.refine_size < h:  # the refined disc (final frame -> canonical: y * ysign)
        fields.append(disc_size_field(ms.refine_x, ysign * ms.refine_y, ms.refine_radius, ms.refine_size, h))

    def threshold(curves: list[int], size: float, dist: float) -> None:
        if not curves or size >= h:
            return
        d = f.add("Distance")
        f.setNumbers(d, "CurvesList", curves)
        f.setNumber(d, "Sampling", 60)
        fields.append(threshold_field(d, size, h, dist))

    threshold(groups.get("contact", []), ms.contact_factor * h, 0.5 * h)
    flex_ts = p.flexure_thicknesses()
    if flex_ts:
        flex_t = min(flex_ts)
        flex_curves = []
        for name, tags in groups.items():
            if name.startswith("flexure_"):
                b = gmsh.model.getBoundary([(2, t) for t in tags], combined=True, oriented=False)
                flex_curves += [abs(t) for d, t in b if d == 1]
        threshold(sorted(set(flex_curves)), ms.flexure_factor * flex_t, flex_t)
    # small arcs (fillets): size proportional to their radius
    by_size: dict[tuple[float, float], list[int]] = {}
    for dim, c in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        k = np.abs(gmsh.model.getCurvature(1, c, [0.5 * (lo[0] + hi[0])]))
        if k.size and k[0] > 1.0 / (0.25 * p.drum_radius):
            s = float(np.round(ms.fillet_factor / k[0], 7))
            reach = float(np.round(ms.fillet_reach / k[0], 7))
            by_size.setdefault((s, reach), []).append(c)
    for (s, reach), cs in by_size.items():
        threshold(cs, s, reach)
    if fields:
        m = f.add("Min")
        f.setNumbers(m, "FieldsList", fields)
        f.setAsBackgroundMesh(m)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)


def disc_size_field(x: float, y: float, radius: float, size: float, h: float) -> int:
    """Add a gmsh size field to the current model: ``size`` within ``radius`` of (x, y) [m],
    growing linearly to ``h`` over the next 4 h; returns its tag (to combine in a Min field)."""
    f = gmsh.model.mesh.field
    d = f.add("MathEval")
    f.setString(d, "F", f"Sqrt((x-({x!r}))^2+(y-({y!r}))^2)")
    return threshold_field(d, size, h, radius)


def _mass_properties(groups: dict[str, list[int]], n_model: int) -> dict:
    """OCC-exact area properties of each zone, scaled by density and thickness later.

    Returned per unit density: area [m^2], centroid [m], polar second moment about the
    origin J_O = int (x^2 + y^2) dA [m^4], about the centroid J_c, and Ixx, Iyy about the
    origin (for the diametral inertia of the whole part)."""

    def props(tags: list[int]) -> dict:
        A = 0.0
        Sx = Sy = 0.0
        Jo = Ixx = Iyy = 0.0
        for t in tags:
            a = occ.getMass(2, t)
            cx, cy, _ = occ.getCenterOfMass(2, t)
            I = np.asarray(occ.getMatrixOfInertia(2, t)).reshape(3, 3)
            # getMatrixOfInertia is about the centre of mass: I[0,0] = int y^2, I[1,1] = int x^2
            ixx_o = I[0, 0] + a * cy * cy  # int y^2 dA about origin
            iyy_o = I[1, 1] + a * cx * cx  # int x^2 dA about origin
            A += a
            Sx += a * cx
            Sy += a * cy
            Ixx += ixx_o
            Iyy += iyy_o
        cx, cy = Sx / A, Sy / A
        Jo = Ixx + Iyy
        return {"area": A, "centroid": (cx, cy), "radius": math.hypot(cx, cy), "J_origin": Jo,
                "J_centroid": Jo - A * (cx * cx + cy * cy), "Ixx_origin": Ixx, "Iyy_origin": Iyy}

    out = {"solid": props(groups["solid"])}
    for j in range(n_model):
        if f"shoe_{j}" in groups:
            out[f"shoe_{j}"] = props(groups[f"shoe_{j}"])
        if f"flexure_{j}" in groups:
            out[f"flexure_{j}"] = props(groups[f"flexure_{j}"])
    return out


def threshold_field(distance: int, size: float, h: float, dist: float) -> int:
    """A gmsh Threshold field on the distance field ``distance``: elements of ``size`` within
    ``dist``, growing to ``h`` over the next 4 h."""
    f = gmsh.model.mesh.field
    t = f.add("Threshold")
    f.setNumber(t, "InField", distance)
    f.setNumber(t, "SizeMin", size)
    f.setNumber(t, "SizeMax", h)
    f.setNumber(t, "DistMin", dist)
    f.setNumber(t, "DistMax", dist + 4 * h)
    return t
