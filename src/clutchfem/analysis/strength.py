"""The strength steps: peak stress against yield, and fatigue under the service cycles.

* :func:`stress_step`: peak von Mises stress and the safety factor against yield at the
  engine's maximum speed, read from the FE sweep (raw vertex stresses, the peak over the part);
* :func:`fatigue_step`: the fatigue safety factor (Goodman, Marin-corrected endurance limit,
  Basquin + Miner: :mod:`clutchfem.durability`) at the worst point, named, under start-stop
  and running-revolution cycles built from solved states (:func:`fatigue_cycles`).

The glue between the FE states and the durability stage: the cycles need the stresses and
torques of the full-slip case at the operating speed w_o (1 -+ delta_max), w_o and the
maximum speed, and of the frictionless case at the same speeds (a handful of memoised
contact solves on the design's one factorisation, :func:`_fatigue_states`); the check is
screened so that the cycles are built only at the points that can be the worst.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..accuracy import AnswerNonlinearity, answer_nonlinearity
from ..clutch import EngineCurve, RippleModel
from ..core import ParameterError, SolverError, rpm_to_rad_s
from ..durability import (
    FatigueLoads,
    FatigueParams,
    LoadCycle,
    ServiceStates,
    candidate_points,
    endurance_limit,
    fatigue_check,
    ripple_classes,
    service_cycles,
    single_cycle_factor,
)
from ..fe import von_mises
from .answers import FatigueAnswer, StressAnswer
from .torque import secondary_case

#: points with the smallest lower bound of the fatigue factor whose cycles are built first
#: (their smallest factor bounds the part's: the screen of fatigue_step)
FATIGUE_PROBE_POINTS = 32
#: the pre-stress Ritz residual at the peak stress's speed from which the peak is re-solved
#: with the per-speed factorisation (:func:`peak_sweep`: it costs an engagement search and a
#: factorisation per speed, ~1-10 s); below it the peak's band carries
#: :data:`~.error_band.PEAK_RESIDUAL_FACTOR` x the residual (concept 4's default: 1.4e-4)
PEAK_RESIDUAL_EXACT = 5e-4


def peak_sweep(design, res, rpm: float):
    """(the sweep to read the peak stress at ``rpm`` from, whether it is a per-speed re-solve):
    ``res``, or where the pre-stress Ritz space leaves a relative equilibrium residual of at
    least :data:`PEAK_RESIDUAL_EXACT` there, the same design solved at ``rpm`` alone with the
    per-speed factorisation (``prestress-exact``: one factorisation of K - w^2 (M - K_sigma1)).
    The residual is the displacement error the space leaves, but the peak stress's error is
    local: measured 0.6-15x the residual (concept 3.1 and the soft concept4-lhs06 against the
    per-speed solve, 6000-14 000 rpm: 3.5 % at a residual of 3.4e-3, 0.7 % at 4.8e-4), while
    the contact forces stay within 1e-5."""
    if design.op.softening != "prestress" or "residual" not in res.curve:
        return res, False
    r = float(np.interp(rpm, res.rpm, res.curve["residual"].to_numpy()))
    if r < PEAK_RESIDUAL_EXACT:
        return res, False
    return design.with_softening("prestress-exact").sweep([rpm]), True


def stress_step(res, rpm: float, material) -> StressAnswer:
    """Peak von Mises and safety factor against yield at the sweep speed ``rpm`` of ``res``."""
    row = res.curve.iloc[res.index(rpm)]
    return StressAnswer(float(rpm), float(row["max_von_mises_Pa"]), float(row["safety_factor"]),
                        (float(row["max_vm_x_m"]), float(row["max_vm_y_m"])), float(material.yield_strength))


def best_estimate(design) -> bool:
    """Whether ``design`` is a best-estimate model whose peak stress and torque get their
    geometric non-linearity corrected (:func:`nonlinearity_step`): the thick plane model with an
    elastic drum and the pre-stress softening (``fidelity="best"``'s model); the fast path
    keeps its band."""
    op = design.op
    return (op.model_formulation == "thick" and bool(op.drum_wall_m)
            and op.softening in ("prestress", "prestress-exact"))


def nonlinearity_step(design, peak_rpm: float, torque_rpm: float | None
                      ) -> tuple[dict[str, AnswerNonlinearity] | None, str | None]:
    """(the geometric non-linearity of the peak stress at ``peak_rpm`` and of the torque at
    ``torque_rpm``, or None; why not) for a best-estimate ``design`` (:func:`best_estimate`;
    :func:`~clutchfem.accuracy.answer_nonlinearity`).  A non-linear state that does not
    converge leaves the answers uncorrected, with the reason: their bands then carry the
    measured bound instead."""
    if not best_estimate(design):
        return None, None
    try:
        return answer_nonlinearity(design, peak_rpm, torque_rpm), None
    except SolverError as exc:
        return None, (f"peak stress and torque not corrected for geometric non-linearity ({exc}): their bands "
                      "carry the measured bound instead")


def fatigue_cycles(design, res, engine: EngineCurve, loads=None,
                   ripple_model: RippleModel | None = None, points=None):
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
    st, kw, ripple = _fatigue_states(design, res, engine, loads, ripple_model)
    cs = service_cycles(st, points=points, **kw)
    cs.info["ripple"] = ripple
    return cs


def _fatigue_states(design, res, engine: EngineCurve, loads=None,
                    ripple_model: RippleModel | None = None):
    """(ServiceStates, the other arguments of service_cycles, ripple info) of
    :func:`fatigue_cycles`."""
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
    rm = ripple_model or RippleModel()
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
    Mf = np.array([cf.friction_torque(lam, mu) for lam in lamf])
    k_max = res.find(rpm_max)
    lam_fmax = res.lam[k_max] if k_max is not None else cf.solve(float(w_max))[0]
    lam0 = [c0.solve(float(x), a if a.any() else None)[0]
            for x, a in zip(np.append(w, w_max), [lam > 0 for lam in lamf] + [lam_fmax > 0])]
    M0 = np.array([c0.friction_torque(lam, mu) for lam in lam0])
    S0 = c0.stresses(np.append(w, w_max), np.vstack(lam0))
    k_o = res.find(rpm_o)
    Sf_o = (res.fields.stresses(slice(k_o, k_o + 1))[..., 0] if k_o is not None
            else cf.stresses(w[1:2], lamf[1][None])[..., 0])
    if k_max is not None:
        Sf_max = res.fields.stresses(slice(k_max, k_max + 1))[..., 0]
        Mf_max = float(res.curve["torque_Nm"].iloc[k_max])
    else:
        Sf_max = cf.stresses([w_max], lam_fmax[None])[..., 0]
        Mf_max = cf.friction_torque(lam_fmax, mu)
    st = ServiceStates(omegas=w, S0=np.moveaxis(S0[..., :3], 2, 0), Sf_o=Sf_o, Mf=Mf, M0=M0[:3],
                       omega_max=w_max, S0_max=S0[..., 3], Sf_max=Sf_max, Mf_max=Mf_max, M0_max=float(M0[3]))
    kw = dict(delta_classes=classes, cutting_torque=m_o, inertia=loads.drive_inertia,
              max_speed_torque=float(engine.torque_at(rpm_max)), start_stops=loads.start_stops,
              samples=loads.samples)
    ripple = {"delta_mean": float(rm.delta_mean(rpm_o)), "delta_std": float(rm.delta_std(rpm_o)),
              "assumed": list(rm.assumed)}
    return st, kw, ripple


def fatigue_step(design, res, engine: EngineCurve, *, loads=None, params=None,
                 ripple_model: RippleModel | None = None) -> FatigueAnswer:
    """Fatigue safety factor under the service cycles of :func:`fatigue_cycles`,
    checked by :func:`clutchfem.durability.fatigue.fatigue_check` (Goodman, Marin-corrected
    endurance limit, Basquin + Miner) at every element vertex: the cycles are built only at
    the points a closed-form lower bound of the factor cannot rule out (bounds of every
    cycle's amplitude and mean, :class:`~clutchfem.durability.cycles.CycleSet`), the exact
    check runs on those :func:`~clutchfem.durability.fatigue.candidate_points` leaves (the
    same worst point as checking all; tested).  ``params``:
    :class:`~clutchfem.durability.fatigue.FatigueParams` (default: 51CrV4 with the design
    material's yield strength; another material needs its own, else the answer is 'not
    available')."""
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
    try:
        st, kw, ripple = _fatigue_states(design, res, engine, loads, ripple_model)
    except SolverError as exc:  # a service state the model cannot solve: the other answers stand
        return FatigueAnswer(None, None, None, {
            "available": False, "reason": f"a service state of the fatigue cycles has no solution ({exc}): the "
            "friction-off and ripple states are solved at the operating and maximum speeds"})
    t1 = time.perf_counter()
    # Which points can be the worst, exactly, before any cycle is built (the chord searches
    # are the cost): with upper bounds of every cycle's amplitude and mean at a point
    # (service_cycles' bounds), the closed-form lower bound L(p) of candidate_points holds
    # with them too (the single-type factor falls with both); the cycles of the K points with
    # the smallest L give an upper bound U of the smallest factor, and only points with
    # L <= U are kept.  On those, the closed-form screen with the true amplitudes and means
    # (candidate_points) and the exact check.
    pts = model.stress.points
    elem = model.stress.element  # the 2-D element under each stress point
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
        return cs, fatigue_check(sub, params, xy=pts[:2, points[cand]], cm=design.cm,
                                 element=elem[points[cand]]), cand

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
    if getattr(model, "szz_factor", 0.0):
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
