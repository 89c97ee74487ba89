"""The clutch over its life (:func:`life`): starts, slip energy, wear-in of the contact arc and
the drift of engagement, from one design's FE contact.

Per worn state (:class:`~.state.WornModel`: the worn depths open the rest gaps of the one
factorised model; the part is rebuilt with its worn profile every ``rebuild_depth`` of wear):

1. the clutch torque and the contact pressure along the shoe against the engine speed
   (FE contact solves on a speed grid from below engagement to the rev limiter), the
   engagement and slip speeds, the torque and contact arc at the rpm of maximum engine
   torque;
2. the starts (:func:`~clutchfem.durability.engagement_transient`): one free start (the
   chain's drag) and, with a duty cycle's cutting share, one in the cut; their slip energy,
   time to lock-up, peak slip power, engine droop and the shoe-face temperature rise
   (:func:`~clutchfem.durability.start_heating`);
3. the wear rate per start (:func:`~clutchfem.durability.wear_rate`): the starts' sliding-
   pressure integrals and, with a duty cycle, its held-drum slips per start (the pressure at
   the slip speed, sliding at the slip speed for the slip's duration), shoe and drum.

The worn depths are integrated over the starts with the controlled wear step of
:func:`~clutchfem.durability.integrate_wear`: no node wears more in one step than
``wear.max_step`` and the step changes the wear rate (linearised with the contact
Jacobian) by no more than ``wear.rate_change`` times the largest rate.  The contact's
elastic give (the worn depth that would unload a loaded node, p_i / |dp_i/dw_i|, weighted
by the wear each node takes) is reported per state (``wear_steps.elastic_give_m``).  Requirements: engagement > a x idle and slip
< b x rpm of maximum engine torque (:class:`~clutchfem.analysis.Requirements`), the first
number of starts at which one is missed interpolated between the states.  Band: the
answers depend on Archard's k / H only through n k / H (:mod:`clutchfem.durability.wear`),
so the starts at which a requirement is missed scale exactly with k over its band, and
the answers at N starts with k at the ends of its band are the run's own answers at
N k_end / k where the run reaches them.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..analysis import Requirements, idle_speed
from ..clutch import EngineCurve
from ..core import ParameterError
from ..durability import DriveLine, WearParams, engagement_transient, integrate_wear, start_heating, wear_rate
from ..durability.engagement import LIMITER_SHARE
from ..loadcase import Design
from .duty import DutyCycle
from .result import Life
from .state import WornModel, rebuild, state_fields

__all__ = ["life"]

#: speeds of the clutch torque / pressure table of a worn state
GRID = 64
#: arc fractions along the shoe at which the worn profile is reported
PROFILE_S = np.linspace(0.0, 1.0, 41)
#: default worn depth between two rebuilds of the part [m] (benchmarks/bench_life.py)
REBUILD_DEPTH = 0.1e-3
#: relative tolerance of the starts' integration (their energy balance closes to ~1e-8)
RTOL = 1e-8
#: relative change of the starts' sliding speed or patch length after which the heat
#: partition is evaluated again
PARTITION_CHANGE = 0.1


class _Holder:
    """The current worn model (replaced at a rebuild) and what the run counts."""

    def __init__(self, model: WornModel):
        self.model = model
        self.built = np.zeros(model.m)
        self.rebuilds: list[float] = []
        self.max_balance = 0.0
        self.count = 0
        self.partition = None  # (sliding speed, patch length, fraction) of the last partition


def life(design, *, starts: float = 100_000, duty: DutyCycle | None = None, engine: EngineCurve | None = None,
         drive: DriveLine | None = None, wear: WearParams | None = None, requirements: Requirements | None = None,
         idle_rpm: float | None = None, rebuild_depth: float | None = REBUILD_DEPTH, fields: int = 0,
         log=None) -> Life:
    """The clutch over ``starts`` starts (module docstring).

    Parameters
    ----------
    design : Design
        The design (a concept's, to rebuild the worn part; a user mesh wears in its gaps only).
    starts : float
        Number of starts of the life (1..1e8).
    duty : DutyCycle, optional
        Held-drum slips, cutting share and hours (None: starts only, chain running free).
    engine : EngineCurve, optional
    drive : DriveLine, optional
        Inertias, loads and throttle ramp of the starts (ASSUMED defaults).
    wear : WearParams, optional
        Archard's coefficients and the wear-step control (ASSUMED defaults).
    requirements : Requirements, optional
    idle_rpm : float, optional
    rebuild_depth : float or None
        Worn depth [m] after which the part is rebuilt with its worn profile (None: never;
        the wear is then kept in the contact gaps of the new part's model).
    fields : int
        Number of worn states whose displacement and von Mises fields at the rpm of maximum
        engine torque are kept (``Life.fields``, written as a ParaView .pvd by
        :func:`~clutchfem.lifetime.life_files`): the new part, the end of the life and states
        log-spaced in the starts between (0..200; 0: none, 1: the end only).
    log : callable, optional
        Receives a line per wear state.

    Returns
    -------
    Life

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> L = cf.life(d, starts=1000, rebuild_depth=None)
    >>> bool(L.engagement_rpm[-1] >= L.engagement_rpm[0]), L.energy_balance < 1e-6
    (True, True)
    """
    t0 = time.perf_counter()
    if not isinstance(design, Design):
        raise ParameterError("design", type(design).__name__, "a clutchfem Design", "life")
    if isinstance(starts, bool) or not isinstance(starts, (int, float)) or not (1 <= starts <= 1e8):
        raise ParameterError("starts", starts, "a number of starts in [1, 1e8]", "life")
    for name, v, cls in (("duty", duty, DutyCycle), ("drive", drive, DriveLine), ("wear", wear, WearParams),
                         ("requirements", requirements, Requirements)):
        if v is not None and not isinstance(v, cls):
            raise ParameterError(name, type(v).__name__, f"a {cls.__name__} or None", "life")
    if rebuild_depth is not None and (isinstance(rebuild_depth, bool) or not isinstance(rebuild_depth, (int, float))
                                      or not 1e-6 <= rebuild_depth <= 1e-2):
        raise ParameterError("rebuild_depth", rebuild_depth, "a worn depth in [1 um, 10 mm] or None (never rebuild)",
                             "life")
    if isinstance(fields, bool) or not isinstance(fields, (int, np.integer)) or not 0 <= fields <= 200:
        raise ParameterError("fields", fields, "a number of worn states in [0, 200] whose fields are kept", "life")
    if design.drum_radius is None:
        raise ParameterError("drum_radius", None, "the drum's inner radius in m (a user mesh carries none)", "life")
    if rebuild_depth is not None and design.params is None:
        rebuild_depth = None  # a user mesh: no profile to rebuild (said in the notes)
    engine = EngineCurve.of(engine)
    drive = drive or DriveLine()
    wear = wear or WearParams()
    req = requirements or Requirements()
    idle, idle_assumed = idle_speed(engine, idle_rpm if idle_rpm is not None else drive.idle_rpm)
    if drive.idle_rpm is None:
        drive = drive.replace(idle_rpm=idle)
    lo, hi = engine.rpm_range
    grid = np.linspace(min(0.5 * idle, lo), hi * (1 + LIMITER_SHARE), GRID)
    h = _Holder(WornModel(design))
    R = design.drum_radius

    def rate(W):
        m = h.model
        extra = W[:-1] + W[-1]
        a = m.answers(extra, engine, grid)
        P, x = a.table_pressure_Pa, a.table_rpm
        free = engagement_transient(x, a.table_torque_Nm, engine, drive, pressure_Pa=P, drum_radius=R,
                                    rtol=RTOL)
        S = free.sliding_by_rpm_m.copy()
        h.max_balance = max(h.max_balance, free.energy_balance)
        cut = None
        if duty is not None:
            if duty.cutting_share > 0:
                cut = engagement_transient(x, a.table_torque_Nm, engine, drive, pressure_Pa=P, drum_radius=R,
                                           load_torque=drive.cutting_torque, rtol=RTOL)
                h.max_balance = max(h.max_balance, cut.energy_balance)
                S = (1 - duty.cutting_share) * S + duty.cutting_share * cut.sliding_by_rpm_m
            if duty.held_slips_per_hour > 0 and duty.held_slip_duration > 0:
                n_h = a.slip_rpm if a.slip_rpm is not None else hi
                S = S + _hat(x, n_h) * duty.held_slips_per_start * R * (n_h * math.pi / 30.0) * duty.held_slip_duration
        I = S @ P
        dh, dd = wear_rate(I, wear, weight_m=m.weight, scale=m.scale, drum_radius_m=R)
        J, give = _jacobian(m, x, S, P, wear, R)
        info = _state_info(m, a, free, cut, W, R, h)
        info["elastic_give_m"] = give
        if log:
            log(f"{h.count:4d} state: engagement {a.engagement_rpm or math.nan:.0f} rpm, slip "
                f"{a.slip_rpm or math.nan:.0f} rpm, arc {a.contact_arc_deg:.1f} deg, worn {1e6 * W[:-1].max():.1f} um, "
                f"slip energy {free.slip_energy_J:.1f} J per start")
        h.count += 1
        return np.concatenate([dh, [dd]]), J, info

    want = _field_starts(int(fields), float(starts))
    kept: list[dict] = []

    def keep(n, W):
        while want and n >= want[0] * (1 - 1e-9):
            want.pop(0)
            if not kept or kept[-1]["starts"] != n:
                kept.append(state_fields(h.model, W[:-1] + W[-1], W[:-1], float(engine.rpm_max_torque), n))

    if fields > 1:
        keep(0.0, np.zeros(h.model.m + 1))

    def on_state(n, W, info):
        keep(n, W)
        if rebuild_depth is None or np.max(np.abs(W[:-1] - h.built)) < rebuild_depth:
            return None
        new, w_new = rebuild(h.model, W[:-1])
        h.model, h.built = new, w_new.copy()
        h.rebuilds.append(float(n))
        if log:
            log(f"rebuilt the worn part at {n:.0f} starts ({new.m} contact nodes)")
        return np.concatenate([w_new, [W[-1]]])

    run = integrate_wear(rate, np.zeros(h.model.m + 1), float(starts), wear, on_state=on_state)
    notes = []
    if design.params is None:
        notes.append("a user mesh: the worn profile is kept in the contact gaps of the new part's model (no rebuild)")
    if idle_assumed:
        notes.append(f"idle speed {idle:.0f} rpm ASSUMED")
    return Life.build(design, run, engine=engine, drive=drive, wear=wear, duty=duty, req=req, idle_rpm=idle,
                      rebuilds=h.rebuilds, rebuild_depth=rebuild_depth, energy_balance=h.max_balance,
                      seconds=time.perf_counter() - t0, notes=notes, profile_s=PROFILE_S, fields=kept)


def _field_starts(k: int, starts: float) -> list[float]:
    """The starts at which ``k`` states' fields are kept: 0, the end and log-spaced between
    (from starts / 1e4, at least 1)."""
    if k <= 0:
        return []
    if k == 1:
        return [starts]
    inner = np.geomspace(max(1.0, starts * 1e-4), starts, k - 1) if starts > 1 else np.array([starts])
    return sorted({0.0, *map(float, inner[:-1]), starts})


def _hat(x: np.ndarray, v: float) -> np.ndarray:
    """Linear-interpolation weights of the speeds ``x`` at ``v``."""
    return np.array([np.interp(v, x, e) for e in np.eye(len(x))])


def _jacobian(m: WornModel, x: np.ndarray, S: np.ndarray, P: np.ndarray, wear: WearParams,
              R: float) -> tuple[np.ndarray, float | None]:
    """(d(wear rate)/d(worn depths) ((m+1) x (m+1): the shoe's nodes and the drum) from the
    contact problem at every speed where the start slides (:mod:`clutchfem.durability.wear`),
    the contact's elastic give [m] (None: no contact)).

    The elastic give of a loaded node i is the worn depth that would unload it, linearised:
    p_i / |dp_i/dw_i| (the node's own stiffness against the drum with its neighbours held
    at their gaps); the give of the state is its mean weighted by the wear each node takes at
    each speed (S_j p_i w_i): a step deeper than it unloads the loaded nodes within one step
    and over-wears them (reported per state; the step control is the wear rate's change)."""
    n = m.m
    JI = np.zeros((n, n + 1))
    num = den = 0.0
    for j in np.nonzero(S > 0)[0]:
        A = np.nonzero(P[j] > 0)[0]
        if not len(A):
            continue
        Dp = m.pressure_jacobian(float(x[j]) * math.pi / 30.0, A)
        D = S[j] * Dp
        JI[np.ix_(A, A)] += D
        JI[A, n] += D.sum(axis=1)  # the drum's depth opens every gap
        stiff = -np.diag(Dp)
        ok = stiff > 0
        wgt = S[j] * P[j, A] * m.weight[A]
        num += float(np.sum(wgt[ok] * P[j, A][ok] / stiff[ok]))
        den += float(np.sum(wgt[ok]))
    J = np.zeros((n + 1, n + 1))
    J[:n] = wear.k / wear.hardness * JI
    J[n] = wear.k_drum / wear.drum_hardness * m.scale * (m.weight @ JI) / (2.0 * math.pi * R)
    return J, (num / den if den > 0 else None)


def _state_info(m: WornModel, a, free, cut, W, R, h: _Holder) -> dict:
    """What a state keeps (units in the keys).  The heat partition of the starts is
    evaluated again when their sliding speed or patch length has moved by PARTITION_CHANGE
    since it last was (it depends weakly on both)."""
    order = np.argsort(m.s)
    share = a.contact_share
    patch = max(share * math.radians(m.arc_deg) * R, float(np.max(m.weight)))
    heat = None
    if free.slip_energy_J > 0:
        kw = dict(patch_length_m=patch, n_patches=max(m.design.cm.n_shoes_total, 1), thickness_m=m.thickness,
                  drum_radius_m=R)
        v = free.sliding_distance_m / max(free.time_to_lockup_s or free.times_s[-1], 1e-300)
        key = h.partition
        fresh = key is None or abs(v / key[0] - 1) > PARTITION_CHANGE or abs(patch / key[1] - 1) > PARTITION_CHANGE
        try:
            st = start_heating(free, **kw, fraction_part=None if fresh else key[2])
            if fresh:
                h.partition = (v, patch, st.fraction_part)
            heat = st.to_json()
        except ParameterError as exc:  # a partition outside its model (said in the answers)
            heat = {"reason": str(exc)}
    s_sorted = m.s[order]
    return {"engagement_rpm": a.engagement_rpm, "slip_rpm": a.slip_rpm,
            "torque_at_max_engine_torque_Nm": a.torque_at_max_engine_torque_Nm,
            "contact_arc_deg": a.contact_arc_deg, "start": free.to_json(), "cut_start": None if cut is None
            else cut.to_json(), "heating": heat,
            "worn_profile_m": np.interp(PROFILE_S, s_sorted, W[:-1][order]), "drum_worn_m": float(W[-1]),
            "pressure_s": s_sorted, "pressure_at_max_engine_torque_Pa": a.pressure_at_max_engine_torque_Pa[order]}
