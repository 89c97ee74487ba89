"""Concept 2 (thesis 4.2): concept 1 plus a second flexure inside the shoe -- two springs in
series, meant to make the engagement easier to tune and to let the shoe's outer part
deflect more and fit the drum better.

Parametrisation (no figure survives; built from the text).  Everything of concept 1 (solid
hub, slot under shoe and flexure, root flexure of length L_f and thickness t_f, shoe arc
beta, tip gap; see ``concept1``), plus: at ``flexure2_position`` (fraction of the shoe arc
from its root) the shoe is cut radially from the slot outwards, ``flexure2_gap`` wide,
leaving a thin ligament of radial thickness ``flexure2_thickness`` (t_2) *at the outer
surface*.  That ligament is the second flexure: a short hinge in series with the root
flexure, about which the shoe's tip segment can rotate outwards.  It lies on the contact
surface -- which is exactly why the thesis eliminated the concept: the thin ligament rubs
on the drum and takes the slip heat (making it thicker removes its function).  The cut's
two concave corners under the ligament are rounded with ``fillet_radius``.

Why the second flexure has its own thickness ``flexure2_thickness`` (t_2) rather than
following the root flexure's t_f: the thesis (4.4; quotes translated from Swedish)
optimised concept 2 "so that the two flexible
elements get their deflection at different speeds" and found that the extra element
"mostly gave a better fit at engagement"; it was eliminated because the *thin* extra element
touches the drum and "would have had to be thicker, and then the concept would have lost
the function of its extra bending element".  Both statements make the ligament's thickness a
design variable of its own, independent of (and thinner than) the root flexure.  Measured
with the FE model (defaults otherwise, modal spin softening): t_2 = 0.8 / 1.2 / 2.0 mm
engage at 3376 / 3835 / 4089 rpm, so t_2 is a tuning knob as strong as t_f.  The mesh is
refined in the flexure zones for the thinner of t_f and t_2
(``ConceptParams.flexure_thicknesses``).

Zones: ``flexure_<i>`` holds both flexures of shoe i (root flexure and ligament, one
surface bridged through the empty slot); ``shoe_<i>`` holds the two shoe segments (front and
tip), bridged under the ligament.  The contact surface includes the ligament's outside.

Defaults (60 cc saw): concept 1's (L_f = 16 mm, slot 2 mm, fillets 0.9 mm), with the root
flexure thickened from 2.2 to 2.3 mm to make up for the compliance of a 1.2 mm ligament at
45 % of the arc, and a 2.0 mm cut under the ligament (room for its two 0.9 mm fillets).
FE engagement (51CrV4, default sector mesh, modal spin softening) 3835 rpm, first contact
at the shoe tip: inside the engagement window (> 1.3 x 2700 rpm idle = 3510 rpm).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from clutchfem.core import param
from clutchfem.geometry import Annotation, Shapes, load_concept_file
from clutchfem.geometry import occ as G
from clutchfem.geometry import sketch as K

_C1 = load_concept_file(str(Path(__file__).resolve().with_name("concept1.py")))
Concept1 = type(_C1)
Concept1Params = Concept1.Params


class Concept2Params(Concept1Params):
    context = "concept2"
    flexure_thickness: float = param(2.3e-3, "m", 0.3e-3, 6e-3, "root flexure thickness", "t_f")
    flexure2_position: float = param(0.45, "-", 0.15, 0.85,
                                     "position of the second flexure (ligament) as a fraction of the shoe arc from "
                                     "its root", "s_2")
    flexure2_thickness: float = param(1.2e-3, "m", 0.3e-3, 5e-3,
                                      "radial thickness of the second flexure (ligament at the outer surface)", "t_2")
    flexure2_gap: float = param(2.0e-3, "m", 0.4e-3, 6e-3,
                                "width of the radial cut under the ligament (= the ligament's length)", "g_2")

    def ligament(self):
        """(centre angle, half angle of the cut, ligament inner radius) of shoe 0, canonical."""
        phi_f, beta, _, _ = self.angles()
        t2 = phi_f + self.flexure2_position * beta
        r_o = float(self.outer_radius(np.array([t2]), phi_f, phi_f + beta)[0])
        r_lig = r_o - self.flexure2_thickness
        return t2, 0.5 * self.flexure2_gap / r_lig, r_lig

    def check(self) -> None:
        super().check()
        rho = self.fillet_radius
        _, r_si, _, _, _ = self.radii()
        phi_f, beta, _, _ = self.angles()
        t2, half, r_lig = self.ligament()
        if r_lig - r_si < 2 * rho + 0.5e-3 - 1e-12:
            room = self.shoe_thickness - 2 * rho - 0.5e-3
            self.fail("flexure2_thickness", f"<= {room * 1e3:.2f} mm (the cut under the ligament must reach "
                                            "2 fillet radii + 0.5 mm into the shoe)")
        if self.flexure2_gap < 2 * rho + 0.1e-3:
            self.fail("flexure2_gap", f">= 2 x fillet_radius + 0.1 mm = {(2 * rho + 0.1e-3) * 1e3:.2f} mm")
        seg_min = 2e-3 / r_si + half
        lo, hi = phi_f + seg_min, phi_f + beta - seg_min
        if not (lo <= t2 <= hi):
            if lo > hi:
                self.fail("shoe_arc", "wider: the shoe cannot hold the second flexure with >= 2 mm segments on "
                                      "both sides")
            self.fail("flexure2_position", f"in [{(lo - phi_f) / beta:.3f}, {(hi - phi_f) / beta:.3f}] (>= 2 mm of "
                                           "shoe on both sides of the cut)")


class Concept2(Concept1):
    name = "concept2"
    title = "Concept 2: concept 1 + a second flexure (ligament) in the shoe"
    thesis = ("Same basis as concept 1 with one more flexible element: meant to make the engagement speed easier "
              "to set, to need less radius fitting of the whole shoe and to let the shoe's outer part deflect "
              "more; drawback: hard to balance the mass of the two parts of each shoe. Optimised so the two "
              "flexures deflect at different speeds; the extra flexure mostly improved the fit at engagement. "
              "Eliminated: the thin extra flexure touches the drum and cannot take the heat of slip and braking.")
    parametrisation = __doc__
    Params = Concept2Params

    def build(self, p: Concept2Params) -> Shapes:
        shapes = super().build(p)
        r_so, r_si, r_h, r_fi, r_fo = p.radii()
        phi_f, beta, _, _ = p.angles()
        t2, half, r_lig = p.ligament()
        w = p.slot_width
        rho = p.fillet_radius
        R_ext = p.drum_radius + 2e-3
        cuts = []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            cuts.append(G.annular_sector(r_si - 0.5 * w, r_lig, a + t2 - half, a + t2 + half, rho))
        material = G.cut(shapes.material, cuts)
        # zones: drop concept 1's, draw the two-flexure / two-segment zones
        G.occ.remove([(2, t) for t in shapes.shoe_zones + shapes.flexure_zones], recursive=True)
        hz = half + p.flexure2_thickness / r_lig
        rb0, rb1 = r_h + 0.45 * w, r_h + 0.55 * w
        rs0, rs1 = r_si - 0.5 * w, r_si - 0.25 * w
        shoes, flexures = [], []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            f = K.Outline(K.polar(rb0, a)).line_to(K.polar(R_ext, a))
            f.arc_to(K.polar(R_ext, a + phi_f)).line_to(K.polar(rb1, a + phi_f))
            f.arc_to(K.polar(rb1, a + t2 - hz)).line_to(K.polar(R_ext, a + t2 - hz))
            f.arc_to(K.polar(R_ext, a + t2 + hz)).line_to(K.polar(rb0, a + t2 + hz))
            f.arc_to(K.polar(rb0, a), ccw=False)
            flexures.append(f.close().surface())
            s = K.Outline(K.polar(rs0, a + phi_f)).line_to(K.polar(R_ext, a + phi_f))
            s.arc_to(K.polar(R_ext, a + t2 - hz)).line_to(K.polar(rs1, a + t2 - hz))
            s.arc_to(K.polar(rs1, a + t2 + hz)).line_to(K.polar(R_ext, a + t2 + hz))
            s.arc_to(K.polar(R_ext, a + phi_f + beta)).line_to(K.polar(rs0, a + phi_f + beta))
            s.arc_to(K.polar(rs0, a + phi_f), ccw=False)
            shoes.append(s.close().surface())
        return Shapes(material=material, shoe_zones=shoes, flexure_zones=flexures,
                      sector_start=shapes.sector_start)

    def annotations(self, p: Concept2Params) -> list[Annotation]:
        out = super().annotations(p)
        t2, half, r_lig = p.ligament()
        R = p.drum_radius
        out.append(Annotation(f"2nd flexure at s_2 = {p.flexure2_position:.2f} of the arc: t_2 = "
                              f"{p.flexure2_thickness * 1e3:.2f} mm at the contact surface, gap g_2 = "
                              f"{p.flexure2_gap * 1e3:.1f} mm",
                              tuple(K.polar(r_lig + 0.5 * p.flexure2_thickness, t2)),
                              tuple(K.polar(1.4 * R, t2 + 0.75))))
        return out


CONCEPT = Concept2()
