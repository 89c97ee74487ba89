"""Design guidelines: which parameter moves which property, and how much (thesis 4.4, with
numbers).

For each studied parameter x of a concept at a design point x0, and each answer A in
:data:`ANSWERS` (engagement rpm, slip rpm, torque at the rpm of maximum engine torque, peak
von Mises at the engine's maximum speed, shoe mass, contact arc), the **local elasticity**

    E = d ln A / d ln x   (1 % more x gives about E % more A)

and a **one-at-a-time sweep** of x over x0 (1 -+ span) within its declared range, the other
parameters at the design point.  Everything runs on the study engine
(:func:`clutchfem.studies.runner.run_points`: Dask, store, resume): :mod:`.guideline_study`
runs a guideline study and writes its tables, :mod:`.guideline_charts` draws them.  This
module holds the method: what is studied (:class:`GuidelineSettings`), the designs it takes
(:func:`plan`), the elasticity with its stability check (:func:`elasticity`) and the result
(:class:`GuidelineResult`).

Finite differences against mesh noise.  Every design is meshed anew and the mesh topology
changes with the parameters, so A(x) carries a small, non-smooth noise eps (relative) on
top of its smooth trend.  A central difference with relative step r,

    E_r = [ln A(x0 (1 + r)) - ln A(x0 (1 - r))] / [ln(1 + r) - ln(1 - r)],

has a truncation error ~ r^2 (curvature) and a noise error ~ eps / (sqrt 2 r): too small a
step amplifies the mesh noise, too large a step sees the curvature.  Each parameter is
therefore evaluated at seven designs, x0 and x0 (1 -+ r) for r = h/2, h and 2h (h = 2 %
by default), and a quadratic in ln x is fitted through all seven (least squares: its slope
at x0 is E_fit, its residual is the noise estimate eps).  The reported elasticity is E_h,
and it is called **stable** when E_h/2, E_2h and E_fit all agree with it within
0.05 + 10 % of |E_h| (0.05: below it a parameter has no influence worth a guideline; 10 %:
the precision a guideline needs).  An unstable derivative is reported as such, with its
spread, never silently: typically the contact arc, which moves in steps of one contact
node, or the peak stress, which sits on one node of a fillet.  Where the concept refuses
the design on one side of x0 (x0 on the edge of its feasible set), the differences are
one-sided on the other side, marked; where a step has no answer the verdict is
'unchecked'.  Parameters are ranked by their largest |E| that is not unstable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, get_origin

import numpy as np

from ..core import ParameterError, clean
from ..geometry import MeshSettings, get_concept
from ..loadcase import OperatingPoint
from .point import Settings
from .values import param_bounds, round12

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
#: the step multiples evaluated (relative to h)
STEP_FACTORS = (0.5, 1.0, 2.0)


@dataclass(frozen=True)
class GuidelineSettings:
    """What to study: concept, design point (``--set`` values), parameters, relative step h,
    one-at-a-time points and span, and the shared analysis settings."""

    concept: str
    params: tuple[str, ...]
    settings: Settings
    step: float = 0.02
    points: int = 7
    span: float = 0.5
    notes: tuple[str, ...] = ()
    errors: bool = True

    @property
    def base(self) -> dict:
        return dict(self.settings.fixed)

    @classmethod
    def create(cls, concept: str, base: dict | None = None, params=None, *, step: float = 0.02, points: int = 7,
               span: float = 0.5, mesh=None, op=None, engine=None, idle_rpm=None, a: float = 1.3,
               b: float = 1.0, min_safety_factor: float = 1.0) -> "GuidelineSettings":
        """Validated settings (API); ``base`` concept parameters in their units, ``params``
        names (default: every continuous parameter with a non-zero design value)."""
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
        op = op or OperatingPoint()
        settings = Settings(concept=c.name, fixed=tuple(sorted(base.items())), op=op,
                            mesh=mesh or MeshSettings.preset(op.fidelity), engine=engine, idle_rpm=idle_rpm, a=a, b=b,
                            min_safety_factor=min_safety_factor)
        return cls(concept=c.name, params=tuple(chosen), settings=settings, step=float(step), points=points,
                   span=float(span), notes=tuple(notes))

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
    """All points of a guideline study and, per parameter, its FD and OAT values."""
    P = get_concept(gs.concept).Params
    p0 = P(**gs.base)
    points, per = [{}], {}
    for n in gs.params:
        x0 = float(getattr(p0, n))
        lo, hi = param_bounds(P, n)
        fd = fd_values(x0, gs.step)
        inside = [v for v in fd if (lo is None or v >= lo) and (hi is None or v <= hi)]
        oat = oat_values(x0, lo, hi, gs.span, gs.points)
        per[n] = {"x0": x0, "fd": fd, "fd_outside": [v for v in fd if v not in inside], "oat": oat,
                  "unit": P.unit(n)}
        points += [{n: v} for v in sorted(set(inside) | set(oat)) if v != x0]
    return points, per


# ---------------------------------------------------------------------------------------
# derivatives
# ---------------------------------------------------------------------------------------
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
    table and the files written."""

    concept: str
    base: dict
    step: float
    table: list[dict]
    ranking: list[str]
    oat: Any
    files: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    run: Any = None
    base_errors: dict = field(default_factory=dict)

    def as_json(self) -> dict:
        return clean({"concept": self.concept, "design_point": self.base, "step": self.step,
                      "stability_rule": f"E_h/2, E_2h and E_fit within {STABLE_ABS} + {STABLE_REL:.0%} of |E_h| "
                                        "(verdicts: stable, unstable, unchecked, no answer)",
                      "ranking": self.ranking, "elasticities": self.table, "notes": self.notes,
                      "design_point_errors": self.base_errors,
                      "run": self.run.as_dict() if self.run is not None else None,
                      "files": [str(f) for f in self.files]})
