"""The shoe-face temperature rise of one start (:func:`start_heating`), through the slip-heat
model's heat partition and step response (:mod:`clutchfem.thermal`).

The friction power of the start P(t) = M_c (w_e - w_d) (:func:`~.engagement.engagement_transient`)
is split between shoe and drum by Blok's equal patch temperatures
(:func:`~clutchfem.thermal.heat_partition`: the part's share gamma, at the start's
mean sliding speed and its slip duration as the reference time, the shoe a half-space); the
shoe's share enters the n contact patches of length L (the FE contact arc per shoe) over
the axial thickness h as the mean patch flux

    q(t) = gamma P(t) / (n L h),

and the mean patch temperature of the shoe face follows by Duhamel's superposition of the
half-space's step response S(t) = 2 sqrt(t / pi) / e (e = sqrt(k rho c),
:func:`~clutchfem.thermal.wall_step_response`):

    dT(t) = sum_j (q_j - q_{j-1}) S(t - t_j)      (q piecewise constant on a uniform grid).

Why a half-space: a start lasts a fraction of a second, and the heat penetrates
sqrt(kappa t) ~ 2 mm in 0.3 s, less than the shoe's radial thickness; the answer states the
penetration depth so that a long slip (where the FE heat model of ``clutchfem slip-heat``
is the right tool) shows itself.  It is the *mean* patch temperature of a start beginning
at the part's temperature: the flash temperature of the asperities comes on top.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import ParameterError, clean
from ..thermal import DrumThermal, ThermalMaterial, heat_partition, wall_step_response
from .engagement import Engagement

__all__ = ["StartHeating", "start_heating"]

#: points of the uniform time grid of the superposition
GRID = 400


@dataclass(frozen=True)
class StartHeating:
    """The shoe face during one start (:func:`start_heating`): its peak mean patch
    temperature rise [K] and when, the part's share of the friction heat, the heat into the
    part [J], the mean sliding speed [m/s] and the heat's penetration depth [m].

    Examples
    --------
    >>> import clutchfem as cf
    >>> s = cf.engagement_transient([0, 20000], [5.0, 5.0], held_engine_rpm=8000, drum_radius=0.0344)
    >>> h = cf.start_heating(s, patch_length_m=0.01, n_patches=3, thickness_m=0.011, drum_radius_m=0.0344)
    >>> sorted(h.to_json())[:2]
    ['fraction_part', 'heat_into_part_J']
    """

    peak_rise_K: float
    peak_time_s: float
    fraction_part: float
    heat_into_part_J: float
    mean_sliding_speed_m_s: float
    penetration_depth_m: float
    patch_length_m: float

    def to_json(self) -> dict:
        return clean(dict(self.__dict__))


def start_heating(start: Engagement, *, patch_length_m: float, n_patches: int, thickness_m: float,
                  drum_radius_m: float, material: ThermalMaterial | None = None,
                  drum: DrumThermal | None = None, fraction_part: float | None = None) -> StartHeating:
    """The mean patch temperature rise of the shoe face during the start ``start`` (module
    docstring).

    Parameters
    ----------
    start : Engagement
        The start (its slip power against time and its sliding distance).
    patch_length_m : float
        Contact length per shoe along the drum [m].
    n_patches : int
        Shoes of the whole clutch.
    thickness_m : float
        Axial thickness of the shoe face [m].
    drum_radius_m : float
        Drum radius [m].
    material, drum : optional
        The part's and the drum's thermal properties (ASSUMED defaults of the slip-heat model).
    fraction_part : float, optional
        The part's share of the heat, if known (else from the heat partition).

    Returns
    -------
    StartHeating

    Examples
    --------
    >>> import clutchfem as cf
    >>> s = cf.engagement_transient([0, 20000], [5.0, 5.0], held_engine_rpm=8000, load_torque=0.0,
    ...                             drum_radius=0.0344)
    >>> h = cf.start_heating(s, patch_length_m=0.01, n_patches=3, thickness_m=0.011, drum_radius_m=0.0344)
    >>> 0 < h.fraction_part < 1, h.peak_rise_K > 0
    (True, True)
    """
    if not isinstance(start, Engagement):
        raise ParameterError("start", type(start).__name__, "an Engagement (engagement_transient)", "start heating")
    for name, v in (("patch_length_m", patch_length_m), ("thickness_m", thickness_m),
                    ("drum_radius_m", drum_radius_m)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
            raise ParameterError(name, v, "a length > 0 m", "start heating")
    if start.sliding_distance_m is None:
        raise ParameterError("start", "no sliding distance", "a start computed with drum_radius", "start heating")
    material = material or ThermalMaterial()
    drum = drum or DrumThermal()
    t, P = start.times_s, start.slip_power_W
    sliding = P > 0
    if not sliding.any() or start.slip_energy_J <= 0:
        return StartHeating(0.0, 0.0, math.nan, 0.0, 0.0, 0.0, float(patch_length_m))
    t_slip = float(t[sliding][-1] - t[sliding][0]) or float(t[-1])
    v = start.sliding_distance_m / t_slip
    L = min(float(patch_length_m), 2 * math.pi * drum_radius_m / n_patches)
    if fraction_part is None:
        fraction_part = heat_partition(material, drum, slip_speed_m_s=v, patch_length_m=L, drum_radius_m=drum_radius_m,
                                       n_patches=n_patches, t_ref_s=t_slip).fraction_part
    elif not 0.0 <= fraction_part <= 1.0:
        raise ParameterError("fraction_part", fraction_part, "a share of the heat in [0, 1]", "start heating")
    g = float(fraction_part)
    tg = np.linspace(t[0], t[-1], GRID + 1)
    # the mean power over each grid step (energy-exact: cumulative trapezoid of the samples)
    E = np.concatenate([[0.0], np.cumsum(0.5 * (P[1:] + P[:-1]) * np.diff(t))])
    Pm = np.diff(np.interp(tg, t, E)) / np.diff(tg)
    q = g * Pm / (n_patches * L * thickness_m)
    dq = np.diff(np.concatenate([[0.0], q]))
    rise = np.zeros(GRID + 1)
    for j in range(GRID):
        rise[j + 1:] += dq[j] * wall_step_response(tg[j + 1:] - tg[j], material.conductivity, material.density,
                                                   material.specific_heat, math.inf)
    k = int(np.argmax(rise))
    return StartHeating(peak_rise_K=float(rise[k]), peak_time_s=float(tg[k]), fraction_part=float(g),
                        heat_into_part_J=float(g * start.slip_energy_J), mean_sliding_speed_m_s=float(v),
                        penetration_depth_m=float(math.sqrt(material.diffusivity * t_slip)),
                        patch_length_m=float(L))
