"""Concept 1 (thesis 4.2: A2 B2 C1): solid hub disc, each shoe an arc cut free by a
circumferential slot and joined to the hub by one short bending flexure at its root.

Parametrisation (no figure survives; built from the text).  Per sector, going ccw in the
canonical (plus) frame: a hub *post* (full-radius hub material), the *flexure* (a thin
circumferential beam of length L_f and thickness t_f whose inner edge sits ``flexure_offset``
above the shoe's inner radius), the *shoe* (arc ``shoe_arc``, radial thickness ``shoe_thickness``),
and the *tip gap* g separating the shoe tip from the next post.  Under shoe and flexure runs
the slot of width w; above the flexure a relief opens to the outside.  All cut corners are
rounded with ``fillet_radius``.  The minus arrangement (default) mirrors this.

Defaults (60 cc saw), tuned with the FE model (51CrV4, mu = 0.165, default sector mesh,
modal spin softening, minus arrangement).  The first parametrisation (t_f = 1.6 mm,
L_f = 10 mm, slot 1.5 mm, fillets 0.5 mm) engaged at 3239 rpm (3277 rpm without spin
softening): *below* the engagement window, engagement > a x idle with idle 2700 rpm and the
assumed a = 1.3, i.e. > 3510 rpm (``clutch.analyze.Requirements``), and its flexure reached
1.31 GPa at 14 000 rpm, above Rp0.2 = 1250 MPa.  The thesis optimised concept 1 by "a
longer flexure ... moved to a position that gave better results" and "larger radii at the
flexure to reduce its stresses", ending with the stress at racing speed "just below the
allowable" (4.4-4.5, translated).  Following that recipe: L_f 10 -> 16 mm (lower stress
for the same deflection), t_f 1.6 -> 2.2 mm (a longer flexure is softer, k ~ t^3 / L^3, so
it must be thicker to lift the engagement speed), fillets 0.5 -> 0.9 mm and, so that they
fit (fillet < slot / 2), slot 1.5 -> 2.0 mm.  Result: engagement 3910 rpm (3959 rpm
without spin softening; 3910 rpm on a mesh of half the size), first contact at the shoe
tip; peak von Mises 417 MPa at 4000 rpm and 911 MPa at 14 000 rpm (safety factor 1.37);
shoe mass 20.9 g, R_Tp 28.7 mm unchanged.  Same steps measured one at a time (engagement,
rpm): t_f 2.2 / L_f 10 -> 4983; t_f 2.2 / L_f 16 -> 3863; + fillets 0.9 mm, slot 2 mm ->
3910 (fillets mostly cut the peak stress: 1130 -> 911 MPa at 14 000 rpm).
"""

from __future__ import annotations

import math

from clutchfem.core import param
from clutchfem.geometry import Annotation, Concept, ConceptParams, Shapes
from clutchfem.geometry import occ as G


class Concept1Params(ConceptParams):
    context = "concept1"
    shoe_arc: float = param(75.0, "deg", 10.0, 170.0, "angular extent of each shoe", "beta")
    shoe_thickness: float = param(6.0e-3, "m", 1.5e-3, 20e-3, "radial thickness of the shoe", "t_s")
    slot_width: float = param(2.0e-3, "m", 0.3e-3, 6e-3, "radial width of the slot under shoe and flexure", "w")
    flexure_length: float = param(16e-3, "m", 2e-3, 40e-3, "flexure length (arc length at its centre line)", "L_f")
    flexure_thickness: float = param(2.2e-3, "m", 0.3e-3, 6e-3, "flexure thickness", "t_f")
    flexure_offset: float = param(0.0, "m", 0.0, 15e-3, "radial position of the flexure's inner edge above the shoe's inner edge", "e_f")
    tip_gap: float = param(2.0e-3, "m", 0.5e-3, 10e-3, "circumferential gap between shoe tip and the next hub post", "g")
    fillet_radius: float = param(0.9e-3, "m", 0.0, 5e-3, "fillet radius at slot ends / flexure roots", "rho")

    # derived dimensions ------------------------------------------------------------
    def radii(self):
        r_so = self.drum_radius - max(self.clearance, self.clearance_tip if self.profile == "linear" else 0.0)
        r_si = self.drum_radius - self.clearance - self.shoe_thickness
        r_h = r_si - self.slot_width
        r_fi = r_si + self.flexure_offset
        r_fo = r_fi + self.flexure_thickness
        return r_so, r_si, r_h, r_fi, r_fo

    def angles(self):
        _, r_si, r_h, r_fi, r_fo = self.radii()
        r_fc = 0.5 * (r_fi + r_fo)
        phi_f = self.flexure_length / r_fc
        beta = math.radians(self.shoe_arc)
        phi_g = self.tip_gap / r_h
        post = self.sector_angle - phi_f - beta - phi_g
        return phi_f, beta, phi_g, post

    @classmethod
    def rule_dimensions(cls, v: dict) -> dict:
        """The hub post's width at the slot's bottom radius (its rule: >= 3 mm): the peak
        stress at the flexure's hub-end fillet falls steeply as the post thins towards it
        (BENCHMARKS.md section 24: -6.7 to -21.5 MPa per 0.94 deg of shoe arc)."""
        r_si = v["drum_radius"] - v["clearance"] - v["shoe_thickness"]
        r_h = r_si - v["slot_width"]
        r_fc = r_si + v["flexure_offset"] + 0.5 * v["flexure_thickness"]
        post = 2 * math.pi / v["n_shoes"] - v["flexure_length"] / r_fc - v["shoe_arc"] * (math.pi / 180) - v["tip_gap"] / r_h
        return {"hub_post_width": post * r_h}

    def check(self) -> None:
        r_so, r_si, r_h, r_fi, r_fo = self.radii()
        if r_h < self.bore_radius + 2e-3:
            self.fail("shoe_thickness", f"a shoe + slot that leaves >= 2 mm of hub around the bore "
                                        f"(hub radius {r_h * 1e3:.2f} mm, bore {self.bore_radius * 1e3:.2f} mm)")
        if r_fo > self.drum_radius - self.clearance - 0.3e-3:
            self.fail("flexure_offset", f"<= {(self.shoe_thickness - self.flexure_thickness - 0.3e-3) * 1e3:.2f} mm "
                                        "(flexure must stay 0.3 mm below the shoe's outer surface)")
        if 2 * self.fillet_radius > min(self.slot_width, self.flexure_length, self.tip_gap) - 1e-6:
            self.fail("fillet_radius", f"< half of min(slot_width, flexure_length, tip_gap) = "
                                       f"{0.5 * min(self.slot_width, self.flexure_length, self.tip_gap) * 1e3:.3f} mm")
        phi_f, beta, phi_g, post = self.angles()
        post_min = 3e-3 / r_h
        if post < post_min:
            room = math.degrees(self.sector_angle - phi_f - phi_g - post_min)
            self.fail("shoe_arc", f"<= {room:.1f} deg for n_shoes = {self.n_shoes} (flexure, tip gap and a "
                                  f"3 mm hub post must fit in 360/n)")
        self.check_profile(phi_f, phi_f + beta)


class Concept1(Concept):
    name = "concept1"
    title = "Concept 1: solid hub, one short flexure per shoe"
    thesis = ("A2 B2 C1, like go-kart compliant clutches. Simple to change stiffness or mass; much dead "
              "mass in the hub. Prototype engaged and slipped ~25 % above prediction with contact on "
              "~1/3 of the shoe arc. Kept because it sheds slip heat better.")
    parametrisation = __doc__
    Params = Concept1Params

    def build(self, p: Concept1Params) -> Shapes:
        r_so, r_si, r_h, r_fi, r_fo = p.radii()
        phi_f, beta, phi_g, post = p.angles()
        R_ext = p.drum_radius + 2e-3
        rho = p.fillet_radius
        material, shoes, flexures = [], [], []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            cuts = [
                G.annular_sector(r_h, r_si, a, a + phi_f + beta + phi_g, rho),       # slot under
                G.annular_sector(r_h, R_ext, a + phi_f + beta, a + phi_f + beta + phi_g, rho),  # tip gap
                G.annular_sector(r_fo, R_ext, a, a + phi_f, rho),                     # relief above flexure
                G.annular_sector(r_si, R_ext, a + phi_f, a + phi_f + beta),           # shoe envelope
            ]
            if p.flexure_offset > 0:
                cuts.append(G.annular_sector(r_h, r_fi, a, a + phi_f, min(rho, 0.49 * (r_fi - r_h))))
            if i == 0:
                hub = [G.disk(r_so)]
            hub = G.cut(hub, cuts)
            t0, t1 = a + phi_f, a + phi_f + beta
            shoe = G.shoe_body(r_si, t0, t1, lambda th, a=a: p.outer_radius(th - a, phi_f, phi_f + beta),
                               p.profile, p.eccentric_centre(phi_f, phi_f + beta, a))
            material.append(shoe)
            shoes.append(G.annular_sector(r_si - 0.5 * p.slot_width, R_ext, t0, t1))
            # the zone's start line a quarter of the hub post before the slot's end wall: on the
            # wall itself it would leave the slot's corner fillet tangentially (a wedge of zero
            # angle, degenerate elements at the end of the fillet that carries the peak stress)
            flexures.append(G.annular_sector(0.5 * (r_h + r_fi), R_ext, a - 0.25 * post, a + phi_f))
        part = G.fuse(hub + material)
        return Shapes(material=part, shoe_zones=shoes, flexure_zones=flexures,
                      sector_start=-0.5 * post)

    def shoe_arc(self, p: Concept1Params) -> tuple[float, float]:
        phi_f, beta, _, _ = p.angles()
        return phi_f, phi_f + beta

    def pivot(self, p: Concept1Params) -> tuple[float, float]:
        _, _, _, r_fi, r_fo = p.radii()
        phi_f = p.angles()[0]
        r = 0.5 * (r_fi + r_fo)
        return r * math.cos(0.5 * phi_f), r * math.sin(0.5 * phi_f)

    def annotations(self, p: Concept1Params) -> list[Annotation]:
        r_so, r_si, r_h, r_fi, r_fo = p.radii()
        phi_f, beta, phi_g, _ = p.angles()
        pol = lambda r, t: (r * math.cos(t), r * math.sin(t))
        rf = 0.5 * (r_fi + r_fo)
        return [
            Annotation(f"flexure t_f = {p.flexure_thickness * 1e3:.2f} mm, L_f = {p.flexure_length * 1e3:.1f} mm"
                       + (f", e_f = {p.flexure_offset * 1e3:.1f} mm above the shoe's inner edge"
                          if p.flexure_offset > 0 else ""),
                       pol(rf, 0.5 * phi_f), pol(p.drum_radius * 1.35, 0.5 * phi_f - 0.35)),
            Annotation(f"shoe: beta = {p.shoe_arc:.0f} deg, t_s = {p.shoe_thickness * 1e3:.1f} mm",
                       pol(0.5 * (r_si + r_so), phi_f + 0.5 * beta), pol(p.drum_radius * 1.35, phi_f + 0.5 * beta)),
            Annotation(f"slot w = {p.slot_width * 1e3:.1f} mm", pol(r_si - 0.5 * p.slot_width, phi_f + 0.8 * beta),
                       pol(p.drum_radius * 0.55, phi_f + 1.1 * beta)),
            Annotation(f"tip gap g = {p.tip_gap * 1e3:.1f} mm", pol(r_so, phi_f + beta + 0.5 * phi_g),
                       pol(p.drum_radius * 1.3, phi_f + beta + 0.5 * phi_g + 0.2)),
            Annotation(f"fillets rho = {p.fillet_radius * 1e3:.2f} mm", pol(r_h + p.fillet_radius, 0.0), None),
        ]


CONCEPT = Concept1()
