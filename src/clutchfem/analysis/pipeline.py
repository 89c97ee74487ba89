"""From a design to the answers a clutch designer asks for: a sequence of small steps.

:func:`analyze` runs, on one :class:`~clutchfem.design.Design` (one FE model, one
factorisation for everything below):

1. :func:`slip_step`: the slip speed with the drum held, from the *exact* FE torque (crossings
   bracketed on a fixed internal grid and refined by bisection with FE solves: the answer
   does not depend on the speeds the user asked to tabulate);
2. :func:`fe_sweep`: the FE speed sweep with stresses on the output speeds, to which the
   engagement and slip speeds, the rpm of maximum engine torque and the engine's maximum
   speed are added (every answer is read at a solved speed, never interpolated);
3. :func:`engagement_step`: static engagement (FE, closed form) and with the 2-stroke ripple;
4. :func:`character_step`: plus/minus character per shoe (normal force with and without
   friction at the rpm of maximum engine torque);
5. :func:`mu_sensitivity_step`: torque and slip speed at mu x 0.7 and x 1.3;
6. :func:`coupling_step`: the analytical plus/minus shoe model fitted to the FE (below);
7. :func:`stress_step`: peak stress and safety factor at the engine's maximum speed;
8. :func:`requirements_step`: engagement > a x idle, slip < b x rpm of max engine torque;
9. :func:`whirl_step`: the crankshaft's first critical speed with this clutch on its
   overhang (:mod:`clutchfem.clutch.crankshaft`) against the engine's maximum speed;
10. :func:`fatigue_step`: the fatigue safety factor (Goodman, Miner) at the worst point,
    named, under start-stop and running-revolution cycles built from solved states
    (:mod:`clutchfem.durability.cycles`, :mod:`clutchfem.durability.fatigue`).
11. :func:`error_step`: the error of engagement, slip, torque and peak stress
    (:mod:`clutchfem.errorest`: a mesh twice as fine, measured model-form terms).

Each returns a small frozen result; :class:`Analysis` collects the answers the report
renders (:mod:`clutchfem.report`).

FE -> analytical coupling (thesis eqs 1-8 via :mod:`clutchfem.clutch.shoe`):

* shoe mass m and centre-of-mass radius R_Tp: OCC-exact mass properties of the shoe zone;
* effective spring force F_f = m R_Tp w_e^2 from the FE engagement speed w_e (eq 1 inverted:
  the FE flexure is reduced to the force it exerts at engagement);
* pivot distance A and lever L *from the geometry*: the pivot is the flexure's compliant
  centre reported by the concept; L is the distance from the pivot to the radial line of
  action of the centrifugal apply force through the shoe's centre of mass;
* lining angles phi_1, phi_2 measured from the pivot ray: the *nominal* full shoe arc (what
  the thesis did) or the arc in contact in the FE solution at each speed.

Three torque curves come out side by side: FE direct (sum of mu * contact force * R_d),
analytical with the FE contact arc, analytical with the nominal arc.  The difference between
the last two is the thesis's error mechanism (contact on a fraction of the arc).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..clutch import EngineCurve, ShoeGeometry, arc_torque, first_slip_rpm, holds, shoe_torque, torque_crossings
from ..clutch import ripple as ripple_mod
from ..core import ClutchfemError, ParameterError, rpm_to_rad_s, wrap_angle

#: Defaults of the requirement factors.  The thesis keeps a and b confidential: ASSUMED.
DEFAULT_A = 1.3
DEFAULT_B = 1.0
#: Idle speed used when the engine curve carries none (typical saw idle): ASSUMED.
DEFAULT_IDLE_RPM = 2700.0
#: normal force with / without friction above which a plus shoe is called strongly
#: self-energising (near self-locking) in the warnings
SELF_ENERGISING_WARN = 1.5
#: required margin of the first crankshaft critical speed over the engine's maximum speed
#: (ASSUMED: the usual 20-30 % separation rule for rotors running below their first critical)
WHIRL_MARGIN = 0.25
#: points with the smallest lower bound of the fatigue factor whose cycles are built first
#: (their smallest factor bounds the part's: the screen of fatigue_step)
FATIGUE_PROBE_POINTS = 32
#: Friction factors of the mu sensitivity study (mu +- 30 %).
MU_FACTORS = (0.7, 1.3)
#: spacing [rpm] of the internal grid on which clutch/engine crossings are bracketed (then
#: refined by bisection with exact FE solves); also the default output spacing
GRID_RPM = 125.0
#: the same for the mu +-30 % sensitivity cases (two crossings closer than this could merge
#: there; the answer itself is refined to 1e-9 like the main one)
GRID_RPM_SENSITIVITY = 250.0


@dataclass
class Requirements:
    """Designer's factors: engagement > a x idle rpm; slip < b x rpm of max engine torque.

    The thesis keeps a and b confidential: the defaults a = 1.3, b = 1.0 are ASSUMED.
    """

    a: float = DEFAULT_A
    b: float = DEFAULT_B

    def __post_init__(self):
        what = {"a": "engagement rpm must exceed a x idle rpm",
                "b": "slip rpm must stay below b x rpm of the maximum engine torque"}
        for name in ("a", "b"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                    or not math.isfinite(float(v)) or float(v) <= 0:
                raise ParameterError(name, v, f"a finite factor > 0 ({what[name]})",
                                     context="requirement factors")

    @property
    def assumed(self) -> bool:
        return (self.a, self.b) == (DEFAULT_A, DEFAULT_B)


# ---------------------------------------------------------------------------------------
# step results
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SlipAnswer:
    """Slip speed with the drum held and full throttle.

    ``status``: 'slips' (clutch torque meets the engine curve at ``rpm``: below it the clutch
    slips, there it holds the engine), 'holds at start' (the clutch already holds the engine
    torque at the lowest speed of the engine curve), 'never holds' (the clutch torque stays
    below the engine torque at every speed: it slips all the way and the engine runs to its
    maximum speed; mu = 0 or an engine far stronger than the clutch), 'never engages' (no
    contact within the engine's speed range: no torque at all).
    """

    rpm: float | None
    status: str
    note: str
    crossings: tuple[tuple[float, str], ...] = ()


@dataclass(frozen=True)
class EngagementAnswer:
    """Static engagement (FE) and with the 2-stroke ripple (3 sigma and typical cycle) [rpm]."""

    static_rpm: float | None
    with_ripple_rpm: float | None
    with_ripple_typical_rpm: float | None
    note: str


@dataclass(frozen=True)
class CharacterAnswer:
    """Plus/minus character of the shoes from the FE (friction raises or lowers N)."""

    overall: str
    per_shoe: tuple
    probe_rpm: float


@dataclass(frozen=True)
class MuSensitivity:
    """Torque at ``rpm`` and slip speed at mu x 0.7 / 1.0 / 1.3."""

    rpm: float
    mu: float
    torque_Nm: dict
    slip_rpm: dict
    torque_change_pct: dict | None = None
    elasticity: float | None = None

    def as_dict(self) -> dict:
        d = {"rpm": self.rpm, "mu": self.mu, "torque_Nm": dict(self.torque_Nm), "slip_rpm": dict(self.slip_rpm)}
        if self.torque_change_pct is not None:
            d["torque_change_pct"] = dict(self.torque_change_pct)
            d["elasticity"] = self.elasticity
        return d


@dataclass(frozen=True)
class StressAnswer:
    """Peak von Mises and safety factor against yield at ``rpm`` (the engine maximum)."""

    rpm: float
    max_von_mises_Pa: float
    safety_factor: float
    location_m: tuple[float, float]
    yield_strength_Pa: float


@dataclass(frozen=True)
class FatigueAnswer:
    """Fatigue check of the part (step 10): ``safety_factor`` the load multiplier at which
    Miner's sum reaches 1 at the worst point (None: not available, ``details['reason']``;
    inf: no stress changes), ``location`` that point named (zone, flexure end, boundary),
    ``governing_cycle`` the cycle type with the largest damage share there, ``details`` the
    rest (JSON-ready: per-cycle amplitude/mean/damage, loads, counts, ASSUMED values)."""

    safety_factor: float | None
    location: str | None
    governing_cycle: str | None
    details: dict

    def as_dict(self) -> dict:
        return {"safety_factor": self.safety_factor, "location": self.location,
                "governing_cycle": self.governing_cycle, **self.details}


@dataclass(frozen=True)
class Analysis:
    """Answers for one design (see :func:`analyze`); units in the field names or docstrings."""

    design: str
    engagement_rpm: float | None
    engagement_rpm_with_ripple: float | None
    engagement_rpm_with_ripple_typical: float | None
    engagement_note: str
    slip_rpm: float | None
    slip_status: str
    slip_note: str
    slip_crossings_rpm: list
    rpm_max_engine_torque: float
    max_engine_torque_Nm: float
    torque_at_max_engine_torque_Nm: float
    torque_margin_Nm: float
    max_engine_rpm: float
    max_von_mises_Pa: float
    safety_factor: float
    max_stress_rpm: float
    max_stress_location_m: list
    yield_strength_Pa: float
    slip_power_W: float | None
    shoe_character: str
    shoe_character_per_shoe: list
    mu: float
    mu_sensitivity: dict
    torque_models_at_max_engine_torque_Nm: dict
    contact_arc_at_max_engine_torque_deg: float
    requirements: dict
    engine: dict
    coupling: dict
    curves: pd.DataFrame
    first_touch: str | None
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    #: whole part (and per-shoe zones where the mesh names them) from the mesh: area, mass,
    #: centre of mass; see :func:`mesh_mass_properties`
    part: dict = field(default_factory=dict)
    #: False for a user mesh: no shoe mass properties / pivot / nominal arc, so the
    #: analytical shoe-model curves are not available (NaN), the FE answers are
    analytical_available: bool = True
    #: polar angle [deg] of the first contact node (drum frame); with a user mesh the shoe's
    #: root and tip are unknown, so ``first_touch`` is 'unknown' and this angle locates it
    first_touch_angle_deg: float | None = None
    #: everything that defines the answers (clutchfem.traceability.design_inputs) and the
    #: file-name stem that tells this design apart from others in one folder
    inputs: dict = field(default_factory=dict)
    label: str = ""
    #: crankshaft whirl with this clutch on the overhang (clutchfem.clutch.crankshaft.WhirlAnswer.as_dict)
    whirl: dict = field(default_factory=dict)
    #: error estimate of the main answers (clutchfem.errorest): per answer the discretisation
    #: (two mesh levels), the model-form terms and their total band
    errors: dict = field(default_factory=dict)
    #: fatigue (step 10): load multiplier at which Miner's sum reaches 1 at the worst point
    #: (None: not available, see ``fatigue['reason']``), where that point is, which cycle
    #: type governs there, and the details (:meth:`FatigueAnswer.as_dict`)
    fatigue_safety_factor: float | None = None
    fatigue_location: str | None = None
    fatigue_governing_cycle: str | None = None
    fatigue: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        from ..core import clean

        d = {k: v for k, v in self.__dict__.items() if k != "curves"}
        d["units"] = {"rpm": "1/min", "torque": "N m", "stress": "Pa", "power": "W",
                      "safety_factor": "- (yield strength / max von Mises)",
                      "fatigue_safety_factor": "- (load multiplier at which Miner's sum reaches 1)", "angles": "deg",
                      "lengths": "m", "mass": "kg", "force": "N"}
        d["curves"] = self.curves.to_dict("records")
        return clean(d)


# ---------------------------------------------------------------------------------------
# pure helpers (no FE)
# ---------------------------------------------------------------------------------------
def slip_answer(engine: EngineCurve, clutch_torque_at_rpm, engagement_rpm: float | None,
                grid: np.ndarray | None = None) -> SlipAnswer:
    """Classify the slip speed: see :class:`SlipAnswer` (``clutch_torque_at_rpm`` is any
    vectorised function; crossings are bracketed on ``grid``, default 2001 equal steps)."""
    lo, hi = engine.rpm_range
    if engagement_rpm is None or not math.isfinite(engagement_rpm) or engagement_rpm > hi:
        eng = "none found" if engagement_rpm is None else f"{engagement_rpm:.0f} rpm"
        return SlipAnswer(None, "never engages",
                          f"never engages within the engine's speed range (up to {hi:.0f} rpm; "
                          f"engagement {eng}): the clutch transmits no torque")
    cross = tuple(torque_crossings(engine, clutch_torque_at_rpm, grid=grid))
    ups = [r for r, d in cross if d == "up"]
    s = float(lo) if bool(holds(engine, clutch_torque_at_rpm, np.array([lo]))[0]) else (ups[0] if ups else None)
    extra = ""
    if len(cross) > 1:
        extra = ("; the curves cross " + str(len(cross)) + " times ("
                 + ", ".join(f"{r:.0f} rpm {d}" for r, d in cross)
                 + "): the engine stops at the first upward crossing")
    if s is None:
        t_max = float(np.max(np.asarray(clutch_torque_at_rpm(np.array([hi])), dtype=float)))
        why = ("the clutch transmits no torque (mu = 0?)" if t_max <= 0 else
               f"the clutch torque stays below the engine torque up to {hi:.0f} rpm "
               f"({t_max:.3g} N m there against {float(engine.torque_at(hi)):.3g} N m)")
        return SlipAnswer(None, "never holds",
                          f"never holds: {why}; with the drum held the clutch slips at every speed and "
                          f"the engine runs to its maximum speed" + extra, cross)
    if not ups or s <= lo * (1 + 1e-12):
        return SlipAnswer(float(s), "holds at start",
                          f"the clutch already holds the engine torque at {lo:.0f} rpm, the lowest "
                          f"speed of the engine curve" + extra, cross)
    return SlipAnswer(float(s), "slips", "clutch torque meets the engine curve" + extra, cross)


def shoe_kind(arrangement: str, rotation: str) -> str:
    """'minus' arrangement turning ccw is a minus shoe; flipping either flips the kind."""
    plus = (arrangement == "plus") == (rotation == "ccw")
    return "plus" if plus else "minus"


def check_speeds(rpm, engine: EngineCurve) -> np.ndarray:
    """The output speeds [rpm]: finite, >= 0, within 0..max rpm of the engine curve, sorted,
    and always including the engine's maximum speed (where stresses are reported) and the
    rpm of its maximum torque (where torque, arc and character are reported)."""
    lo, hi = engine.rpm_range
    if rpm is None:
        r = np.arange(0.0, hi + 1e-9, GRID_RPM)
    else:
        r = np.atleast_1d(np.asarray(rpm, dtype=float)).ravel()
        if r.size == 0 or not np.all(np.isfinite(r)):
            raise ParameterError("rpm", rpm, "finite speeds in rpm (at least one)")
        if r.min() < 0 or r.max() > hi:
            raise ParameterError("rpm", f"{r.min():g}..{r.max():g}",
                                 f"speeds within 0..{hi:g} rpm (the engine curve, {engine.source}, "
                                 f"ends at {hi:g} rpm; extend the curve to analyse faster)")
    return np.union1d(r, [hi, float(engine.rpm_max_torque)])


def bracket_grid(engine: EngineCurve, step: float = GRID_RPM) -> np.ndarray:
    """The internal grid on which crossings with the engine curve are bracketed: the engine
    range in ``step`` rpm steps plus the engine table's own speeds (fixed: independent of the
    speeds the user tabulates)."""
    lo, hi = engine.rpm_range
    return np.union1d(np.append(np.arange(lo, hi, step), hi), engine.rpm)


def _character(n_mu0: float, n_mu: float) -> str:
    if n_mu0 <= 0:
        return "not in contact"
    if n_mu > n_mu0 * (1 + 1e-6):
        return "plus"
    if n_mu < n_mu0 * (1 - 1e-6):
        return "minus"
    return "neutral"


class FETorque:
    """The exact FE clutch torque [N m] as a vectorised function of rpm (each speed one small
    contact solve with the design's one factorisation; results memoised)."""

    def __init__(self, case, start=None):
        self.case = case
        self.memo: dict[float, float] = {}
        self._active = None
        self._start = start  # a load case on the same nodes whose solved states start the solves

    def __call__(self, rpm) -> np.ndarray:
        r = np.atleast_1d(np.asarray(rpm, dtype=float))
        out = np.empty(r.shape)
        for k, x in enumerate(r.ravel()):
            x = float(x)
            if x not in self.memo:
                w = rpm_to_rad_s(x)
                hit = self._start.solved(w) if self._start is not None else None
                lam, act = self.case.solve(w, hit if hit is not None and hit.any() else self._active)
                if act is not None:
                    self._active = act
                c = self.case.contact
                self.memo[x] = 0.0 if c is None else float(c.mu * c.drum_radius * lam.sum() * self.case.scale)
            out.flat[k] = self.memo[x]
        return out


# ---------------------------------------------------------------------------------------
# steps
# ---------------------------------------------------------------------------------------
def fe_sweep(design, speeds):
    """Step 1: the FE sweep with stresses at the output ``speeds`` [rpm]."""
    return design.sweep(speeds, stresses=True)


def engagement_step(res, ripple_model, in_range: bool, slip: SlipAnswer) -> EngagementAnswer:
    """Step 2: static engagement and the crank speed at which the ripple's peak reaches it."""
    if not in_range:
        return EngagementAnswer(None, None, None, slip.note)
    eng = res.engagement_rpm
    return EngagementAnswer(
        eng, ripple_mod.effective_engagement_rpm(eng, ripple_model, k_sigma=3.0),
        ripple_mod.effective_engagement_rpm(eng, ripple_model, k_sigma=0.0),
        "static: steady speed (FE, closed form); with ripple: mean crank speed at which the 2-stroke "
        "speed ripple's peak reaches the static value (3 sigma cycle; typical cycle also given); ripple "
        "growth with rpm ASSUMED proportional")


def slip_step(case, engine: EngineCurve, step: float = GRID_RPM) -> SlipAnswer:
    """Step 3: slip speed from the exact FE torque (see module docstring); crossings are
    bracketed every ``step`` rpm and then refined to 1e-9."""
    return slip_answer(engine, FETorque(case), case.engagement_rpm, grid=bracket_grid(engine, step))


def secondary_case(design, mu: float):
    """The load case of a secondary friction coefficient (friction off, mu +-30 %): the
    design's softening, with one Ritz space for all of them (seeded by both contact load
    parts, :class:`~clutchfem.softening.Ritz` ``seeds='all'``) instead of one each, built as
    the extension of the design's own space (``base_mu``: only the tangential seeds are
    back-solved)."""
    from dataclasses import replace

    from ..softening import get_softening

    soft = get_softening(design.op.softening)
    if hasattr(soft, "seeds"):  # Ritz and PrestressRitz
        soft = replace(soft, seeds="all", base_mu=float(design.op.mu))
    return design.case(mu=mu, softening=soft)


def character_step(design, probe: float) -> CharacterAnswer:
    """Step 4: per shoe, normal force with friction (the design's mu) and without, at ``probe``
    (both with the secondary cases' shared Ritz space, so the ratio compares like with like)."""
    w = rpm_to_rad_s(probe)
    c0, c1 = secondary_case(design, 0.0), secondary_case(design, design.op.mu)
    if c0.contact is None:
        return CharacterAnswer("not in contact", (), probe)
    start = design.case().solve(w)[1]  # the design's own contact nodes there start both solves
    lam0, _ = c0.solve(w, start)
    lam1, _ = c1.solve(w, start)
    nd = c0.contact.nodes
    per = []
    for s_ in nd.shoes:
        sel = nd.shoe == s_
        n0, n1 = float(lam0[sel].sum()), float(lam1[sel].sum())
        per.append({"shoe": int(s_), "character": _character(n0, n1), "rpm": probe,
                    "normal_force_mu0_N": n0, "normal_force_N": n1,
                    "normal_force_ratio": n1 / n0 if n0 > 0 else math.nan})
    chars = sorted({p_["character"] for p_ in per})
    if len(chars) == 1:
        overall = chars[0]
    elif chars:
        overall = "mixed: " + ", ".join(chars)
    else:
        overall = _character(float(lam0.sum()), float(lam1.sum()))
    return CharacterAnswer(overall, tuple(per), probe)


def mu_sensitivity_step(design, engine: EngineCurve, probe: float, slip: SlipAnswer,
                        notes: list[str]) -> MuSensitivity:
    """Step 5: torque at ``probe`` and slip speed at mu x 0.7 and x 1.3 (same FE model)."""
    mu = design.op.mu
    t_probe = float(FETorque(design.case())(probe)[0])
    torque, slips = {"x1.0": t_probe}, {"x1.0": slip.rpm}
    for f in MU_FACTORS:
        key = f"x{f}"
        if mu * f > 1.0:
            notes.append(f"mu x {f} = {mu * f:.3g} > 1: sensitivity point skipped")
            continue
        case = secondary_case(design, mu * f)
        # the contact solves start from the design's own contact nodes at the same speed
        torque[key] = float(FETorque(case, start=design.case())(probe)[0])
        # the slip speed only (no later crossings): the grid walk stops at the answer
        slips[key] = first_slip_rpm(engine, FETorque(case, start=design.case()),
                                    bracket_grid(engine, GRID_RPM_SENSITIVITY))
    if t_probe > 0 and all(f"x{f}" in torque for f in MU_FACTORS):
        t_lo, t_hi = torque["x0.7"], torque["x1.3"]
        pct = {"x0.7": 100 * (t_lo / t_probe - 1), "x1.3": 100 * (t_hi / t_probe - 1)}
        # d ln M / d ln mu: 1 for a point load (eq 12), < 1 minus shoe, > 1 plus shoe
        el = math.log(t_hi / t_lo) / math.log(1.3 / 0.7) if t_lo > 0 else math.nan
        return MuSensitivity(probe, mu, torque, slips, pct, el)
    return MuSensitivity(probe, mu, torque, slips)


def coupling_step(design, res) -> tuple[dict, pd.DataFrame]:
    """Step 6: analytical torque with the nominal arc and with the FE contact arc (per speed)."""
    cm, params, material = design.cm, design.params, design.model.material
    R, h = design.drum_radius, design.thickness
    mu, rotation = design.op.mu, design.op.rotation
    rpm = res.rpm
    ext = res.contact_extent(0)
    out = {"rpm": rpm, "fe_torque_Nm": res.curve["torque_Nm"].to_numpy(),
           "contact_arc_deg": np.degrees(np.nan_to_num(ext[:, 1] - ext[:, 0]))}  # the columns
    shoe = cm.mass.get("shoe_0") if cm.mass else None
    if shoe is None or not cm.pivots or not cm.contact_arcs or params is None:
        out["analytic_nominal_arc_Nm"] = np.full(len(rpm), math.nan)
        out["analytic_fe_arc_Nm"] = np.full(len(rpm), math.nan)
        return {"source": "no analytical coupling: the design carries no shoe mass properties, "
                          "pivot or nominal arc (user mesh)"}, pd.DataFrame(out)
    rho_h = material.rho * h
    m = shoe["area"] * rho_h
    cx, cy = shoe["centroid"]
    R_Tp = math.hypot(cx, cy)
    px, py = cm.pivots[0]
    A = math.hypot(px, py)
    # lever of the radial apply force (through the centre of mass) about the pivot
    L = abs(px * cy - py * cx) / R_Tp
    root, tip = cm.contact_arcs[0]
    th_p = math.atan2(py, px)
    phi1, phi2 = sorted((abs(wrap_angle(root - th_p)), abs(wrap_angle(tip - th_p))))
    kind = shoe_kind(params.arrangement, rotation)
    n = cm.n_shoes_total
    w_e = None if res.engagement_rpm is None else rpm_to_rad_s(res.engagement_rpm)
    F_f = m * R_Tp * w_e ** 2 if w_e else math.nan
    coupling = {"m_kg": m, "R_Tp_m": R_Tp, "F_f_N": F_f, "A_m": A, "L_m": L, "R_m": R,
                "phi1_deg": math.degrees(phi1), "phi2_deg": math.degrees(phi2), "kind": kind, "n": n,
                "source": "m, R_Tp: OCC mass properties of the shoe zone; F_f: from the FE engagement "
                          "speed (eq 1 inverted); A, L: geometry (pivot = flexure's compliant centre, "
                          "not fitted); phi: nominal shoe arc, measured from the pivot ray; FE arc: "
                          "nodes in contact plus half a node spacing at each end"}
    w = rpm_to_rad_s(rpm)
    F = np.where(np.isfinite(F_f), np.maximum(m * R_Tp * w ** 2 - (F_f if np.isfinite(F_f) else 0), 0.0), 0.0)
    try:
        geom = ShoeGeometry(phi1, phi2, A, R, L)
        out["analytic_nominal_arc_Nm"] = shoe_torque(F, geom, mu, kind, n).total
    except ClutchfemError as exc:
        out["analytic_nominal_arc_Nm"] = np.full(len(rpm), math.nan)
        coupling["nominal_error"] = str(exc)
    # FE contact arc per speed, measured from the pivot ray
    fe_arc = np.zeros(len(rpm))
    q_deg = np.full((len(rpm), 2), np.nan)
    touch = np.isfinite(ext[:, 0])
    qa, qb = np.abs(wrap_angle(ext[touch, 0] - th_p)), np.abs(wrap_angle(ext[touch, 1] - th_p))
    q1, q2 = np.maximum(np.minimum(qa, qb), 0.0), np.minimum(np.maximum(qa, qb), math.pi)
    q_deg[touch] = np.degrees(np.column_stack([q1, q2]))
    on = np.nonzero(touch)[0]
    sel = F[on] > 0
    try:
        fe_arc[on[sel]] = arc_torque(F[on[sel]], q1[sel], q2[sel], A, R, L, mu, kind, n)
    except ClutchfemError:  # an arc the shoe model does not take: speed by speed
        for k, a1, a2 in zip(on[sel], q1[sel], q2[sel]):
            try:
                fe_arc[k] = arc_torque(F[k:k + 1], [a1], [a2], A, R, L, mu, kind, n)[0]
            except ClutchfemError:
                fe_arc[k] = math.nan
    out["analytic_fe_arc_Nm"] = fe_arc
    out["contact_phi1_deg"] = q_deg[:, 0]  # FE contact extent from the pivot ray (nominal: phi1..phi2)
    out["contact_phi2_deg"] = q_deg[:, 1]
    return coupling, pd.DataFrame(out)


def stress_step(res, rpm: float, material) -> StressAnswer:
    """Step 7: peak von Mises and safety factor at the sweep speed ``rpm``."""
    row = res.curve.iloc[res.index(rpm)]
    return StressAnswer(float(rpm), float(row["max_von_mises_Pa"]), float(row["safety_factor"]),
                        (float(row["max_vm_x_m"]), float(row["max_vm_y_m"])), float(material.yield_strength))


def whirl_step(design, max_rpm: float):
    """Step 9: the crankshaft's first critical (whirl) speed with this clutch, drum and
    sprocket (ASSUMED layout) on its overhang, against the engine's maximum speed."""
    from ..clutch import whirl

    return whirl(design, max_rpm=max_rpm)


def error_step(design, engine: EngineCurve, values: dict, w0_rpm: float | None,
               slip_rpm_value: float | None) -> dict:
    """Step 11: the error of the main answers (:mod:`clutchfem.errorest`): the same answers on
    a mesh twice as fine (discretisation) and the measured model-form terms."""
    from ..accuracy import ANSWERS, AnswerError, discretisation, model_form, refined_design
    from ..accuracy.answer_error import NOT_ESTIMATED

    lo, hi = engine.rpm_range
    coarse = {}
    cd = refined_design(design)
    if cd is not None:
        case = cd.case()
        coarse["engagement_rpm"] = case.engagement_rpm
        coarse["slip_rpm"] = slip_step(case, engine).rpm
        coarse["torque_at_max_engine_torque_Nm"] = float(FETorque(case)(float(engine.rpm_max_torque))[0])
        coarse["max_von_mises_Pa"] = float(cd.sweep([hi]).curve["max_von_mises_Pa"].iloc[0])
    out = {}
    for q, unit in ANSWERS.items():
        v = values.get(q)
        w = {"slip_rpm": slip_rpm_value, "torque_at_max_engine_torque_Nm": float(engine.rpm_max_torque)}.get(q)
        terms, notes = model_form(design, q, v, w0=w0_rpm, w=w)
        d = discretisation(v, coarse.get(q)) if cd is not None else None
        if cd is None:
            notes = notes + (NOT_ESTIMATED[design.op.formulation == "3d"],)
        out[q] = AnswerError(q, v, unit, d, terms, notes).as_dict()
    out["method"] = ("discretisation: 2 |a_h - a_h/2| (Richardson, p = 1) against the same design on a mesh twice "
                     "as fine; model form: measured terms (axial thickness 2-D vs 3-D, geometric non-linearity of "
                     "the softening model, rigid vs 2 mm steel drum), relative; total = sum of magnitudes")
    return out


def _stresses(case, omegas, lams) -> np.ndarray:
    """Vertex stresses (3, npts, n) of ``case``'s solved contact states (speeds ``omegas``
    [rad/s], nodal forces ``lams`` (n, m)) from the case's reduced-basis fields: no new
    factorisation."""
    om = np.atleast_1d(np.asarray(omegas, dtype=float))
    basis, coef, U = case.response.fields(om, np.asarray(lams))
    u = U if U is not None else basis @ coef
    return case.model.stress(u).reshape(3, -1, len(om))


def _sweep_index(res, rpm: float) -> int | None:
    k = int(np.argmin(np.abs(res.rpm - rpm)))
    return k if abs(res.rpm[k] - rpm) <= 1e-9 * max(1.0, rpm) else None


def _case_torque(case, lam: np.ndarray, mu: float) -> float:
    """mu R_d sum(lam) x (n_total / n_model) [N m] (``mu``: the friction coefficient the
    torque is meant with; the frictionless case's forces give M_0 = mu R_d N_0)."""
    return float(mu * case.contact.drum_radius * lam.sum() * case.scale)


def fatigue_cycles(design, res, engine: EngineCurve, loads=None,
                   ripple_model: ripple_mod.RippleModel | None = None, points=None):
    """The service cycles of :mod:`clutchfem.durability.cycles` for ``design`` (a
    :class:`~clutchfem.durability.cycles.CycleSet`): start-stop to the speed each start
    reaches (default the engine's maximum), running revolutions at the operating speed with
    the 2-stroke ripple and seed 000's load torque carried by static friction.

    States: the design's full-slip case at w_o (1 -+ delta_max) and w_o (its state at w_o
    and at the maximum speed taken from the sweep ``res`` when solved there), and the
    frictionless case (mu = 0, the secondary cases' Ritz space) at the same speeds,
    warm-started from the slip state's contact nodes: a handful of memoised contact solves,
    no factorisation.  ``loads``: :class:`~clutchfem.durability.cycles.FatigueLoads`;
    ``points``: the cycles at these stress points only (default all)."""
    from ..durability import service_cycles

    st, kw, ripple = _fatigue_states(design, res, engine, loads, ripple_model)
    cs = service_cycles(st, points=points, **kw)
    cs.info["ripple"] = ripple
    return cs


def _fatigue_states(design, res, engine: EngineCurve, loads=None,
                    ripple_model: ripple_mod.RippleModel | None = None):
    """(ServiceStates, the other arguments of service_cycles, ripple info) of
    :func:`fatigue_cycles`."""
    from ..durability import FatigueLoads, ServiceStates, ripple_classes

    loads = loads if loads is not None else FatigueLoads()
    if not isinstance(loads, FatigueLoads):
        raise ParameterError("fatigue loads", type(loads).__name__, "a clutchfem.durability.cycles.FatigueLoads")
    if design.nodes is None:
        raise ParameterError("drum_radius", None, "a drum: the fatigue loads act through the shoes' contact")
    lo, hi = engine.rpm_range
    rpm_o = float(loads.operating_rpm if loads.operating_rpm is not None else engine.rpm_max_torque)
    rpm_max = float(loads.max_rpm if loads.max_rpm is not None else hi)
    for name, v in (("operating_rpm", rpm_o), ("max_rpm", rpm_max)):
        if not lo <= v <= hi:
            raise ParameterError(name, v, f"a speed within the engine curve's range {lo:g}..{hi:g} rpm",
                                 context="fatigue loads")
    m_o = float(loads.cutting_torque if loads.cutting_torque is not None else engine.torque_at(rpm_o))
    rm = ripple_model or ripple_mod.RippleModel()
    classes = ripple_classes(rm, rpm_o, loads.revolutions)
    d_max = max(c["delta"] for c in classes)
    if d_max <= 0:
        d_max = 1e-3  # no ripple: any bracket of w_o serves the interpolation
    mu = design.op.mu
    w = rpm_to_rad_s(rpm_o * np.array([1.0 - d_max, 1.0, 1.0 + d_max]))
    w_max = rpm_to_rad_s(rpm_max)
    c0, cf = secondary_case(design, 0.0), design.case()
    # full slip at the three operating speeds (torques; the stress at w_o from the sweep when
    # it was solved there), then frictionless states warm-started from the slip state's
    # contact nodes (one blocked condensation instead of a pivot-by-pivot one)
    lam_o, act_o = cf.solve(float(w[1]))  # (solved already when w_o is on the sweep's grid)
    lamf = [cf.solve(float(w[0]), act_o)[0], lam_o, cf.solve(float(w[2]), act_o)[0]]
    Mf = np.array([_case_torque(cf, lam, mu) for lam in lamf])
    k_max = _sweep_index(res, rpm_max)
    lam_fmax = res.lam[k_max] if k_max is not None else cf.solve(float(w_max))[0]
    lam0 = [c0.solve(float(x), a if a.any() else None)[0]
            for x, a in zip(np.append(w, w_max), [lam > 0 for lam in lamf] + [lam_fmax > 0])]
    M0 = np.array([_case_torque(c0, lam, mu) for lam in lam0])
    S0 = _stresses(c0, np.append(w, w_max), np.vstack(lam0))
    k_o = _sweep_index(res, rpm_o)
    Sf_o = (res.fields.stresses(slice(k_o, k_o + 1))[..., 0] if k_o is not None
            else _stresses(cf, w[1:2], lamf[1][None])[..., 0])
    if k_max is not None:
        Sf_max = res.fields.stresses(slice(k_max, k_max + 1))[..., 0]
        Mf_max = float(res.curve["torque_Nm"].iloc[k_max])
    else:
        Sf_max = _stresses(cf, [w_max], lam_fmax[None])[..., 0]
        Mf_max = _case_torque(cf, lam_fmax, mu)
    st = ServiceStates(omegas=w, S0=np.moveaxis(S0[..., :3], 2, 0), Sf_o=Sf_o, Mf=Mf, M0=M0[:3],
                       omega_max=w_max, S0_max=S0[..., 3], Sf_max=Sf_max, Mf_max=Mf_max, M0_max=float(M0[3]))
    kw = dict(delta_classes=classes, cutting_torque=m_o, inertia=loads.drive_inertia,
              max_speed_torque=float(engine.torque_at(rpm_max)), start_stops=loads.start_stops,
              samples=loads.samples)
    ripple = {"delta_mean": float(rm.delta_mean(rpm_o)), "delta_std": float(rm.delta_std(rpm_o)),
              "assumed": list(rm.assumed)}
    return st, kw, ripple


def fatigue_step(design, res, engine: EngineCurve, *, loads=None, params=None,
                 ripple_model: ripple_mod.RippleModel | None = None) -> FatigueAnswer:
    """Step 10: fatigue safety factor under the service cycles of :func:`fatigue_cycles`,
    checked by :func:`clutchfem.durability.fatigue.fatigue_check` (Goodman, Marin-corrected
    endurance limit, Basquin + Miner) at every element vertex: the cycles are built only at
    the points a closed-form lower bound of the factor cannot rule out (bounds of every
    cycle's amplitude and mean, :class:`~clutchfem.durability.cycles.CycleSet`), the exact
    check runs on those :func:`~clutchfem.durability.fatigue.candidate_points` leaves (the
    same worst point as checking all; tested).  ``params``:
    :class:`~clutchfem.durability.fatigue.FatigueParams` (default: 51CrV4 with the design
    material's yield strength; another material needs its own, else the answer is 'not
    available')."""
    import time

    from ..durability import (
        FatigueLoads,
        FatigueParams,
        LoadCycle,
        candidate_points,
        endurance_limit,
        fatigue_check,
        service_cycles,
        single_cycle_factor,
    )
    from ..fe import von_mises

    t0 = time.perf_counter()
    model = design.model
    material = model.material
    if params is None:
        if not material.name.startswith("51CrV4"):
            return FatigueAnswer(None, None, None, {
                "available": False, "reason": f"no fatigue strength data for {material.name}: the defaults are "
                "for hardened 51CrV4; give FatigueParams (S_ut, endurance limit, surface finish) for it"})
        params = FatigueParams(yield_strength=min(material.yield_strength, FatigueParams().ultimate_strength))
    if not isinstance(params, FatigueParams):
        raise ParameterError("fatigue params", type(params).__name__, "a clutchfem.durability.fatigue.FatigueParams")
    st, kw, ripple = _fatigue_states(design, res, engine, loads, ripple_model)
    t1 = time.perf_counter()
    # Which points can be the worst, exactly, before any cycle is built (the chord searches
    # are the cost): with upper bounds of every cycle's amplitude and mean at a point
    # (service_cycles' bounds), the closed-form lower bound L(p) of candidate_points holds
    # with them too (the single-type factor falls with both); the cycles of the K points with
    # the smallest L give an upper bound U of the smallest factor, and only points with
    # L <= U are kept.  On those, the closed-form screen with the true amplitudes and means
    # (candidate_points) and the exact check.
    pts = model.stress.points
    elem = np.arange(design.cm.n_elements).repeat(3)
    b = service_cycles(st, bound_only=True, **kw)
    M = b.stress_bound
    counts = [kw["start_stops"]] + [max(float(c["count"]), 1.0) for c in kw["delta_classes"]]
    C = len(counts)
    Se = endurance_limit(params)[0]
    L = np.min([single_cycle_factor(b.amplitude_bound[i], b.mean_bound[i], C * counts[i], params, Se)
                for i in range(C)], axis=0)
    top = np.argsort(L, kind="stable")[:FATIGUE_PROBE_POINTS]

    def check(points):
        cs = service_cycles(st, points=points, **kw)
        cand = candidate_points(cs.cycles, params, Se)
        sub = [LoadCycle(c.name, c.state_a[:, cand], c.state_b[:, cand], c.count) for c in cs.cycles]
        return cs, fatigue_check(sub, params, xy=pts[:, points[cand]], cm=design.cm, element=elem[points[cand]]), cand

    cs_top, fr_top, cand_top = check(top)
    with np.errstate(divide="ignore"):
        keep = np.nonzero(L <= fr_top.safety_factor * (1.0 + 1e-9))[0] if math.isfinite(fr_top.safety_factor) \
            else np.arange(len(M))
    keep = np.union1d(keep, top)
    cs, fr, cand = (cs_top, fr_top, cand_top) if len(keep) == len(top) else check(keep)
    cs.info["ripple"] = ripple

    def peak_vm(cycles):
        return max((float(np.maximum(von_mises(c.state_a), von_mises(c.state_b)).max(initial=0.0)) for c in cycles),
                   default=0.0)

    # Langer's first yield over the cycles at every point: where the bound exceeds the peak
    # found so far, the cycles are built too
    vmax = peak_vm(cs.cycles)
    rest = np.setdiff1d(np.nonzero(M > vmax)[0], keep)
    if len(rest):
        vmax = max(vmax, peak_vm(service_cycles(st, points=rest, **kw).cycles))
    t2 = time.perf_counter()
    info = cs.info
    notes = []
    rpm_o = info["operating_rpm"]
    if not info["engaged_at_operating_speed"]:
        notes.append(f"the shoes do not touch the drum at the operating speed {rpm_o:.0f} rpm: no load torque is "
                     "carried (running cycles: speed ripple only)")
    elif info["cutting_torque_Nm"] > info["capacity_forward_Nm"][1]:
        notes.append(f"the mean cutting torque {info['cutting_torque_Nm']:.2f} N m exceeds the clutch's capacity "
                     f"{info['capacity_forward_Nm'][1]:.2f} N m at the operating speed {rpm_o:.0f} rpm: it slips "
                     "continuously there (running cycles at capacity)")
    if model.szz_factor:
        notes.append("plane strain: the fatigue check uses the in-plane stresses (s_zz left out)")
    details = {
        "available": True, "location_detail": None if fr.location is None else fr.location.to_json(),
        "worst_xy_m": None if fr.worst_xy_m is None else list(fr.worst_xy_m),
        "damage_at_worst": fr.damage_at_worst, "per_cycle": [dict(c) for c in fr.per_cycle],
        "yield_safety_factor_over_cycles": params.yield_strength / vmax if vmax > 0 else math.inf,
        "points_checked": int(len(cand)), "points_screened": int(len(keep)), "points_yield_checked":
        int(len(keep) + len(rest)), "points": int(pts.shape[1]), "endurance_limit_Pa": fr.endurance_limit_Pa,
        "marin_factors": dict(fr.factors), "params": dict(fr.params),
        "loads": (loads if loads is not None else FatigueLoads()).model_dump(),
        "ripple": info.pop("ripple"), "cycles": info, "notes": notes,
        "approximations": [
            "holding state at load torque M: the straight line through the frictionless and the full-slip "
            "state at that speed (exact for one contact node; traction distributed like the slip state's)",
            "reverse torque (drum overrunning the crank) on the same line; slip (torque clipped) beyond the "
            "forward / reverse capacity",
            "states between the solved speeds w_o (1 -+ delta_max), w_o: piecewise linear in w^2",
            "non-proportional revolution cycle: amplitude and mean from the longest von Mises chord of the "
            "sampled stress path",
        ],
        "assumed": list(fr.assumed) + ["service loads: start-stop count, revolutions, operating speed, cutting "
                                       "torque and drive inertia (FatigueLoads), ripple law (RippleModel)"],
        "time_s": {"states_s": t1 - t0, "check_s": t2 - t1},
    }
    loc = None if fr.location is None else fr.location.description
    return FatigueAnswer(fr.safety_factor, loc, fr.governing_cycle, details)


def requirements_step(req: Requirements, idle_rpm: float, engine: EngineCurve, eng: EngagementAnswer,
                      slip: SlipAnswer, in_range: bool) -> dict:
    """Step 8: the two requirement checks (with the values checked and the limits)."""
    eng_limit = req.a * idle_rpm
    slip_limit = req.b * engine.rpm_max_torque
    eng_r = eng.with_ripple_rpm
    return {"a": req.a, "b": req.b, "idle_rpm": float(idle_rpm), "rpm_max_torque": float(engine.rpm_max_torque),
            "engagement_limit_rpm": eng_limit, "engagement_checked_rpm": eng_r,
            "engagement_checked_with": "engagement with ripple (3 sigma cycle)",
            "slip_limit_rpm": slip_limit,
            "engagement_ok": bool((not in_range) or (eng_r is not None and eng_r > eng_limit)),
            "slip_ok": bool(slip.rpm is not None and slip.rpm < slip_limit),
            "assumed": ("a = 1.3 and b = 1.0 are ASSUMED defaults (confidential in the thesis)" if req.assumed
                        else "user factors a, b")}


# ---------------------------------------------------------------------------------------
# the sequence
# ---------------------------------------------------------------------------------------
def analyze(design, *, engine: EngineCurve | None = None, requirements: Requirements | None = None,
            idle_rpm: float | None = None, ripple_model: ripple_mod.RippleModel | None = None,
            errors: bool = True, fatigue_loads=None, fatigue_params=None) -> Analysis:
    """Run the steps (module docstring) on ``design`` (a :class:`~clutchfem.design.Design`:
    mesh, parameters, material, mu, rotation, drum, thickness, softening and output speeds in
    its operating point).  engine: full-throttle curve (default: the ASSUMED 56.5 cc saw
    curve); requirements: factors a, b; idle_rpm: overrides the engine's idle speed (else the
    curve's, else 2700 rpm, ASSUMED); errors: estimate the error of the main answers (step
    11: a mesh twice as fine and its solves, ~3x the time; off for bulk studies that rank
    designs, whose error the study states from a sample); fatigue_loads, fatigue_params: the
    service loads (:class:`~clutchfem.durability.cycles.FatigueLoads`) and fatigue strength
    (:class:`~clutchfem.durability.fatigue.FatigueParams`) of step 10.  A user mesh
    (``design.params`` None) gets every FE answer; the analytical curves are then NaN and
    ``analytical_available`` is False."""
    from ..loadcase import Design, design_inputs, design_label

    if not isinstance(design, Design):
        raise ParameterError("design", type(design).__name__, "a clutchfem.design.Design (mesh + operating point)")
    engine = engine or EngineCurve.default()
    req = requirements or Requirements()
    if design.drum_radius is None:
        raise ParameterError("drum_radius", None, "the drum's inner radius in m, larger than the outer radius "
                             "of the contact surface: a user mesh carries no drum, and without a drum there "
                             "is no friction torque", context="user mesh")
    notes: list[str] = []
    warnings: list[str] = []
    if idle_rpm is None:
        idle_rpm = engine.idle_rpm
        if idle_rpm is None:
            idle_rpm = DEFAULT_IDLE_RPM
            notes.append(f"idle speed {DEFAULT_IDLE_RPM:.0f} rpm ASSUMED (the engine curve gives none)")
    if isinstance(idle_rpm, bool) or not (isinstance(idle_rpm, (int, float)) and math.isfinite(idle_rpm)
                                          and idle_rpm > 0):
        raise ParameterError("idle_rpm", idle_rpm, "an idle speed > 0 rpm")
    lo, hi = engine.rpm_range
    op = design.op
    rpm = check_speeds(None if op.rpm is None else op.speeds(), engine)
    material = design.model.material
    case = design.case()
    # 1-3: slip (exact FE crossings), the sweep (output speeds plus the engagement and slip
    # speeds, so the curves hold the exact answers), engagement with ripple
    slip = slip_step(case, engine)
    in_range = slip.status != "never engages"
    key = [x for x in (case.engagement_rpm, slip.rpm) if x is not None and 0 <= x <= hi]
    res = fe_sweep(design, np.union1d(rpm, key))
    eng = engagement_step(res, ripple_model, in_range, slip)
    # 4-5: character and mu sensitivity at the rpm of max engine torque (engine max if the
    # clutch is not engaged there)
    probe = float(engine.rpm_max_torque)
    if res.engagement_rpm is not None and res.engagement_rpm > probe and res.engagement_rpm <= hi:
        probe = hi
        notes.append(f"not engaged at the rpm of max engine torque: plus/minus character and mu "
                     f"sensitivity evaluated at {hi:.0f} rpm")
    ch = character_step(design, probe)
    character = ch.overall if in_range else "never engages"
    if ch.per_shoe and design.cm.sector_angle:
        notes.append(f"sector model: shoe 0 stands for all {design.cm.n_shoes_total} identical shoes")
    sens = mu_sensitivity_step(design, engine, probe, slip, notes)
    # 6: analytical coupling
    coupling, curves = coupling_step(design, res)
    analytical = bool(coupling.get("kind"))
    if not analytical:
        notes.append("analytical shoe-model curves (eqs 2-8) not available: a user mesh carries no shoe "
                     "pivot or nominal shoe arc (shoe mass from the mesh is reported for information); "
                     "every FE answer (engagement, slip, torque, stress, shoe character, mu sensitivity) "
                     "is given")
    basis = design.model.basis if design.model.basis.mesh is design.cm.mesh else None  # 3-D: its own
    part = mesh_mass_properties(design.cm, material.rho, design.thickness, basis)
    strong = [p_ for p_ in ch.per_shoe if p_["normal_force_ratio"] > SELF_ENERGISING_WARN]
    if strong:
        r = max(p_["normal_force_ratio"] for p_ in strong)
        warnings.append(f"STRONGLY SELF-ENERGISING (plus) shoe: friction multiplies the normal force by {r:.2f} "
                        f"at {probe:.0f} rpm (mu = {op.mu:g}): the torque is very sensitive to mu and the clutch "
                        "grabs, near self-locking; a minus arrangement or lower mu is the robust choice")
    if coupling.get("kind") and character in ("plus", "minus") and coupling["kind"] != character:
        warnings.append(f"the FE model behaves as a {character} shoe but the flexure arrangement "
                        f"suggests a {coupling['kind']} shoe: the analytical curves assume "
                        f"{coupling['kind']}; trust the FE")
    k_nom = res.index(float(engine.rpm_max_torque))
    t_nom = float(res.curve["torque_Nm"].iloc[k_nom])
    models = {"rpm": float(engine.rpm_max_torque)}
    for col in ("fe_torque_Nm", "analytic_fe_arc_Nm", "analytic_nominal_arc_Nm"):
        models[col] = float(curves[col].iloc[k_nom])
    arc_probe = float(curves["contact_arc_deg"].iloc[k_nom])
    # the sweep's own numerical and model-applicability warnings (stress is checked below
    # at the engine's maximum speed)
    from ..loadcase import model_warnings

    warnings += list(res.warnings) + [w for w in model_warnings(res, material.yield_strength)
                                      if not w.startswith("STRESS ABOVE YIELD")]
    # 7: stress at the engine's maximum speed
    st = stress_step(res, hi, material)
    fy = st.yield_strength_Pa
    if st.safety_factor < 1.0:
        warnings.append(f"STRESS ABOVE YIELD: peak von Mises {st.max_von_mises_Pa / 1e6:.0f} MPa at {hi:.0f} rpm "
                        f"(engine maximum) exceeds the yield strength {fy / 1e6:.0f} MPa of {material.name} "
                        f"(safety factor {st.safety_factor:.2f} < 1): this design would yield at full speed")
    slip_power = None
    if slip.rpm is not None:
        slip_power = float(engine.torque_at(slip.rpm) * rpm_to_rad_s(slip.rpm))
    r_c = curves["rpm"].to_numpy(dtype=float)
    inside = (r_c >= lo) & (r_c <= hi)
    e_t = np.full(len(r_c), math.nan)
    e_t[inside] = engine.torque_at(r_c[inside])
    nominal = coupling.get("phi2_deg", math.nan) - coupling.get("phi1_deg", math.nan)
    arc = curves["contact_arc_deg"].to_numpy()
    curves = pd.DataFrame({  # (one frame: column by column inserts cost ~0.1 ms each)
        **{c: curves[c].to_numpy() for c in curves.columns}, "engine_torque_Nm": e_t,
        "normal_force_N": res.curve["normal_force_N"].to_numpy(),
        "max_von_mises_Pa": res.curve["max_von_mises_Pa"].to_numpy(),
        "safety_factor": res.curve["safety_factor"].to_numpy(),
        "arc_fraction": arc / nominal if nominal and math.isfinite(nominal) else np.full(len(arc), math.nan)})
    # 8: requirements
    checks = requirements_step(req, idle_rpm, engine, eng, slip, in_range)
    # 11: error of the main answers
    err = {}
    if errors:
        err = error_step(design, engine, {"engagement_rpm": eng.static_rpm, "slip_rpm": slip.rpm,
                                          "torque_at_max_engine_torque_Nm": t_nom,
                                          "max_von_mises_Pa": st.max_von_mises_Pa},
                         eng.static_rpm, slip.rpm)
    # 9: crankshaft whirl
    wh = whirl_step(design, hi)
    if wh.margin < WHIRL_MARGIN:
        warnings.append(f"CRANKSHAFT WHIRL: the first critical speed {wh.rpm_crit_lowest:,.0f} rpm is only "
                        f"{100 * wh.margin:+.0f} % above the engine's maximum {hi:,.0f} rpm (wanted >= "
                        f"{100 * WHIRL_MARGIN:.0f} %, ASSUMED); crankshaft, drum and sprocket are ASSUMED")
    # 10: fatigue
    fat = fatigue_step(design, res, engine, loads=fatigue_loads, params=fatigue_params, ripple_model=ripple_model)
    if fat.safety_factor is not None and fat.safety_factor < 1.0:
        warnings.append(f"FATIGUE: safety factor {fat.safety_factor:.2f} < 1 at {fat.location}, governed by "
                        f"{fat.governing_cycle}: the part is expected to crack within the ASSUMED service life "
                        "(start-stop and running cycles, Goodman, Miner; see fatigue details)")
    if not fat.details.get("available", True):
        notes.append("fatigue: " + fat.details["reason"])
    notes += ["fatigue: " + n_ for n_ in fat.details.get("notes", [])]
    if not checks["engagement_ok"]:
        warnings.append(f"REQUIREMENT NOT MET: engagement with ripple {eng.with_ripple_rpm:.0f} rpm is not above "
                        f"a x idle = {req.a:g} x {idle_rpm:.0f} = {checks['engagement_limit_rpm']:.0f} rpm "
                        "(chain may move at idle)")
    if not checks["slip_ok"]:
        got = {"never holds": "the clutch never holds the engine (slips at every speed)",
               "never engages": "never engages"}.get(
            slip.status, f"slip {slip.rpm:.0f} rpm" if slip.rpm is not None else "no slip speed")
        warnings.append(f"REQUIREMENT NOT MET: {got}; required slip below b x rpm(max torque) = "
                        f"{req.b:g} x {engine.rpm_max_torque:.0f} = {checks['slip_limit_rpm']:.0f} rpm")
    if engine.assumed:
        notes.append("engine curve: built-in 56.5 cc saw curve; its SHAPE IS ASSUMED (anchors 3.40 N m at "
                     "8000 rpm and 3.20 N m at 9072 rpm from seed 000); use --engine CSV for design work")
    if req.assumed:
        notes.append("requirement factors a = 1.3, b = 1.0 are ASSUMED defaults (the thesis keeps them confidential)")
    eng_info = {"source": engine.source, "assumed_shape": engine.assumed, "rpm_range": list(engine.rpm_range),
                "max_torque_Nm": engine.max_torque, "rpm_max_torque": float(engine.rpm_max_torque),
                "idle_rpm": float(idle_rpm)}
    return Analysis(design=design.name, engagement_rpm=eng.static_rpm,
                    engagement_rpm_with_ripple=eng.with_ripple_rpm,
                    engagement_rpm_with_ripple_typical=eng.with_ripple_typical_rpm, engagement_note=eng.note,
                    slip_rpm=slip.rpm, slip_status=slip.status, slip_note=slip.note,
                    slip_crossings_rpm=[{"rpm": r, "direction": d} for r, d in slip.crossings],
                    rpm_max_engine_torque=float(engine.rpm_max_torque), max_engine_torque_Nm=engine.max_torque,
                    torque_at_max_engine_torque_Nm=t_nom, torque_margin_Nm=t_nom - engine.max_torque,
                    max_engine_rpm=float(hi), max_von_mises_Pa=st.max_von_mises_Pa, safety_factor=st.safety_factor,
                    max_stress_rpm=st.rpm, max_stress_location_m=list(st.location_m), yield_strength_Pa=fy,
                    slip_power_W=slip_power, shoe_character=character, shoe_character_per_shoe=list(ch.per_shoe),
                    mu=float(op.mu), mu_sensitivity=sens.as_dict(), torque_models_at_max_engine_torque_Nm=models,
                    contact_arc_at_max_engine_torque_deg=arc_probe, requirements=checks, engine=eng_info,
                    coupling=coupling, curves=curves, first_touch=res.first_touch, warnings=warnings, notes=notes,
                    part=part, analytical_available=analytical, first_touch_angle_deg=res.first_touch_angle_deg,
                    inputs={**design_inputs(design), "engine": eng_info, "requirements": {"a": req.a, "b": req.b}},
                    label=design_label(design), whirl=wh.as_dict(), fatigue_safety_factor=fat.safety_factor,
                    fatigue_location=fat.location, fatigue_governing_cycle=fat.governing_cycle,
                    fatigue=fat.as_dict(), errors=err)


def mesh_mass_properties(cm, rho: float, thickness: float, basis=None) -> dict:
    """Area, mass and centre of mass of the meshed part (and of each ``shoe_<i>`` zone the mesh
    names), by quadrature over the (possibly curved) P2 triangles: mass = area x rho x thickness.
    ``basis``: a scikit-fem basis on ``cm.mesh`` whose quadrature to use (default: P0,
    order 4).

    A one-sector model is scaled to the whole part (``n_shoes_total / n_shoes_model``); its
    centre of mass is then not meaningful and left out.  For a full part, ``unbalance_kg_m``
    = mass x distance of the centre of mass from the rotation axis.
    """
    from skfem import Basis, ElementTriP0

    mesh = cm.mesh
    if basis is None:  # any basis on the mesh will do (an FE model's: its quadrature is reused)
        basis = Basis(mesh, ElementTriP0(), intorder=4)
    dx = basis.dx  # (nelem, nqp) quadrature weights x |det J|
    xq = basis.mapping.F(basis.X)  # (2, nelem, nqp)
    a_e, x_e, y_e = dx.sum(axis=1), (xq[0] * dx).sum(axis=1), (xq[1] * dx).sum(axis=1)

    def props(elements=None) -> tuple[float, float, float]:
        sel = slice(None) if elements is None else np.asarray(elements)
        a = float(a_e[sel].sum())
        return a, float(x_e[sel].sum()) / a, float(y_e[sel].sum()) / a

    area, cx, cy = props()
    sector = cm.sector_angle is not None
    scale = cm.n_shoes_total / cm.n_shoes_model if sector else 1.0
    out = {"thickness_m": thickness, "rho_kg_m3": float(rho), "area_m2": area * scale,
           "mass_kg": area * scale * rho * thickness,
           "source": "quadrature over the mesh: area x rho x thickness"
                     + (f" (one-sector model x {scale:g})" if sector else "")}
    if not sector:
        e = math.hypot(cx, cy)
        out.update({"centroid_m": [cx, cy], "unbalance_kg_m": out["mass_kg"] * e})
    shoes = []
    sub = cm.mesh.subdomains or {}
    i = 0
    while f"shoe_{i}" in sub and len(sub[f"shoe_{i}"]):
        a, sx, sy = props(np.asarray(sub[f"shoe_{i}"]))
        shoes.append({"shoe": i, "mass_kg": a * rho * thickness, "centroid_m": [sx, sy],
                      "R_Tp_m": math.hypot(sx, sy)})
        i += 1
    if shoes:
        out["shoes"] = shoes
    return out
