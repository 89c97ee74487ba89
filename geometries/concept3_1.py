"""Concept 3.1 (thesis 4.2): concept 3 with the spoke-shoe joint turned into the bending
elements.  Each shoe is split into two halves that hang on the head of the radial spoke by
one thin circumferential flexure each; with the part turning ccw the half ahead of the
spoke trails its flexure (a *minus* half) and the half behind leads it (a *plus* half).

Parametrisation (no figure survives; built from the text and concept 3, whose parameters,
checks and outline it inherits: ``Concept31`` subclasses ``Concept3`` and only replaces the
top of the shoe).  Hub disc
``hub_radius`` (r_h); per shoe a radial spoke of width ``spoke_width`` (w_s) from the hub up
to the shoe's inner radius r_si = R_d - c - t_s.  From the spoke head two flexures of
radial thickness ``flexure_thickness`` (t_f, band r_si .. r_si + t_f) run circumferentially
for ``flexure_length`` (L_f, at their mid radius) in both directions to the *roots* of the
two shoe halves.  The whole shoe (both halves and the relief between them above the
spoke) spans ``shoe_arc`` (beta), centred on the spoke; each half's contact arc is
(beta - middle) / 2 where the middle = spoke + 2 flexures.  Above the spoke head and the
flexures a relief opens to the drum (so the flexures cannot touch it).  All concave
corners (spoke/hub, spoke/flexure underside, flexure top/half roots) get exact tangent
fillets of ``fillet_radius``; the part is one analytic outline.

Frames and profile: shoe 0 spans [0, beta] in the canonical frame with the spoke at
beta/2.  The part is symmetric about the spoke, so the minus arrangement (the mirror) is
the same part: whichever way it turns, one half is plus and one is minus -- the thesis's
objection (uneven load between the halves, unpredictable behaviour).  The outer profile is
defined over the whole shoe [0, beta] (for the linear profile: clearance c at angle 0, c_tip
at beta, so the two halves differ).  ``pivot`` returns the spoke head (between the two
flexures); each half really has its own pivot at its flexure.

Defaults: t_f = 1.0 mm, L_f = 6 mm, beta = 110 deg (two 38 deg halves): FE engagement
(default mesh, no spin softening) ~4600 rpm, first contact at the outer end of a half.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from clutchfem.core import param
from clutchfem.geometry import Annotation, load_concept_file
from clutchfem.geometry import occ as G
from clutchfem.geometry import sketch as K

_C3 = load_concept_file(str(Path(__file__).resolve().with_name("concept3.py")))
Concept3 = type(_C3)
Concept3Params = Concept3.Params


class Concept31Params(Concept3Params):
    context = "concept3.1"
    fillet_radius: float = param(0.6e-3, "m", 0.0, 4e-3, "fillet radius of all concave corners", "rho")
    shoe_arc: float = param(110.0, "deg", 20.0, 170.0,
                            "angular extent of the whole shoe (two halves + the middle), centred on the spoke", "beta")
    shoe_thickness: float = param(5.0e-3, "m", 1.5e-3, 15e-3, "radial thickness of the shoe halves", "t_s")
    flexure_length: float = param(6.0e-3, "m", 1.0e-3, 25e-3,
                                  "length of each of the two flexures (spoke side to half root)", "L_f")
    flexure_thickness: float = param(1.0e-3, "m", 0.3e-3, 5e-3, "radial thickness of the flexures", "t_f")

    # derived ----------------------------------------------------------------------------
    def radii(self):
        r_si = self.r_si()
        return r_si, r_si + self.flexure_thickness

    def angles(self):
        """(spoke centre, cw half root, ccw half root, half arc) in radians."""
        beta = math.radians(self.shoe_arc)
        r_si, r_fo = self.radii()
        tc = 0.5 * beta
        phi_w = math.asin(min(1.0, 0.5 * self.spoke_width / r_si))
        phi_f = self.flexure_length / (0.5 * (r_si + r_fo))
        return tc, tc - phi_w - phi_f, tc + phi_w + phi_f, tc - phi_w - phi_f

    def fillets(self):
        """Concept 3's spoke fillets plus the fillets at the two half roots (keyed
        (side, 'root')); None if one does not exist."""
        out = super().fillets()
        if out is None:
            return None
        _, r_fo = self.radii()
        rho = self.fillet_radius
        _, tr0, tr1, _ = self.angles()
        for side, t, sgn in (("cw", tr0, +1.0), ("ccw", tr1, -1.0)):
            X = K.polar(r_fo, t)
            f = (X, X, X) if rho == 0 else K.fillet_line_circle(K.radial_line(t), sgn, r_fo, True, rho, X)
            if f is None:
                return None
            out[(side, "root")] = f
        return out

    def check(self) -> None:
        super().check()  # hub, spoke, shoe arc vs sector, profile, spoke fillets
        beta = math.radians(self.shoe_arc)
        rho = self.fillet_radius
        r_si, r_fo = self.radii()
        r_so = float(np.min(self.designed_outer_radius(np.linspace(0, beta, 61), 0.0, beta)))
        if r_so - r_fo < 2 * rho + 0.5e-3:
            self.fail("flexure_thickness", f"<= {(r_so - r_fo + self.flexure_thickness - 2 * rho - 0.5e-3) * 1e3:.2f} mm "
                                           "(the relief above the flexures must be >= 2 fillet radii + 0.5 mm deep)")
        if self.flexure_length < 2 * rho + 0.5e-3:
            self.fail("flexure_length", f">= {(2 * rho + 0.5e-3) * 1e3:.2f} mm (room for the fillets at both ends)")
        if 2 * self.flexure_thickness > self.flexure_length + 1e-12 and self.flexure_length < 2e-3:
            self.fail("flexure_length", ">= 2 x flexure_thickness (a flexure, not a block)")
        tc, tr0, tr1, half = self.angles()
        half_min = max(math.radians(4.0), 2e-3 / r_si)
        if half < half_min:
            need = math.degrees(2 * half_min + (tr1 - tr0))
            self.fail("shoe_arc", f">= {need:.1f} deg (each half needs >= {math.degrees(half_min):.1f} deg of contact "
                                  "arc besides the spoke and the two flexures)")
        if self.fillets() is None:
            self.fail("fillet_radius", "smaller: no tangent fillet fits at the half roots")


class Concept31(Concept3):
    name = "concept3.1"
    title = "Concept 3.1: split shoe on a spoke, two flexures (one plus, one minus half)"
    thesis = ("Concept 3 with the spoke-shoe joint used as the bending elements; otherwise like concept 3. "
              "Problems remained: small total contact area; the shoe would bend in the arms joining hub and "
              "shoe, giving unpredictable behaviour and uneven load between the two halves on one arm; one "
              "half of each shoe acts as a plus shoe, the other as a minus shoe.")
    parametrisation = __doc__
    Params = Concept31Params

    def shoe_top(self, out: K.Outline, p: Concept31Params, R) -> None:
        """Concept 3's shoe top split in two: cw half profile, its root face and fillet, the
        flexure tops over the spoke head, the ccw half's root fillet and face, its profile."""
        beta = math.radians(p.shoe_arc)
        tc, tr0, tr1, _ = p.angles()
        f = p.fillets()
        rho = p.fillet_radius
        ro = lambda t: float(p.outer_radius(np.array([t]), 0.0, beta)[0])  # noqa: E731
        out.line_to(R(K.polar(ro(0.0), 0.0)))                # outer end of the cw half
        K.add_profile(out, p, R, 0.0, tr0, 0.0, beta, n=25)  # cw half contact surface
        c, tl, tcirc = f[("cw", "root")]
        out.line_to(R(tl))                                   # cw half root face
        if rho > 0:
            out.arc_to(R(tcirc), R(c), ccw=False)
        c, tl, tcirc = f[("ccw", "root")]
        out.arc_to(R(tcirc), ccw=True)                       # flexure tops over the spoke head
        if rho > 0:
            out.arc_to(R(tl), R(c), ccw=False)
        out.line_to(R(K.polar(ro(tr1), tr1)))                # ccw half root face
        K.add_profile(out, p, R, tr1, beta, 0.0, beta, n=25)  # ccw half contact surface

    def zones(self, p: Concept31Params) -> tuple[list[int], list[int]]:
        """Shoe zone: both halves, U-shaped (bridged through the relief over the flexures);
        flexure zone: the spoke head and the two flexures up to the half roots."""
        beta = math.radians(p.shoe_arc)
        r_si, r_fo = p.radii()
        tc, tr0, tr1, _ = p.angles()
        R_ext = p.drum_radius + 2e-3
        r_in = r_si - min(1e-3, 0.3 * (r_si - p.hub_radius))
        r_so = float(np.min(p.outer_radius(np.linspace(0, beta, 61), 0.0, beta)))
        r_br = 0.5 * (r_fo + p.fillet_radius + r_so)
        shoes, flexures = [], []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            u = K.Outline(K.polar(r_in, a))
            u.line_to(K.polar(R_ext, a)).arc_to(K.polar(R_ext, a + beta))
            u.line_to(K.polar(r_in, a + beta)).arc_to(K.polar(r_in, a + tr1), ccw=False)
            u.line_to(K.polar(r_br, a + tr1)).arc_to(K.polar(r_br, a + tr0), ccw=False)
            u.line_to(K.polar(r_in, a + tr0)).arc_to(K.polar(r_in, a), ccw=False)
            shoes.append(u.close().surface())
            flexures.append(G.annular_sector(r_in, R_ext, a + tr0, a + tr1))
        return shoes, flexures

    def pivot(self, p: Concept31Params) -> tuple[float, float]:
        r_si, r_fo = p.radii()
        return tuple(K.polar(0.5 * (r_si + r_fo), p.angles()[0]))

    def annotations(self, p: Concept31Params) -> list[Annotation]:
        beta = math.radians(p.shoe_arc)
        r_si, r_fo = p.radii()
        tc, tr0, tr1, half = p.angles()
        Rd = p.drum_radius
        r_so = Rd - p.clearance
        # canonical frame = plus arrangement: the half ccw of the spoke leads its flexure (plus);
        # the drawing mirrors the annotations for 'minus', which swaps the two halves' roles
        ccw_half, cw_half = ("plus half", "minus half") if p.arrangement == "plus" else ("minus half", "plus half")
        return [
            Annotation(f"flexures t_f = {p.flexure_thickness * 1e3:.2f} mm, L_f = {p.flexure_length * 1e3:.1f} mm",
                       tuple(K.polar(0.5 * (r_si + r_fo), 0.5 * (tc + tr1))), tuple(K.polar(1.4 * Rd, tc + 0.5))),
            Annotation(ccw_half, tuple(K.polar(0.5 * (r_si + r_so), 0.5 * (tr1 + beta))),
                       tuple(K.polar(1.3 * Rd, 0.5 * (tr1 + beta) + 0.25))),
            Annotation(cw_half, tuple(K.polar(0.5 * (r_si + r_so), 0.5 * tr0)),
                       tuple(K.polar(1.3 * Rd, 0.5 * tr0 - 0.25))),
            Annotation(f"spoke w_s = {p.spoke_width * 1e3:.1f} mm", tuple(K.polar(0.5 * (p.hub_radius + r_si), tc)),
                       tuple(K.polar(0.45 * Rd, tc + 1.2))),
            Annotation(f"hub r_h = {p.hub_radius * 1e3:.1f} mm", tuple(K.polar(p.hub_radius, tc + 0.5 * p.sector_angle)),
                       None),
            Annotation(f"fillets rho = {p.fillet_radius * 1e3:.2f} mm", tuple(p.fillets()[("ccw", "hub")][2]), None),
        ]


CONCEPT = Concept31()
