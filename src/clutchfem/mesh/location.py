"""Naming places in the clutch: the zone, the position in it and the boundary of a point
(:func:`name_location`, :class:`Location`) and of a P2 node (:func:`zone_of_node`,
:func:`describe_node`), for the worst fatigue point and the hottest slip-heat points.

Zones are the mesh subdomains ``flexure_<i>``, ``shoe_<i>``, ``hub`` (``solid`` is the
whole part and never names a place).  In a flexure the position is its end: hub end / shoe
end / middle, by the distances to the flexure's interfaces with the hub and the shoe, in
thirds of the way; a flexure that joins only shoe material is an 'in-shoe flexure'.  A hub
or shoe point within a flexure's width of it is 'at flexure <j> root' / 'at flexure <j>
joint' (the width: 2 area / perimeter of the flexure).  The boundary is the group of the
boundary facet whose P2 node the point is: 'bore', 'contact surface', 'sector cut', or
'free edge' (a fillet or slot flank).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree
from skfem import Basis

from ..core import InputError, ParameterError
from .clutch_mesh import ClutchMesh
from .topology import element_components, element_set_area, element_set_perimeter, facet_nodes, p2_nodes

__all__ = ["Location", "describe_node", "name_location", "zone_of_node"]


@dataclass(frozen=True)
class Location:
    """Where a point lies in the clutch: zone, position in it and the boundary it is on."""

    zone: str
    kind: str
    index: int | None
    position: str
    boundary: str | None
    x_m: float
    y_m: float

    @property
    def radius_m(self) -> float:
        return math.hypot(self.x_m, self.y_m)

    @property
    def angle_deg(self) -> float:
        return math.degrees(math.atan2(self.y_m, self.x_m))

    @property
    def description(self) -> str:
        s = self.zone if self.index is None else f"{self.kind} {self.index}"
        if self.position:
            s += f", {self.position}"
        if self.boundary:
            s += f", on the {self.boundary}"
        return s + f" (r = {self.radius_m * 1e3:.2f} mm, {self.angle_deg:.1f} deg)"

    def to_json(self) -> dict:
        return {"zone": self.zone, "kind": self.kind, "index": self.index, "position": self.position,
                "boundary": self.boundary, "x_m": self.x_m, "y_m": self.y_m,
                "description": self.description}


def _element_zone(cm: ClutchMesh) -> np.ndarray:
    """Zone name of every element ('' where none but 'solid')."""
    sub = cm.mesh.subdomains or {}
    z = np.full(cm.mesh.t.shape[1], "", dtype=object)
    for name in sorted(sub):  # hub, flexure_<i>, shoe_<i>: later (shoe) wins over flexure
        if name == "solid":
            continue
        z[np.asarray(sub[name])] = name
    return z


def _interface_points(cm: ClutchMesh, comp: np.ndarray, zone: np.ndarray, prefix: str) -> np.ndarray:
    """Vertices of the edges between the elements ``comp`` and elements of zones ``prefix*``."""
    mesh = cm.mesh
    inner = np.nonzero(mesh.f2t[1] >= 0)[0]
    a, b = mesh.f2t[0, inner], mesh.f2t[1, inner]
    in_zone = np.char.startswith(zone.astype(str), prefix)  # per element
    ina, inb = np.isin(a, comp), np.isin(b, comp)
    hit = (ina & in_zone[b]) | (inb & in_zone[a])
    f = mesh.facets[:, inner[hit]]
    return mesh.p[:, np.unique(f)]


def name_location(cm: ClutchMesh, xy, element: int | None = None) -> Location:
    """Name the place of point ``xy`` (2,) [m] in ``cm``: its zone (``flexure_<i>``,
    ``shoe_<i>``, ``hub``), for a flexure its end (hub end / shoe end / middle: by the
    distances to the flexure's interfaces with the hub and the shoe, thirds of the way),
    for a flexure that joins only shoe material 'in-shoe flexure', for a hub or shoe point
    near a flexure (within the flexure's width) 'at flexure <j> root' / 'at flexure <j>
    joint'; and the boundary it lies on ('bore', 'contact surface', 'free edge' = a fillet
    or slot flank), if any.  ``element``: the element the point belongs to (e.g. of a raw
    vertex stress); without it the element is found by position (flexure preferred on an
    interface)."""
    if not isinstance(cm, ClutchMesh):
        raise InputError(f"name_location: cm must be a ClutchMesh (got {type(cm).__name__})")
    pt = np.asarray(xy, dtype=float).reshape(-1)
    if pt.shape != (2,) or not np.all(np.isfinite(pt)):
        raise InputError(f"name_location: xy must be a finite point (x, y) (got {xy!r})")
    mesh = cm.mesh
    p, t = mesh.p, mesh.t
    nel = t.shape[1]
    zone = _element_zone(cm)
    scale = float(np.max(np.abs(p)))
    if element is not None:
        if isinstance(element, bool) or int(element) != element or not 0 <= int(element) < nel:
            raise ParameterError("element", element, f"an element index in [0, {nel - 1}]")
        e = int(element)
    else:
        cen = p[:, t].mean(axis=1)
        _, cand = cKDTree(cen.T).query(pt, k=min(12, nel))
        cand = np.atleast_1d(cand)
        inside = []
        for c in cand:
            v = p[:, t[:, c]]
            T = np.array([v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]]).T
            lam = np.linalg.solve(T, pt - v[:, 0])
            if lam.min() >= -1e-6 and lam.sum() <= 1 + 1e-6:
                inside.append(int(c))
        if not inside:
            d = np.linalg.norm(cen[:, cand] - pt[:, None], axis=0)
            if d.min() > 0.05 * scale:
                raise InputError(f"name_location: point ({pt[0]:.6g}, {pt[1]:.6g}) m lies outside the part")
            inside = [int(cand[0])]
        pref = sorted(inside, key=lambda c: (0 if str(zone[c]).startswith("flexure") else 1))
        e = pref[0]
    zname = str(zone[e]) or "part"
    kind = zname.split("_")[0]
    idx = int(zname.split("_")[1]) if "_" in zname and zname.split("_")[1].isdigit() else None
    # boundary: the point is one of the P2 nodes (corner or mid-edge) of a boundary facet
    bnd = None
    nodes = facet_nodes(mesh)
    bfac = mesh.boundary_facets()
    bnodes = np.unique(nodes[:, bfac])
    xyn = p2_nodes(mesh)
    dist, j = cKDTree(xyn[:, bnodes].T).query(pt)
    if dist <= 1e-9 * scale:
        v = int(bnodes[j])
        groups = mesh.boundaries or {}
        names = [g for g in ("bore", "contact", "cut_a", "cut_b")
                 if g in groups and np.isin(v, nodes[:, np.asarray(groups[g])]).any()]
        bnd = {"bore": "bore", "contact": "contact surface", "cut_a": "sector cut", "cut_b": "sector cut"}.get(
            names[0], names[0]) if names else "free edge"
    position = ""
    sub = mesh.subdomains or {}
    if kind == "flexure":
        comps = element_components(mesh, np.asarray(sub[zname]))
        comp = next(c for c in comps if e in c)
        hub_pts = _interface_points(cm, comp, zone, "hub")
        shoe_pts = _interface_points(cm, comp, zone, "shoe")
        if hub_pts.shape[1] and shoe_pts.shape[1]:
            dh = np.min(np.linalg.norm(hub_pts - pt[:, None], axis=0))
            ds = np.min(np.linalg.norm(shoe_pts - pt[:, None], axis=0))
            frac = dh / max(dh + ds, 1e-300)
            position = "hub end" if frac < 1 / 3 else ("shoe end" if frac > 2 / 3 else "middle")
            if len(comps) > 1:
                position = "main flexure, " + position
        elif shoe_pts.shape[1]:
            position = "in-shoe flexure"
        elif hub_pts.shape[1]:
            position = "hub end"
    elif kind in ("hub", "shoe"):
        best = None
        for fname in sorted(n for n in sub if n.startswith("flexure")):
            fel = np.asarray(sub[fname])
            fv = np.unique(t[:, fel])
            d = float(np.min(np.linalg.norm(p[:, fv] - pt[:, None], axis=0)))
            area = element_set_area(mesh, fel)
            width = 2.0 * area / max(element_set_perimeter(mesh, fel), 1e-300)
            if d <= width and (best is None or d < best[0]):
                best = (d, fname)
        if best is not None:
            j_ = best[1].split("_")[1]
            position = f"at flexure {j_} root" if kind == "hub" else f"at flexure {j_} joint"
        elif kind == "hub":
            position = "hub body"
        elif bnd != "contact surface":
            position = "shoe body"
    return Location(zone=zname, kind=kind, index=idx, position=position, boundary=bnd,
                    x_m=float(pt[0]), y_m=float(pt[1]))


def zone_of_node(cm: ClutchMesh, basis: Basis, node: int) -> str:
    """The zone of P2 node ``node`` of ``basis``: of the zones of the elements that hold it,
    a flexure before a shoe before the hub (the first by name); 'part' if none."""
    elems = np.nonzero((basis.element_dofs == node).any(axis=0))[0]
    sub = cm.mesh.subdomains or {}
    names = [n for n, e in sub.items() if n != "solid" and np.isin(elems, e).any()]
    for pref in ("flexure", "shoe", "hub"):
        hit = sorted(n for n in names if n.startswith(pref))
        if hit:
            return hit[0]
    return names[0] if names else "part"


def describe_node(cm: ClutchMesh, basis: Basis, node: int) -> str:
    """Zone, position and boundary of a P2 node (:func:`name_location` with an element of the
    node's zone (:func:`zone_of_node`) that holds it)."""
    elems = np.nonzero((basis.element_dofs == node).any(axis=0))[0]
    zone = zone_of_node(cm, basis, node)
    sub = cm.mesh.subdomains or {}
    if zone in sub:
        elems = elems[np.isin(elems, sub[zone])]
    return name_location(cm, basis.doflocs[:, node], element=int(elems[0])).description
