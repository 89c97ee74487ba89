"""Design guidelines: which parameter moves which property, and how much (thesis 4.4, with
numbers).

For each studied parameter x of a concept at a design point x0, and each answer A in
:data:`ANSWERS` (engagement rpm, slip rpm, torque at the rpm of maximum engine torque, peak
von Mises at the engine's maximum speed, shoe mass, contact arc), the **local elasticity**

    E = (x0 / A) dA/dx   (1 % more x gives about E % more A)

and a **one-at-a-time sweep** of x over x0 (1 -+ span) within its declared range, the other
parameters at the design point.  Everything runs on the study engine
(:func:`clutchfem.evaluation.runner.run_points`: Dask, store, resume): :mod:`.guideline_study`
runs a guideline study and writes its tables, :mod:`.guideline_charts` draws them.  This
module holds the method: what is studied (:class:`GuidelineSettings`), the designs it takes
(:func:`plan`), the elasticity and its checks (:func:`morphed_elasticity`,
:func:`elasticity`) and the result (:class:`GuidelineResult`).

The elasticity (issue 21).  dA/dx is the design sensitivity of :func:`.sensitivity.sensitivities`:
a central difference on meshes *morphed* from the design's own (step 0.01 mm, 0.01 deg or
1e-3 of a dimensionless value), smooth in the parameters, with no remeshing noise.  Its
method is named per parameter (:func:`method_text`): "central difference on morphed
meshes"; "one-sided (+/-) difference on morphed meshes" where the concept's rules refuse one
side; "... meshed from scratch (morph refused: reason)" where a morph is refused.  Its
**check**: the same difference at ten times the step (0.1 mm); the elasticity is **stable**
when the two agree within 0.05 + 10 % of |E| (0.05: below it a parameter has no influence
worth a guideline; 10 %: the precision a guideline needs), **unstable** otherwise (the
answer has steps of its own at that scale: the contact arc moves by one contact node, the
peak stress jumps between nodes, the slip root has a tolerance), **unchecked** where the
wider step has no answer.  Where a contact node enters or leaves the zone inside the step
(:mod:`.sensitivity`, "Kinks"), ``kink`` says so and the one-sided elasticities of both
sides are given (``E_left``, ``E_right``).  The operating inputs (mu, the elastic drum's wall, the idle
speed) get the same elasticity on the design's own mesh ("central difference, same mesh
(operating input)"); they are listed, not ranked (a designer does not choose them).

The remeshed check (option ``remeshed_check``, CLI ``--remeshed-check``): the former method,
kept as a cross-check against designs meshed from scratch.  Each parameter is evaluated at
seven remeshed designs, x0 and x0 (1 -+ r) for r = h/2, h and 2h (h = 2 % by default); the
central differences of ln A in ln x,

    E_r = [ln A(x0 (1 + r)) - ln A(x0 (1 - r))] / [ln(1 + r) - ln(1 - r)],

and a quadratic in ln x fitted through all seven (slope E_fit, residual: the noise estimate
eps) give E_remeshed = E_h, stable when E_h/2, E_2h and E_fit agree with it within the rule
above.  Remeshing adds a non-smooth noise eps to A(x); its error on E_r is ~ eps / (sqrt 2
r): measured on concept 4's defaults (BENCHMARKS.md, "Guidelines from morphed
sensitivities"), it left most stress elasticities unstable.  It is an option, not the
default, because it costs six meshed designs per parameter (most of a guideline study's
designs) to measure the remeshing noise rather than the derivative.  Parameters are ranked
by their largest |E| that is not unstable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Literal, get_origin

import numpy as np

from ..core import ParameterError, clean, param_bounds, round12, write
from ..evaluation import Sensitivities, Settings
from ..geometry import MeshSettings, get_concept
from ..loadcase import OperatingPoint

#: answers of the guidelines: (row column, label with unit)
ANSWERS: tuple[tuple[str, str], ...] = (
    ("engagement_rpm", "engagement [rpm]"),
    ("slip_rpm", "slip speed [rpm]"),
    ("torque_at_max_engine_torque_Nm", "torque at max engine torque [N m]"),
    ("max_von_mises_MPa", "peak von Mises at max rpm [MPa]"),
    ("shoe_mass_g", "shoe mass [g]"),
    ("contact_arc_deg", "contact arc at max engine torque [deg]"),
)
#: column heads of the ranked table
SHORT = {"engagement_rpm": "engage", "slip_rpm": "slip", "torque_at_max_engine_torque_Nm": "torque",
         "max_von_mises_MPa": "stress", "shoe_mass_g": "shoe m", "contact_arc_deg": "arc"}
#: agreement required of E_h/2, E_2h and E_fit with E_h: absolute + relative part
STABLE_ABS = 0.05
STABLE_REL = 0.10
#: the step multiples evaluated (relative to h) by the remeshed check
STEP_FACTORS = (0.5, 1.0, 2.0)
#: the check of a morphed elasticity: the difference at this multiple of its step
CHECK_FACTOR = 10.0
#: the guideline answer -> the sensitivities' answer (same quantity, SI units)
SENSITIVITY_KEY = {"engagement_rpm": "engagement_rpm", "slip_rpm": "slip_rpm",
                   "torque_at_max_engine_torque_Nm": "torque_at_max_engine_torque_Nm",
                   "max_von_mises_MPa": "max_von_mises_Pa", "shoe_mass_g": "shoe_mass_kg",
                   "contact_arc_deg": "contact_arc_deg"}


@dataclass(frozen=True)
class GuidelineSettings:
    """What to study: concept, design point (``--set`` values), parameters, relative step h
    of the remeshed check, one-at-a-time points and span, the shared analysis settings,
    the operating inputs (None: every one :func:`.sensitivity.operating_inputs` offers) and
    whether to run the remeshed check.  Made (validated) by :meth:`create` (or
    :meth:`from_design`); :func:`~clutchfem.run_guidelines` runs it.

    Examples
    --------
    >>> import clutchfem as cf
    >>> gs = cf.GuidelineSettings.create("concept1", {"flexure_thickness": "2.4mm"},
    ...                                  ["flexure_thickness", "shoe_arc"], points=5)
    >>> gs.params, gs.points, gs.span                   # span: x0 (1 -+ 0.5) one at a time
    (('flexure_thickness', 'shoe_arc'), 5, 0.5)
    >>> gs.notes[0]                                     # the other profiles' controls
    "not studied (no effect with the 'concentric' profile, elasticity 0): clearance_tip, ..."
    """

    concept: str
    params: tuple[str, ...]
    settings: Settings
    step: float = 0.02
    points: int = 7
    span: float = 0.5
    notes: tuple[str, ...] = ()
    errors: bool = True
    inputs: tuple[str, ...] | None = None
    remeshed_check: bool = False

    @property
    def base(self) -> dict:
        return dict(self.settings.fixed)

    @classmethod
    def create(cls, concept: str, base: dict | None = None, params=None, *, step: float = 0.02, points: int = 7,
               span: float = 0.5, mesh=None, op=None, engine=None, idle_rpm=None, a: float = 1.3,
               b: float = 1.0, min_safety_factor: float = 1.0, inputs=None,
               remeshed_check: bool = False) -> "GuidelineSettings":
        """Validated settings (API); ``base`` concept parameters in their units, ``params``
        names (default: every continuous parameter with a non-zero design value);
        ``inputs`` operating inputs (default: every one available, ``()``: none);
        ``remeshed_check``: also the seven-point fit on remeshed designs."""
        c = get_concept(concept)
        base = dict(base or {})
        p0 = c.Params(**base)  # the design point must itself be valid
        if isinstance(step, bool) or not (isinstance(step, (int, float)) and 0 < step <= 0.1):
            raise ParameterError("step", step, "a relative step h in (0, 0.1] (2h is evaluated too)", "guidelines")
        if isinstance(points, bool) or not (isinstance(points, int) and 3 <= points <= 101):
            raise ParameterError("points", points, "an integer in [3, 101] (one-at-a-time sweep)", "guidelines")
        if isinstance(span, bool) or not (isinstance(span, (int, float)) and 0 < span <= 0.9):
            raise ParameterError("span", span, "a relative span in (0, 0.9]: x0 (1 -+ span)", "guidelines")
        candidates = _continuous(c.Params, p0)
        notes = []
        off = [n for n in p0.inactive() if n in c.Params.model_fields]
        if off:
            notes.append(f"not studied (no effect with the '{p0.profile}' profile, elasticity 0): " + _names(off))
        if params is None:
            chosen = [n for n in candidates if getattr(p0, n) != 0]
            zero = [n for n in candidates if getattr(p0, n) == 0]
            if zero:
                notes.append("not studied (zero at the design point, no elasticity): " + ", ".join(zero))
        else:
            chosen = list(params)
            if not chosen:
                raise ParameterError("params", "", "at least one parameter name", "guidelines")
            for n in chosen:
                if n not in c.Params.model_fields:
                    raise ParameterError("params", n, f"parameters of {c.name}: " + ", ".join(candidates), "guidelines")
                if n not in candidates:
                    raise ParameterError("params", n, "a continuous parameter (not a count or a choice, and "
                                         f"active for this design): one of {', '.join(candidates)}", "guidelines")
                if getattr(p0, n) == 0:
                    raise ParameterError("params", n, f"a parameter with a non-zero design value ({n} = 0 has no "
                                         "elasticity; --set it to a non-zero value)", "guidelines")
            if len(set(chosen)) != len(chosen):
                raise ParameterError("params", ",".join(chosen), "each parameter once", "guidelines")
        if inputs is not None:
            inputs = tuple(inputs)
            allowed = ("mu", "drum_wall", "idle_rpm")
            for n in inputs:
                if n not in allowed:
                    raise ParameterError("inputs", n, "operating inputs among " + ", ".join(allowed), "guidelines")
            if len(set(inputs)) != len(inputs):
                raise ParameterError("inputs", ",".join(inputs), "each operating input once", "guidelines")
        if not isinstance(remeshed_check, bool):
            raise ParameterError("remeshed_check", remeshed_check, "True or False", "guidelines")
        op = op or OperatingPoint()
        settings = Settings(concept=c.name, fixed=tuple(sorted(base.items())), op=op,
                            mesh=mesh or MeshSettings.preset(op.fidelity), engine=engine, idle_rpm=idle_rpm, a=a, b=b,
                            min_safety_factor=min_safety_factor)
        return cls(concept=c.name, params=tuple(chosen), settings=settings, step=float(step), points=points,
                   span=float(span), notes=tuple(notes), inputs=inputs, remeshed_check=remeshed_check)

    @classmethod
    def from_design(cls, design, params=None, *, engine=None, requirements=None, **kw) -> "GuidelineSettings":
        """The settings of a concept's :class:`~clutchfem.Design` (its parameters, operating
        point and mesh) with the engine curve and requirement factors; ``kw`` as :meth:`create`."""
        if design.params is None:
            raise ParameterError("design", design.name, "a concept's design (a user mesh has no parameters to vary)",
                                 "guidelines")
        P = type(design.params)
        base = {k: v for k, v in design.params.model_dump().items() if v != P.model_fields[k].default}
        mesh = MeshSettings(**design.cm.mesh_settings) if design.cm.mesh_settings else None
        return cls.create(design.name, base, params, mesh=mesh, op=design.op, engine=engine,
                          a=getattr(requirements, "a", 1.3), b=getattr(requirements, "b", 1.0), **kw)


def _continuous(P, p0) -> list[str]:
    """Continuous (float) parameters of ParamSet ``P`` that act on design ``p0`` (not those it
    calls inactive: the other profiles' controls)."""
    off = set(p0.inactive()) if hasattr(p0, "inactive") else set()
    out = []
    for n, f in P.model_fields.items():
        ann = f.annotation
        if get_origin(ann) is Literal or ann is not float or n in off:
            continue
        out.append(n)
    return out


def _names(names: list[str]) -> str:
    """Names joined, a run table_c0, table_c1, ... shortened to table_c0..table_c16."""
    tab = [n for n in names if n.startswith("table_c")]
    rest = [n for n in names if not n.startswith("table_c")]
    if len(tab) > 2:
        rest.append(f"{tab[0]}..{tab[-1]} (the table profile's {len(tab)} control values)")
    else:
        rest += tab
    return ", ".join(rest)


# ---------------------------------------------------------------------------------------
# points
# ---------------------------------------------------------------------------------------
def fd_values(x0: float, h: float) -> list[float]:
    """The finite-difference abscissae: x0 (1 -+ r) for r in h/2, h, 2h (ascending)."""
    out = [x0]
    for f in STEP_FACTORS:
        out += [round12(x0 * (1 - f * h)), round12(x0 * (1 + f * h))]
    return sorted(out)


def oat_values(x0: float, lo, hi, span: float, n: int) -> list[float]:
    """``n`` equally spaced values over x0 (1 -+ span) clipped to [lo, hi], plus x0."""
    a, b = x0 * (1 - span), x0 * (1 + span)
    if x0 < 0:
        a, b = b, a
    a = max(a, lo) if lo is not None else a
    b = min(b, hi) if hi is not None else b
    return sorted({round12(v) for v in np.linspace(a, b, n)} | {x0})


def plan(gs: GuidelineSettings) -> tuple[list[dict], dict]:
    """All remeshed points of a guideline study and, per parameter, its FD (only with the
    remeshed check) and OAT values."""
    P = get_concept(gs.concept).Params
    p0 = P(**gs.base)
    points, per = [{}], {}
    for n in gs.params:
        x0 = float(getattr(p0, n))
        lo, hi = param_bounds(P, n)
        fd = fd_values(x0, gs.step) if gs.remeshed_check else [x0]
        inside = [v for v in fd if (lo is None or v >= lo) and (hi is None or v <= hi)]
        oat = oat_values(x0, lo, hi, gs.span, gs.points)
        per[n] = {"x0": x0, "fd": fd, "fd_outside": [v for v in fd if v not in inside], "oat": oat,
                  "unit": P.unit(n)}
        points += [{n: v} for v in sorted(set(inside) | set(oat)) if v != x0]
    return points, per


# ---------------------------------------------------------------------------------------
# derivatives
# ---------------------------------------------------------------------------------------
def method_text(s: Sensitivities, name: str) -> str:
    """The method of an elasticity, in words (module docstring), from the sensitivities'
    short method and notes."""
    m = s.methods.get(name, "")
    if m.startswith("not evaluated"):
        return m
    how = m.split(",")[0]
    if s.kinds.get(name) == "operating input":
        return f"{how} difference, same mesh (operating input)"
    if m.endswith("meshed from scratch"):
        why = next((n.split(": ", 1)[1] for n in s.notes if n.startswith(f"{name}: ")), "")
        return f"{how} difference, meshed from scratch (morph refused: {why})"
    side = " (one side refused by the concept's rules)" if how.startswith("one-sided") else ""
    return f"{how} difference on morphed meshes{side}"


def morphed_elasticity(s: Sensitivities, check: Sensitivities, name: str, key: str) -> dict:
    """E = (x0 / A) dA/dx from the sensitivities ``s`` at answer ``key``, its check at the
    wider step (``check``), their spread and the verdict (module docstring)."""
    e, e2 = s.elasticity(name, key), check.elasticity(name, key)
    e = math.nan if e is None else float(e)
    e2 = math.nan if e2 is None else float(e2)
    spread = abs(e - e2) if math.isfinite(e) and math.isfinite(e2) else math.nan
    if not math.isfinite(e):
        verdict = "no answer"
    elif not math.isfinite(e2):
        verdict = "unchecked"
    else:
        verdict = "stable" if spread <= STABLE_ABS + STABLE_REL * abs(e) else "unstable"
    out = {"E": e, "method": method_text(s, name), "step": s.steps.get(name), "E_check": e2,
           "check_step": check.steps.get(name), "check_method": method_text(check, name), "spread": spread,
           "verdict": verdict, "stable": verdict == "stable"}
    kink = s.kinks.get(name, {}).get(key)
    a, x = s.base.get(key), s.values.get(name)
    if kink and a and x is not None:  # a contact node enters or leaves inside the step: both sides
        out["kink"] = f"a contact node enters or leaves inside the step (at the {kink['speed']} speed)"
        out["E_left"], out["E_right"] = kink["left"] * x / a, kink["right"] * x / a
    return out


def central(a_minus: float, a_plus: float, r: float) -> float:
    """E_r: the central difference of ln A in ln x at relative step r (module docstring)."""
    if not (_pos(a_minus) and _pos(a_plus)):
        return math.nan
    return (math.log(a_plus) - math.log(a_minus)) / (math.log1p(r) - math.log1p(-r))


def one_sided(a0: float, a: float, r: float) -> float:
    """The one-sided difference of ln A in ln x from x0 to x0 (1 + r) (r < 0: downwards)."""
    if not (_pos(a0) and _pos(a)):
        return math.nan
    return (math.log(a) - math.log(a0)) / math.log1p(r)


def _pos(a) -> bool:
    return a is not None and math.isfinite(a) and a > 0


def elasticity(x0: float, h: float, value_at) -> dict:
    """E_h, E_h/2, E_2h, E_fit, the noise estimate and the verdict for one answer;
    ``value_at(x)`` the answer at parameter value x (NaN/None if not answered).

    Central differences where both sides are answered; where a side is not (x0 at the edge
    of the concept's feasible set: a refused design on one side), one-sided differences on
    the other, marked.  The fit is a quadratic in ln x through every answered point (a line
    if only four are).  Verdict: 'stable' (E_h/2, E_2h and E_fit within 0.05 + 10 % of E_h),
    'unstable', 'unchecked' (a comparison is missing: a step was not answered) or
    'no answer'."""
    def v(x):
        y = value_at(x)
        return math.nan if y is None else float(y)

    a0 = v(x0)
    ys = {x: v(x) for x in fd_values(x0, h)}

    def at(f):
        return ys.get(round12(x0 * (1 + f * h)), math.nan)

    est = {f: central(at(-f), at(f), f * h) for f in STEP_FACTORS}
    method = "central"
    if not math.isfinite(est[1.0]):
        for side in (1, -1):
            one = {f: one_sided(a0, at(side * f), side * f * h) for f in STEP_FACTORS}
            if math.isfinite(one[1.0]):
                est, method = one, f"one-sided ({'+' if side > 0 else '-'})"
                break
    pts = [(math.log(x / x0), math.log(y)) for x, y in ys.items() if _pos(y)]
    e_fit = noise = math.nan
    if len(pts) >= 4:
        lx, ly = (np.array(c) for c in zip(*pts))
        deg = 2 if len(pts) >= 5 else 1
        c, res, *_ = np.polyfit(lx, ly, deg, full=True)
        e_fit = float(c[-2])
        dof = len(pts) - (deg + 1)
        noise = float(math.sqrt(res[0] / dof)) if len(res) and dof > 0 else math.nan
    e_h = est[1.0]
    others = [est[0.5], est[2.0], e_fit]
    have = [e for e in others if math.isfinite(e)]
    spread = max((abs(e - e_h) for e in have), default=math.nan) if math.isfinite(e_h) else math.nan
    if not math.isfinite(e_h):
        verdict = "no answer"
    elif len(have) < len(others):
        verdict = "unchecked" if not (math.isfinite(spread) and spread > STABLE_ABS + STABLE_REL * abs(e_h)) \
            else "unstable"
    else:
        verdict = "stable" if spread <= STABLE_ABS + STABLE_REL * abs(e_h) else "unstable"
    return {"value_at_x0": a0, "E": e_h, "method": method, "E_half_step": est[0.5], "E_double_step": est[2.0],
            "E_fit": e_fit, "spread": spread, "noise_rel": noise,
            "noise_error": (noise / (math.sqrt(2) * h)) if math.isfinite(noise) else math.nan,
            "verdict": verdict, "stable": verdict == "stable"}


# ---------------------------------------------------------------------------------------
# the study
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class GuidelineResult:
    """Elasticities (one dict per parameter and answer), the ranking, the one-at-a-time
    table and the files written (:func:`~clutchfem.run_guidelines`).

    Attributes
    ----------
    table : list of dict
        Per parameter (or operating input) and answer: ``parameter``, ``answer``, ``unit``,
        ``x0``, the elasticity ``E`` = (x / A) dA/dx, its ``method`` and check ``verdict``.
    ranking : list of str
        The parameters, strongest first (the operating inputs in ``inputs``).
    oat : pandas.DataFrame
        The one-at-a-time rows.
    files : tuple of Path
    out : Path or None
        The study's folder.

    Examples
    --------
    >>> from clutchfem.guidelines import GuidelineResult
    >>> row = {"parameter": "flexure_thickness", "answer": "engagement_rpm", "unit": "m", "x0": 0.0022, "E": 0.9,
    ...        "verdict": "stable", "method": "central difference on morphed meshes"}
    >>> g = GuidelineResult("concept1", {}, 0.02, [row], ["flexure_thickness"], oat=None)
    >>> [f.name for f in g.with_files(["oat.png"]).files], g.to_json()["elasticities"][0]["E"]
    (['oat.png'], 0.9)
    """

    concept: str
    base: dict
    step: float
    table: list[dict]
    ranking: list[str]
    oat: Any
    files: tuple[Path, ...] = ()
    notes: list[str] = field(default_factory=list)
    run: Any = None
    base_errors: dict = field(default_factory=dict)
    #: the method of each parameter's / operating input's elasticity, in words
    methods: dict = field(default_factory=dict)
    #: the operating inputs in the table (listed, not ranked)
    inputs: list[str] = field(default_factory=list)
    #: True: the rows also carry the remeshed seven-point check (E_remeshed, remeshed_verdict)
    remeshed: bool = False
    #: the study's folder (store, tables, ``guidelines.json``)
    out: Path | None = None

    def with_files(self, files) -> "GuidelineResult":
        """This result with ``files`` (the charts a face drew into its folder) added to its
        record, ``guidelines.json`` written again with them."""
        record = self.out / "guidelines.json" if self.out is not None else None
        done = tuple(f for f in self.files if f != record)
        new = replace(self, files=(*done, *map(Path, files), *(() if record is None else (record,))))
        if record is not None:
            write(record, new.to_json(), indent=1)
        return new

    def to_json(self) -> dict:
        return clean({"concept": self.concept, "design_point": self.base,
                      "elasticity": "E = (x / A) dA/dx, dA/dx by central differences on meshes morphed from the "
                                    "design (operating inputs: on the design's own mesh); the method per row",
                      "stability_rule": f"E at {CHECK_FACTOR:g}x the step within {STABLE_ABS} + {STABLE_REL:.0%} of "
                                        "|E| (verdicts: stable, unstable, unchecked, no answer)",
                      "methods": self.methods,
                      "remeshed_check": ({"step": self.step, "rule": f"E_h/2, E_2h and E_fit within {STABLE_ABS} + "
                                                                    f"{STABLE_REL:.0%} of |E_h| on remeshed designs"}
                                         if self.remeshed else None),
                      "ranking": self.ranking, "operating_inputs": self.inputs, "elasticities": self.table, "notes": self.notes,
                      "design_point_errors": self.base_errors,
                      "run": self.run.to_json() if self.run is not None else None,
                      "files": [str(f) for f in self.files]})
