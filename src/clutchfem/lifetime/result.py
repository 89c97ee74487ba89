"""What :func:`~clutchfem.lifetime.life` returns: :class:`Life`, the answers against the number of
starts (units in the names), the worn profile, the first misses of the requirements with
their band, and its JSON (:meth:`Life.to_json`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core import clean
from ..loadcase import design_inputs, design_label

__all__ = ["Life"]


def _first_miss(starts: np.ndarray, margin: np.ndarray) -> float | None:
    """First number of starts where ``margin`` (>= 0: met) turns negative, linear between the
    states; 0 when missed from the start, None when never."""
    bad = np.nonzero(~(margin >= 0))[0]
    if not len(bad):
        return None
    k = int(bad[0])
    if k == 0 or not math.isfinite(margin[k]):
        return float(starts[k])
    m0, m1 = margin[k - 1], margin[k]
    return float(starts[k - 1] + m0 / (m0 - m1) * (starts[k] - starts[k - 1]))


@dataclass(frozen=True)
class Life:
    """The clutch over its life (:func:`~clutchfem.lifetime.life`): arrays against the number of
    starts ``starts`` (one value per wear state), the worn profile along the shoe, the
    requirement misses and their band, the energy balance of the starts.

    Attributes
    ----------
    starts : ndarray
        Number of starts of each state.
    hours : ndarray or None
        Running hours of each state (with a duty cycle).
    engagement_rpm, slip_rpm : ndarray
        Static engagement and slip speed (drum held, full throttle) [rpm] (NaN: none).
    torque_at_max_engine_torque_Nm, contact_arc_deg : ndarray
        At the rpm of maximum engine torque.
    slip_energy_per_start_J, time_to_lockup_s, peak_slip_power_W, engine_droop_rpm : ndarray
        Of a free start at each state.
    shoe_face_rise_K : ndarray
        Peak mean patch temperature rise of the shoe face in a free start [K].
    worn_profile_m : ndarray (states, len(profile_s))
        The shoe's worn depth along its arc (``profile_s``: 0 root, 1 tip) [m].
    drum_worn_m : ndarray
        The drum's uniform worn depth [m].
    first_miss : dict
        Per requirement the first number of starts at which it is missed (None: never; 0:
        from new) with its band over Archard's k.
    energy_balance : float
        Largest relative residual of the energy balance of every start computed.
    fields : list of dict
        The kept worn states' mesh, displacement, von Mises stress and worn depth
        (``life(fields=...)``; :func:`~clutchfem.lifetime.state.state_fields`).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> L = cf.life(d, starts=500, rebuild_depth=None)
    >>> sorted(k for k in L.to_json()["arrays"] if k.startswith("engagement"))
    ['engagement_rpm']
    """

    design: str
    label: str
    starts: np.ndarray
    hours: np.ndarray | None
    engagement_rpm: np.ndarray
    slip_rpm: np.ndarray
    torque_at_max_engine_torque_Nm: np.ndarray
    contact_arc_deg: np.ndarray
    slip_energy_per_start_J: np.ndarray
    time_to_lockup_s: np.ndarray
    peak_slip_power_W: np.ndarray
    engine_droop_rpm: np.ndarray
    shoe_face_rise_K: np.ndarray
    drum_worn_m: np.ndarray
    profile_s: np.ndarray
    worn_profile_m: np.ndarray
    pressure_s_new: np.ndarray
    pressure_new_Pa: np.ndarray
    pressure_s_worn: np.ndarray
    pressure_worn_Pa: np.ndarray
    first_miss: dict
    limits: dict
    band: dict
    energy_balance: float
    wear_steps: dict
    rebuilds_at_starts: list
    assumptions: dict
    inputs: dict
    seconds: float
    notes: list = field(default_factory=list)
    states: list = field(default_factory=list, repr=False)
    fields: list = field(default_factory=list, repr=False)

    ARRAYS = ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "contact_arc_deg",
              "slip_energy_per_start_J", "time_to_lockup_s", "peak_slip_power_W", "engine_droop_rpm",
              "shoe_face_rise_K", "drum_worn_m")

    @classmethod
    def build(cls, design, run, *, engine, drive, wear, duty, req, idle_rpm, rebuilds, rebuild_depth,
              energy_balance, seconds, notes, profile_s, fields=()) -> "Life":
        """The result of a wear run (:func:`~clutchfem.durability.integrate_wear` whose infos are
        the life run's states)."""
        info = run.info
        starts = np.asarray(run.starts, dtype=float)

        def col(key, sub=None):
            out = []
            for i in info:
                v = i[key] if sub is None else (i[key] or {}).get(sub)
                out.append(math.nan if v is None else float(v))
            return np.array(out)

        eng, slip = col("engagement_rpm"), col("slip_rpm")
        limits = {"engagement_min_rpm": req.a * idle_rpm, "slip_max_rpm": req.b * float(engine.rpm_max_torque),
                  "requirement_factors": {"a": req.a, "b": req.b}, "idle_rpm": idle_rpm,
                  "rpm_max_engine_torque": float(engine.rpm_max_torque)}
        miss = {"engagement": _first_miss(starts, eng - limits["engagement_min_rpm"]),
                "slip": _first_miss(starts, np.where(np.isnan(slip), -1.0, limits["slip_max_rpm"] - slip))}
        k = wear.k
        k_lo, k_hi = wear.k_band
        # the answers depend on n k / H only: a first miss at n (central k) is at n k / k_end
        band = {"wear_coefficient": k, "wear_coefficient_band": [k_lo, k_hi], "assumed": wear.assumed,
                "first_miss_band_starts": {q: None if v is None else [v * k / k_hi, v * k / k_lo]
                                           for q, v in miss.items()}}
        N = float(starts[-1])
        at_end = {}
        for q in ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "contact_arc_deg"):
            y = {"engagement_rpm": eng, "slip_rpm": slip}.get(q, col(q))
            lo_n, hi_n = N * k_lo / k, N * k_hi / k
            at_end[q] = {"value": float(y[-1]), "at_low_k": float(np.interp(lo_n, starts, y)),
                         "at_high_k": float(np.interp(hi_n, starts, y)) if hi_n <= N * (1 + 1e-9) else None}
        band["at_end"] = at_end
        band["note"] = ("the answers depend on Archard's k/H only through n k/H: at the high end of k the answers "
                        f"at {N:.0f} starts are the run's at {N * k_hi / k:.0f} starts (null where the run did not "
                        "reach them: run with that many starts); the other assumed inputs (inertias, loads, "
                        "throttle ramp, duty cycle) are not in the band, their values are in 'assumptions'")
        first, last = info[0], info[-1]
        hours = None if duty is None else np.asarray(duty.hours(starts), dtype=float)
        d_in = design_inputs(design)
        return cls(
            design=design.name, label=design_label(design), starts=starts, hours=hours, engagement_rpm=eng,
            slip_rpm=slip, torque_at_max_engine_torque_Nm=col("torque_at_max_engine_torque_Nm"),
            contact_arc_deg=col("contact_arc_deg"), slip_energy_per_start_J=col("start", "slip_energy_J"),
            time_to_lockup_s=col("start", "time_to_lockup_s"), peak_slip_power_W=col("start", "peak_slip_power_W"),
            engine_droop_rpm=col("start", "engine_droop_rpm"), shoe_face_rise_K=col("heating", "peak_rise_K"),
            drum_worn_m=col("drum_worn_m"), profile_s=np.asarray(profile_s),
            worn_profile_m=np.array([i["worn_profile_m"] for i in info]),
            pressure_s_new=first["pressure_s"], pressure_new_Pa=first["pressure_at_max_engine_torque_Pa"],
            pressure_s_worn=last["pressure_s"], pressure_worn_Pa=last["pressure_at_max_engine_torque_Pa"],
            first_miss=miss, limits=limits, band=band, energy_balance=float(energy_balance),
            wear_steps={"states": len(starts), "shrunk_steps": run.shrunk, "max_step_m": wear.max_step,
                        "rate_change": wear.rate_change,
                        "step_limit_m": {"min": float(np.min(run.limits_m)) if run.limits_m else None,
                                         "max": float(np.max(run.limits_m)) if run.limits_m else None},
                        "elastic_give_m": [i.get("elastic_give_m") for i in info],
                        "method": "linearly implicit Euler in the number of starts (the contact problem's "
                                  "Jacobian) with Newton corrections, no node wearing more per step than "
                                  "max_step and the wear rate changing by no more than rate_change x its "
                                  "largest value (linearised)",
                        "rebuild_depth_m": rebuild_depth},
            rebuilds_at_starts=list(rebuilds),
            assumptions={"drive_line": drive.model_dump(), "wear": {**wear.model_dump(), "k_used": k},
                         "duty_cycle": None if duty is None else duty.model_dump(),
                         "engine": {"source": engine.source, "assumed_shape": engine.assumed}},
            inputs=d_in, seconds=float(seconds), notes=list(notes), states=list(info), fields=list(fields))

    def to_json(self) -> dict:
        """Strict-JSON dict: ``arrays`` against ``starts`` (units in the keys), the worn
        profile, the pressure along the arc new and worn, the first misses with their band,
        ``energy_balance`` and the assumptions."""
        arrays = {"starts": self.starts.tolist()}
        if self.hours is not None:
            arrays["hours"] = self.hours.tolist()
        for k in self.ARRAYS:
            arrays[k] = getattr(self, k).tolist()
        return clean({
            "design": self.design, "label": self.label, "arrays": arrays,
            "units": {"starts": "-", "hours": "h", "rpm": "1/min", "Nm": "N m", "deg": "deg", "J": "J", "s": "s",
                      "W": "W", "K": "K", "m": "m", "Pa": "Pa"},
            "slip_energy_per_start_J": float(self.slip_energy_per_start_J[0]),
            "worn_profile": {"s": self.profile_s.tolist(), "worn_m": self.worn_profile_m.tolist(),
                             "note": "arc fraction s from the shoe's root (0) to its tip (1); one row per state"},
            "pressure_along_arc": {"rpm": self.limits["rpm_max_engine_torque"],
                                   "new": {"s": self.pressure_s_new.tolist(), "pressure_Pa": self.pressure_new_Pa.tolist()},
                                   "worn": {"s": self.pressure_s_worn.tolist(),
                                            "pressure_Pa": self.pressure_worn_Pa.tolist()}},
            "first_miss_starts": self.first_miss, "limits": self.limits, "band": self.band,
            "energy_balance": self.energy_balance, "wear_steps": self.wear_steps,
            "rebuilds_at_starts": self.rebuilds_at_starts, "assumptions": self.assumptions, "inputs": self.inputs,
            "seconds": self.seconds, "notes": self.notes,
            "first_start": self.states[0]["start"] if self.states else None,
            "first_start_heating": self.states[0]["heating"] if self.states else None})
