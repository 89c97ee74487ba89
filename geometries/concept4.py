"""Concept 4 (thesis 4.2: A2 B2 C1): concept 1 with the hub material removed -- a small hub
around the bore, each shoe joined to it by one thin, long, straight bending beam.

Parametrisation (no figure survives; built from the text).  Canonical (plus) frame, shoe 0:

* the **hub** is a disc of radius ``hub_radius`` (r_h) around the bore;
* the **shoe** spans polar angles [0 (root), ``shoe_arc`` (tip)], inner radius
  r_si = R_d - c - t_s, outer surface = the chosen profile (concentric / eccentric /
  linear clearance from root to tip);
* the **beam** leaves the hub at H on the hub circle at ``flexure_angle`` (gamma) from the
  hub's tangent, runs outward and clockwise for the free length ``flexure_length`` (L_f)
  and meets the shoe's *root* radial line (polar angle 0) at S, below the shoe's inner
  surface.  So the beam lies under its own shoe, its hub end roughly below the shoe's
  centre of mass (H sits at polar angle atan2(L cos g, r_h + L sin g) ~ 35 deg).  The
  centrifugal force of the shoe then passes close to H: the bending moment is largest at
  the shoe end S and small at the hub end, which is what the thesis's optimisation found
  ("higher stresses further from the shoe's centre of mass, so the beam was made a little
  thicker at that end"): the beam is straight-tapered from ``flexure_thickness`` (t_f, at
  the hub end) to t_f * ``flexure_taper`` at the shoe end.  If the beam instead bends at
  its hub end, the effective pivot moves under the shoe and the shoe acts partly as a
  *plus* shoe -- the risk the thesis names;
* a **heel** fills the space between the beam's end and the shoe at the root; the slot
  between beam and shoe ends in a round tangent to both (radius >= ``fillet_radius``,
  enlarged automatically so that it stays inside the shoe's angular span); the beam meets
  the hub through two exact fillets of ``fillet_radius`` (one acute, one obtuse corner).

The whole beam lies below the shoe's inner surface, so it can never touch the drum.  The
minus arrangement (default) is the mirror image (the shoe trails its flexure).

Hand estimate of the defaults: steel E = 210 GPa, rho = 7850, h = 11 mm.  Shoe (90 deg,
27.8-33.8 mm): m = 25.1 g, R_Tp = 27.8 mm.  Plain cantilever k = 3 E I / L^3 with
I = h t^3 / 12, t = 2.01 mm (mean of 1.75 and 2.28 mm), L = 19 mm: I = 7.5e-12 m^4,
k = 6.9e5 N/m; the centroid moves the 0.6 mm clearance when m R_Tp w^2 = k c, i.e.
w = 770 rad/s ~ 7300 rpm.  But the shoe also *rotates*: the load passes close to H, so the
bending moment grows towards S and the tip (~25 mm beyond the load line) moves ~3x more
than the centroid while the root moves slightly inwards.  Integrating M m / (E I(s)) along
the tapered beam with rigid hub and shoe (``Concept4.hand_estimate``) puts first contact
at the shoe tip at ~5850 rpm (peak beam stress then 6 M / (h t^2) ~ 530 MPa at the shoe
end).  The FE model (P2, default mesh, no spin softening) is softer -- heel, shoe and hub
are not rigid -- and gives 4180 rpm at the tip (4178 rpm at half the element size): in the
3500-5000 rpm window, well above the 2700 rpm idle; hence t_f = 1.75 mm.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from clutchfem.core import param
from clutchfem.geometry import Annotation, Concept, ConceptParams, Shapes
from clutchfem.geometry import occ as G
from clutchfem.geometry import sketch as K


class Layout4(SimpleNamespace):
    """Derived geometry of shoe 0 (canonical frame), computed without gmsh.

    (A SimpleNamespace, not a dataclass: the concept registry executes this file without
    registering it in sys.modules, which dataclasses need.)"""

    # r_si: float
    # r_so_min: float
    # H: np.ndarray
    # S: np.ndarray
    # theta_H: float
    # up: K.Line beam edge facing the shoe (outer)
    # lo: K.Line beam edge facing the hub / tip gap (inner)
    # centre: K.Line
    # t_hub: float
    # t_shoe: float
    # r_u0: float radius where the outer edge meets the root line
    # r_l0: float radius where the inner edge meets the root line
    # fil_up: tuple | None (centre, tangent on edge, tangent on hub, corner)
    # fil_lo: tuple | None
    # round_e: tuple | None slot-end round (centre, tangent on edge, tangent on shoe, radius)
    # theta_end: float largest polar angle of beam material (incl. fillets)


class Concept4Params(ConceptParams):
    context = "concept4"
    fillet_radius: float = param(0.8e-3, "m", 0.0, 5e-3,
                                 "fillet radius where the beam meets the hub (slot-end round >= this)", "rho")
    hub_radius: float = param(12e-3, "m", 5e-3, 25e-3, "radius of the small hub around the bore", "r_h")
    shoe_arc: float = param(90.0, "deg", 20.0, 170.0, "angular extent of each shoe", "beta")
    shoe_thickness: float = param(6.0e-3, "m", 2e-3, 15e-3, "radial thickness of the shoe (at the root clearance)", "t_s")
    flexure_length: float = param(19e-3, "m", 4e-3, 40e-3,
                                  "free length of the beam centre line, hub circle to the shoe's root line", "L_f")
    flexure_thickness: float = param(1.75e-3, "m", 0.5e-3, 4e-3, "beam thickness at the hub end", "t_f")
    flexure_taper: float = param(1.3, "-", 0.5, 2.5,
                                 "beam thickness at the shoe end / at the hub end (>1: thicker at the shoe end)", "k_t")
    flexure_angle: float = param(30.0, "deg", 5.0, 80.0,
                                 "angle between the beam and the hub's tangent where it leaves the hub", "gamma")

    # ---------------------------------------------------------------------------------
    def layout(self) -> Layout4:
        """All derived points/lines of shoe 0; raises ParameterError if inconsistent."""
        Rd, c, ts = self.drum_radius, self.clearance, self.shoe_thickness
        beta = math.radians(self.shoe_arc)
        r_si = Rd - c - ts
        r_so_min = float(np.min(self.designed_outer_radius(np.linspace(0, beta, 61), 0.0, beta)))
        rh, L, g = self.hub_radius, self.flexure_length, math.radians(self.flexure_angle)
        th = math.atan2(L * math.cos(g), rh + L * math.sin(g))
        H = K.polar(rh, th)
        d = math.cos(g) * K.vec(math.sin(th), -math.cos(th)) + math.sin(g) * K.polar(1.0, th)
        S = H + L * d
        S[1] = 0.0  # on the root line by construction (rounding)
        n = K.perp(d)
        if np.dot(n, S) < 0:
            n = -n
        t_h, t_s = self.flexure_thickness, self.flexure_thickness * self.flexure_taper
        up = K.Line.through(H + 0.5 * t_h * n, S + 0.5 * t_s * n)
        lo = K.Line.through(H - 0.5 * t_h * n, S - 0.5 * t_s * n)
        centre = K.Line.through(H, S)
        s_u0, s_l0 = up.polar_angle_param(0.0), lo.polar_angle_param(0.0)
        r_u0 = float(np.linalg.norm(up.at(s_u0))) if s_u0 is not None else float("nan")
        r_l0 = float(np.linalg.norm(lo.at(s_l0))) if s_l0 is not None else float("nan")
        return Layout4(r_si=r_si, r_so_min=r_so_min, H=H, S=S, theta_H=th, up=up, lo=lo,
                       centre=centre, t_hub=t_h, t_shoe=t_s, r_u0=r_u0, r_l0=r_l0,
                       fil_up=None, fil_lo=None, round_e=None, theta_end=th)

    def _hub_fillet(self, lay: Layout4, edge: K.Line, side: float):
        """Fillet between a beam edge and the hub circle where the edge leaves the hub."""
        rh, rho = self.hub_radius, self.fillet_radius
        ss = edge.circle_params(rh)
        if not ss:
            return None
        X = edge.at(ss[1])  # exit point (the edge runs from the hub towards the shoe)
        if rho == 0.0:
            return (X, X, X, X)
        f = K.fillet_line_circle(edge, side, rh, True, rho, X + 0.5 * rho * edge.d)
        if f is None:
            return None
        cen, t_line, t_circ = f
        if edge.param(t_line) < ss[1] - 1e-9:
            return None
        return (cen, t_line, t_circ, X)

    def _slot_round(self, lay: Layout4):
        """Round that ends the slot between the beam's outer edge and the shoe's inner
        surface: tangent to both, inside the shoe's angular span (polar angle > margin)."""
        r_si = lay.r_si
        margin = 0.3e-3 / r_si
        near = lay.up.at(lay.up.polar_angle_param(0.0) or 0.0)

        def ok(rho):
            f = self._round_at(lay, rho, near)
            if f is None:
                return False
            cen = f[0]
            return K.angle_of(cen) - math.asin(min(1.0, rho / np.linalg.norm(cen))) >= margin

        rho0 = max(self.fillet_radius, 0.25e-3)
        rho_max = 0.5 * (r_si - self.hub_radius)
        if ok(rho0):
            rho = rho0
        else:
            if not ok(rho_max):
                return None
            lo_, hi_ = rho0, rho_max
            for _ in range(50):
                mid = 0.5 * (lo_ + hi_)
                lo_, hi_ = (lo_, mid) if ok(mid) else (mid, hi_)
            rho = hi_
        cen, t_line, t_circ = self._round_at(lay, rho, near)
        return (cen, t_line, t_circ, rho)

    @staticmethod
    def _round_at(lay: Layout4, rho: float, near):
        # centre on the shoe side of the outer edge (the side away from the beam)
        n_out = K.perp(lay.up.d)
        side = 1.0 if np.dot(n_out, lay.S) > 0 else -1.0
        return K.fillet_line_circle(lay.up, side, lay.r_si, False, rho, near)

    def full_layout(self) -> Layout4:
        lay = self.layout()
        side_up = 1.0 if np.dot(K.perp(lay.up.d), lay.S) > 0 else -1.0
        side_lo = -1.0 if np.dot(K.perp(lay.lo.d), lay.S) > 0 else 1.0
        lay.fil_up = self._hub_fillet(lay, lay.up, side_up)
        lay.fil_lo = self._hub_fillet(lay, lay.lo, side_lo)
        lay.round_e = self._slot_round(lay) if math.isfinite(lay.r_u0) else None
        angs = [lay.theta_H]
        for f in (lay.fil_up, lay.fil_lo):
            if f is not None:
                angs += [K.angle_of(f[2]), K.angle_of(f[3])]
        lay.theta_end = max(angs)
        return lay

    # ---------------------------------------------------------------------------------
    def check(self) -> None:
        Theta = self.sector_angle
        beta = math.radians(self.shoe_arc)
        rh, rho = self.hub_radius, self.fillet_radius
        if rh < self.bore_radius + 2.5e-3:
            self.fail("hub_radius", f">= bore radius + 2.5 mm = {(self.bore_radius + 2.5e-3) * 1e3:.2f} mm")
        r_si = self.drum_radius - self.clearance - self.shoe_thickness
        if r_si < rh + 5e-3:
            self.fail("shoe_thickness", f"<= {(self.drum_radius - self.clearance - rh - 5e-3) * 1e3:.2f} mm "
                                        "(the shoe's inner surface must stay >= 5 mm outside the hub)")
        gap_min = max(1.5e-3, 2.2 * rho)
        beta_max = Theta - gap_min / r_si
        if beta > beta_max:
            self.fail("shoe_arc", f"<= {math.degrees(beta_max):.1f} deg for n_shoes = {self.n_shoes} "
                                  f"(tip gap >= {gap_min * 1e3:.2f} mm to the next shoe's root)")
        self.check_profile(0.0, beta)
        t_max = self.flexure_thickness * max(1.0, self.flexure_taper)
        if t_max > 0.35 * self.flexure_length:
            self.fail("flexure_taper" if self.flexure_taper > 1 else "flexure_thickness",
                      f"a beam whose thickest end ({t_max * 1e3:.2f} mm) is <= 0.35 x flexure_length "
                      f"= {0.35 * self.flexure_length * 1e3:.2f} mm (a beam, not a block)")
        lay = self.layout()
        r_so = lay.r_so_min
        if lay.up.distance_origin() > rh - 0.3e-3:
            self.fail("flexure_angle", f"steeper (larger angle): the beam's outer edge must cut into the hub "
                                       f"(now it passes {lay.up.distance_origin() * 1e3:.2f} mm from the centre, "
                                       f"hub radius {rh * 1e3:.2f} mm)")
        if not (math.isfinite(lay.r_l0) and math.isfinite(lay.r_u0)):
            self.fail("flexure_length", "a beam that reaches the shoe's root line")
        if lay.r_l0 > r_si - 0.3e-3 or lay.r_u0 > 0.5 * (r_si + r_so):
            if self.quiet():  # a feasibility probe: the limit's value is not read
                self.fail("flexure_length", "shorter")
            Lmax = self._max_length()
            self.fail("flexure_length", f"<= {Lmax * 1e3:.2f} mm with hub_radius {rh * 1e3:.3g} mm, flexure_angle "
                                        f"{self.flexure_angle:.3g} deg, flexure_thickness "
                                        f"{self.flexure_thickness * 1e3:.3g} mm and flexure_taper "
                                        f"{self.flexure_taper:.3g} (the beam must end below the shoe's inner "
                                        f"surface, radius {r_si * 1e3:.2f} mm; now its end spans "
                                        f"{lay.r_l0 * 1e3:.2f}-{lay.r_u0 * 1e3:.2f} mm): shorten the flexure or "
                                        "change one of those")
        if lay.r_l0 < rh + 1.0e-3:
            self.fail("flexure_length", f"longer: the beam's root end must stay >= 1 mm outside the hub "
                                        f"(inner edge meets the root line at {lay.r_l0 * 1e3:.2f} mm)")
        lay = self.full_layout()
        if lay.fil_up is None or lay.fil_lo is None:
            self.fail("fillet_radius", "a hub fillet that fits between the beam and the hub (smaller)")
        if lay.round_e is None:
            self.fail("flexure_length", "a beam whose end leaves room for the slot-end round under the shoe")
        s_fu = lay.up.param(lay.fil_up[1])
        s_re = lay.up.param(lay.round_e[1])
        if s_re < s_fu + 0.5e-3:
            self.fail("flexure_length", "longer (or a smaller fillet_radius): the hub fillet and the slot-end "
                                        "round overlap along the beam's outer edge")
        s_fl = lay.lo.param(lay.fil_lo[1])
        s_l0 = lay.lo.polar_angle_param(0.0)
        if s_fl > s_l0 - 0.5e-3:
            self.fail("fillet_radius", f"smaller: the acute hub fillet ({rho * 1e3:.2f} mm) runs along the beam's "
                                       "inner edge past the root line")
        rho_e, cen_e = lay.round_e[3], lay.round_e[0]
        if K.angle_of(cen_e) + math.asin(min(1.0, rho_e / np.linalg.norm(cen_e))) > beta - 0.1:
            self.fail("shoe_arc", "wider: the slot-end round under the shoe root must lie inside the shoe's arc")
        # the beam (and its hub fillets) must stay inside this shoe's sector of the part
        lim = 0.5 * (beta + Theta) - 0.6e-3 / rh
        if lay.theta_end > lim:
            need = math.degrees(2 * (lay.theta_end + 0.6e-3 / rh) - Theta)
            self.fail("shoe_arc", f">= {need:.1f} deg for n_shoes = {self.n_shoes}: the beam reaches polar angle "
                                  f"{math.degrees(lay.theta_end):.1f} deg and must stay within its own sector")

    def _max_length(self) -> float:
        """Largest flexure_length whose end still fits below the shoe (bisection)."""
        lo, hi = 1e-3, 60e-3
        r_si = self.drum_radius - self.clearance - self.shoe_thickness
        r_so = float(np.min(self.designed_outer_radius(np.linspace(0, math.radians(self.shoe_arc), 61), 0.0,
                                                       math.radians(self.shoe_arc))))
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            q = self.model_copy(update={"flexure_length": mid})
            lay = Concept4Params.layout(q)
            bad = (not math.isfinite(lay.r_l0)) or lay.r_l0 > r_si - 0.3e-3 or lay.r_u0 > 0.5 * (r_si + r_so)
            lo, hi = (lo, mid) if bad else (mid, hi)
        return lo

    def flexure_thicknesses(self) -> list[float]:
        """Both ends of the tapered beam (the mesh is refined for the thinner one)."""
        return [self.flexure_thickness, self.flexure_thickness * self.flexure_taper]


class Concept4(Concept):
    name = "concept4"
    title = "Concept 4: small hub, one long tapered bending beam per shoe"
    thesis = ("A2 B2 C1: concept 1 with the hub material removed; the shoe is joined to a small hub by a "
              "thin beam. Lightest concept; risk: if the beam bends at its hub end the shoe acts as a plus "
              "shoe. Optimised: longer/wider flexure, slightly angled and a little thicker at the end far "
              "from the shoe's centre of mass (where the stresses are higher); shoe profile with less "
              "clearance near the flexure and more at the tip. Tested: engagement only a few % above "
              "target, slip rpm like concept 1, contact on ~1/3 of the arc; overheated in slip tests.")
    parametrisation = __doc__
    Params = Concept4Params

    def outline(self, p: Concept4Params) -> K.Outline:
        """The part's outer boundary (all shoes, canonical frame), one closed loop traversed
        ccw: hub arc, acute hub fillet, beam inner edge, root line, shoe profile, tip side,
        shoe inner arc, slot-end round, beam outer edge, obtuse hub fillet, next hub arc."""
        lay = p.full_layout()
        beta = math.radians(p.shoe_arc)
        r_si = lay.r_si
        Theta = p.sector_angle
        c_lo, tl_lo, tc_lo, Y = lay.fil_lo
        c_up, tl_up, tc_up, X = lay.fil_up
        c_e, t_b, t_a, _ = lay.round_e
        toe = lay.lo.at(lay.lo.polar_angle_param(0.0))
        r_root = float(p.outer_radius(np.array([0.0]), 0.0, beta)[0])
        out = None
        for i in range(p.n_shoes):
            a = i * Theta
            R = lambda q, a=a: K.rotate(np.asarray(q, float), a)  # noqa: E731
            if out is None:
                out = K.Outline(R(tc_lo))
            else:
                out.arc_to(R(tc_lo), ccw=True)                      # hub between beams
            if p.fillet_radius > 0:
                out.arc_to(R(tl_lo), R(c_lo), ccw=False)             # acute hub fillet
            out.line_to(R(toe))                                      # beam inner edge
            out.line_to(R(K.polar(r_root, 0.0)))                     # root line
            K.add_profile(out, p, R, 0.0, beta, 0.0, beta)           # shoe profile
            out.line_to(R(K.polar(r_si, beta)))                      # tip side
            out.arc_to(R(t_a), ccw=False)                            # shoe inner surface
            out.arc_to(R(t_b), R(c_e), ccw=False)                    # slot-end round
            out.line_to(R(tl_up))                                    # beam outer edge
            if p.fillet_radius > 0:
                out.arc_to(R(tc_up), R(c_up), ccw=False)             # obtuse hub fillet
        out.arc_to(out.points[0], ccw=True)
        out.close()
        return out

    def build(self, p: Concept4Params) -> Shapes:
        lay = p.full_layout()
        beta = math.radians(p.shoe_arc)
        out = self.outline(p)
        K.check_outlines(self.name, p, out)
        part = out.surface()
        R_ext = p.drum_radius + 2e-3
        shoes, flexures = [], []
        for i in range(p.n_shoes):
            a = i * p.sector_angle
            shoes.append(G.annular_sector(lay.r_si, R_ext, a, a + beta))
            flexures.append(G.annular_sector(p.hub_radius, lay.r_si, a - 0.02, a + lay.theta_end + 0.01))
        return Shapes(material=[part], shoe_zones=shoes, flexure_zones=flexures,
                      sector_start=0.5 * (beta - p.sector_angle))

    def shoe_arc(self, p: Concept4Params) -> tuple[float, float]:
        return 0.0, math.radians(p.shoe_arc)

    def pivot(self, p: Concept4Params) -> tuple[float, float]:
        """Instantaneous centre of rotation of the (rigid) shoe when the beam bends under
        the shoe's centrifugal load (Euler-Bernoulli, see :meth:`hand_estimate`)."""
        return tuple(self.hand_estimate(p)["pivot"])

    # ---------------------------------------------------------------------------------
    def hand_estimate(self, p: Concept4Params, E: float = 210e9, rho: float = 7850.0) -> dict:
        """Beam-theory estimate: tapered Euler-Bernoulli beam clamped at the hub, rigid shoe.

        Returns the shoe's mass and centroid (concentric annular-sector approximation), the
        radial displacement per w^2 along the outer surface, the engagement speed (rpm) at
        which the first point closes its clearance, the pivot (instantaneous centre of the
        shoe's rigid motion) and the peak beam bending stress at engagement."""
        lay = p.layout()
        beta = math.radians(p.shoe_arc)
        r_o, r_i = p.drum_radius - p.clearance, lay.r_si
        area = 0.5 * beta * (r_o ** 2 - r_i ** 2)
        r_c = (2.0 / 3.0) * (r_o ** 3 - r_i ** 3) / (r_o ** 2 - r_i ** 2) * math.sin(beta / 2) / (beta / 2)
        m = rho * p.thickness * area
        cg = K.polar(r_c, beta / 2)
        F = m * cg  # force per w^2 (vector), acting through cg
        ns = 400
        s = (np.arange(ns) + 0.5) / ns * p.flexure_length
        ds = p.flexure_length / ns
        x = lay.H[None, :] + s[:, None] * lay.centre.d[None, :]
        t = lay.t_hub + (lay.t_shoe - lay.t_hub) * s / p.flexure_length
        EI = E * p.thickness * t ** 3 / 12.0
        Mz = (cg[0] - x[:, 0]) * F[1] - (cg[1] - x[:, 1]) * F[0]  # moment of the load about x(s)
        kappa = Mz / EI
        theta = float(np.sum(kappa) * ds)
        # displacement of a shoe point q: sum kappa ds (z x (q - x))
        def disp(q):
            rel = q[None, :] - x
            return np.array([-np.sum(kappa * rel[:, 1]), np.sum(kappa * rel[:, 0])]) * ds
        ths = np.linspace(0.0, beta, 61)
        r_out = p.outer_radius(ths, 0.0, beta)
        ur = []
        for th_, r_ in zip(ths, r_out):
            q = K.polar(r_, th_)
            ur.append(float(np.dot(disp(q), q / r_)))
        ur = np.array(ur)
        gap = p.drum_radius - r_out
        with np.errstate(divide="ignore"):
            w2 = np.where(ur > 0, gap / ur, np.inf)
        k = int(np.argmin(w2))
        w0 = math.sqrt(w2[k])
        # pivot: point q with disp(q) = 0 -> q = S + z x u_S / theta
        uS = disp(lay.S)
        piv = lay.S + np.array([-uS[1], uS[0]]) / theta if abs(theta) > 0 else lay.S
        sigma = 6.0 * np.abs(Mz) * w0 ** 2 / (p.thickness * t ** 2)
        return {"mass": m, "R_Tp": r_c, "engage_rpm": w0 * 60 / (2 * math.pi), "first_contact_deg":
                math.degrees(ths[k]), "ur_per_w2": ur, "pivot": piv, "sigma_max": float(sigma.max()),
                "sigma_at": float(s[int(np.argmax(sigma))] / p.flexure_length)}

    def annotations(self, p: Concept4Params) -> list[Annotation]:
        lay = p.layout()
        beta = math.radians(p.shoe_arc)
        R = p.drum_radius
        mid = 0.5 * (lay.H + lay.S)
        r_so = p.drum_radius - p.clearance
        return [
            Annotation(f"beam L_f = {p.flexure_length * 1e3:.1f} mm, t = {lay.t_hub * 1e3:.2f} -> "
                       f"{lay.t_shoe * 1e3:.2f} mm, gamma = {p.flexure_angle:.0f} deg",
                       tuple(mid), tuple(K.polar(1.45 * R, -0.35))),
            Annotation(f"hub r_h = {p.hub_radius * 1e3:.1f} mm", tuple(K.polar(p.hub_radius, math.pi + 0.6)),
                       tuple(K.polar(1.3 * R, math.pi + 0.9))),
            Annotation(f"shoe: beta = {p.shoe_arc:.0f} deg, t_s = {p.shoe_thickness * 1e3:.1f} mm",
                       tuple(K.polar(0.5 * (lay.r_si + r_so), 0.6 * beta)), tuple(K.polar(1.35 * R, 0.6 * beta))),
            Annotation(f"hub fillets rho = {p.fillet_radius * 1e3:.2f} mm", tuple(p.full_layout().fil_up[2]), None),
        ]


CONCEPT = Concept4()
