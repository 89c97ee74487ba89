"""What a calibration reads: the measurements of a part (with their uncertainty) and the
uncertain inputs (with their priors), parsed from texts with units and checked.

**Measurements** (:class:`Measurement`, :func:`parse_measured`): ``NAME=VALUE+-U`` with units
as everywhere (``U`` one standard uncertainty, in the value's dimension):

* ``engagement=4191rpm+-25rpm``: the static engagement speed (the rig's speed at which the
  drum starts to turn, the engine's speed ripple removed); ``engagement_ripple=...``: the
  engagement with the 2-stroke ripple, as the rig reads it off a running engine;
* ``slip=7512rpm+-40rpm``: the slip speed with the drum held;
* ``torque@6000rpm=5.1Nm+-0.2Nm``: the clutch torque at a speed; the reduced model holds the
  torque at the rpm of the engine's maximum torque, so that speed (within 1 rpm) is the one a
  torque is measured at (a torque-speed curve from a CSV is read there: :func:`torque_from_csv`);
* ``mass=0.21kg+-1g``, ``shoe_mass=...``: the part's and one shoe's mass;
* ``flexure_thickness=2.26mm+-0.01mm``: a measured dimension of the part (a micrometer
  reading) -- any uncertain input's name: the reading is data on the input itself.

**Several parts of one design**: a measurement may name its part, ``PART:NAME=VALUE+-U``
(``p1:engagement=4191rpm+-25rpm``, ``p2:slip=7480rpm+-40rpm``, ``p2:flexure_thickness=2.27mm+-0.01mm``;
PART: letters, digits, ``_``, ``-``, ``.``).  The parts share the operating inputs (``mu``,
``drum_wall``, ``E``, ``density``: one material, one lining, one rig) and each has its own
geometry as built (:func:`clutchfem.calibrate`).  Once one measurement names its part, every
one must.

A name may be repeated on one part (several readings of one part): the readings of one
answer are combined into their weighted mean (:func:`~.readings.combine_readings`; the model's error of
that answer is one and the same for all of them, so it enters once -- the same posterior as
the readings' joint normal likelihood), and readings that disagree beyond their
uncertainties are said to.  Refused: an unknown
name, a value or uncertainty without its unit or in another dimension, an uncertainty of zero
or below, a measured slip speed below the measured engagement speed (a clutch slips only
once it holds), a torque at another speed than the model's.

**Uncertain inputs** (:class:`Uncertain`, :func:`parse_uncertain`), the part as built:

* ``mu=0.1:0.35``: a range, uniform prior (any input);
* ``flexure_thickness=+-0.1mm``: a deviation from the drawn value, normal with the
  tolerance at +-3 sigma (as ``tolerance --tol``, ASSUMED Cp = 1);
* ``mu=0.2+-0.06``: normal about a given value, +-3 sigma likewise.

Names: the concept's real-valued shape parameters (with a declared range: the clearance, the
flexure, the drum radius, ...), ``mu`` and ``drum_wall`` (the reduced model's operating axes,
:data:`clutchfem.reduced.OPERATING_AXES`), and the material's ``E`` and ``density``, which
enter by exact similarity (:mod:`.forward`).  A normal prior is truncated at +-4 sigma: the
reduced model's region reaches that far (a part beyond 4 sigma is 6 in 100,000).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from ..clutch.engine_csv import read_engine_csv
from ..core import InputError, ParameterError, param_bounds, parse_quantity
from ..core.units import UnitError
from ..reduced import OPERATING_AXES

__all__ = ["ANSWER_OF", "SIMILARITY", "Measurement", "Uncertain", "check_measurements",
           "parse_measured", "parse_uncertain", "torque_from_csv"]

#: measurement name -> (the reduced model's answer, unit, what it is)
ANSWER_OF: dict[str, tuple[str, str, str]] = {
    "engagement": ("engagement_rpm", "rpm", "engagement speed (static)"),
    "engagement_ripple": ("engagement_rpm_with_ripple", "rpm", "engagement speed with the engine's ripple"),
    "slip": ("slip_rpm", "rpm", "slip speed (drum held)"),
    "torque": ("torque_at_max_engine_torque_Nm", "N m", "clutch torque"),
    "mass": ("mass_kg", "kg", "part mass"),
    "shoe_mass": ("shoe_mass_kg", "kg", "mass of one shoe"),
}
#: inputs that enter by exact similarity, not as axes of the reduced model: name -> (unit, material field)
SIMILARITY: dict[str, tuple[str, str]] = {"E": ("Pa", "E"), "density": ("kg/m^3", "rho")}
#: a normal prior's truncation (and the reduced model's region) in sigmas; the tolerance is 3
SIGMAS = 4.0
#: the speed a torque is measured at must be the model's within this [rpm]
RPM_MATCH = 1.0
_PM = r"(?:\+-|±|\+/-)"
#: a part's name in ``PART:NAME=...``
_PART = r"[A-Za-z0-9][A-Za-z0-9_.-]*"


@dataclass(frozen=True)
class Measurement:
    """One measured value of the part.

    Attributes
    ----------
    name : str
        ``engagement``, ``slip``, ``torque``, ... (:data:`ANSWER_OF`) or an uncertain input's
        name (a measured dimension).
    value, sd : float
        The value and its standard uncertainty, SI (speeds in rpm).
    unit : str
        The unit of ``value`` (``rpm``, ``N m``, ``m``, ...).
    at_rpm : float or None
        The speed of a torque measurement [rpm].
    text : str
        What was given.
    part : str or None
        The measured part of several of one design (``p1:engagement=...``), or None.
    readings : int
        How many readings it combines (:func:`~.readings.combine_readings`).

    Examples
    --------
    >>> import clutchfem as cf
    >>> m = cf.parse_measured("slip=7512rpm+-40rpm")
    >>> m.name, m.value, m.sd, m.answer
    ('slip', 7512.0, 40.0, 'slip_rpm')
    """

    name: str
    value: float
    sd: float
    unit: str
    at_rpm: float | None = None
    text: str = ""
    part: str | None = None
    readings: int = 1

    @property
    def answer(self) -> str:
        """The reduced model's answer it measures, or the input's name (a dimension)."""
        return ANSWER_OF[self.name][0] if self.name in ANSWER_OF else self.name

    @property
    def is_dimension(self) -> bool:
        return self.name not in ANSWER_OF

    @property
    def key(self) -> str:
        """The answer (or input) it measures, with its part: ``slip_rpm`` or ``slip_rpm[p2]``."""
        return self.answer if self.part is None else f"{self.answer}[{self.part}]"

    def to_json(self) -> dict:
        return {"name": self.name, "value": self.value, "sd": self.sd, "unit": self.unit, "at_rpm": self.at_rpm,
                "text": self.text, "part": self.part, "readings": self.readings}


@dataclass(frozen=True)
class Uncertain:
    """One uncertain input of the part as built, with its prior.

    Attributes
    ----------
    name : str
        The input (a concept parameter, ``mu``, ``drum_wall``, ``E`` or ``density``).
    kind : str
        ``uniform`` (on ``lo..hi``) or ``normal`` (``mean``, ``sd``; truncated at +-4 sd).
    lo, hi : float
        The prior's support (SI): the range, or ``mean +- 4 sd``.
    mean, sd : float
        The prior's centre and standard deviation (of the uniform too).
    unit : str
        The input's unit (``m``, ``-``, ``Pa``, ``kg/m^3``, ``deg``).
    drawn : float
        The design's own value (a deviation is from it).
    text : str
        What was given.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", fidelity="live")
    >>> u = cf.parse_uncertain(d, "flexure_thickness=+-0.1mm")
    >>> u.kind, round(u.mean * 1e3, 6), round(u.sd * 1e6, 3), round(u.hi * 1e3, 6)
    ('normal', 2.2, 33.333, 2.333333)
    >>> [round(x, 6) for x in cf.parse_uncertain(d, "mu=0.1:0.35").prior_ci95()]
    [0.10625, 0.34375]
    """

    name: str
    kind: str
    lo: float
    hi: float
    mean: float
    sd: float
    unit: str
    drawn: float
    text: str = ""

    @property
    def axis(self) -> str:
        """``similarity`` (E, density) or ``region`` (an axis of the reduced model)."""
        return "similarity" if self.name in SIMILARITY else "region"

    def logpdf(self, x: np.ndarray) -> np.ndarray:
        """The prior's log density (up to a constant) at ``x``; -inf outside the support."""
        x = np.asarray(x, dtype=float)
        inside = (x >= self.lo) & (x <= self.hi)
        v = np.zeros_like(x) if self.kind == "uniform" else -0.5 * ((x - self.mean) / self.sd) ** 2
        return np.where(inside, v, -np.inf)

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` draws of the prior."""
        if self.kind == "uniform":
            return rng.uniform(self.lo, self.hi, n)
        out = rng.normal(self.mean, self.sd, 2 * n + 16)
        out = out[(out >= self.lo) & (out <= self.hi)]
        while len(out) < n:
            more = rng.normal(self.mean, self.sd, n)
            out = np.concatenate([out, more[(more >= self.lo) & (more <= self.hi)]])
        return out[:n]

    def prior_ci95(self) -> tuple[float, float]:
        """The central 95 % interval of the prior."""
        if self.kind == "uniform":
            w = self.hi - self.lo
            return (self.lo + 0.025 * w, self.hi - 0.025 * w)
        from scipy.stats import truncnorm

        a, b = (self.lo - self.mean) / self.sd, (self.hi - self.mean) / self.sd
        lo, hi = truncnorm.ppf([0.025, 0.975], a, b, loc=self.mean, scale=self.sd)
        return (float(lo), float(hi))

    def to_json(self) -> dict:
        d = {"kind": self.kind, "lo": self.lo, "hi": self.hi, "mean": self.mean, "sd": self.sd,
             "ci95": list(self.prior_ci95()), "unit": self.unit, "drawn": self.drawn, "text": self.text}
        if self.kind == "normal":
            d["truncated_at_sigmas"] = SIGMAS
        return d


# -- parsing -------------------------------------------------------------------------------
def _unit_and_bounds(design, name: str, option: str):
    """(unit, (lo, hi) declared, drawn value) of an uncertain input of ``design``."""
    P = type(design.params)
    if name in SIMILARITY:
        unit, field = SIMILARITY[name]
        return unit, (0.0, math.inf), float(getattr(design.op.material, field))
    if name in OPERATING_AXES:
        if name == "drum_wall" and design.op.drum_wall is None:
            raise ParameterError(name, None, "an elastic drum's wall: the design's drum is rigid (set drum_wall first)",
                                 option)
        a, b = param_bounds(type(design.op), name)
        return OPERATING_AXES[name], (a, b), float(getattr(design.op, name))
    f = P.model_fields.get(name)
    known = [n for n, g in P.model_fields.items() if g.annotation is float and None not in param_bounds(P, n)]
    if f is None or name not in known:
        raise ParameterError(name, None, "an uncertain input: " + ", ".join(known + list(OPERATING_AXES)
                                                                              + list(SIMILARITY)), option)
    return P.unit(name), param_bounds(P, name), float(getattr(design.params, name))


def _q(raw: str, unit: str, name: str, text: str, option: str) -> float:
    try:
        v = parse_quantity(raw, unit)
    except UnitError as exc:
        raise ParameterError(name, text, exc.expected, option) from None
    if not math.isfinite(v):
        raise ParameterError(name, text, "a finite value", option)
    return float(v)


def _show(v: float, unit: str) -> str:
    return {"m": f"{v * 1e3:g} mm", "Pa": f"{v * 1e-9:g} GPa"}.get(unit, f"{v:g} {unit}".rstrip(" -"))


def parse_uncertain(design, text: str) -> Uncertain:
    """An uncertain input of ``design`` from ``NAME=SPEC`` (module docstring).

    Parameters
    ----------
    design : Design
        The drawn design (a concept's): a deviation is from its value.
    text : str
        ``mu=0.1:0.35`` (uniform), ``flexure_thickness=+-0.1mm`` (normal, +-3 sigma about
        the drawn value) or ``mu=0.2+-0.06`` (normal about the value given).

    Returns
    -------
    Uncertain

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", fidelity="live")
    >>> cf.parse_uncertain(d, "clearance=0.5mm:0.8mm").lo
    0.0005
    >>> cf.parse_uncertain(d, "mu=0:0.35")
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: option --uncertain: parameter 'mu' = 'mu=0:0.35' is not allowed: a range lo:hi with lo < hi within the declared range 0 .. 1 and lo > 0 (no torque without friction)
    """
    option = "option --uncertain"
    if design.params is None:
        raise ParameterError("design", design.name, "a concept's design (a user mesh has no parameters to calibrate)",
                             option)
    m = re.fullmatch(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.+?)\s*", str(text))
    if not m:
        raise ParameterError("uncertain", text, "NAME=lo:hi, NAME=+-tol or NAME=value+-tol with units, e.g. "
                             "mu=0.1:0.35 or flexure_thickness=+-0.1mm", option)
    name, spec = m.groups()
    unit, (a, b), drawn = _unit_and_bounds(design, name, option)
    a = -math.inf if a is None else a
    b = math.inf if b is None else b
    if ":" in spec:
        lo_t, hi_t = spec.split(":", 1)
        lo, hi = _q(lo_t, unit, name, text, option), _q(hi_t, unit, name, text, option)
        if not (a <= lo < hi <= b) or (name == "mu" and lo <= 0):
            raise ParameterError(name, text, f"a range lo:hi with lo < hi within the declared range "
                                 f"{_show(a, unit)} .. {_show(b, unit)}" + (" and lo > 0 (no torque without friction)"
                                                                            if name == "mu" else ""), option)
        mean, sd = 0.5 * (lo + hi), (hi - lo) / math.sqrt(12.0)
        return Uncertain(name, "uniform", lo, hi, mean, sd, unit, drawn, text)
    mm = re.fullmatch(rf"(.*?)\s*{_PM}\s*(\S+)", spec)
    if not mm:
        raise ParameterError(name, text, "lo:hi (uniform), +-tol (normal about the drawn value, tol = 3 sigma) or "
                             "value+-tol (normal about value)", option)
    centre_t, tol_t = mm.groups()
    mean = drawn if not centre_t.strip() else _q(centre_t, unit, name, text, option)
    tol = _q(tol_t, unit, name, text, option)
    if tol <= 0:
        raise ParameterError(name, text, f"a tolerance > 0 (+-3 sigma, in {unit})".replace(" in -", ""), option)
    sd = tol / 3.0
    lo, hi = mean - SIGMAS * sd, mean + SIGMAS * sd
    if lo <= a or hi >= b:
        raise ParameterError(name, text, f"value +-{SIGMAS:g} sigma ({_show(lo, unit)} .. {_show(hi, unit)}) within "
                             f"the declared range ({_show(a, unit)} .. {_show(b, unit)}): a narrower tolerance",
                             option)
    return Uncertain(name, "normal", lo, hi, mean, sd, unit, drawn, text)


def parse_measured(text: str, *, design=None) -> Measurement:
    """A measurement from ``NAME=VALUE+-U`` (module docstring; ``torque@RPM=...``).

    Parameters
    ----------
    text : str
        ``engagement=4191rpm+-25rpm``, ``torque@6000rpm=5.1Nm+-0.2Nm``, or a measured
        dimension ``flexure_thickness=2.26mm+-0.01mm`` (then ``design`` gives its unit).
    design : Design, optional
        The drawn design (the unit of a measured dimension).

    Returns
    -------
    Measurement

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.parse_measured("torque@6000rpm=5.1Nm+-0.2Nm").at_rpm
    6000.0
    >>> cf.parse_measured("slip=7512rpm+-0rpm")
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: option --measured: parameter 'slip' = 'slip=7512rpm+-0rpm' is not allowed: an uncertainty > 0 (one standard uncertainty, e.g. +-25rpm): a measurement without one cannot be weighed
    """
    option = "option --measured"
    m = re.fullmatch(rf"\s*(?:({_PART})\s*:\s*)?([A-Za-z_][A-Za-z0-9_]*)\s*(?:@\s*(\S+?))?\s*=\s*(.+?)\s*{_PM}"
                     r"\s*(\S+)\s*", str(text))
    if not m:
        raise ParameterError("measured", text, "[PART:]NAME=VALUE+-U with units (U one standard uncertainty), e.g. "
                             "engagement=4191rpm+-25rpm, torque@6000rpm=5.1Nm+-0.2Nm, p2:slip=7480rpm+-40rpm", option)
    part, name, at, val_t, sd_t = m.groups()
    if name in ANSWER_OF:
        unit = ANSWER_OF[name][1]
    elif design is not None and design.params is not None:
        try:
            unit = _unit_and_bounds(design, name, option)[0]
        except ParameterError:
            raise ParameterError(name, text, "a measured answer (" + ", ".join(ANSWER_OF) + ") or a measured "
                                 "dimension of an uncertain input", option) from None
    else:
        raise ParameterError(name, text, "a measured answer: " + ", ".join(ANSWER_OF), option)
    if (at is not None) != (name == "torque"):
        raise ParameterError(name, text, "torque@SPEED=VALUE+-U (a torque at a speed); other measurements have no "
                             "@SPEED", option)
    value, sd = _q(val_t, unit, name, text, option), _q(sd_t, unit, name, text, option)
    if not sd > 0:
        raise ParameterError(name, text, f"an uncertainty > 0 (one standard uncertainty, e.g. "
                             f"{'+-25rpm' if unit == 'rpm' else '+-0.01mm' if unit == 'm' else '+-0.1Nm'}): a "
                             "measurement without one cannot be weighed", option)
    if not value > 0 and unit != "deg":
        raise ParameterError(name, text, f"a value > 0 {unit}".rstrip(" -"), option)
    at_rpm = _q(at, "rpm", name, text, option) if at is not None else None
    if at_rpm is not None and not at_rpm > 0:
        raise ParameterError(name, text, "a speed > 0 rpm after @", option)
    return Measurement(name, value, sd, unit, at_rpm, str(text).strip(), part)


def check_measurements(measured: list[Measurement]) -> None:
    """Refuse a set of measurements that contradict each other (a slip speed below the
    engagement speed: a clutch slips only once it holds).

    Parameters
    ----------
    measured : list of Measurement

    Returns
    -------
    None
        Or a :class:`~clutchfem.ParameterError` naming the contradicting measurement.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.check_measurements([cf.parse_measured("engagement=4191rpm+-25rpm"), cf.parse_measured("slip=7512rpm+-40rpm")])
    >>> cf.check_measurements([cf.parse_measured("p1:engagement=4191rpm+-25rpm"), cf.parse_measured("p2:slip=4100rpm+-40rpm")])
    >>> cf.check_measurements([cf.parse_measured("engagement=4191rpm+-25rpm"), cf.parse_measured("slip=4000rpm+-40rpm")])
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: option --measured: parameter 'slip' = 'slip=4000rpm+-40rpm' is not allowed: a slip speed above the measured engagement speed (engagement=4191rpm+-25rpm): a clutch slips only once it has engaged
    """
    eng = [m for m in measured if m.name in ("engagement", "engagement_ripple")]
    slip = [m for m in measured if m.name == "slip"]
    for s in slip:
        for e in eng:
            if s.part == e.part and s.value <= e.value:
                raise ParameterError("slip", s.text, f"a slip speed above the measured engagement speed ({e.text}): a "
                                     "clutch slips only once it has engaged", "option --measured")


def torque_from_csv(path, rpm: float, sd: float) -> Measurement:
    """The measured torque at ``rpm`` from a torque-speed curve in a CSV file (the engine
    curve's reader, :func:`clutchfem.clutch.engine_csv.read_engine_csv`: the units from the
    header), linearly interpolated.

    Parameters
    ----------
    path : str or Path
        The CSV file (a speed and a torque column, units in the header).
    rpm : float
        The speed to read the torque at [rpm] (the engine's maximum-torque speed).
    sd : float
        The torque's standard uncertainty [N m].

    Returns
    -------
    Measurement
        ``torque`` at ``rpm``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from clutchfem.calibration import torque_from_csv
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "rig.csv"
    >>> _ = p.write_text("speed [rpm],torque [N cm]\\n5000,200\\n7000,600\\n")
    >>> m = torque_from_csv(p, 6000.0, 0.1)
    >>> m.name, round(m.value, 9), m.at_rpm
    ('torque', 4.0, 6000.0)
    """
    t = read_engine_csv(path)
    r, q = np.asarray(t.rpm, dtype=float), np.asarray(t.torque, dtype=float)
    if not (r.min() <= rpm <= r.max()):
        raise InputError(f"torque curve file {path}: its speeds {r.min():.0f}..{r.max():.0f} rpm do not reach "
                         f"{rpm:.0f} rpm, the speed the reduced model holds the torque at")
    if not (isinstance(sd, (int, float)) and sd > 0):
        raise ParameterError("torque_sd", sd, "an uncertainty > 0 N m of the curve's torque", "torque curve")
    order = np.argsort(r)
    v = float(np.interp(rpm, r[order], q[order]))
    return Measurement("torque", v, float(sd), "N m", float(rpm), f"torque@{rpm:.0f}rpm from {path}")
