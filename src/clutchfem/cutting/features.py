"""The features a cutter must make, measured on the exact outline, and the check against a
process's limits.

Three kinds, measured on the part as built (not read from the concept's parameters, so a
new concept is checked without code of its own):

* **inside radius**: every arc (and spline stretch) that turns away from the material -- a
  fillet, a slot end, the bore -- and every sharp inside corner (radius 0) where two
  segments meet at an angle with the material outside the turn.  The tool, of radius
  kerf / 2 at least, cannot make a smaller one;
* **slot**: the width of the waste between two walls that face each other across it;
* **web**: the width of material between two walls that face each other across it (a
  flexure, a shoe, the hub ring).

Slot and web widths come from the boundary sampled every :data:`SPACING` with its normals:
two samples face each other when the line joining them lies within :data:`CONE` of both
normals (into the waste for a slot, into the material for a web); the narrowest pair of each
pair of zones is then refined on the exact segments to the smallest distance between points
whose joining line lies within :data:`FACING` of both normals (exact between parallel walls
and concentric arcs, the narrowest chord between radial walls; a corner is not a slot: its
walls do not face each other, and the rounded end of a slot measures the slot's width).  Each feature is named by
the zones its walls bound (``flexure 0``, ``slot between shoe 1 and hub``) and, where its size
equals one of the concept's length parameters to 1e-6, by that parameter; identical
features of the n shoes are reported once with their count.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..core import ClutchfemError, format_quantity
from .rules import ProcessRules

#: boundary sample spacing [m] for slot and web widths
SPACING = 0.1e-3
#: half-angle of the cone within which two samples face each other
CONE = math.radians(15.0)
#: the refined width's pair faces within this angle of both walls' normals
FACING = math.radians(3.0)
#: widths above this [m] are not reported (the hub, the bore)
MAX_WIDTH = 8e-3


class CuttingError(ClutchfemError):
    """A design that the chosen process cannot cut: the message names every feature below
    a limit, its size, the limit and the process; ``violations`` lists them.

    Examples
    --------
    >>> import clutchfem as cf
    >>> issubclass(cf.CuttingError, cf.ClutchfemError)
    True
    """

    def __init__(self, violations: list[str], rules: ProcessRules):
        self.violations = list(violations)
        self.rules = rules
        super().__init__(f"the part cannot be cut by {rules.process} ({rules.sources()}): " + "; ".join(violations)
                         + " (change the design, or give the shop's own limits: --min-inside-radius, --min-slot, "
                           "--min-web)")


@dataclass(frozen=True)
class Feature:
    """One measured feature (the smallest of its kind and place; see module docstring)."""

    kind: str  # "inside radius" | "slot" | "web"
    size: float  # [m]
    where: str
    at: tuple[float, float]
    count: int = 1
    parameter: str = ""
    detail: str = ""

    def text(self) -> str:
        name = {"inside radius": ("fillet radius" if self.detail == "fillet" else "inside radius") if self.size > 0
                else "sharp inside corner (radius",
                "slot": "slot width", "web": "web width"}[self.kind]
        size = format_quantity(self.size, "m", digits=4)
        s = f"{self.where} {name} {size}" + (")" if name.endswith("(radius") else "")
        if self.parameter:
            s += f" (= {self.parameter})"
        if self.count > 1:
            s += f" x{self.count}"
        return s

    def to_json(self) -> dict:
        return {"kind": self.kind, "size_m": self.size, "where": self.where, "at_m": list(self.at),
                "count": self.count, "parameter": self.parameter, "text": self.text()}


def zone_of(tag: str) -> str:
    """'flexure_0+hub/contact' -> 'flexure 0'; a bore curve -> 'bore'."""
    if tag.endswith("/bore"):
        return "bore"
    z = tag.split("/")[0].split("+")[0] or "part"
    return z.replace("_", " ")


def family_of(where: str) -> str:
    """'flexure 0' -> 'flexure' (the n shoes' copies of one feature)."""
    return " ".join(w for w in where.split() if not w.isdigit())


#: words of the parameter names that set each kind of feature (preferred when several match)
_WORDS = {"inside radius": ("fillet", "radius", "round"), "slot": ("slot", "gap", "width"),
          "web": ("thickness", "width")}


def parameter_of(params, size: float, kind: str) -> str:
    """The concept's length parameters equal to ``size`` (1e-6 relative), those whose name
    fits the feature's kind first; inert ones (a table value of a non-table profile) left out."""
    if params is None or size <= 0:
        return ""
    P = type(params)
    dump = params.model_dump()
    names = [n for n in P.model_fields if n in dump and P.unit(n) == "m" and isinstance(dump[n], float)
             and abs(dump[n] - size) <= 1e-6 * size
             and not (n == "clearance_tip" and getattr(params, "profile", "") != "linear")]
    fit = [n for n in names if any(w in n for w in _WORDS[kind])]
    return " or ".join(fit or names)


def inside_radii(outline) -> list[Feature]:
    """Every inside radius of the part (arcs, spline stretches and sharp corners turning
    away from the material), the smallest per zone family."""
    found = []
    for lp in outline.loops:
        segs = lp.segments
        for i, s in enumerate(segs):
            if s.kind == "arc" and s.sweep < 0:
                small = s.radius < 0.25 * float(getattr(outline.params, "drum_radius", math.inf))
                kind = "bore" if zone_of(s.tag) == "bore" else ("fillet" if small else "arc")
                found.append((s.radius, zone_of(s.tag), tuple(s.point([0.5])[0]), kind))
            elif s.kind == "spline":
                t = np.linspace(0, 1, 401)
                k = s.curvature(t)
                if np.any(k < 0):
                    j = int(np.argmin(k))
                    found.append((-1.0 / k[j], zone_of(s.tag), tuple(s.point([t[j]])[0]), "spline"))
            nxt = segs[(i + 1) % len(segs)]
            if len(segs) > 1:
                ta, tb = s.tangent(1.0), nxt.tangent(0.0)
                ang = math.atan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb)
                if ang < -1e-6:  # a right turn with the material on the left: an inside corner
                    found.append((0.0, zone_of(s.tag), tuple(s.end), f"corner {math.degrees(-ang):.0f} deg"))
    return _smallest(found, "inside radius", outline.params)


def _smallest(found, kind: str, params) -> list[Feature]:
    groups: dict[str, list] = {}
    for size, where, at, detail in found:
        groups.setdefault(family_of(where), []).append((size, where, at, detail))
    out = []
    for fam, items in groups.items():
        size, where, at, detail = min(items, key=lambda x: x[0])
        n = len({w for s, w, _, _ in items if abs(s - size) <= 1e-9 + 1e-6 * size})
        out.append(Feature(kind, float(size), where, (float(at[0]), float(at[1])), n,
                           parameter_of(params, size, kind), detail))
    return sorted(out, key=lambda f: f.size)


def boundary_samples(segs, *, into: str, spacing: float = SPACING):
    """The outline's segments sampled every ``spacing`` (at least 3 points a segment, its end
    left to the next): points P, unit normals N pointing ``into`` "waste" (right of travel)
    or "material" (left), the segment index S and the curve parameter T of each sample."""
    pts, nrm, sid, par = [], [], [], []
    sign = 1.0 if into == "waste" else -1.0
    for k, s in enumerate(segs):
        n = max(3, int(math.ceil(s.length / spacing)) + 1)
        t = np.linspace(0.0, 1.0, n)[:-1]
        d = s.derivative(t)
        d /= np.linalg.norm(d, axis=1)[:, None]
        pts.append(s.point(t))
        nrm.append(sign * np.column_stack([d[:, 1], -d[:, 0]]))
        sid.append(np.full(len(t), k))
        par.append(t)
    return np.vstack(pts), np.vstack(nrm), np.concatenate(sid), np.concatenate(par)


def widths(outline) -> tuple[list[Feature], list[Feature]]:
    """(slots, webs): the narrowest facing-wall widths per zone family (module docstring)."""
    segs = [s for lp in outline.loops for s in lp.segments]
    P, N, S, T = boundary_samples(segs, into="waste")
    zones = sorted({zone_of(s.tag) for s in segs})
    zid = np.array([zones.index(zone_of(s.tag)) for s in segs], dtype=int)[S]  # each sample's segment's zone
    pairs = cKDTree(P).query_pairs(MAX_WIDTH, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    v = P[j] - P[i]
    dist = np.linalg.norm(v, axis=1)
    u = v / np.maximum(dist, 1e-30)[:, None]
    ci, cj = np.einsum("ij,ij->i", u, N[i]), np.einsum("ij,ij->i", u, N[j])
    cos = math.cos(CONE)
    out = []
    for kind, mask in (("slot", (ci >= cos) & (cj <= -cos)), ("web", (ci <= -cos) & (cj >= cos))):
        a, b, d = i[mask], j[mask], dist[mask]
        za, zb = np.minimum(zid[a], zid[b]), np.maximum(zid[a], zid[b])
        key = za * len(zones) + zb
        found = []
        for k in np.unique(key):
            sel = np.nonzero(key == k)[0]
            m = sel[np.argmin(d[sel])]
            w = _refine(segs[S[a[m]]], T[a[m]], segs[S[b[m]]], T[b[m]], kind, float(d[m]))
            z1, z2 = zones[za[m]], zones[zb[m]]
            if kind == "slot":
                where = f"slot between {z1} and {z2}" if z1 != z2 else f"slot in {z1}"
            else:
                where = z1 if z1 == z2 else f"{z1} / {z2}"
            found.append((w, where, tuple(0.5 * (P[a[m]] + P[b[m]])), ""))
        out.append(_smallest(found, kind, outline.params))
    return out[0], out[1]


def _refine(A, ta: float, B, tb: float, kind: str, coarse: float) -> float:
    """The smallest distance between points of segments A and B near parameters ta, tb whose
    joining line lies within :data:`FACING` of both walls' normals (shrinking windows of
    101 x 101 samples): the width to ~1 nm; ``coarse`` if no such pair is found."""
    sign = 1.0 if kind == "slot" else -1.0
    cos = math.cos(FACING)
    wa, wb = 3 * SPACING / max(A.length, 1e-12), 3 * SPACING / max(B.length, 1e-12)
    best = None
    for _ in range(8):
        sa = np.clip(np.linspace(ta - wa, ta + wa, 101), 0.0, 1.0)
        sb = np.clip(np.linspace(tb - wb, tb + wb, 101), 0.0, 1.0)
        pa, pb = A.point(sa), B.point(sb)
        na, nb = A.derivative(sa), B.derivative(sb)
        na = np.column_stack([na[:, 1], -na[:, 0]]) / np.linalg.norm(na, axis=1)[:, None]
        nb = np.column_stack([nb[:, 1], -nb[:, 0]]) / np.linalg.norm(nb, axis=1)[:, None]
        v = pb[None, :, :] - pa[:, None, :]
        D = np.linalg.norm(v, axis=2)
        u = v / np.maximum(D, 1e-30)[:, :, None]
        ok = (sign * np.einsum("ijk,ik->ij", u, na) >= cos) & (sign * np.einsum("ijk,jk->ij", u, nb) <= -cos)
        if not ok.any():
            break
        D = np.where(ok, D, np.inf)
        k = np.unravel_index(np.argmin(D), D.shape)
        best = float(D[k]) if best is None else min(best, float(D[k]))
        ta, tb = sa[k[0]], sb[k[1]]
        wa, wb = wa / 10, wb / 10
    return coarse if best is None else best


def measure(outline) -> dict[str, list[Feature]]:
    """Every feature kind of the part: {'inside radius': [...], 'slot': [...], 'web': [...]}."""
    slots, webs = widths(outline)
    return {"inside radius": inside_radii(outline), "slot": slots, "web": webs}


def check(features: dict[str, list[Feature]], rules: ProcessRules, thickness: float) -> list[str]:
    """The violations of ``rules`` (one text per feature below its limit); empty: cuttable."""
    lim = rules.limits(thickness)
    what = {"inside radius": ("min_inside_radius", "minimum inside radius"), "slot": ("min_slot", "minimum slot width"),
            "web": ("min_web", "minimum web width")}
    out = []
    for kind, feats in features.items():
        key, label = what[kind]
        for f in feats:
            if f.size < lim[key] * (1 - 1e-9):
                extra = ""
                if key != "min_inside_radius" and lim[key] > getattr(rules, key):
                    extra = f" ({getattr(rules, key + '_per_thickness'):g} x the {thickness * 1e3:g} mm plate)"
                out.append(f"{f.text()} < {rules.process} {label} {format_quantity(lim[key], 'm', digits=4)}{extra}")
    return out
