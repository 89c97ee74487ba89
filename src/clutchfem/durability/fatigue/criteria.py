"""Fatigue criteria: the Marin-corrected endurance limit, the Haigh diagram (equivalent fully
reversed amplitude), the Basquin S-N curve and its inverse, and the closed-form load factor
of one cycle type.

Fatigue strength (Marin, Shigley eqs. 6-8, 6-18 to 6-28; values in :mod:`.strength`)
--------------------------------------------------------------------------------------
S_e = k_a k_b k_c k_d k_e k_f S_e',  S_e' = 0.5 S_ut (700 MPa for S_ut > 1400 MPa);
k_a = a S_ut^b (surface, S_ut in MPa), k_d from the temperature (Shigley eq. 6-27,
21-538 C; 1 at room temperature), k_e = 1 - 0.08 z_a (8 % standard deviation of S_e,
Shigley eq. 6-29), k_b, k_c, k_f given.

Haigh diagram
-------------
Equivalent fully reversed amplitude s_ar (the amplitude at zero mean with the same life):

    Goodman (default):  s_ar = s_a / (1 - s_m / S_ut)
    Gerber:             s_ar = s_a / (1 - (s_m / S_ut)^2)
    s_m <= 0:           s_ar = s_a;         s_m >= S_ut: s_ar = infinity.

Goodman is the default for hardened spring steel cut to shape: Gerber runs through the
middle of ductile-steel test data and is unconservative for high-strength, notch- and
mean-stress-sensitive steels, and the cut edge carries tensile residual stress (recast
layer); the FKM guideline's mean-stress sensitivity for R_m = 1450 MPa (M = 0.35e-3 R_m -
0.1 = 0.41) is even steeper than the Goodman line here (S_e / S_ut ~ 0.1-0.25), so
Goodman is not conservative by a wide margin either.

S-N curve (Basquin)
-------------------
S(N) = f S_ut (N / 1e3)^b between 1e3 cycles and the knee N_e (S(N_e) = S_e, so
b = log10(S_e / (f S_ut)) / log10(N_e / 1e3)); below 1e3 cycles S(N) = S_ut N^(log10 f / 3)
(eq. 6-17).  Above the knee: 'elementary' (default, Shigley): amplitudes below S_e do no
damage (infinite life); 'haibach' (FKM guideline, conservative for many cycles):
N = N_e (S_e / s_ar)^(2k - 1), k = -1/b.
"""

from __future__ import annotations

import math
from statistics import NormalDist

import numpy as np

from ...core import ParameterError
from .strength import SURFACE_TABLE, FatigueParams

__all__ = ["allowed_amplitude", "cycles_to_failure", "endurance_limit", "haigh_safety_factor", "marin_factors",
           "reversed_equivalent", "single_cycle_factor"]


def _kd(T_C: float) -> float:
    """Shigley eq. 6-27 (T in F, 70-1000 F); 1 below 70 F (21 C)."""
    TF = max(T_C * 9.0 / 5.0 + 32.0, 70.0)
    return (0.975 + 0.432e-3 * TF - 0.115e-5 * TF ** 2 + 0.104e-8 * TF ** 3 - 0.595e-12 * TF ** 4)


def marin_factors(p: FatigueParams) -> dict[str, float]:
    """k_a ... k_f of :class:`FatigueParams` (module docstring)."""
    if p.surface_factor > 0:
        ka = p.surface_factor
    else:
        a, b = SURFACE_TABLE[p.edge_finish]
        ka = min(a * (p.ultimate_strength / 1e6) ** b, 1.0)
    z = NormalDist().inv_cdf(p.reliability)
    return {"k_a": float(ka), "k_b": p.size_factor, "k_c": p.load_factor, "k_d": float(_kd(p.temperature)),
            "k_e": float(1.0 - 0.08 * z), "k_f": p.misc_factor}


def endurance_limit(p: FatigueParams) -> tuple[float, dict[str, float]]:
    """(S_e [Pa], Marin factors): S_e = prod(k) min(endurance_ratio S_ut, endurance_cap)."""
    k = marin_factors(p)
    se_prime = min(p.endurance_ratio * p.ultimate_strength, p.endurance_cap)
    return float(se_prime * np.prod(list(k.values()))), k | {"S_e_prime_Pa": float(se_prime)}


def reversed_equivalent(s_a, s_m, ultimate_strength: float, rule: str = "goodman") -> np.ndarray:
    """Equivalent fully reversed amplitude s_ar [Pa] (module docstring)."""
    s_a = np.asarray(s_a, dtype=float)
    s_m = np.asarray(s_m, dtype=float)
    r = np.maximum(s_m, 0.0) / ultimate_strength
    if rule == "goodman":
        den = 1.0 - r
    elif rule == "gerber":
        den = 1.0 - r * r
    else:
        raise ParameterError("mean_stress_rule", rule, "one of 'goodman', 'gerber'")
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(den > 0, s_a / np.where(den > 0, den, 1.0), np.inf)
    return np.where((s_a == 0) & (r < 1), 0.0, out)


def _sn_constants(p: FatigueParams, Se: float) -> tuple[float, float, float]:
    S3 = p.fatigue_fraction * p.ultimate_strength
    if Se >= S3:
        raise ParameterError("fatigue_fraction", p.fatigue_fraction,
                             f"f S_ut above the endurance limit S_e = {Se:.4g} Pa")
    b = math.log10(Se / S3) / math.log10(p.knee_cycles / 1e3)
    return S3, b, -1.0 / b


def cycles_to_failure(s_ar, p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Allowed cycles N at equivalent reversed amplitude s_ar [Pa] (module docstring)."""
    if Se is None:
        Se = endurance_limit(p)[0]
    s = np.asarray(s_ar, dtype=float)
    S3, b, k = _sn_constants(p, Se)
    Su = p.ultimate_strength
    N = np.full(s.shape, np.inf)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        hcf = (s > Se) & (s <= S3)
        N[hcf] = 1e3 * (s[hcf] / S3) ** (1.0 / b)
        lcf = (s > S3) & (s < Su)
        N[lcf] = (s[lcf] / Su) ** (3.0 / math.log10(p.fatigue_fraction))
        N[s >= Su] = 0.0
        if p.miner == "haibach":
            low = (s > 0) & (s <= Se)
            N[low] = p.knee_cycles * (Se / s[low]) ** (2.0 * k - 1.0)
    return N


def allowed_amplitude(count, p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Fully reversed amplitude S(n) [Pa] that ``count`` cycles may have (the inverse of
    :func:`cycles_to_failure`): S_ut n^(log10 f / 3) below 1e3 cycles, f S_ut (n / 1e3)^b up to
    the knee, S_e above it ('elementary'; 'haibach': S_e (N_e / n)^(1 / (2k - 1)))."""
    if Se is None:
        Se = endurance_limit(p)[0]
    n = np.asarray(count, dtype=float)
    S3, b, k = _sn_constants(p, Se)
    with np.errstate(divide="ignore", over="ignore"):
        S = np.where(n <= 1e3, p.ultimate_strength * np.maximum(n, 1.0) ** (math.log10(p.fatigue_fraction) / 3.0),
                     S3 * (n / 1e3) ** b)
        above = n >= p.knee_cycles
        if p.miner == "haibach":
            S = np.where(above, Se * (p.knee_cycles / n) ** (1.0 / (2.0 * k - 1.0)), S)
        else:
            S = np.where(above, Se, S)
    return S


def single_cycle_factor(s_a, s_m, count, p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Closed-form load multiplier X at which ``count`` cycles of one type alone reach
    Miner's sum 1: s_ar(X s_a, X s_m) = S(count), i.e. Goodman X = S / (s_a + S s_m / S_ut),
    Gerber the positive root of S (s_m/S_ut)^2 X^2 + s_a X - S = 0, and X = S / s_a for
    s_m <= 0 (inf without stress).  Equals the bisection of :func:`fatigue_check` for one
    cycle type (tested)."""
    s_a = np.asarray(s_a, dtype=float)
    s_m = np.maximum(np.asarray(s_m, dtype=float), 0.0)
    S = allowed_amplitude(count, p, Se)
    r = s_m / p.ultimate_strength
    with np.errstate(divide="ignore", invalid="ignore"):
        if p.mean_stress_rule == "goodman":
            X = S / (s_a + S * r)
        else:
            a = S * r * r
            X = np.where(a > 0, (-s_a + np.sqrt(s_a * s_a + 4.0 * a * S)) / (2.0 * np.where(a > 0, a, 1.0)),
                         S / s_a)
    return np.where((s_a <= 0) & (s_m <= 0), np.inf, X)


def haigh_safety_factor(s_a, s_m, Se: float, Sut: float, rule: str = "goodman") -> np.ndarray:
    """Shigley's infinite-life safety factor on a load line through the origin:
    Goodman 1 / (s_a/S_e + s_m/S_ut); Gerber (1/2)(S_ut/s_m)^2 (s_a/S_e)
    (-1 + sqrt(1 + (2 s_m S_e / (S_ut s_a))^2)); s_m <= 0: S_e / s_a."""
    s_a = np.asarray(s_a, dtype=float)
    s_m = np.asarray(s_m, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        if rule == "goodman":
            n = 1.0 / (s_a / Se + np.maximum(s_m, 0.0) / Sut)
        elif rule == "gerber":
            sm = np.maximum(s_m, 0.0)
            ger = 0.5 * (Sut / sm) ** 2 * (s_a / Se) * (-1.0 + np.sqrt(1.0 + (2.0 * sm * Se / (Sut * s_a)) ** 2))
            n = np.where(sm > 0, np.where(s_a > 0, ger, Sut / np.where(sm > 0, sm, 1.0)), Se / s_a)
        else:
            raise ParameterError("mean_stress_rule", rule, "one of 'goodman', 'gerber'")
    return n
