"""High-cycle fatigue of the clutch from stress states: pure functions, no FE solve inside.

Input: for every *cycle type* the plane stresses (sxx, syy, sxy) [Pa] at the same points
(e.g. the raw element-vertex stresses of the elastic model) in the two extreme states of
the cycle, A and B, and the number of such cycles in the clutch's life.  Typical cycle
types (issue 14): start-stop (A = at rest, B = maximum speed; ~1e4-1e5), the two-stroke
speed ripple at the operating speed (A, B = states at w (1 -+ delta); ~1e7, one per
revolution) and the load-torque fluctuation while the clutch holds (A, B = states at the
minimum and maximum transmitted torque).  The elastic model is linear between solved
states, so a cycle's stress path is the straight line from A to B.

Amplitude and mean
------------------
Per point the tensors sigma_a = (B - A)/2 and sigma_m = (A + B)/2 (exact for a straight
path between the extremes).  Equivalent values (Shigley, *Mechanical Engineering Design*,
10th ed., sec. 6-14, "combinations of loading modes"):

    s_a = vonMises(sigma_a),      s_m = sign(tr sigma_m) vonMises(sigma_m)

(plane stress: vM^2 = sxx^2 - sxx syy + syy^2 + 3 sxy^2).  Why von Mises and the sign of
the trace: fatigue cracks in a flexure start at its free edges (fillets, slot ends), where
plane stress is *uniaxial* along the edge; there s_a and s_m are exactly the amplitude
and mean of the edge stress with its sign, and every critical-plane or principal-stress
criterion gives the same numbers.  Inside the part (biaxial) von Mises is the usual
ductile-steel equivalent; the signed mean only decides whether the mean is tensile.
Compressive means get no credit (Shigley: for s_m < 0 failure when s_a = S_e).

Haigh diagram
-------------
Equivalent fully reversed amplitude s_ar (the amplitude at zero mean with the same life):

    Goodman (default):  s_ar = s_a / (1 - s_m / S_ut)
    Gerber:             s_ar = s_a / (1 - (s_m / S_ut)^2)
    s_m <= 0:           s_ar = s_a;         s_m >= S_ut: s_ar = infinity.

Goodman is the default for hardened spring steel cut to shape: Gerber runs through the
middle of ductile-steel test data and is unconservative for high-strength, notch- and
mean-stress-sensitive steels, and the cut edge carries tensile residual stress (recast
layer); the FKM guideline's mean-stress sensitivity for R_m = 1450 MPa (M = 0.35e-3 R_m -
0.1 = 0.41) is even steeper than the Goodman line here (S_e / S_ut ~ 0.1-0.25), so
Goodman is not conservative by a wide margin either.  Langer's first-cycle yield line,
n_y = S_y / max(vM(A), vM(B)), is reported separately.

Fatigue strength (Marin, Shigley eqs. 6-8, 6-18 to 6-28; all ASSUMED, configurable)
--------------------------------------------------------------------------------------
S_e = k_a k_b k_c k_d k_e k_f S_e',  S_e' = 0.5 S_ut (700 MPa for S_ut > 1400 MPa).

* S_ut = 1450 MPa: 51CrV4 at ~45 HRC (hardness conversion, ASTM E140 / ISO 18265); the
  thesis gives only Rp0.2 = 1250 MPa.
* k_a = a S_ut^b [MPa] (Shigley Table 6-2): ground (1.58, -0.085), machined (4.51,
  -0.265), hot-rolled (57.7, -0.718), as-forged (272, -0.995).  Cut edges are not in
  the table: ASSUMED wire-EDM = machined (shallow recast layer, Ra ~ 1-3 um), laser =
  hot-rolled (recast/oxide layer, heat-affected zone, striations).  Default: laser.
* k_b = 1: Shigley's bending size factor for the flexure's equivalent diameter
  d_e = 0.808 sqrt(h t) ~ 3.6 mm is 1.08 (eq. 6-20/6-25); capped at 1 (ASSUMED).
* k_c = 1 (bending / combined stresses evaluated with von Mises); 0.85 for axial.
* k_d from the temperature (Shigley eq. 6-27, 21-538 C; 1 at room temperature).
* k_e = 1 - 0.08 z_a (8 % standard deviation of S_e, Shigley eq. 6-29); 99 %: 0.814.
* k_f = 1: no residual-stress or corrosion credit/penalty.
* Notches: the FE stress at a fillet already holds K_t; it is used without a notch-
  sensitivity reduction (q = 1, conservative; q ~ 0.85-0.95 for r = 0.5 mm at 1450 MPa).

S-N curve (Basquin) and damage
------------------------------
S(N) = f S_ut (N / 1e3)^b between 1e3 cycles and the knee N_e (S(N_e) = S_e, so
b = log10(S_e / (f S_ut)) / log10(N_e / 1e3)); f = 0.77 for S_ut >= 1380 MPa (Shigley
Fig. 6-18); below 1e3 cycles S(N) = S_ut N^(log10 f / 3) (eq. 6-17); N_e = 1e6.  Above the
knee: 'elementary' (default, Shigley): amplitudes below S_e do no damage (infinite life);
'haibach' (FKM guideline, conservative for many cycles): N = N_e (S_e / s_ar)^(2k - 1),
k = -1/b.  Several cycle types combine by Palmgren-Miner, D = sum n_i / N_i(s_ar,i); a
cycle type below the knee contributes nothing under 'elementary', so Miner only acts where
more than one type is finite-life.

Safety factor: the load multiplier X at which the Miner sum reaches 1, all stresses (means
and amplitudes of every cycle type) scaled together: D(X) = 1, found by bisection per
point (D is monotone in X).  For one cycle type with at least N_e cycles this is Shigley's
infinite-life factor, e.g. Goodman n = 1 / (s_a/S_e + s_m/S_ut); for finite-life types it
is the factor on stress for the required life.  The governing cycle is the one with the
largest share of the damage at X at the worst point.

Location: :func:`name_location` names the zone (``flexure_<i>``, ``shoe_<i>``, ``hub``) of
a point and, in a flexure, its end (hub end / shoe end / middle, by the distances to the
flexure's interfaces with the hub and the shoe), and whether it lies on a free edge
(a fillet or slot flank) or on the bore / contact surface.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from statistics import NormalDist
from typing import ClassVar, Literal

import numpy as np
from scipy.spatial import cKDTree

from ...core import InputError, ParameterError, ParamSet, choice, param
from ...fe import von_mises
from ...mesh import ClutchMesh

__all__ = [
    "FatigueParams", "LoadCycle", "FatigueResult", "Location", "amplitude_mean",
    "equivalent_stresses", "marin_factors", "endurance_limit", "reversed_equivalent",
    "cycles_to_failure", "haigh_safety_factor", "fatigue_check", "name_location", "SURFACE_TABLE",
    "allowed_amplitude", "single_cycle_factor", "candidate_points",
]

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
    defaults: 51CrV4 at ~45 HRC, laser-cut edges; see module docstring for sources)."""

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


# ---------------------------------------------------------------------------------------
# stresses
# ---------------------------------------------------------------------------------------
def _stress_array(name: str, s) -> np.ndarray:
    try:
        a = np.asarray(s, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: not a numeric array of stresses") from None
    if a.ndim != 2 or a.shape[0] != 3 or a.shape[1] == 0:
        raise InputError(f"{name}: stresses must have shape (3, npts) = (sxx, syy, sxy) x points "
                         f"(got shape {a.shape})")
    if not np.all(np.isfinite(a)):
        k = int(np.nonzero(~np.isfinite(a).all(axis=0))[0][0])
        raise InputError(f"{name}: non-finite stress at point {k}")
    if np.abs(a).max() > 1e11:
        raise InputError(f"{name}: stresses up to {np.abs(a).max():.3g} Pa: expected Pa (|s| <= 1e11)")
    return a


def amplitude_mean(state_a, state_b) -> tuple[np.ndarray, np.ndarray]:
    """(amplitude tensor (B - A)/2, mean tensor (A + B)/2), each (3, npts) [Pa]."""
    A = _stress_array("state_a", state_a)
    B = _stress_array("state_b", state_b)
    if A.shape != B.shape:
        raise InputError(f"state_a and state_b must have the same shape (got {A.shape} and {B.shape})")
    return 0.5 * (B - A), 0.5 * (A + B)


def equivalent_stresses(amplitude, mean) -> tuple[np.ndarray, np.ndarray]:
    """(s_a, s_m): von Mises of the amplitude tensor, von Mises of the mean tensor signed by
    its trace (+ for a zero trace) [Pa] (module docstring)."""
    amp = np.asarray(amplitude, dtype=float)
    mean = np.asarray(mean, dtype=float)
    sign = np.where(mean[0] + mean[1] < 0.0, -1.0, 1.0)
    return von_mises(amp), sign * von_mises(mean)


@dataclass(frozen=True)
class LoadCycle:
    """One cycle type: the stresses at the same points in its two extreme states [Pa],
    arrays (3, npts) of (sxx, syy, sxy), and how many such cycles the part must survive."""

    name: str
    state_a: np.ndarray
    state_b: np.ndarray
    count: float

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise ParameterError("name", self.name, "a non-empty name of the cycle type")
        amp, mean = amplitude_mean(self.state_a, self.state_b)
        object.__setattr__(self, "state_a", _stress_array("state_a", self.state_a))
        object.__setattr__(self, "state_b", _stress_array("state_b", self.state_b))
        try:
            n = float(self.count)
        except (TypeError, ValueError):
            raise ParameterError("count", self.count, "a number of cycles in [1, 1e12]") from None
        if not (math.isfinite(n) and 1.0 <= n <= 1e12):
            raise ParameterError("count", self.count, "a number of cycles in [1, 1e12]")
        object.__setattr__(self, "count", n)

    @classmethod
    def from_mean_amplitude(cls, name: str, mean, amplitude, count: float) -> "LoadCycle":
        """A cycle between mean - amplitude and mean + amplitude (tensors (3, npts) [Pa])."""
        m = _stress_array("mean", mean)
        a = _stress_array("amplitude", amplitude)
        if m.shape != a.shape:
            raise InputError(f"mean and amplitude must have the same shape (got {m.shape} and {a.shape})")
        return cls(name=name, state_a=m - a, state_b=m + a, count=count)

    @property
    def npts(self) -> int:
        return int(self.state_a.shape[1])

    def equivalent(self) -> tuple[np.ndarray, np.ndarray]:
        """(s_a, s_m) [Pa] at every point."""
        return equivalent_stresses(*amplitude_mean(self.state_a, self.state_b))


# ---------------------------------------------------------------------------------------
# strength
# ---------------------------------------------------------------------------------------
def _kd(T_C: float) -> float:
    """Shigley eq. 6-27 (T in F, 70-1000 F); 1 below 70 F (21 C)."""
    TF = max(T_C * 9.0 / 5.0 + 32.0, 70.0)
    return (0.975 + 0.432e-3 * TF - 0.115e-5 * TF ** 2 + 0.104e-8 * TF ** 3 - 0.595e-12 * TF ** 4)


def marin_factors(p: FatigueParams) -> dict[str, float]:
    """k_a ... k_f of :class:`FatigueParams` (module docstring)."""
    if p.surface_factor > 0:
        ka = p.surface_factor
    else:
        a, b = SURFACE_TABLE[p.edge_finish]
        ka = min(a * (p.ultimate_strength / 1e6) ** b, 1.0)
    z = NormalDist().inv_cdf(p.reliability)
    return {"k_a": float(ka), "k_b": p.size_factor, "k_c": p.load_factor, "k_d": float(_kd(p.temperature)),
            "k_e": float(1.0 - 0.08 * z), "k_f": p.misc_factor}


def endurance_limit(p: FatigueParams) -> tuple[float, dict[str, float]]:
    """(S_e [Pa], Marin factors): S_e = prod(k) min(endurance_ratio S_ut, endurance_cap)."""
    k = marin_factors(p)
    se_prime = min(p.endurance_ratio * p.ultimate_strength, p.endurance_cap)
    return float(se_prime * np.prod(list(k.values()))), k | {"S_e_prime_Pa": float(se_prime)}


def reversed_equivalent(s_a, s_m, ultimate_strength: float, rule: str = "goodman") -> np.ndarray:
    """Equivalent fully reversed amplitude s_ar [Pa] (module docstring)."""
    s_a = np.asarray(s_a, dtype=float)
    s_m = np.asarray(s_m, dtype=float)
    r = np.maximum(s_m, 0.0) / ultimate_strength
    if rule == "goodman":
        den = 1.0 - r
    elif rule == "gerber":
        den = 1.0 - r * r
    else:
        raise ParameterError("mean_stress_rule", rule, "one of 'goodman', 'gerber'")
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(den > 0, s_a / np.where(den > 0, den, 1.0), np.inf)
    return np.where((s_a == 0) & (r < 1), 0.0, out)


def _sn_constants(p: FatigueParams, Se: float) -> tuple[float, float, float]:
    S3 = p.fatigue_fraction * p.ultimate_strength
    if Se >= S3:
        raise ParameterError("fatigue_fraction", p.fatigue_fraction,
                             f"f S_ut above the endurance limit S_e = {Se:.4g} Pa")
    b = math.log10(Se / S3) / math.log10(p.knee_cycles / 1e3)
    return S3, b, -1.0 / b


def cycles_to_failure(s_ar, p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Allowed cycles N at equivalent reversed amplitude s_ar [Pa] (module docstring)."""
    if Se is None:
        Se = endurance_limit(p)[0]
    s = np.asarray(s_ar, dtype=float)
    S3, b, k = _sn_constants(p, Se)
    Su = p.ultimate_strength
    N = np.full(s.shape, np.inf)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        hcf = (s > Se) & (s <= S3)
        N[hcf] = 1e3 * (s[hcf] / S3) ** (1.0 / b)
        lcf = (s > S3) & (s < Su)
        N[lcf] = (s[lcf] / Su) ** (3.0 / math.log10(p.fatigue_fraction))
        N[s >= Su] = 0.0
        if p.miner == "haibach":
            low = (s > 0) & (s <= Se)
            N[low] = p.knee_cycles * (Se / s[low]) ** (2.0 * k - 1.0)
    return N


def allowed_amplitude(count, p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Fully reversed amplitude S(n) [Pa] that ``count`` cycles may have (the inverse of
    :func:`cycles_to_failure`): S_ut n^(log10 f / 3) below 1e3 cycles, f S_ut (n / 1e3)^b up to
    the knee, S_e above it ('elementary'; 'haibach': S_e (N_e / n)^(1 / (2k - 1)))."""
    if Se is None:
        Se = endurance_limit(p)[0]
    n = np.asarray(count, dtype=float)
    S3, b, k = _sn_constants(p, Se)
    with np.errstate(divide="ignore", over="ignore"):
        S = np.where(n <= 1e3, p.ultimate_strength * np.maximum(n, 1.0) ** (math.log10(p.fatigue_fraction) / 3.0),
                     S3 * (n / 1e3) ** b)
        above = n >= p.knee_cycles
        if p.miner == "haibach":
            S = np.where(above, Se * (p.knee_cycles / n) ** (1.0 / (2.0 * k - 1.0)), S)
        else:
            S = np.where(above, Se, S)
    return S


def single_cycle_factor(s_a, s_m, count, p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Closed-form load multiplier X at which ``count`` cycles of one type alone reach
    Miner's sum 1: s_ar(X s_a, X s_m) = S(count), i.e. Goodman X = S / (s_a + S s_m / S_ut),
    Gerber the positive root of S (s_m/S_ut)^2 X^2 + s_a X - S = 0, and X = S / s_a for
    s_m <= 0 (inf without stress).  Equals the bisection of :func:`fatigue_check` for one
    cycle type (tested)."""
    s_a = np.asarray(s_a, dtype=float)
    s_m = np.maximum(np.asarray(s_m, dtype=float), 0.0)
    S = allowed_amplitude(count, p, Se)
    r = s_m / p.ultimate_strength
    with np.errstate(divide="ignore", invalid="ignore"):
        if p.mean_stress_rule == "goodman":
            X = S / (s_a + S * r)
        else:
            a = S * r * r
            X = np.where(a > 0, (-s_a + np.sqrt(s_a * s_a + 4.0 * a * S)) / (2.0 * np.where(a > 0, a, 1.0)),
                         S / s_a)
    return np.where((s_a <= 0) & (s_m <= 0), np.inf, X)


def candidate_points(cycles: Sequence["LoadCycle"], p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Indices of the points that can hold the smallest combined safety factor: a screen
    that lets :func:`fatigue_check` bisect a few points instead of every one, exactly.

    With C cycle types, X_i(n) the closed-form factor of type i alone with n cycles
    (:func:`single_cycle_factor`): the combined factor of a point lies between
    L = min_i X_i(C n_i) (at that load every type's damage is <= 1/C, the sum <= 1) and
    U = min_i X_i(n_i) (one type alone reaches 1).  The worst point p* has
    L(p*) <= X(p*) <= min U, so it is among the points with L <= min U (all points are
    returned if there is no finite bound)."""
    if Se is None:
        Se = endurance_limit(p)[0]
    C = len(cycles)
    eq = [c.equivalent() for c in cycles]
    U = np.min([single_cycle_factor(sa, sm, c.count, p, Se) for (sa, sm), c in zip(eq, cycles)], axis=0)
    L = np.min([single_cycle_factor(sa, sm, C * c.count, p, Se) for (sa, sm), c in zip(eq, cycles)], axis=0)
    bound = float(np.min(U))
    if not math.isfinite(bound):
        return np.arange(len(U))
    return np.nonzero(L <= bound * (1.0 + 1e-9))[0]


def haigh_safety_factor(s_a, s_m, Se: float, Sut: float, rule: str = "goodman") -> np.ndarray:
    """Shigley's infinite-life safety factor on a load line through the origin:
    Goodman 1 / (s_a/S_e + s_m/S_ut); Gerber (1/2)(S_ut/s_m)^2 (s_a/S_e)
    (-1 + sqrt(1 + (2 s_m S_e / (S_ut s_a))^2)); s_m <= 0: S_e / s_a."""
    s_a = np.asarray(s_a, dtype=float)
    s_m = np.asarray(s_m, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        if rule == "goodman":
            n = 1.0 / (s_a / Se + np.maximum(s_m, 0.0) / Sut)
        elif rule == "gerber":
            sm = np.maximum(s_m, 0.0)
            ger = 0.5 * (Sut / sm) ** 2 * (s_a / Se) * (-1.0 + np.sqrt(1.0 + (2.0 * sm * Se / (Sut * s_a)) ** 2))
            n = np.where(sm > 0, np.where(s_a > 0, ger, Sut / np.where(sm > 0, sm, 1.0)), Se / s_a)
        else:
            raise ParameterError("mean_stress_rule", rule, "one of 'goodman', 'gerber'")
    return n


# ---------------------------------------------------------------------------------------
# the check
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Location:
    """Where a point lies in the clutch: zone, position in it and the boundary it is on."""

    zone: str
    kind: str
    index: int | None
    position: str
    boundary: str | None
    x_m: float
    y_m: float

    @property
    def radius_m(self) -> float:
        return math.hypot(self.x_m, self.y_m)

    @property
    def angle_deg(self) -> float:
        return math.degrees(math.atan2(self.y_m, self.x_m))

    @property
    def description(self) -> str:
        s = self.zone if self.index is None else f"{self.kind} {self.index}"
        if self.position:
            s += f", {self.position}"
        if self.boundary:
            s += f", on the {self.boundary}"
        return s + f" (r = {self.radius_m * 1e3:.2f} mm, {self.angle_deg:.1f} deg)"

    def to_json(self) -> dict:
        return {"zone": self.zone, "kind": self.kind, "index": self.index, "position": self.position,
                "boundary": self.boundary, "x_m": self.x_m, "y_m": self.y_m,
                "description": self.description}


@dataclass(frozen=True)
class FatigueResult:
    """What :func:`fatigue_check` returns (stresses in Pa, at the worst point unless noted)."""

    safety_factor: float
    worst_index: int
    governing_cycle: str
    damage_at_worst: float
    max_damage: float
    per_cycle: tuple
    point_safety_factor: np.ndarray
    yield_safety_factor: float
    yield_worst_index: int
    endurance_limit_Pa: float
    factors: dict
    params: dict
    worst_xy_m: tuple[float, float] | None = None
    location: Location | None = None
    assumed: tuple[str, ...] = field(default=())

    def to_json(self) -> dict:
        return {"fatigue_safety_factor": self.safety_factor, "governing_cycle": self.governing_cycle,
                "worst_index": self.worst_index,
                "worst_xy_m": None if self.worst_xy_m is None else list(self.worst_xy_m),
                "location": None if self.location is None else self.location.to_json(),
                "damage_at_worst": self.damage_at_worst, "max_damage": self.max_damage,
                "per_cycle": [dict(c) for c in self.per_cycle],
                "yield_safety_factor": self.yield_safety_factor, "yield_worst_index": self.yield_worst_index,
                "endurance_limit_Pa": self.endurance_limit_Pa, "factors": dict(self.factors),
                "params": dict(self.params), "assumed": list(self.assumed)}


ASSUMED = (
    "S_ut = 1450 MPa for 51CrV4 at ~45 HRC (hardness conversion); S_e' = min(0.5 S_ut, 700 MPa) (Shigley 6-8)",
    "surface factor of the cut edge from Shigley Table 6-2 (laser = hot-rolled, wire-EDM = machined)",
    "size factor 1 (Shigley's 1.08 capped), load factor 1, reliability 99 % (k_e = 0.814)",
    "no notch-sensitivity reduction of FE peak stresses (q = 1)",
    "Basquin S-N: f = 0.77 at 1e3 cycles, knee at 1e6 cycles; Palmgren-Miner over cycle types",
    "equivalent amplitude = von Mises of the amplitude tensor, mean = von Mises signed by the trace",
)


def _damage(X: np.ndarray, sa: np.ndarray, sm: np.ndarray, n: np.ndarray, p: FatigueParams,
            Se: float) -> np.ndarray:
    """Miner damage per cycle type (C, P) with all stresses scaled by X (P,)."""
    sar = reversed_equivalent(sa * X, sm * X, p.ultimate_strength, p.mean_stress_rule)
    N = cycles_to_failure(sar, p, Se)
    with np.errstate(divide="ignore"):
        return np.where(N > 0, n[:, None] / N, np.inf)


def _load_factor(sa, sm, n, p, Se, sections: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Per point the X with D(X) = 1: ``sections``-section search in log X on [1e-6, 1e6]
    (D is monotone in X; every pass evaluates D at ``sections`` - 1 interior points of each
    point's bracket at once and keeps the sub-bracket where D crosses 1, until the brackets
    reach adjacent doubles); returns (X = geometric mean of the bracket, its upper end)."""
    P = sa.shape[1]
    lo = np.full(P, math.log(1e-6))
    hi = np.full(P, math.log(1e6))
    never = _damage(np.exp(hi), sa, sm, n, p, Se).sum(axis=0) < 1.0  # no stress: no damage at any X
    frac = np.arange(1, sections) / sections
    for _ in range(64):
        t = lo[:, None] + (hi - lo)[:, None] * frac[None, :]  # (P, sections - 1)
        X = np.exp(t)
        sar = reversed_equivalent(sa[:, :, None] * X, sm[:, :, None] * X, p.ultimate_strength, p.mean_stress_rule)
        N = cycles_to_failure(sar, p, Se)
        with np.errstate(divide="ignore"):
            D = np.where(N > 0, n[:, None, None] / N, np.inf).sum(axis=0)  # (P, sections - 1)
        up = D >= 1.0
        first = np.where(up.any(axis=1), up.argmax(axis=1), sections - 1)  # first interior point with D >= 1
        rows = np.arange(P)
        new_hi = np.where(first < sections - 1, t[rows, np.minimum(first, sections - 2)], hi)
        new_lo = np.where(first > 0, t[rows, np.maximum(first - 1, 0)], lo)
        if np.array_equal(new_hi, hi) and np.array_equal(new_lo, lo):
            break  # adjacent doubles: no interior point left
        lo, hi = new_lo, new_hi
    X = np.exp(0.5 * (lo + hi))
    X[never] = np.inf
    return X, np.exp(hi)


def fatigue_check(cycles: Sequence[LoadCycle], params: FatigueParams | None = None, *,
                  xy=None, cm: ClutchMesh | None = None, element=None) -> FatigueResult:
    """Fatigue safety factor of the part under the cycle types ``cycles`` (module docstring).

    ``xy`` (2, npts) [m]: the points' coordinates (for the worst point's position);
    with ``cm`` the worst point's location is named (:func:`name_location`), using
    ``element`` (npts,) -- the element each point belongs to, e.g. ``arange(nelem).repeat(3)``
    for the solver's raw vertex stresses -- when given."""
    p = params or FatigueParams()
    if not isinstance(p, FatigueParams):
        raise InputError(f"params must be FatigueParams (got {type(p).__name__})")
    cycles = list(cycles)
    if not cycles:
        raise InputError("fatigue_check: no load cycles given")
    for c in cycles:
        if not isinstance(c, LoadCycle):
            raise InputError(f"fatigue_check: every cycle must be a LoadCycle (got {type(c).__name__})")
    names = [c.name for c in cycles]
    if len(set(names)) != len(names):
        raise InputError(f"fatigue_check: cycle names must be unique (got {names})")
    npts = cycles[0].npts
    for c in cycles:
        if c.npts != npts:
            raise InputError(f"fatigue_check: cycle '{c.name}' has {c.npts} points, '{cycles[0].name}' {npts}")
    if xy is not None:
        xy = np.asarray(xy, dtype=float)
        if xy.shape != (2, npts) or not np.all(np.isfinite(xy)):
            raise InputError(f"fatigue_check: xy must be finite with shape (2, {npts}) (got {xy.shape})")
    Se, k = endurance_limit(p)
    eq = [c.equivalent() for c in cycles]
    sa = np.stack([e[0] for e in eq])
    sm = np.stack([e[1] for e in eq])
    n = np.array([c.count for c in cycles])
    X, Xhi = _load_factor(sa, sm, n, p, Se)
    worst = int(np.argmin(X))
    D1 = _damage(np.ones(npts), sa, sm, n, p, Se)
    Dtot = D1.sum(axis=0)
    share = _damage(Xhi[worst:worst + 1], sa[:, worst:worst + 1], sm[:, worst:worst + 1], n, p, Se)[:, 0]
    gov = int(np.argmax(share))
    sar1 = reversed_equivalent(sa[:, worst], sm[:, worst], p.ultimate_strength, p.mean_stress_rule)
    N1 = cycles_to_failure(sar1, p, Se)
    per = []
    # each type alone at the worst point: closed form (equals the bisection for one type)
    X_alone = single_cycle_factor(sa[:, worst], sm[:, worst], n, p, Se)
    for i, c in enumerate(cycles):
        Xi = X_alone[i:i + 1]
        per.append({"name": c.name, "count": float(n[i]), "amplitude_Pa": float(sa[i, worst]),
                    "mean_Pa": float(sm[i, worst]), "reversed_equivalent_Pa": float(sar1[i]),
                    "allowed_cycles": float(N1[i]), "damage": float(D1[i, worst]),
                    "safety_factor_alone": float(Xi[0]),
                    "damage_share_at_failure": (float(share[i] / share.sum())
                                                if np.isfinite(share).all() and share.sum() > 0 else float(i == gov))})
    vmax = np.max(np.stack([np.maximum(von_mises(c.state_a), von_mises(c.state_b)) for c in cycles]), axis=0)
    with np.errstate(divide="ignore"):
        ny = np.where(vmax > 0, p.yield_strength / np.where(vmax > 0, vmax, 1.0), np.inf)
    wy = int(np.argmin(ny))
    wxy = None if xy is None else (float(xy[0, worst]), float(xy[1, worst]))
    loc = None
    if cm is not None:
        if xy is None:
            raise InputError("fatigue_check: naming the location needs the points' coordinates xy")
        el = None
        if element is not None:
            element = np.asarray(element)
            if element.shape != (npts,):
                raise InputError(f"fatigue_check: element must have shape ({npts},) (got {element.shape})")
            el = int(element[worst])
        loc = name_location(cm, xy[:, worst], element=el)
    return FatigueResult(safety_factor=float(X[worst]), worst_index=worst, governing_cycle=names[gov],
                         damage_at_worst=float(Dtot[worst]), max_damage=float(Dtot.max()), per_cycle=tuple(per),
                         point_safety_factor=X, yield_safety_factor=float(ny[wy]), yield_worst_index=wy,
                         endurance_limit_Pa=float(Se), factors=k, params=p.model_dump(), worst_xy_m=wxy,
                         location=loc, assumed=ASSUMED)


# ---------------------------------------------------------------------------------------
# location naming
# ---------------------------------------------------------------------------------------
def _element_zone(cm: ClutchMesh) -> np.ndarray:
    """Zone name of every element ('' where none but 'solid')."""
    sub = cm.mesh.subdomains or {}
    z = np.full(cm.mesh.t.shape[1], "", dtype=object)
    for name in sorted(sub):  # hub, flexure_<i>, shoe_<i>: later (shoe) wins over flexure
        if name == "solid":
            continue
        z[np.asarray(sub[name])] = name
    return z


def _components(cm: ClutchMesh, elems: np.ndarray) -> list[np.ndarray]:
    """Connected components (through shared edges) of a set of elements, each sorted."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    mesh = cm.mesh
    elems = np.unique(np.asarray(elems, dtype=np.int64))
    inner = np.nonzero(mesh.f2t[1] >= 0)[0]
    a, b = mesh.f2t[0, inner], mesh.f2t[1, inner]
    sel = np.isin(a, elems) & np.isin(b, elems)
    ia, ib = np.searchsorted(elems, a[sel]), np.searchsorted(elems, b[sel])
    n = len(elems)
    _, label = connected_components(coo_matrix((np.ones(len(ia)), (ia, ib)), shape=(n, n)), directed=False)
    return [elems[label == k] for k in np.unique(label)]


def _interface_points(cm: ClutchMesh, comp: np.ndarray, zone: np.ndarray, prefix: str) -> np.ndarray:
    """Vertices of the edges between the elements ``comp`` and elements of zones ``prefix*``."""
    mesh = cm.mesh
    inner = np.nonzero(mesh.f2t[1] >= 0)[0]
    a, b = mesh.f2t[0, inner], mesh.f2t[1, inner]
    in_zone = np.char.startswith(zone.astype(str), prefix)  # per element
    ina, inb = np.isin(a, comp), np.isin(b, comp)
    hit = (ina & in_zone[b]) | (inb & in_zone[a])
    f = mesh.facets[:, inner[hit]]
    return mesh.p[:, np.unique(f)]


def name_location(cm: ClutchMesh, xy, element: int | None = None) -> Location:
    """Name the place of point ``xy`` (2,) [m] in ``cm``: its zone (``flexure_<i>``,
    ``shoe_<i>``, ``hub``), for a flexure its end (hub end / shoe end / middle: by the
    distances to the flexure's interfaces with the hub and the shoe, thirds of the way),
    for a flexure that joins only shoe material 'in-shoe flexure', for a hub or shoe point
    near a flexure (within the flexure's width) 'at flexure <j> root' / 'at flexure <j>
    joint'; and the boundary it lies on ('bore', 'contact surface', 'free edge' = a fillet
    or slot flank), if any.  ``element``: the element the point belongs to (e.g. of a raw
    vertex stress); without it the element is found by position (flexure preferred on an
    interface)."""
    if not isinstance(cm, ClutchMesh):
        raise InputError(f"name_location: cm must be a ClutchMesh (got {type(cm).__name__})")
    pt = np.asarray(xy, dtype=float).reshape(-1)
    if pt.shape != (2,) or not np.all(np.isfinite(pt)):
        raise InputError(f"name_location: xy must be a finite point (x, y) (got {xy!r})")
    mesh = cm.mesh
    p, t = mesh.p, mesh.t
    nel = t.shape[1]
    zone = _element_zone(cm)
    scale = float(np.max(np.abs(p)))
    if element is not None:
        if isinstance(element, bool) or int(element) != element or not 0 <= int(element) < nel:
            raise ParameterError("element", element, f"an element index in [0, {nel - 1}]")
        e = int(element)
    else:
        cen = p[:, t].mean(axis=1)
        _, cand = cKDTree(cen.T).query(pt, k=min(12, nel))
        cand = np.atleast_1d(cand)
        inside = []
        for c in cand:
            v = p[:, t[:, c]]
            T = np.array([v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]]).T
            lam = np.linalg.solve(T, pt - v[:, 0])
            if lam.min() >= -1e-6 and lam.sum() <= 1 + 1e-6:
                inside.append(int(c))
        if not inside:
            d = np.linalg.norm(cen[:, cand] - pt[:, None], axis=0)
            if d.min() > 0.05 * scale:
                raise InputError(f"name_location: point ({pt[0]:.6g}, {pt[1]:.6g}) m lies outside the part")
            inside = [int(cand[0])]
        pref = sorted(inside, key=lambda c: (0 if str(zone[c]).startswith("flexure") else 1))
        e = pref[0]
    zname = str(zone[e]) or "part"
    kind = zname.split("_")[0]
    idx = int(zname.split("_")[1]) if "_" in zname and zname.split("_")[1].isdigit() else None
    # boundary: the point is one of the P2 nodes (corner or mid-edge) of a boundary facet
    bnd = None
    nodes = _facet_nodes(cm)
    bfac = mesh.boundary_facets()
    bnodes = np.unique(nodes[:, bfac])
    xyn = _p2_nodes(cm)
    dist, j = cKDTree(xyn[:, bnodes].T).query(pt)
    if dist <= 1e-9 * scale:
        v = int(bnodes[j])
        groups = mesh.boundaries or {}
        names = [g for g in ("bore", "contact", "cut_a", "cut_b")
                 if g in groups and np.isin(v, nodes[:, np.asarray(groups[g])]).any()]
        bnd = {"bore": "bore", "contact": "contact surface", "cut_a": "sector cut", "cut_b": "sector cut"}.get(
            names[0], names[0]) if names else "free edge"
    position = ""
    sub = mesh.subdomains or {}
    if kind == "flexure":
        comps = _components(cm, np.asarray(sub[zname]))
        comp = next(c for c in comps if e in c)
        hub_pts = _interface_points(cm, comp, zone, "hub")
        shoe_pts = _interface_points(cm, comp, zone, "shoe")
        if hub_pts.shape[1] and shoe_pts.shape[1]:
            dh = np.min(np.linalg.norm(hub_pts - pt[:, None], axis=0))
            ds = np.min(np.linalg.norm(shoe_pts - pt[:, None], axis=0))
            frac = dh / max(dh + ds, 1e-300)
            position = "hub end" if frac < 1 / 3 else ("shoe end" if frac > 2 / 3 else "middle")
            if len(comps) > 1:
                position = "main flexure, " + position
        elif shoe_pts.shape[1]:
            position = "in-shoe flexure"
        elif hub_pts.shape[1]:
            position = "hub end"
    elif kind in ("hub", "shoe"):
        best = None
        for fname in sorted(n for n in sub if n.startswith("flexure")):
            fel = np.asarray(sub[fname])
            fv = np.unique(t[:, fel])
            d = float(np.min(np.linalg.norm(p[:, fv] - pt[:, None], axis=0)))
            area = _area(cm, fel)
            width = 2.0 * area / max(_perimeter(cm, fel), 1e-300)
            if d <= width and (best is None or d < best[0]):
                best = (d, fname)
        if best is not None:
            j_ = best[1].split("_")[1]
            position = f"at flexure {j_} root" if kind == "hub" else f"at flexure {j_} joint"
        elif kind == "hub":
            position = "hub body"
        elif bnd != "contact surface":
            position = "shoe body"
    return Location(zone=zname, kind=kind, index=idx, position=position, boundary=bnd,
                    x_m=float(pt[0]), y_m=float(pt[1]))


#: P2 bases of the last meshes named (a mesh is immutable: its basis is built once)
_P2_BASES: dict[int, tuple] = {}


def _p2_basis(cm: ClutchMesh):
    from skfem import Basis, ElementTriP2

    hit = _P2_BASES.get(id(cm.mesh))
    if hit is None or hit[0] is not cm.mesh:
        if len(_P2_BASES) >= 4:
            _P2_BASES.pop(next(iter(_P2_BASES)))
        hit = _P2_BASES[id(cm.mesh)] = (cm.mesh, Basis(cm.mesh, ElementTriP2(), intorder=1))
    return hit[1]


def _quadratic(cm: ClutchMesh) -> bool:
    """The mesh carries its P2 nodes (a quadratic MeshTri2: vertices, then one per facet)."""
    m = cm.mesh
    return m.doflocs.shape[1] == m.nvertices + m.facets.shape[1]


def _facet_nodes(cm: ClutchMesh) -> np.ndarray:
    """(3, nfacets) P2 node ids of every facet: its two corners and its mid-edge node."""
    m = cm.mesh
    mid = m.nvertices + np.arange(m.facets.shape[1]) if _quadratic(cm) else _p2_basis(cm).facet_dofs[0]
    return np.vstack([m.facets, mid])


def _p2_nodes(cm: ClutchMesh) -> np.ndarray:
    """(2, n) positions of the P2 nodes (corners keep the mesh's vertex numbers)."""
    return cm.mesh.doflocs if _quadratic(cm) else _p2_basis(cm).doflocs


def _area(cm: ClutchMesh, elems: np.ndarray) -> float:
    p, t = cm.mesh.p, cm.mesh.t[:, elems]
    a, b, c = p[:, t[0]], p[:, t[1]], p[:, t[2]]
    return float(0.5 * np.abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).sum())


def _perimeter(cm: ClutchMesh, elems: np.ndarray) -> float:
    """Length of the edges of ``elems`` that border no other element of the set."""
    mesh = cm.mesh
    f = mesh.t2f[:, elems].ravel()
    uniq, cnt = np.unique(f, return_counts=True)
    edge = uniq[cnt == 1]
    a, b = mesh.p[:, mesh.facets[0, edge]], mesh.p[:, mesh.facets[1, edge]]
    return float(np.linalg.norm(b - a, axis=0).sum())
