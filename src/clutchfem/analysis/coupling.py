"""Coupling with the analytical shoe model: the thesis's torque (eqs 1-8,
:mod:`clutchfem.clutch.shoe`) next to the FE torque, and the curves of the answer.

FE -> analytical coupling (:func:`coupling_step`):

* shoe mass m and centre-of-mass radius R_Tp: OCC-exact mass properties of the shoe zone;
* effective spring force F_f = m R_Tp w_e^2 from the FE engagement speed w_e (eq 1 inverted:
  the FE flexure is reduced to the force it exerts at engagement), so the apply force is
  F = m R_Tp w^2 - F_f (eq 3, :func:`~clutchfem.clutch.apply_force`);
* pivot distance A and lever L *from the geometry*: the pivot is the flexure's compliant
  centre reported by the concept; L is the distance from the pivot to the radial line of
  action of the centrifugal apply force through the shoe's centre of mass;
* lining angles phi_1, phi_2 measured from the pivot ray: the *nominal* full shoe arc (what
  the thesis did) or the arc in contact in the FE solution at each speed;
* plus or minus shoe from the flexure arrangement and the sense of rotation
  (:func:`~clutchfem.clutch.shoe_kind`).

Three torque curves come out side by side: FE direct (sum of mu * contact force * R_d),
analytical with the FE contact arc, analytical with the nominal arc.  The difference between
the last two is the thesis's error mechanism (contact on a fraction of the arc).  A user mesh
carries no shoe zone, pivot or nominal arc: its analytical curves are NaN.

:func:`answer_curves` adds the engine torque, the FE normal force and stress and the share of
the nominal arc in contact to these columns: the curves table of the answer.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..clutch import EngineCurve, ShoeGeometry, apply_force, arc_torque, shoe_kind, shoe_torque
from ..core import ClutchfemError, rpm_to_rad_s, wrap_angle


def coupling_step(design, res) -> tuple[dict, pd.DataFrame]:
    """(coupling, curves): the coupling's parameters and sources (module docstring), and per
    sweep speed of ``res`` the FE torque, contact arc and the analytical torque with the
    nominal arc and with the FE contact arc."""
    cm, params, material = design.cm, design.params, design.model.material
    R, h = design.drum_radius, design.thickness
    mu, rotation = design.op.mu, design.op.rotation
    rpm = res.rpm
    ext = res.contact_extent(0)
    out = {"rpm": rpm, "fe_torque_Nm": res.curve["torque_Nm"].to_numpy(),
           "contact_arc_deg": np.degrees(np.nan_to_num(ext[:, 1] - ext[:, 0])),  # the columns
           "contact_arc_error_deg": np.degrees(np.nan_to_num(ext[:, 2] + ext[:, 3]))}
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
    F_f = m * R_Tp * w_e ** 2 if w_e else math.nan  # eq 1 inverted
    coupling = {"m_kg": m, "R_Tp_m": R_Tp, "F_f_N": F_f, "A_m": A, "L_m": L, "R_m": R,
                "phi1_deg": math.degrees(phi1), "phi2_deg": math.degrees(phi2), "kind": kind, "n": n,
                "source": "m, R_Tp: OCC mass properties of the shoe zone; F_f: from the FE engagement "
                          "speed (eq 1 inverted); A, L: geometry (pivot = flexure's compliant centre, "
                          "not fitted); phi: nominal shoe arc, measured from the pivot ray; FE arc: "
                          "its ends between the nodes, from the gap and the pressure interpolated along "
                          "the P2 boundary (clutchfem.contact.arc)"}
    # apply force per shoe (eq 3; none without an engagement speed)
    F = apply_force(rpm_to_rad_s(rpm), m, R_Tp, F_f) if math.isfinite(F_f) else np.zeros(len(rpm))
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


def torque_models(res, curves: pd.DataFrame, rpm: float) -> tuple[dict, float]:
    """({"rpm", "fe_torque_Nm", "analytic_fe_arc_Nm", "analytic_nominal_arc_Nm"}, contact arc
    [deg]) at the sweep speed ``rpm`` of ``res`` (the rpm of maximum engine torque)."""
    k = res.index(rpm)
    models = {"rpm": rpm}
    for col in ("fe_torque_Nm", "analytic_fe_arc_Nm", "analytic_nominal_arc_Nm"):
        models[col] = float(curves[col].iloc[k])
    return models, float(curves["contact_arc_deg"].iloc[k])


def answer_curves(res, curves: pd.DataFrame, coupling: dict, engine: EngineCurve) -> pd.DataFrame:
    """The curves of the answer, one row per sweep speed: the coupling's columns plus the
    engine torque (NaN outside its speed range), the FE normal force, peak von Mises stress
    and safety factor, and the share of the nominal shoe arc in contact."""
    lo, hi = engine.rpm_range
    r_c = curves["rpm"].to_numpy(dtype=float)
    inside = (r_c >= lo) & (r_c <= hi)
    e_t = np.full(len(r_c), math.nan)
    e_t[inside] = engine.torque_at(r_c[inside])
    nominal = coupling.get("phi2_deg", math.nan) - coupling.get("phi1_deg", math.nan)
    arc = curves["contact_arc_deg"].to_numpy()
    return pd.DataFrame({  # (one frame: column by column inserts cost ~0.1 ms each)
        **{c: curves[c].to_numpy() for c in curves.columns}, "engine_torque_Nm": e_t,
        "normal_force_N": res.curve["normal_force_N"].to_numpy(),
        "max_von_mises_Pa": res.curve["max_von_mises_Pa"].to_numpy(),
        "safety_factor": res.curve["safety_factor"].to_numpy(),
        "arc_fraction": arc / nominal if nominal and math.isfinite(nominal) else np.full(len(arc), math.nan)})
