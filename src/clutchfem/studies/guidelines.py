"""Design guidelines: which parameter moves which property, and how much (thesis 4.4, with
numbers).

For each studied parameter x of a concept at a design point x0, and each answer A in
:data:`ANSWERS` (engagement rpm, slip rpm, torque at the rpm of maximum engine torque, peak
von Mises at the engine's maximum speed, shoe mass, contact arc), the **local elasticity**

    E = d ln A / d ln x   (1 % more x gives about E % more A)

and a **one-at-a-time sweep** of x over x0 (1 -+ span) within its declared range, the other
parameters at the design point.  Everything runs on the study engine
(:func:`clutchfem.study.runner.run_points`: Dask, store, resume).

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

from ..core import InputError, ParameterError
from .point import Settings

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
        from ..geometry import MeshSettings, get_concept
        from ..loadcase import OperatingPoint

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
        settings = Settings(concept=c.name, fixed=tuple(sorted(base.items())), op=op or OperatingPoint(),
                            mesh=mesh or MeshSettings(), engine=engine, idle_rpm=idle_rpm, a=a, b=b,
                            min_safety_factor=min_safety_factor)
        return cls(concept=c.name, params=tuple(chosen), settings=settings, step=float(step), points=points,
                   span=float(span), notes=tuple(notes))

    @classmethod
    def from_cli(cls, concept, set_, params, *, step, points, span, mesh_size, mu, material, engine):
        from ..clutch import EngineCurve
        from ..geometry import MeshSettings, get_concept
        from ..loadcase import OperatingPoint

        c = get_concept(concept)
        base = c.Params.parse_assignments(set_)
        names = None if params is None else [s.strip() for s in params.split(",") if s.strip()]
        mesh = MeshSettings()
        if mesh_size is not None:
            try:
                mesh = MeshSettings(size=MeshSettings._parse_value("size", mesh_size))
            except ParameterError as exc:
                raise ParameterError(exc.name, exc.value, exc.allowed, "option --mesh-size") from None
        given = {k: v for k, v in (("mu", mu), ("material", material)) if v is not None}
        try:
            values = OperatingPoint.parse_assignments([f"{k}={v}" for k, v in given.items()])
            op = OperatingPoint(**values)
        except ParameterError as exc:
            raise ParameterError(exc.name, exc.value, exc.allowed, f"option --{exc.name}") from None
        eng = EngineCurve.from_csv(engine) if engine is not None else None
        return cls.create(c.name, base, names, step=step, points=points, span=span, mesh=mesh, op=op, engine=eng)


def _continuous(P, p0) -> list[str]:
    """Continuous (float) parameters of ParamSet ``P`` that act on design ``p0``."""
    out = []
    for n, f in P.model_fields.items():
        ann = f.annotation
        if get_origin(ann) is Literal or ann is not float:
            continue
        if n == "clearance_tip" and getattr(p0, "profile", None) != "linear":
            continue
        if n in ("eccentricity", "eccentric_angle") and getattr(p0, "profile", None) != "eccentric":
            continue
        out.append(n)
    return out


def _bounds(P, name):
    from .spec import _bounds as b

    return b(P, name)


# ---------------------------------------------------------------------------------------
# points
# ---------------------------------------------------------------------------------------
def _clean(x: float) -> float:
    return float(f"{x:.12g}")


def fd_values(x0: float, h: float) -> list[float]:
    """The finite-difference abscissae: x0 (1 -+ r) for r in h/2, h, 2h (ascending)."""
    out = [x0]
    for f in STEP_FACTORS:
        out += [_clean(x0 * (1 - f * h)), _clean(x0 * (1 + f * h))]
    return sorted(out)


def oat_values(x0: float, lo, hi, span: float, n: int) -> list[float]:
    """``n`` equally spaced values over x0 (1 -+ span) clipped to [lo, hi], plus x0."""
    a, b = x0 * (1 - span), x0 * (1 + span)
    if x0 < 0:
        a, b = b, a
    a = max(a, lo) if lo is not None else a
    b = min(b, hi) if hi is not None else b
    return sorted({_clean(v) for v in np.linspace(a, b, n)} | {x0})


def plan(gs: GuidelineSettings) -> tuple[list[dict], dict]:
    """All points of a guideline study and, per parameter, its FD and OAT values."""
    from ..geometry import get_concept

    P = get_concept(gs.concept).Params
    p0 = P(**gs.base)
    points, per = [{}], {}
    for n in gs.params:
        x0 = float(getattr(p0, n))
        lo, hi = _bounds(P, n)
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
        return ys.get(_clean(x0 * (1 + f * h)), math.nan)

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
        from ..core import clean

        return clean({"concept": self.concept, "design_point": self.base, "step": self.step,
                      "stability_rule": f"E_h/2, E_2h and E_fit within {STABLE_ABS} + {STABLE_REL:.0%} of |E_h| "
                                        "(verdicts: stable, unstable, unchecked, no answer)",
                      "ranking": self.ranking, "elasticities": self.table, "notes": self.notes,
                      "design_point_errors": self.base_errors,
                      "run": self.run.as_dict() if self.run is not None else None,
                      "files": [str(f) for f in self.files]})


def run_guidelines(gs: GuidelineSettings, out: str | Path, *, workers: int | None = None,
                   scheduler: str | None = None, progress: bool = True, charts: bool = True) -> GuidelineResult:
    """Run the guideline study ``gs`` on the study engine into ``out`` (store, tables, charts)."""
    import pandas as pd

    from ..core import write
    from .hashing import design_hash
    from .point import COLUMNS
    from .runner import run_points
    from .store import STORE_NAME, ResultStore

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    points, per = plan(gs)
    run = run_points(points, gs.settings, out / STORE_NAME, workers=workers, scheduler=scheduler,
                     progress=progress, source=f"guidelines {gs.concept}", desc="guidelines",
                     error_points=[0] if gs.errors else [])
    with ResultStore(out / STORE_NAME, COLUMNS) as st:
        df = st.frame(run.model_version, run.keys)
    by_hash = {r["design_hash"]: r for r in df.to_dict("records")}
    base_row = by_hash.get(design_hash({}, gs.settings))
    notes = list(gs.notes)
    if base_row is None or base_row["status"] != "ok":
        msg = base_row["message"] if base_row is not None else "not computed"
        raise InputError(f"guidelines {gs.concept}: the design point itself has no answer ({msg})")
    base_errors = {}
    if base_row.get("errors_estimated") == 1:
        from .runner import ERROR_COLUMNS

        for ans, tot, disc, unit in ERROR_COLUMNS:
            base_errors[ans] = {"value": base_row[ans], "band": base_row[tot], "discretisation": base_row[disc],
                                "unit": unit}
            if base_row[tot] is not None and base_row[ans]:
                notes.append(f"design point: {ans} = {base_row[ans]:.4g} +- {base_row[tot]:.3g} {unit} (mesh "
                             f"+- {base_row[disc]:.3g} {unit}, the rest model form): an elasticity says how an answer "
                             "moves, this band how far its value may be off")

    def row_at(name, x):
        if x == per[name]["x0"]:
            return base_row
        return by_hash.get(design_hash({name: x}, gs.settings))

    table = []
    for n in gs.params:
        x0, unit = per[n]["x0"], per[n]["unit"]
        if per[n]["fd_outside"]:
            notes.append(f"{n}: finite-difference values outside its declared range ({per[n]['fd_outside']}): "
                         "those steps are not evaluated")
        refused = [x for x in per[n]["fd"] if (r := row_at(n, x)) is None or r["status"] != "ok"]
        if refused:
            notes.append(f"{n}: no answer at {', '.join(f'{x:.6g}' for x in refused)} {unit} (refused/failed): "
                         "the derivative uses the steps that were answered")
        for col, label in ANSWERS:
            def value_at(x, col=col, n=n):
                r = row_at(n, x)
                return None if r is None or r["status"] != "ok" else r[col]

            e = elasticity(x0, gs.step, value_at)
            a0 = e["value_at_x0"]
            per_unit, du = _per_unit(unit)
            slope = e["E"] * a0 / x0 * du if math.isfinite(e["E"]) and a0 else math.nan
            table.append({"parameter": n, "unit": unit, "x0": x0, "answer": col, "label": label, **e,
                          f"change_per_{per_unit.replace(' ', '_')}": slope, "per": per_unit})
    # ranking: largest |E| over the answers whose derivative is not unstable
    score = {}
    for n in gs.params:
        es = [abs(t["E"]) for t in table if t["parameter"] == n and t["verdict"] in ("stable", "unchecked")
              and math.isfinite(t["E"])]
        score[n] = max(es) if es else 0.0
    ranking = sorted(gs.params, key=lambda n: -score[n])
    # one-at-a-time table
    oat_rows = []
    for n in gs.params:
        for x in per[n]["oat"]:
            r = row_at(n, x)
            rec = {"parameter": n, "unit": per[n]["unit"], "value": x, "relative": x / per[n]["x0"],
                   "status": None if r is None else r["status"], "message": None if r is None else r["message"]}
            for col, _ in ANSWERS:
                rec[col] = None if r is None or r["status"] != "ok" else r[col]
            oat_rows.append(rec)
    oat = pd.DataFrame(oat_rows)
    files = []
    tpath = out / "guidelines.csv"
    pd.DataFrame(table).to_csv(tpath, index=False)
    opath = out / "one_at_a_time.csv"
    oat.to_csv(opath, index=False)
    files += [tpath, opath]
    res = GuidelineResult(concept=gs.concept, base=gs.base, step=gs.step, table=table, ranking=ranking, oat=oat,
                          files=files, notes=notes, run=run, base_errors=base_errors)
    if charts:
        files.append(oat_chart(res, out / "one_at_a_time.png"))
        files.append(elasticity_chart(res, out / "elasticities.png"))
    jpath = out / "guidelines.json"
    write(jpath, res.as_json(), indent=1)
    files.append(jpath)
    return res


def _per_unit(unit: str) -> tuple[str, float]:
    """(the designers' step of a unit, its size in the unit): 0.1 mm, 1 deg, 0.1."""
    return {"m": ("0.1 mm", 1e-4), "deg": ("1 deg", 1.0)}.get(unit, ("0.1", 0.1))


def summary_table(res: GuidelineResult):
    """A rich table: parameters ranked, elasticity of each answer (~: unstable derivative)."""
    from rich.markup import escape
    from rich.table import Table

    from .spec import display_value

    t = Table(title=escape(f"{res.concept}: elasticities d ln(answer) / d ln(parameter) at the design point"),
              caption=escape(f"engage: engagement rpm; slip: slip rpm; torque: at the rpm of max engine torque; "
                             f"stress: peak von Mises at max rpm; shoe m: shoe mass; arc: contact arc.  "
                             f"Step h = {res.step:.0%}; ~: unstable (E at h/2, 2h or the fit differs from E at h "
                             f"by more than {STABLE_ABS} + {STABLE_REL:.0%}); ?: unchecked (a step has no answer); "
                             "1: one-sided (one side refused); -: no answer"))
    t.add_column("rank")
    t.add_column("parameter", no_wrap=True)
    t.add_column("value", justify="right")
    for col, _ in ANSWERS:
        t.add_column(SHORT[col], justify="right")
    for k, n in enumerate(res.ranking, start=1):
        cells = []
        unit = x0 = None
        for col, _ in ANSWERS:
            e = next(r for r in res.table if r["parameter"] == n and r["answer"] == col)
            unit, x0 = e["unit"], e["x0"]
            v = e["E"]
            mark = {"stable": "", "unchecked": "?", "unstable": "~"}.get(e["verdict"], "")
            side = "" if e["method"] == "central" else "1"
            cells.append("-" if not math.isfinite(v) else f"{mark}{v:+.2f}{side}")
        shown = {"m": "mm", "-": ""}.get(unit, unit)
        t.add_row(str(k), escape(n), escape(f"{display_value(x0, unit):.4g} {shown}".strip()), *cells)
    return t


def oat_chart(res: GuidelineResult, path: str | Path) -> Path:
    """Small multiples, one panel per answer: the answer against x / x0 for every parameter."""
    from matplotlib import colormaps

    from ..core import figure

    path = Path(path)
    oat = res.oat
    cmap = colormaps["tab20"]
    fig, axes = figure(2, 3, figsize=(14.0, 7.5), squeeze=False)
    for k, (col, label) in enumerate(ANSWERS):
        ax = axes.flat[k]
        for j, n in enumerate(res.ranking):
            d = oat[oat["parameter"] == n]
            okd = d[d["status"] == "ok"]
            y = okd[col].astype(float)
            colour = cmap((2 * j) % 20 + (j // 10) % 2)
            ax.plot(okd["relative"], y, "-o", ms=3, lw=1.1, color=colour, label=n if k == 0 else None)
            bad = d[d["status"] != "ok"]
            if len(bad):
                for xr in bad["relative"]:
                    ax.axvline(xr, color=colour, lw=0.5, ls=":", alpha=0.6)
        ax.axvline(1.0, color="0.3", lw=0.8)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("parameter / design value [-]", fontsize=8)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=7)
    axes.flat[0].legend(fontsize=7, loc="best")
    fig.suptitle(f"{res.concept}: one parameter at a time around the design point (dotted: no answer there)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path


def elasticity_chart(res: GuidelineResult, path: str | Path) -> Path:
    """Small multiples, one per answer: the elasticity of each parameter as a bar with the
    spread of the step check as its error bar (hatched: unstable)."""
    from ..core import figure

    path = Path(path)
    fig, axes = figure(2, 3, figsize=(14.0, 7.5), squeeze=False)
    names = res.ranking
    for k, (col, label) in enumerate(ANSWERS):
        ax = axes.flat[k]
        rows = [next(r for r in res.table if r["parameter"] == n and r["answer"] == col) for n in names]
        e = np.array([r["E"] for r in rows], dtype=float)
        sp = np.array([r["spread"] for r in rows], dtype=float)
        y = np.arange(len(names))
        colours = [{"stable": "C0", "unchecked": "C1"}.get(r["verdict"], "0.7") for r in rows]
        ax.barh(y, np.nan_to_num(e), xerr=np.nan_to_num(sp), color=colours, ecolor="0.3", capsize=2,
                hatch=None)
        ax.set_yticks(y, names, fontsize=7)
        ax.invert_yaxis()
        ax.axvline(0, color="0.3", lw=0.8)
        ax.set_title(f"{label}: d ln A / d ln x", fontsize=9)
        ax.grid(alpha=0.3, axis="x")
        ax.tick_params(labelsize=7)
    fig.suptitle(f"{res.concept}: elasticities at the design point (blue: stable; orange: unchecked, a step "
                 f"refused; grey: unstable against mesh noise; error bar: spread of E over h/2, 2h and the fit)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path
