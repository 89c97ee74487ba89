"""Shoe-profile compensation: the clearance along the shoe that spreads the contact pressure
evenly over a target share of the shoe's arc at one speed.

Why the contact is on the tip.  At speed X the free shoe (no drum) moves out by u_n(s) along
its outer surface (s: arc fraction, 0 at the root next to the flexure, 1 at the tip), and the
shoe of a compliant clutch does not translate: it *rotates* about the flexure.  Concept 4 at
8000 rpm (default mesh): u_n = -0.18 mm at the root, +1.4 mm mid-shoe, +2.2 mm at the tip.
A concentric shoe (0.6 mm everywhere) therefore touches at the tip only (2 % of the nominal
arc); the thesis's prototypes touched on about a third.

Method: linearised contact with the model's own operators, and a fixed point for the
geometry.  At speed X the contact problem of a design is, exactly for the FE model,

    gap = c - u_n + G lam >= 0,   lam >= 0,   gap . lam = 0

with c the rest clearance at the contact nodes, u_n the free normal displacement at X (spin
softening included) and G = -B (K - X^2 M)^-1 D the condensed contact compliance (friction
included: not symmetric; :mod:`clutchfem.softening`).  If every node of the target arc
T = [s_a, s_a + f] touches, lam_T = G_TT^-1 (u_n,T - c_T) and the pressure is
p_i = lam_i / (h w_i) (h thickness, w_i the node's tributary length).  The profile is the
``table`` profile (:class:`clutchfem.geometry.ConceptParams`): c(s) = sum_k v_k phi_k(s),
a C2 cubic spline through the TABLE_N = 17 control values v_k (phi_k its cardinal
functions, :func:`clutchfem.geometry.table_cardinal`).  The best profile at this
linearisation solves the small quadratic programme (10 unknowns, SLSQP)

    min_{v, P}  sum_T w_i (p_i(v) - P)^2 / sum_T w_i            (even pressure at a level P)
    s.t.   mean_T c(v) = c_mean                                   (level rule, below)
           gap_i(v) >= delta  for the nodes outside T             (contact on T only)
           p_i(v) >= 0        on T                                (T really in contact)
           0.06 mm <= v_k <= 2.95 mm                              (the table's range, kept inside)

Level rule (ASSUMED, the designer can override it with ``mean_clearance``): the mean
clearance over T stays the design's own mean clearance there (0.6 mm for the thesis's shoe):
the compensation *redistributes* the clearance instead of closing it, so the engagement
speed and the torque change are outcomes, reported, not targets.

The profile changes the shoe itself (its outer surface moves by up to ~1 mm on a 6 mm
shoe), so u_n and G change with v: the programme is solved again on the rebuilt design's
own operators until the control values move less than ``tol`` (default 1 um, the
profile's resolution) -- a fixed point v_{k+1} = F(v_k).  Every iteration is re-solved with
the FE contact (the LCP, not the linearisation) and its measured pressure evenness (the
weighted coefficient of variation of p over T), contact share and step are recorded:
convergence is measured, not assumed.

Why not the textbook update ``c += k (p - p_target) / stiffness``: a compliant shoe is no
Winkler foundation.  G has large off-diagonal terms (a push at the tip moves the root the
other way), so a local stiffness is wrong by a factor of several and such an update needs a
damping factor found by trial; G itself costs m back-substitutions with the one
factorisation, so each step here is a Newton step of the linear contact problem and only the
geometry change is iterated.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import lsq_linear

from ..core import InputError, ParameterError, SolverError, clean, rpm_to_rad_s, wrap_angle
from ..core import values as V
from ..geometry import TABLE_FIELDS, TABLE_N, MeshSettings, get_concept, table_cardinal
from ..loadcase import Design, OperatingPoint, contact_extent

#: the control values are kept this far inside the table's declared range [m]
RANGE_MARGIN = 0.01e-3
#: gap required at X outside the target arc [m] (no contact there)
OPEN_GAP = 0.005e-3


@dataclass(frozen=True)
class ShoeState:
    """One design's contact at speed X along shoe 0 (sorted from root to tip)."""

    s: np.ndarray  # arc fraction of each contact node
    clearance_m: np.ndarray  # rest gap g0
    free_m: np.ndarray  # free normal displacement at X
    pressure_Pa: np.ndarray
    force_N: np.ndarray
    weight_m: np.ndarray
    contact_share: float  # contact extent / nominal arc at X (first to last end of contact, between nodes)
    touching_share: float  # tributary length of the nodes in contact / the whole contact surface
    normal_force_N: float  # whole clutch
    torque_Nm: float  # whole clutch


@dataclass(frozen=True)
class CompensationStep:
    """One fixed-point iteration (iteration 0: the design as given)."""

    iteration: int
    texts: dict  # table_c* -> "--set" text
    fit_rms_m: float | None  # rms misfit of the spline to the target clearance over T
    target_pressure_Pa: float | None  # level P of the step's target
    measured_cv: float  # evenness of the FE (LCP) solution over T
    contact_share: float  # contact extent / nominal arc
    touching_share: float  # nodes in contact (tributary length) / contact surface
    step_m: float | None  # max |v_k - v_{k-1}|
    normal_force_N: float
    torque_Nm: float
    engagement_rpm: float | None
    seconds: float
    predicted_cv: float | None  # the cv the spline misfit leaves in the linearised contact


@dataclass(frozen=True)
class Compensation:
    """What :func:`compensate` returns: the ``table`` profile that evens the contact
    pressure at ``rpm`` over the ``target_arc`` share of the shoe (``after``, its ``--set``
    texts ``after_texts``), shoe 0's contact before and after, every rebuild (``steps``) and
    whether the fixed point ``converged``.

    Examples
    --------
    >>> import numpy as np
    >>> from clutchfem.targets import Compensation, ShoeState
    >>> def state(share, p_max, torque):     # shoe 0's contact at the speed, hand-made here
    ...     z = np.zeros(2)
    ...     return ShoeState(z, z, z, np.array([0.0, p_max]), z, z, share, share, 100.0, torque)
    >>> c = Compensation("concept4", 8000.0, 0.33, (0.5, 0.83), 0.6e-3, None, None, {"table_c0": "0.61mm"}, [],
    ...                  True, state(0.02, 40e6, 3.1), state(0.33, 6e6, 3.3), 20.0)
    >>> c.set_args
    ['table_c0=0.61mm']
    >>> for row in c.compare()[::2]:
    ...     print(row)
    ('contact arc at 8000 rpm (share of the nominal arc)', '2.0 %', '33.0 %')
    ('peak contact pressure at 8000 rpm', '40.0 MPa', '6.00 MPa')
    """

    concept: str
    rpm: float
    target_arc: float
    arc: tuple[float, float]
    mean_clearance_m: float
    before: object  # ConceptParams
    after: object  # ConceptParams (profile 'table')
    after_texts: dict  # the --set texts of the profile
    steps: list[CompensationStep]
    converged: bool
    state_before: ShoeState
    state_after: ShoeState
    seconds: float
    notes: list[str] = field(default_factory=list)

    @property
    def set_args(self) -> list[str]:
        return V.assignments(self.after_texts)

    def compare(self, before=None, after=None) -> list[tuple[str, str, str]]:
        """(answer, before, after) as text with units: the contact at the compensation's
        speed, and with the designs' analyses ``before`` and ``after`` (optional,
        :class:`~clutchfem.Analysis`) engagement, slip, torque, stress, safety factor, mass."""
        b, a = self.state_before, self.state_after
        out = [(f"contact arc at {self.rpm:.0f} rpm (share of the nominal arc)",
                f"{100 * b.contact_share:.1f} %", f"{100 * a.contact_share:.1f} %"),
               (f"nodes in contact at {self.rpm:.0f} rpm (share of the arc)", f"{100 * b.touching_share:.1f} %",
                f"{100 * a.touching_share:.1f} %"),
               (f"peak contact pressure at {self.rpm:.0f} rpm", f"{max(b.pressure_Pa) / 1e6:.1f} MPa",
                f"{max(a.pressure_Pa) / 1e6:.2f} MPa"),
               (f"torque at {self.rpm:.0f} rpm", f"{b.torque_Nm:.2f} N m", f"{a.torque_Nm:.2f} N m "
                f"({100 * (a.torque_Nm / b.torque_Nm - 1):+.0f} %)" if b.torque_Nm > 0 else f"{a.torque_Nm:.2f} N m")]
        if before is not None and after is not None:
            out += [("engagement speed (static)", _text(before.engagement_rpm, ".0f", "rpm"),
                     _text(after.engagement_rpm, ".0f", "rpm")),
                    ("engagement speed with ripple", _text(before.engagement_rpm_with_ripple, ".0f", "rpm"),
                     _text(after.engagement_rpm_with_ripple, ".0f", "rpm")),
                    ("slip speed", _text(before.slip_rpm, ".0f", "rpm"), _text(after.slip_rpm, ".0f", "rpm")),
                    (f"torque at {before.rpm_max_engine_torque:.0f} rpm (max engine torque "
                     f"{before.max_engine_torque_Nm:.2f} N m)", _text(before.torque_at_max_engine_torque_Nm, ".2f", "N m"),
                     _text(after.torque_at_max_engine_torque_Nm, ".2f", "N m")),
                    (f"peak von Mises at {before.max_engine_rpm:.0f} rpm", _text(before.max_von_mises_Pa / 1e6, ".0f", "MPa"),
                     _text(after.max_von_mises_Pa / 1e6, ".0f", "MPa")),
                    ("safety factor", _text(before.safety_factor, ".2f"), _text(after.safety_factor, ".2f")),
                    ("part mass", _text(before.part.get("mass_kg", math.nan) * 1e3, ".1f", "g"),
                     _text(after.part.get("mass_kg", math.nan) * 1e3, ".1f", "g"))]
        return out

    def to_json(self, before=None, after=None) -> dict:
        """The compensation as a JSON-ready dict (``compensation.json``, ``--json``): the
        profile's ``--set`` texts, the contact before and after, every rebuild, and
        :meth:`compare` of the analyses ``before`` and ``after`` where given."""
        return clean({
            "concept": self.concept, "rpm": self.rpm, "target_arc": self.target_arc, "arc": list(self.arc),
            "mean_clearance_m": self.mean_clearance_m, "converged": self.converged, "seconds": self.seconds,
            "params": self.after_texts, "set": [f"{k}={v}" for k, v in self.after_texts.items()],
            "before_after": [{"answer": q, "before": x, "after": y} for q, x, y in self.compare(before, after)],
            "contact_share_before": self.state_before.contact_share,
            "contact_share_after": self.state_after.contact_share,
            "torque_at_rpm_before_Nm": self.state_before.torque_Nm, "torque_at_rpm_after_Nm": self.state_after.torque_Nm,
            "steps": [dict(s.__dict__) for s in self.steps], "notes": self.notes,
            "run": {"rpm": self.rpm, "target_arc": self.target_arc, "arc": list(self.arc),
                    "mean_clearance_m": self.mean_clearance_m},
            "units": {"rpm": "1/min", "lengths": "m", "pressure": "Pa", "torque": "N m", "share": "-"}})


def _text(v, fmt: str, unit: str = "") -> str:
    """``v`` formatted with its unit, ``-`` where there is no value."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:{fmt}} {unit}".rstrip()


def shoe_state(design, omega: float, case=None) -> tuple[ShoeState, dict]:
    """The contact of shoe 0 at ``omega`` [rad/s] and the operators of its linearisation
    (``idx`` node indices root->tip, ``G`` (k x k) compliance incl. an elastic drum, ``un``
    free normal displacement incl. the drum's expansion)."""
    case = case or design.case()
    c = case.contact
    if c is None:
        raise InputError("the design has no contact surface facing a drum: nothing to compensate")
    nd = c.nodes
    root, tip = design.cm.contact_arcs[0]
    sel = np.nonzero(nd.shoe == 0)[0]
    ang = wrap_angle(nd.angle[sel], 0.5 * (root + tip))
    s = (ang - root) / (tip - root)
    order = np.argsort(s)
    idx, s = sel[order], s[order]
    lam, _ = case.solve(omega)
    un = case.response.free_normal(omega)[idx] - c.drum_gap(omega)
    G = case.response.columns(omega)(idx)[idx]
    if c.drum_compliance is not None:
        G = G + c.drum_compliance[np.ix_(idx, idx)]
    w = nd.weight[idx]
    p = lam[idx] / (design.thickness * w)
    # the contact extent as the sweep results find it (ends between the nodes)
    e = contact_extent(c, lam[None, :], case.gaps(omega, lam)[None, :], design.thickness, case.contact_modulus, 0)[0]
    share = 0.0 if not np.isfinite(e[0]) else abs(e[1] - e[0]) / abs(tip - root)
    N = float(lam.sum() * case.scale)
    touch = float(w[lam[idx] > 0].sum() / w.sum())
    st = ShoeState(s=s, clearance_m=nd.gap0[idx], free_m=un, pressure_Pa=p, force_N=lam[idx], weight_m=w,
                   contact_share=float(share), touching_share=touch, normal_force_N=N, torque_Nm=float(c.mu * c.drum_radius * N))
    return st, {"idx": idx, "G": G, "un": un}


def evenness(st: ShoeState, arc: tuple[float, float]) -> float:
    """Weighted coefficient of variation of the pressure over the target arc (0: even;
    inf where T carries no load)."""
    T = (st.s >= arc[0] - 1e-9) & (st.s <= arc[1] + 1e-9)
    w = st.weight_m[T]
    p = st.pressure_Pa[T]
    mean = float(w @ p / w.sum())
    if mean <= 0:
        return math.inf
    return float(math.sqrt(w @ (p - mean) ** 2 / w.sum()) / mean)


def _programme(st: ShoeState, ops: dict, arc, h: float, c_mean: float, lo: float, hi: float,
               v_cur: np.ndarray) -> tuple[np.ndarray, float, float, float]:
    """One fixed-point step (module docstring): the target clearance at the nodes of T,
    c* = u_n - P g1 (g1 = G lam1, lam1 = h w on T: the nodal forces of a unit uniform
    pressure), the level P from the mean-clearance rule (closed form), and the table values
    whose spline meets c* best: weighted least squares over T within the table's range
    (``scipy.optimize.lsq_linear``, in micrometres: well conditioned).  The spline is
    corrected by the difference between the mesh's actual rest gaps and the current spline
    (the geometry kernel's own representation of the profile), so that this error is
    iterated away too.

    Returns (v [m], P [Pa], rms misfit over T [m], predicted pressure cv): the cv the misfit
    leaves in the linearised contact (p error = G_TT^-1 misfit / (h w))."""
    s, w, un, G = st.s, st.weight_m, ops["un"], ops["G"]
    T = (s >= arc[0] - 1e-9) & (s <= arc[1] + 1e-9)
    Phi = table_cardinal(s)
    lam1 = np.where(T, h * w, 0.0)
    g1 = G @ lam1  # gap opened by a unit uniform pressure on T [m/Pa]
    mT = w[T] / w[T].sum()
    P = float((mT @ un[T] - c_mean) / (mT @ g1[T]))
    if not P > 0:
        raise SolverError(f"profile compensation: at a mean clearance of {c_mean * 1e3:.3f} mm over the target arc "
                          f"the shoe does not touch at this speed (its free mean displacement there is "
                          f"{mT @ un[T] * 1e3:.3f} mm): lower --mean-clearance or raise --rpm")
    corr = st.clearance_m - table_cardinal(s) @ v_cur  # mesh profile vs spline (geometry representation)
    target = un - P * g1 - corr
    sw = np.sqrt(mT)
    fit = lsq_linear(Phi[T] * sw[:, None], target[T] * 1e6 * sw, bounds=(lo * 1e6, hi * 1e6), method="bvls")
    v = fit.x * 1e-6
    res = Phi[T] @ v - target[T]
    rms = float(math.sqrt(mT @ (res * res)))
    dp = np.linalg.solve(G[np.ix_(T, T)], res) / (h * w[T])
    return v, P, rms, float(math.sqrt(mT @ (dp * dp)) / P)


def place_arc(st: ShoeState, ops: dict, target_arc: float, h: float, c_mean: float | None, lo: float,
              hi: float, v_cur: np.ndarray, n: int = 9) -> tuple[float, float]:
    """(arc start, predicted cv): the start of the target arc, among ``n`` equally spaced
    positions from the root to the tip, whose profile promises the most even pressure at the
    first linearisation (the table spline cannot follow a target that its range clips: on
    concept 4 a centred arc needs clearances below 0.05 mm at the root)."""
    best = None
    for s_a in np.linspace(0.0, 1.0 - target_arc, n):
        arc = (float(s_a), float(min(1.0, s_a + target_arc)))
        cm = c_mean if c_mean is not None else mean_over(st, arc)
        try:
            cv = _programme(st, ops, arc, h, cm, lo, hi, v_cur)[3]
        except SolverError:
            continue
        if best is None or cv < best[1] - 1e-12:
            best = (arc[0], cv)
    if best is None:
        raise SolverError(f"profile compensation: no placement of a {target_arc:g} target arc lets the shoe touch "
                          "at this speed; lower --mean-clearance or raise --rpm")
    return best


def mean_over(st: ShoeState, arc) -> float:
    """Weighted mean rest clearance [m] over the arc."""
    T = (st.s >= arc[0] - 1e-9) & (st.s <= arc[1] + 1e-9)
    return float(st.weight_m[T] @ st.clearance_m[T] / st.weight_m[T].sum())


def compensate(design, params=None, rpm: float = 8000.0, target_arc: float = 0.8, *,
               arc_start: float | None = None, mean_clearance: float | None = None, op=None,
               mesh_settings=None, max_iter: int = 8, tol: float = 5e-9, log=None) -> Compensation:
    """The shoe profile (a table of clearances) that spreads the contact pressure evenly over
    a target share of the shoe at one speed (module docstring).

    Parameters
    ----------
    design : Design, str or Concept
        The design (a concept's :class:`~clutchfem.Design`: its concept, parameters,
        operating point and mesh), or a concept (name or object) with ``params``, ``op`` and
        ``mesh_settings``.
    params : ConceptParams, optional
        With a concept: its parameter set (default: the defaults).
    rpm : float
        The speed [rpm] at which the pressure should be even.
    target_arc : float
        The share of the nominal shoe arc to load evenly (0.05 to 1).
    arc_start : float, optional
        Its start as an arc fraction from the root (default: placed for the most even pressure).
    mean_clearance : float, optional
        Mean clearance [m] over the target arc (default: the design's own there).
    max_iter, tol, log
        The fixed point stops when no control value moves more than ``tol`` [m] or after
        ``max_iter`` rebuilds; ``log`` receives one line per iteration.

    Returns
    -------
    Compensation
        The profile (``after_texts``: ``--set`` texts), the pressure states before and
        after, every step of the fixed point.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="2.5mm"))
    >>> c = cf.compensate(d, rpm=8000, target_arc=0.8, max_iter=2)
    >>> c.after_texts["profile"], c.state_after.contact_share > c.state_before.contact_share
    ('table', True)
    """
    if isinstance(design, Design):
        if design.params is None:
            raise InputError(f"{design.name}: a user mesh has no shoe profile parameters to compensate")
        params = design.params if params is None else params
        op = design.op if op is None else op
        mesh_settings = MeshSettings(**design.cm.mesh_settings) if mesh_settings is None and design.cm.mesh_settings \
            else mesh_settings
        concept = design.concept or design.name
    else:
        concept = design
    t_start = time.perf_counter()
    c = get_concept(concept) if isinstance(concept, str) else concept
    p0 = params if params is not None else c.params()
    ms = mesh_settings or MeshSettings.preset((op or OperatingPoint()).fidelity)
    if isinstance(rpm, bool) or not (isinstance(rpm, (int, float)) and math.isfinite(rpm) and 0 < rpm <= 1e5):
        raise ParameterError("rpm", rpm, "a speed in (0, 100000] rpm", "compensate")
    if isinstance(target_arc, bool) or not (isinstance(target_arc, (int, float)) and 0.05 <= target_arc <= 1.0):
        raise ParameterError("target_arc", target_arc, "a share of the nominal shoe arc in [0.05, 1]", "compensate")
    if arc_start is not None and not (isinstance(arc_start, (int, float)) and
                                      0.0 <= arc_start <= 1.0 - target_arc + 1e-12):
        raise ParameterError("arc_start", arc_start, f"an arc fraction in [0, {1 - target_arc:.3g}] (the target "
                             f"arc {target_arc:g} must fit on the shoe)", "compensate")
    if isinstance(max_iter, bool) or not (isinstance(max_iter, int) and 1 <= max_iter <= 50):
        raise ParameterError("max_iter", max_iter, "an integer in [1, 50]", "compensate")
    P = type(p0)
    lo_r, hi_r = V.param_bounds(P, TABLE_FIELDS[0])
    lo, hi = lo_r + RANGE_MARGIN, hi_r - RANGE_MARGIN
    if mean_clearance is not None and not (isinstance(mean_clearance, (int, float)) and lo <= mean_clearance <= hi):
        raise ParameterError("mean_clearance", mean_clearance, f"a clearance in [{lo * 1e3:.2f} mm, "
                             f"{hi * 1e3:.2f} mm]", "compensate")
    w = rpm_to_rad_s(rpm)
    notes: list[str] = []

    def build(p):
        return Design.from_concept(c, p, op, ms)

    d = build(p0)
    st0, ops = shoe_state(d, w)
    # start: the design's own clearance at the knots
    knots = np.linspace(0.0, 1.0, TABLE_N)
    root, tip = c.shoe_arc(p0)
    v_prev = p0.drum_radius - p0.outer_radius(root + knots * (tip - root), root, tip)
    if arc_start is None:
        s_a, cv0 = place_arc(st0, ops, target_arc, d.thickness, mean_clearance, lo, hi, v_prev)
        notes.append(f"target arc placed at {s_a:.3f}..{min(1.0, s_a + target_arc):.3f} of the shoe from the root "
                     f"(of 9 placements, the most even pressure the first linearisation promised: cv {cv0:.3f})")
    else:
        s_a = float(arc_start)
    arc = (s_a, min(1.0, s_a + target_arc))
    c_mean = float(mean_clearance) if mean_clearance is not None else mean_over(st0, arc)
    steps = [CompensationStep(0, {}, None, None, evenness(st0, arc), st0.contact_share, st0.touching_share, None,
                              st0.normal_force_N, st0.torque_Nm, d.case().engagement_rpm,
                              time.perf_counter() - t_start, None)]
    st, d_cur = st0, d
    best = None
    converged = False
    for k in range(1, max_iter + 1):
        t0 = time.perf_counter()
        v, Pt, fit_rms, cv_pred = _programme(st, ops, arc, d_cur.thickness, c_mean, lo, hi, v_prev)
        vals, texts = V.snap_all(P, {n: float(x) for n, x in zip(TABLE_FIELDS, v)})
        v_snap = np.array([vals[n] for n in TABLE_FIELDS])
        try:
            p_new = p0.replace(profile="table", **vals)
        except ParameterError as exc:
            raise SolverError(f"profile compensation: the compensated profile is refused by the concept ({exc}); "
                              "a smaller --target-arc or another --arc-start") from None
        d_new = build(p_new)
        st_new, ops_new = shoe_state(d_new, w)
        step = float(np.max(np.abs(v_snap - v_prev)))
        cv = evenness(st_new, arc)
        steps.append(CompensationStep(k, texts, fit_rms, Pt, cv, st_new.contact_share, st_new.touching_share, step,
                                      st_new.normal_force_N, st_new.torque_Nm, d_new.case().engagement_rpm,
                                      time.perf_counter() - t0, cv_pred))
        if log:
            log(f"iteration {k}: pressure cv {cv:.3f} over the target arc (linearised {cv_pred:.3f}; level "
                f"{Pt / 1e6:.3f} MPa, spline misfit {fit_rms * 1e9:.1f} nm), in contact "
                f"{100 * st_new.touching_share:.0f} % of the shoe arc, step {step * 1e6:.4f} um")
        if best is None or cv < best[0]:
            best = (cv, p_new, texts, st_new)
        st, ops, d_cur, v_prev = st_new, ops_new, d_new, v_snap
        if step <= tol:
            converged = True
            break
    if not converged:
        notes.append(f"the fixed point did not settle to {tol * 1e9:g} nm in {max_iter} rebuilds: the most even "
                     "profile found is returned")
    _, p_best, texts_b, st_b = best
    return Compensation(concept=c.name, rpm=float(rpm), target_arc=float(target_arc), arc=arc,
                        mean_clearance_m=c_mean, before=p0, after=p_best,
                        after_texts={"profile": "table", **texts_b}, steps=steps, converged=converged,
                        state_before=st0, state_after=st_b, seconds=time.perf_counter() - t_start, notes=notes)
