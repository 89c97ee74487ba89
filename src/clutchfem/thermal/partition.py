"""Share of the friction heat that enters the part: Blok's equal mean patch temperatures,
with the patch stationary on the shoe and moving on the drum (:func:`heat_partition`).

Each side's mean patch temperature per unit patch flux is a thermal resistance [K m^2/W]:

* shoe: R_s, the part's own FE response (given by the caller: the flux-weighted mean
  temperature rise of the loaded nodes at t_ref per mean patch flux) or, without it, a
  half-space under a stationary uniform flux, R_s = 2 sqrt(t/pi) / e_s, e = sqrt(k rho c);
* drum: a drum point passes under n patches per revolution, each for the dwell time
  t_c = L / v; period P = 2 pi R_d / (n v), duty phi = t_c / P = n L / (2 pi R_d).
  One-dimensional conduction normal to the drum surface into a wall of thickness w, outer
  face adiabatic (ASSUMED), heated by the pulse train:

      R_d = phi S_w(t_ref) + F,
      S_w(t)  = slab step response (Carslaw & Jaeger 3.8, :func:`wall_step_response`),
      F       = (1/phi) sum_k 2 sin^2(k pi phi)/(k pi)^2 Re Z(k w0),   w0 = 2 pi / P,
      Z(w)    = coth(m w)/(k m), m = sqrt(i w / kappa)  (surface impedance of the wall),

  F the steady-periodic flash temperature averaged over the dwell.  With fewer than
  ``PERIODIC_PASSES`` passes by t_ref, R_d is instead the exact superposition of every
  pass with S_w, averaged over the patch (:func:`drum_patch_response`).

Equal temperatures gamma q R_s = (1 - gamma) q R_d give the part's share

    gamma = R_d / (R_s + R_d).

Peclet number of the drum surface: Pe = v a / (2 kappa_d), a = L / 2.  The limits (Charron
for Pe -> 0 and Pe -> infinity) and the derivation: ``docs/durability_theory.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.special import erfc

from ..core import ParameterError
from .params import DrumThermal, ThermalMaterial, finite_positive

__all__ = ["PERIODIC_PASSES", "HeatPartition", "drum_patch_response", "heat_partition", "wall_step_response"]

#: Passes of a drum point under the patches by t_ref above which the drum flash is taken in
#: its steady-periodic form (Fourier series); below, every pass is superposed (Duhamel).
PERIODIC_PASSES = 1000


def _ierfc(x):
    return np.exp(-x * x) / math.sqrt(math.pi) - x * erfc(x)


#: the argument from which ierfc(x) is exactly 0.0 in double precision (exp(-x^2) and
#: erfc(x) both underflow to zero from x = 27.3): image terms beyond it add nothing
_IERFC_ZERO = 27.5


def wall_step_response(t, conductivity: float, density: float, specific_heat: float,
                       wall_thickness: float):
    """Surface temperature rise [K per W/m^2] of a wall of thickness w heated on one face by
    a unit flux switched on at t = 0, other face adiabatic (Carslaw & Jaeger 3.8).  Image
    series for Fo = kappa t / w^2 < 1, Fourier series above (both converge in a few terms).
    ``wall_thickness = inf``: half-space, 2 sqrt(t / pi) / e.  0 for t <= 0."""
    t = np.asarray(t, dtype=float)
    k = conductivity
    kappa = k / (density * specific_heat)
    out = np.zeros_like(t)
    pos = t > 0
    if not np.isfinite(wall_thickness):
        out[pos] = 2.0 * np.sqrt(kappa * t[pos]) / (k * math.sqrt(math.pi))
        return out
    w = wall_thickness
    Fo = kappa * np.where(pos, t, 0.0) / (w * w)
    small = pos & (Fo < 1.0)
    if small.any():
        r = np.sqrt(kappa * t[small])
        s = np.full_like(r, 1.0 / math.sqrt(math.pi))
        x1 = w / r
        for n in range(1, 8):  # only the images whose term is not exactly 0.0 (the sum is the same)
            live = n * x1 < _IERFC_ZERO
            if not live.any():
                break
            s[live] += 2.0 * _ierfc(n * x1[live])
        out[small] = 2.0 * r / k * s
    big = pos & (Fo >= 1.0)
    if big.any():
        F = Fo[big]
        s = F + 1.0 / 3.0
        for n in range(1, 6):
            s -= 2.0 / (math.pi ** 2 * n * n) * np.exp(-(n * math.pi) ** 2 * F)
        out[big] = w / k * s
    return out


def _wall_impedance_real(omega, conductivity, density, specific_heat, wall_thickness):
    """Re Z(omega) [K m^2 / W]: steady-periodic surface temperature per unit harmonic flux,
    Z = coth(m w) / (k m), m = sqrt(i omega / kappa)."""
    kappa = conductivity / (density * specific_heat)
    m = np.sqrt(1j * np.asarray(omega, dtype=float) / kappa)
    if np.isfinite(wall_thickness):
        e = np.exp(-2.0 * m * wall_thickness)
        coth = (1.0 + e) / (1.0 - e)
    else:
        coth = 1.0
    return np.real(coth / (conductivity * m))


def drum_patch_response(drum: DrumThermal, *, slip_speed_m_s: float, patch_length_m: float,
                        drum_radius_m: float, n_patches: int, t_ref_s: float,
                        method: Literal["auto", "periodic", "passes"] = "auto") -> dict:
    """Mean temperature rise of the drum under a patch at t_ref per unit patch flux
    [K m^2/W] (module docstring): ``{'track': phi S_w(t), 'flash': F, 'total', 'method',
    'duty', 'dwell_s', 'period_s', 'passes'}``.  ``method`` 'auto' takes the steady-periodic
    form when more than PERIODIC_PASSES passes happened by t_ref, else the pass-by-pass
    superposition; the other two force one (tests compare them)."""
    v, L, R, t = slip_speed_m_s, patch_length_m, drum_radius_m, t_ref_s
    n = int(n_patches)
    props = (drum.conductivity, drum.density, drum.specific_heat, drum.wall_thickness)
    phi = min(n * L / (2.0 * math.pi * R), 1.0)
    tc = L / v
    P = tc / phi
    passes = t / P
    S_t = float(wall_step_response(t, *props))
    if method == "auto":
        method = "periodic" if passes > PERIODIC_PASSES else "passes"
    if phi >= 1.0:  # the patches cover the whole track: continuous heating
        return {"track": S_t, "flash": 0.0, "total": S_t, "method": "continuous", "duty": 1.0,
                "dwell_s": tc, "period_s": P, "passes": passes}
    if method == "periodic":
        w0 = 2.0 * math.pi / P
        K = 200000
        k = np.arange(1, K + 1, dtype=float)
        terms = 2.0 * np.sin(k * math.pi * phi) ** 2 / (k * math.pi) ** 2 * \
            _wall_impedance_real(k * w0, *props)
        e = drum.effusivity
        tail = (1.0 / (math.pi ** 2 * e * math.sqrt(2.0 * w0))) * (2.0 / 3.0) * K ** -1.5
        flash = float((terms.sum() + tail) / phi)
        total = phi * S_t + flash
    elif method == "passes":
        # average over the patch of the exact superposition of every pass (s = L u^2 removes the
        # sqrt(s) behaviour at the leading edge; midpoint rule in u)
        nu = 4000
        u = (np.arange(nu) + 0.5) / nu
        s = L * u * u
        wq = 2.0 * u / nu
        since = np.minimum(s / v, t)  # time under the current patch
        T = wall_step_response(since, *props)
        J = int(math.ceil(t / P)) + 1
        for j in range(1, J + 1):
            entry = t - s / v - j * P
            exit_ = entry + tc
            live = exit_ > 0
            if not live.any():
                break
            T[live] += (wall_step_response(t - np.maximum(entry[live], 0.0), *props)
                        - wall_step_response(t - exit_[live], *props))
        total = float(np.sum(wq * T))
        flash = total - phi * S_t
    else:
        raise ParameterError("method", method, "one of 'auto', 'periodic', 'passes'")
    return {"track": phi * S_t, "flash": flash, "total": total, "method": method, "duty": phi,
            "dwell_s": tc, "period_s": P, "passes": passes}


@dataclass(frozen=True)
class HeatPartition:
    """Share of the friction heat that enters the part (see module docstring)."""

    fraction_part: float
    peclet: float
    slip_speed_m_s: float
    patch_length_m: float
    duty: float
    dwell_time_s: float
    pass_period_s: float
    t_ref_s: float
    r_shoe_K_m2_W: float
    r_drum_track_K_m2_W: float
    r_drum_flash_K_m2_W: float
    drum_method: str
    shoe_side: str

    @property
    def fraction_drum(self) -> float:
        return 1.0 - self.fraction_part

    def to_json(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__} | {"fraction_drum": self.fraction_drum}


def heat_partition(part: ThermalMaterial, drum: DrumThermal, *, slip_speed_m_s: float,
                   patch_length_m: float, drum_radius_m: float, n_patches: int, t_ref_s: float,
                   shoe_response_K_m2_W: float | None = None,
                   drum_method: Literal["auto", "periodic", "passes"] = "auto") -> HeatPartition:
    """gamma = R_d / (R_s + R_d): Blok's equal mean patch temperatures, stationary patch on
    the shoe, moving patch on the drum (module docstring).  ``shoe_response_K_m2_W``: the
    shoe's mean patch temperature rise per unit patch flux at t_ref (from the FE model);
    None: a half-space, 2 sqrt(t_ref/pi)/e_s.  ``n_patches``: shoes of the whole clutch."""
    v = finite_positive("slip_speed_m_s", slip_speed_m_s, "a sliding speed > 0 m/s")
    L = finite_positive("patch_length_m", patch_length_m, "a contact patch length > 0 m")
    R = finite_positive("drum_radius_m", drum_radius_m, "a drum radius > 0 m")
    t = finite_positive("t_ref_s", t_ref_s, "a reference time > 0 s")
    if isinstance(n_patches, bool) or int(n_patches) != n_patches or int(n_patches) < 1:
        raise ParameterError("n_patches", n_patches, "an integer number of contact patches >= 1")
    if int(n_patches) * L > 2.0 * math.pi * R * (1.0 + 1e-6):
        raise ParameterError("patch_length_m", L, f"n_patches x patch length <= the drum circumference "
                                                   f"{2 * math.pi * R:.6g} m")
    if shoe_response_K_m2_W is None:
        Rs = 2.0 * math.sqrt(t / math.pi) / part.effusivity
        side = "semi_infinite"
    else:
        Rs = finite_positive("shoe_response_K_m2_W", shoe_response_K_m2_W,
                              "a shoe temperature rise per unit flux > 0 K m^2/W")
        side = "fe"
    d = drum_patch_response(drum, slip_speed_m_s=v, patch_length_m=L, drum_radius_m=R,
                            n_patches=int(n_patches), t_ref_s=t, method=drum_method)
    gamma = d["total"] / (Rs + d["total"])
    pe = v * (0.5 * L) / (2.0 * drum.diffusivity)
    return HeatPartition(fraction_part=float(gamma), peclet=float(pe), slip_speed_m_s=v, patch_length_m=L,
                         duty=float(d["duty"]), dwell_time_s=float(d["dwell_s"]),
                         pass_period_s=float(d["period_s"]), t_ref_s=t, r_shoe_K_m2_W=float(Rs),
                         r_drum_track_K_m2_W=float(d["track"]), r_drum_flash_K_m2_W=float(d["flash"]),
                         drum_method=str(d["method"]), shoe_side=side)
