"""The thinnest ligament of a part: the narrowest section of material, where it is and how
many of the shoes have it.

Definition.  A *section* of the part is a chord p-q between two boundary points whose
joining line is normal to the boundary at both ends (within :data:`FACING`) and runs
through the material, with the disc on p-q as diameter empty of boundary (the inscribed
circle that touches the outline at p and q: a point of the part's medial axis).  Its
length is the material's width there.  The **thinnest ligament** is the shortest such
chord with at least one end on a zone of ``zones`` (default: the flexures; every zone if the
part has none of them).  A sharp or rounded *outside* corner is not a section (its walls do
not face each other), so the width never collapses to zero at a corner; between parallel
walls and concentric arcs the chord is exact, and a straight strip of thickness t has
width t everywhere.

Method.  The outline is sampled every :data:`SPACING` with its normals; pairs facing each
other across the material within :data:`CONE` whose midpoint is at least half their
distance (less one sample spacing) from every boundary sample are candidates; the
shortest is refined on the exact segments (shrinking windows, as
:func:`~clutchfem.cutting.features._refine`) to the shortest chord facing within
:data:`FACING`.

Why it is not ``flexure_thickness``.  A concept's thickness parameter is the beam's
thickness where the concept defines it, not the narrowest section of the part.  Concept
4's ``flexure_thickness`` (t_f = 1.75 mm) is the beam's thickness at its *hub* end,
perpendicular to its centre line; the beam widens to t_f x ``flexure_taper`` = 2.275 mm at
the shoe end.  But the beam meets the shoe's root face obliquely, and the round that ends
the slot between beam and shoe (radius >= ``fillet_radius``) is cut into the heel, inside
the shoe's angular span.  What joins beam and shoe there is the material between that
round and the root face: 1.35 mm at the defaults (the round's centre 2.15 mm from the
root-face line, less its 0.8 mm radius), at radius ~26.9 mm, where the beam's bending
moment is largest.  That is what ``export`` reports as "flexure 1 web width 1.35 mm x3"
(:mod:`.features`, the manufacturability web) and what :func:`thinnest_ligament` finds: the
fatigue-critical section is the heel ligament, not the parameter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..core import format_quantity
from .features import boundary_samples, family_of, zone_of

#: boundary sample spacing [m]
SPACING = 0.1e-3
#: half-angle within which two samples face each other (candidate pairs)
CONE = math.radians(20.0)
#: the refined chord is normal to both walls within this angle
FACING = math.radians(3.0)
#: widths above this [m] are not looked for
MAX_WIDTH = 8e-3


@dataclass(frozen=True)
class Ligament:
    """The thinnest section of a part (lengths in m, final frame of the outline).

    Attributes
    ----------
    width : float
        The section's width [m].
    p, q : tuple of float
        Its two ends on the outline [m].
    where : str
        The zones its ends lie on (``"flexure 0"``, ``"flexure 0 / shoe 0"``).
    count : int
        How many of the n shoes' copies have the same width (1e-6 relative).

    Examples
    --------
    >>> from clutchfem.cutting import Ligament
    >>> lg = Ligament(1.35e-3, (26.6e-3, -1.35e-3), (26.6e-3, 0.0), "flexure 0", 3)
    >>> lg.text()
    'thinnest ligament 1.35 mm (flexure 0, at r = 26.61 mm, -1.5 deg) x3'
    """

    width: float
    p: tuple[float, float]
    q: tuple[float, float]
    where: str
    count: int = 1

    @property
    def at(self) -> tuple[float, float]:
        """Midpoint of the section [m]."""
        return (0.5 * (self.p[0] + self.q[0]), 0.5 * (self.p[1] + self.q[1]))

    @property
    def radius(self) -> float:
        """Distance of the midpoint from the axis [m]."""
        return float(math.hypot(*self.at))

    @property
    def angle_deg(self) -> float:
        """Polar angle of the midpoint [deg] (final frame, x axis 0)."""
        return float(math.degrees(math.atan2(self.at[1], self.at[0])))

    def text(self) -> str:
        s = (f"thinnest ligament {format_quantity(self.width, 'm', digits=4)} ({self.where}, at r = "
             f"{self.radius * 1e3:.2f} mm, {self.angle_deg:.1f} deg)")
        return s + (f" x{self.count}" if self.count > 1 else "")

    def to_json(self) -> dict:
        return {"width_m": self.width, "p_m": list(self.p), "q_m": list(self.q), "at_m": list(self.at),
                "radius_m": self.radius, "angle_deg": self.angle_deg, "where": self.where, "count": self.count,
                "text": self.text()}


def thinnest_ligament(outline, zones: tuple[str, ...] = ("flexure",)) -> Ligament | None:
    """The thinnest section of the part (module docstring), on the given zone families.

    Parameters
    ----------
    outline : PartOutline
        The part (:func:`~clutchfem.cutting.part_outline`), or any object with ``loops``
        (outer loop ccw, holes cw) whose segments carry zone tags.
    zones : tuple of str
        Zone families (``"flexure"``, ``"shoe"``, ``"hub"``) one end of the section must lie
        on; when the part has none of them, the whole part.

    Returns
    -------
    Ligament or None
        None if the part has no section narrower than :data:`MAX_WIDTH`.

    Examples
    --------
    A straight strip 2 mm thick between two blocks (the flexure zone): its thinnest section
    is the strip.

    >>> from clutchfem.mesh import Loop, Segment
    >>> from clutchfem.cutting import thinnest_ligament
    >>> from types import SimpleNamespace
    >>> pts = [(0, 0), (8e-3, 0), (8e-3, 4e-3), (18e-3, 4e-3), (18e-3, 0), (26e-3, 0), (26e-3, 8e-3),
    ...        (18e-3, 8e-3), (18e-3, 6e-3), (8e-3, 6e-3), (8e-3, 8e-3), (0, 8e-3)]
    >>> tag = lambda a, b: "flexure_0" if 8e-3 < 0.5 * (a[0] + b[0]) < 18e-3 else "hub"
    >>> segs = [Segment("line", a, b, tag=tag(a, b)) for a, b in zip(pts, pts[1:] + pts[:1])]
    >>> lg = thinnest_ligament(SimpleNamespace(loops=(Loop(tuple(segs)),)))
    >>> round(lg.width * 1e3, 6), lg.where
    (2.0, 'flexure 0')
    """
    segs = [s for lp in outline.loops for s in lp.segments]
    if not segs:
        return None
    P, N, S, T = boundary_samples(segs, into="material", spacing=SPACING)
    zone = [zone_of(s.tag) for s in segs]
    fam = [family_of(z) for z in zone]  # per segment (a sample's is its segment's)
    fams = set(fam)
    want = {f for f in zones if f in fams} or fams
    on = np.array([f in want for f in fam], dtype=bool)[S]
    tree = cKDTree(P)
    pairs = tree.query_pairs(MAX_WIDTH, output_type="ndarray")
    if len(pairs) == 0:
        return None
    i, j = pairs[:, 0], pairs[:, 1]
    keep = on[i] | on[j]
    i, j = i[keep], j[keep]
    v = P[j] - P[i]
    dist = np.linalg.norm(v, axis=1)
    u = v / np.maximum(dist, 1e-30)[:, None]
    cos = math.cos(CONE)
    face = (np.einsum("ij,ij->i", u, N[i]) >= cos) & (np.einsum("ij,ij->i", u, N[j]) <= -cos)
    i, j, dist = i[face], j[face], dist[face]
    if len(i) == 0:
        return None
    mid = 0.5 * (P[i] + P[j])
    near, _ = tree.query(mid)
    inscribed = near >= 0.5 * dist - 1.5 * SPACING
    i, j, dist = i[inscribed], j[inscribed], dist[inscribed]
    if len(i) == 0:
        return None
    # the narrowest chord of each pair of segments, refined; the shortest of them wins
    best = None
    order = np.argsort(dist)
    seen = set()
    for m in order[:400]:
        key = (int(S[i[m]]), int(S[j[m]]))
        if key in seen:
            continue
        seen.add(key)
        if best is not None and dist[m] > best[0] + 4 * SPACING:
            break
        w, pa, pb = _refine(segs[S[i[m]]], T[i[m]], segs[S[j[m]]], T[j[m]], float(dist[m]), P[i[m]], P[j[m]])
        if best is None or w < best[0]:
            best = (w, pa, pb, S[i[m]], S[j[m]])
    w, pa, pb, sa, sb = best
    za, zb = zone[sa], zone[sb]
    where = za if za == zb else " / ".join(sorted((za, zb)))
    # copies on the other shoes: chords of the same width between zones of the same families
    fa, fb = family_of(za), family_of(zb)
    same = np.nonzero(np.abs(dist - w) <= 2 * SPACING + 1e-6 * w)[0]
    seg_pairs = set(zip(S[i[same]].tolist(), S[j[same]].tolist()))  # their segment pairs, each once
    shoes = {z.split()[-1] for a, b in seg_pairs for z in (zone[a], zone[b])
             if {fam[a], fam[b]} == {fa, fb} and z.split()[-1].isdigit()}
    # reported on shoe 0's copy when it has one (the drawing dimensions shoe 0)
    for m in same:
        zs = (zone[S[i[m]]], zone[S[j[m]]])
        if {fam[S[i[m]]], fam[S[j[m]]]} == {fa, fb} and any(z.endswith(" 0") for z in zs) and not (
                za.endswith(" 0") or zb.endswith(" 0")):
            w0, qa, qb = _refine(segs[S[i[m]]], T[i[m]], segs[S[j[m]]], T[j[m]], float(dist[m]), P[i[m]], P[j[m]])
            if abs(w0 - w) <= 1e-6 * w:
                w, pa, pb = w0, qa, qb
                where = zs[0] if zs[0] == zs[1] else " / ".join(sorted(zs))
                break
    return Ligament(float(w), (float(pa[0]), float(pa[1])), (float(pb[0]), float(pb[1])), where, max(1, len(shoes)))


def _refine(A, ta: float, B, tb: float, coarse: float, pa0, pb0):
    """The shortest chord between segments A and B near parameters ta, tb that is normal to
    both within :data:`FACING` (across the material): (width, pa, pb)."""
    cos = math.cos(FACING)
    wa, wb = 3 * SPACING / max(A.length, 1e-12), 3 * SPACING / max(B.length, 1e-12)
    best = (coarse, np.asarray(pa0, float), np.asarray(pb0, float))
    for _ in range(8):
        sa = np.clip(np.linspace(ta - wa, ta + wa, 81), 0.0, 1.0)
        sb = np.clip(np.linspace(tb - wb, tb + wb, 81), 0.0, 1.0)
        pa, pb = A.point(sa), B.point(sb)
        na, nb = A.derivative(sa), B.derivative(sb)
        na = np.column_stack([-na[:, 1], na[:, 0]]) / np.linalg.norm(na, axis=1)[:, None]
        nb = np.column_stack([-nb[:, 1], nb[:, 0]]) / np.linalg.norm(nb, axis=1)[:, None]
        v = pb[None, :, :] - pa[:, None, :]
        D = np.linalg.norm(v, axis=2)
        u = v / np.maximum(D, 1e-30)[:, :, None]
        ok = (np.einsum("ijk,ik->ij", u, na) >= cos) & (np.einsum("ijk,jk->ij", u, nb) <= -cos)
        if not ok.any():
            break
        D = np.where(ok, D, np.inf)
        k = np.unravel_index(np.argmin(D), D.shape)
        if D[k] < best[0] or _ == 0:
            best = (float(D[k]), pa[k[0]], pb[k[1]])
        ta, tb = sa[k[0]], sb[k[1]]
        wa, wb = wa / 8, wb / 8
    return best
