"""Where a slip-heat answer leaves the range its model holds: tempering, phase change,
melting, and the clearance closed by thermal growth; the answer cut at the first limit past
which it means nothing.

The heat model (:mod:`.slip`) has constant room-temperature properties, a constant friction
coefficient and linear conduction; none of it holds far above the tempering temperature
(issue 24: ``slip-heat concept2 --cycles 3 --pause 20`` reported the shoe face at 1873 C,
above steel's melting point, without a word).  Levels, hottest node of the part
(``part_max_C``), first crossing in time (linear between steps):

* ``tempering`` at ``material.limit_temperature`` (default 400 C, ASSUMED, params.py): the
  steel softens for good; k, c, mu and the hot yield strength are extrapolated: the
  temperatures past it are an estimate and the damage at least that of reaching the limit
  (an upper bound on the life left). The answer stands, flagged.
* ``phase change`` at ``ThermalMaterial.phase_change_temperature``, default
  :data:`PHASE_CHANGE_C` = 727 C (the eutectoid A1 of carbon steels,
  ASSUMED for 51CrV4 whose Ac1 is ~740 C by EN 10089 data): the steel starts to turn
  austenitic, absorbs latent heat and is rehardened/softened on cooling; the model has no
  latent heat.  **The transient is stopped there**: every series, peak and event row is
  cut at the crossing and the answer says so.
* ``melting`` at ``ThermalMaterial.melting_temperature``, default :data:`MELTING_C` = 1420 C (solidus of low-alloy steels, ASSUMED; ~1450 C
  is often quoted for the liquidus): flagged, and the answer is cut as for a phase change
  (it is past it by then).
* ``clearance closed``: the part grows by ``alpha (T_mean - T_ambient) r`` at radius ``r``
  (free uniform thermal expansion, ``alpha`` = :data:`EXPANSION_PER_K` = 12e-6 /K, ASSUMED:
  carbon steel 20-300 C; the drum held at ambient, conservative); once that growth at the
  contact radius reaches the clearance at rest the shoes touch the drum standing still: the
  clutch drags at idle until it cools.  Flagged with its time (the answer stands: the slip
  test holds the drum anyway).

The integration itself runs to the end of the scenario (it is causal: the answer up to the
cut is the same as if it had stopped); the cut is in what is reported.
"""

from __future__ import annotations

import numpy as np

__all__ = ["EXPANSION_PER_K", "MELTING_C", "PHASE_CHANGE_C", "slip_heat_validity"]

#: A1 eutectoid temperature of carbon steels [C] (ASSUMED, module docstring)
PHASE_CHANGE_C = 727.0
#: solidus of low-alloy steels [C] (ASSUMED, module docstring)
MELTING_C = 1420.0
#: linear thermal expansion coefficient of the part [1/K] (ASSUMED, carbon steel 20-300 C)
EXPANSION_PER_K = 12e-6


def _crossing(t: np.ndarray, y: np.ndarray, level: float) -> tuple[int, float] | None:
    """(index of the first step at or above ``level``, the time of the crossing) or None."""
    above = np.nonzero(np.asarray(y) >= level)[0]
    if len(above) == 0:
        return None
    k = int(above[0])
    if k == 0:
        return 0, float(t[0])
    y0, y1 = float(y[k - 1]), float(y[k])
    return k, float(t[k - 1] + (level - y0) / (y1 - y0) * (t[k] - t[k - 1]))


def slip_heat_validity(doc: dict, *, limit_C: float, clearance_m: float | None = None,
                       contact_radius_m: float | None = None, phase_change_C: float = PHASE_CHANGE_C,
                       melting_C: float = MELTING_C) -> dict:
    """The validity flags of a slip-heat answer ``doc`` (the JSON of
    :meth:`SlipHeatResult.to_json`), and the answer cut at a phase change or melting.

    Parameters
    ----------
    doc : dict
        The answer, with ``series`` (``times_s``, ``part_max_C``, ``part_mean_C``, ...),
        ``ambient_temperature_C``, ``cycles_table``, ``seconds`` and ``pause_s``.
    limit_C : float
        The tempering (limit) temperature [C].
    phase_change_C, melting_C : float, optional
        The material's phase change and melting temperatures [C] (defaults: steel, module
        docstring; ``ThermalMaterial.phase_change_temperature`` / ``melting_temperature``
        for another material, e.g. aluminium, which melts near 600 C).
    clearance_m, contact_radius_m : float, optional
        Radial clearance between the shoes and the drum at rest [m] and the contact radius
        [m]; without them the clearance is not checked.

    Returns
    -------
    dict
        The fields to update ``doc`` with: ``validity`` (a list of ``{"flag", "level_C",
        "time_s", "meaning"}``, empty when the whole answer is in range), ``valid`` (False
        once cut), and when cut ``stopped_at_s`` with the series, peaks and event rows up to
        the crossing (``time_to_limit_s`` None if the limit comes later).

    Examples
    --------
    >>> doc = {"series": {"times_s": [0.0, 1.0, 2.0], "part_max_C": [25.0, 500.0, 900.0],
    ...        "part_mean_C": [25.0, 60.0, 90.0]}, "ambient_temperature_C": 25.0,
    ...        "cycles_table": [], "seconds": 2.0, "pause_s": 0.0}
    >>> v = slip_heat_validity(doc, limit_C=400.0)
    >>> [f["flag"] for f in v["validity"]], round(v["stopped_at_s"], 2)
    (['tempering', 'phase change'], 1.57)
    """
    s = doc["series"]
    t = np.asarray(s["times_s"], dtype=float)
    pmax = np.asarray(s["part_max_C"], dtype=float)
    flags: list[dict] = []
    out: dict = {"valid": True}
    c = _crossing(t, pmax, limit_C)
    if c is not None:
        flags.append({"flag": "tempering", "level_C": float(limit_C), "time_s": c[1],
                      "meaning": f"the hottest point passes the tempering temperature {limit_C:.0f} C at {c[1]:.2f} s: "
                                 "the steel softens for good; material data, conduction and friction are extrapolated "
                                 "past it, so later temperatures are estimates and the damage is at least that of "
                                 "reaching the limit"})
    stop = None
    for flag, level, what in (("phase change", phase_change_C, "the material changes phase (steel: austenite "
                               "starts at A1, ASSUMED): latent heat and rehardening the model does not have"),
                              ("melting", melting_C, "the surface melts (solidus, ASSUMED)")):
        c = _crossing(t, pmax, level)
        if c is None:
            continue
        if stop is None:
            stop = c
            tail = "the transient is stopped there"
        else:
            tail = (f"reached only by the model continued past the stop at {stop[1]:.2f} s, which does not hold "
                    "there: a warning that the part can melt, not an answer")
        flags.append({"flag": flag, "level_C": level, "time_s": c[1],
                      "meaning": f"the hottest point reaches {level:.0f} C at {c[1]:.2f} s: {what}; {tail}"})
    if clearance_m is not None and contact_radius_m is not None and clearance_m > 0 and "part_mean_C" in s:
        dT = clearance_m / (EXPANSION_PER_K * contact_radius_m)
        T_close = float(doc["ambient_temperature_C"]) + dT
        c = _crossing(t, np.asarray(s["part_mean_C"], dtype=float), T_close)
        if c is not None and (stop is None or c[0] <= stop[0]):
            flags.append({"flag": "clearance closed", "level_C": T_close, "time_s": c[1],
                          "meaning": f"the part's mean temperature reaches {T_close:.0f} C at {c[1]:.2f} s: thermal "
                                     f"growth ({EXPANSION_PER_K:.0e} /K, ASSUMED) closes the {clearance_m * 1e3:.2f} mm "
                                     "clearance at rest: the shoes touch the drum standing still (the clutch drags at "
                                     "idle) until it cools"})
    out["validity"] = flags
    if stop is not None:
        k, ts = stop
        # every series up to the crossing, ending at it (linear between the steps around it)
        f = 0.0 if k == 0 else (ts - t[k - 1]) / (t[k] - t[k - 1])

        def upto(v):
            v = np.asarray(v, dtype=float)
            return list(v[:k]) + [float(v[k] if k == 0 else v[k - 1] + f * (v[k] - v[k - 1]))]

        cut = {name: (None if v is None else upto(v)) for name, v in s.items()}
        cut["times_s"] = list(t[:k]) + [ts]
        pm = np.asarray(cut["part_max_C"])
        kp = int(np.argmax(pm))
        out.update({"valid": False, "stopped_at_s": ts, "series": cut,
                    "peak_temperature_C": float(pm[kp]), "peak_time_s": float(cut["times_s"][kp])})
        flex = cut.get("flexure_C")
        if flex:
            kf = int(np.argmax(flex))
            out.update({"flexure_temperature_C": float(flex[kf]), "flexure_peak_time_s": float(cut["times_s"][kf])})
        if doc.get("time_to_limit_s") is not None and doc["time_to_limit_s"] > ts:
            out["time_to_limit_s"] = None
        period = float(doc["seconds"]) + float(doc.get("pause_s") or 0.0)
        # an event row holds its end-of-slip and end-of-pause values: kept only if it ended before the stop
        out["cycles_table"] = [r for r in doc.get("cycles_table", []) if (r["cycle"] - 1) * period
                               + (float(doc["seconds"]) if "end_of_pause_part_max_C" not in r else period) <= ts]
    return out
