"""The torque/speed steps: slip speed, FE sweep, engagement, plus/minus character and mu
sensitivity, all from the exact FE torque of one design.

* :func:`slip_step`: the slip speed with the drum held, from the *exact* FE torque
  (:class:`FETorque`: each speed one small contact solve with the design's one
  factorisation); crossings with the engine curve are bracketed on a fixed internal grid
  (:func:`bracket_grid`) and refined by bisection with FE solves, so the answer does not
  depend on the speeds the user asked to tabulate; :func:`slip_answer` classifies it
  (slips, holds at start, never holds, never engages);
* :func:`fe_sweep`: the FE speed sweep with stresses on the output speeds
  (:func:`check_speeds`), to which the engagement and slip speeds, the rpm of maximum engine
  torque and the engine's maximum speed are added (every answer is read at a solved speed,
  never interpolated);
* :func:`engagement_step`: static engagement (FE, closed form) and with the 2-stroke ripple;
* :func:`character_step`: plus/minus character per shoe: the normal force with and without
  friction at the probe speed (:func:`probe_speed`: the rpm of maximum engine torque);
* :func:`mu_sensitivity_step`: torque and slip speed at mu x 0.7 and x 1.3;
* :func:`contact_sets_step`: which contact nodes carry load at the speeds the contact answers
  are read at (slip speed, rpm of maximum engine torque, engine's maximum speed): designs
  morphed from one reference share the node numbering, so a change of these sets between
  neighbouring designs marks a kink of those answers (the slope jumps where a node enters
  or leaves the contact zone), which design sensitivities report.

Friction off and mu +-30 % are load cases of the same design (:func:`secondary_case`): the
same model and factorisation, one shared Ritz space.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..clutch import EngineCurve, effective_engagement_rpm, first_slip_rpm, holds, torque_crossings
from ..core import ClutchfemError, ParameterError, rpm_to_rad_s
from ..softening import get_softening
from .answers import CharacterAnswer, EngagementAnswer, MuSensitivity, SlipAnswer

#: Friction factors of the mu sensitivity study (mu +- 30 %).
MU_FACTORS = (0.7, 1.3)
#: spacing [rpm] of the internal grid on which clutch/engine crossings are bracketed (then
#: refined by bisection with exact FE solves); also the default output spacing
GRID_RPM = 125.0
#: the same for the mu +-30 % sensitivity cases (two crossings closer than this could merge
#: there; the answer itself is refined to 1e-9 like the main one)
GRID_RPM_SENSITIVITY = 250.0


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


def check_speeds(rpm, engine: EngineCurve) -> np.ndarray:
    """The output speeds [rpm]: finite, >= 0, within 0..max rpm of the engine curve, sorted,
    and always including the engine's maximum speed (where stresses are reported) and the
    rpm of its maximum torque (where torque, arc and character are reported).

    Parameters
    ----------
    rpm : sequence of float or None
        The speeds asked for [rpm] (None: 0 to the engine's maximum in 250 rpm steps).
    engine : EngineCurve
        The full-throttle curve; speeds above its last one are refused
        (:class:`~clutchfem.ParameterError`).

    Returns
    -------
    numpy.ndarray
        The sorted speeds [rpm], the engine's two reporting speeds added.

    Examples
    --------
    >>> import clutchfem as cf
    >>> e = cf.EngineCurve((2500, 8000, 14000), (1.9, 3.4, 1.0))
    >>> cf.check_speeds([5000, 0], e).tolist()
    [0.0, 5000.0, 8000.0, 14000.0]
    """
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
    range in ``step`` rpm steps plus the engine table's own speeds when the table is not
    denser than the grid (fixed: independent of the speeds the user tabulates; a dense
    table's every row used to become a contact solve: a 1e6-row curve ran for minutes)."""
    lo, hi = engine.rpm_range
    base = np.append(np.arange(lo, hi, step), hi)
    return np.union1d(base, engine.rpm) if len(engine.rpm) <= len(base) else base


def _character(n_mu0: float, n_mu: float) -> str:
    """plus / minus / neutral from a shoe's normal force without (``n_mu0``) and with friction."""
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
                self.memo[x] = self.case.friction_torque(lam)
            out.flat[k] = self.memo[x]
        return out


def fe_sweep(design, speeds):
    """The FE sweep with stresses at the output ``speeds`` [rpm] (a
    :class:`~clutchfem.loadcase.SweepResult`)."""
    return design.sweep(speeds, stresses=True)


#: the contact answers -> the speeds they are read at (:func:`contact_sets_step`'s keys); the
#: fatigue factor's service states are at the operating speed (the rpm of maximum engine
#: torque) and the maximum speed (its friction-off and ripple states are other cases: their
#: own contact events are not tracked)
CONTACT_SPEED_OF = {"slip_rpm": ("slip",), "torque_at_max_engine_torque_Nm": ("torque",),
                    "contact_arc_deg": ("torque",), "max_von_mises_Pa": ("peak",), "safety_factor": ("peak",),
                    "fatigue_safety_factor": ("torque", "peak")}


def contact_sets_step(case, speeds: dict) -> dict:
    """Per label of ``speeds`` (label -> rpm or None) the indices of the contact nodes with a
    positive force in the solved state of ``case`` at that speed (sorted list; [] below
    engagement; None where the speed is None or the state has no solution).  Solved states
    are memoised, so the slip speed's and the torque speed's cost nothing; the engine's
    maximum speed is one contact solve of the linear (Ritz) case, also where the peak stress
    was re-solved per speed: the sets only locate kinks, they are no answer."""
    out = {}
    for label, rpm in speeds.items():
        if rpm is None or not math.isfinite(rpm):
            out[label] = None
            continue
        try:
            lam, _ = case.solve(rpm_to_rad_s(float(rpm)))
        except ClutchfemError:
            out[label] = None
            continue
        out[label] = [int(i) for i in np.flatnonzero(np.asarray(lam) > 0)]
    return out


def engagement_step(res, ripple_model, in_range: bool, slip: SlipAnswer) -> EngagementAnswer:
    """Static engagement and the crank speed at which the ripple's peak reaches it.  The
    engagement speed is the part's (the FE's closed form): it does not depend on the engine,
    so a curve that ends below it still gets it (``in_range`` False: the note says the
    clutch never engages on this engine; issue 24: it used to say "never engages" with no
    speed).  None only when the shoes never reach the drum at all."""
    eng = res.engagement_rpm
    if eng is None:
        return EngagementAnswer(None, None, None, slip.note)
    note = ("static: steady speed (FE, closed form); with ripple: mean crank speed at which the 2-stroke "
            "speed ripple's peak reaches the static value (3 sigma cycle; typical cycle also given); ripple "
            "growth with rpm ASSUMED proportional")
    if not in_range:
        note = f"{slip.note}; the engagement speed is the part's own (it does not depend on the engine): {note}"
    return EngagementAnswer(eng, effective_engagement_rpm(eng, ripple_model, k_sigma=3.0),
                            effective_engagement_rpm(eng, ripple_model, k_sigma=0.0), note)


def slip_step(case, engine: EngineCurve, step: float = GRID_RPM) -> SlipAnswer:
    """Slip speed from the exact FE torque of ``case`` (see module docstring); crossings are
    bracketed every ``step`` rpm and then refined to 1e-9."""
    return slip_answer(engine, FETorque(case), case.engagement_rpm, grid=bracket_grid(engine, step))


def secondary_case(design, mu: float):
    """The load case of a secondary friction coefficient (friction off, mu +-30 %): the
    design's softening, with one Ritz space for all of them (seeded by both contact load
    parts, :class:`~clutchfem.softening.Ritz` ``seeds='all'``) instead of one each, built as
    the extension of the design's own space (``base_mu``: only the tangential seeds are
    back-solved)."""
    soft = get_softening(design.op.softening)
    if hasattr(soft, "seeds"):  # Ritz and PrestressRitz
        soft = replace(soft, seeds="all", base_mu=float(design.op.mu))
    return design.case(mu=mu, softening=soft)


def probe_speed(res, engine: EngineCurve) -> float:
    """The speed [rpm] at which character and mu sensitivity are evaluated: the rpm of maximum
    engine torque, or the engine's maximum speed when the clutch engages only above it (but
    within the engine's range)."""
    probe = float(engine.rpm_max_torque)
    hi = engine.rpm_range[1]
    if res.engagement_rpm is not None and res.engagement_rpm > probe and res.engagement_rpm <= hi:
        probe = hi
    return probe


def character_step(design, probe: float) -> CharacterAnswer:
    """Per shoe, normal force with friction (the design's mu) and without, at ``probe``
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


def mu_sensitivity_step(design, engine: EngineCurve, probe: float, slip: SlipAnswer) -> MuSensitivity:
    """Torque at ``probe`` and slip speed at mu x 0.7 and x 1.3 (same FE model).  A side
    case never takes the main answers with it: a factor that would make mu > 1, or whose
    solve is refused (a plus shoe that self-locks at mu x 1.3), is marked not available in
    ``not_available`` with its reason and said so in the answer's ``notes``."""
    notes: list[str] = []
    missing: dict[str, str] = {}
    mu = design.op.mu
    t_probe = float(FETorque(design.case())(probe)[0])
    torque, slips = {"x1.0": t_probe}, {"x1.0": slip.rpm}
    for f in MU_FACTORS:
        key = f"x{f}"
        if mu * f > 1.0:
            missing[key] = f"mu x {f} = {mu * f:.3g} > 1 (outside the friction model)"
            notes.append(f"mu x {f} = {mu * f:.3g} > 1: sensitivity point skipped")
            continue
        case = secondary_case(design, mu * f)
        try:
            # the contact solves start from the design's own contact nodes at the same speed
            t_f = float(FETorque(case, start=design.case())(probe)[0])
            # the slip speed only (no later crossings): the grid walk stops at the answer
            s_f = first_slip_rpm(engine, FETorque(case, start=design.case()),
                                 bracket_grid(engine, GRID_RPM_SENSITIVITY))
        except ClutchfemError as exc:
            missing[key] = f"mu x {f} = {mu * f:.3g}: {exc}"
            notes.append(f"mu sensitivity at mu x {f} = {mu * f:.3g} not available (the main answers at mu = "
                         f"{mu:.3g} stand): {exc}")
            continue
        torque[key], slips[key] = t_f, s_f
    if t_probe > 0 and all(f"x{f}" in torque for f in MU_FACTORS):
        t_lo, t_hi = torque["x0.7"], torque["x1.3"]
        pct = {"x0.7": 100 * (t_lo / t_probe - 1), "x1.3": 100 * (t_hi / t_probe - 1)}
        # d ln M / d ln mu: 1 for a point load (eq 12), < 1 minus shoe, > 1 plus shoe
        el = math.log(t_hi / t_lo) / math.log(1.3 / 0.7) if t_lo > 0 else math.nan
        return MuSensitivity(probe, mu, torque, slips, pct, el, notes=tuple(notes), not_available=missing)
    return MuSensitivity(probe, mu, torque, slips, notes=tuple(notes), not_available=missing)
