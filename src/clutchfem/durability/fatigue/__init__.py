"""High-cycle fatigue of the clutch from stress states: pure functions, no FE solve inside.

For every cycle type the plane stresses at the same points in the cycle's two extreme
states and its number of cycles in the clutch's life; out comes the load factor at which
Miner's sum over the cycle types reaches 1, at the worst point, named.  By job:

* :mod:`.strength` -- :class:`FatigueParams`, the strength data and rules (ASSUMED, sourced);
* :mod:`.stresses` -- amplitude and mean tensors, their equivalent (von Mises) values;
* :mod:`.criteria` -- Marin factors and endurance limit, Haigh (Goodman/Gerber), Basquin
  S-N curve with its knee, allowed amplitude, the one-cycle-type load factor;
* :mod:`.check` -- :class:`LoadCycle`, Miner's damage, the load factor per point,
  :func:`fatigue_check` and :class:`FatigueResult`;
* the worst point's name comes from :mod:`clutchfem.mesh.location`
  (:class:`~clutchfem.durability.Location`, :func:`~clutchfem.durability.name_location`).

The names load on first use: a fatigue check of given stresses needs neither the mesh nor the
FE model (and a live answer none of this).
"""

from ...core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562)
_NAMES: dict[str, str] = {
    "allowed_amplitude": "criteria",
    "amplitude_mean": "stresses",
    "ASSUMED": "strength",
    "candidate_points": "check",
    "cycles_to_failure": "criteria",
    "endurance_limit": "criteria",
    "equivalent_stresses": "stresses",
    "fatigue_check": "check",
    "FatigueParams": "strength",
    "FatigueResult": "check",
    "haigh_safety_factor": "criteria",
    "LoadCycle": "check",
    "marin_factors": "criteria",
    "reversed_equivalent": "criteria",
    "single_cycle_factor": "criteria",
    "SURFACE_TABLE": "strength",
}

__all__ = [
    "FatigueParams", "LoadCycle", "FatigueResult", "amplitude_mean",
    "equivalent_stresses", "marin_factors", "endurance_limit", "reversed_equivalent",
    "cycles_to_failure", "haigh_safety_factor", "fatigue_check", "SURFACE_TABLE",
    "allowed_amplitude", "single_cycle_factor", "candidate_points", "ASSUMED",
]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
