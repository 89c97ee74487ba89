"""From a solved design to the answers a clutch designer asks for.

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

from ..errors import ClutchfemError, ParameterError
from ..units import rpm_to_rad_s
from . import ripple as ripple_mod
from .engine import EngineCurve, slip_rpm, torque_crossings
from .shoe import ShoeGeometry, shoe_torque


#: Defaults of the requirement factors.  The thesis keeps a and b confidential: ASSUMED.
DEFAULT_A = 1.3
DEFAULT_B = 1.0
#: Idle speed used when the engine curve carries none (typical saw idle): ASSUMED.
DEFAULT_IDLE_RPM = 2700.0
#: Safety factor below which the report adds a fatigue caution (ASSUMED threshold; yield
#: itself is the hard limit, sf < 1).
FATIGUE_CAUTION_SF = 1.5
#: A user mesh's drum radius may exceed the contact surface's outer radius by at most this
#: factor (a units check: a gap of half the part's radius cannot close elastically).
DRUM_GAP_LIMIT = 1.5
#: Friction factors of the mu sensitivity study (mu +- 30 %).
MU_FACTORS = (0.7, 1.3)


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


@dataclass(frozen=True)
class SlipAnswer:
    """Slip speed with the drum held and full throttle.

    ``status``: 'slips' (clutch torque meets the engine curve at ``rpm``), 'holds at start'
    (the clutch already holds the engine torque at the lowest speed of the engine curve),
    'never slips' (clutch torque stays below the engine curve: the engine runs to its maximum
    speed), 'never engages' (no contact within the engine's speed range).
    """

    rpm: float | None
    status: str
    note: str
    crossings: tuple[tuple[float, str], ...] = ()


def slip_answer(engine: EngineCurve, clutch_torque_at_rpm, engagement_rpm: float | None) -> SlipAnswer:
    """Classify the slip speed: see :class:`SlipAnswer` (pure function, no FE)."""
    lo, hi = engine.rpm_range
    if engagement_rpm is None or not math.isfinite(engagement_rpm) or engagement_rpm > hi:
        eng = "none found" if engagement_rpm is None else f"{engagement_rpm:.0f} rpm"
        return SlipAnswer(None, "never engages",
                          f"never engages within the engine's speed range (up to {hi:.0f} rpm; "
                          f"engagement {eng}): the clutch transmits no torque")
    cross = tuple(torque_crossings(engine, clutch_torque_at_rpm))
    s = slip_rpm(engine, clutch_torque_at_rpm)
    extra = ""
    ups = [r for r, d in cross if d == "up"]
    if len(cross) > 1:
        extra = ("; the curves cross " + str(len(cross)) + " times ("
                 + ", ".join(f"{r:.0f} rpm {d}" for r, d in cross)
                 + "): the engine stops at the first upward crossing")
    if s is None:
        return SlipAnswer(None, "never slips",
                          f"never slips: the clutch torque stays below the engine torque up to "
                          f"{hi:.0f} rpm, so with the drum held the engine runs to its maximum speed"
                          + extra, cross)
    if not ups or s <= lo * (1 + 1e-12):
        return SlipAnswer(float(s), "holds at start",
                          f"the clutch already holds the engine torque at {lo:.0f} rpm, the lowest "
                          f"speed of the engine curve" + extra, cross)
    return SlipAnswer(float(s), "slips", "clutch torque meets the engine curve" + extra, cross)


@dataclass
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

    def to_json(self) -> dict:
        d = {k: v for k, v in self.__dict__.items() if k != "curves"}
        d["units"] = {"rpm": "1/min", "torque": "N m", "stress": "Pa", "power": "W",
                      "safety_factor": "- (yield strength / max von Mises)", "angles": "deg",
                      "lengths": "m", "mass": "kg", "force": "N"}
        d["curves"] = self.curves.replace({np.inf: None}).to_dict("records")
        return _clean(d)


def _clean(x):
    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    if isinstance(x, (np.floating, float)):
        return None if not math.isfinite(float(x)) else float(x)
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, np.bool_):
        return bool(x)
    return x


def shoe_kind(arrangement: str, rotation: str) -> str:
    """'minus' arrangement turning ccw is a minus shoe; flipping either flips the kind."""
    plus = (arrangement == "plus") == (rotation == "ccw")
    return "plus" if plus else "minus"


def check_speeds(rpm, engine: EngineCurve) -> np.ndarray:
    """The sweep speeds [rpm]: finite, >= 0, within 0..max rpm of the engine curve, sorted,
    and always including the engine's maximum speed (where stresses are reported)."""
    lo, hi = engine.rpm_range
    if rpm is None:
        return np.arange(0.0, hi + 1e-9, 125.0) if hi % 125.0 == 0 else np.append(np.arange(0.0, hi, 125.0), hi)
    r = np.atleast_1d(np.asarray(rpm, dtype=float)).ravel()
    if r.size == 0 or not np.all(np.isfinite(r)):
        raise ParameterError("rpm", rpm, "finite speeds in rpm (at least one)")
    if r.min() < 0 or r.max() > hi:
        raise ParameterError("rpm", f"{r.min():g}..{r.max():g}",
                             f"speeds within 0..{hi:g} rpm (the engine curve, {engine.source}, "
                             f"ends at {hi:g} rpm; extend the curve to analyse faster)")
    return np.union1d(r, [hi])


def _character(n_mu0: float, n_mu: float) -> str:
    if n_mu0 <= 0:
        return "not in contact"
    if n_mu > n_mu0 * (1 + 1e-6):
        return "plus"
    if n_mu < n_mu0 * (1 - 1e-6):
        return "minus"
    return "neutral"


def analyze(cm, params, material, *, mu: float = 0.165, rotation: str = "ccw",
            engine: EngineCurve | None = None, requirements: Requirements | None = None,
            rpm=None, spin_softening: str = "modal", design: str = "",
            idle_rpm: float | None = None, ripple_model: ripple_mod.RippleModel | None = None,
            drum_radius: float | None = None, thickness: float | None = None) -> Analysis:
    """Run the FE sweeps and turn them into engagement / slip / torque / stress answers.

    cm: meshed design (concept mesh: mass properties, pivots and nominal arcs give the
    analytical coupling; a user mesh from :func:`clutchfem.mesh.load_user_geometry` gives
    every FE answer, the analytical curves are then NaN and ``analytical_available`` is
    False); params: the concept's parameters (drum radius, thickness, arrangement), or None
    for a user mesh; drum_radius [m], thickness [m]: override the concept's values; for a
    user mesh the drum radius is required (no drum, no torque) and the thickness defaults to
    ``cm.thickness``; material: E, nu, rho, yield strength; mu: friction coefficient [-];
    rotation: 'ccw' or 'cw'; engine: full-throttle curve (default: the ASSUMED 56.5 cc saw
    curve); requirements: factors a, b; rpm: sweep speeds (default 0..engine max in 125 rpm
    steps); idle_rpm: overrides the engine's idle speed (else the curve's, else 2700 rpm,
    ASSUMED).
    """
    from ..solver import ClutchSolver

    engine = engine or EngineCurve.default()
    req = requirements or Requirements()
    if not isinstance(mu, (int, float)) or not (math.isfinite(mu) and 0.0 <= mu <= 1.0):
        raise ParameterError("mu", mu, "a friction coefficient in [0, 1]")
    if rotation not in ("ccw", "cw"):
        raise ParameterError("rotation", rotation, "'ccw' or 'cw' (hub's sense of rotation)")
    notes: list[str] = []
    warnings: list[str] = []
    if idle_rpm is None:
        idle_rpm = engine.idle_rpm
        if idle_rpm is None:
            idle_rpm = DEFAULT_IDLE_RPM
            notes.append(f"idle speed {DEFAULT_IDLE_RPM:.0f} rpm ASSUMED (the engine curve gives none)")
    if not (isinstance(idle_rpm, (int, float)) and math.isfinite(idle_rpm) and idle_rpm > 0):
        raise ParameterError("idle_rpm", idle_rpm, "an idle speed > 0 rpm")
    lo, hi = engine.rpm_range
    rpm = check_speeds(rpm, engine)
    R, h = _drum_and_thickness(cm, params, drum_radius, thickness)
    kw = dict(drum_radius=R, rotation=rotation, spin_softening=spin_softening, thickness=h)
    fe = ClutchSolver(cm, material, mu=mu, **kw)
    res = fe.sweep(rpm)
    curve = res.curve
    eng = res.engagement_rpm
    fe_torque = lambda x: np.interp(x, curve["rpm"], curve["torque_Nm"])  # noqa: E731
    slip = slip_answer(engine, fe_torque, eng)
    in_range = slip.status != "never engages"
    if in_range:
        eng_r = ripple_mod.effective_engagement_rpm(eng, ripple_model, k_sigma=3.0)
        eng_r0 = ripple_mod.effective_engagement_rpm(eng, ripple_model, k_sigma=0.0)
        eng_note = ("static: steady speed (FE, closed form); with ripple: mean crank speed at which the "
                    "2-stroke speed ripple's peak reaches the static value (3 sigma cycle; typical cycle "
                    "also given); ripple growth with rpm ASSUMED proportional")
    else:
        eng_r = eng_r0 = None
        eng_note = slip.note
    # plus/minus character from the model itself: friction raises (plus) or lowers (minus) N
    probe = float(engine.rpm_max_torque)
    if eng is not None and eng > probe and eng <= hi:
        probe = hi
        notes.append(f"not engaged at the rpm of max engine torque: plus/minus character and mu "
                     f"sensitivity evaluated at {hi:.0f} rpm")
    sw0 = ClutchSolver(cm, material, mu=0.0, **kw).sweep([probe], stresses=False)
    sw1 = fe.sweep([probe], stresses=False)
    per_shoe = []
    if not sw0.shoes.empty:
        for s_ in sorted(set(sw0.shoes["shoe"])):
            n0 = float(sw0.shoes.loc[sw0.shoes["shoe"] == s_, "normal_force_N"].iloc[0])
            n1 = float(sw1.shoes.loc[sw1.shoes["shoe"] == s_, "normal_force_N"].iloc[0])
            per_shoe.append({"shoe": int(s_), "character": _character(n0, n1), "rpm": probe,
                             "normal_force_mu0_N": n0, "normal_force_N": n1,
                             "normal_force_ratio": n1 / n0 if n0 > 0 else math.nan})
        if cm.sector_angle:
            notes.append(f"sector model: shoe 0 stands for all {cm.n_shoes_total} identical shoes")
    chars = sorted({p_["character"] for p_ in per_shoe})
    if not in_range:
        character = "never engages"
    elif len(chars) == 1:
        character = chars[0]
    elif chars:
        character = "mixed: " + ", ".join(chars)
    else:
        character = _character(float(sw0.curve["normal_force_N"].iloc[0]),
                               float(sw1.curve["normal_force_N"].iloc[0]))
    # sensitivity to mu +- 30 %: torque at the probe speed and slip speed
    t_probe = float(sw1.curve["torque_Nm"].iloc[0])
    sens: dict = {"rpm": probe, "mu": mu, "torque_Nm": {"x1.0": t_probe}, "slip_rpm": {"x1.0": slip.rpm}}
    for f in MU_FACTORS:
        key = f"x{f}"
        if mu * f > 1.0:
            notes.append(f"mu x {f} = {mu * f:.3g} > 1: sensitivity point skipped")
            continue
        s_ = ClutchSolver(cm, material, mu=mu * f, **kw).sweep(rpm, stresses=False)
        c_ = s_.curve
        sens["torque_Nm"][key] = float(np.interp(probe, c_["rpm"], c_["torque_Nm"]))
        sens["slip_rpm"][key] = slip_answer(
            engine, lambda x, c_=c_: np.interp(x, c_["rpm"], c_["torque_Nm"]), s_.engagement_rpm).rpm
    if t_probe > 0 and all(f"x{f}" in sens["torque_Nm"] for f in MU_FACTORS):
        t_lo, t_hi = sens["torque_Nm"]["x0.7"], sens["torque_Nm"]["x1.3"]
        sens["torque_change_pct"] = {"x0.7": 100 * (t_lo / t_probe - 1), "x1.3": 100 * (t_hi / t_probe - 1)}
        # d ln M / d ln mu: 1 for a point load (eq 12), < 1 minus shoe, > 1 plus shoe
        sens["elasticity"] = math.log(t_hi / t_lo) / math.log(1.3 / 0.7) if t_lo > 0 else math.nan
    # analytical coupling
    coupling, curves = _coupled_curves(cm, params, material, res, mu, rotation, R, h)
    analytical = bool(coupling.get("kind"))
    if not analytical:
        notes.append("analytical shoe-model curves (eqs 2-8) not available: a user mesh carries no shoe "
                     "pivot or nominal shoe arc (shoe mass from the mesh is reported for information); "
                     "every FE answer (engagement, slip, torque, stress, shoe character, mu sensitivity) "
                     "is given")
    part = mesh_mass_properties(cm, material.rho, h)
    if coupling.get("kind") and character in ("plus", "minus") and coupling["kind"] != character:
        warnings.append(f"the FE model behaves as a {character} shoe but the flexure arrangement "
                        f"suggests a {coupling['kind']} shoe: the analytical curves assume "
                        f"{coupling['kind']}; trust the FE")
    t_nom = float(np.interp(engine.rpm_max_torque, curve["rpm"], curve["torque_Nm"]))
    at = curves.set_index("rpm")
    models = {"rpm": float(engine.rpm_max_torque)}
    for col in ("fe_torque_Nm", "analytic_fe_arc_Nm", "analytic_nominal_arc_Nm"):
        models[col] = float(np.interp(engine.rpm_max_torque, at.index, at[col]))
    arc_probe = float(np.interp(engine.rpm_max_torque, curves["rpm"], curves["contact_arc_deg"]))
    # stress at the engine's maximum speed (the sweep always contains it)
    last = curve.loc[curve["rpm"] == hi].iloc[0]
    sf = float(last["safety_factor"])
    vm = float(last["max_von_mises_Pa"])
    fy = float(material.yield_strength)
    if sf < 1.0:
        warnings.append(f"STRESS ABOVE YIELD: peak von Mises {vm / 1e6:.0f} MPa at {hi:.0f} rpm (engine "
                        f"maximum) exceeds the yield strength {fy / 1e6:.0f} MPa of {material.name} "
                        f"(safety factor {sf:.2f} < 1): this design would yield at full speed")
    elif sf < FATIGUE_CAUTION_SF:
        warnings.append(f"low stress margin: safety factor {sf:.2f} at {hi:.0f} rpm (below "
                        f"{FATIGUE_CAUTION_SF}, an ASSUMED minimum with fatigue in mind)")
    slip_power = None
    if slip.rpm is not None:
        slip_power = float(engine.torque_at(slip.rpm) * rpm_to_rad_s(slip.rpm))
    curves["engine_torque_Nm"] = [float(engine.torque_at(x)) if lo <= x <= hi else math.nan for x in curves["rpm"]]
    curves["normal_force_N"] = curve["normal_force_N"].to_numpy()
    curves["max_von_mises_Pa"] = curve["max_von_mises_Pa"].to_numpy()
    curves["safety_factor"] = curve["safety_factor"].to_numpy()
    nominal = coupling.get("phi2_deg", math.nan) - coupling.get("phi1_deg", math.nan)
    curves["arc_fraction"] = curves["contact_arc_deg"] / nominal if nominal and math.isfinite(nominal) else math.nan
    eng_limit = req.a * idle_rpm
    slip_limit = req.b * engine.rpm_max_torque
    eng_ok = (not in_range) or (eng_r is not None and eng_r > eng_limit)
    slip_ok = slip.rpm is not None and slip.rpm < slip_limit
    checks = {
        "a": req.a, "b": req.b, "idle_rpm": float(idle_rpm), "rpm_max_torque": float(engine.rpm_max_torque),
        "engagement_limit_rpm": eng_limit, "engagement_checked_rpm": eng_r,
        "engagement_checked_with": "engagement with ripple (3 sigma cycle)",
        "slip_limit_rpm": slip_limit,
        "engagement_ok": bool(eng_ok), "slip_ok": bool(slip_ok),
        "assumed": ("a = 1.3 and b = 1.0 are ASSUMED defaults (confidential in the thesis)" if req.assumed
                    else "user factors a, b"),
    }
    if not eng_ok:
        warnings.append(f"REQUIREMENT NOT MET: engagement with ripple {eng_r:.0f} rpm is not above "
                        f"a x idle = {req.a:g} x {idle_rpm:.0f} = {eng_limit:.0f} rpm (chain may move at idle)")
    if not slip_ok:
        got = {"never slips": "never slips", "never engages": "never engages"}.get(
            slip.status, f"slip {slip.rpm:.0f} rpm" if slip.rpm is not None else "no slip speed")
        warnings.append(f"REQUIREMENT NOT MET: {got}; required slip below b x rpm(max torque) = "
                        f"{req.b:g} x {engine.rpm_max_torque:.0f} = {slip_limit:.0f} rpm")
    if engine.assumed:
        notes.append("engine curve: built-in 56.5 cc saw curve; its SHAPE IS ASSUMED (anchors 3.40 N m at "
                     "8000 rpm and 3.20 N m at 9072 rpm from seed 000); use --engine CSV for design work")
    if req.assumed:
        notes.append("requirement factors a = 1.3, b = 1.0 are ASSUMED defaults (the thesis keeps them confidential)")
    eng_info = {"source": engine.source, "assumed_shape": engine.assumed, "rpm_range": list(engine.rpm_range),
                "max_torque_Nm": engine.max_torque, "rpm_max_torque": float(engine.rpm_max_torque),
                "idle_rpm": float(idle_rpm)}
    return Analysis(design=design, engagement_rpm=eng if in_range else None,
                    engagement_rpm_with_ripple=eng_r, engagement_rpm_with_ripple_typical=eng_r0,
                    engagement_note=eng_note,
                    slip_rpm=slip.rpm, slip_status=slip.status, slip_note=slip.note,
                    slip_crossings_rpm=[{"rpm": r, "direction": d} for r, d in slip.crossings],
                    rpm_max_engine_torque=float(engine.rpm_max_torque), max_engine_torque_Nm=engine.max_torque,
                    torque_at_max_engine_torque_Nm=t_nom, torque_margin_Nm=t_nom - engine.max_torque,
                    max_engine_rpm=float(hi), max_von_mises_Pa=vm, safety_factor=sf, max_stress_rpm=float(hi),
                    max_stress_location_m=[float(last["max_vm_x_m"]), float(last["max_vm_y_m"])],
                    yield_strength_Pa=fy, slip_power_W=slip_power, shoe_character=character,
                    shoe_character_per_shoe=per_shoe, mu=float(mu), mu_sensitivity=sens,
                    torque_models_at_max_engine_torque_Nm=models,
                    contact_arc_at_max_engine_torque_deg=arc_probe,
                    requirements=checks, engine=eng_info, coupling=coupling, curves=curves,
                    first_touch=res.first_touch, warnings=warnings, notes=notes, part=part,
                    analytical_available=analytical, first_touch_angle_deg=res.first_touch_angle_deg)


def _drum_and_thickness(cm, params, drum_radius, thickness) -> tuple[float, float]:
    """Drum radius and axial thickness [m]: explicit values, else the concept's, else (user
    mesh) the thickness stored with the mesh; the drum radius has no default for a user mesh."""
    R = drum_radius if drum_radius is not None else (params.drum_radius if params is not None else None)
    if R is None:
        raise ParameterError("drum_radius", None, "the drum's inner radius in m, larger than the outer radius "
                             "of the contact surface: a user mesh carries no drum, and without a drum there "
                             "is no friction torque", context="user mesh")
    h = thickness if thickness is not None else (params.thickness if params is not None else cm.thickness)
    for name, v, what in (("drum_radius", R, "the drum's inner radius, a length > 0 m (metres: 0.035 for 35 mm)"),
                          ("thickness", h, "the axial thickness, a length > 0 m (metres: 0.011 for 11 mm)")):
        if v is None or isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                or not math.isfinite(float(v)) or float(v) <= 0:
            raise ParameterError(name, v, what)
    b = cm.mesh.boundaries or {}
    if params is None and "contact" in b and len(b["contact"]):
        # a units slip (mm for m) or a drum far from the part: no elastic part closes a gap as
        # large as half its own radius (steel yields at ~0.6 % strain)
        r_c = float(np.hypot(*cm.mesh.p[:, cm.mesh.facets[:, b["contact"]].ravel()]).max())
        if R > DRUM_GAP_LIMIT * r_c:
            raise ParameterError("drum_radius", R, f"a radius in m between the contact surface's outer radius "
                                 f"{r_c:.6g} m and {DRUM_GAP_LIMIT:g} x that ({DRUM_GAP_LIMIT * r_c:.6g} m): a larger "
                                 f"gap cannot close elastically (lengths are in metres, not mm)", context="user mesh")
    return float(R), float(h)


def mesh_mass_properties(cm, rho: float, thickness: float) -> dict:
    """Area, mass and centre of mass of the meshed part (and of each ``shoe_<i>`` zone the mesh
    names), by quadrature over the (possibly curved) P2 triangles: mass = area x rho x thickness.

    A one-sector model is scaled to the whole part (``n_shoes_total / n_shoes_model``); its
    centre of mass is then not meaningful and left out.  For a full part, ``unbalance_kg_m``
    = mass x distance of the centre of mass from the rotation axis.
    """
    from skfem import Basis, ElementTriP0, Functional

    mesh = cm.mesh
    basis = Basis(mesh, ElementTriP0(), intorder=4)
    one, fx, fy = (Functional(lambda w: 1.0 + 0.0 * w.x[0]), Functional(lambda w: w.x[0]),
                   Functional(lambda w: w.x[1]))

    def props(elements=None) -> tuple[float, float, float]:
        b = basis if elements is None else Basis(mesh, ElementTriP0(), intorder=4, elements=elements)
        a = float(one.assemble(b))
        return a, float(fx.assemble(b)) / a, float(fy.assemble(b)) / a

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
    sub = mesh.subdomains or {}
    i = 0
    while f"shoe_{i}" in sub and len(sub[f"shoe_{i}"]):
        a, sx, sy = props(np.asarray(sub[f"shoe_{i}"]))
        shoes.append({"shoe": i, "mass_kg": a * rho * thickness, "centroid_m": [sx, sy],
                      "R_Tp_m": math.hypot(sx, sy)})
        i += 1
    if shoes:
        out["shoes"] = shoes
    return out


def contact_extent(res, shoe: int = 0) -> np.ndarray:
    """Angular extent [rad] (start, end) of shoe ``shoe``'s contact at each speed of a sweep.

    The extent runs from the outermost nodes in contact plus half the spacing to the next
    node on each side (each node stands for the boundary up to half-way to its neighbours),
    so a single node in contact has the width of one node spacing instead of zero.  NaN rows
    where the shoe does not touch.  Angles are polar angles of the drum frame.
    """
    nd = res.solver.nodes
    out = np.full((len(res.states), 2), np.nan)
    if nd is None:
        return out
    sel = np.nonzero(nd.shoe == shoe)[0]
    if sel.size == 0:
        return out
    ang = nd.angle[sel]
    ref = float(np.mean(ang))
    ang = ref + (ang - ref + math.pi) % (2 * math.pi) - math.pi  # unwrap around the shoe
    order = np.argsort(ang)
    a = ang[order]
    gaps = np.diff(a)
    lo_half = np.concatenate([[gaps[0] if gaps.size else 0.0], gaps]) / 2  # to the previous node
    hi_half = np.concatenate([gaps, [gaps[-1] if gaps.size else 0.0]]) / 2  # to the next node
    for k, st in enumerate(res.states):
        lam = st.lam[sel][order] if st.lam.size else np.zeros(0)
        on = np.nonzero(lam > 0)[0]
        if on.size == 0:
            continue
        i0, i1 = int(on.min()), int(on.max())
        out[k] = (a[i0] - lo_half[i0], a[i1] + hi_half[i1])
    return out


def _coupled_curves(cm, params, material, res, mu, rotation, R, h):
    """Analytical torque with the nominal arc and with the FE contact arc (per speed);
    R: drum radius [m], h: thickness [m]."""
    rpm = res.curve["rpm"].to_numpy()
    ext = contact_extent(res, 0)
    out = pd.DataFrame({"rpm": rpm, "fe_torque_Nm": res.curve["torque_Nm"].to_numpy(),
                        "contact_arc_deg": np.degrees(np.nan_to_num(ext[:, 1] - ext[:, 0])),
                        "contact_node_span_deg": res.curve["contact_arc_deg"].to_numpy()})
    shoe = cm.mass.get("shoe_0") if cm.mass else None
    if shoe is None or not cm.pivots or not cm.contact_arcs or params is None:
        out["analytic_nominal_arc_Nm"] = math.nan
        out["analytic_fe_arc_Nm"] = math.nan
        return {"source": "no analytical coupling: the design carries no shoe mass properties, "
                          "pivot or nominal arc (user mesh)"}, out
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
    phi1, phi2 = sorted((abs(_wrap(root - th_p)), abs(_wrap(tip - th_p))))
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
        out["analytic_nominal_arc_Nm"] = math.nan
        coupling["nominal_error"] = str(exc)
    # FE contact arc per speed, measured from the pivot ray
    fe_arc = []
    q_deg = np.full((len(rpm), 2), np.nan)
    for k in range(len(rpm)):
        if np.isfinite(ext[k, 0]):
            q = sorted((abs(_wrap(ext[k, 0] - th_p)), abs(_wrap(ext[k, 1] - th_p))))
            q1, q2 = max(q[0], 0.0), min(q[1], math.pi)
            q_deg[k] = np.degrees([q1, q2])
        if not np.isfinite(ext[k, 0]) or F[k] <= 0:
            fe_arc.append(0.0)
            continue
        try:
            fe_arc.append(float(shoe_torque(F[k], ShoeGeometry(q1, q2, A, R, L), mu, kind, n).total))
        except ClutchfemError:
            fe_arc.append(math.nan)
    out["analytic_fe_arc_Nm"] = fe_arc
    out["contact_phi1_deg"] = q_deg[:, 0]  # FE contact extent from the pivot ray (nominal: phi1..phi2)
    out["contact_phi2_deg"] = q_deg[:, 1]
    return coupling, out


def _wrap(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi
