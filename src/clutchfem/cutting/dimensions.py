"""The dimensions of a workshop drawing, taken from the part's exact outline (and, for a
beam flexure, from the concept's own layout): what is dimensioned, its value, where it
points, and which parameter (and so which ``--tol`` tolerance) it carries.

Every feature is dimensioned once, on shoe 0 (the n shoes are copies, counted ``3x``):

* the bore (diameter) and every radius about the axis (hub, shoe inner face, flexure
  faces, the shoe's contact face: one dimension per distinct radius, on the zone it bounds:
  contact face, then shoe, flexure, hub);
* every small arc of shoe 0's sector (the fillets and slot-end rounds: radius < 1/4 of the
  drum radius), one dimension each with the number of copies;
* the shoe's arc (the contact face's sweep), the pitch of the shoes (360 deg / n) and the
  gap between a shoe's tip and the next shoe's root (a reference: pitch - arc);
* the plate thickness (side view);
* the measured webs and slots (:mod:`.features`), as reference dimensions in parentheses
  (they follow from the others; one per distinct width);
* the thinnest ligament (:mod:`.ligament`), reference;
* a straight beam flexure (a concept whose parameters lay one out: ``layout()`` with the
  beam's hub end H, shoe end S and thicknesses, as concept 4): the beam's length H-S, its
  thickness at both ends (perpendicular to its centre line), its angle to the hub's tangent
  at H, the polar angle of H from the shoe's root face, and (reference) the radii at which
  the centre line and the beam's inner edge meet the root face.

Values are in SI (m, angles in deg); :meth:`Dimension.text` formats them in the sheet's
unit.  A dimension equal to one of the concept's parameters names it, and a tolerance
given for that parameter (``export(..., tolerances={"flexure_thickness": 2e-5})``, the
``--tol`` of ``clutchfem export``) is printed with it; the others fall under the general
tolerance of the title block.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .features import family_of, parameter_of, zone_of


@dataclass(frozen=True)
class Dimension:
    """One dimension of the drawing (module docstring).

    Attributes
    ----------
    key : str
        Stable name (``"bore"``, ``"radius:hub"``, ``"fillet:2"``, ``"flexure_length"``):
        the SVG group id is ``"dim:" + key``.
    kind : {"diameter", "radius", "length", "angle"}
    value : float
        [m], angles [deg].
    name : str
        What it measures, in words.
    view : {"main", "detail", "side"}
    anchor : tuple
        Geometry (m / rad, final frame): diameter and radius ``(cx, cy, r, angle)``; length
        ``(x0, y0, x1, y1)``; angle ``(cx, cy, a0, a1, r)``.
    parameter : str
        The concept parameter it equals ("" if derived).
    count : int
        Copies on the part (``3x``).
    ref : bool
        A reference dimension (derived from the others: in parentheses, no tolerance).
    tol : float or None
        +- half-width from ``--tol`` [m or deg].

    Examples
    --------
    >>> from clutchfem.cutting import Dimension
    >>> Dimension("bore", "diameter", 0.013, "bore", "main", (0, 0, 0.0065, 0.5), "bore_radius",
    ...           tol=2e-5).text()
    'Ø13 ±0.02'
    >>> Dimension("pitch", "angle", 120.0, "pitch", "main", (0, 0, 0, 1, 0.03), count=3).text()
    '3x 120°'
    """

    key: str
    kind: str
    value: float
    name: str
    view: str
    anchor: tuple
    parameter: str = ""
    count: int = 1
    ref: bool = False
    tol: float | None = None

    def number(self, units: str = "mm") -> str:
        """The value alone as printed (mm or in, or deg)."""
        if self.kind == "angle":
            return _fmt(self.value, 2)
        return _fmt(self.value * 1e3, 3) if units == "mm" else _fmt(self.value / 0.0254, 4)

    def text(self, units: str = "mm") -> str:
        """As printed on the sheet: ``Ø13``, ``R0.8``, ``3x R0.8``, ``19 ±0.05``, ``(1.35)``, ``90°``."""
        s = self.number(units)
        if self.kind == "diameter":
            s = "Ø" + s
        elif self.kind == "radius":
            s = "R" + s
        elif self.kind == "angle":
            s += "°"
        if self.tol and not self.ref:
            t = self.tol if self.kind == "angle" else (self.tol * 1e3 if units == "mm" else self.tol / 0.0254)
            s += f" ±{_fmt(t, 3 if self.kind == 'angle' else 4)}" + ("°" if self.kind == "angle" else "")
        if self.ref:
            s = f"({s})"
        if self.count > 1:
            s = f"{self.count}x {s}"
        return s


def _fmt(v: float, digits: int) -> str:
    s = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _index(zone: str) -> int | None:
    w = zone.split()[-1]
    return int(w) if w.isdigit() else None


def _mid_angle(s) -> float:
    m = s.point([0.5])[0]
    c = s.centre if s.kind == "arc" else (0.0, 0.0)
    return math.atan2(m[1] - c[1], m[0] - c[0])


def dimensions(outline, features=None, ligament=None, tolerances: dict | None = None) -> list[Dimension]:
    """Every dimension of the drawing of ``outline`` (module docstring).

    Parameters
    ----------
    outline : PartOutline
    features : dict, optional
        :func:`~clutchfem.cutting.measure`'s result (webs and slots as references).
    ligament : Ligament, optional
        The thinnest ligament (a reference dimension).
    tolerances : dict, optional
        ``{parameter: half-width}`` in the parameter's SI unit (``--tol``).

    Returns
    -------
    list of Dimension
        In drawing order; keys unique.

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.cutting import dimensions, part_outline
    >>> d = cf.Design.from_concept("concept4")
    >>> dims = {x.key: x for x in dimensions(part_outline(d.concept, d.params))}
    >>> dims["bore"].text(), dims["radius:contact"].text(), dims["flexure_thickness_hub"].text()
    ('Ø13', 'R33.8', '3x 1.75')
    """
    p = outline.params
    tol = dict(tolerances or {})
    n = int(getattr(p, "n_shoes", 1))
    segs = [s for lp in outline.loops for s in lp.segments]
    out: list[Dimension] = []

    def add(key, kind, value, name, view, anchor, parameter="", count=1, ref=False):
        t = tol.get(parameter) if parameter and not ref else None
        if t is not None and kind == "diameter" and parameter.endswith("radius"):
            t = 2 * t
        out.append(Dimension(key, kind, float(value), name, view, tuple(float(a) for a in anchor), parameter, count,
                             ref, t))

    def param_of(size: float, kind: str) -> str:
        return parameter_of(p, size, kind).split(" or ")[0]

    # the bore
    bore = [s for lp in outline.loops if lp.layer == "BORE" for s in lp.segments]
    if bore and bore[0].kind == "arc":
        b = bore[0]
        add("bore", "diameter", 2 * b.radius, "bore", "main", (*b.centre, b.radius, math.radians(135)),
            "bore_radius" if abs(b.radius - getattr(p, "bore_radius", -1)) < 1e-9 else "")
    # radii about the axis and large arcs: one per distinct radius
    drum = float(getattr(p, "drum_radius", math.inf))
    big = [s for s in segs if s.kind == "arc" and not s.tag.endswith("/bore") and s.radius >= 0.25 * drum]
    prio = {"contact": 0, "shoe": 1, "flexure": 2, "hub": 3}
    groups: dict[float, list] = {}
    for s in big:
        r = next((r for r in groups if abs(r - s.radius) <= 1e-9 * drum), s.radius)
        groups.setdefault(r, []).append(s)
    ranked: dict[str, list] = {}
    for r, ss in groups.items():
        def role(s):
            return "contact" if "/contact" in s.tag else family_of(zone_of(s.tag))
        best = min(ss, key=lambda s: (prio.get(role(s), 9), _index(zone_of(s.tag)) not in (0, None)))
        ranked.setdefault(role(best), []).append((r, best))
    names = {"contact": "shoe outer face (contact)", "shoe": "shoe inner face", "flexure": "flexure face", "hub": "hub"}
    used = [math.radians(-60.0)]  # leave the lower right to detail A's mark
    for fam in sorted(ranked, key=lambda f: prio.get(f, 9)):
        for k, (r, s) in enumerate(sorted(ranked[fam], key=lambda x: -x[0])):
            key = f"radius:{fam}" + (f":{k + 1}" if k else "")
            centred = math.hypot(*s.centre) < 1e-9 * drum
            ang = _spread(s, groups[r], used) if centred else _mid_angle(s)
            used.append(ang)
            add(key, "radius", r, names.get(fam, fam) + ("" if centred else " (centre off the axis: see DXF)"),
                "main", (*s.centre, r, ang), param_of(r, "inside radius"))
    # small arcs of shoe 0's sector: fillets and slot-end rounds, each once
    small = [s for s in segs if s.kind == "arc" and not s.tag.endswith("/bore") and s.radius < 0.25 * drum]
    sector0 = [s for s in small if _index(zone_of(s.tag)) == 0]
    hub_small = [s for s in small if _index(zone_of(s.tag)) is None]
    if hub_small and sector0:  # the hub's own fillets nearest to shoe 0's
        ref_ang = np.mean([_mid_angle(s) for s in sector0])
        per = max(1, len(hub_small) // max(n, 1))
        hub_small.sort(key=lambda s: abs(math.remainder(math.atan2(*s.point([0.5])[0][::-1]) - ref_ang, 2 * math.pi)))
        sector0 += hub_small[:per]
    for k, s in enumerate(sector0):
        copies = sum(1 for t in small if abs(t.radius - s.radius) <= 1e-9 * drum and family_of(zone_of(t.tag))
                     == family_of(zone_of(s.tag)) and _same_shape(s, t))
        add(f"fillet:{k + 1}", "radius", s.radius, ("slot-end round" if s.sweep < 0 and _touches(s, segs, "shoe")
                                                    else "fillet") + f" ({zone_of(s.tag)})",
            "detail", (*s.centre, s.radius, _mid_angle(s)),
            "fillet_radius" if abs(s.radius - getattr(p, "fillet_radius", -1)) < 1e-9 else "",
            count=max(1, min(copies, n)))
    # shoe arc, pitch, tip gap
    contact = [s for s in segs if "/contact" in s.tag and _index(zone_of(s.tag)) == 0]
    if contact:
        c0 = contact[0]
        a0 = math.atan2(c0.start[1], c0.start[0])
        sweep = sum(abs(s.sweep) if s.kind == "arc" else 0.0 for s in contact)
        a_lo = min(a0, a0 + math.copysign(sweep, c0.sweep if c0.kind == "arc" else 1.0))
        arc_deg = math.degrees(sweep)
        add("shoe_arc", "angle", arc_deg, "shoe arc", "main", (0, 0, a_lo, a_lo + math.radians(arc_deg), 0),
            "shoe_arc" if abs(getattr(p, "shoe_arc", -1) - arc_deg) < 1e-6 else "")
        if n > 1:
            pitch = 360.0 / n
            add("pitch", "angle", pitch, "pitch of the shoes", "main",
                (0, 0, a_lo - math.radians(pitch), a_lo, 0), count=n)
            add("tip_gap", "angle", pitch - arc_deg, "gap between a shoe's tip and the next shoe's root", "main",
                (0, 0, a_lo - math.radians(pitch - arc_deg), a_lo, 0), ref=True)
    add("thickness", "length", outline.thickness, "plate thickness", "side", (0, 0, 0, 0), "thickness")
    # a straight beam flexure
    _beam(p, outline, add)
    # the shoe's radial thickness on its tip face (a reference: the two radii give it)
    if contact:
        inner = [s for s in segs if s.kind == "arc" and family_of(zone_of(s.tag)) == "shoe" and "/contact" not in s.tag
                 and math.hypot(*s.centre) < 1e-9 * drum and s.radius < contact[0].radius]
        if inner and contact[0].kind == "arc" and math.hypot(*contact[0].centre) < 1e-9 * drum:
            r_i, r_o = max(s.radius for s in inner), contact[0].radius
            tip = a_lo if c0.sweep > 0 else a_lo + math.radians(arc_deg)
            e = np.array([math.cos(tip), math.sin(tip)])
            add("shoe_thickness", "length", r_o - r_i, "shoe's radial thickness (tip face)", "main",
                (*(r_i * e), *(r_o * e)), "shoe_thickness" if abs(r_o - r_i - getattr(p, "shoe_thickness", -1)) < 1e-9
                else param_of(r_o - r_i, "web"), count=n, ref=True)
    if ligament is not None:
        add("ligament", "length", ligament.width, "thinnest ligament", "detail", (*ligament.p, *ligament.q),
            count=ligament.count, ref=True)
    return out


def _spread(s, copies, used) -> float:
    """An angle on one of the arcs ``copies`` (same radius about the axis) far from the
    angles ``used`` by other radius leaders (every 5 deg tried)."""
    best, far = _mid_angle(s), -1.0
    for deg in range(-180, 180, 5):
        a = math.radians(deg)
        on = False
        for c in copies:
            a0 = math.atan2(c.start[1] - c.centre[1], c.start[0] - c.centre[0])
            x = math.remainder(a - a0, 2 * math.pi) * (1 if c.sweep > 0 else -1)
            x = x % (2 * math.pi)
            if 0.15 * abs(c.sweep) < x < 0.85 * abs(c.sweep):
                on = True
                break
        if not on:
            continue
        gap = min(abs(math.remainder(a - u, 2 * math.pi)) for u in used + [math.radians(135)])
        if gap > far:
            best, far = a, gap
    return best


def _same_shape(a, b) -> bool:
    return abs(abs(a.sweep) - abs(b.sweep)) < 1e-6


def _touches(s, segs, family: str) -> bool:
    """Does small arc ``s`` join a segment of ``family``'s zone (end to start)?"""
    for t in segs:
        if t is s:
            continue
        if (math.dist(t.start, s.end) < 1e-9 or math.dist(t.end, s.start) < 1e-9) and family_of(zone_of(t.tag)) == family:
            return True
    return False


def _beam(p, outline, add) -> None:
    """The beam dimensions of a concept that lays out one straight beam per shoe (module
    docstring); nothing for others."""
    lay_fn = getattr(p, "layout", None)
    if lay_fn is None:
        return
    try:
        lay = lay_fn()
    except Exception:  # noqa: BLE001 - a concept whose layout is not a beam
        return
    if not all(hasattr(lay, k) for k in ("H", "S", "t_hub", "t_shoe", "centre", "lo", "r_l0")):
        return
    sy = -1.0 if outline.mirrored else 1.0
    H = np.array([lay.H[0], sy * lay.H[1]])
    S = np.array([lay.S[0], sy * lay.S[1]])
    d = (S - H) / np.linalg.norm(S - H)
    nrm = np.array([-d[1], d[0]])
    n = int(getattr(p, "n_shoes", 1))
    L = float(np.linalg.norm(S - H))
    add("flexure_length", "length", L, "beam length (centre line, hub circle to the root face)", "detail",
        (*H, *S), "flexure_length" if abs(L - getattr(p, "flexure_length", -1)) < 1e-9 else "", count=n)
    a, b = H + 0.5 * lay.t_hub * nrm, H - 0.5 * lay.t_hub * nrm
    add("flexure_thickness_hub", "length", lay.t_hub, "beam thickness at the hub end (normal to the centre line)",
        "detail", (*a, *b), "flexure_thickness", count=n)
    a, b = S + 0.5 * lay.t_shoe * nrm, S - 0.5 * lay.t_shoe * nrm
    add("flexure_thickness_shoe", "length", lay.t_shoe, "beam thickness at the shoe end (normal to the centre line)",
        "detail", (*a, *b), "", count=n)
    # angle between the hub's tangent at H and the beam
    tang = np.array([-H[1], H[0]]) / np.linalg.norm(H)
    gam = math.degrees(math.acos(min(1.0, abs(float(tang @ d)))))
    aH = math.atan2(d[1], d[0])
    aT = math.atan2(tang[1], tang[0]) if tang @ d > 0 else math.atan2(-tang[1], -tang[0])
    lo_, hi_ = sorted((aT, aH), key=lambda x: x)
    if hi_ - lo_ > math.pi:
        lo_, hi_ = hi_, lo_ + 2 * math.pi
    add("flexure_angle", "angle", gam, "beam angle to the hub's tangent", "detail", (*H, lo_, hi_, 0),
        "flexure_angle" if abs(gam - getattr(p, "flexure_angle", -1)) < 1e-6 else "", count=n)
    th = math.degrees(math.atan2(H[1], H[0]))
    add("flexure_position", "angle", abs(th), "polar angle of the beam's hub end from the shoe's root face", "main",
        (0, 0, min(0.0, math.radians(th)), max(0.0, math.radians(th)), 0), count=n)
    add("flexure_end", "radius", float(np.linalg.norm(S)), "beam centre line meets the root face", "detail",
        (0, 0, float(np.linalg.norm(S)), 0.0), count=n, ref=True)
    add("flexure_toe", "radius", float(lay.r_l0), "beam's inner edge meets the root face", "detail",
        (0, 0, float(lay.r_l0), 0.0), count=n, ref=True)
