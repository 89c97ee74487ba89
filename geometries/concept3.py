"""Concept 3 (thesis 4.2: A1+A2, B5, C2): each shoe sits on a long radial spoke that is meant
to *stretch* (tension), so that the whole shoe translates radially onto the drum.

Parametrisation (no figure survives; built from the text).  A hub disc of radius
``hub_radius`` (r_h); per shoe one straight radial spoke of constant width ``spoke_width``
(w_s) from the hub to the middle of the shoe's inner surface; the shoe is an arc of
``shoe_arc`` (beta) centred on the spoke, radial thickness ``shoe_thickness`` (t_s), outer
surface after the chosen profile.  The four concave corners (spoke/hub, spoke/shoe) are
rounded with exact tangent fillets of ``fillet_radius``.  The part is built as one
analytic outline.  In the canonical frame shoe 0 spans [0, beta]; the spoke is at beta/2.

The shoe is symmetric about its spoke, so plus and minus are mirror images of the same
part (A1+A2: one half of the shoe leads, the other trails); the "root" of the contact arc
(angle 0) only matters for the linear profile (clearance c at angle 0, c_tip at beta).
The nominal pivot returned is the spoke-shoe joint: the shoe translates (C2) rather than
rotates.  Zones: ``shoe_<i>`` is the shoe arc, ``flexure_<i>`` the spoke (the intended
spring, in tension) with its fillets.

Why it was eliminated, in numbers (steel, defaults): spoke stiffness in tension
E w_s h / L = 210e9 * 4e-3 * 11e-3 / 17.8e-3 ~ 5.2e8 N/m against a shoe of m = 18.9 g at
R_Tp = 28.9 mm: at 10 000 rpm (F = m R_Tp w^2 ~ 600 N) the spoke stretches ~1.2 um, far
short of the 0.6 mm clearance.  The only compliance left is the bending of the shoe wings
about the spoke-shoe joint -- where the thesis saw high bending stresses, which led to
concept 3.1.  The FE model (default mesh) puts first contact at the wing tips only at
~62 000 rpm: the concept never engages.
"""

from __future__ import annotations

import math

import numpy as np

from clutchfem.core import param
from clutchfem.geometry import Annotation, Concept, ConceptParams, Shapes
from clutchfem.geometry import occ as G
from clutchfem.geometry import sketch as K


class Concept3Params(ConceptParams):
    context = "concept3"
    fillet_radius: float = param(1.0e-3, "m", 0.0, 5e-3, "fillet radius at the spoke's ends", "rho")
    hub_radius: float = param(11e-3, "m", 5e-3, 25e-3, "radius of the hub disc", "r_h")
    spoke_width: float = param(4.0e-3, "m", 1.0e-3, 15e-3, "width of the radial spoke", "w_s")
    shoe_arc: float = param(80.0, "deg", 15.0, 170.0, "angular extent of each shoe (centred on its spoke)", "beta")
    shoe_thickness: float = param(5.0e-3, "m", 1.5e-3, 15e-3, "radial thickness of the shoe", "t_s")

    def r_si(self) -> float:
        return self.drum_radius - self.clearance - self.shoe_thickness

    def spoke_lines(self) -> tuple[K.Line, K.Line]:
        """(cw side, ccw side) of shoe 0's spoke, directed outward."""
        tc = 0.5 * math.radians(self.shoe_arc)
        axis = K.radial_line(tc)
        return axis.offset(-0.5 * self.spoke_width), axis.offset(0.5 * self.spoke_width)

    def fillets(self):
        """Fillets of shoe 0: {(side, 'hub'|'shoe'): (centre, tangent on spoke, tangent on circle)}."""
        r_si, rh, rho = self.r_si(), self.hub_radius, self.fillet_radius
        out = {}
        for side, line, sgn in (("cw", self.spoke_lines()[0], -1.0), ("ccw", self.spoke_lines()[1], +1.0)):
            for where, R, outside in (("hub", rh, True), ("shoe", r_si, False)):
                ss = line.circle_params(R)
                if not ss:
                    return None
                X = line.at(ss[1])
                if rho == 0:
                    out[(side, where)] = (X, X, X)
                    continue
                f = K.fillet_line_circle(line, sgn, R, outside, rho, X)
                if f is None:
                    return None
                out[(side, where)] = f
        return out

    def check(self) -> None:
        Theta = self.sector_angle
        beta = math.radians(self.shoe_arc)
        rh, rho, ws = self.hub_radius, self.fillet_radius, self.spoke_width
        r_si = self.r_si()
        if rh < self.bore_radius + 2.5e-3:
            self.fail("hub_radius", f">= bore radius + 2.5 mm = {(self.bore_radius + 2.5e-3) * 1e3:.2f} mm")
        if r_si - rh < 2 * rho + 3e-3:
            self.fail("shoe_thickness", f"<= {(self.drum_radius - self.clearance - rh - 2 * rho - 3e-3) * 1e3:.2f} mm "
                                        "(the spoke needs >= 3 mm of free length between its end fillets)")
        if 0.5 * ws + rho > 0.7 * rh:
            self.fail("spoke_width", f"<= {2 * (0.7 * rh - rho) * 1e3:.2f} mm (spoke plus fillets must fit on the hub)")
        gap_min = max(1.5e-3, 2 * rho)
        beta_max = Theta - gap_min / r_si
        if beta > beta_max:
            self.fail("shoe_arc", f"<= {math.degrees(beta_max):.1f} deg for n_shoes = {self.n_shoes} "
                                  f"(gap >= {gap_min * 1e3:.1f} mm between neighbouring shoes)")
        wing_min = 0.5 * ws + rho + 1.0e-3
        if 0.5 * beta * r_si < wing_min:
            self.fail("shoe_arc", f">= {math.degrees(2 * wing_min / r_si):.1f} deg (each shoe half must reach "
                                  "beyond the spoke and its fillets)")
        self.check_profile(0.0, beta)
        f = self.fillets()
        if f is None:
            self.fail("fillet_radius", "smaller: no tangent fillet fits at the spoke's ends")
        for side, line in zip(("cw", "ccw"), self.spoke_lines()):
            if line.param(f[(side, "shoe")][1]) - line.param(f[(side, "hub")][1]) < 1e-3:
                self.fail("fillet_radius", "smaller: the spoke's fillets overlap (keep >= 1 mm straight spoke)")


class Concept3(Concept):
    name = "concept3"
    title = "Concept 3: shoe on a long radial spoke in tension"
    thesis = ("A1+A2, B5 (tension), C2 (radial translation): the long spoke of the hub was meant to stretch so "
              "the whole shoe meets the drum, which would make the contact easy to fit. Tension needs far "
              "more force than bending: FEM gave far too little deflection, and high bending stresses at "
              "the spoke-shoe joint. Eliminated; the joint bending led to concept 3.1.")
    parametrisation = __doc__
    Params = Concept3Params

    def outline(self, p: Concept3Params) -> K.Outline:
        """The part's boundary (all shoes, canonical frame), one closed loop traversed ccw:
        hub arc, spoke/hub fillet, spoke's cw side, spoke/shoe fillet, shoe's inner surface
        back to its root end, :meth:`shoe_top` (root face, outer profile, tip face), the
        shoe's inner surface forward to the spoke, and the spoke's ccw side down to the hub."""
        beta = math.radians(p.shoe_arc)
        r_si = p.r_si()
        f = p.fillets()
        rho = p.fillet_radius
        out = None
        for i in range(p.n_shoes):
            R = lambda q, a=i * p.sector_angle: K.rotate(np.asarray(q, float), a)  # noqa: E731
            c, tl, tc = f[("cw", "hub")]
            if out is None:
                out = K.Outline(R(tc))
            else:
                out.arc_to(R(tc), ccw=True)                          # hub between spokes
            if rho > 0:
                out.arc_to(R(tl), R(c), ccw=False)
            c, tl, tc = f[("cw", "shoe")]
            out.line_to(R(tl))                                       # spoke, cw side
            if rho > 0:
                out.arc_to(R(tc), R(c), ccw=False)
            out.arc_to(R(K.polar(r_si, 0.0)), ccw=False)             # under the shoe to its root end
            self.shoe_top(out, p, R)
            out.line_to(R(K.polar(r_si, beta)))                      # tip face
            c, tl, tc = f[("ccw", "shoe")]
            out.arc_to(R(tc), ccw=False)                             # under the shoe back to the spoke
            if rho > 0:
                out.arc_to(R(tl), R(c), ccw=False)
            c, tl, tc = f[("ccw", "hub")]
            out.line_to(R(tl))                                       # spoke, ccw side
            if rho > 0:
                out.arc_to(R(tc), R(c), ccw=False)
        out.arc_to(out.points[0], ccw=True)
        return out.close()

    def shoe_top(self, out: K.Outline, p: Concept3Params, R) -> None:
        """From the shoe's inner root corner: root face and the outer profile to the tip."""
        beta = math.radians(p.shoe_arc)
        out.line_to(R(K.polar(float(p.outer_radius(np.array([0.0]), 0.0, beta)[0]), 0.0)))
        K.add_profile(out, p, R, 0.0, beta, 0.0, beta)

    def zones(self, p: Concept3Params) -> tuple[list[int], list[int]]:
        """(shoe zones, flexure zones): the shoe arc, and the spoke with its fillets (the
        annulus between hub and shoe over the spoke; its radial sides in the empty windows)."""
        beta = math.radians(p.shoe_arc)
        r_si = p.r_si()
        R_ext = p.drum_radius + 2e-3
        tc = 0.5 * beta
        f = p.fillets()
        half = max(abs(K.angle_of(f[(side, where)][k]) - tc) for side in ("cw", "ccw")
                   for where in ("hub", "shoe") for k in (1, 2)) + 0.5e-3 / p.hub_radius
        half = min(half, 0.5 * (tc + 0.5 * (p.sector_angle - beta)))
        shoes, flexures = [], []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            shoes.append(G.annular_sector(r_si, R_ext, a, a + beta))
            flexures.append(G.annular_sector(p.hub_radius, r_si, a + tc - half, a + tc + half))
        return shoes, flexures

    def build(self, p: Concept3Params) -> Shapes:
        out = self.outline(p)
        K.check_outlines(self.name, p, out)
        part = out.surface()
        shoes, flexures = self.zones(p)
        return Shapes(material=[part], shoe_zones=shoes, flexure_zones=flexures,
                      sector_start=0.5 * (math.radians(p.shoe_arc) - p.sector_angle))

    def shoe_arc(self, p: Concept3Params) -> tuple[float, float]:
        return 0.0, math.radians(p.shoe_arc)

    def pivot(self, p: Concept3Params) -> tuple[float, float]:
        tc = 0.5 * math.radians(p.shoe_arc)
        return tuple(K.polar(p.r_si(), tc))

    def annotations(self, p: Concept3Params) -> list[Annotation]:
        beta = math.radians(p.shoe_arc)
        tc = 0.5 * beta
        r_si = p.r_si()
        R = p.drum_radius
        r_mid = 0.5 * (p.hub_radius + r_si)
        return [
            Annotation(f"spoke w_s = {p.spoke_width * 1e3:.1f} mm, L = {(r_si - p.hub_radius) * 1e3:.1f} mm "
                       "(tension)", tuple(K.polar(r_mid, tc)), tuple(K.polar(1.4 * R, tc - 0.9))),
            Annotation(f"shoe: beta = {p.shoe_arc:.0f} deg, t_s = {p.shoe_thickness * 1e3:.1f} mm",
                       tuple(K.polar(r_si + 0.5 * p.shoe_thickness, 0.8 * beta)),
                       tuple(K.polar(1.35 * R, 0.8 * beta + 0.3))),
            Annotation(f"hub r_h = {p.hub_radius * 1e3:.1f} mm", tuple(K.polar(p.hub_radius, math.pi)),
                       tuple(K.polar(1.3 * R, math.pi + 0.5))),
            Annotation(f"fillets rho = {p.fillet_radius * 1e3:.2f} mm", tuple(p.fillets()[("ccw", "shoe")][2]), None),
        ]


CONCEPT = Concept3()
