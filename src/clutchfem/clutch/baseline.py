"""Today's spring-and-shoe centrifugal clutch (seed ``000`` eqs 1-5), the reference design.

Each of ``k`` sliding shoes (mass ``m_s``, centre of mass at ``r_s``) is held by garter-spring
segments that leave the shoe at angle ``gamma`` on both sides.  Forces on a shoe in contact
with the drum (radius ``r_b``), SI units:

* clutch torque          ``M_s = T r_b k = N mu r_b k``                       (1)
* normal force           ``N = P_n - 2 P_p cos(gamma)``                       (2)
* centrifugal force      ``P_n = m_s r_s w^2``                                (3)
* spring tension         ``P_p = m_s r_s w_o^2 / (2 cos gamma) - q_spr r_spr^2 (w^2 - w_o^2)`` (4)
* characteristic         ``M_s = (m_s r_s + 2 q_spr r_spr^2 cos gamma) r_b k mu (w^2 - w_o^2)`` (5)

Eq 4 reconstructed from the physics: once the shoe touches the drum the spring no longer
stretches, its elastic tension is constant, and its own mass (``q_spr`` kg per m of
spring, wound at radius ``r_spr``) sheds the hoop tension of a rotating ring,
``q_spr v^2 = q_spr r_spr^2 w^2``.  Choosing the constant so that N = 0 at ``w = w_o`` gives
eq 4, and eqs 1-3 then give eq 5: the spring's own mass adds ``2 q_spr r_spr^2 cos gamma``
to the shoe's ``m_s r_s``.  Below ``w_o`` the shoes do not touch: M_s = 0 (never negative).

Paper data (Husqvarna, seed 000): see :meth:`BaselineClutch.new` / :meth:`BaselineClutch.worn`.
Known reproduction: M_s(950 rad/s) = 10.23 N m new, 8.61 N m worn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np

from ..core import ParameterError, rpm_to_rad_s

__all__ = ["BaselineClutch", "baseline_torque_at_rpm"]


@dataclass(frozen=True)
class BaselineClutch:
    """Parameters of the spring-and-shoe clutch (SI units).

    m_s [kg] shoe mass; r_s [m] radius of the shoe's centre of mass in contact; r_spr [m]
    radius of the spring coils; r_b [m] drum inner radius; q_spr [kg/m] spring mass per
    length; gamma [rad] angle at which the spring leaves the shoe; k number of shoes;
    mu friction coefficient; w_o [rad/s] engagement speed.
    """

    m_s: float = 0.04815
    r_s: float = 0.022
    r_spr: float = 0.028
    r_b: float = 0.0344
    q_spr: float = 0.0686
    gamma: float = math.pi / 6
    k: int = 2
    mu: float = 0.165
    w_o: float = 347.0
    label: str = "new"

    def __post_init__(self) -> None:
        for name, unit in (("m_s", "kg"), ("r_s", "m"), ("r_spr", "m"), ("r_b", "m"),
                           ("w_o", "rad/s")):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0.0):
                raise ParameterError(name, v, f"finite and > 0 {unit}")
        if not (math.isfinite(self.q_spr) and self.q_spr >= 0.0):
            raise ParameterError("q_spr", self.q_spr, "finite and >= 0 kg/m")
        if not (0.0 <= self.gamma < math.pi / 2):
            raise ParameterError("gamma", self.gamma, "0 <= gamma < pi/2 rad")
        if isinstance(self.k, bool) or int(self.k) != self.k or self.k < 1:
            raise ParameterError("k", self.k, "number of shoes, integer >= 1")
        if not (0.0 <= self.mu < 2.0):
            raise ParameterError("mu", self.mu, "friction coefficient in [0, 2)")
        if self.r_s >= self.r_b:
            raise ParameterError("r_s", self.r_s, f"< drum radius r_b = {self.r_b} m")

    # ---- paper designs --------------------------------------------------------------
    @classmethod
    def new(cls) -> "BaselineClutch":
        """New shoes (lining 3.5 mm): m_s = 0.04815 kg, w_o = 347 rad/s (seed 000)."""
        return cls()

    @classmethod
    def worn(cls) -> "BaselineClutch":
        """Shoes at the wear limit (lining 0.8-1.0 mm): m_s = 0.04107 kg, w_o = 376 rad/s."""
        return cls(m_s=0.04107, w_o=376.0, label="worn")

    def with_(self, **changes) -> "BaselineClutch":
        """Copy with some parameters changed (validated)."""
        return replace(self, **changes)

    # ---- model ------------------------------------------------------------------------
    @property
    def spring_mass_term(self) -> float:
        """``2 q_spr r_spr^2 cos(gamma)`` [kg m]: the spring's own-mass share of eq 5."""
        return 2.0 * self.q_spr * self.r_spr**2 * math.cos(self.gamma)

    @property
    def effective_first_moment(self) -> float:
        """``m_s r_s + 2 q_spr r_spr^2 cos(gamma)`` [kg m] (eq 5)."""
        return self.m_s * self.r_s + self.spring_mass_term

    @property
    def coefficient(self) -> float:
        """``M_s / (w^2 - w_o^2)`` [N m s^2] of eq 5."""
        return self.effective_first_moment * self.r_b * self.k * self.mu

    @property
    def engagement_rpm(self) -> float:
        return self.w_o * 60.0 / (2.0 * math.pi)

    @property
    def spring_tension_at_engagement(self) -> float:
        """P_p(w_o) = m_s r_s w_o^2 / (2 cos gamma) [N] (eq 4 at w = w_o)."""
        return self.m_s * self.r_s * self.w_o**2 / (2.0 * math.cos(self.gamma))

    @staticmethod
    def _omega(omega) -> np.ndarray:
        w = np.asarray(omega, dtype=float)
        if np.any(~np.isfinite(w)) or np.any(w < 0.0):
            raise ParameterError("omega", omega, "angular speed(s) finite and >= 0 rad/s")
        return w

    def centrifugal_force(self, omega):
        """P_n = m_s r_s w^2 [N] (eq 3)."""
        return self.m_s * self.r_s * self._omega(omega) ** 2

    def spring_tension(self, omega):
        """P_p(w) [N] (eq 4), valid in contact (w >= w_o)."""
        w = self._omega(omega)
        return self.spring_tension_at_engagement - self.q_spr * self.r_spr**2 * (w**2 - self.w_o**2)

    def normal_force(self, omega):
        """N(w) per shoe [N] (eq 2 with 3, 4), 0 below engagement."""
        w = self._omega(omega)
        n = self.centrifugal_force(w) - 2.0 * self.spring_tension(w) * math.cos(self.gamma)
        return np.where(w >= self.w_o, np.maximum(n, 0.0), 0.0)

    def torque(self, omega):
        """Clutch characteristic M_s(w) [N m] (eq 5), 0 below w_o; arrays ok."""
        w = self._omega(omega)
        return self.coefficient * np.maximum(w**2 - self.w_o**2, 0.0)

    def torque_from_forces(self, omega):
        """M_s via eqs 1-4 step by step (same value as eq 5; a consistency check)."""
        return self.normal_force(omega) * self.mu * self.r_b * self.k

    def torque_at_rpm(self, rpm):
        """M_s [N m] at crank speed(s) in rpm."""
        return self.torque(rpm_to_rad_s(rpm))


def baseline_torque_at_rpm(rpm, state: Literal["new", "worn"] = "new"):
    """Torque [N m] of the built-in baseline (today's clutch, seed 000) at rpm array(s).

    For comparing a compliant concept with today's clutch on one torque-vs-rpm chart.
    """
    if state == "new":
        clutch = BaselineClutch.new()
    elif state == "worn":
        clutch = BaselineClutch.worn()
    else:
        raise ParameterError("state", state, "'new' or 'worn'")
    return clutch.torque_at_rpm(rpm)
