"""The answer records of an analysis: the designer's requirement factors, each step's frozen
answer, and :class:`Analysis`, everything the report renders.

Each step of :func:`clutchfem.analysis.analyze` returns one small frozen record (slip,
engagement, character, mu sensitivity, stress, fatigue); :class:`Analysis` collects the
answers with their units in the field names (rpm: 1/min, torque N m, stress Pa, power W,
angles deg, lengths m, mass kg) and writes them as strict JSON (:meth:`Analysis.to_json`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..core import ParameterError, clean

if TYPE_CHECKING:  # pandas loads when a table of curves is first read (a live answer's start-up needs none)
    import pandas as pd

#: Defaults of the requirement factors.  The thesis keeps a and b confidential: ASSUMED.
DEFAULT_A = 1.3
DEFAULT_B = 1.0


@dataclass
class Requirements:
    """Designer's factors: engagement > a x idle rpm; slip < b x rpm of max engine torque.

    The thesis keeps a and b confidential: the defaults a = 1.3, b = 1.0 are ASSUMED.

    Parameters
    ----------
    a, b : float

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.Requirements(a=1.4).a
    1.4
    """

    a: float = DEFAULT_A
    b: float = DEFAULT_B

    def __post_init__(self):
        what = {"a": "engagement rpm must exceed a x idle rpm",
                "b": "slip rpm must stay below b x rpm of the maximum engine torque"}
        for name in ("a", "b"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                    or not math.isfinite(float(v)) or float(v) <= 0:
                raise ParameterError(name, v, f"a finite factor > 0 ({what[name]})",
                                     context="requirement factors")

    @property
    def assumed(self) -> bool:
        return (self.a, self.b) == (DEFAULT_A, DEFAULT_B)


@dataclass(frozen=True)
class SlipAnswer:
    """Slip speed with the drum held and full throttle.

    ``status``: 'slips' (clutch torque meets the engine curve at ``rpm``: below it the clutch
    slips, there it holds the engine), 'holds at start' (the clutch already holds the engine
    torque at the lowest speed of the engine curve), 'never holds' (the clutch torque stays
    below the engine torque at every speed: it slips all the way and the engine runs to its
    maximum speed; mu = 0 or an engine far stronger than the clutch), 'never engages' (no
    contact within the engine's speed range: no torque at all).
    """

    rpm: float | None
    status: str
    note: str
    crossings: tuple[tuple[float, str], ...] = ()


@dataclass(frozen=True)
class EngagementAnswer:
    """Static engagement (FE) and with the 2-stroke ripple (3 sigma and typical cycle) [rpm]."""

    static_rpm: float | None
    with_ripple_rpm: float | None
    with_ripple_typical_rpm: float | None
    note: str


@dataclass(frozen=True)
class CharacterAnswer:
    """Plus/minus character of the shoes from the FE (friction raises or lowers N)."""

    overall: str
    per_shoe: tuple
    probe_rpm: float


@dataclass(frozen=True)
class MuSensitivity:
    """Torque at ``rpm`` and slip speed at mu x 0.7 / 1.0 / 1.3."""

    rpm: float
    mu: float
    torque_Nm: dict
    slip_rpm: dict
    torque_change_pct: dict | None = None
    elasticity: float | None = None
    #: what the step could not do (a factor giving mu > 1 is skipped); the analysis's notes
    notes: tuple[str, ...] = ()
    #: factor key -> why that case has no answer (mu > 1, a self-locking plus shoe, ...): a
    #: side case that fails never takes the main answers with it
    not_available: dict | None = None

    def to_json(self) -> dict:
        d = {"rpm": self.rpm, "mu": self.mu, "torque_Nm": dict(self.torque_Nm), "slip_rpm": dict(self.slip_rpm),
             "not_available": dict(self.not_available or {})}
        if self.torque_change_pct is not None:
            d["torque_change_pct"] = dict(self.torque_change_pct)
            d["elasticity"] = self.elasticity
        return d


@dataclass(frozen=True)
class StressAnswer:
    """Peak von Mises and safety factor against yield at ``rpm`` (the engine maximum)."""

    rpm: float
    max_von_mises_Pa: float
    safety_factor: float
    location_m: tuple[float, float]
    yield_strength_Pa: float

    def corrected(self, max_von_mises_Pa: float) -> "StressAnswer":
        """The same answer with the peak ``max_von_mises_Pa`` [Pa] (a corrected best estimate)
        and its safety factor against yield."""
        sf = self.yield_strength_Pa / max_von_mises_Pa if max_von_mises_Pa > 0 else self.safety_factor
        return StressAnswer(self.rpm, float(max_von_mises_Pa), float(sf), self.location_m, self.yield_strength_Pa)


@dataclass(frozen=True)
class FatigueAnswer:
    """Fatigue check of the part (:func:`~clutchfem.analysis.strength.fatigue_step`):
    ``safety_factor`` the load multiplier at which Miner's sum reaches 1 at the worst point
    (None: not available, ``details['reason']``; inf: no stress changes), ``location`` that
    point named (zone, flexure end, boundary), ``governing_cycle`` the cycle type with the
    largest damage share there, ``details`` the rest (JSON-ready: per-cycle
    amplitude/mean/damage, loads, counts, ASSUMED values)."""

    safety_factor: float | None
    location: str | None
    governing_cycle: str | None
    details: dict

    def to_json(self) -> dict:
        return {"safety_factor": self.safety_factor, "location": self.location,
                "governing_cycle": self.governing_cycle, **self.details}


@dataclass(frozen=True)
class Analysis:
    """Answers for one design (see :func:`analyze`); units in the field names or docstrings.

    Attributes
    ----------
    engagement_rpm, engagement_rpm_with_ripple : float or None
        Static and 2-stroke ripple engagement speeds [rpm].
    slip_rpm : float or None
        Slip speed, drum held, full throttle [rpm]; ``slip_status`` says why None.
    torque_at_max_engine_torque_Nm, torque_margin_Nm : float
    max_von_mises_Pa, safety_factor : float
        At the engine's maximum speed.
    fatigue_safety_factor : float or None
    errors : dict
        The error band of every main answer (discretisation and model form).
    curves : pandas.DataFrame
        Torque, arc, stress and the analytical models against rpm.  May be given as a mapping of
        column name -> array: it becomes the DataFrame on first read (pandas is then imported).
    warnings, notes : list of str

    Examples
    --------
    >>> import clutchfem as cf
    >>> a = cf.analyze(cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm")), errors=False)
    >>> a.slip_status, a.engagement_rpm < a.slip_rpm
    ('slips', True)
    """

    design: str
    engagement_rpm: float | None
    engagement_rpm_with_ripple: float | None
    engagement_rpm_with_ripple_typical: float | None
    engagement_note: str
    slip_rpm: float | None
    slip_status: str
    slip_note: str
    slip_crossings_rpm: list
    rpm_max_engine_torque: float
    max_engine_torque_Nm: float
    torque_at_max_engine_torque_Nm: float
    torque_margin_Nm: float
    max_engine_rpm: float
    max_von_mises_Pa: float
    safety_factor: float
    max_stress_rpm: float
    max_stress_location_m: list
    yield_strength_Pa: float
    slip_power_W: float | None
    shoe_character: str
    shoe_character_per_shoe: list
    mu: float
    mu_sensitivity: dict
    torque_models_at_max_engine_torque_Nm: dict
    contact_arc_at_max_engine_torque_deg: float
    requirements: dict
    engine: dict
    coupling: dict
    curves: pd.DataFrame
    first_touch: str | None
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    #: whole part (and per-shoe zones where the mesh names them) from the mesh: area, mass,
    #: centre of mass; see :func:`clutchfem.mesh.mesh_mass_properties`
    part: dict = field(default_factory=dict)
    #: False for a user mesh: no shoe mass properties / pivot / nominal arc, so the
    #: analytical shoe-model curves are not available (NaN), the FE answers are
    analytical_available: bool = True
    #: polar angle [deg] of the first contact node (drum frame); with a user mesh the shoe's
    #: root and tip are unknown, so ``first_touch`` is 'unknown' and this angle locates it
    first_touch_angle_deg: float | None = None
    #: everything that defines the answers (clutchfem.loadcase.design_inputs) and the
    #: file-name stem that tells this design apart from others in one folder
    inputs: dict = field(default_factory=dict)
    label: str = ""
    #: the design's identity hash (clutchfem.loadcase.identity; 12 hex): the same design gives the
    #: same hash in every face (analyze, solve, report, export, the app, a study row)
    design_hash: str = ""
    #: crankshaft whirl with this clutch on the overhang (clutchfem.clutch.crankshaft.WhirlAnswer.to_json)
    whirl: dict = field(default_factory=dict)
    #: error estimate of the main answers (clutchfem.accuracy): per answer the discretisation
    #: (two mesh levels), the model-form terms and their total band
    errors: dict = field(default_factory=dict)
    #: fatigue (fatigue_step): load multiplier at which Miner's sum reaches 1 at the worst point
    #: (None: not available, see ``fatigue['reason']``), where that point is, which cycle
    #: type governs there, and the details (:meth:`FatigueAnswer.to_json`)
    fatigue_safety_factor: float | None = None
    fatigue_location: str | None = None
    fatigue_governing_cycle: str | None = None
    fatigue: dict = field(default_factory=dict)
    #: the contact nodes carrying load (indices of the design's contact surface) at the slip
    #: speed, the rpm of maximum engine torque and the engine's maximum speed: keys "slip",
    #: "torque", "peak" (clutchfem.analysis.torque.contact_sets_step); designs morphed from one
    #: reference share the numbering, and a change between them is a kink of those answers
    contact_sets: dict = field(default_factory=dict)
    #: what answered: "FE" (the analysis steps above), "reduced model" (a live answer of
    #: clutchfem.reduced: milliseconds, its own measured error in every band) or "FE (fallback)"
    #: (a live design the reduced model could not answer; the notes say why)
    answered_by: str = "FE"
    #: the key of the reduced model's region of a live answer (clutchfem.reduced.Region.key)
    region_key: str | None = None

    @property
    def curve_names(self) -> list[str]:
        """The names of the columns of :attr:`curves`, read without making the table."""
        return list(self.__dict__[_CURVES])

    def to_json(self) -> dict:
        d = {k: v for k, v in self.__dict__.items() if k != _CURVES}
        d["units"] = {"rpm": "1/min", "torque": "N m", "stress": "Pa", "power": "W",
                      "safety_factor": "- (yield strength / max von Mises)",
                      "fatigue_safety_factor": "- (load multiplier at which Miner's sum reaches 1)", "angles": "deg",
                      "lengths": "m", "mass": "kg", "force": "N"}
        c = self.__dict__[_CURVES]
        if isinstance(c, dict):  # still its columns: the records without pandas
            cols = {k: np.asarray(v).tolist() for k, v in c.items()}
            d["curves"] = [dict(zip(cols, row)) for row in zip(*cols.values())]
        else:
            d["curves"] = c.to_dict("records")
        return clean(d)


#: where an Analysis keeps its curves: a DataFrame, or the columns it is made from on first read
_CURVES = "_curves"


def _get_curves(self: Analysis) -> pd.DataFrame:
    c = self.__dict__[_CURVES]
    if isinstance(c, dict):
        import pandas as pd

        c = self.__dict__[_CURVES] = pd.DataFrame(c)
    return c


def _set_curves(self: Analysis, value) -> None:
    self.__dict__[_CURVES] = dict(value) if isinstance(value, dict) else value


# set after the dataclass is made, so that ``curves`` stays an ordinary (required) field of its
# __init__, __eq__ and dataclasses.replace, read and written through the property
Analysis.curves = property(_get_curves, _set_curves, doc="Torque, arc, stress and the analytical models against "
                                                         "rpm (:class:`pandas.DataFrame`).")

