"""What a concept is, and the generic pipeline that turns one into a meshed gmsh model.

A concept file in ``geometries/`` defines a :class:`Concept` subclass with a parameter
class (a :class:`ConceptParams` subclass) and a :meth:`Concept.build` that draws the
full one-piece part with gmsh-OCC in the *canonical frame*:

* the rotation axis is z through the origin, the part lies in z = 0, lengths in metres;
* shoe ``i`` is shoe 0 rotated by ``i * 360/n`` degrees;
* shoe 0 is joined to the hub at its *root* end (the flexure) at the smaller polar angle
  and extends counter-clockwise to its free *tip*.  With the hub turning ccw against a held
  drum, friction drags each shoe towards its root (the hub pushes the shoe from behind):
  the canonical frame is the **plus** (self-energizing) arrangement.  The **minus**
  arrangement, the default, is its mirror image (y -> -y), done here, not in the concepts.

Everything else is generic and lives here: mirroring, the one-sector cut with periodic
(rotated) matching of the two cut lines, partition into shoe / flexure / hub zones,
classification of the boundary curves (clamped bore, per-shoe contact surface, cut lines),
physical groups, mesh size fields, second-order meshing and OCC-exact mass properties.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal

import gmsh
import numpy as np
from pydantic import model_serializer

from ..core import GeometryError, ParamSet, choice, param, wrap_angle
from . import occ as G
from .profile import MIN_PROFILE_CLEARANCE, TABLE_FIELDS, TABLE_N, table_param, table_spline

occ = gmsh.model.occ
class ConceptParams(ParamSet):
    """Parameters common to every one-piece concept (defaults: the 60 cc saw of the thesis)."""

    n_shoes: int = param(3, "-", 2, 6, "number of shoes", "n")
    drum_radius: float = param(34.4e-3, "m", 15e-3, 100e-3, "drum inner radius R_d", "R_d")
    clearance: float = param(0.6e-3, "m", 0.05e-3, 3e-3,
                             "radial shoe-drum clearance at rest (at the root end for a linear profile)", "c")
    profile: Literal["concentric", "eccentric", "linear", "table"] = choice(
        "concentric", "shoe outer profile (morphological row D); 'table': clearances table_c0..table_c16 "
                      "along the shoe, joined by a cubic spline")
    clearance_tip: float = param(0.6e-3, "m", 0.05e-3, 3e-3,
                                 "clearance at the shoe tip (linear profile only)", "c_tip")
    eccentricity: float = param(0.0, "m", -3e-3, 3e-3,
                                "offset of the eccentric profile's centre (eccentric profile only)", "e")
    eccentric_angle: float = param(0.0, "deg", -180.0, 180.0,
                                   "direction of the eccentric offset from the shoe's mid-angle (towards the tip > 0)", "psi_e")
    thickness: float = param(11e-3, "m", 2e-3, 40e-3, "axial thickness of the part (assumed ~10-12 mm)", "h")
    bore_radius: float = param(6.5e-3, "m", 2e-3, 20e-3, "crankshaft bore radius (assumed)", "r_b")
    arrangement: Literal["minus", "plus"] = choice(
        "minus", "flexure placement for ccw rotation: minus = shoe trails its flexure")
    fillet_radius: float = param(0.5e-3, "m", 0.0, 5e-3, "fillet radius at slot ends / flexure roots", "rho")
    table_c0: float = table_param(0)
    table_c1: float = table_param(1)
    table_c2: float = table_param(2)
    table_c3: float = table_param(3)
    table_c4: float = table_param(4)
    table_c5: float = table_param(5)
    table_c6: float = table_param(6)
    table_c7: float = table_param(7)
    table_c8: float = table_param(8)
    table_c9: float = table_param(9)
    table_c10: float = table_param(10)
    table_c11: float = table_param(11)
    table_c12: float = table_param(12)
    table_c13: float = table_param(13)
    table_c14: float = table_param(14)
    table_c15: float = table_param(15)
    table_c16: float = table_param(16)

    @model_serializer(mode="wrap")
    def _dump_without_inert_table(self, handler):
        """The table profile's control values are inert for every other profile and are then
        left out of the dump: the mesh cache key, the design hash and every recorded input of
        a concentric / eccentric / linear design stay what they were before the table profile
        existed."""
        d = handler(self)
        if self.profile != "table":
            for name in TABLE_FIELDS:
                d.pop(name, None)
        return d

    # ---- profile of the shoe outer surface (canonical frame, shoe 0) ----------------------
    def outer_radius(self, theta: np.ndarray, t0: float, t1: float) -> np.ndarray:
        """Radius of the shoe's outer surface at polar angle ``theta`` (rad), for a shoe
        spanning [t0 (root), t1 (tip)] in the canonical frame."""
        theta = np.asarray(theta, dtype=float)
        Rd = self.drum_radius
        if self.profile == "table":
            return Rd - self.table_clearance((theta - t0) / (t1 - t0))
        if self.profile == "concentric":
            return np.full_like(theta, Rd - self.clearance)
        if self.profile == "linear":
            s = (theta - t0) / (t1 - t0)
            return Rd - (self.clearance + (self.clearance_tip - self.clearance) * s)
        cx, cy, rho_e = self.eccentric_circle(t0, t1)
        # intersect the ray at theta with the circle |x - c| = rho_e
        ux, uy = np.cos(theta), np.sin(theta)
        b = ux * cx + uy * cy
        return b + np.sqrt(rho_e ** 2 - (cx * cx + cy * cy) + b * b)

    @property
    def table(self) -> tuple[float, ...]:
        """The table profile's control clearances [m], root to tip."""
        return tuple(float(getattr(self, n)) for n in TABLE_FIELDS)

    def table_clearance(self, s) -> np.ndarray:
        """Clearance [m] of the table profile at arc fraction ``s`` (0 root, 1 tip)."""
        return table_spline(self.table)(np.asarray(s, dtype=float))

    def eccentric_circle(self, t0: float, t1: float) -> tuple[float, float, float]:
        """Centre (x, y) and radius of the eccentric profile: offset ``eccentricity`` in the
        direction (mid-angle + eccentric_angle), radius chosen so that the clearance at the
        shoe's mid-angle equals ``clearance``."""
        tm = 0.5 * (t0 + t1)
        a = tm + math.radians(self.eccentric_angle)
        cx, cy = self.eccentricity * math.cos(a), self.eccentricity * math.sin(a)
        r_mid = self.drum_radius - self.clearance
        px, py = r_mid * math.cos(tm), r_mid * math.sin(tm)
        return cx, cy, math.hypot(px - cx, py - cy)

    def eccentric_centre(self, t0: float, t1: float, a: float = 0.0) -> np.ndarray | None:
        """Centre (x, y) of the eccentric profile of a shoe spanning [t0, t1], rotated by
        ``a`` (rad) about the origin; None unless the profile is eccentric."""
        if self.profile != "eccentric":
            return None
        cx, cy, _ = self.eccentric_circle(t0, t1)
        c, s = math.cos(a), math.sin(a)
        return np.array([c * cx - s * cy, s * cx + c * cy])

    def flexure_thicknesses(self) -> list[float]:
        """Thicknesses [m] of the concept's flexures (every ``flexure*thickness`` parameter by
        default; concepts with tapered or derived flexures override this).  The mesh is
        refined in the flexure zones to ``flexure_factor`` x the thinnest of them."""
        return [float(getattr(self, n)) for n in type(self).model_fields
                if n.startswith("flexure") and n.endswith("thickness")]

    def min_clearance(self, t0: float, t1: float) -> float:
        th = np.linspace(t0, t1, 201 if self.profile != "table" else 801)
        return float(np.min(self.drum_radius - self.outer_radius(th, t0, t1)))

    def check_profile(self, t0: float, t1: float) -> None:
        """Raise if the shoe profile touches or crosses the drum anywhere (the table profile's
        spline is sampled at 801 points: it may dip below its control values between them)."""
        if self.profile == "eccentric":
            cx, cy, rho = self.eccentric_circle(t0, t1)
            if rho <= math.hypot(cx, cy):
                self.fail("eccentricity", "|e| smaller than the profile radius")
        if self.profile == "table":
            s = np.linspace(0.0, 1.0, 801)
            c = self.table_clearance(s)
            k = int(np.argmin(c))
            if c[k] <= MIN_PROFILE_CLEARANCE:
                near = TABLE_FIELDS[int(round(s[k] * (TABLE_N - 1)))]
                self.fail(near, f"a table whose spline keeps a clearance > {MIN_PROFILE_CLEARANCE * 1e3:.2f} mm "
                                f"everywhere (it dips to {c[k] * 1e3:.3f} mm at {s[k]:.3f} of the shoe arc from "
                                "the root, next to this control value: raise it or smooth its neighbours)")
            return
        cmin = self.min_clearance(t0, t1)
        if cmin <= MIN_PROFILE_CLEARANCE:
            name = {"linear": "clearance_tip", "eccentric": "eccentricity"}.get(self.profile, "clearance")
            self.fail(name, f"a profile whose clearance stays > 0.02 mm everywhere (minimum here "
                            f"{cmin * 1e3:.3f} mm)")

    @property
    def sector_angle(self) -> float:
        """Angle of one sector (rad)."""
        return 2 * math.pi / self.n_shoes


class MeshSettings(ParamSet):
    """Mesh controls: one global size knob plus optional local factors."""

    context: ClassVar[str] = "mesh settings"
    size: float = param(1.2e-3, "m", 0.05e-3, 10e-3, "global target element size", "h_mesh")
    flexure_factor: float = param(0.4, "-", 0.05, 2.0,
                                  "element size in flexures as a fraction of the flexure thickness")
    contact_factor: float = param(0.5, "-", 0.05, 2.0, "element size on contact surfaces / global size")
    fillet_factor: float = param(0.5, "-", 0.05, 2.0, "element size on small arcs (fillets) / arc radius")
    order: int = param(2, "-", 1, 2, "element order (2: curved P2 triangles)")
    model: Literal["sector", "full"] = choice("sector", "one cyclic sector or the full 360 degree part")


@dataclass
class Shapes:
    """What :meth:`Concept.build` returns (all in the canonical frame, full 360 degrees)."""

    material: list[int]
    """surface tags of the whole one-piece part, without the bore (cut by the framework)"""
    shoe_zones: list[int]
    """one surface per shoe covering (at least) that shoe's body; used to partition"""
    flexure_zones: list[int] = field(default_factory=list)
    """one surface per shoe covering its flexure(s) (may be empty)"""
    sector_start: float = 0.0
    """polar angle (rad) of a radial line that crosses only hub material (sector cut)"""


@dataclass
class Annotation:
    """A labelled dimension/callout on the concept drawing (canonical frame, metres)."""

    text: str
    at: tuple[float, float]
    to: tuple[float, float] | None = None


class Concept:
    """Base class of a parametric concept (subclass it in ``geometries/<name>.py``)."""

    name: ClassVar[str] = ""
    title: ClassVar[str] = ""
    thesis: ClassVar[str] = ""
    """what the thesis says of the concept (for docs and `--list-params`)"""
    parametrisation: ClassVar[str] = ""
    """how the text description was turned into parameters"""
    Params: ClassVar[type[ConceptParams]] = ConceptParams

    def build(self, p: ConceptParams) -> Shapes:  # pragma: no cover - abstract
        raise NotImplementedError

    def shoe_arc(self, p: ConceptParams) -> tuple[float, float]:
        """(root, tip) polar angles (rad) of shoe 0's contact surface, canonical frame."""
        raise NotImplementedError

    def pivot(self, p: ConceptParams) -> tuple[float, float]:
        """Nominal pivot point of shoe 0 (canonical frame): the flexure's compliant centre."""
        raise NotImplementedError

    def annotations(self, p: ConceptParams) -> list[Annotation]:
        return []

    def params(self, **values) -> ConceptParams:
        return self.Params(**values)


# ---------------------------------------------------------------------------------------
# generic build pipeline
# ---------------------------------------------------------------------------------------
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
    _size_fields(p, ms, groups)
    return BuiltModel(concept=concept.name, n_shoes_total=n, n_shoes_model=n_model,
                      sector_angle=Theta if sector else None,
                      sector_start=cut_angles[0] if cut_angles else None, mirrored=mirrored,
                      entity_groups=groups, group_dims=dims, mass=mass, pivots=pivots,
                      contact_arcs=arcs)


def _size_fields(p: ConceptParams, ms: MeshSettings, groups: dict[str, list[int]]) -> None:
    f = gmsh.model.mesh.field
    h = ms.size
    fields = []

    def threshold(curves: list[int], size: float, dist: float) -> None:
        if not curves or size >= h:
            return
        d = f.add("Distance")
        f.setNumbers(d, "CurvesList", curves)
        f.setNumber(d, "Sampling", 60)
        t = f.add("Threshold")
        f.setNumber(t, "InField", d)
        f.setNumber(t, "SizeMin", size)
        f.setNumber(t, "SizeMax", h)
        f.setNumber(t, "DistMin", dist)
        f.setNumber(t, "DistMax", dist + 4 * h)
        fields.append(t)

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
    by_size: dict[float, list[int]] = {}
    for dim, c in gmsh.model.getEntities(1):
        lo, hi = gmsh.model.getParametrizationBounds(1, c)
        k = np.abs(gmsh.model.getCurvature(1, c, [0.5 * (lo[0] + hi[0])]))
        if k.size and k[0] > 1.0 / (0.25 * p.drum_radius):
            s = float(np.round(ms.fillet_factor / k[0], 7))
            by_size.setdefault(s, []).append(c)
    for s, cs in by_size.items():
        threshold(cs, s, 0.0)
    if fields:
        m = f.add("Min")
        f.setNumbers(m, "FieldsList", fields)
        f.setAsBackgroundMesh(m)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)


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
