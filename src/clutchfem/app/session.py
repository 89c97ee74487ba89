"""One browser tab's design session: the controls of a concept, a value typed or refused,
the live analysis of the current design, its error bands, the field at one speed, a pinned
design to compare with.  No user interface here: :mod:`.page` draws it, the tests drive it.

A control shows a parameter in the unit designers read (mm, deg, the dimensionless as they
are) with its declared range; a value is checked by the concept's own parameter set (the
same refusal, naming the parameter, its value and what is allowed, as ``--set``).  A refused
value leaves the last valid design on screen.

The analysis is run in two passes so that the screen follows a slider: the answers without
the error estimate first (``analyze(errors=False)``: ~0.15 s in process for concept 4 on the
default mesh, ~0.1 s more when the mesh is new), marked "(first pass)" on each value, then
the design analysed exactly as ``clutchfem analyze`` does (:meth:`DesignSession.complete`: the
corrected answers and their bands, seconds) that replace them when they arrive: the page ends
on the answers of ``analyze`` and ``report`` for the same design (one answer set).

With the model ``live`` the first pass answers from the reduced model of a cached region that
holds the design (milliseconds, no mesh, its bands in the answers), and the second pass is the
full FE of the same design on the best path (:meth:`DesignSession.verify`): its answers
replace the live ones where they differ by more than the live band, and the page says so.
Where no reduced model holds the design the app does not build one (minutes: ``clutchfem
reduce`` does) and the FE answers, saying why.
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Any, Literal, get_args, get_origin

import numpy as np

from ..analysis import Analysis, Requirements, analyze
from ..clutch import EngineCurve
from ..core import ClutchfemError, ParameterError, format_quantity, param_bounds, resolution
from ..geometry import MeshSettings, concepts, get_concept
from ..loadcase import Design, OperatingPoint, design_label

__all__ = ["Control", "DesignSession", "Outcome"]

#: display unit and factor of a canonical unit (value shown = value x factor)
_SHOW = {"m": ("mm", 1e3), "deg": ("deg", 1.0), "-": ("", 1.0), "": ("", 1.0)}
#: operating-point fields the panel offers
OP_FIELDS = ("fidelity", "mu", "rotation", "material", "drum_wall")


@dataclass(frozen=True)
class Control:
    """One parameter as the panel shows it: a slider with a number field (``kind`` "number")
    or a choice (``kind`` "choice"), in its display unit, with the declared range."""

    name: str
    label: str
    kind: Literal["number", "choice"]
    unit: str
    value: Any
    lo: float | None = None
    hi: float | None = None
    step: float | None = None
    choices: tuple = ()
    integer: bool = False
    group: str = "geometry"
    #: the range the concept's rules allow with the other parameters as they are (display unit;
    #: None: not computed or the declared range itself)
    feasible: tuple[float, float] | None = None


@dataclass
class Outcome:
    """What one analysis of the current design gives the page (all JSON-ready but the
    analysis itself): the answers table, the badges, the warnings, the charts' series."""

    analysis: Analysis
    label: str
    design: Design
    rows: list[tuple[str, str, str]] = field(default_factory=list)  # (answer, value, verdict)
    seconds: float = 0.0

    @property
    def live(self) -> bool:
        """Answered by the reduced model (the FE check follows)."""
        return self.analysis.answered_by == "reduced model"

    @cached_property
    def fe_design(self) -> Design:
        """The design the FE solves (a live design's best-path twin: the field, the check)."""
        d = self.design
        return d.with_fidelity("best") if d.op.fidelity == "live" else d


def _is_choice(P, name: str) -> bool:
    return get_origin(P.model_fields[name].annotation) is Literal


class DesignSession:
    """The state of one tab (module docstring).  Thread-safe for one writer: the page calls
    :meth:`set_value` from its event loop and :meth:`run` in a worker thread."""

    def __init__(self, concept: str = "concept4", out_dir: str | Path | None = None):
        self.lock = threading.Lock()
        self.out_dir = Path(out_dir) if out_dir is not None else None
        self.engine = EngineCurve.default()
        self.requirements = Requirements()
        self.mesh: MeshSettings | None = None  # None: the fidelity's mesh (MeshSettings.preset)
        self.pinned: Outcome | None = None
        self.last: Outcome | None = None
        self.generation = 0
        self.select(concept)

    # -- the design ------------------------------------------------------------------------
    def select(self, concept: str) -> None:
        """Start from a concept's defaults (the operating point is kept)."""
        c = get_concept(concept)
        self.concept = c
        self.params = c.params()
        self.part = None  # an uploaded part (mesh mode) replaces the concept
        self.op = getattr(self, "op", OperatingPoint())
        self.errors: dict[str, str] = {}
        self.generation += 1

    @staticmethod
    def concept_names() -> list[str]:
        return list(concepts())

    def controls(self) -> list[Control]:
        """The concept's active parameters (the profile's own: the 17 values of the table
        profile, the tip clearance of the linear one, the eccentricity of the eccentric one)
        and the operating point's, in display units."""
        out = []
        if self.part is not None:
            for name, label in (("drum_radius", "drum inner radius (required)"), ("thickness", "axial thickness")):
                v = getattr(self.op, name)
                out.append(Control(name, label, "number", "mm", None if v is None else v * 1e3, 1.0, 2000.0
                                   if name == "drum_radius" else 200.0, 0.01, group="your part"))
            return out + self._op_controls()
        P = type(self.params)
        profile = getattr(self.params, "profile", None)
        inactive = {"clearance_tip": profile != "linear", "eccentricity": profile != "eccentric",
                    "eccentric_angle": profile != "eccentric"}
        for name, f in P.model_fields.items():
            if (name.startswith("table_c") and profile != "table") or inactive.get(name, False):
                continue
            out.append(self._control(P, name, getattr(self.params, name), f.description or name, "geometry"))
        return out + self._op_controls()

    def feasible(self) -> dict[str, tuple[float, float]]:
        """The range each numeric geometry parameter may take with the others as they are (in
        its display unit: the declared range cut by the concept's coupled rules,
        :meth:`~clutchfem.core.params.ParamSet.feasible_range`), for the sliders.  Tens of ms
        a parameter when a rule cuts it: the page calls it off the event loop."""
        if self.part is not None:
            return {}
        with self.lock:
            params = self.params
        P, values, out = type(params), params.model_dump(), {}
        for c in self.controls():
            if c.kind != "number" or c.group != "geometry":
                continue
            lo, hi = P.feasible_range(values, c.name)
            if lo is None:
                continue
            f = _SHOW.get(P.unit(c.name), ("", 1.0))[1]
            out[c.name] = (lo * f, hi * f)
        return out

    def _op_controls(self) -> list[Control]:
        out = []
        for name in OP_FIELDS:
            v = getattr(self.op, name)
            if name == "material":
                out.append(Control(name, "material", "choice", "", _material_key(v), choices=("51CrV4", "titanium",
                                                                                             "aluminium"),
                                   group="operating point"))
                continue
            if name == "fidelity":
                out.append(Control(name, "model: best (best estimate) | fast (2-D, ~half the time) | live (the "
                                   "reduced model of a built region, checked by the FE)", "choice", "", v,
                                   choices=("best", "fast", "live"), group="operating point"))
                continue
            if name == "drum_wall":  # the wall used: the fidelity's when not set (best: 2 mm), 0 rigid
                w = self.op.drum_wall_m
                shown = 0.0 if w is None else w * 1e3
                out.append(Control(name, "elastic drum wall (0: rigid drum)", "number", "mm", shown, 0.0, 30.0, 0.1,
                                   group="operating point"))
                continue
            out.append(self._control(OperatingPoint, name, v, OperatingPoint.model_fields[name].description or name,
                                     "operating point"))
        return out

    @staticmethod
    def _control(P, name: str, value, label: str, group: str) -> Control:
        if _is_choice(P, name):
            return Control(name, label, "choice", "", value, choices=tuple(get_args(P.model_fields[name].annotation)),
                           group=group)
        unit = P.unit(name)
        shown_unit, f = _SHOW.get(unit, (unit, 1.0))
        lo, hi = param_bounds(P, name)
        integer = P.model_fields[name].annotation is int
        step = 1.0 if integer else resolution(P, name) * f
        return Control(name, label, "number", shown_unit, None if value is None else value * f,
                       None if lo is None else lo * f, None if hi is None else hi * f, step, integer=integer,
                       group=group)

    def set_value(self, name: str, shown) -> str | None:
        """Change one parameter to ``shown`` (in its display unit, or a string with a unit):
        None if the design accepts it, else the refusal message (the design is unchanged)."""
        with self.lock:
            try:
                if name in OP_FIELDS:
                    self.op = self._op_with(name, shown)
                elif self.part is not None and name in ("drum_radius", "thickness"):
                    self.op = self.op.replace(**{name: f"{float(shown):.12g}mm" if not isinstance(shown, str)
                                                 else shown})
                else:
                    P = type(self.params)
                    raw = self._raw(P, name, shown)
                    self.params = self.params.replace(**{name: raw})
            except ClutchfemError as exc:
                self.errors[name] = str(exc)
                return str(exc)
            self.errors.pop(name, None)
            self.generation += 1
            return None

    def _op_with(self, name: str, shown) -> OperatingPoint:
        if name == "drum_wall":
            v = float(shown) if not isinstance(shown, str) else float(OperatingPoint.parse_value("drum_wall", shown)
                                                                      * 1e3)
            return self.op.replace(drum_wall="rigid" if v == 0 else f"{v}mm")
        if name == "material":
            return self.op.replace(material=str(shown))
        return self.op.replace(**{name: self._raw(OperatingPoint, name, shown)})

    @staticmethod
    def _raw(P, name: str, shown):
        """A display-unit value (or a string with its own unit) as the parameter set reads it."""
        if isinstance(shown, str) or _is_choice(P, name):
            return shown
        if shown is None or (isinstance(shown, float) and math.isnan(shown)):
            raise ParameterError(name, shown, P.allowed(name), P.context)
        unit = P.unit(name)
        shown_unit, f = _SHOW.get(unit, (unit, 1.0))
        if P.model_fields[name].annotation is int:
            return int(round(float(shown)))
        return f"{float(shown):.12g}{shown_unit}" if shown_unit else float(shown)

    def set_requirements(self, a=None, b=None) -> str | None:
        try:
            self.requirements = Requirements(a=self.requirements.a if a is None else float(a),
                                             b=self.requirements.b if b is None else float(b))
        except (ClutchfemError, ValueError, TypeError) as exc:
            return str(exc)
        self.generation += 1
        return None

    def set_engine_csv(self, path: str | Path) -> str | None:
        """An uploaded engine curve (read as ``--engine`` reads it: the same refusals)."""
        try:
            self.engine = EngineCurve.from_csv(path)
        except ClutchfemError as exc:
            return str(exc)
        self.generation += 1
        return None

    # -- the analysis ----------------------------------------------------------------------
    def set_part(self, path: str | Path) -> str | None:
        """Analyse an uploaded part (``.msh`` or STEP) instead of the concept: read as
        ``--mesh`` reads it (the same refusals); its drum radius is then asked for."""
        try:
            Design.from_mesh(path, operating=self.op.replace(drum_radius=None))  # readable at all?
        except ClutchfemError as exc:
            return str(exc)
        with self.lock:
            self.part = Path(path)
            self.generation += 1
        return None

    def design(self) -> Design:
        if self.part is not None:
            if self.op.drum_radius is None:
                raise ParameterError("drum_radius", None, "the drum's inner radius in mm (your part has no drum)",
                                     "your part")
            return Design.from_mesh(self.part, operating=self.op)
        return Design.from_concept(self.concept, self.params, self.op,
                                   self.mesh if self.mesh is not None else MeshSettings.preset(self.op.fidelity))

    def run(self) -> Outcome:
        """The first pass: the live answers (model ``live``, a reduced model holding the
        design), else the design meshed and analysed without the error estimate."""
        t0 = time.perf_counter()
        with self.lock:
            d = self.design()
        an = None
        if d.op.fidelity == "live" and d.params is None:
            raise ParameterError("fidelity", "live", "best or fast for an uploaded part: the model live is a reduced "
                                 "model over a concept's parameters", "your part")
        if d.op.fidelity == "live":
            from ..reduced import find, live_analysis

            if d.params is not None and find(d, engine=self.engine, requirements=self.requirements) is not None:
                an = live_analysis(d, engine=self.engine, requirements=self.requirements, build=False)
            if an is None or an.answered_by != "reduced model":
                why = (an.notes[-1] if an is not None else "no reduced model holds this design (`clutchfem reduce "
                       f"{d.name} --set ...` builds one around it: minutes)")
                d = d.with_fidelity("best")  # (the answers, the name and the downloads are this design's)
                an = analyze(d, engine=self.engine, requirements=self.requirements, errors=False)
                an.notes.append(f"answered by the FE (best path), not live: {why}")
                an = replace(an, answered_by="FE (fallback)")
        else:
            an = analyze(d, engine=self.engine, requirements=self.requirements, errors=False)
        out = Outcome(an, design_label(d), d, answer_rows(an), time.perf_counter() - t0)
        self.last = out
        return out

    def verify(self, outcome: Outcome) -> tuple[Outcome, list[str]]:
        """The second pass of a live outcome: the full FE of its design on the best path with
        its error step (the answers the reduced model was built from: the corrected peak, the
        bands) and the answers where it differs from the live one by more than the live band
        (each "answer: FE x, live y +- band", in the answer's unit); the outcome to show is the
        live one when they agree, else the FE's with its own bands (the page says which)."""
        t0 = time.perf_counter()
        fe = analyze(outcome.fe_design, engine=self.engine, requirements=self.requirements)
        live = outcome.analysis
        off = []
        for q in ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_Pa"):
            got, want = getattr(live, q), getattr(fe, q)
            band = (live.errors.get(q) or {}).get("total")
            if want is None or got is None or band is None or abs(got - want) > band:
                unit, f = {"max_von_mises_Pa": ("MPa", 1e-6), "torque_at_max_engine_torque_Nm": ("N m", 1.0)}.get(
                    q, ("rpm", 1.0))
                show = (lambda x: "none" if x is None else f"{x * f:.4g} {unit}")  # noqa: E731
                off.append(f"{q}: FE {show(want)}, live {show(got)} +- {show(band)}")
        fe_out = Outcome(fe, design_label(outcome.fe_design), outcome.fe_design, answer_rows(fe),
                         time.perf_counter() - t0)
        fe_out.__dict__["fe_design"] = outcome.fe_design
        if not off:
            return outcome, []
        fe.notes.append("the FE replaced the live answers: " + "; ".join(off))
        if self.last is outcome:
            self.last = fe_out
        return fe_out, off

    def complete(self, outcome: Outcome) -> Outcome:
        """The second pass of an FE outcome: the design analysed as ``analyze`` analyses it
        (:func:`~clutchfem.analysis.analyze` with its error step: the corrected answers --
        non-linearity, mesh extrapolation, refinement to the accuracy target -- and their
        bands), so that the page ends on the answers ``clutchfem analyze`` and ``report`` give
        for the same design, not on the first pass's design-mesh values (issue 37: one answer
        set).  The first pass is marked as such on the page until this replaces it."""
        t0 = time.perf_counter()
        an = analyze(outcome.design, engine=self.engine, requirements=self.requirements)
        out = Outcome(an, outcome.label, outcome.design, answer_rows(an), time.perf_counter() - t0)
        if self.last is outcome:
            self.last = out
        return out

    def field(self, outcome: Outcome, rpm: float):
        """The state at ``rpm`` (a one-speed sweep of the outcome's design, the same load case;
        a live design's on the best path)."""
        return outcome.fe_design.sweep([float(rpm)])

    def pin(self) -> None:
        self.pinned = self.last

    def swap(self) -> None:
        """Make the pinned design the current one (and the current one pinned)."""
        if self.pinned is None or self.last is None:
            return
        cur, pin = self.last, self.pinned
        with self.lock:
            self.params = pin.design.params
            self.op = pin.design.op
            self.concept = get_concept(pin.design.name)
            self.generation += 1
        self.pinned, self.last = cur, pin


def _material_key(m) -> str:
    n = getattr(m, "name", str(m)).lower()
    return "titanium" if "ti" in n.split("-")[0] else "aluminium" if "alumin" in n else "51CrV4"


def _finite(x) -> bool:
    return x is not None and isinstance(x, (int, float)) and math.isfinite(x)


def _f(x, unit: str, digits: int = 4) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return format_quantity(x, unit, digits)


#: the mark of a first-pass value (the design mesh's, uncorrected, no band) until analyze's replaces it
FIRST_PASS = " (first pass)"


def answer_rows(an: Analysis, errors: dict | None = None) -> list[tuple[str, str, str]]:
    """(answer, value with its unit and band, verdict) of the main answers.  An FE analysis
    without its error step (the page's first pass) marks the answers that ``analyze`` corrects
    and bands with :data:`FIRST_PASS`: they are not yet the answers of record."""
    errors = errors if errors is not None else (an.errors or {})
    req = an.requirements
    first = not errors and an.answered_by != "reduced model"

    def band(key: str, unit: str, scale: float = 1.0, fmt: str = ".0f") -> str:
        e = errors.get(key) or {}
        if e.get("total") is None:
            return FIRST_PASS if first else ""
        return f" +- {e['total'] * scale:{fmt}} {unit}"

    eng = an.engagement_rpm
    rows = [
        ("engagement speed (static)", ("-" if eng is None else f"{eng:.0f} rpm") + band("engagement_rpm", "rpm"), ""),
        ("engagement with 2-stroke ripple", "-" if an.engagement_rpm_with_ripple is None else
         f"{an.engagement_rpm_with_ripple:.0f} rpm", ("PASS" if req.get("engagement_ok") else "FAIL")
         + f" (> {req['engagement_limit_rpm']:.0f} rpm)"),
        ("slip speed (drum held, full throttle)", (an.slip_status.upper() if an.slip_rpm is None else
                                                   f"{an.slip_rpm:.0f} rpm") + band("slip_rpm", "rpm"),
         ("PASS" if req.get("slip_ok") else "FAIL") + f" (< {req['slip_limit_rpm']:.0f} rpm)"),
        (f"torque at {an.rpm_max_engine_torque:.0f} rpm", f"{an.torque_at_max_engine_torque_Nm:.2f} N m"
         + band("torque_at_max_engine_torque_Nm", "N m", 1.0, ".2f"),
         f"margin {an.torque_margin_Nm:+.2f} N m"),
        (f"peak von Mises at {an.max_engine_rpm:.0f} rpm", f"{an.max_von_mises_Pa / 1e6:.0f} MPa"
         + band("max_von_mises_Pa", "MPa", 1e-6), ("PASS" if an.safety_factor >= 1.5 else "FAIL")
         + f" (safety factor {an.safety_factor:.2f}, >= 1.5)"),
        ("fatigue safety factor", "-" if an.fatigue_safety_factor is None else f"{an.fatigue_safety_factor:.2f}",
         "" if an.fatigue_safety_factor is None else ("PASS" if an.fatigue_safety_factor >= 1 else "FAIL")),
        ("contact arc per shoe at max torque", _f(an.contact_arc_at_max_engine_torque_deg, "deg", 3)
         if _finite(an.contact_arc_at_max_engine_torque_deg) else "-",
         "not given live (the FE gives it)" if an.answered_by == "reduced model"
         and not _finite(an.contact_arc_at_max_engine_torque_deg) else ""),
        ("part mass", "-" if not (an.part or {}).get("mass_kg") else f"{an.part['mass_kg'] * 1e3:.1f} g", ""),
        ("shoe character", an.shoe_character, ""),
    ]
    return rows


def curve_arrays(an: Analysis) -> dict[str, np.ndarray]:
    """The torque-speed chart's series of an analysis (rpm, FE torque, engine torque)."""
    c = an.curves
    return {"rpm": c["rpm"].to_numpy(float), "torque": c["fe_torque_Nm"].to_numpy(float),
            "engine": c["engine_torque_Nm"].to_numpy(float)}
