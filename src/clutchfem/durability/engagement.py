"""The engagement transient of one start: the engine runs up from idle, the clutch slips, the
drum and chain catch up and lock (:func:`engagement_transient`, :class:`DriveLine`).

Two rotating bodies coupled by the slipping clutch (angular speeds w_e, w_d, rad/s):

    J_e dw_e/dt = theta(t) M_e(n_e) - M_c(n_e)            engine side (crank, flywheel, clutch)
    J_d dw_d/dt = M_c(n_e) - M_L                           driven side (drum, sprockets, chain)

while w_e > w_d; lock-up is the event w_e = w_d (``scipy.integrate.solve_ivp``, terminal
event), where the start ends.  n_e = w_e 60 / (2 pi) [rpm].

* M_e(n): the full-throttle engine curve (:class:`~clutchfem.clutch.EngineCurve`); below
  its lowest speed the lowest value, above its top speed a rev limiter that takes the
  torque linearly to zero over 2 % of the top speed (ASSUMED: a governed engine).
* theta(t) = min(1, t / t_r): the throttle opened linearly from idle in ``throttle_ramp``
  t_r (ASSUMED 0.2 s, a thumb on a trigger).  A closed throttle delivers no net torque: the
  engine idles at n_idle in equilibrium with the disengaged clutch (the engine's own
  friction is inside the full-throttle curve; the closed-throttle brake torque acts only
  before the throttle opens and is neglected).
* M_c(n_e): the torque the slipping clutch transmits at the engine speed, the FE answer
  (the shoes are loaded by the centrifugal force of the hub speed; friction with the
  drum-held sense, which is the sense of every slip with w_e > w_d), interpolated
  monotonically (PCHIP) in the table the caller gives.  The drum's own speed does not
  enter (the rigid or elastic drum of the FE model; the drum's hoop growth at its lower
  speed is neglected).
* M_L: the load on the driven side while it turns, a constant (Coulomb) torque: the chain's
  drag on the bar (``drag_torque``) and, for a start made in the cut, the cutting torque.
  At rest the drum stays put until M_c exceeds M_L (static friction of the chain).

Energies, integrated with the motion (states of the same ODE):

    E_in   = int theta M_e w_e dt            (engine work; with the engine held: int M_c w_e dt)
    E_slip = int M_c (w_e - w_d) dt          (friction heat in the clutch)
    E_load = int M_L w_d dt                  (work on the chain)

and the balance E_in = dKE_e + dKE_d + E_slip + E_load, whose relative residual
``energy_balance`` measures the integration error (it closes to ~1e-9 at the default
tolerances, and to a few ``rtol`` at any, tested).  The state at lock-up is stepped to from
the last accepted step, not read off the dense output at the event (that interpolant's error
is not bounded by the step control: read off it, the balance of some starts closed only to
~1e2 rtol).  The sliding distance on the shoe face is R_d int (w_e - w_d) dt; with
a pressure table p_i(n_j) of the contact nodes at the table's speeds n_j the transient
also integrates the sliding distance spent near each speed, S_j = R_d int phi_j(n_e)
(w_e - w_d) dt (phi_j the hat functions of linear interpolation in n), and from it
int p_i v dt = sum_j S_j p_i(n_j) [Pa m] per node, the sliding-pressure integral Archard's
law needs (:mod:`clutchfem.durability.wear`).

Closed form (tested): engine held at w, constant clutch torque M, no load: the drum locks
at t = J_d w / M and E_slip = M w t - M^2 t^2 / (2 J_d) = J_d w^2 / 2, the kinetic energy
it gained.

ASSUMED inertias and loads (every one a field of :class:`DriveLine`, its source there):
engine side J_e = 1.0e-3 kg m^2 (56.5 cc saw: flywheel with fan and magnets ~0.45 kg at
~55 mm, crank webs and rod ~1e-4, the clutch ~5e-5, the piston's mean 0.5 m r^2 ~1e-5;
an estimate, no measured value in the sources: band x/ 1.5), driven side seed 000's
J_b + m_p r_k^2 = 2.078e-4 kg m^2, chain drag 0.25 N m (a free-running 3/8" chain on a
15" bar takes ~150-300 W at ~9000 rpm, ASSUMED), cutting torque 3.20 N m (seed 000's mean
cutting torque).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import PchipInterpolator

from ..clutch import SEED_DRIVE_INERTIA, EngineCurve
from ..core import InputError, ParameterError, ParamSet, clean, param, rad_s_to_rpm, rpm_to_rad_s

__all__ = ["DriveLine", "Engagement", "engagement_transient", "DEFAULT_IDLE_RPM"]

#: idle speed [rpm] when neither the engine curve nor the drive line names one (ASSUMED, as
#: the analysis does)
DEFAULT_IDLE_RPM = 2700.0
#: width of the rev limiter above the curve's top speed, a share of that speed
LIMITER_SHARE = 0.02
#: dense-output samples per integration segment (peak slip power, droop, the plots)
SAMPLES = 2001
#: points of the dense solution the sliding by speed is integrated on (:func:`_sliding_by_rpm`)
FINE = 5001


class DriveLine(ParamSet):
    """The inertias and loads of the engagement transient (ASSUMED values with their sources;
    module :mod:`clutchfem.durability.engagement`).

    Parameters
    ----------
    engine_inertia : float or str
        Crank, flywheel and clutch on the crank axis [kg m^2].
    driven_inertia : float or str
        Drum, sprockets and chain reduced to the clutch axis [kg m^2].
    drag_torque : float or str
        Chain drag on the bar while the chain runs free [N m].
    cutting_torque : float or str
        Load of a start made in the cut [N m] (drag included).
    throttle_ramp : float or str
        Time to open the throttle from idle to full [s].
    idle_rpm : float or str, optional
        Idle speed [rpm] (default: the engine curve's, else 2700 rpm).
    max_time : float or str
        A start that has not locked by then is given up ("never locks") [s].

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.DriveLine(engine_inertia="1.2e-3 kg m^2")
    >>> d.engine_inertia, round(d.driven_inertia, 7)
    (0.0012, 0.0002078)
    >>> cf.DriveLine(driven_inertia=-1e-4)
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: drive line: parameter 'driven_inertia' = -0.0001 kg m^2 is not allowed: ...
    """

    context: ClassVar[str] = "drive line"
    engine_inertia: float = param(1.0e-3, "kg m^2", 1e-6, 1.0, "crank, flywheel and clutch on the crank axis "
                                  "(ASSUMED estimate for a 56.5 cc saw: flywheel ~0.45 kg at ~55 mm, crank and rod "
                                  "~1e-4, clutch ~5e-5; band x/ 1.5)", "J_e")
    driven_inertia: float = param(SEED_DRIVE_INERTIA, "kg m^2", 1e-7, 1.0, "drum, sprockets and chain reduced to "
                                  "the clutch axis, J_b + m_p r_k^2 (seed 000: 2.078e-4 kg m^2)", "J_d")
    drag_torque: float = param(0.25, "N m", 0.0, 100.0, "chain drag on the bar, chain running free (ASSUMED: "
                               "150-300 W at ~9000 rpm for a 3/8\" chain on a 15\" bar)", "M_drag")
    cutting_torque: float = param(3.2, "N m", 0.0, 100.0, "load of a start made in the cut, drag included (seed "
                                  "000: mean cutting torque 3.20 N m)", "M_cut")
    throttle_ramp: float = param(0.2, "s", 0.0, 10.0, "time to open the throttle from idle to full (ASSUMED)", "t_r")
    idle_rpm: float | None = param(None, "rpm", 100.0, 1e5, "idle speed (default: the engine curve's, else 2700 "
                                   "rpm, ASSUMED)", "n_idle")
    max_time: float = param(20.0, "s", 0.01, 3600.0, "a start not locked by then is given up", "t_max")


@dataclass(frozen=True)
class Engagement:
    """One start (:func:`engagement_transient`): answers with their units in the names, the
    trajectory (``times_s``, ``engine_rpm``, ``drum_rpm``, ``slip_power_W``) and the
    sliding-pressure integral per contact node (``pressure_sliding_Pa_m``, None without a
    pressure table) and the sliding distance spent at each speed of the table
    (``sliding_by_rpm_m``: the hat-function weights of its linear interpolation, so that
    ``pressure_sliding_Pa_m = sliding_by_rpm_m @ pressure_Pa`` exactly).

    ``status``: 'locks' (the drum caught up), 'never locks' (still slipping at
    ``max_time``: the clutch cannot carry the load at the speed the engine reaches),
    'never engages' (the clutch transmitted no torque).

    Examples
    --------
    >>> import clutchfem as cf
    >>> r = cf.engagement_transient([0, 4000, 20000], [0.0, 0.0, 20.0])
    >>> r.status, r.energy_balance < 1e-6, r.to_json()["slip_energy_J"] > 0
    ('locks', True, True)
    """

    status: str
    time_to_lockup_s: float | None
    lockup_rpm: float | None
    slip_energy_J: float
    peak_slip_power_W: float
    sliding_distance_m: float | None
    peak_engine_rpm: float
    engine_droop_rpm: float
    energies_J: dict
    energy_balance: float
    load_torque_Nm: float
    idle_rpm: float
    times_s: np.ndarray = field(repr=False)
    engine_rpm: np.ndarray = field(repr=False)
    drum_rpm: np.ndarray = field(repr=False)
    slip_power_W: np.ndarray = field(repr=False)
    pressure_sliding_Pa_m: np.ndarray | None = field(default=None, repr=False)
    sliding_by_rpm_m: np.ndarray | None = field(default=None, repr=False)
    solver: dict = field(default_factory=dict)

    def to_json(self, trajectory: bool = False) -> dict:
        """The answers as a JSON-ready dict (``trajectory``: with the time series)."""
        d = {k: getattr(self, k) for k in ("status", "time_to_lockup_s", "lockup_rpm", "slip_energy_J",
                                           "peak_slip_power_W", "sliding_distance_m", "peak_engine_rpm",
                                           "engine_droop_rpm", "energies_J", "energy_balance", "load_torque_Nm",
                                           "idle_rpm", "solver")}
        if trajectory:
            d.update(times_s=self.times_s.tolist(), engine_rpm=self.engine_rpm.tolist(),
                     drum_rpm=self.drum_rpm.tolist(), slip_power_W=self.slip_power_W.tolist())
        return clean(d)


class _Torques:
    """M_e(n), M_c(n) and p_i(n) of one start, n in rpm (module docstring)."""

    def __init__(self, engine: EngineCurve, rpm, torque, pressure):
        rpm = np.asarray(rpm, dtype=float)
        torque = np.asarray(torque, dtype=float)
        if rpm.ndim != 1 or rpm.shape != torque.shape or len(rpm) < 2:
            raise InputError(f"clutch torque table: {rpm.size} speeds and {torque.size} torques; give at least 2 "
                             "pairs (rpm, N m) of the same length")
        if not (np.all(np.isfinite(rpm)) and np.all(np.isfinite(torque))) or np.any(np.diff(rpm) <= 0):
            raise InputError("clutch torque table: the speeds must be finite and strictly increasing, the torques "
                             "finite")
        if np.any(torque < 0):
            raise InputError(f"clutch torque table: torques must be >= 0 N m (got {torque.min():g} N m)")
        self.engine = engine
        self.lo, self.hi = engine.rpm_range
        self.table = (float(rpm[0]), float(rpm[-1]))
        self.clutch = _Cubic(rpm, torque)
        self.full = _Cubic(engine.rpm, engine.torque)
        self.p = None
        if pressure is not None:
            p = np.asarray(pressure, dtype=float)
            if p.ndim != 2 or p.shape[0] != len(rpm) or not np.all(np.isfinite(p)) or np.any(p < 0):
                raise InputError(f"pressure table: shape {p.shape}, expected ({len(rpm)}, nodes) of finite "
                                 "pressures >= 0 Pa at the torque table's speeds")
            self.rpm, self.p = rpm, p

    def engine_torque(self, n: float) -> float:
        top = self.hi
        if n <= self.lo:
            return self.full(self.lo)
        if n <= top:
            return self.full(n)
        return self.full(top) * max(0.0, 1.0 - (n - top) / (LIMITER_SHARE * top))

    def clutch_torque(self, n: float) -> float:
        if n < self.table[0]:
            return 0.0 if self.clutch(self.table[0]) == 0.0 else self._outside(n)
        if n > self.table[1]:
            return self._outside(n)
        return max(self.clutch(n), 0.0)

    def clutch_torques(self, n: np.ndarray) -> np.ndarray:
        """:meth:`clutch_torque` of every speed of ``n`` at once: the same values bit for bit
        (the same Horner sums on the same pieces; a speed off the table refused as the first
        such speed of ``n`` would be)."""
        n = np.asarray(n, dtype=float)
        lo, hi = self.table
        off = (n > hi) | ((n < lo) & (self.clutch(lo) != 0.0))
        if off.any():
            self._outside(float(n[int(np.argmax(off))]))
        m = self.clutch.many(n)
        out = np.where(0.0 > m, 0.0, m)  # max(m, 0.0) as Python's max takes it
        out[n < lo] = 0.0
        return out

    def _outside(self, n: float) -> float:
        raise InputError(f"clutch torque table covers {self.table[0]:.0f}..{self.table[1]:.0f} rpm but the engine "
                         f"reached {n:.0f} rpm: give the table from a speed where the clutch transmits nothing "
                         f"up to the engine's top speed plus its rev limiter ({self.hi * (1 + LIMITER_SHARE):.0f} "
                         "rpm)")



class _Cubic:
    """The monotone PCHIP interpolant of a table, evaluated one scalar at a time without
    numpy's per-call overhead (the ODE's right side calls it thousands of times)."""

    def __init__(self, x, y):
        pp = PchipInterpolator(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        self.x = [float(v) for v in pp.x]
        self.c = [[float(v) for v in col] for col in pp.c.T]

    def __call__(self, v: float) -> float:
        k = min(max(bisect.bisect_right(self.x, v) - 1, 0), len(self.x) - 2)
        a, b, c, d = self.c[k]
        u = v - self.x[k]
        return ((a * u + b) * u + c) * u + d

    def many(self, v: np.ndarray) -> np.ndarray:
        """The interpolant at every value of ``v``: :meth:`__call__`'s pieces and Horner sums
        elementwise (float64 products and sums, no fused multiply-add: the same bits)."""
        x = np.asarray(self.x)
        k = np.clip(np.searchsorted(x, v, side="right") - 1, 0, len(x) - 2)
        c = np.asarray(self.c)[k]
        u = v - x[k]
        return ((c[:, 0] * u + c[:, 1]) * u + c[:, 2]) * u + c[:, 3]


def _positive(name: str, v, what: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not \
            math.isfinite(float(v)) or float(v) <= 0:
        raise ParameterError(name, v, what, "engagement transient")
    return float(v)


def engagement_transient(clutch_rpm, clutch_torque_Nm, engine: EngineCurve | None = None,
                         drive: DriveLine | None = None, *, load_torque: float | None = None,
                         held_engine_rpm: float | None = None, pressure_Pa=None, drum_radius: float | None = None,
                         rtol: float = 1e-10, max_step: float | None = None) -> Engagement:
    """One start: the engine from idle (or held at ``held_engine_rpm``) drives the drum
    through the slipping clutch until they lock (module docstring).

    Parameters
    ----------
    clutch_rpm, clutch_torque_Nm : sequence of float
        The torque the slipping clutch transmits [N m] against the engine speed [rpm]
        (strictly increasing speeds, from one where it transmits nothing to the engine's
        top speed and rev limiter).
    engine : EngineCurve, optional
        Full-throttle curve (default: the built-in, ASSUMED).
    drive : DriveLine, optional
        Inertias, loads, throttle ramp (default: the ASSUMED values).
    load_torque : float, optional
        Load on the driven side while it turns [N m] (default: ``drive.drag_torque``).
    held_engine_rpm : float, optional
        Hold the engine at this speed (an infinitely stiff engine; the closed-form check).
    pressure_Pa : array (len(clutch_rpm), m), optional
        Contact pressure of m shoe-face nodes at the table's speeds: the start then also
        integrates int p_i v dt per node (``pressure_sliding_Pa_m``).
    drum_radius : float, optional
        Drum radius [m] (the sliding distance; needed with ``pressure_Pa``).
    rtol : float
        Relative tolerance of the integration (absolute tolerances scale with it).
    max_step : float, optional
        Largest time step [s] (the convergence checks).

    Returns
    -------
    Engagement

    Examples
    --------
    >>> import clutchfem as cf
    >>> r = cf.engagement_transient([0, 20000], [5.0, 5.0], held_engine_rpm=8000,
    ...                             drive=cf.DriveLine(driven_inertia=2e-4), load_torque=0.0)
    >>> w = 8000 * 3.141592653589793 / 30
    >>> r.status, abs(r.slip_energy_J / (0.5 * 2e-4 * w * w) - 1) < 1e-8
    ('locks', True)
    """
    engine = EngineCurve.of(engine)
    drive = drive or DriveLine()
    if not isinstance(drive, DriveLine):
        raise ParameterError("drive", type(drive).__name__, "a DriveLine", "engagement transient")
    rtol = _positive("rtol", rtol, "a relative tolerance in (0, 1e-3]")
    if rtol > 1e-3 or rtol < 1e-13:
        raise ParameterError("rtol", rtol, "a relative tolerance in [1e-13, 1e-3]", "engagement transient")
    if max_step is not None:
        max_step = _positive("max_step", max_step, "a time step > 0 s")
    ML = drive.drag_torque if load_torque is None else load_torque
    if isinstance(ML, bool) or not isinstance(ML, (int, float)) or not math.isfinite(ML) or ML < 0:
        raise ParameterError("load_torque", ML, "a load torque >= 0 N m", "engagement transient")
    tq = _Torques(engine, clutch_rpm, clutch_torque_Nm, pressure_Pa)
    if tq.p is not None:
        drum_radius = _positive("drum_radius", drum_radius, "the drum radius > 0 m (with a pressure table)")
    R = drum_radius
    held = held_engine_rpm is not None
    if held:
        n0 = _positive("held_engine_rpm", held_engine_rpm, "an engine speed > 0 rpm")
    else:
        n0 = drive.idle_rpm or engine.idle_rpm or DEFAULT_IDLE_RPM
    Je, Jd = drive.engine_inertia, drive.driven_inertia
    t_r = 0.0 if held else drive.throttle_ramp
    m = 0 if tq.p is None else len(tq.rpm)  # sliding distance per table speed (hat functions)

    def rates(t, y):
        we, wd = y[0], max(y[1], 0.0)
        n = rad_s_to_rpm(we)
        Mc = tq.clutch_torque(n)
        moving = y[1] > 0.0 or Mc > ML
        dwd = (Mc - ML) / Jd if moving else 0.0
        if held:
            dwe, p_in = 0.0, Mc * we
        else:
            th = 1.0 if t_r == 0.0 or t >= t_r else t / t_r
            Me = th * tq.engine_torque(n)
            dwe, p_in = (Me - Mc) / Je, Me * we
        return np.array((dwe, dwd, p_in, Mc * (we - wd), ML * wd if moving else 0.0, we - wd))

    def lock(t, y):
        return y[0] - y[1]

    lock.terminal, lock.direction = True, -1
    w0 = rpm_to_rad_s(n0)
    y = np.zeros(6)
    y[0] = w0
    wmax = rpm_to_rad_s(max(n0, engine.rpm_range[1] * (1 + LIMITER_SHARE)))
    atol = np.full(6, rtol * wmax)
    e_scale = 0.5 * (Je + Jd) * wmax ** 2
    atol[2:5] = rtol * e_scale
    atol[5] = rtol * wmax * drive.max_time
    bounds = [0.0, t_r, drive.max_time] if 0.0 < t_r < drive.max_time else [0.0, drive.max_time]
    ts, ys, nfev, locked = [], [], 0, False
    by_rpm = np.zeros(m)
    for a, b in zip(bounds[:-1], bounds[1:]):
        sol = solve_ivp(rates, (a, b), y, method="DOP853", rtol=rtol, atol=atol, events=lock, dense_output=True,
                        max_step=max_step if max_step is not None else np.inf)
        if sol.status < 0:
            raise InputError(f"engagement transient: the integration failed ({sol.message})")
        nfev += sol.nfev
        t_end = float(sol.t[-1])
        tt = np.unique(np.concatenate([np.linspace(a, t_end, SAMPLES), sol.t]))
        ts.append(tt)
        ys.append(sol.sol(tt))
        if m:
            by_rpm += _sliding_by_rpm(sol, a, t_end, tq.rpm, R)
        y = sol.y[:, -1].copy()
        if sol.status == 1 and len(sol.t_events[0]):
            # the state at the event is the dense output's (an interpolant of lower order whose
            # error the step control does not bound): step from the last accepted step to the
            # lock-up instant itself, so that the energies at lock-up carry the step's
            # tolerance (the energy balance closes to ~rtol, not to the interpolant's error)
            if len(sol.t) >= 2 and sol.t[-2] < t_end:
                end = solve_ivp(rates, (float(sol.t[-2]), t_end), sol.y[:, -2], method="DOP853", rtol=rtol,
                                atol=atol, max_step=max_step if max_step is not None else np.inf)
                if end.status < 0:
                    raise InputError(f"engagement transient: the integration failed ({end.message})")
                nfev += end.nfev
                y = end.y[:, -1].copy()
            locked = True
            break
    t = np.concatenate(ts)
    Y = np.concatenate(ys, axis=1)
    return _answer(t, Y, y, locked, tq, n0, Je, Jd, ML, R, held, by_rpm if m else None, nfev, rtol)


def _sliding_by_rpm(sol, a: float, b: float, rpm: np.ndarray, R: float) -> np.ndarray:
    """The sliding distance [m] a run spends at each speed of the table on [a, b]: the
    integral of R (w_e - w_d) hat_k(n_e(t)) dt with hat_k the linear-interpolation weights of
    the table speeds, by the trapezoid rule on the dense solution at :data:`FINE` points (and
    the integrator's own steps).  Outside the integration: the hats are kinked at the table's
    speeds, which made the integrator take ~4x the steps when they were states of the ODE."""
    tt = np.unique(np.concatenate([np.linspace(a, b, FINE), sol.t[(sol.t >= a) & (sol.t <= b)]]))
    Y = sol.sol(tt)
    n = rad_s_to_rpm(Y[0])
    v = R * (Y[0] - Y[1])
    k = np.clip(np.searchsorted(rpm, n, side="right") - 1, 0, len(rpm) - 2)
    w = np.clip((n - rpm[k]) / (rpm[k + 1] - rpm[k]), 0.0, 1.0)
    dt = np.diff(tt)
    out = np.zeros(len(rpm))
    for kk, ww in ((k, 1.0 - w), (k + 1, w)):  # trapezoid: each interval's two ends, half each
        f = ww * v
        np.add.at(out, kk[:-1], 0.5 * dt * f[:-1])
        np.add.at(out, kk[1:], 0.5 * dt * f[1:])
    return out


def _answer(t, Y, y, locked, tq, n0, Je, Jd, ML, R, held, by_rpm, nfev, rtol) -> Engagement:
    """The answers of a run (module docstring)."""
    we, wd = Y[0], np.maximum(Y[1], 0.0)
    n_e = rad_s_to_rpm(we)
    Mc = tq.clutch_torques(n_e)
    P = Mc * np.maximum(we - wd, 0.0)
    E_in, E_slip, E_load = (float(v) for v in y[2:5])
    w0 = rpm_to_rad_s(n0)
    dKe = 0.0 if held else 0.5 * Je * (y[0] ** 2 - w0 ** 2)
    dKd = 0.5 * Jd * max(y[1], 0.0) ** 2
    resid = E_in - dKe - dKd - E_slip - E_load
    scale = max(abs(E_in), abs(dKe) + dKd + abs(E_slip) + abs(E_load), 1e-300)
    k_pk = int(np.argmax(n_e))
    droop = float(n_e[k_pk] - n_e[k_pk:].min())
    if locked:
        status = "locks"
    elif E_slip <= 0.0:
        status = "never engages"
    else:
        status = "never locks"
    return Engagement(
        status=status, time_to_lockup_s=float(t[-1]) if locked else None,
        lockup_rpm=float(rad_s_to_rpm(y[0])) if locked else None, slip_energy_J=E_slip,
        peak_slip_power_W=float(P.max()), sliding_distance_m=None if R is None else float(R * y[5]),
        peak_engine_rpm=float(n_e[k_pk]), engine_droop_rpm=droop,
        energies_J={"engine_work_J": E_in, "engine_kinetic_J": dKe, "driven_kinetic_J": dKd, "slip_heat_J": E_slip,
                    "load_work_J": E_load, "residual_J": resid},
        energy_balance=float(abs(resid) / scale), load_torque_Nm=float(ML), idle_rpm=float(n0),
        times_s=t, engine_rpm=n_e, drum_rpm=rad_s_to_rpm(wd), slip_power_W=P,
        sliding_by_rpm_m=None if by_rpm is None else np.maximum(by_rpm, 0.0),
        pressure_sliding_Pa_m=None if by_rpm is None else np.maximum(by_rpm, 0.0) @ tq.p,
        solver={"method": "DOP853", "rtol": rtol, "rhs_evaluations": int(nfev), "engine_held": bool(held)})
