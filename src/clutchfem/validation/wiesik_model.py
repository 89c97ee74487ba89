"""The seed-000 load model (J. Wiesik, chain saw clutch load): drive data, the clutch load
over an engine cycle, the probability that a cycle slips, two slip-loss models, the shoe
mass against slip, and the range a computed value spans over the paper's rounded inputs.

The paper's equations (Husqvarna 357 XP, 56.5 cm3; :mod:`.wiesik` compares the numbers):

* instantaneous clutch load ``M = M_b + M_p`` (10) with the inertia part
  ``M_b = (J_b + m_p r_k^2) delta w_sr^2 cos(w_sr t)`` (11) and the cutting part
  ``M_p = M_o (1 - cos(w_sr t))`` (12); no slip iff ``M_s >= M`` over the cycle (13).
  Over one cycle ``dM/dtheta = (M_o - J delta w^2) sin(theta)``, so the peak load is
  ``max(J delta w^2, 2 M_o - J delta w^2)`` (:func:`peak_load`): for the paper's data the
  inertia peak at theta = 0 governs, as the paper states.
* probability that a cycle slips: ``delta ~ Normal(0.032, 0.013)`` (cycle to cycle),
  ``P = P(peak_load(delta) > M_s)`` with ``M_s`` at the mean speed w_sr
  (:func:`slip_probability`).  delta >= 0 by definition (eq 8): the Normal law's tail
  below 0 (0.7 % for the paper's data) is read as delta = 0, a smooth cycle.

The paper's design conclusions from eqs 4-5 (the spring's elastic tension at contact held):
the engagement speed of worn, lighter shoes (:func:`worn_engagement_speed`) and the shoe
mass that lifts M_s to a given load (:func:`shoe_mass_for_no_slip`, w_o kept or the spring
kept).  The clutch characteristic M_s(w) (eqs 1-5) is
:class:`clutchfem.clutch.BaselineClutch`, the speed ripple (eqs 6-9, 14)
:mod:`clutchfem.clutch.ripple`, the drive inertia of the paper's example
:mod:`clutchfem.clutch.drive`.

Models the paper does not spell out (all are ASSUMPTIONS):

* **Bar length -> chain mass** (:class:`ChainModel`): chain mass is proportional to the
  chain loop length ``2 L_bar + c0``.  ``c0 = 12 in`` from the standard 3/8" chain for a 15"
  bar, 56 drive links = 112 pitches x 0.375 in = 42 in = 2 x 15 + 12.  J_b (drum, sprocket,
  nose sprocket) is taken independent of the bar.  The paper's "-10 % chain mass for 13""
  is then a check, not an input.
* **Slip energy loss** (:func:`loss_deficit`, the reported model): the torque-deficit model
  ``loss = E[(M_peak - M_s)^+] / M_o``: in a cycle whose peak demand exceeds the clutch
  capacity, the shortfall ``M_peak - M_s`` is taken as torque lost for that whole engine
  cycle, relative to the mean transmitted torque ``M_o`` (both act through the same crank
  angle 2 pi per cycle, so this is an energy ratio).  It is a capacity-deficit measure, an
  upper-bound style estimate: it assumes the deficit is dissipated for a whole cycle.
* **Rigid-drum slip dynamics** (:func:`loss_dynamic`, for contrast): the crank speed is
  prescribed by eq 6, the drum + chain (inertia J) is driven through the clutch with torque
  capacity M_s against M_p; while slipping, friction dissipates ``M_s |w_crank - w_drum|``.

The rounding bound (:func:`rounding_bound`, the validation's rule R2): the range of a
computed value over the paper's printed inputs within their own rounding
(:data:`PRINTED_INPUT_HALF_UNITS`), restricted to the inputs consistent with the paper's
own M_b(2) = 13.31 N m (:data:`MB2_CONSISTENT_N_M`): linearised box, two linear programs,
exact re-evaluation at the extreme vertices.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from scipy import integrate
from scipy.optimize import linprog
from scipy.stats import norm

from ..clutch import SEED_CHAIN_MASS, SEED_J_B, SEED_SPROCKET_PITCH_RADIUS, BaselineClutch, reduced_inertia
from ..core import ParameterError, SolverError

__all__ = [
    "MB2_CONSISTENT_N_M",
    "PRINTED_INPUT_HALF_UNITS",
    "ChainModel",
    "DriveData",
    "RoundingBound",
    "active_load",
    "cycle_slip_energy",
    "inertia_load",
    "limit_inertia_load",
    "loss_deficit",
    "loss_dynamic",
    "peak_load",
    "rounding_bound",
    "shoe_mass_for_no_slip",
    "slip_probability",
    "total_load",
    "worn_engagement_speed",
]


@dataclass(frozen=True)
class ChainModel:
    """ASSUMED chain mass vs guide-bar length (see module docstring).

    m_ref [kg] chain mass on the reference bar (0.273 kg, 3/8" chain, 15" bar, seed 000);
    loop length = 2 L_bar + extra_in [in], extra_in = 12 in (56 drive links on a 15" bar).
    """

    m_ref: float = SEED_CHAIN_MASS
    bar_ref_in: float = 15.0
    extra_in: float = 12.0

    def mass(self, bar_in: float) -> float:
        """Chain mass [kg] for a bar of ``bar_in`` inches."""
        if not (math.isfinite(bar_in) and 8.0 <= bar_in <= 42.0):
            raise ParameterError("bar_in", bar_in, "guide-bar length 8 to 42 in")
        return self.m_ref * (2.0 * bar_in + self.extra_in) / (2.0 * self.bar_ref_in + self.extra_in)


@dataclass(frozen=True)
class DriveData:
    """Drive-line data of the paper's example (Husqvarna 357 XP), SI units.

    J_b [kg m^2] drum + sprockets reduced to the clutch axis; r_k [m] drive sprocket pitch
    radius; omega_sr [rad/s] mean speed; M_o [N m] mean cutting torque, s_p its std;
    delta_mean, delta_std: cycle-to-cycle Normal law of delta; k_sigma: the limit cycle
    (delta_mean + 3 s); bar_in: guide-bar length [in]; chain: chain-mass model.
    """

    J_b: float = SEED_J_B
    r_k: float = SEED_SPROCKET_PITCH_RADIUS
    omega_sr: float = 950.0
    M_o: float = 3.20
    s_p: float = 0.51
    delta_mean: float = 0.032
    delta_std: float = 0.013
    k_sigma: float = 3.0
    bar_in: float = 15.0
    chain: ChainModel = ChainModel()

    @property
    def m_p(self) -> float:
        """Chain mass [kg] for this bar."""
        return self.chain.mass(self.bar_in)

    @property
    def J(self) -> float:
        """Reduced inertia J_b + m_p r_k^2 [kg m^2] of eq 11."""
        return reduced_inertia(self.J_b, self.m_p, self.r_k)

    def with_(self, **changes) -> "DriveData":
        return replace(self, **changes)


def inertia_load(t, J: float, delta, omega_sr: float):
    """M_b(t) [N m], eq 11 (t [s])."""
    return J * np.asarray(delta) * omega_sr**2 * np.cos(omega_sr * np.asarray(t, dtype=float))


def active_load(t, M_o: float, omega_sr: float):
    """M_p(t) [N m], eq 12: zero at TDC (t = 0), 2 M_o at mid-cycle."""
    return M_o * (1.0 - np.cos(omega_sr * np.asarray(t, dtype=float)))


def total_load(t, J: float, delta, omega_sr: float, M_o: float):
    """M(t) = M_b + M_p [N m], eq 10."""
    return inertia_load(t, J, delta, omega_sr) + active_load(t, M_o, omega_sr)


def peak_load(delta, J: float, omega_sr: float, M_o: float):
    """Largest M(t) over one cycle [N m]: ``max(J delta w^2, 2 M_o - J delta w^2)``."""
    x = J * np.asarray(delta, dtype=float) * omega_sr**2
    return np.maximum(x, 2.0 * M_o - x)


def limit_inertia_load(drive: DriveData) -> float:
    """M_b(2) = J (delta_mean + k_sigma s) w_sr^2 [N m] (the paper's 13.31 N m)."""
    return drive.J * (drive.delta_mean + drive.k_sigma * drive.delta_std) * drive.omega_sr**2


def _delta_bounds(M_s: float, drive: DriveData) -> tuple[float, float]:
    """A cycle slips iff delta > d_hi (inertia peak) or 0 <= delta < d_lo (cutting peak).

    delta >= 0 by definition (eq 8); the Normal law's tail below 0 (0.7 % for the paper's
    data) is read as delta = 0, a smooth cycle.  d_lo <= 0 means the cutting peak alone
    never slips the clutch.
    """
    jw2 = drive.J * drive.omega_sr**2
    return M_s / jw2, (2.0 * drive.M_o - M_s) / jw2


def slip_probability(M_s: float, drive: DriveData) -> float:
    """Probability that one engine cycle's peak load exceeds the clutch torque M_s [N m]."""
    d_hi, d_lo = _delta_bounds(M_s, drive)
    if d_lo >= d_hi:
        return 1.0
    m, s = drive.delta_mean, drive.delta_std
    p_low = float(norm.cdf(d_lo, m, s)) if d_lo > 0.0 else 0.0
    return float(norm.sf(d_hi, m, s)) + p_low


def loss_deficit(M_s: float, drive: DriveData) -> float:
    """Torque-deficit slip loss ``E[(M_peak - M_s)^+] / M_o`` (fraction, not %).

    Expectation over delta ~ Normal(delta_mean, delta_std) by adaptive quadrature of the
    exact peak load (:func:`peak_load`).  See the module docstring for the model.
    """
    m, s = drive.delta_mean, drive.delta_std

    def f(d: float) -> float:
        excess = float(peak_load(max(d, 0.0), drive.J, drive.omega_sr, drive.M_o)) - M_s
        return max(excess, 0.0) * norm.pdf(d, m, s)

    d_hi, d_lo = _delta_bounds(M_s, drive)
    a, b = m - 10.0 * s, m + 10.0 * s
    pts = [p for p in (d_hi, d_lo, 0.0) if a < p < b]
    val, _ = integrate.quad(f, a, b, points=pts or None, limit=200, epsabs=1e-12, epsrel=1e-10)
    return val / drive.M_o


def cycle_slip_energy(
    delta, M_s: float, drive: DriveData, n_cycles: int = 3, steps_per_cycle: int = 2000
) -> np.ndarray:
    """Friction energy [J] dissipated in the last of ``n_cycles`` cycles (rigid-drum model).

    Crank speed prescribed by eq 6 (the crank/flywheel inertia is taken as infinite: an
    upper bound on slip), drum + chain inertia J driven by the clutch torque, limited to
    +-M_s, against the cutting load M_p (eq 12).  Start locked at TDC; explicit time
    stepping with re-lock detection; vectorised over ``delta``.
    """
    d = np.atleast_1d(np.asarray(delta, dtype=float))
    w, J, Mo = drive.omega_sr, drive.J, drive.M_o
    dt = 2.0 * np.pi / w / steps_per_cycle
    wd = np.full(d.shape, w)  # drum speed; starts locked at theta = 0 where w_crank = w
    sgn = np.zeros(d.shape)  # 0 locked, +1 crank faster (drum lags), -1 drum faster
    energy = np.zeros(d.shape)
    for c in range(n_cycles):
        energy[:] = 0.0
        for i in range(steps_per_cycle):
            t = (c * steps_per_cycle + i) * dt
            th = w * t
            wc = w * (1.0 + d * np.sin(th))
            need = J * d * w**2 * np.cos(th) + Mo * (1.0 - np.cos(th))
            mp = Mo * (1.0 - np.cos(th))
            unlock = (sgn == 0) & (np.abs(need) > M_s)
            sgn = np.where(unlock, np.sign(need), sgn)
            slipping = sgn != 0
            ad = (sgn * M_s - mp) / J
            wd_new = np.where(slipping, wd + ad * dt, w * (1.0 + d * np.sin(w * (t + dt))))
            wc_new = w * (1.0 + d * np.sin(w * (t + dt)))
            energy += np.where(slipping, M_s * 0.5 * (np.abs(wc - wd) + np.abs(wc_new - wd_new)) * dt, 0.0)
            relock = slipping & (np.sign(wc_new - wd_new) != sgn)
            wd = np.where(relock, wc_new, wd_new)
            sgn = np.where(relock, 0.0, sgn)
    return energy


def loss_dynamic(M_s: float, drive: DriveData, n_delta: int = 40) -> float:
    """Expected friction loss per cycle / engine work per cycle (2 pi M_o), rigid-drum model."""
    d_hi, d_lo = _delta_bounds(M_s, drive)
    m, s = drive.delta_mean, drive.delta_std
    top = min(m + 8.0 * s, 0.99)
    if d_hi >= top:
        return 0.0
    nodes = np.linspace(d_hi, top, n_delta)
    e = cycle_slip_energy(nodes, M_s, drive)
    val = np.trapezoid(e * norm.pdf(nodes, m, s), nodes)
    if d_lo > 0.0:  # slips on the cutting-load branch as well (delta < 0 read as 0)
        low = np.linspace(0.0, d_lo, n_delta)
        e2 = cycle_slip_energy(low, M_s, drive)
        val += np.trapezoid(e2 * norm.pdf(low, m, s), low) + e2[0] * norm.cdf(0.0, m, s)
    return float(val / (2.0 * np.pi * drive.M_o))


def worn_engagement_speed(new: BaselineClutch, m_worn: float) -> float:
    """Engagement speed [rad/s] of the same clutch with lighter (worn) shoes, same spring.

    With the spring's elastic tension at contact unchanged, eq 4 at N = 0 gives
    ``(m r_s + 2 q r_spr^2 cos gamma) w_o^2 = const``.  (Neglecting the extra spring stretch
    from the thinner lining, which would raise w_o further.)
    """
    worn = new.with_(m_s=m_worn)
    return new.w_o * math.sqrt(new.effective_first_moment / worn.effective_first_moment)


def shoe_mass_for_no_slip(
    clutch: BaselineClutch,
    target_torque: float,
    omega: float,
    keep: Literal["engagement", "spring"] = "engagement",
) -> tuple[float, float]:
    """Shoe mass [kg] (and resulting w_o [rad/s]) giving ``M_s(omega) = target_torque``.

    keep='engagement': w_o is kept (the spring is re-rated so the chain still stands at
    idle, the design-relevant choice); keep='spring': same spring, w_o falls as the mass
    grows (eq 4 at N = 0, see :func:`worn_engagement_speed`).  Closed form from eq 5.
    """
    c = clutch.r_b * clutch.k * clutch.mu
    sq = clutch.spring_mass_term
    if keep == "engagement":
        if omega <= clutch.w_o:
            raise ParameterError("omega", omega, f"> w_o = {clutch.w_o} rad/s")
        m = (target_torque / (c * (omega**2 - clutch.w_o**2)) - sq) / clutch.r_s
        return m, clutch.w_o
    if keep == "spring":
        p0 = clutch.effective_first_moment * clutch.w_o**2
        m = ((target_torque / c + p0) / omega**2 - sq) / clutch.r_s
        return m, math.sqrt(p0 / (m * clutch.r_s + sq))
    raise ParameterError("keep", keep, "'engagement' or 'spring'")


#: Inputs of the cycle statistics as the paper prints them, with half a unit of the last
#: printed digit (their rounding): delta_sr = 0.032, s = 0.013 (2 digits), J_b = 85.10e-6
#: kg m^2, r_k = 0.0212 m, m_p = 0.273 kg (chain on the 15" bar), M_o = 3.20 N m, and the
#: clutch torque the paper carries into its statistics, M_s = 10.23 / 8.61 N m.
PRINTED_INPUT_HALF_UNITS: dict[str, float] = {
    "delta_mean": 5e-4, "delta_std": 5e-4, "J_b": 0.005e-6, "r_k": 0.5e-4, "m_ref": 0.5e-3,
    "M_o": 0.005, "M_s": 0.005,
}
#: The paper's own M_b(2) = 13.31 N m pins J (delta_sr + 3 s) w_sr^2: inputs are consistent
#: with it when M_b(2) lies in [13.305, 13.32) N m (13.31 rounded *or* truncated: the
#: printed inputs give 13.3152, which the paper prints as 13.31).
MB2_CONSISTENT_N_M: tuple[float, float] = (13.305, 13.32)


@dataclass(frozen=True)
class RoundingBound:
    """Range of a computed value over the paper's inputs within their printed rounding.

    ``lo``/``hi``: the value at the two vertices of the (linearised) input box that minimise
    and maximise it, re-evaluated exactly; ``nominal``: at the printed inputs;
    ``constrained``: whether M_b(2) in :data:`MB2_CONSISTENT_N_M` was imposed.
    """

    nominal: float
    lo: float
    hi: float
    constrained: bool

    def tol_for(self, paper: float, paper_half_unit: float) -> float:
        """Relative tolerance: the paper's value (give or take half its last printed digit)
        must lie in [lo, hi]; the side of the range towards the paper is used.  Negative
        values cannot occur (nominal is clipped into the range)."""
        hi, lo = max(self.hi, self.nominal), min(self.lo, self.nominal)
        reach = (hi - self.nominal) if paper >= self.nominal else (self.nominal - lo)
        return (reach + paper_half_unit) / abs(paper)


def _apply_inputs(drive: DriveData, ms: float, x: dict[str, float]) -> tuple[DriveData, float]:
    chain = replace(drive.chain, m_ref=x["m_ref"])
    d = replace(drive, delta_mean=x["delta_mean"], delta_std=x["delta_std"], J_b=x["J_b"],
                r_k=x["r_k"], M_o=x["M_o"], chain=chain)
    return d, x["M_s"]


def rounding_bound(fn: Callable[[DriveData, float], float], drive: DriveData, ms: float,
                   constrain_mb2: bool = True) -> RoundingBound:
    """Range of ``fn(drive, M_s)`` over :data:`PRINTED_INPUT_HALF_UNITS` (rule R2).

    Linearised by central differences (step = half unit) about the printed inputs; the
    extreme vertices of the box ``|dx_i| <= h_i`` (intersected, when ``constrain_mb2``, with
    the slab ``M_b(2)`` in :data:`MB2_CONSISTENT_N_M`, also linearised) come from two small
    linear programs; ``fn`` is then evaluated exactly at those vertices.  ``drive`` may have
    another bar length: the constraint always uses the 15" bar, as the paper's M_b(2).
    """
    names = list(PRINTED_INPUT_HALF_UNITS)
    h = np.array([PRINTED_INPUT_HALF_UNITS[n] for n in names])
    x0 = {"delta_mean": drive.delta_mean, "delta_std": drive.delta_std, "J_b": drive.J_b,
          "r_k": drive.r_k, "m_ref": drive.chain.m_ref, "M_o": drive.M_o, "M_s": ms}

    def at(dx) -> dict[str, float]:
        return {n: x0[n] + float(v) for n, v in zip(names, dx)}

    def f(dx) -> float:
        return float(fn(*_apply_inputs(drive, ms, at(dx))))

    def mb2(dx) -> float:
        d, _ = _apply_inputs(drive, ms, at(dx))
        return limit_inertia_load(replace(d, bar_in=15.0))

    def grad(g) -> np.ndarray:
        out = np.empty(len(names))
        for i, hi in enumerate(h):
            e = np.zeros(len(names))
            e[i] = hi
            out[i] = (g(e) - g(-e)) / (2 * hi)
        return out

    f0 = f(np.zeros(len(names)))
    gf = grad(f)
    kw: dict = {"bounds": list(zip(-h, h)), "method": "highs"}
    if constrain_mb2:
        c0, gc = mb2(np.zeros(len(names))), grad(mb2)
        lo_c, hi_c = MB2_CONSISTENT_N_M
        kw |= {"A_ub": np.vstack([gc, -gc]), "b_ub": np.array([hi_c - c0, c0 - lo_c])}
    vals = []
    for sign in (1.0, -1.0):
        res = linprog(sign * gf, **kw)
        if not res.success:
            raise SolverError(f"rounding bound: {res.message}")
        vals.append(f(res.x))
    return RoundingBound(f0, min(vals), max(vals), constrain_mb2)
