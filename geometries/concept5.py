"""Concept 5 (thesis 4.2: A3, B2, C1): a cross-shaped hub; each large shoe sits between two
arms of the cross and is held by two small beams, one to each neighbouring arm.

Parametrisation (no figure survives; built from the text: "the clutch consists of a larger
part clamped by two small beams to the hub, which is shaped like a cross").  A core disc of
``core_radius`` (r_c) carries n radial, parallel-sided arms (n = 4: the cross) of width
``arm_width`` (w_a).  Each arm reaches up to
``arm_recess`` below the shoes' outer surface, so it never touches the drum.  Between two
arms sits a shoe of radial thickness ``shoe_thickness`` (t_s); its arc is what is left of
the sector after the arms and the beams (derived, not a parameter).  At each end the shoe is
joined to the neighbouring arm by a short circumferential beam of length ``flexure_length``
(L_b, the gap between arm side and shoe end) and radial thickness ``flexure_thickness``
(t_b), whose underside sits ``beam_offset`` above the shoe's inner surface.  Under each shoe
an enclosed window separates it from the core.  All concave corners (beam/arm, beam/shoe,
arm/core) get exact tangent fillets of ``fillet_radius``; the part is one analytic face
with n holes.  The sector cut runs along the centre line of arm 0 (hub material only).

The shoe is symmetric and held at both ends, so it has no plus/minus character ("the shoes
get no +/- function"): both arrangements give the same part.  The pivot returned is the
shoe's mid-point on its inner surface (it translates, it does not rotate).

Why it was eliminated, in numbers (steel, defaults): the shoe moves out along its bisector,
which for a beam at the shoe's end (45 deg away) is ~45 deg off the beam's axis, so about
half of the motion *stretches* the beams: axial stiffness 2 E t_b h cos^2(45) / L_b ~
2 * 210e9 * 0.8e-3 * 11e-3 * 0.5 / 3e-3 ~ 6e8 N/m, against m R_Tp w^2 ~ 0.9 N per (rad/s)^2
x 1e-3: the 0.6 mm clearance would need ~20 000+ rpm even before bending stiffness is
added.  The FE model confirms that the concept does not engage below ~40 000 rpm, and the
thesis tried beams down to 0.5 mm without success.
"""

from __future__ import annotations

import math

import numpy as np

from clutchfem.core import GeometryError, param
from clutchfem.geometry import Annotation, Concept, ConceptParams, Shapes
from clutchfem.geometry import occ as G
from clutchfem.geometry import sketch as K


class Concept5Params(ConceptParams):
    context = "concept5"
    n_shoes: int = param(4, "-", 3, 6, "number of shoes = number of hub arms (4: a cross)", "n")
    fillet_radius: float = param(0.4e-3, "m", 0.0, 3e-3, "fillet radius of all concave corners", "rho")
    core_radius: float = param(11e-3, "m", 5e-3, 25e-3, "radius of the hub's core disc", "r_c")
    arm_width: float = param(6e-3, "m", 1.5e-3, 20e-3, "width of each hub arm (at the beams' radius)", "w_a")
    arm_recess: float = param(0.8e-3, "m", 0.2e-3, 5e-3, "arm tips below the shoes' outer surface", "d_a")
    shoe_thickness: float = param(6e-3, "m", 2e-3, 15e-3, "radial thickness of the shoe", "t_s")
    flexure_length: float = param(3e-3, "m", 0.5e-3, 15e-3, "beam length (gap between arm and shoe end)", "L_b")
    flexure_thickness: float = param(0.8e-3, "m", 0.3e-3, 4e-3, "beam thickness (radial)", "t_b")
    beam_offset: float = param(2.6e-3, "m", 0.2e-3, 12e-3,
                               "radial distance from the shoe's inner surface to the beam's underside", "e_b")

    # derived ----------------------------------------------------------------------------
    def radii(self):
        """r_si, r_bb (beam bottom), r_bt (beam top), r_bc (beam centre), r_at (arm top), r_so_min."""
        Theta = self.sector_angle
        r_si = self.drum_radius - self.clearance - self.shoe_thickness
        r_bb = r_si + self.beam_offset
        r_bt = r_bb + self.flexure_thickness
        r_bc = 0.5 * (r_bb + r_bt)
        phi_a, phi_b = self._phis(r_bc)
        t0, t1 = phi_a + phi_b, Theta - phi_a - phi_b
        if t1 > t0:
            r_so = float(np.min(self.outer_radius(np.linspace(t0, t1, 61), t0, t1)))
        else:
            r_so = self.drum_radius - self.clearance
        return r_si, r_bb, r_bt, r_bc, r_so - self.arm_recess, r_so

    def _phis(self, r_bc):
        """(polar angle of the arm's side at the beams' radius, angle spanned by a beam)."""
        return math.asin(min(1.0, 0.5 * self.arm_width / r_bc)), self.flexure_length / r_bc

    def arm_sides(self, k: int = 0) -> tuple[K.Line, K.Line]:
        """(cw side, ccw side) of arm k (parallel-sided, directed outward)."""
        axis = K.radial_line(k * self.sector_angle)
        return axis.offset(-0.5 * self.arm_width), axis.offset(0.5 * self.arm_width)

    def angles(self):
        """(half arm angle, beam angle, shoe root, shoe tip) in radians (canonical frame)."""
        r_bc = self.radii()[3]
        phi_a, phi_b = self._phis(r_bc)
        return phi_a, phi_b, phi_a + phi_b, self.sector_angle - phi_a - phi_b

    def check(self) -> None:
        rho = self.fillet_radius
        if self.core_radius < self.bore_radius + 2.5e-3:
            self.fail("core_radius", f">= bore radius + 2.5 mm = {(self.bore_radius + 2.5e-3) * 1e3:.2f} mm")
        r_si, r_bb, r_bt, r_bc, r_at, r_so = self.radii()
        if r_si - self.core_radius < 2 * rho + 2e-3:
            self.fail("shoe_thickness", f"<= {(self.drum_radius - self.clearance - self.core_radius - 2 * rho - 2e-3) * 1e3:.2f} mm "
                                        "(the window under the shoe must be >= 2 mm + 2 fillets high)")
        phi_a, phi_b, t0, t1 = self.angles()
        if t1 - t0 < math.radians(10.0):
            self.fail("arm_width", f"narrower (or shorter beams): the shoe arc left between two arms is "
                                   f"{math.degrees(t1 - t0):.1f} deg, need >= 10 deg")
        if 0.5 * self.arm_width + rho > 0.7 * self.core_radius:
            self.fail("arm_width", f"<= {2 * (0.7 * self.core_radius - rho) * 1e3:.2f} mm (arm plus fillets must fit "
                                   "on the core)")
        a_core = 2 * math.asin(min(1.0, (0.5 * self.arm_width + rho) / self.core_radius))
        if self.core_radius * (self.sector_angle - a_core) < 2 * rho + 1e-3:
            self.fail("arm_width", "narrower: the arms must leave >= 1 mm + 2 fillets of core between them")
        self.check_profile(t0, t1)
        r_so = self.radii()[5]
        if r_bb - r_si < rho + 0.2e-3:
            self.fail("beam_offset", f">= {(rho + 0.2e-3) * 1e3:.2f} mm (fillet + 0.2 mm under the beam at the shoe end)")
        if r_so - r_bt < rho + 0.2e-3:
            self.fail("beam_offset", f"<= {(r_so - r_si - self.flexure_thickness - rho - 0.2e-3) * 1e3:.2f} mm "
                                     "(the beam must stay a fillet + 0.2 mm below the shoe's outer surface)")
        if r_at - r_bt < rho + 0.2e-3:
            self.fail("arm_recess", f"<= {(r_so - r_bt - rho - 0.2e-3) * 1e3:.2f} mm (the arm tip must stay a fillet "
                                    "+ 0.2 mm above the beam)")
        if self.flexure_length < 2 * rho + 0.3e-3:
            self.fail("flexure_length", f">= {(2 * rho + 0.3e-3) * 1e3:.2f} mm (two fillets + 0.3 mm)")


def _corner(line, side: float, R: float, outside: bool, rho: float):
    """Fillet between ``line`` (a K.Line, or a polar angle for the radial line there) and the
    origin circle R: (centre, tangent on the line, tangent on the circle)."""
    if not isinstance(line, K.Line):
        line = K.radial_line(line)
    ss = line.circle_params(R)
    if not ss:  # pragma: no cover - excluded by check()
        raise GeometryError(f"concept5: a side line misses the circle R = {R}")
    X = line.at(ss[1])
    if rho == 0:
        return X, X, X
    f = K.fillet_line_circle(line, side, R, outside, rho, X)
    if f is None:  # pragma: no cover - excluded by check()
        raise GeometryError(f"concept5: no fillet between a side line and the circle R = {R}")
    return f


class Concept5(Concept):
    name = "concept5"
    title = "Concept 5: cross-shaped hub, each shoe held by two small beams (tension)"
    thesis = ("A3, B2, C1: a cross-shaped hub; each larger part (the shoe) is clamped by two small beams to the "
              "hub and is meant to be flung out at engagement; no +/- function. The beams see mostly tension "
              "and little bending, so the deflection is far too small even at 0.5 mm beam thickness; very thin "
              "sections, hard to make, very tolerance sensitive. Eliminated.")
    parametrisation = __doc__
    Params = Concept5Params

    def outlines(self, p: Concept5Params) -> tuple[K.Outline, list[K.Outline]]:
        """(outer boundary, window holes), canonical frame, material on the left."""
        Theta = p.sector_angle
        rho = p.fillet_radius
        r_si, r_bb, r_bt, r_bc, r_at, _ = p.radii()
        phi_a, phi_b, t0, t1 = p.angles()
        rc = p.core_radius
        ro = lambda t: float(p.outer_radius(np.array([t]), t0, t1)[0])  # noqa: E731
        # outer loop, starting at arm 0's top centre
        out = K.Outline(K.polar(r_at, 0.0))
        holes = []
        a_cw, a_ccw = p.arm_sides(0)        # arm 0
        n_cw, n_ccw = p.arm_sides(1)        # arm 1 (the next one)
        top0 = a_ccw.at(a_ccw.circle_params(r_at)[1])
        top1 = n_cw.at(n_cw.circle_params(r_at)[1])
        for i in range(p.n_shoes):
            a = i * Theta
            R = lambda q, a=a: K.rotate(np.asarray(q, float), a)  # noqa: E731
            out.arc_to(R(top0), ccw=True)                                       # arm top
            c, tl, tc = _corner(a_ccw, +1.0, r_bt, True, rho)                   # arm side / beam top
            out.line_to(R(tl))
            out.arc_to(R(tc), R(c), ccw=False)
            c, tl, tc = _corner(t0, -1.0, r_bt, True, rho)                      # beam top / shoe end
            out.arc_to(R(tc), ccw=True)
            out.arc_to(R(tl), R(c), ccw=False)
            out.line_to(R(K.polar(ro(t0), t0)))                                 # shoe root face
            K.add_profile(out, p, R, t0, t1, t0, t1)                             # shoe profile
            c, tl, tc = _corner(t1, +1.0, r_bt, True, rho)                      # shoe tip face / beam top
            out.line_to(R(tl))
            out.arc_to(R(tc), R(c), ccw=False)
            c, tl, tc = _corner(n_cw, -1.0, r_bt, True, rho)                    # beam top / next arm side
            out.arc_to(R(tc), ccw=True)
            out.arc_to(R(tl), R(c), ccw=False)
            out.line_to(R(top1))
            out.arc_to(R(K.polar(r_at, Theta)), ccw=True)                       # next arm top (half)
            # window under the shoe (material on the left)
            c, tl, tc = _corner(a_ccw, +1.0, rc, True, rho)
            h = K.Outline(R(tc))
            c2, tl2, tc2 = _corner(n_cw, -1.0, rc, True, rho)                   # core / next arm side
            h.arc_to(R(tc2), ccw=True)
            h.arc_to(R(tl2), R(c2), ccw=False)
            c3, tl3, tc3 = _corner(n_cw, -1.0, r_bb, False, rho)                # arm side / beam bottom
            h.line_to(R(tl3))
            h.arc_to(R(tc3), R(c3), ccw=False)
            c4, tl4, tc4 = _corner(t1, +1.0, r_bb, False, rho)                  # beam bottom / shoe tip face
            h.arc_to(R(tc4), ccw=False)
            h.arc_to(R(tl4), R(c4), ccw=False)
            h.line_to(R(K.polar(r_si, t1)))
            h.arc_to(R(K.polar(r_si, t0)), ccw=False)                           # shoe inner surface
            c5, tl5, tc5 = _corner(t0, -1.0, r_bb, False, rho)                  # shoe root face / beam bottom
            h.line_to(R(tl5))
            h.arc_to(R(tc5), R(c5), ccw=False)
            c6, tl6, tc6 = _corner(a_ccw, +1.0, r_bb, False, rho)               # beam bottom / arm side
            h.arc_to(R(tc6), ccw=False)
            h.arc_to(R(tl6), R(c6), ccw=False)
            h.line_to(R(tl))                                                    # arm side down to the core
            h.arc_to(R(tc), R(c), ccw=False)
            holes.append(h.close())
        return out.close(), holes

    def build(self, p: Concept5Params) -> Shapes:
        out, holes = self.outlines(p)
        K.check_outlines(self.name, p, out, *holes)
        part = out.surface(holes)
        r_si, r_bb, r_bt, r_bc, r_at, _ = p.radii()
        phi_a, phi_b, t0, t1 = p.angles()
        R_ext = p.drum_radius + 2e-3
        rho = p.fillet_radius
        r_fz = r_bb - rho - 0.5 * (r_bb - rho - r_si)
        # the flexure zone starts just past the arm-side fillets (a radial line crossing the
        # beam transversally, not grazing a fillet); it spans both beams of a shoe, bridged
        # over the shoe, where the shoe zone takes precedence
        a_ccw = p.arm_sides(0)[1]
        phi_z = max(K.angle_of(_corner(a_ccw, +1.0, r_bt, True, rho)[2]),
                    K.angle_of(_corner(a_ccw, +1.0, r_bb, False, rho)[2])) + 0.1e-3 / r_bc
        shoes, flexures = [], []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            shoes.append(G.annular_sector(r_si, R_ext, a + t0, a + t1))
            flexures.append(G.annular_sector(r_fz, R_ext, a + phi_z, a + p.sector_angle - phi_z))
        return Shapes(material=[part], shoe_zones=shoes, flexure_zones=flexures, sector_start=0.0)

    def shoe_arc(self, p: Concept5Params) -> tuple[float, float]:
        _, _, t0, t1 = p.angles()
        return t0, t1

    def pivot(self, p: Concept5Params) -> tuple[float, float]:
        return tuple(K.polar(p.radii()[0], 0.5 * p.sector_angle))

    def annotations(self, p: Concept5Params) -> list[Annotation]:
        r_si, r_bb, r_bt, r_bc, r_at, r_so = p.radii()
        phi_a, phi_b, t0, t1 = p.angles()
        Rd = p.drum_radius
        return [
            Annotation(f"beams t_b = {p.flexure_thickness * 1e3:.2f} mm, L_b = {p.flexure_length * 1e3:.1f} mm",
                       tuple(K.polar(r_bc, phi_a + 0.5 * phi_b)), tuple(K.polar(1.35 * Rd, -0.45))),
            Annotation(f"arm w_a = {p.arm_width * 1e3:.1f} mm", tuple(K.polar(0.5 * (p.core_radius + r_si), 0.0)),
                       tuple(K.polar(0.5 * Rd, -0.8))),
            Annotation(f"shoe: {math.degrees(t1 - t0):.0f} deg, t_s = {p.shoe_thickness * 1e3:.1f} mm",
                       tuple(K.polar(0.5 * (r_si + r_so), 0.5 * (t0 + t1))),
                       tuple(K.polar(1.35 * Rd, 0.5 * (t0 + t1)))),
            Annotation(f"core r_c = {p.core_radius * 1e3:.1f} mm", tuple(K.polar(p.core_radius, 0.25 * p.sector_angle)),
                       None),
            Annotation(f"arm tip d_a = {p.arm_recess * 1e3:.1f} mm below the shoes", tuple(K.polar(r_at, 0.0)), None),
            Annotation(f"beam offset e_b = {p.beam_offset * 1e3:.1f} mm above the shoe's inner surface",
                       tuple(K.polar(0.5 * (r_si + r_bb), t1 - 0.3 * phi_b)), None),
            Annotation(f"fillets rho = {p.fillet_radius * 1e3:.2f} mm",
                       tuple(_corner(p.arm_sides(0)[1], +1.0, p.core_radius, True, p.fillet_radius)[2]), None),
        ]


CONCEPT = Concept5()
