"""Thermal parameter sets of the slip-heat model: the part's material, the drum, the
boundary conditions, the slip scenario, and the hot yield strength of steel.

ASSUMED values (all configurable, defaults for 51CrV4 in a steel drum)
---------------------------------------------------------------------
* part: k = 46.6 W/(m K), c = 460 J/(kg K), rho = 7850 kg/m^3: room-temperature handbook
  values of low-alloy Cr-V spring steel (AISI 6150 ~ 51CrV4; ASM Handbook vol. 1 / MatWeb
  data for 6150).  Constant properties (k falls and c rises with temperature: at 400 C
  roughly -15 % and +20 %; not modelled).
* limit temperature 400 C: the low end of the tempering range (~400-500 C after an oil
  quench from ~850 C) that gives ~45 HRC in 51CrV4 (tempering charts of 1.8159 / EN 10089
  spring steels); above it the hardness is lost for good.  Spring relaxation starts lower
  (~200-250 C): set ``limit_temperature`` to study it.
* hot yield strength: EN 1993-1-2 (Eurocode 3 fire design) Table 3.1 reduction factors for
  carbon steel, ``k_p`` (proportional limit; conservative, default) or ``k_y`` (effective
  yield at 2 % strain).  The 0.2 % proof stress of a hardened steel at temperature lies
  between the two: both are reported.
* faces: h_f = 50 W/(m^2 K) per face (a free disc of 34 mm at 7000 rpm: ~63 W/(m^2 K),
  Cobb & Saunders 1956; the clutch runs enclosed in its drum).  Radiation neglected
  (~10 W/(m^2 K) at 400 C: conservative).
* bore: joint conductance h_b = 3000 W/(m^2 K) (threaded steel-steel joint, 1e3-1e4:
  Incropera Table 3.1 / Madhusudana 1996) to a crankshaft at T_crank = 60 C (engine warm);
  ambient 25 C; free edges h_e = 0 (conservative); initial state: steady state of the
  idling clutch (no friction).
* drum: steel (same k, c, rho), rim wall w = 2.0 mm, outer face adiabatic.

The derivations behind these numbers: ``docs/durability_theory.md``.  Units: SI,
temperatures in deg C.
"""

from __future__ import annotations

import math
from typing import ClassVar, Literal

import numpy as np
from pydantic import Field

from ..core import ParameterError, ParamSet, choice, param

__all__ = ["ASSUMED", "HOT_YIELD_TABLE", "MAX_TIME_STEPS", "DrumThermal", "SlipScenario", "ThermalEnvironment",
           "ThermalMaterial", "finite_positive", "hot_yield_ratio"]

#: Time steps of one run (every event and pause; the 2 dt error estimate adds half, the
#: partition pre-run one event) above which a scenario is refused: ~0.1 ms per step on a
#: 5k-node sector, so 2e5 steps are tens of seconds, 1e8 would be hours
MAX_TIME_STEPS = 200_000

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
class _Conducting(ParamSet):
    """A solid with ``conductivity`` k, ``density`` rho and ``specific_heat`` c (declared by
    each subclass with its own defaults): its diffusivity and effusivity, one formula each
    for the part and the drum."""

    @property
    def diffusivity(self) -> float:
        """kappa = k / (rho c) [m^2/s]."""
        return self.conductivity / (self.density * self.specific_heat)

    @property
    def effusivity(self) -> float:
        """e = sqrt(k rho c) [W s^0.5 / (m^2 K)]."""
        return math.sqrt(self.conductivity * self.density * self.specific_heat)


class ThermalMaterial(_Conducting):
    """Thermal data of the part (defaults: hardened 51CrV4, ASSUMED, see module docstring).

    Parameters
    ----------
    conductivity, specific_heat, density : float or str
        k [W/(m K)], c [J/(kg K)], rho [kg/m^3].
    limit_temperature : float or str
        Above it the hardness is lost (tempering) [C]; ``"673.15K"`` is read as 400 C.
    yield_strength : float or str
        Room-temperature Rp0.2 [Pa].
    phase_change_temperature, melting_temperature : float or str
        Where the transient stops [C].
    hot_yield_basis : {"proportional", "effective"}
        EN 1993-1-2's k_p (conservative) or k_y for the hot yield strength.

    Examples
    --------
    >>> import clutchfem as cf
    >>> m = cf.ThermalMaterial(limit_temperature="673.15K")
    >>> m.limit_temperature, m.yield_ratio(20.0), m.yield_ratio(300.0)   # hot yield / cold yield
    (400.0, 1.0, 0.613)
    """

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
    phase_change_temperature: float = param(727.0, "C", 100.0, 2000.0,
                                            "phase change (steel: A1, austenite starts; ASSUMED): the slip-heat "
                                            "transient is stopped there (thermal.validity)", "T_A1")
    melting_temperature: float = param(1420.0, "C", 100.0, 3500.0,
                                       "melting (solidus; low-alloy steel ~1420 C, ASSUMED)", "T_m")
    hot_yield_basis: Literal["proportional", "effective"] = choice(
        "proportional", "EN 1993-1-2 reduction factor used for the hot yield strength: k_p (conservative) or k_y")

    def yield_ratio(self, T_C) -> float:
        """Hot yield strength / room-temperature yield strength at T_C (see HOT_YIELD_TABLE)."""
        return hot_yield_ratio(T_C, self.hot_yield_basis)


class DrumThermal(_Conducting):
    """The drum as seen by the heat partition: a rim wall heated on its inner face, outer
    face adiabatic (ASSUMED, conservative for the part).  Defaults: steel, 2 mm (ASSUMED).

    Parameters
    ----------
    conductivity, specific_heat, density : float or str
        The drum's k [W/(m K)], c [J/(kg K)], rho [kg/m^3].
    wall_thickness : float or str
        Its rim wall [m].

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.DrumThermal(wall_thickness="3mm")
    >>> d.wall_thickness, round(d.effusivity)             # sqrt(k rho c) [W s^0.5 / (m^2 K)]
    (0.003, 12972)
    """

    context: ClassVar[str] = "drum (thermal)"
    conductivity: float = param(46.6, "W/(m K)", 0.1, 500.0, "drum conductivity (ASSUMED steel)", "k_d")
    specific_heat: float = param(460.0, "J/(kg K)", 50.0, 5000.0, "drum specific heat (ASSUMED steel)", "c_d")
    density: float = param(7850.0, "kg/m^3", 100.0, 25000.0, "drum density (ASSUMED steel)", "rho_d")
    wall_thickness: float = param(2.0e-3, "m", 0.2e-3, 50e-3, "drum rim wall thickness (ASSUMED)", "w_d")


class ThermalEnvironment(ParamSet):
    """Boundary conditions and initial state (all ASSUMED, see module docstring).

    Parameters
    ----------
    ambient_temperature, crankshaft_temperature : float or str
        Air, and the crankshaft at the bore [C].
    face_htc, edge_htc : float or str
        Convection of each axial face and of the free edges [W/(m^2 K)].
    bore_conductance : float or str
        The bore joint to the crankshaft [W/(m^2 K)].
    initial : {"steady", "ambient", "uniform"}
        Initial field: the idling clutch's steady state, ambient, or ``initial_temperature``.
    initial_temperature : float or str
        [C], with ``initial="uniform"``.

    Examples
    --------
    >>> import clutchfem as cf
    >>> e = cf.ThermalEnvironment(face_htc="80 W/m2K", initial="ambient")
    >>> e.face_htc, e.initial, e.bore_conductance
    (80.0, 'ambient', 3000.0)
    """

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
    """The slip test: events of ``seconds`` separated by cooling pauses of ``pause``.

    Parameters
    ----------
    seconds : float or str
        One slip event (default 10 s).
    cycles : int
        Events (default 1).
    pause : float or str
        Cooling pause after each event (idle, no friction).
    steps_per_event : int
        Time steps per event.
    error_estimate : bool
        Estimate the time-stepping error (a run with half the steps).

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.SlipScenario(seconds="5s", cycles=3, pause="20s").pause
    20.0
    """

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


#: the assumptions of every run, listed in its result
ASSUMED = (
    "thermal data of the part: k, c constant at room-temperature values (51CrV4/6150 handbook)",
    "limit temperature = tempering temperature of ~45 HRC 51CrV4, low end of 400-500 C",
    "phase change 727 C (A1) and melting 1420 C (solidus) of low-alloy steel: the transient stops at the first",
    "hot yield strength: EN 1993-1-2 Table 3.1 reduction factors (carbon steel)",
    "face convection coefficient (rotating disc estimate, Cobb & Saunders), no radiation",
    "bore joint conductance and crankshaft temperature",
    "drum: steel rim of the given wall thickness, outer face adiabatic; 1-D conduction normal to the drum",
    "heat partition from equal mean patch temperatures at the end of one slip event (Blok), kept constant",
    "temperature uniform through the axial thickness (plate model)",
)


def finite_positive(name: str, value, allowed: str, *, zero_ok: bool = False) -> float:
    """``value`` as a finite float > 0 (>= 0 with ``zero_ok``); ParameterError naming ``name``
    and what is ``allowed`` otherwise."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, allowed) from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not zero_ok):
        raise ParameterError(name, value, allowed)
    return v
