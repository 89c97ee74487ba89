"""Crank-speed ripple of a one-cylinder two-stroke engine and its effect on engagement.

Seed ``000`` eqs 6-9 and 14 (SI units, rad/s, s):

* ``w(t) = w_sr (1 + delta sin(w_sr t))``                       (6)
* ``eps(t) = dw/dt = delta w_sr^2 cos(w_sr t)``                  (7)
* ``delta = (w_max - w_sr) / w_sr``, ``w_sr = (w_min + w_max)/2`` (8, 9)
* cycle time ``t_c = 2 pi / w_sr``                                (14)

Measured ripple (Gendek, quoted in seed 000, fig. 3): at 8000 rpm the mean of ``delta`` is
0.032 with standard deviation 0.013, "both growing with the engine speed".  The paper gives
no law for the growth.  **ASSUMPTION** (:class:`RippleModel`): mean and standard deviation
scale as ``(rpm / 8000)^exponent`` with ``exponent = 1`` (proportional) by default; the
cycle-to-cycle scatter of ``delta`` is Normal.  Change ``exponent`` (0 = constant) to test
the sensitivity.

Effective engagement: the shoes follow the instantaneous speed, so a clutch whose static
(steady-speed) engagement is ``w_eng`` first touches the drum in a cycle whose *peak* speed
``w_sr (1 + delta)`` reaches ``w_eng`` (thesis 2.3: the real engagement rpm is lower than
computed).  :func:`effective_engagement_rpm` solves ``rpm_eff (1 + delta(rpm_eff)) =
rpm_eng`` with ``delta = mean + k_sigma std`` evaluated at the mean speed ``rpm_eff``:
``k_sigma = 0`` is a typical cycle, ``k_sigma = 3`` the 3-sigma cycle (the lowest speed at
which the chain can be expected to twitch: use it for the "no chain motion at idle" check).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import ParameterError, rad_s_to_rpm, rpm_to_rad_s

__all__ = [
    "RippleModel",
    "speed",
    "acceleration",
    "delta_from_extremes",
    "cycle_time",
    "effective_engagement_rpm",
    "effective_engagement_rpms",
    "effective_engagement_speed",
]


@dataclass(frozen=True)
class RippleModel:
    """Cyclic speed-irregularity coefficient ``delta`` vs mean crank speed.

    delta_mean(rpm) = delta_ref (rpm/rpm_ref)^exponent and likewise std(rpm).
    Defaults: delta_ref = 0.032, std_ref = 0.013 at rpm_ref = 8000 (seed 000, measured);
    exponent = 1.0 is an ASSUMPTION (see module docstring).
    """

    delta_ref: float = 0.032
    std_ref: float = 0.013
    rpm_ref: float = 8000.0
    exponent: float = 1.0
    assumed: tuple[str, ...] = (
        "delta mean and std scale as (rpm/8000)^exponent, exponent = 1 (proportional)",
        "cycle-to-cycle delta is Normal(mean, std)",
    )

    def __post_init__(self) -> None:
        if not (0.0 <= self.delta_ref < 1.0):
            raise ParameterError("delta_ref", self.delta_ref, "0 <= delta_ref < 1")
        if not (0.0 <= self.std_ref < 1.0):
            raise ParameterError("std_ref", self.std_ref, "0 <= std_ref < 1")
        if not (self.rpm_ref > 0.0):
            raise ParameterError("rpm_ref", self.rpm_ref, "> 0 rpm")
        if not (math.isfinite(self.exponent) and 0.0 <= self.exponent <= 4.0):
            raise ParameterError("exponent", self.exponent, "0 <= exponent <= 4")

    def _scale(self, rpm):
        r = np.asarray(rpm, dtype=float)
        if np.any(~np.isfinite(r)) or np.any(r < 0.0):
            raise ParameterError("rpm", rpm, "finite and >= 0 rpm")
        return (r / self.rpm_ref) ** self.exponent

    def delta_mean(self, rpm):
        """Mean delta at mean crank speed(s) ``rpm``."""
        return self.delta_ref * self._scale(rpm)

    def delta_std(self, rpm):
        """Standard deviation of delta at ``rpm``."""
        return self.std_ref * self._scale(rpm)

    def delta(self, rpm, k_sigma: float = 0.0):
        """``mean + k_sigma * std`` of delta at ``rpm`` (clipped at 0)."""
        return np.maximum(self.delta_mean(rpm) + k_sigma * self.delta_std(rpm), 0.0)


def _check_delta(delta):
    d = np.asarray(delta, dtype=float)
    if np.any(~np.isfinite(d)) or np.any(d < 0.0) or np.any(d >= 1.0):
        raise ParameterError("delta", delta, "speed-irregularity coefficient 0 <= delta < 1")
    return d


def _check_omega(omega, name: str = "omega_sr"):
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w <= 0.0):
        raise ParameterError(name, omega, "mean angular speed > 0 rad/s")
    return w


def speed(t, omega_sr, delta):
    """Instantaneous crank speed [rad/s], eq 6 (t [s], omega_sr [rad/s])."""
    w = _check_omega(omega_sr)
    return w * (1.0 + _check_delta(delta) * np.sin(w * np.asarray(t, dtype=float)))


def acceleration(t, omega_sr, delta):
    """Crank angular acceleration [rad/s^2], eq 7 (the time derivative of eq 6)."""
    w = _check_omega(omega_sr)
    return _check_delta(delta) * w**2 * np.cos(w * np.asarray(t, dtype=float))


def delta_from_extremes(omega_min: float, omega_max: float) -> tuple[float, float]:
    """(w_sr [rad/s], delta) from the cycle's min and max speed, eqs 8-9."""
    if not (0.0 < omega_min <= omega_max):
        raise ParameterError("omega_min, omega_max", (omega_min, omega_max), "0 < omega_min <= omega_max rad/s")
    w_sr = 0.5 * (omega_min + omega_max)
    return w_sr, (omega_max - w_sr) / w_sr


def cycle_time(omega_sr):
    """Duration of one engine cycle (one crank revolution, 2-stroke) [s], eq 14."""
    return 2.0 * np.pi / _check_omega(omega_sr)


def effective_engagement_rpm(
    static_rpm: float, model: RippleModel | None = None, k_sigma: float = 0.0
) -> float:
    """Mean crank speed [rpm] at which a cycle's peak speed reaches ``static_rpm``.

    Solves ``x (1 + delta(x)) = static_rpm`` with ``delta(x) = mean + k_sigma std`` of
    ``model`` at the mean speed x (monotone in x, so the root is unique).
    """
    model = RippleModel() if model is None else model
    s = float(static_rpm)
    if not (math.isfinite(s) and s > 0.0):
        raise ParameterError("static_rpm", static_rpm, "static engagement speed > 0 rpm")
    if not (math.isfinite(k_sigma) and k_sigma >= 0.0):
        raise ParameterError("k_sigma", k_sigma, "number of standard deviations >= 0")

    return float(effective_engagement_rpms(np.array([s]), model, k_sigma)[0])


def effective_engagement_rpms(static_rpm, model: RippleModel | None = None, k_sigma: float = 0.0) -> np.ndarray:
    """:func:`effective_engagement_rpm` of an array of static speeds [rpm] at once (a reduced
    model's thousands of designs): the root by Newton's method from the static speed, to the
    last bit (``x (1 + delta(x))`` rises with x and is convex: the iterates fall onto it; the
    static speed itself where delta is 0); NaN where the static speed is NaN or not > 0.

    Examples
    --------
    >>> import numpy as np
    >>> from clutchfem.clutch.ripple import RippleModel, effective_engagement_rpm, effective_engagement_rpms
    >>> w = effective_engagement_rpms(np.array([3000.0, 4200.0, np.nan]), k_sigma=3.0)
    >>> bool(w[0] == effective_engagement_rpm(3000.0, k_sigma=3.0)), bool(np.isnan(w[2]))
    (True, True)
    >>> x = w[1]                                   # the 3-sigma cycle's peak reaches the static speed
    >>> bool(abs(x * (1 + RippleModel().delta(x, 3.0)) / 4200.0 - 1) < 1e-15)
    True
    """
    model = RippleModel() if model is None else model
    if not (math.isfinite(k_sigma) and k_sigma >= 0.0):
        raise ParameterError("k_sigma", k_sigma, "number of standard deviations >= 0")
    s = np.asarray(static_rpm, dtype=float)
    good = np.isfinite(s) & (s > 0.0)
    s1 = np.where(good, s, 1.0)
    # Newton from x = s: g(x) = x (1 + delta(x)) - s is increasing and convex for x > 0 (delta ~ x^p,
    # p >= 0), so the iterates fall monotonically onto the root; g' = 1 + (1 + p) delta(x)
    x = s1.copy()
    for _ in range(60):
        d = model.delta(x, k_sigma)
        step = (x * (1.0 + d) - s1) / (1.0 + (1.0 + model.exponent) * d)
        x = x - step
        if np.all(np.abs(step) <= 4e-16 * x):
            break
    return np.where(good, x, np.nan)


def effective_engagement_speed(
    static_omega: float, model: RippleModel | None = None, k_sigma: float = 0.0
) -> float:
    """Same as :func:`effective_engagement_rpm` in rad/s."""
    return rpm_to_rad_s(effective_engagement_rpm(rad_s_to_rpm(static_omega), model, k_sigma))
