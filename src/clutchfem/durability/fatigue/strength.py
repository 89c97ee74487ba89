"""Fatigue strength data of the part's material and the rules applied: :class:`FatigueParams`
and the surface-factor table (all ASSUMED, configurable; defaults 51CrV4 at ~45 HRC with
laser-cut edges).

Sources of the defaults (Shigley, *Mechanical Engineering Design*, 10th ed., ch. 6):

* S_ut = 1450 MPa: 51CrV4 at ~45 HRC (hardness conversion, ASTM E140 / ISO 18265); the
  thesis gives only Rp0.2 = 1250 MPa.
* k_a = a S_ut^b [MPa] (Shigley Table 6-2): ground (1.58, -0.085), machined (4.51,
  -0.265), hot-rolled (57.7, -0.718), as-forged (272, -0.995).  Cut edges are not in
  the table: ASSUMED wire-EDM = machined (shallow recast layer, Ra ~ 1-3 um), laser =
  hot-rolled (recast/oxide layer, heat-affected zone, striations).  Default: laser.
* k_b = 1: Shigley's bending size factor for the flexure's equivalent diameter
  d_e = 0.808 sqrt(h t) ~ 3.6 mm is 1.08 (eq. 6-20/6-25); capped at 1 (ASSUMED).
* k_c = 1 (bending / combined stresses evaluated with von Mises); 0.85 for axial.
* k_e at 99 % reliability: 0.814; k_f = 1: no residual-stress or corrosion credit/penalty.
* Notches: the FE stress at a fillet already holds K_t; it is used without a notch-
  sensitivity reduction (q = 1, conservative; q ~ 0.85-0.95 for r = 0.5 mm at 1450 MPa).
* Basquin: f = 0.77 for S_ut >= 1380 MPa (Shigley Fig. 6-18), knee N_e = 1e6 cycles.
* Goodman is the default mean-stress rule (why: :mod:`.criteria`).
"""

from __future__ import annotations

from typing import ClassVar, Literal

from ...core import ParamSet, choice, param

__all__ = ["ASSUMED", "SURFACE_TABLE", "FatigueParams"]

#: Shigley Table 6-2: k_a = a S_ut^b with S_ut in MPa.  'wire_edm' and 'laser' are ASSUMED
#: equivalents (module docstring).
SURFACE_TABLE = {
    "ground": (1.58, -0.085),
    "machined": (4.51, -0.265),
    "wire_edm": (4.51, -0.265),
    "hot_rolled": (57.7, -0.718),
    "laser": (57.7, -0.718),
    "as_forged": (272.0, -0.995),
}


class FatigueParams(ParamSet):
    """Fatigue strength of the part's material and the rules applied (all ASSUMED,
    defaults: 51CrV4 at ~45 HRC, laser-cut edges; see module docstring for sources).

    Parameters
    ----------
    ultimate_strength, yield_strength, endurance_cap : float or str
        S_ut, Rp0.2 and the cap of S_e' [Pa] (``"1450MPa"``).
    endurance_ratio : float
        S_e' / S_ut of a polished specimen.
    edge_finish : {"laser", "wire_edm", "machined", "ground", "hot_rolled", "as_forged"}
        The cut edges' finish (surface factor k_a), unless ``surface_factor`` > 0 sets k_a.
    size_factor, load_factor, misc_factor : float
        k_b, k_c, k_f.
    temperature : float or str
        Part temperature for k_d [C].
    reliability : float
        For k_e.
    fatigue_fraction, knee_cycles : float
        Basquin's S-N line: f at 1e3 cycles, the knee N_e.
    mean_stress_rule : {"goodman", "gerber"}
    miner : {"elementary", "haibach"}

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.durability import endurance_limit
    >>> se, k = endurance_limit(cf.FatigueParams(edge_finish="ground"))   # S_e [Pa], Marin factors
    >>> round(se / 1e6), round(k["k_a"], 2), round(endurance_limit(cf.FatigueParams())[0] / 1e6)
    (485, 0.85, 177)
    """

    context: ClassVar[str] = "fatigue"
    ultimate_strength: float = param(1450e6, "Pa", 1e8, 3e9, "ultimate tensile strength S_ut (~45 HRC)", "S_ut")
    yield_strength: float = param(1250e6, "Pa", 1e8, 3e9, "yield strength Rp0.2 (thesis)", "S_y")
    endurance_ratio: float = param(0.5, "-", 0.2, 0.7, "S_e' / S_ut of a polished specimen (Shigley 6-8)", "S_e'/S_ut")
    endurance_cap: float = param(700e6, "Pa", 1e8, 1.5e9, "upper bound of S_e' (Shigley: 700 MPa)", "S_e'max")
    edge_finish: Literal["ground", "machined", "wire_edm", "laser", "hot_rolled", "as_forged"] = choice(
        "laser", "finish of the cut edges (surface factor k_a)")
    surface_factor: float = param(0.0, "-", 0.0, 1.0, "k_a override (0: from edge_finish)", "k_a")
    size_factor: float = param(1.0, "-", 0.5, 1.0, "k_b (Shigley gives 1.08 for the flexure, capped at 1)", "k_b")
    load_factor: float = param(1.0, "-", 0.5, 1.0, "k_c (1 bending/combined, 0.85 axial)", "k_c")
    temperature: float = param(20.0, "C", -60.0, 538.0, "part temperature for k_d (Shigley 6-27)", "T")
    reliability: float = param(0.99, "-", 0.5, 0.999999, "reliability for k_e = 1 - 0.08 z_a", "R")
    misc_factor: float = param(1.0, "-", 0.1, 1.0, "k_f (miscellaneous effects)", "k_f")
    fatigue_fraction: float = param(0.77, "-", 0.5, 0.95, "f: S(1e3 cycles) / S_ut (Shigley Fig. 6-18)", "f")
    knee_cycles: float = param(1e6, "-", 1e5, 1e8, "cycles at the endurance knee N_e", "N_e")
    mean_stress_rule: Literal["goodman", "gerber"] = choice("goodman", "Haigh diagram mean-stress rule")
    miner: Literal["elementary", "haibach"] = choice(
        "elementary", "damage below the knee: none (elementary) or slope 2k-1 (Haibach)")

    def check(self) -> None:
        if self.yield_strength > self.ultimate_strength:
            self.fail("yield_strength", f"a yield strength <= ultimate_strength ({self.ultimate_strength:g} Pa)")


ASSUMED = (
    "S_ut = 1450 MPa for 51CrV4 at ~45 HRC (hardness conversion); S_e' = min(0.5 S_ut, 700 MPa) (Shigley 6-8)",
    "surface factor of the cut edge from Shigley Table 6-2 (laser = hot-rolled, wire-EDM = machined)",
    "size factor 1 (Shigley's 1.08 capped), load factor 1, reliability 99 % (k_e = 0.814)",
    "no notch-sensitivity reduction of FE peak stresses (q = 1)",
    "Basquin S-N: f = 0.77 at 1e3 cycles, knee at 1e6 cycles; Palmgren-Miner over cycle types",
    "equivalent amplitude = von Mises of the amplitude tensor, mean = von Mises signed by the trace",
)
