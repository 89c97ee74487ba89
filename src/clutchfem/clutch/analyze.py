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
from .engine import EngineCurve, slip_rpm
from .shoe import ShoeGeometry, shoe_torque


@dataclass
class Requirements:
    """Designer's factors: engagement > a x idle rpm; slip < b x rpm of max engine torque
    (the thesis keeps a, b confidential: these defaults are ASSUMED)."""

    a: float = 1.3
    b: float = 1.0

    def __post_init__(self):
        for name in ("a", "b"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ParameterError(name, v, "a factor > 0")


@dataclass
class Analysis:
    design: str
    engagement_rpm: float | None
    engagement_rpm_with_ripple: float | None
    slip_rpm: float | None
    slip_note: str
    torque_at_max_engine_torque_Nm: float
    torque_margin_Nm: float
    max_von_mises_Pa: float
    safety_factor: float
    max_stress_rpm: float
    slip_power_W: float | None
    shoe_character: str
    mu_sensitivity: dict
    requirements: dict
    coupling: dict
    curves: pd.DataFrame
    first_touch: str | None
    notes: list[str] = field(default_factory=list)

    def to_json(self) -> dict:
        d = {k: v for k, v in self.__dict__.items() if k != "curves"}
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
    return x


def shoe_kind(arrangement: str, rotation: str) -> str:
    """'minus' arrangement turning ccw is a minus shoe; flipping either flips the kind."""
    plus = (arrangement == "plus") == (rotation == "ccw")
    return "plus" if plus else "minus"


def analyze(cm, params, material, *, mu: float = 0.165, rotation: str = "ccw",
            engine: EngineCurve | None = None, requirements: Requirements | None = None,
            rpm=None, spin_softening: str = "modal", design: str = "") -> Analysis:
    """Run the FE sweeps and turn them into engagement / slip / torque / stress answers."""
    from ..solver import ClutchSolver

    engine = engine or EngineCurve.default()
    req = requirements or Requirements()
    lo, hi = engine.rpm_range
    rpm = np.arange(0.0, hi + 1e-9, 125.0) if rpm is None else np.asarray(rpm, dtype=float)
    if rpm.max() > hi or rpm.min() < 0:
        raise ParameterError("rpm", f"{rpm.min():g}..{rpm.max():g}", f"speeds within 0..{hi:g} rpm (engine curve)")
    R = params.drum_radius
    kw = dict(drum_radius=R, rotation=rotation, spin_softening=spin_softening, thickness=params.thickness)
    fe = ClutchSolver(cm, material, mu=mu, **kw)
    res = fe.sweep(rpm)
    notes: list[str] = []
    # plus/minus character from the model itself: friction raises (plus) or lowers (minus) N
    probe = float(engine.rpm_max_torque)
    n0 = ClutchSolver(cm, material, mu=0.0, **kw).sweep([probe], stresses=False).curve["normal_force_N"].iloc[0]
    n1 = fe.sweep([probe], stresses=False).curve["normal_force_N"].iloc[0]
    if n0 <= 0:
        character = "not engaged at the rpm of max engine torque"
    else:
        character = "plus" if n1 > n0 * (1 + 1e-6) else ("minus" if n1 < n0 * (1 - 1e-6) else "neutral")
    sens = {}
    for f in (0.7, 1.3):
        s_ = ClutchSolver(cm, material, mu=mu * f, **kw).sweep([probe], stresses=False)
        sens[f"torque_at_{probe:.0f}rpm_mu_x{f}_Nm"] = float(s_.curve["torque_Nm"].iloc[0])
    t_nom = float(np.interp(probe, res.curve["rpm"], res.curve["torque_Nm"]))
    sens[f"torque_at_{probe:.0f}rpm_mu_x1.0_Nm"] = t_nom
    # analytical coupling
    coupling, curves = _coupled_curves(cm, params, material, res, mu, rotation)
    eng = res.engagement_rpm
    eng_r = ripple_mod.effective_engagement_rpm(eng, k_sigma=3.0) if eng else None
    fe_torque = lambda x: np.interp(x, res.curve["rpm"], res.curve["torque_Nm"])
    s_rpm = slip_rpm(engine, fe_torque)
    if s_rpm is None:
        slip_note = "never slips within the engine curve: clutch torque stays below engine torque (engine runs to max rpm)"
    elif eng is not None and s_rpm <= max(lo, eng):
        slip_note = "clutch already holds the engine torque at engagement"
    else:
        slip_note = "clutch torque meets the engine curve"
    if eng is None:
        slip_note = "never engages within the speed range"
    # stress at engine max rpm
    last = res.curve.iloc[-1]
    slip_power = None
    if s_rpm is not None:
        slip_power = float(engine.torque_at(s_rpm) * rpm_to_rad_s(s_rpm))
    curves["engine_torque_Nm"] = [float(engine.torque_at(x)) if lo <= x <= hi else math.nan for x in curves["rpm"]]
    checks = {
        "a": req.a, "b": req.b, "idle_rpm": engine.idle_rpm, "rpm_max_torque": float(engine.rpm_max_torque),
        "engagement_ok": bool(eng_r is not None and eng_r > req.a * engine.idle_rpm),
        "slip_ok": bool(s_rpm is not None and s_rpm < req.b * engine.rpm_max_torque),
        "assumed": "a and b are confidential in the thesis; defaults assumed",
    }
    return Analysis(design=design, engagement_rpm=eng, engagement_rpm_with_ripple=eng_r,
                    slip_rpm=s_rpm, slip_note=slip_note,
                    torque_at_max_engine_torque_Nm=t_nom, torque_margin_Nm=t_nom - engine.max_torque,
                    max_von_mises_Pa=float(last["max_von_mises_Pa"]), safety_factor=float(last["safety_factor"]),
                    max_stress_rpm=float(last["rpm"]), slip_power_W=slip_power, shoe_character=character,
                    mu_sensitivity=sens, requirements=checks, coupling=coupling, curves=curves,
                    first_touch=res.first_touch, notes=notes)


def _coupled_curves(cm, params, material, res, mu, rotation):
    """Analytical torque with the nominal arc and with the FE contact arc (per speed)."""
    shoe = cm.mass["shoe_0"]
    rho_h = material.rho * params.thickness
    m = shoe["area"] * rho_h
    cx, cy = shoe["centroid"]
    R_Tp = math.hypot(cx, cy)
    px, py = cm.pivots[0]
    A = math.hypot(px, py)
    # lever of the radial apply force (through the centre of mass) about the pivot
    L = abs(px * cy - py * cx) / R_Tp
    R = params.drum_radius
    root, tip = cm.contact_arcs[0]
    th_p = math.atan2(py, px)
    phi1, phi2 = sorted((abs(_wrap(root - th_p)), abs(_wrap(tip - th_p))))
    kind = shoe_kind(params.arrangement, rotation)
    n = cm.n_shoes_total
    w_e = None if res.engagement_rpm is None else rpm_to_rad_s(res.engagement_rpm)
    F_f = m * R_Tp * w_e ** 2 if w_e else math.nan
    coupling = {"m_kg": m, "R_Tp_m": R_Tp, "F_f_N": F_f, "A_m": A, "L_m": L, "R_m": R,
                "phi1_deg": math.degrees(phi1), "phi2_deg": math.degrees(phi2), "kind": kind,
                "source": "m, R_Tp: OCC mass properties; F_f: FE engagement speed (eq 1); A, L: geometry "
                          "(pivot = flexure centre); phi: nominal arc from the pivot ray"}
    rpm = res.curve["rpm"].to_numpy()
    w = rpm_to_rad_s(rpm)
    F = np.where(np.isfinite(F_f), np.maximum(m * R_Tp * w ** 2 - (F_f if np.isfinite(F_f) else 0), 0.0), 0.0)
    out = pd.DataFrame({"rpm": rpm, "fe_torque_Nm": res.curve["torque_Nm"].to_numpy(),
                        "contact_arc_deg": res.curve["contact_arc_deg"].to_numpy()})
    try:
        geom = ShoeGeometry(phi1, phi2, A, R, L)
        out["analytic_nominal_arc_Nm"] = shoe_torque(F, geom, mu, kind, n).total
    except ClutchfemError as exc:
        out["analytic_nominal_arc_Nm"] = math.nan
        coupling["nominal_error"] = str(exc)
    # FE contact arc per speed, measured from the pivot ray
    fe_arc = []
    shoes = res.shoes
    for k, r_ in enumerate(rpm):
        row = shoes[(shoes["rpm"] == r_) & (shoes["shoe"] == 0)] if not shoes.empty else shoes
        if row.empty or not np.isfinite(row["arc_start_deg"].iloc[0]) or F[k] <= 0:
            fe_arc.append(0.0)
            continue
        a0 = math.radians(row["arc_start_deg"].iloc[0])
        a1 = math.radians(row["arc_end_deg"].iloc[0])
        q1, q2 = sorted((abs(_wrap(a0 - th_p)), abs(_wrap(a1 - th_p))))
        if q2 - q1 < 1e-6:  # a single node in contact: give it the node spacing
            q2 = q1 + math.radians(0.5)
        try:
            fe_arc.append(float(shoe_torque(F[k], ShoeGeometry(q1, q2, A, R, L), mu, kind, n).total))
        except ClutchfemError:
            fe_arc.append(math.nan)
    out["analytic_fe_arc_Nm"] = fe_arc
    return coupling, out


def _wrap(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi
