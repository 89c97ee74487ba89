"""Internal expanding shoe model of a centrifugal clutch (plus / minus shoe).

Sources: thesis ``003`` (Chalmers 2020) section 2.1, eqs 1-8, 11, 12, which quote
Maegi et al. (2017, pp. 303, 338-339); the same derivation is Shigley's "internal expanding
rim brake" (Shigley's Mechanical Engineering Design, ch. 16).  SI units throughout.

Geometry and sign conventions (one shoe, seen along the crankshaft)
--------------------------------------------------------------------
* ``R`` [m]: drum inner radius (the lining sits on it when engaged).
* ``A`` [m]: distance from the drum centre O to the shoe's pivot P (for a compliant shoe:
  the flexure's rotation centre).  ``0 < A < R``.
* ``phi`` [rad]: angle at O measured from the ray O->P to a point of the lining, positive in
  the direction pointing from the pivot to the lining.  The lining spans
  ``0 <= phi1 < phi2 <= pi`` (so ``sin(phi) >= 0`` and the Shigley pressure law is >= 0).
* ``L`` [m]: lever arm of the apply force F about the pivot (F = centrifugal force of the
  shoe minus the spring/flexure force, eq 3).
* Pressure law (Shigley): ``p(phi) = p_max sin(phi) / sin(phi_a)``, ``phi_a`` the angle of
  the largest ``sin`` inside the lining (pi/2 when the lining covers it).

Moments about the pivot of the drum's action on the lining (derived in
:func:`quadrature_shoe_torque` from the force vectors): the normal pressure gives
``M_N = p0 b R A I_ss``, the friction ``M_f = mu p0 b R (R I_s - A I_sc)`` with
``p0 = p_max / sin(phi_a)`` and ``b`` the face width; the friction torque on the drum is
``M = mu p0 b R^2 I_s``.

* **Plus (self-energising) shoe**: the friction moment about the pivot has the same sense
  as the apply force's moment, ``F L = M_N - M_f``.  In a clutch whose drum is held while the
  hub turns, this is the case when the lining lies *ahead* of the pivot in the hub's
  direction of rotation (the pivot pushes the shoe; the drum's relative motion drags the
  lining towards the pivot and wedges it in).
* **Minus shoe**: the pivot is ahead (the shoe trails behind its flexure), friction pulls
  the lining off the drum, ``F L = M_N + M_f``.

Eliminating ``p0 b R^2`` gives eq 2 (plus) and eq 7 (minus):
``M = mu I_s F L / ((A/R) I_ss -/+ mu (I_s - (A/R) I_sc))``.  A plus shoe whose denominator
is <= 0 is **self-locking**: any apply force gives unbounded torque (in practice: the
clutch grabs and stalls the engine).  This module never returns a negative torque for that
case; it returns ``inf`` with ``self_locking=True``.

The printed thesis eq 4 reads ``I_s = cos(phi2) - cos(phi1)``; the integral of sin from
phi1 to phi2 is ``cos(phi1) - cos(phi2)`` (positive for 0 <= phi1 < phi2 <= pi) and the
thesis's own MATLAB script (appendix 1) uses ``Is=(cos(fi1)-cos(fi2))``: the printed sign is
a typo and the derived sign is used here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, NamedTuple

import numpy as np
from scipy import integrate

from ..core import ParameterError, rpm_to_rad_s

ShoeKind = Literal["plus", "minus"]
_KINDS = ("plus", "minus")

__all__ = [
    "ShoeKind",
    "shoe_kind",
    "LiningIntegrals",
    "ShoeGeometry",
    "TorqueFactor",
    "ShoeTorque",
    "CentrifugalShoe",
    "QuadratureShoe",
    "lining_integrals",
    "torque_factor",
    "arc_torque",
    "shoe_torque",
    "engagement_speed",
    "apply_force",
    "simplified_torque",
    "torque_from_normal_force",
    "pressure_distribution",
    "quadrature_shoe_torque",
]


def _check_kind(kind: str) -> ShoeKind:
    if kind not in _KINDS:
        raise ParameterError("kind", kind, "'plus' (self-energising) or 'minus'")
    return kind  # type: ignore[return-value]


def shoe_kind(arrangement: str, rotation: str) -> ShoeKind:
    """The kind of a concept's shoe: its flexure ``arrangement`` ('plus' or 'minus', named for
    a hub turning ccw) turning in ``rotation`` ('ccw' or 'cw').  A 'minus' arrangement turning
    ccw is a minus shoe; flipping either flips the kind (the pivot then leads instead of
    trailing, module docstring)."""
    plus = (arrangement == "plus") == (rotation == "ccw")
    return "plus" if plus else "minus"


def _check_positive(name: str, value: float, unit: str, allow_zero: bool = False) -> float:
    v = float(value)
    ok = (v >= 0.0) if allow_zero else (v > 0.0)
    if not (math.isfinite(v) and ok):
        rel = ">= 0" if allow_zero else "> 0"
        raise ParameterError(name, value, f"finite and {rel} {unit}".rstrip())
    return v


def _check_mu(mu: float) -> float:
    v = float(mu)
    if not (math.isfinite(v) and 0.0 <= v < 2.0):
        raise ParameterError("mu", mu, "friction coefficient in [0, 2)")
    return v


class LiningIntegrals(NamedTuple):
    """The three lining integrals of thesis eqs 4-6 (dimensionless)."""

    I_s: float
    """int_{phi1}^{phi2} sin(phi) dphi = cos(phi1) - cos(phi2) (eq 4, sign corrected)."""
    I_ss: float
    """int sin^2(phi) dphi = (phi2 - phi1)/2 - (sin 2phi2 - sin 2phi1)/4 (eq 5)."""
    I_sc: float
    """int sin(phi) cos(phi) dphi = (cos 2phi1 - cos 2phi2)/4 (eq 6)."""


def _check_angles(phi1: float, phi2: float) -> tuple[float, float]:
    p1, p2 = float(phi1), float(phi2)
    if not (math.isfinite(p1) and 0.0 <= p1 < math.pi):
        raise ParameterError("phi1", phi1, "lining start angle in [0, pi) rad from the pivot ray")
    if not (math.isfinite(p2) and p1 < p2 <= math.pi):
        raise ParameterError("phi2", phi2, f"lining end angle in (phi1={p1:.6g}, pi] rad")
    return p1, p2


def _check_geometry(A: float, R: float, L: float) -> None:
    _check_positive("R", R, "m")
    if _check_positive("A", A, "m") >= R:
        raise ParameterError("A", A, f"pivot inside the drum: 0 < A < R = {R} m")
    _check_positive("L", L, "m")


def lining_integrals(phi1: float, phi2: float) -> LiningIntegrals:
    """Closed-form lining integrals I_s, I_ss, I_sc (thesis eqs 4-6) for angles in rad."""
    p1, p2 = _check_angles(phi1, phi2)
    return LiningIntegrals(*(float(v) for v in _integrals(p1, p2)))


def _integrals(p1, p2):
    """(I_s, I_ss, I_sc) for angles (floats or arrays, checked by the caller)."""
    return (np.cos(p1) - np.cos(p2), 0.5 * (p2 - p1) - 0.25 * (np.sin(2.0 * p2) - np.sin(2.0 * p1)),
            0.25 * (np.cos(2.0 * p1) - np.cos(2.0 * p2)))


def _factor(integrals, a: float, L: float, mu: float, kind: ShoeKind):
    """(M/F, denominator) of eq 2 (plus) / eq 7 (minus) for lining integrals (floats or
    arrays); a = A / R.  M/F is inf where the denominator is <= 0 (self-locking)."""
    I_s, I_ss, I_sc = integrals
    sign = -1.0 if kind == "plus" else 1.0
    den = a * I_ss + sign * mu * (I_s - a * I_sc)
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(den > 0.0, mu * I_s * L / np.where(den > 0.0, den, 1.0), np.inf)
    return k, den


@dataclass(frozen=True)
class ShoeGeometry:
    """Geometry of one shoe (see the module docstring for the conventions).

    phi1, phi2 [rad]: lining extent from the pivot ray; A [m]: drum centre to pivot;
    R [m]: drum inner radius; L [m]: lever arm of the apply force about the pivot.
    """

    phi1: float
    phi2: float
    A: float
    R: float
    L: float

    def __post_init__(self) -> None:
        _check_angles(self.phi1, self.phi2)
        _check_geometry(self.A, self.R, self.L)

    @property
    def integrals(self) -> LiningIntegrals:
        return lining_integrals(self.phi1, self.phi2)

    @property
    def phi_a(self) -> float:
        """Angle of maximum pressure (largest sin(phi) on the lining) [rad]."""
        if self.phi1 <= math.pi / 2 <= self.phi2:
            return math.pi / 2
        return self.phi2 if self.phi2 < math.pi / 2 else self.phi1


class TorqueFactor(NamedTuple):
    """Per-shoe torque per unit apply force, ``M = k F`` [m]; see :func:`torque_factor`."""

    k: float
    """M/F [N m per N] = mu I_s L / denominator; ``inf`` when self-locking."""
    denominator: float
    """(A/R) I_ss -/+ mu (I_s - (A/R) I_sc) (dimensionless); <= 0 means self-locking."""
    self_locking: bool


def torque_factor(geometry: ShoeGeometry, mu: float, kind: ShoeKind) -> TorqueFactor:
    """Torque per unit apply force of one shoe, eq 2 (plus) / eq 7 (minus)."""
    mu = _check_mu(mu)
    kind = _check_kind(kind)
    k, den = _factor(geometry.integrals, geometry.A / geometry.R, geometry.L, mu, kind)
    return TorqueFactor(float(k), float(den), bool(den <= 0.0))


def arc_torque(F, phi1, phi2, A: float, R: float, L: float, mu: float, kind: ShoeKind, n: int = 1) -> np.ndarray:
    """Total torque [N m] of n shoes, eqs 2/7 and 8, for apply forces ``F`` [N] on linings
    ``phi1``..``phi2`` [rad] (arrays of one length: one lining per force; the geometry
    otherwise as :class:`ShoeGeometry`): the vectorised :func:`shoe_torque` (inf where
    self-locking and F > 0).  Angles outside 0 <= phi1 < phi2 <= pi are refused, naming the
    first."""
    F, p1, p2 = (np.asarray(x, dtype=float) for x in (F, phi1, phi2))
    bad = ~(np.isfinite(p1) & np.isfinite(p2) & (p1 >= 0.0) & (p1 < p2) & (p2 <= math.pi))
    if np.any(bad):
        i = int(np.argmax(bad))
        _check_angles(p1.flat[i], p2.flat[i])
    if np.any(~np.isfinite(F)) or np.any(F < 0.0):
        raise ParameterError("F", F.min() if F.size else F, "apply force finite and >= 0 N")
    _check_geometry(A, R, L)
    k, _ = _factor(_integrals(p1, p2), A / R, L, _check_mu(mu), _check_kind(kind))
    with np.errstate(invalid="ignore"):
        m = np.where(F > 0.0, k * F, 0.0)
    return _check_n(n) * m


@dataclass(frozen=True)
class ShoeTorque:
    """Result of a torque evaluation (arrays broadcast with the input speed/force).

    ``per_shoe`` and ``total`` [N m] are >= 0; where the apply force is > 0 and the shoe is
    self-locking they are ``inf`` and ``self_locking`` is True.
    """

    apply_force: np.ndarray
    per_shoe: np.ndarray
    total: np.ndarray
    n: int
    self_locking: bool
    denominator: float


def _torque_from_force(F: np.ndarray, factor: TorqueFactor) -> np.ndarray:
    if factor.self_locking:
        return np.where(F > 0.0, np.inf, 0.0)
    return factor.k * F


def shoe_torque(
    F, geometry: ShoeGeometry, mu: float, kind: ShoeKind, n: int = 1
) -> ShoeTorque:
    """Friction torque for apply force(s) ``F`` [N] (array ok), eqs 2/7 and M_tot = n M (8).

    Negative apply forces are a caller error (below engagement the shoe does not touch the
    drum; use :func:`apply_force`, which clips at zero).
    """
    F = np.asarray(F, dtype=float)
    if np.any(~np.isfinite(F)) or np.any(F < 0.0):
        raise ParameterError("F", F.min() if F.size else F, "apply force finite and >= 0 N")
    n = _check_n(n)
    fac = torque_factor(geometry, mu, kind)
    m = _torque_from_force(F, fac)
    return ShoeTorque(F, m, n * m, n, fac.self_locking, fac.denominator)


def _check_n(n: int) -> int:
    if isinstance(n, bool) or int(n) != n or int(n) < 1:
        raise ParameterError("n", n, "number of shoes, integer >= 1")
    return int(n)


def engagement_speed(F_f: float, m: float, R_Tp: float) -> float:
    """Engagement angular speed ``w0 = sqrt(F_f / (m R_Tp))`` [rad/s] (thesis eq 1).

    F_f [N]: spring (flexure) force when the shoe touches the drum; m [kg]: shoe mass;
    R_Tp [m]: drum centre to the shoe's centre of mass.
    """
    F_f = _check_positive("F_f", F_f, "N", allow_zero=True)
    m = _check_positive("m", m, "kg")
    R_Tp = _check_positive("R_Tp", R_Tp, "m")
    return math.sqrt(F_f / (m * R_Tp))


def _omega_array(omega) -> np.ndarray:
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0.0):
        raise ParameterError("omega", omega, "angular speed(s) finite and >= 0 rad/s")
    return w


def apply_force(omega, m: float, R_Tp: float, F_f: float) -> np.ndarray:
    """Apply force per shoe ``F = m R_Tp w^2 - F_f`` [N] (thesis eq 3), clipped at 0.

    Below the engagement speed the shoe does not touch the drum and F = 0 (never negative).
    """
    w = _omega_array(omega)
    m = _check_positive("m", m, "kg")
    R_Tp = _check_positive("R_Tp", R_Tp, "m")
    F_f = _check_positive("F_f", F_f, "N", allow_zero=True)
    return np.maximum(m * R_Tp * w**2 - F_f, 0.0)


def simplified_torque(omega, m: float, R_Tp: float, F_f: float, mu: float, R: float, n: int = 1):
    """Point-load simplification ``M = n mu (m R_Tp w^2 - F_f) R`` [N m] (thesis eq 11).

    Like eq 3 the apply force is clipped at 0 below engagement.  It equals eqs 2/7 only for
    a short lining whose apply force acts on the contact point (L = A, mu -> 0); it is a
    trend tool (the thesis does not use it for results).
    """
    mu = _check_mu(mu)
    R = _check_positive("R", R, "m")
    return _check_n(n) * mu * apply_force(omega, m, R_Tp, F_f) * R


def torque_from_normal_force(N, mu: float, R: float):
    """``M = mu N R`` [N m] (thesis eq 12) for normal force(s) N >= 0 [N]."""
    N = np.asarray(N, dtype=float)
    if np.any(~np.isfinite(N)) or np.any(N < 0.0):
        raise ParameterError("N", N, "normal force(s) finite and >= 0 N")
    return _check_mu(mu) * N * _check_positive("R", R, "m")


@dataclass(frozen=True)
class CentrifugalShoe:
    """A centrifugal clutch made of ``n`` identical shoes (thesis eqs 1-3, 7, 8).

    m [kg]: mass of one shoe; R_Tp [m]: radius of its centre of mass; F_f [N]: spring /
    flexure force at first contact (referred to the line of the apply force); mu: friction
    coefficient; kind: 'plus' or 'minus' (see module docstring).
    """

    geometry: ShoeGeometry
    m: float
    R_Tp: float
    F_f: float
    mu: float
    n: int = 3
    kind: ShoeKind = "minus"

    def __post_init__(self) -> None:
        _check_positive("m", self.m, "kg")
        _check_positive("R_Tp", self.R_Tp, "m")
        _check_positive("F_f", self.F_f, "N", allow_zero=True)
        _check_mu(self.mu)
        _check_n(self.n)
        _check_kind(self.kind)

    @property
    def engagement_speed(self) -> float:
        """w0 [rad/s], eq 1."""
        return engagement_speed(self.F_f, self.m, self.R_Tp)

    def apply_force(self, omega) -> np.ndarray:
        """F(w) per shoe [N], eq 3, >= 0."""
        return apply_force(omega, self.m, self.R_Tp, self.F_f)

    def torque(self, omega) -> ShoeTorque:
        """Transmissible (slip) torque at angular speed(s) ``omega`` [rad/s], eqs 3, 7/2, 8."""
        return shoe_torque(self.apply_force(omega), self.geometry, self.mu, self.kind, self.n)

    def torque_at_rpm(self, rpm) -> np.ndarray:
        """Total clutch torque [N m] at crank speed(s) in rpm (inf where self-locking)."""
        return self.torque(rpm_to_rad_s(rpm)).total


# --------------------------------------------------------------------------------------
# Independent numerical check (Shigley): integrate the pressure over the lining.
# --------------------------------------------------------------------------------------


def pressure_distribution(phi, p_max: float, geometry: ShoeGeometry):
    """Shigley pressure law ``p = p_max sin(phi)/sin(phi_a)`` [Pa] on the lining."""
    phi = np.asarray(phi, dtype=float)
    return p_max * np.sin(phi) / math.sin(geometry.phi_a)


@dataclass(frozen=True)
class QuadratureShoe:
    """Result of :func:`quadrature_shoe_torque` (one shoe).

    torque [N m] on the drum; p_max [Pa] for the given face width; normal_moment and
    friction_moment [N m]: signed moments about the pivot (counter-clockwise positive, in the
    frame of :func:`quadrature_shoe_torque`) of the drum's normal and friction loads at the
    solution (per unit p_max when self-locking).
    """

    torque: float
    p_max: float
    normal_moment: float
    friction_moment: float
    self_locking: bool


def quadrature_shoe_torque(
    F: float, geometry: ShoeGeometry, mu: float, kind: ShoeKind, width: float = 1.0
) -> QuadratureShoe:
    """Shoe torque by numerical quadrature of the pressure and a moment balance about the pivot.

    Independent of the closed form: the moments are built from 2-D force vectors (cross
    products) at each lining point and integrated with ``scipy.integrate.quad``; nothing
    from :func:`lining_integrals` is used.  Pivot at P = (A, 0), drum centre at the origin,
    lining point Q = R (cos phi, sin phi).  The drum acts on the shoe with the normal load
    ``-p b R dphi (cos phi, sin phi)`` and the friction load ``s mu p b R dphi t`` with
    ``t = (-sin phi, cos phi)``; s = -1 for a plus shoe (drum's relative motion runs towards
    the pivot), s = +1 for a minus shoe.  Moment balance about P with the apply force's
    moment ``-F L`` (the apply force pushes the lining onto the drum) gives p_max; the
    torque on the drum is ``int mu p b R^2 dphi``.

    F [N] >= 0; width b [m] only scales p_max (the torque is independent of it).
    """
    F = _check_positive("F", F, "N", allow_zero=True)
    mu = _check_mu(mu)
    kind = _check_kind(kind)
    b = _check_positive("width", width, "m")
    A, R = geometry.A, geometry.R
    s = -1.0 if kind == "plus" else 1.0
    sin_a = math.sin(geometry.phi_a)

    def cross(rx, ry, fx, fy):
        return rx * fy - ry * fx

    def normal_integrand(phi):  # moment about P of the normal load for p_max = 1
        p = math.sin(phi) / sin_a
        rx, ry = R * math.cos(phi) - A, R * math.sin(phi)
        return cross(rx, ry, -p * b * R * math.cos(phi), -p * b * R * math.sin(phi))

    def friction_integrand(phi):  # moment about P of the friction load for p_max = 1
        p = math.sin(phi) / sin_a
        rx, ry = R * math.cos(phi) - A, R * math.sin(phi)
        return cross(rx, ry, s * mu * p * b * R * -math.sin(phi), s * mu * p * b * R * math.cos(phi))

    opts = dict(epsabs=0.0, epsrel=1e-12, limit=200)
    m_n, _ = integrate.quad(normal_integrand, geometry.phi1, geometry.phi2, **opts)
    m_f, _ = integrate.quad(friction_integrand, geometry.phi1, geometry.phi2, **opts)
    # Equilibrium of the shoe about P: F-moment (-F L) + p_max (m_n + m_f) = 0.
    resist = m_n + m_f  # moment the drum's reaction exerts per unit p_max (>0 resists F)
    if resist <= 0.0:
        torque = math.inf if F > 0.0 else 0.0
        return QuadratureShoe(torque, math.inf if F > 0.0 else 0.0, m_n, m_f, True)
    p_max = F * geometry.L / resist
    t_int, _ = integrate.quad(
        lambda phi: mu * math.sin(phi) / sin_a * b * R * R, geometry.phi1, geometry.phi2, **opts
    )
    return QuadratureShoe(p_max * t_int, p_max, p_max * m_n, p_max * m_f, False)
