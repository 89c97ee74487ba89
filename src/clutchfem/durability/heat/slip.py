"""Slip heat: transient heat conduction in a one-piece clutch while it slips in a held drum.

Scenario (thesis test, issue 14): chain brake on (drum held), full throttle; the engine
settles at the slip speed omega and the shoes rub the drum at v = omega R_d.  The friction
power mu v lam_i of every contact node is split between the shoe and the drum; the shoe's
share conducts into the part, which loses heat through its two faces and into the
crankshaft.  Repeated slip events with cooling pauses show whether heat accumulates.

Field equation (plate: temperature uniform through the axial thickness h)
--------------------------------------------------------------------------
    rho c h dT/dt = div(k h grad T) - 2 h_f (T - T_amb)                 in the part
    -k h dT/dn    = h_b h (T - T_crank)                                  on the bore
    -k h dT/dn    = h_e h (T - T_amb)                                    on free edges
    -k h dT/dn    = -gamma q h                                           on the contact patch

h_f: convection coefficient of each face (both faces: 2 h_f), h_b: conductance of the
bore joint to the crankshaft at T_crank, h_e: optional convection on the free edges (0 by
default; the loaded contact facets never convect: they touch the drum), q = mu p v the
friction heat flux, gamma the part's share (below).  Units: SI, temperatures in deg C
(the equation is linear, only differences matter).

Weak form with scalar P2 (scikit-fem ``ElementTriP2`` on the curved ``MeshTri2``, the
same mesh and node numbering as the elastic model):

    M dT/dt + (K + H) T = f + Q,
    M = int rho c h phi_i phi_j,   K = int k h grad phi_i . grad phi_j,
    H = int 2 h_f phi_i phi_j + oint_bore h_b h phi_i phi_j + oint_edges h_e h phi_i phi_j,
    f = int 2 h_f T_amb phi_i + oint_bore h_b h T_crank phi_i + oint_edges h_e h T_amb phi_i.

**Heat load from the contact forces.**  The contact solver's nodal forces are consistent:
lam_i = int p phi_i h ds over the contact surface, for the full axial thickness.  The
consistent nodal heat load of the flux gamma mu v p on that surface is therefore exactly

    Q_i = int gamma mu v p phi_i h ds = gamma mu v lam_i     [W],

no pressure reconstruction, no tributary lengths (:class:`SlipHeatLoad`).

**Cyclic sector.**  For a one-sector model (``cut_a``/``cut_b``) the temperature is the
same at a node of cut_b and its partner on cut_a rotated by the sector angle (a scalar:
no rotation of the value).  A sparse map P (all nodes x independent nodes), T = P a, is
applied as in :func:`clutchfem.fem.constraint_map`; the full part needs none.  Energies
are reported for the whole part (sector values x n_total / n_model).

Time stepping
-------------
Crank-Nicolson (second order, A-stable) with a fixed step, each slip event and each pause
being one segment of equal steps.  The load is piecewise constant in time and jumps at
segment ends, which sit on step boundaries.  A jump excites the stiff (fine-scale) modes,
which Crank-Nicolson does not damp (amplification -> -1): every segment therefore starts
with two backward-Euler half steps (Rannacher start).  Backward Euler with dt/2 has the
matrix 2 M/dt + A = 2 (M/dt + A/2), the Crank-Nicolson matrix: **one factorisation per
step size** (SPD, :func:`clutchfem.linsolve.factorize`).  Fixed rather than adaptive steps:
the only non-smoothness is at the known switch times, one factorisation serves the whole
run, and the time error is estimated by repeating the run with 2 dt (Richardson for order
2: err ~ (T_dt - T_2dt)/3, reported as ``time_error_estimate_K``).  Measured orders are in
``tests/test_durability_heat.py`` and ``docs/durability_handoff.md``.

The energy tallies use the scheme's own quadrature in time (CN: trapezoid of the loss
rates; BE: end-point), so the discrete balance stored = input - losses holds to solver
round-off: int grad(1) = 0 makes conduction drop out of 1' (M dT/dt + A T), and the
all-ones field is cyclic, so the sector map keeps the identity.

Heat partition shoe/drum (:func:`heat_partition`)
-------------------------------------------------
Blok's postulate (Blok 1937): the two mean surface temperatures of the patch are equal.
The shoe patch is *stationary* on the shoe; on the drum it is a *moving* source: a drum
point passes under n patches per revolution, each for the dwell time t_c = L / v (L the
patch length along the drum, period P = 2 pi R_d / (n v), duty phi = t_c / P =
n L / (2 pi R_d), the covered fraction of the track).  Peclet number of the drum surface
(Jaeger 1942, Archard 1959): Pe = v a / (2 kappa_d), a = L / 2.

Each side's mean patch temperature per unit patch flux (a thermal resistance, K m^2/W):

* shoe, ``shoe_side='fe'`` (default): the part's own FE response: the flux-weighted mean
  temperature rise of the loaded nodes at t_ref for the full friction power, divided by
  the mean patch flux q = P_fric / (n L h).  ``'semi_infinite'``: 2 sqrt(t/pi) / e_s
  (stationary uniform flux on a half-space, Carslaw & Jaeger 2.9), e = sqrt(k rho c).
* drum: one-dimensional conduction normal to the drum surface (valid for Pe >> 1: lateral
  conduction is negligible during the dwell), in a wall of thickness w whose outer face is
  adiabatic (ASSUMED, conservative for the part: a drum that keeps its heat pushes more
  into the shoe).  The heated face sees the pulse train q_d(t) = q on for t_c, off for
  P - t_c.  Split into its mean phi q and the zero-mean rest:

      R_d = phi S_w(t_ref) + F,
      S_w(t)  = slab step response (surface temperature for unit flux, Carslaw & Jaeger 3.8:
                (w/k)[Fo + 1/3 - 2/pi^2 sum exp(-n^2 pi^2 Fo)/n^2], image series for Fo < 1),
      F       = (1/phi) sum_k 2 sin^2(k pi phi)/(k pi)^2 Re Z(k w0),   w0 = 2 pi / P,
      Z(w)    = coth(m w)/(k m), m = sqrt(i w / kappa)  (surface impedance of the wall),

  F being the steady-periodic flash temperature averaged over the dwell (exact Fourier
  series of the pulse train).  When fewer than ``PERIODIC_PASSES`` passes have happened by
  t_ref (slow sliding), the steady-periodic assumption does not hold and R_d is instead
  the exact Duhamel superposition of every pass with S_w, averaged over the patch.

Equal temperatures gamma q R_s = (1 - gamma) q R_d give the part's share

    gamma = R_d / (R_s + R_d).

Limits (tested): Pe -> infinity (t_c, P -> 0): F -> 0 and, for a thick wall,
gamma -> phi e_s / (phi e_s + e_d): Charron's (1943) partition with Newcomb's area
weighting A_shoe / A_track = phi.  Pe -> 0 (v -> 0): the drum point never leaves the patch,
R_d -> S_w(t) and, for a thick wall, gamma -> e_s / (e_s + e_d): two stationary bodies
(Charron).  With the FE shoe side the patch length cancels from gamma except in the small
flash term (phi S_w and R_s are both proportional to L).  gamma is evaluated once, at
t_ref = the duration of one slip event, and kept for the whole run (the equation stays
linear and the energy split exact).

ASSUMED values (all configurable, defaults for 51CrV4 in a steel drum)
---------------------------------------------------------------------
* part: k = 46.6 W/(m K), c = 460 J/(kg K), rho = 7850 kg/m^3: room-temperature handbook
  values of low-alloy Cr-V spring steel (AISI 6150 ~ 51CrV4; ASM Handbook vol. 1 / MatWeb
  data for 6150).  Constant properties (k falls and c rises with temperature: at 400 C
  roughly -15 % and +20 %, which makes the real part slightly slower to heat and slower to
  conduct; not modelled).
* limit temperature 400 C: the low end of the tempering range (~400-500 C after an oil
  quench from ~850 C) that gives ~45 HRC in 51CrV4 (tempering charts of 1.8159 / EN 10089
  spring steels); above it the hardness is lost for good.  Spring relaxation starts lower
  (~200-250 C): set ``limit_temperature`` to study it.
* hot yield strength: EN 1993-1-2 (Eurocode 3 fire design) Table 3.1 reduction factors for
  carbon steel, ``k_p`` (proportional limit; conservative, default) or ``k_y`` (effective
  yield at 2 % strain).  The 0.2 % proof stress of a hardened steel at temperature lies
  between the two: both are reported.
* faces: h_f = 50 W/(m^2 K) per face.  A free disc of radius 34 mm spinning at 7000 rpm in
  air has Re = omega R^2 / nu ~ 5e4 (laminar) and a mean Nu = 0.36 Re^0.5 ~ 83 (Cobb &
  Saunders 1956), h ~ 63 W/(m^2 K); the clutch runs enclosed in its drum: 50 taken.
  Radiation is neglected (~10 W/(m^2 K) at 400 C for oxidised steel: conservative).
* bore: joint conductance h_b = 3000 W/(m^2 K) (threaded steel-steel joint; contact
  conductances of 1e3-1e4 W/(m^2 K), Incropera Table 3.1 / Madhusudana 1996) to a
  crankshaft at T_crank = 60 C (engine warm); ambient 25 C; free edges h_e = 0
  (conservative); initial state: steady state of the idling clutch (no friction).
* drum: steel (same k, c, rho), rim wall w = 2.0 mm, outer face adiabatic.

References: H. Blok, Proc. General Discussion on Lubrication, IMechE 1937; J.C. Jaeger,
J. Proc. Roy. Soc. NSW 76 (1942) 203; A. Charron, 1943 (partition by effusivities, via
Newcomb & Spurr / Limpert, Brake Design and Safety); J.F. Archard, Wear 2 (1959) 438;
H.S. Carslaw & J.C. Jaeger, Conduction of Heat in Solids (1959); W.G. Cobb & O.A. Saunders,
Proc. Roy. Soc. A 236 (1956) 343; EN 1993-1-2:2005 Table 3.1.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar, Literal

import numpy as np
import scipy.sparse as sp
from pydantic import Field
from scipy.spatial import cKDTree
from scipy.special import erfc
from skfem import Basis, BilinearForm, ElementTriP2, FacetBasis, LinearForm, asm
from skfem.helpers import dot, grad

from ...core import InputError, MeshError, ParameterError, ParamSet, choice, param
from ...fe import factorize
from ...mesh import ClutchMesh

__all__ = [
    "ThermalMaterial", "DrumThermal", "ThermalEnvironment", "SlipScenario", "SlipHeatLoad",
    "slip_heat_load", "HeatPartition", "heat_partition", "wall_step_response",
    "drum_patch_response", "HeatModel", "build_heat_model", "slip_heat", "SlipHeatResult",
    "write_vtu", "render_png", "hot_yield_ratio", "HOT_YIELD_TABLE", "PERIODIC_PASSES",
]

#: Time steps of one run (every event and pause; the 2 dt error estimate adds half, the
#: partition pre-run one event) above which a scenario is refused: ~0.1 ms per step on a
#: 5k-node sector, so 2e5 steps are tens of seconds, 1e8 would be hours
MAX_TIME_STEPS = 200_000

#: Passes of a drum point under the patches by t_ref above which the drum flash is taken in
#: its steady-periodic form (Fourier series); below, every pass is superposed (Duhamel).
PERIODIC_PASSES = 1000

#: EN 1993-1-2:2005 Table 3.1 (carbon steel at elevated temperature): temperature [C],
#: k_y (effective yield strength, 2 % strain), k_p (proportional limit).
HOT_YIELD_TABLE = {
    "T_C": (20.0, 100.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 900.0, 1000.0, 1100.0, 1200.0),
    "effective": (1.0, 1.0, 1.0, 1.0, 1.0, 0.78, 0.47, 0.23, 0.11, 0.06, 0.04, 0.02, 0.0),
    "proportional": (1.0, 1.0, 0.807, 0.613, 0.42, 0.36, 0.18, 0.075, 0.05, 0.0375, 0.025, 0.0125, 0.0),
}


def hot_yield_ratio(T_C, basis: Literal["proportional", "effective"] = "proportional"):
    """Yield strength at temperature / at 20 C, EN 1993-1-2 Table 3.1 (linear between rows,
    1 below 20 C).  ``basis``: 'proportional' (k_p, lower bound) or 'effective' (k_y)."""
    if basis not in ("proportional", "effective"):
        raise ParameterError("hot_yield_basis", basis, "one of 'proportional', 'effective'")
    T = np.asarray(T_C, dtype=float)
    if np.any(~np.isfinite(T)):
        raise ParameterError("temperature", T_C, "a finite temperature in C")
    r = np.interp(T, HOT_YIELD_TABLE["T_C"], HOT_YIELD_TABLE[basis], left=1.0, right=0.0)
    return float(r) if r.ndim == 0 else r


# ---------------------------------------------------------------------------------------
# parameter sets
# ---------------------------------------------------------------------------------------
class ThermalMaterial(ParamSet):
    """Thermal data of the part (defaults: hardened 51CrV4, ASSUMED, see module docstring)."""

    context: ClassVar[str] = "thermal material"
    name: str = "51CrV4 (SS 2230) spring steel, hardened ~45 HRC"
    conductivity: float = param(46.6, "W/(m K)", 0.1, 500.0,
                                "thermal conductivity k (ASSUMED, 6150/51CrV4 handbook)", "k")
    specific_heat: float = param(460.0, "J/(kg K)", 50.0, 5000.0, "specific heat c (ASSUMED)", "c")
    density: float = param(7850.0, "kg/m^3", 100.0, 25000.0, "density rho (thesis)", "rho")
    limit_temperature: float = param(400.0, "C", 50.0, 1200.0,
                                     "limit temperature: tempering temperature of the hardened steel "
                                     "(ASSUMED, low end of 400-500 C for ~45 HRC)", "T_lim")
    yield_strength: float = param(1250e6, "Pa", 1e5, 1e11, "room-temperature yield strength Rp0.2 (thesis)", "R_p0.2")
    hot_yield_basis: Literal["proportional", "effective"] = choice(
        "proportional", "EN 1993-1-2 reduction factor used for the hot yield strength: k_p (conservative) or k_y")

    @property
    def diffusivity(self) -> float:
        """kappa = k / (rho c) [m^2/s]."""
        return self.conductivity / (self.density * self.specific_heat)

    @property
    def effusivity(self) -> float:
        """e = sqrt(k rho c) [W s^0.5 / (m^2 K)]."""
        return math.sqrt(self.conductivity * self.density * self.specific_heat)

    def yield_ratio(self, T_C) -> float:
        """Hot yield strength / room-temperature yield strength at T_C (see HOT_YIELD_TABLE)."""
        return hot_yield_ratio(T_C, self.hot_yield_basis)


class DrumThermal(ParamSet):
    """The drum as seen by the heat partition: a rim wall heated on its inner face, outer
    face adiabatic (ASSUMED, conservative for the part).  Defaults: steel, 2 mm (ASSUMED)."""

    context: ClassVar[str] = "drum (thermal)"
    conductivity: float = param(46.6, "W/(m K)", 0.1, 500.0, "drum conductivity (ASSUMED steel)", "k_d")
    specific_heat: float = param(460.0, "J/(kg K)", 50.0, 5000.0, "drum specific heat (ASSUMED steel)", "c_d")
    density: float = param(7850.0, "kg/m^3", 100.0, 25000.0, "drum density (ASSUMED steel)", "rho_d")
    wall_thickness: float = param(2.0e-3, "m", 0.2e-3, 50e-3, "drum rim wall thickness (ASSUMED)", "w_d")

    @property
    def diffusivity(self) -> float:
        return self.conductivity / (self.density * self.specific_heat)

    @property
    def effusivity(self) -> float:
        return math.sqrt(self.conductivity * self.density * self.specific_heat)


class ThermalEnvironment(ParamSet):
    """Boundary conditions and initial state (all ASSUMED, see module docstring)."""

    context: ClassVar[str] = "thermal environment"
    ambient_temperature: float = param(25.0, "C", -60.0, 200.0, "air temperature T_amb", "T_amb")
    face_htc: float = param(50.0, "W/(m^2 K)", 0.0, 1e4, "convection coefficient of each axial face", "h_f")
    edge_htc: float = param(0.0, "W/(m^2 K)", 0.0, 1e4, "convection coefficient of the free edges (not bore, "
                            "not the loaded contact patch)", "h_e")
    bore_conductance: float = param(3000.0, "W/(m^2 K)", 0.0, 1e7,
                                    "conductance of the bore joint to the crankshaft", "h_b")
    crankshaft_temperature: float = param(60.0, "C", -60.0, 400.0, "crankshaft temperature at the bore", "T_crank")
    initial: Literal["steady", "ambient", "uniform"] = choice(
        "steady", "initial field: steady state without friction, ambient, or uniform initial_temperature")
    initial_temperature: float = param(25.0, "C", -60.0, 1200.0, "initial temperature (initial='uniform' only)", "T_0")


class SlipScenario(ParamSet):
    """The slip test: events of ``seconds`` separated by cooling pauses of ``pause``."""

    context: ClassVar[str] = "slip scenario"
    seconds: float = param(10.0, "s", 1e-3, 3600.0, "duration of one slip event", "t_slip")
    cycles: int = param(1, "-", 1, 1000, "number of slip events", "N")
    pause: float = param(0.0, "s", 0.0, 36000.0, "cooling pause after each slip event (idle, no friction)", "t_pause")
    steps_per_event: int = param(200, "-", 4, 100000, "time steps per slip event (fixed step; the pause "
                                 "gets the nearest equal step)", "n_t")
    error_estimate: bool = Field(True, description="repeat the run with 2 dt and report a Richardson "
                                 "time-error estimate", json_schema_extra={"unit": "-", "symbol": ""})

    def check(self) -> None:
        if self.cycles > 1 and self.pause <= 0.0:
            self.fail("pause", "a pause > 0 s between repeated slip events (cycles > 1)")
        n_slip, n_pause = self.steps()
        total = self.cycles * (n_slip + n_pause)
        if total > MAX_TIME_STEPS:
            name = "pause" if n_pause > n_slip else ("cycles" if self.cycles > 1 else "steps_per_event")
            self.fail(name, f"a run of at most {MAX_TIME_STEPS} time steps; cycles x (steps per event + pause / "
                      f"dt) = {self.cycles} x ({n_slip} + {n_pause}) = {total} (dt = seconds / steps_per_event = "
                      f"{self.seconds / n_slip:.3g} s): fewer cycles, a shorter pause or fewer steps per event")

    def steps(self) -> tuple[int, int]:
        """(steps per slip event, steps per pause): equal steps dt = seconds / n_slip (n_slip
        even, for the 2 dt error estimate), the pause with the nearest even number of steps
        of about dt (at least 2; 0 without a pause)."""
        n_slip = self.steps_per_event + (self.steps_per_event % 2)
        n_pause = 0
        if self.pause > 0:
            n_pause = max(2, int(round(self.pause / (self.seconds / n_slip))))
            n_pause += n_pause % 2
        return n_slip, n_pause



# ---------------------------------------------------------------------------------------
# heat load from the contact forces
# ---------------------------------------------------------------------------------------
def _finite_positive(name: str, value, allowed: str, *, zero_ok: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, allowed) from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not zero_ok):
        raise ParameterError(name, value, allowed)
    return v


@dataclass(frozen=True)
class SlipHeatLoad:
    """Friction heat at the contact nodes of one slip state (the model: sector or full part).

    ``node_index`` (m,): scalar P2 node ids on the clutch mesh (= the dofs of skfem's
    ``ElementTriP2`` basis: vertices first, then one per edge; a vector P2 dof d of the
    elastic model belongs to node d // 2).  ``lam_N`` (m,): normal contact forces [N] at
    those nodes, consistent nodal forces for the full axial thickness, >= 0.  ``mu``:
    friction coefficient; ``omega_rad_s``: slip speed of the hub relative to the held drum;
    ``drum_radius_m``: R_d, so v = omega R_d.  Nodal friction power: mu v lam_i [W]
    (before the partition)."""

    node_index: np.ndarray
    lam_N: np.ndarray
    mu: float
    omega_rad_s: float
    drum_radius_m: float

    def __post_init__(self):
        idx = np.asarray(self.node_index)
        lam = np.asarray(self.lam_N, dtype=float) if np.size(self.lam_N) else np.zeros(0)
        if idx.ndim != 1 or lam.ndim != 1 or len(idx) != len(lam):
            raise InputError(f"SlipHeatLoad: node_index and lam_N must be 1-D arrays of equal length "
                             f"(got shapes {np.shape(self.node_index)} and {np.shape(self.lam_N)})")
        if len(idx) == 0:
            raise InputError("SlipHeatLoad: no contact nodes given (node_index is empty)")
        if not np.issubdtype(idx.dtype, np.integer):
            if not np.all(np.isfinite(idx)) or np.any(idx != np.round(idx)):
                raise ParameterError("node_index", self.node_index, "integer node ids >= 0")
            idx = idx.astype(np.int64)
        if np.any(idx < 0):
            raise ParameterError("node_index", int(idx.min()), "integer node ids >= 0")
        if len(np.unique(idx)) != len(idx):
            raise InputError("SlipHeatLoad: node_index lists a node more than once")
        if np.any(~np.isfinite(lam)) or np.any(lam < 0):
            bad = lam[~np.isfinite(lam) | (lam < 0)][0]
            raise ParameterError("lam_N", float(bad), "finite nodal contact forces >= 0 N")
        if not lam.any():
            raise ParameterError("lam_N", 0.0, "at least one contact force > 0 N (the clutch must touch the drum)")
        object.__setattr__(self, "node_index", idx.astype(np.int64))
        object.__setattr__(self, "lam_N", lam)
        mu = _finite_positive("mu", self.mu, "a friction coefficient in (0, 1]")
        if mu > 1.0:
            raise ParameterError("mu", self.mu, "a friction coefficient in (0, 1]")
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "omega_rad_s", _finite_positive(
            "omega_rad_s", self.omega_rad_s, "a slip speed > 0 rad/s (and <= 5000 rad/s)"))
        if self.omega_rad_s > 5000.0:
            raise ParameterError("omega_rad_s", self.omega_rad_s, "a slip speed > 0 rad/s (and <= 5000 rad/s)")
        R = _finite_positive("drum_radius_m", self.drum_radius_m, "a drum radius in (0, 1] m")
        if R > 1.0:
            raise ParameterError("drum_radius_m", self.drum_radius_m, "a drum radius in (0, 1] m")
        object.__setattr__(self, "drum_radius_m", R)

    @property
    def slip_speed_m_s(self) -> float:
        """Sliding speed v = omega R_d [m/s]."""
        return self.omega_rad_s * self.drum_radius_m

    @property
    def nodal_power_W(self) -> np.ndarray:
        """Friction power mu v lam_i per node [W] (shoe + drum)."""
        return self.mu * self.slip_speed_m_s * self.lam_N

    @property
    def power_W(self) -> float:
        """Friction power of the model (sector or full part) [W]."""
        return float(self.nodal_power_W.sum())


def slip_heat_load(cm: ClutchMesh, xy, lam_N, *, mu: float, omega_rad_s: float,
                   drum_radius_m: float) -> SlipHeatLoad:
    """Build a :class:`SlipHeatLoad` from contact-node positions ``xy`` (2, m) [m] and forces
    ``lam_N`` (m,) [N] (e.g. ``ContactNodes.xy`` and ``SpeedState.lam`` of the slip state):
    each position is matched to the P2 node of ``cm`` at that place (tolerance 1e-8 of the
    part size)."""
    xy = np.asarray(xy, dtype=float)
    if xy.ndim != 2 or xy.shape[0] != 2:
        raise InputError(f"slip_heat_load: xy must have shape (2, m) (got {xy.shape})")
    if np.any(~np.isfinite(xy)):
        raise InputError("slip_heat_load: xy contains non-finite coordinates")
    nodes = _scalar_basis(cm).doflocs
    dist, idx = cKDTree(nodes.T).query(xy.T)
    scale = float(np.max(np.abs(nodes)))
    if len(dist) and dist.max() > 1e-8 * scale:
        k = int(np.argmax(dist))
        raise InputError(f"slip_heat_load: contact point {k} at ({xy[0, k]:.6g}, {xy[1, k]:.6g}) m is "
                         f"{dist[k]:.3g} m from the nearest P2 node of {cm.source}: not a node of this mesh")
    return SlipHeatLoad(node_index=idx, lam_N=lam_N, mu=mu, omega_rad_s=omega_rad_s,
                        drum_radius_m=drum_radius_m)


def _scalar_basis(cm: ClutchMesh) -> Basis:
    return Basis(cm.mesh, ElementTriP2(), intorder=4)


# ---------------------------------------------------------------------------------------
# heat partition (Blok's postulate, moving source on the drum)
# ---------------------------------------------------------------------------------------
def _ierfc(x):
    return np.exp(-x * x) / math.sqrt(math.pi) - x * erfc(x)


def wall_step_response(t, conductivity: float, density: float, specific_heat: float,
                       wall_thickness: float):
    """Surface temperature rise [K per W/m^2] of a wall of thickness w heated on one face by
    a unit flux switched on at t = 0, other face adiabatic (Carslaw & Jaeger 3.8).  Image
    series for Fo = kappa t / w^2 < 1, Fourier series above (both converge in a few terms).
    ``wall_thickness = inf``: half-space, 2 sqrt(t / pi) / e.  0 for t <= 0."""
    t = np.asarray(t, dtype=float)
    k = conductivity
    kappa = k / (density * specific_heat)
    out = np.zeros_like(t)
    pos = t > 0
    if not np.isfinite(wall_thickness):
        out[pos] = 2.0 * np.sqrt(kappa * t[pos]) / (k * math.sqrt(math.pi))
        return out
    w = wall_thickness
    Fo = kappa * np.where(pos, t, 0.0) / (w * w)
    small = pos & (Fo < 1.0)
    if small.any():
        r = np.sqrt(kappa * t[small])
        s = np.full_like(r, 1.0 / math.sqrt(math.pi))
        for n in range(1, 8):
            s += 2.0 * _ierfc(n * w / r)
        out[small] = 2.0 * r / k * s
    big = pos & (Fo >= 1.0)
    if big.any():
        F = Fo[big]
        s = F + 1.0 / 3.0
        for n in range(1, 6):
            s -= 2.0 / (math.pi ** 2 * n * n) * np.exp(-(n * math.pi) ** 2 * F)
        out[big] = w / k * s
    return out


def _wall_impedance_real(omega, conductivity, density, specific_heat, wall_thickness):
    """Re Z(omega) [K m^2 / W]: steady-periodic surface temperature per unit harmonic flux,
    Z = coth(m w) / (k m), m = sqrt(i omega / kappa)."""
    kappa = conductivity / (density * specific_heat)
    m = np.sqrt(1j * np.asarray(omega, dtype=float) / kappa)
    if np.isfinite(wall_thickness):
        e = np.exp(-2.0 * m * wall_thickness)
        coth = (1.0 + e) / (1.0 - e)
    else:
        coth = 1.0
    return np.real(coth / (conductivity * m))


def drum_patch_response(drum: DrumThermal, *, slip_speed_m_s: float, patch_length_m: float,
                        drum_radius_m: float, n_patches: int, t_ref_s: float,
                        method: Literal["auto", "periodic", "passes"] = "auto") -> dict:
    """Mean temperature rise of the drum under a patch at t_ref per unit patch flux
    [K m^2/W] (module docstring): ``{'track': phi S_w(t), 'flash': F, 'total', 'method',
    'duty', 'dwell_s', 'period_s', 'passes'}``.  ``method`` 'auto' takes the steady-periodic
    form when more than PERIODIC_PASSES passes happened by t_ref, else the pass-by-pass
    superposition; the other two force one (tests compare them)."""
    v, L, R, t = slip_speed_m_s, patch_length_m, drum_radius_m, t_ref_s
    n = int(n_patches)
    props = (drum.conductivity, drum.density, drum.specific_heat, drum.wall_thickness)
    phi = min(n * L / (2.0 * math.pi * R), 1.0)
    tc = L / v
    P = tc / phi
    passes = t / P
    S_t = float(wall_step_response(t, *props))
    if method == "auto":
        method = "periodic" if passes > PERIODIC_PASSES else "passes"
    if phi >= 1.0:  # the patches cover the whole track: continuous heating
        return {"track": S_t, "flash": 0.0, "total": S_t, "method": "continuous", "duty": 1.0,
                "dwell_s": tc, "period_s": P, "passes": passes}
    if method == "periodic":
        w0 = 2.0 * math.pi / P
        K = 200000
        k = np.arange(1, K + 1, dtype=float)
        terms = 2.0 * np.sin(k * math.pi * phi) ** 2 / (k * math.pi) ** 2 * \
            _wall_impedance_real(k * w0, *props)
        e = drum.effusivity
        tail = (1.0 / (math.pi ** 2 * e * math.sqrt(2.0 * w0))) * (2.0 / 3.0) * K ** -1.5
        flash = float((terms.sum() + tail) / phi)
        total = phi * S_t + flash
    elif method == "passes":
        # average over the patch of the exact superposition of every pass (s = L u^2 removes the
        # sqrt(s) behaviour at the leading edge; midpoint rule in u)
        nu = 4000
        u = (np.arange(nu) + 0.5) / nu
        s = L * u * u
        wq = 2.0 * u / nu
        since = np.minimum(s / v, t)  # time under the current patch
        T = wall_step_response(since, *props)
        J = int(math.ceil(t / P)) + 1
        for j in range(1, J + 1):
            entry = t - s / v - j * P
            exit_ = entry + tc
            live = exit_ > 0
            if not live.any():
                break
            T[live] += (wall_step_response(t - np.maximum(entry[live], 0.0), *props)
                        - wall_step_response(t - exit_[live], *props))
        total = float(np.sum(wq * T))
        flash = total - phi * S_t
    else:
        raise ParameterError("method", method, "one of 'auto', 'periodic', 'passes'")
    return {"track": phi * S_t, "flash": flash, "total": total, "method": method, "duty": phi,
            "dwell_s": tc, "period_s": P, "passes": passes}


@dataclass(frozen=True)
class HeatPartition:
    """Share of the friction heat that enters the part (see module docstring)."""

    fraction_part: float
    peclet: float
    slip_speed_m_s: float
    patch_length_m: float
    duty: float
    dwell_time_s: float
    pass_period_s: float
    t_ref_s: float
    r_shoe_K_m2_W: float
    r_drum_track_K_m2_W: float
    r_drum_flash_K_m2_W: float
    drum_method: str
    shoe_side: str

    @property
    def fraction_drum(self) -> float:
        return 1.0 - self.fraction_part

    def to_json(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__} | {"fraction_drum": self.fraction_drum}


def heat_partition(part: ThermalMaterial, drum: DrumThermal, *, slip_speed_m_s: float,
                   patch_length_m: float, drum_radius_m: float, n_patches: int, t_ref_s: float,
                   shoe_response_K_m2_W: float | None = None,
                   drum_method: Literal["auto", "periodic", "passes"] = "auto") -> HeatPartition:
    """gamma = R_d / (R_s + R_d): Blok's equal mean patch temperatures, stationary patch on
    the shoe, moving patch on the drum (module docstring).  ``shoe_response_K_m2_W``: the
    shoe's mean patch temperature rise per unit patch flux at t_ref (from the FE model);
    None: a half-space, 2 sqrt(t_ref/pi)/e_s.  ``n_patches``: shoes of the whole clutch."""
    v = _finite_positive("slip_speed_m_s", slip_speed_m_s, "a sliding speed > 0 m/s")
    L = _finite_positive("patch_length_m", patch_length_m, "a contact patch length > 0 m")
    R = _finite_positive("drum_radius_m", drum_radius_m, "a drum radius > 0 m")
    t = _finite_positive("t_ref_s", t_ref_s, "a reference time > 0 s")
    if isinstance(n_patches, bool) or int(n_patches) != n_patches or int(n_patches) < 1:
        raise ParameterError("n_patches", n_patches, "an integer number of contact patches >= 1")
    if int(n_patches) * L > 2.0 * math.pi * R * (1.0 + 1e-6):
        raise ParameterError("patch_length_m", L, f"n_patches x patch length <= the drum circumference "
                                                   f"{2 * math.pi * R:.6g} m")
    if shoe_response_K_m2_W is None:
        Rs = 2.0 * math.sqrt(t / math.pi) / part.effusivity
        side = "semi_infinite"
    else:
        Rs = _finite_positive("shoe_response_K_m2_W", shoe_response_K_m2_W,
                              "a shoe temperature rise per unit flux > 0 K m^2/W")
        side = "fe"
    d = drum_patch_response(drum, slip_speed_m_s=v, patch_length_m=L, drum_radius_m=R,
                            n_patches=int(n_patches), t_ref_s=t, method=drum_method)
    gamma = d["total"] / (Rs + d["total"])
    pe = v * (0.5 * L) / (2.0 * drum.diffusivity)
    return HeatPartition(fraction_part=float(gamma), peclet=float(pe), slip_speed_m_s=v, patch_length_m=L,
                         duty=float(d["duty"]), dwell_time_s=float(d["dwell_s"]),
                         pass_period_s=float(d["period_s"]), t_ref_s=t, r_shoe_K_m2_W=float(Rs),
                         r_drum_track_K_m2_W=float(d["track"]), r_drum_flash_K_m2_W=float(d["flash"]),
                         drum_method=str(d["method"]), shoe_side=side)


# ---------------------------------------------------------------------------------------
# FE model
# ---------------------------------------------------------------------------------------
@dataclass
class HeatModel:
    """Assembled scalar-P2 operators of one part (module docstring): M, K, the Robin
    matrices H_face, H_bore, H_edge with their right sides, and the cyclic map P."""

    cm: ClutchMesh
    thickness: float
    material: ThermalMaterial
    env: ThermalEnvironment
    basis: Basis
    M: sp.csr_matrix
    K: sp.csr_matrix
    H: dict  # name -> (matrix, rhs vector) for 'face', 'bore', 'edge'
    P: sp.csr_matrix
    scale: float  # whole part / model (n_shoes_total / n_shoes_model for a sector)
    timings: dict = field(default_factory=dict)

    @property
    def N(self) -> int:
        return self.basis.N

    @property
    def A(self) -> sp.csr_matrix:
        return (self.K + sum(m for m, _ in self.H.values())).tocsr()

    @property
    def f(self) -> np.ndarray:
        return sum(b for _, b in self.H.values())

    def node_zone(self) -> dict[str, np.ndarray]:
        """Scalar P2 nodes of each subdomain (nodes of its elements)."""
        out = {}
        ed = self.basis.element_dofs
        for name, elems in (self.cm.mesh.subdomains or {}).items():
            out[name] = np.unique(ed[:, np.asarray(elems)])
        return out


def _cyclic_map(cm: ClutchMesh, basis: Basis) -> sp.csr_matrix:
    """T = P a: identity, except that every node of cut_b takes the value of its partner on
    cut_a (rotated by the sector angle); the full part gets the identity."""
    N = basis.N
    if cm.sector_angle is None:
        return sp.identity(N, format="csr")
    b = cm.mesh.boundaries or {}
    if "cut_a" not in b or "cut_b" not in b:
        raise MeshError(f"{cm.source}: a sector model needs boundary groups 'cut_a' and 'cut_b'")
    a_dofs = np.unique(basis.get_dofs(cm.boundary("cut_a")).all())
    b_dofs = np.unique(basis.get_dofs(cm.boundary("cut_b")).all())
    c, s = math.cos(cm.sector_angle), math.sin(cm.sector_angle)
    rot = np.array([[c, -s], [s, c]]) @ basis.doflocs[:, a_dofs]
    dist, j = cKDTree(basis.doflocs[:, b_dofs].T).query(rot.T)
    scale = float(np.max(np.abs(basis.doflocs)))
    if len(a_dofs) != len(b_dofs) or (len(dist) and dist.max() > 1e-8 * scale):
        raise MeshError(f"{cm.source}: the sector cut lines do not have matching nodes "
                        f"(worst mismatch {dist.max() if len(dist) else float('nan'):.3g} m)")
    slave, master = b_dofs[j], a_dofs
    keep = slave != master
    slave, master = slave[keep], master[keep]
    dep = np.zeros(N, dtype=bool)
    dep[slave] = True
    indep = np.nonzero(~dep)[0]
    col = -np.ones(N, dtype=np.int64)
    col[indep] = np.arange(len(indep))
    if np.any(col[master] < 0):
        raise MeshError(f"{cm.source}: a cut_a node is also a cut_b node of another pair")
    rows = np.concatenate([indep, slave])
    cols = np.concatenate([col[indep], col[master]])
    return sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(N, len(indep)))


def build_heat_model(cm: ClutchMesh, thickness: float, material: ThermalMaterial,
                     env: ThermalEnvironment, *, no_edge_nodes=None) -> HeatModel:
    """Assemble the operators of the plate heat equation on ``cm`` (module docstring).
    ``no_edge_nodes``: scalar nodes whose boundary facets never convect (the loaded contact
    patch); the cut lines of a sector and the bore never count as free edges."""
    t0 = time.perf_counter()
    h = _finite_positive("thickness", thickness, "an axial thickness > 0 m (<= 0.2 m)")
    if h > 0.2:
        raise ParameterError("thickness", thickness, "an axial thickness > 0 m (<= 0.2 m)")
    if not isinstance(material, ThermalMaterial):
        raise InputError(f"material must be a ThermalMaterial (got {type(material).__name__})")
    if not isinstance(env, ThermalEnvironment):
        raise InputError(f"env must be a ThermalEnvironment (got {type(env).__name__})")
    mesh = cm.mesh
    b = mesh.boundaries or {}
    if "bore" not in b:
        raise MeshError(f"{cm.source}: no 'bore' boundary group (the joint to the crankshaft)")
    basis = _scalar_basis(cm)
    k, rc = material.conductivity, material.density * material.specific_heat
    M = asm(BilinearForm(lambda u, v, w: rc * h * u * v), basis).tocsr()
    K = asm(BilinearForm(lambda u, v, w: k * h * dot(grad(u), grad(v))), basis).tocsr()
    hf, Ta = env.face_htc, env.ambient_temperature
    H = {"face": (asm(BilinearForm(lambda u, v, w: 2.0 * hf * u * v), basis).tocsr(),
                  asm(LinearForm(lambda v, w: 2.0 * hf * Ta * v), basis))}

    def robin(facets, coef, Tinf):
        if len(facets) == 0 or coef == 0.0:
            return sp.csr_matrix((basis.N, basis.N)), np.zeros(basis.N)
        fb = FacetBasis(mesh, ElementTriP2(), facets=np.asarray(facets), intorder=5)
        return (asm(BilinearForm(lambda u, v, w: coef * h * u * v), fb).tocsr(),
                asm(LinearForm(lambda v, w: coef * h * Tinf * v), fb))

    bore = cm.boundary("bore")
    H["bore"] = robin(bore, env.bore_conductance, env.crankshaft_temperature)
    exclude = set(bore.tolist())
    for cut in ("cut_a", "cut_b"):
        if cut in b:
            exclude |= set(np.asarray(b[cut]).tolist())
    edges = np.array([f for f in mesh.boundary_facets() if f not in exclude], dtype=np.int64)
    if no_edge_nodes is not None and len(edges):
        fd = basis.facet_dofs[0, edges]  # mid-edge node of each facet
        ends = mesh.facets[:, edges]
        hot = np.isin(fd, no_edge_nodes) | (np.isin(ends[0], no_edge_nodes) & np.isin(ends[1], no_edge_nodes))
        edges = edges[~hot]
    H["edge"] = robin(edges, env.edge_htc, Ta)
    P = _cyclic_map(cm, basis)
    scale = float(cm.sector_copies)
    return HeatModel(cm=cm, thickness=h, material=material, env=env, basis=basis, M=M, K=K, H=H,
                     P=P, scale=float(scale), timings={"assemble_s": time.perf_counter() - t0})


# ---------------------------------------------------------------------------------------
# time integration
# ---------------------------------------------------------------------------------------
@dataclass
class _Segment:
    duration: float
    steps: int
    heated: bool


@dataclass
class _Probe:
    name: str
    nodes: np.ndarray | None = None  # 'max' over these nodes
    weights: np.ndarray | None = None  # 'mean': weights @ T (full vector)


@dataclass
class _Run:
    times: np.ndarray
    probes: dict
    part_max: np.ndarray
    part_argmax: np.ndarray
    nodal_max: np.ndarray
    segment_end: list  # full fields at each segment end
    energy: dict
    final: np.ndarray
    solve_s: float
    factorisations: int


def _one_blas_thread():
    """Many tiny dot products per step: multi-threaded BLAS only adds contention (measured
    ~1000x slower on a shared 2-core machine), so the time loop runs on one BLAS thread."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # optional dependency
        import contextlib

        return contextlib.nullcontext()
    return threadpool_limits(1, user_api="blas")


def _integrate(model: HeatModel, T0: np.ndarray, Q: np.ndarray, segments: list[_Segment],
               probes: list[_Probe], *, homogeneous: bool = False) -> _Run:
    """Crank-Nicolson with two backward-Euler half steps at the start of every segment
    (module docstring).  ``homogeneous``: drop the ambient/crankshaft terms (the response to
    Q alone, for the FE side of the heat partition)."""
    with _one_blas_thread():
        return _integrate_loop(model, T0, Q, segments, probes, homogeneous)


def _integrate_loop(model, T0, Q, segments, probes, homogeneous) -> _Run:
    t0 = time.perf_counter()
    P = model.P
    Pt = P.T.tocsr()
    Mr = (Pt @ model.M @ P).tocsc()
    Ar = (Pt @ model.A @ P).tocsc()
    f = np.zeros(model.N) if homogeneous else model.f
    fr, Qr = Pt @ f, Pt @ Q
    # loss-rate row sums: loss_x(T) = hsum_x . T - c_x  (int of h (T - T_inf) over the boundary part)
    loss = {}
    for name, (Hm, rhs) in model.H.items():
        loss[name] = (np.asarray(Hm.sum(axis=0)).ravel(), 0.0 if homogeneous else float(rhs.sum()))
    msum = np.asarray(model.M.sum(axis=0)).ravel()
    cache = {}

    def factor(dt):
        key = round(dt, 15)
        if key not in cache:
            cache[key] = (factorize((Mr / dt + 0.5 * Ar).tocsc()), (Mr / dt - 0.5 * Ar).tocsr(), Mr / dt)
        return cache[key]

    # reduced initial vector: T0 is cyclic (equal on paired nodes), so the mean over each
    # column's nodes is the independent value
    a = (Pt @ T0) / np.asarray(P.sum(axis=0)).ravel()
    T = P @ a
    nsteps = sum(s.steps for s in segments)
    times = np.zeros(nsteps + 1)
    series = {p.name: np.zeros(nsteps + 1) for p in probes}
    pmax = np.zeros(nsteps + 1)
    parg = np.zeros(nsteps + 1, dtype=np.int64)
    nodal_max = T.copy()

    def record(k, T):
        for p in probes:
            series[p.name][k] = T[p.nodes].max() if p.nodes is not None else p.weights @ T
        j = int(np.argmax(T))
        pmax[k], parg[k] = T[j], j

    record(0, T)
    E = {"input_J": 0.0, "face_J": 0.0, "bore_J": 0.0, "edge_J": 0.0}
    stored0 = msum @ T

    def rate(T):
        return {n: hs @ T - c for n, (hs, c) in loss.items()}

    ends = []
    k = 0
    tnow = 0.0
    for seg in segments:
        dt = seg.duration / seg.steps
        F, B, Mdt = factor(dt)
        rhs = fr + (Qr if seg.heated else 0.0)
        qin = float(Q.sum()) if seg.heated else 0.0
        for i in range(seg.steps):
            if i == 0:  # two backward-Euler half steps (Rannacher start)
                for _ in range(2):
                    a = F.solve(Mdt @ a + 0.5 * rhs)
                    T = P @ a
                    r = rate(T)
                    for n in r:
                        E[f"{n}_J"] += 0.5 * dt * r[n]
            else:
                r0 = rate(T)
                a = F.solve(B @ a + rhs)
                T = P @ a
                r = rate(T)
                for n in r:
                    E[f"{n}_J"] += 0.5 * dt * (r0[n] + r[n])
            E["input_J"] += dt * qin
            tnow += dt
            k += 1
            times[k] = tnow
            record(k, T)
            np.maximum(nodal_max, T, out=nodal_max)
        ends.append(T.copy())
    E["stored_J"] = float(msum @ T - stored0)
    return _Run(times=times, probes=series, part_max=pmax, part_argmax=parg, nodal_max=nodal_max,
                segment_end=ends, energy=E, final=T, solve_s=time.perf_counter() - t0,
                factorisations=len(cache))


def _steady(model: HeatModel) -> np.ndarray:
    """Steady state without friction: A T = f (None if nothing removes heat)."""
    A = model.A
    if not any(m.nnz and abs(m).sum() > 0 for m, _ in model.H.values()):
        return None
    P = model.P
    Pt = P.T.tocsr()
    F = factorize((Pt @ A @ P).tocsc())
    return P @ F.solve(Pt @ model.f)


# ---------------------------------------------------------------------------------------
# scenario
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SlipHeatResult:
    """What :func:`slip_heat` returns.  Temperatures in C, energies in J for the whole part;
    ``peak_location`` / ``flexure_peak_location`` name the zone, the flexure end and the
    boundary of the hottest points (e.g. concept 2's 'in-shoe flexure').

    Probes (time series over ``times_s``):
    * ``flexure_C``: the hottest node of all ``flexure_<i>`` zones at each time (None if the
      mesh has no flexure zone);
    * ``shoe_face_C``: the hottest node of the ``contact`` surface (the shoes' friction face);
    * ``hub_C``: the area-weighted mean temperature of the ``hub`` zone (of the bore edge if
      the mesh has no hub zone: see ``probe_definitions``);
    * ``part_max_C``: the hottest node anywhere;
    * ``part_mean_C``: the area-weighted mean temperature of the part (its heat content).
    """

    times_s: np.ndarray
    flexure_C: np.ndarray | None
    shoe_face_C: np.ndarray
    hub_C: np.ndarray
    part_max_C: np.ndarray
    probe_definitions: dict
    peak_temperature_C: float
    peak_time_s: float
    peak_xy_m: tuple[float, float]
    peak_zone: str
    peak_location: str
    flexure_peak_C: float | None
    flexure_peak_time_s: float | None
    flexure_peak_xy_m: tuple[float, float] | None
    flexure_peak_location: str | None
    limit_temperature_C: float
    time_to_limit_s: float | None
    yield_ratio_at_limit: float
    yield_strength_at_limit_Pa: float
    yield_strength_at_limit_bounds_Pa: tuple[float, float]
    yield_strength_at_flexure_peak_Pa: float | None
    slip_rpm: float
    slip_power_W: float
    friction_work_J: float
    heat_into_part_J: float
    partition: HeatPartition
    energy: dict
    cycles: list
    initial_field_C: np.ndarray
    final_field_C: np.ndarray
    nodal_max_C: np.ndarray
    ambient_temperature_C: float
    initial_state: str
    dt_s: float
    n_steps: int
    time_error_estimate_K: float | None
    scenario: dict
    timings: dict
    assumed: tuple[str, ...]
    #: area-weighted mean temperature of the part over ``times_s`` (its heat content): what
    #: a thermometer on the whole clutch would read after the heat has spread
    part_mean_C: np.ndarray | None = None

    @property
    def seconds(self) -> float:
        return float(self.scenario["seconds"])

    def to_json(self) -> dict:
        def r(x):
            return None if x is None else [float(v) for v in x]

        return {
            "seconds": self.seconds, "cycles": int(self.scenario["cycles"]), "pause_s": float(self.scenario["pause"]),
            "slip_rpm": self.slip_rpm, "slip_power_W": self.slip_power_W, "friction_work_J": self.friction_work_J,
            "heat_into_part_J": self.heat_into_part_J, "heat_fraction_part": self.partition.fraction_part,
            "flexure_temperature_C": self.flexure_peak_C, "flexure_peak_time_s": self.flexure_peak_time_s,
            "peak_temperature_C": self.peak_temperature_C, "peak_time_s": self.peak_time_s,
            "peak_xy_m": list(self.peak_xy_m), "peak_zone": self.peak_zone, "peak_location": self.peak_location,
            "flexure_peak_xy_m": None if self.flexure_peak_xy_m is None else list(self.flexure_peak_xy_m),
            "flexure_peak_location": self.flexure_peak_location,
            "ambient_temperature_C": self.ambient_temperature_C,
            "limit_temperature_C": self.limit_temperature_C, "time_to_limit_s": self.time_to_limit_s,
            "yield_strength_at_limit_Pa": self.yield_strength_at_limit_Pa,
            "yield_strength_at_limit_bounds_Pa": list(self.yield_strength_at_limit_bounds_Pa),
            "yield_strength_at_flexure_peak_Pa": self.yield_strength_at_flexure_peak_Pa,
            "energy_J": dict(self.energy), "partition": self.partition.to_json(), "cycles_table": self.cycles,
            "dt_s": self.dt_s, "n_steps": self.n_steps, "time_error_estimate_K": self.time_error_estimate_K,
            "initial_state": self.initial_state, "probe_definitions": dict(self.probe_definitions),
            "series": {"times_s": r(self.times_s), "flexure_C": r(self.flexure_C),
                       "shoe_face_C": r(self.shoe_face_C), "hub_C": r(self.hub_C),
                       "part_mean_C": r(self.part_mean_C),
                       "part_max_C": r(self.part_max_C)},
            "timings_s": dict(self.timings), "assumed": list(self.assumed),
        }


ASSUMED = (
    "thermal data of the part: k, c constant at room-temperature values (51CrV4/6150 handbook)",
    "limit temperature = tempering temperature of ~45 HRC 51CrV4, low end of 400-500 C",
    "hot yield strength: EN 1993-1-2 Table 3.1 reduction factors (carbon steel)",
    "face convection coefficient (rotating disc estimate, Cobb & Saunders), no radiation",
    "bore joint conductance and crankshaft temperature",
    "drum: steel rim of the given wall thickness, outer face adiabatic; 1-D conduction normal to the drum",
    "heat partition from equal mean patch temperatures at the end of one slip event (Blok), kept constant",
    "temperature uniform through the axial thickness (plate model)",
)


def _first_crossing(t: np.ndarray, y: np.ndarray, level: float) -> float | None:
    above = np.nonzero(y >= level)[0]
    if len(above) == 0:
        return None
    k = int(above[0])
    if k == 0:
        return float(t[0])
    y0, y1 = y[k - 1], y[k]
    return float(t[k - 1] + (level - y0) / (y1 - y0) * (t[k] - t[k - 1]))


def _zone_of_node(cm: ClutchMesh, basis: Basis, node: int) -> str:
    elems = np.nonzero((basis.element_dofs == node).any(axis=0))[0]
    sub = cm.mesh.subdomains or {}
    names = [n for n, e in sub.items() if n != "solid" and np.isin(elems, e).any()]
    for pref in ("flexure", "shoe", "hub"):
        hit = sorted(n for n in names if n.startswith(pref))
        if hit:
            return hit[0]
    return names[0] if names else "part"


def _describe(cm: ClutchMesh, basis: Basis, node: int) -> str:
    """Zone, position and boundary of a P2 node (:func:`clutchfem.durability.fatigue.name_location`
    with an element of the node's zone that holds it)."""
    from ..fatigue import name_location

    elems = np.nonzero((basis.element_dofs == node).any(axis=0))[0]
    zone = _zone_of_node(cm, basis, node)
    sub = cm.mesh.subdomains or {}
    if zone in sub:
        elems = elems[np.isin(elems, sub[zone])]
    return name_location(cm, basis.doflocs[:, node], element=int(elems[0])).description


def slip_heat(cm: ClutchMesh, thickness: float | None, material: ThermalMaterial | None,
              load: SlipHeatLoad, *, seconds: float | None = None, cycles: int | None = None,
              pause: float | None = None, scenario: SlipScenario | None = None,
              env: ThermalEnvironment | None = None, drum: DrumThermal | None = None,
              heat_fraction: float | None = None,
              shoe_side: Literal["fe", "semi_infinite"] = "fe") -> SlipHeatResult:
    """Repeated slip events (``cycles`` x [``seconds`` of slip, ``pause`` of cooling]) with the
    friction heat of ``load`` entering the part ``cm`` (thickness [m]; None: the mesh's).

    ``heat_fraction``: the part's share gamma of the friction heat (0: no heat, a cooling
    what-if), or None to compute it
    with :func:`heat_partition` (``shoe_side`` 'fe': the part's own FE response at the end
    of one slip event, or 'semi_infinite').  ``seconds``/``cycles``/``pause`` override the
    fields of ``scenario`` (:class:`SlipScenario`).  See the module docstring for the model."""
    timings = {}
    t_start = time.perf_counter()
    material = material or ThermalMaterial()
    env = env or ThermalEnvironment()
    drum = drum or DrumThermal()
    if not isinstance(load, SlipHeatLoad):
        raise InputError(f"load must be a SlipHeatLoad (got {type(load).__name__})")
    if not isinstance(drum, DrumThermal):
        raise InputError(f"drum must be a DrumThermal (got {type(drum).__name__})")
    sc = scenario or SlipScenario()
    over = {k: v for k, v in (("seconds", seconds), ("cycles", cycles), ("pause", pause)) if v is not None}
    if over:
        sc = sc.replace(**over)
    if shoe_side not in ("fe", "semi_infinite"):
        raise ParameterError("shoe_side", shoe_side, "one of 'fe', 'semi_infinite'")
    if heat_fraction is not None:
        heat_fraction = _finite_positive("heat_fraction", heat_fraction, "a share of the friction heat in [0, 1]",
                                         zero_ok=True)
        if heat_fraction > 1.0:
            raise ParameterError("heat_fraction", heat_fraction, "a share of the friction heat in [0, 1]")
    h = thickness if thickness is not None else cm.thickness
    if h is None:
        raise ParameterError("thickness", None, "an axial thickness > 0 m (the mesh carries none)")
    basis = _scalar_basis(cm)
    N = basis.N
    if load.node_index.max() >= N:
        raise ParameterError("node_index", int(load.node_index.max()), f"a node id of this mesh, 0 <= id < {N}")
    loaded = load.node_index[load.lam_N > 0]
    model = build_heat_model(cm, h, material, env, no_edge_nodes=loaded)
    timings["assemble_s"] = model.timings["assemble_s"]
    mesh = cm.mesh
    b = mesh.boundaries or {}
    sub = mesh.subdomains or {}

    # friction power per node (gamma = 1), patch geometry
    Q1 = np.zeros(N)
    np.add.at(Q1, load.node_index, load.nodal_power_W)
    contact_f = cm.boundary("contact") if "contact" in b else mesh.boundary_facets()
    fb = FacetBasis(mesh, ElementTriP2(), facets=contact_f, intorder=5)
    trib = asm(LinearForm(lambda v, w: v), fb)
    L_model = float(trib[loaded].sum())
    if not L_model > 0:
        raise InputError("slip_heat: the loaded nodes do not lie on the contact surface (zero patch length)")
    n_model = cm.n_shoes_model if cm.sector_angle is not None else max(cm.n_shoes_total, 1)
    n_total = max(cm.n_shoes_total, 1)
    L_patch = L_model / n_model
    P_model = float(Q1.sum())

    # probes
    zones = model.node_zone()
    flex_names = sorted(n for n in sub if n.startswith("flexure"))
    flex_nodes = np.unique(np.concatenate([zones[n] for n in flex_names])) if flex_names else None
    face_nodes = np.unique(basis.get_dofs(contact_f).all())
    probes = [_Probe("shoe_face", nodes=face_nodes),
              _Probe("patch_mean", weights=Q1 / P_model)]
    defs = {"shoe_face_C": "hottest P2 node of the 'contact' surface",
            "part_max_C": "hottest P2 node of the part"}
    if flex_nodes is not None:
        probes.append(_Probe("flexure", nodes=flex_nodes))
        defs["flexure_C"] = "hottest P2 node of the zones " + ", ".join(flex_names)
    if "hub" in sub:
        wh = asm(LinearForm(lambda v, w: v), Basis(mesh, ElementTriP2(), elements=np.asarray(sub["hub"]), intorder=4))
        defs["hub_C"] = "area-weighted mean temperature of the 'hub' zone"
    else:
        wh = asm(LinearForm(lambda v, w: v), FacetBasis(mesh, ElementTriP2(), facets=cm.boundary("bore"), intorder=5))
        defs["hub_C"] = "length-weighted mean temperature of the bore edge (the mesh has no 'hub' zone)"
    probes.append(_Probe("hub", weights=wh / wh.sum()))
    wa = asm(LinearForm(lambda v, w: v), basis)  # int phi_i dA: area (= mass) weights
    probes.append(_Probe("part_mean", weights=wa / wa.sum()))
    defs["part_mean_C"] = "area-weighted mean temperature of the part (its heat content / (rho c h A))"

    # steps: equal steps per slip event (even, for the 2 dt error estimate), pause likewise
    n_slip, n_pause = sc.steps()
    dt = sc.seconds / n_slip

    def segments(factor=1):
        segs = []
        for _ in range(sc.cycles):
            segs.append(_Segment(sc.seconds, n_slip // factor, True))
            if n_pause:
                segs.append(_Segment(sc.pause, n_pause // factor, False))
        return segs

    # heat partition
    t0 = time.perf_counter()
    if heat_fraction is None:
        Rs = None
        if shoe_side == "fe":
            pre = _integrate(model, np.zeros(N), Q1, [_Segment(sc.seconds, n_slip, True)],
                             [_Probe("patch_mean", weights=Q1 / P_model)], homogeneous=True)
            q_mean = P_model / (L_model * model.thickness)
            Rs = float(pre.probes["patch_mean"][-1]) / q_mean
        part = heat_partition(material, drum, slip_speed_m_s=load.slip_speed_m_s, patch_length_m=L_patch,
                              drum_radius_m=load.drum_radius_m, n_patches=n_total, t_ref_s=sc.seconds,
                              shoe_response_K_m2_W=Rs)
        gamma = part.fraction_part
    else:
        gamma = heat_fraction
        part = HeatPartition(fraction_part=gamma, peclet=float("nan"), slip_speed_m_s=load.slip_speed_m_s,
                             patch_length_m=L_patch, duty=float("nan"), dwell_time_s=float("nan"),
                             pass_period_s=float("nan"), t_ref_s=sc.seconds, r_shoe_K_m2_W=float("nan"),
                             r_drum_track_K_m2_W=float("nan"), r_drum_flash_K_m2_W=float("nan"),
                             drum_method="given", shoe_side="given")
    timings["partition_s"] = time.perf_counter() - t0

    # initial field
    initial = env.initial
    T0 = None
    if initial == "steady":
        T0 = _steady(model)
        if T0 is None:
            initial = "ambient (no heat path out of the part: no steady state)"
    if T0 is None:
        T0 = np.full(N, env.initial_temperature if initial == "uniform" else env.ambient_temperature)

    Q = gamma * Q1
    run = _integrate(model, T0, Q, segments(), probes)
    timings["solve_s"] = run.solve_s
    err = None
    if sc.error_estimate:
        coarse = _integrate(model, T0, Q, segments(2), probes)
        timings["error_estimate_s"] = coarse.solve_s
        diffs = [np.max(np.abs(run.part_max[::2] - coarse.part_max))]
        for p in probes:
            diffs.append(np.max(np.abs(run.probes[p.name][::2] - coarse.probes[p.name])))
        err = float(max(diffs) / 3.0)

    # answers
    t = run.times
    s = model.scale
    E = {"input_J": run.energy["input_J"] * s, "stored_J": run.energy["stored_J"] * s,
         "lost_faces_J": run.energy["face_J"] * s, "lost_bore_J": run.energy["bore_J"] * s,
         "lost_edges_J": run.energy["edge_J"] * s}
    lost = E["lost_faces_J"] + E["lost_bore_J"] + E["lost_edges_J"]
    # the initial state may carry a steady heat flow (crankshaft -> faces) that the losses
    # include; the balance is stored = input - losses either way
    E["balance_error_J"] = E["stored_J"] - (E["input_J"] - lost)
    E["balance_error_rel"] = abs(E["balance_error_J"]) / max(E["input_J"], abs(E["stored_J"]), abs(lost), 1e-300)
    kpk = int(np.argmax(run.part_max))
    node = int(run.part_argmax[kpk])
    xy = basis.doflocs[:, node]
    flex = run.probes.get("flexure")
    fpk = ftime = fxy = fn = None
    if flex is not None:
        kf = int(np.argmax(flex))
        fpk, ftime = float(flex[kf]), float(t[kf])
        # where: re-run is not needed: the flexure maximum at its peak time is the largest
        # nodal maximum of the flexure over the run
        fn = flex_nodes[int(np.argmax(run.nodal_max[flex_nodes]))]
        fxy = (float(basis.doflocs[0, fn]), float(basis.doflocs[1, fn]))
    lim = material.limit_temperature
    cyc = []
    seg_ends = run.segment_end
    k_end = 0
    for c in range(sc.cycles):
        row = {"cycle": c + 1}
        T_slip = seg_ends[k_end]
        k_end += 1
        row["end_of_slip_part_max_C"] = float(T_slip.max())
        if flex_nodes is not None:
            row["end_of_slip_flexure_C"] = float(T_slip[flex_nodes].max())
        if n_pause:
            T_p = seg_ends[k_end]
            k_end += 1
            row["end_of_pause_part_max_C"] = float(T_p.max())
            if flex_nodes is not None:
                row["end_of_pause_flexure_C"] = float(T_p[flex_nodes].max())
        cyc.append(row)
    ratio = material.yield_ratio(lim)
    bounds = (hot_yield_ratio(lim, "proportional") * material.yield_strength,
              hot_yield_ratio(lim, "effective") * material.yield_strength)
    timings["total_s"] = time.perf_counter() - t_start
    return SlipHeatResult(
        times_s=t, flexure_C=flex, shoe_face_C=run.probes["shoe_face"], hub_C=run.probes["hub"],
        part_mean_C=run.probes["part_mean"],
        part_max_C=run.part_max, probe_definitions=defs,
        peak_temperature_C=float(run.part_max[kpk]), peak_time_s=float(t[kpk]),
        peak_xy_m=(float(xy[0]), float(xy[1])), peak_zone=_zone_of_node(cm, basis, node),
        peak_location=_describe(cm, basis, node),
        flexure_peak_C=fpk, flexure_peak_time_s=ftime, flexure_peak_xy_m=fxy,
        flexure_peak_location=None if fn is None else _describe(cm, basis, fn),
        limit_temperature_C=float(lim),
        time_to_limit_s=None if flex is None else _first_crossing(t, flex, lim),
        yield_ratio_at_limit=float(ratio), yield_strength_at_limit_Pa=float(ratio * material.yield_strength),
        yield_strength_at_limit_bounds_Pa=(float(bounds[0]), float(bounds[1])),
        yield_strength_at_flexure_peak_Pa=(None if fpk is None
                                           else float(material.yield_ratio(fpk) * material.yield_strength)),
        slip_rpm=float(load.omega_rad_s * 60.0 / (2.0 * math.pi)), slip_power_W=P_model * s,
        friction_work_J=P_model * s * sc.seconds * sc.cycles, heat_into_part_J=E["input_J"],
        partition=part, energy=E, cycles=cyc, initial_field_C=T0, final_field_C=run.final, nodal_max_C=run.nodal_max,
        ambient_temperature_C=float(env.ambient_temperature), initial_state=initial, dt_s=float(dt),
        n_steps=int(len(t) - 1), time_error_estimate_K=err, scenario=sc.model_dump(), timings=timings,
        assumed=ASSUMED)


# ---------------------------------------------------------------------------------------
# output
# ---------------------------------------------------------------------------------------
def _p2_cells(cm: ClutchMesh) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3), cells (ne, 6)): every scalar P2 node once, VTK triangle6 order (3
    corners, mid-edges 01, 12, 20: scikit-fem's order too)."""
    b = _scalar_basis(cm)
    xy = b.doflocs
    return np.column_stack([xy.T, np.zeros(xy.shape[1])]), b.element_dofs.T.copy()


def write_vtu(cm: ClutchMesh, result: SlipHeatResult, path: str | Path) -> Path:
    """The final temperature field and each node's maximum over the run [C] as a .vtu on
    the quadratic (triangle6) mesh (opens in ParaView)."""
    import meshio

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    pts, cells = _p2_cells(cm)
    if len(pts) != len(result.final_field_C):
        raise InputError(f"write_vtu: the result has {len(result.final_field_C)} nodes, the mesh {len(pts)}")
    meshio.Mesh(pts, [("triangle6", cells)],
                point_data={"temperature_C": np.asarray(result.final_field_C),
                            "max_temperature_C": np.asarray(result.nodal_max_C)}).write(path)
    return path


def render_png(cm: ClutchMesh, result: SlipHeatResult, path: str | Path, *, title: str = "",
               full_part: bool = True) -> Path:
    """Picture (matplotlib, headless): each node's maximum temperature over the run (left;
    the whole clutch for a sector model when ``full_part``) and the probe time series
    (right)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.tri import Triangulation

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    pts, cells = _p2_cells(cm)
    sub = np.vstack([cells[:, [0, 3, 5]], cells[:, [3, 1, 4]], cells[:, [5, 4, 2]], cells[:, [3, 4, 5]]])
    val = np.asarray(result.nodal_max_C)
    copies = 1
    if full_part and cm.sector_angle is not None:
        copies = cm.sector_copies
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 5.2))
    vmin, vmax = float(val.min()), float(val.max())
    for c in range(copies):
        a = c * (cm.sector_angle or 0.0)
        x = math.cos(a) * pts[:, 0] - math.sin(a) * pts[:, 1]
        y = math.sin(a) * pts[:, 0] + math.cos(a) * pts[:, 1]
        tp = ax.tripcolor(Triangulation(x * 1e3, y * 1e3, sub), val, shading="gouraud", cmap="inferno",
                          vmin=vmin, vmax=vmax)
    fig.colorbar(tp, ax=ax, label="maximum temperature over the run [C]")
    ax.plot(result.peak_xy_m[0] * 1e3, result.peak_xy_m[1] * 1e3, "c*", ms=12, label="peak")
    if result.flexure_peak_xy_m is not None:
        ax.plot(result.flexure_peak_xy_m[0] * 1e3, result.flexure_peak_xy_m[1] * 1e3, "co", mfc="none",
                ms=10, label="flexure peak")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(loc="lower left", fontsize=8)
    t = result.times_s
    if result.flexure_C is not None:
        ax2.plot(t, result.flexure_C, label="flexure (hottest point)")
    ax2.plot(t, result.shoe_face_C, label="shoe face (hottest point)")
    ax2.plot(t, result.hub_C, label="hub (mean)")
    if result.part_mean_C is not None:
        ax2.plot(t, result.part_mean_C, "k:", label="whole part (mean)")
    ax2.axhline(result.limit_temperature_C, color="r", ls="--", lw=1, label="limit temperature")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("temperature [C]")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.suptitle(title or f"slip heat: {result.slip_power_W:.0f} W at {result.slip_rpm:.0f} rpm, "
                          f"{result.partition.fraction_part:.0%} into the part")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
