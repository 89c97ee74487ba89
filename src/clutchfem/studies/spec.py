"""Study specifications: a TOML file -> a validated, frozen :class:`StudySpec` -> points.

A spec names one design family (a concept, or a user mesh), the settings every point
shares, the requirement factors, and the varied parameters::

    [design]
    concept = "concept4"              # or mesh = "part.msh" (relative to the spec file)
    [design.set]                      # concept parameters held fixed (concept's units)
    shoe_arc = "90deg"

    [settings]                        # operating point, engine, mesh
    material = "51CrV4"
    mu = 0.165
    mesh_size = "2mm"
    engine = "engine.csv"             # columns rpm, torque [N m]; default: built-in curve

    [requirements]
    a = 1.3                           # engagement (with ripple) > a x idle rpm
    b = 1.0                           # slip rpm < b x rpm of the engine's maximum torque
    min_safety_factor = 1.0           # yield safety factor at the engine's maximum speed

    [errors]
    sample = 3                        # designs that also get their error estimate

    [vary]
    method = "grid"                   # grid | list | lhs | sobol
    [vary.params]
    flexure_thickness = {min = "1.5mm", max = "2.1mm", steps = 4}
    shoe_thickness = {values = ["5mm", "6mm", "7mm"]}

Methods: ``grid`` is the full product of every parameter's values (a list, or a range
with ``steps`` or ``step``); ``list`` zips lists of equal length (point i takes the i-th
value of each: explicit designs); ``lhs`` and ``sobol`` draw ``samples`` seeded
space-filling points (``scipy.stats.qmc``, ``seed``) over the ranges jointly, crossed with
any lists (e.g. a profile choice).  Sobol wants a power of 2 samples (its balance
properties hold only then).  Integer parameters (``n_shoes``) take integer values.

The study states its error from a sample (``[errors] sample``, default 3 designs evenly
spaced in point order): those designs are also analysed on a mesh twice as fine, and their
rows carry the error bands of engagement, slip, torque and peak stress (discretisation plus
the measured model-form terms, :mod:`clutchfem.errorest`); every other point is analysed
without (the error estimate triples a design's time).  The sample is not part of a
design's hash: changing it recomputes only the newly sampled points.

Validation happens here, before any worker starts: an error (:class:`SpecError`) names the
key (``vary.params.flexure_thickness.min``), its value and what is allowed.  Values are read
in the parameter's own unit (m, deg, -) and may carry a unit suffix of its dimension
(``"1.5mm"``, ``"80deg"``), through the concept's own :class:`~clutchfem.params.ParamSet`:
its declared ranges and choices are the allowed values.  Cross-parameter rules of the
concept (a fillet larger than its slot ...) are checked per point: such a point is stored
as *refused* with the concept's message, and the study goes on.
"""

from __future__ import annotations

import itertools
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal, get_args, get_origin

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, Strict, ValidationError

from ..core import ClutchfemError, InputError, ParameterError
from .point import Settings

#: more points than this in one spec are refused (split the study)
MAX_POINTS = 100_000
#: operating-point fields a spec may set (or vary); rpm is the analysis's own business
_OP_EXCLUDED = ("rpm",)
#: settings that are not operating-point fields
_EXTRA_SETTINGS = ("engine", "idle_rpm", "mesh_size", "mesh_model")
#: thickness of a user mesh when the spec gives none [m] (as the CLI's analyze --mesh)
USER_THICKNESS = 11e-3

_MISSING = object()


class SpecError(InputError):
    """A study spec key has a value that is not allowed (names key, value and what is allowed)."""

    def __init__(self, key: str, value: Any, allowed: str, source: str = ""):
        self.key, self.value, self.allowed, self.source = key, value, allowed, source
        where = f"study spec {source}" if source else "study spec"
        if value is _MISSING:
            msg = f"{where}: key '{key}' is missing: {allowed}"
        else:
            msg = f"{where}: key '{key}' = {value!r} is not allowed: {allowed}"
        super().__init__(msg)


# ---------------------------------------------------------------------------------------
# the raw TOML structure (pydantic: unknown keys, types and simple ranges)
# ---------------------------------------------------------------------------------------
Float = Annotated[float, Strict()]
Int = Annotated[int, Strict()]
Text = Annotated[str, Strict()]


class _Table(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class _DesignT(_Table):
    concept: Text | None = None
    mesh: Text | None = None
    set: dict[str, Any] = {}


class _RequirementsT(_Table):
    a: Annotated[Float, Field(gt=0, allow_inf_nan=False)] = 1.3
    b: Annotated[Float, Field(gt=0, allow_inf_nan=False)] = 1.0
    min_safety_factor: Annotated[Float, Field(ge=0, allow_inf_nan=False)] = 1.0


class _AxisT(_Table):
    min: Any = None
    max: Any = None
    steps: Annotated[Int, Field(ge=2, le=MAX_POINTS)] | None = None
    step: Any = None
    values: list[Any] | None = None


class _VaryT(_Table):
    method: Literal["grid", "list", "lhs", "sobol"] = "grid"
    samples: Annotated[Int, Field(ge=1, le=MAX_POINTS)] | None = None
    seed: Int = 0
    params: dict[str, _AxisT]


class _ErrorsT(_Table):
    sample: Annotated[Int, Field(ge=0, le=1000)] = 3


class _SpecT(_Table):
    design: _DesignT
    settings: dict[str, Any] = {}
    requirements: _RequirementsT = _RequirementsT()
    errors: _ErrorsT = _ErrorsT()
    vary: _VaryT


_TABLES = {(): _SpecT, ("design",): _DesignT, ("requirements",): _RequirementsT, ("vary",): _VaryT,
           ("errors",): _ErrorsT}


def _translate(exc: ValidationError, raw: dict, source: str) -> SpecError:
    err = exc.errors()[0]
    loc = tuple(str(x) for x in err["loc"])
    key = ".".join(loc) or "(top level)"
    value: Any = raw
    for part in loc:
        value = value.get(part, _MISSING) if isinstance(value, dict) else _MISSING
    kind = err["type"]
    if kind == "missing":
        what = {"design": "a [design] table with concept = NAME or mesh = FILE",
                "vary": "a [vary] table with [vary.params] (the varied parameters)",
                "vary.params": "the varied parameters, e.g. flexure_thickness = {min = \"1.5mm\", max = \"2.5mm\", "
                               "steps = 3}"}
        return SpecError(key, _MISSING, what.get(key, "required"), source)
    if kind == "extra_forbidden":
        parent = loc[:-1]
        if len(parent) == 3 and parent[:2] == ("vary", "params"):
            known = list(_AxisT.model_fields)
        else:
            known = list(_TABLES.get(parent, _SpecT).model_fields)
        return SpecError(key, err.get("input"), "unknown key; allowed here: " + ", ".join(known), source)
    if kind == "literal_error":
        return SpecError(key, err.get("input"), "one of " + str(err["ctx"]["expected"]).replace(" or ", ", "), source)
    allowed = err["msg"].replace("Input should be ", "")
    for words, sym in (("greater than or equal to ", ">= "), ("less than or equal to ", "<= "),
                       ("greater than ", "> "), ("less than ", "< ")):
        allowed = allowed.replace(words, sym)
    if kind in ("greater_than_equal", "less_than_equal", "greater_than", "less_than") and key.endswith(
            ("steps", "samples")):
        allowed = "an integer " + allowed
    if kind in ("float_type", "int_type", "string_type", "dict_type", "list_type", "model_type"):
        allowed = {"float_type": "a number", "int_type": "an integer (no quotes, no decimals)",
                   "string_type": "a text in quotes", "dict_type": "a table",
                   "list_type": "a list [..]", "model_type": "a table"}[kind]
        if key.startswith("vary.params.") and len(loc) == 3:
            allowed = ("a table {min = .., max = .., steps = ..} or {values = [..]}")
    return SpecError(key, err.get("input", value), allowed, source)


# ---------------------------------------------------------------------------------------
# resolved spec
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Axis:
    """One varied parameter: explicit ``values`` (a list, or a range gridded) or a sampled
    range ``lo``..``hi``; ``target`` is 'concept' (a concept parameter) or 'settings' (an
    operating-point field); ``unit`` the parameter's unit (m, deg, -)."""

    name: str
    unit: str
    target: str
    values: tuple = ()
    lo: float | None = None
    hi: float | None = None
    integer: bool = False

    @property
    def sampled(self) -> bool:
        return not self.values

    def label(self) -> str:
        return axis_label(self.name, self.unit)


def axis_label(name: str, unit: str) -> str:
    """Chart/table label of a parameter in the unit designers read (mm for lengths)."""
    shown = {"m": "mm", "-": ""}.get(unit, unit)
    return f"{name} [{shown}]" if shown else name


def display_value(x, unit: str):
    """A parameter value in the unit of :func:`axis_label` (lengths in mm)."""
    if isinstance(x, (int, float)) and not isinstance(x, bool) and unit == "m":
        return x * 1e3
    return x


@dataclass(frozen=True)
class StudySpec:
    """A validated study (see module docstring): fixed settings, varied axes and a method."""

    source: str
    settings: Settings
    axes: tuple[Axis, ...]
    method: str = "grid"
    samples: int | None = None
    seed: int = 0
    text: str = ""
    error_sample: int = 3

    @property
    def design(self) -> str:
        return self.settings.design_name

    def count(self) -> int:
        lists = [len(a.values) for a in self.axes if not a.sampled]
        if self.method == "grid":
            return math.prod(lists)
        if self.method == "list":
            return lists[0] if lists else 0
        return (self.samples or 0) * math.prod(lists)

    def error_points(self, n: int | None = None) -> list[int]:
        """Indices of the ``error_sample`` points (evenly spaced in point order, ends
        included) whose answers also get their error estimate."""
        n = self.count() if n is None else n
        k = min(self.error_sample, n)
        if k <= 0:
            return []
        return sorted({int(round(x)) for x in np.linspace(0, n - 1, k)})

    def points(self) -> list[dict]:
        """The points, in a reproducible order (``seed`` fixes the samples)."""
        if self.method == "grid":
            names = [a.name for a in self.axes]
            return [dict(zip(names, combo)) for combo in itertools.product(*(a.values for a in self.axes))]
        if self.method == "list":
            n = len(self.axes[0].values)
            return [{a.name: a.values[i] for a in self.axes} for i in range(n)]
        ranges = [a for a in self.axes if a.sampled]
        lists = [a for a in self.axes if not a.sampled]
        u = unit_samples(self.method, len(ranges), self.samples, self.seed)
        out = []
        for row in u:
            base = {a.name: _from_unit(a, x) for a, x in zip(ranges, row)}
            for combo in itertools.product(*(a.values for a in lists)):
                out.append({**base, **dict(zip((a.name for a in lists), combo))})
        return out


def unit_samples(method: str, d: int, n: int, seed: int) -> np.ndarray:
    """``n`` seeded points in the unit hypercube [0, 1)^d: Latin hypercube or scrambled Sobol."""
    from scipy.stats import qmc

    rng = np.random.default_rng(seed)
    if method == "lhs":
        return qmc.LatinHypercube(d, rng=rng).random(n)
    m = int(round(math.log2(n)))
    return qmc.Sobol(d, scramble=True, rng=rng).random_base2(m)


def _from_unit(a: Axis, x: float):
    if a.integer:
        lo, hi = int(a.lo), int(a.hi)
        return int(min(hi, lo + math.floor(x * (hi - lo + 1))))
    return _clean(a.lo + x * (a.hi - a.lo))


def _clean(x: float) -> float:
    return float(f"{x:.12g}")


# ---------------------------------------------------------------------------------------
# loading
# ---------------------------------------------------------------------------------------
def load_spec(path: str | Path) -> StudySpec:
    """Read and validate a spec file (relative paths inside it are relative to its folder)."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"study spec {path}: file not found (write one with `clutchfem study --example > "
                         f"{path.name}`)")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"study spec {path}: cannot be read as UTF-8 text ({exc})") from None
    return parse_spec(text, source=str(path), base=path.parent)


def parse_spec(text: str, source: str = "<text>", base: Path | None = None) -> StudySpec:
    """Validate the TOML ``text`` of a spec (see module docstring)."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"study spec {source}: not valid TOML ({exc})") from None
    try:
        t = _SpecT.model_validate(raw)
    except ValidationError as exc:
        raise _translate(exc, raw, source) from None
    base = base or Path.cwd()
    design = t.design
    if (design.concept is None) == (design.mesh is None):
        raise SpecError("design", {k: v for k, v in raw["design"].items() if k in ("concept", "mesh")},
                        "exactly one of concept = NAME or mesh = FILE", source)
    concept = params_cls = None
    mesh_file = mesh_bytes = None
    if design.concept is not None:
        from ..geometry import concepts, get_concept

        try:
            concept = get_concept(design.concept)
        except ParameterError:
            raise SpecError("design.concept", design.concept, "one of " + ", ".join(concepts()), source) from None
        params_cls = concept.Params
    else:
        if design.set:
            raise SpecError("design.set", design.set, "nothing: [design.set] holds concept parameters, and a "
                            "user mesh has none (vary or set operating-point settings instead)", source)
        p = Path(design.mesh)
        p = p if p.is_absolute() else base / p
        if not p.is_file():
            raise SpecError("design.mesh", design.mesh, f"an existing .msh or STEP file (looked for {p})", source)
        mesh_file, mesh_bytes = str(p), p.read_bytes()
    from ..loadcase import OperatingPoint

    fixed = {}
    for name, raw_v in design.set.items():
        key = f"design.set.{name}"
        _check_known(params_cls, name, key, source, concept.name)
        fixed[name] = _value(params_cls, name, raw_v, key, source)
    settings_kw = _settings(t.settings, concept is not None, base, source)
    op_fields = [f for f in OperatingPoint.model_fields if f not in _OP_EXCLUDED]
    axes = []
    vary = t.vary
    if not vary.params:
        raise SpecError("vary.params", {}, "at least one varied parameter", source)
    for name, ax in vary.params.items():
        key = f"vary.params.{name}"
        if params_cls is not None and name in params_cls.model_fields:
            cls, target = params_cls, "concept"
            if name in fixed:
                raise SpecError(key, _axis_raw(ax), f"varied or fixed, not both (also in [design.set]: "
                                f"{name} = {design.set[name]!r})", source)
        elif name in op_fields and not (concept is not None and name in ("drum_radius", "thickness")):
            cls, target = OperatingPoint, "settings"
            if name in t.settings:
                raise SpecError(key, _axis_raw(ax), f"varied or fixed, not both (also in [settings]: "
                                f"{name} = {t.settings[name]!r})", source)
        else:
            known = (list(params_cls.model_fields) if params_cls is not None else []) + \
                    [f for f in op_fields if concept is None or f not in ("drum_radius", "thickness")]
            what = f"a parameter of {concept.name}" if concept is not None else "an operating-point setting"
            raise SpecError("vary.params", name, f"{what} or setting: one of " + ", ".join(known), source)
        axes.append(_axis(cls, name, ax, vary.method, key, source, target))
    method = vary.method
    if method in ("grid", "list") and vary.samples is not None:
        raise SpecError("vary.samples", vary.samples, f"nothing for method '{method}' (samples applies to lhs "
                        "and sobol; a grid's size comes from its steps and lists)", source)
    if method == "list":
        lens = {a.name: len(a.values) for a in axes}
        for a in axes:
            if a.sampled:
                raise SpecError(f"vary.params.{a.name}", _axis_raw(vary.params[a.name]),
                                "a list {values = [..]} (method 'list' zips lists of equal length)", source)
        if len(set(lens.values())) > 1:
            raise SpecError("vary.params", lens, "lists of one length (method 'list' zips them: point i "
                            "takes the i-th value of each)", source)
    samples = None
    if method in ("lhs", "sobol"):
        if vary.samples is None:
            raise SpecError("vary.samples", _MISSING, f"the number of {method} samples (an integer >= 1)", source)
        samples = vary.samples
        if method == "sobol" and samples & (samples - 1):
            lo = 1 << (samples.bit_length() - 1)
            raise SpecError("vary.samples", samples, f"a power of 2 for sobol (its balance properties need it), "
                            f"e.g. {lo} or {2 * lo}", source)
        if not any(a.sampled for a in axes):
            raise SpecError("vary.params", sorted(vary.params), f"at least one range {{min = .., max = ..}} to "
                            f"sample with {method}", source)
    settings = Settings(concept=concept.name if concept else None, fixed=tuple(sorted(fixed.items())),
                        mesh_file=mesh_file, mesh_bytes=mesh_bytes, **settings_kw,
                        a=t.requirements.a, b=t.requirements.b,
                        min_safety_factor=t.requirements.min_safety_factor)
    spec = StudySpec(source=source, settings=settings, axes=tuple(axes), method=method, samples=samples,
                     seed=vary.seed, text=text, error_sample=t.errors.sample)
    n = spec.count()
    if n > MAX_POINTS:
        raise SpecError("vary", f"{n} points", f"at most {MAX_POINTS} points in one spec (split the study)", source)
    return spec


def _axis_raw(ax: _AxisT) -> dict:
    return ax.model_dump(exclude_none=True)


def _check_known(cls, name: str, key: str, source: str, what: str) -> None:
    if name not in cls.model_fields:
        raise SpecError(key, name, f"a parameter of {what}: one of " + ", ".join(cls.model_fields), source)


def _unit_hint(cls, name: str) -> str:
    unit = cls.unit(name)
    return {"m": "; plain numbers are in m: write \"1.5mm\" for 1.5 mm",
            "deg": "; angles in deg (\"80deg\" or 80)"}.get(unit, "")


def _value(cls, name: str, raw: Any, key: str, source: str):
    """One value of parameter ``name`` of ParamSet ``cls``: parsed with its unit suffix and
    checked against its declared range or choices (cross-parameter rules are per point)."""
    f = cls.model_fields[name]
    ann = f.annotation
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
        raise SpecError(key, raw, cls.allowed(name) if name != "material" else
                        "a material name", source)
    if name == "material":
        from ..core import get_material

        if not isinstance(raw, str):
            raise SpecError(key, raw, "a material name (text)", source)
        try:
            get_material(raw)
        except ParameterError as exc:
            raise SpecError(key, raw, exc.allowed, source) from None
        return raw
    if get_origin(ann) is Literal:
        if raw not in get_args(ann):
            raise SpecError(key, raw, cls.allowed(name), source)
        return raw
    try:
        v = cls._parse_value(name, raw) if isinstance(raw, str) else raw
    except ParameterError as exc:
        raise SpecError(key, raw, exc.allowed + _unit_hint(cls, name), source) from None
    if isinstance(v, str):  # a non-numeric field typed as a number, or text for a number
        raise SpecError(key, raw, cls.allowed(name), source)
    args = [a for a in get_args(ann) if a is not type(None)]
    integer = ann is int or args == [int]
    if integer:
        if not float(v).is_integer():
            raise SpecError(key, raw, cls.allowed(name), source)
        v = int(v)
    else:
        v = float(v)
    if not math.isfinite(v):
        raise SpecError(key, raw, cls.allowed(name), source)
    lo, hi = _bounds(cls, name)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise SpecError(key, raw, cls.allowed(name) + _unit_hint(cls, name), source)
    return v if integer else _clean(v)  # "1.8mm" is 0.0018, not 0.0018000000000000002


def _bounds(cls, name: str) -> tuple[float | None, float | None]:
    lo = hi = None
    for m in cls.model_fields[name].metadata:
        lo = m.ge if getattr(m, "ge", None) is not None else lo
        hi = m.le if getattr(m, "le", None) is not None else hi
    return lo, hi


def _axis(cls, name: str, ax: _AxisT, method: str, key: str, source: str, target: str) -> Axis:
    unit = cls.unit(name)
    if ax.values is not None:
        if any(v is not None for v in (ax.min, ax.max, ax.steps, ax.step)):
            raise SpecError(key, _axis_raw(ax), "either values = [..] or a range min/max, not both", source)
        if not ax.values:
            raise SpecError(f"{key}.values", [], "at least one value", source)
        vals = tuple(_value(cls, name, v, f"{key}.values[{i}]", source) for i, v in enumerate(ax.values))
        if method != "list" and len(set(vals)) != len(vals):
            raise SpecError(f"{key}.values", ax.values, "distinct values (a repeated value is the same design)", source)
        return Axis(name, unit, target, values=vals)
    for which in ("min", "max"):
        if getattr(ax, which) is None:
            raise SpecError(f"{key}.{which}", _MISSING, f"a range needs min and max (in {unit}; "
                            f"{cls.allowed(name)}), or give values = [..]", source)
    ann = cls.model_fields[name].annotation
    if get_origin(ann) is Literal or name == "material":
        raise SpecError(key, _axis_raw(ax), f"a list values = [..]: {name} is a choice ({cls.allowed(name)})",
                        source)
    lo = _value(cls, name, ax.min, f"{key}.min", source)
    hi = _value(cls, name, ax.max, f"{key}.max", source)
    integer = isinstance(lo, int)
    if not lo < hi:
        raise SpecError(f"{key}.max", ax.max, f"a value above min = {ax.min!r}", source)
    if method in ("lhs", "sobol"):
        if ax.steps is not None or ax.step is not None:
            raise SpecError(key, _axis_raw(ax), f"min and max only: method '{method}' samples the range "
                            "(steps/step apply to method 'grid')", source)
        return Axis(name, unit, target, lo=lo, hi=hi, integer=integer)
    if method == "list":
        raise SpecError(key, _axis_raw(ax), "a list {values = [..]} (method 'list' zips lists)", source)
    if (ax.steps is None) == (ax.step is None):
        raise SpecError(key, _axis_raw(ax), "a grid range with exactly one of steps = N (>= 2 values, ends "
                        "included) or step = size (in the parameter's unit)", source)
    if ax.steps is not None:
        vals = np.linspace(lo, hi, ax.steps)
    else:
        step = _value_step(cls, name, ax.step, f"{key}.step", source)
        if not 0 < step <= hi - lo:
            raise SpecError(f"{key}.step", ax.step, "a step > 0 and at most max - min", source)
        n = int(math.floor((hi - lo) / step + 1e-9)) + 1
        if n > MAX_POINTS:
            raise SpecError(f"{key}.step", ax.step, f"a step giving at most {MAX_POINTS} values", source)
        vals = lo + step * np.arange(n)
    if integer:
        out = tuple(sorted({int(round(v)) for v in vals}))
    else:
        out = tuple(_clean(float(v)) for v in vals)
    return Axis(name, unit, target, values=out, integer=integer)


def _value_step(cls, name: str, raw: Any, key: str, source: str) -> float:
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
        raise SpecError(key, raw, f"a step in {cls.unit(name)}", source)
    try:
        return float(cls._parse_value(name, raw)) if isinstance(raw, str) else float(raw)
    except ParameterError as exc:
        raise SpecError(key, raw, exc.allowed, source) from None


def _settings(raw: dict, is_concept: bool, base: Path, source: str) -> dict:
    """The fixed settings: operating point, engine curve, idle speed, mesh settings."""
    from ..clutch import EngineCurve
    from ..geometry import MeshSettings
    from ..loadcase import OperatingPoint

    op_fields = [f for f in OperatingPoint.model_fields if f not in _OP_EXCLUDED]
    allowed_keys = [f for f in op_fields if not (is_concept and f in ("drum_radius", "thickness"))]
    allowed_keys += list(_EXTRA_SETTINGS)
    values: dict = {}
    for name, v in raw.items():
        key = f"settings.{name}"
        if is_concept and name in ("drum_radius", "thickness"):
            raise SpecError(key, v, f"nothing here: for a concept, {name} is a concept parameter (put it under "
                            "[design.set] or vary it)", source)
        if name not in allowed_keys:
            raise SpecError(key, v, "unknown setting; allowed: " + ", ".join(allowed_keys), source)
        if name in _EXTRA_SETTINGS:
            continue
        values[name] = _value(OperatingPoint, name, v, key, source)
    if not is_concept:
        values.setdefault("thickness", USER_THICKNESS)
        if "drum_radius" not in values:
            raise SpecError("settings.drum_radius", _MISSING, "the drum's inner radius for a user mesh (e.g. "
                            "\"34.4mm\"), larger than the outer radius of its contact curves", source)
    try:
        op = OperatingPoint(**values)
    except ParameterError as exc:
        raise SpecError(f"settings.{exc.name}", exc.value, exc.allowed, source) from None
    idle = None
    if "idle_rpm" in raw:
        v = raw["idle_rpm"]
        try:
            idle = _rpm_value(v)
        except (TypeError, ValueError):
            idle = None
        if idle is None or not (0 < idle < 1e6):
            raise SpecError("settings.idle_rpm", v, "an idle speed > 0 rpm (e.g. 2700)", source)
    engine = None
    if "engine" in raw:
        v = raw["engine"]
        if not isinstance(v, str):
            raise SpecError("settings.engine", v, "the path of an engine curve CSV (columns rpm, torque [N m])",
                            source)
        p = Path(v)
        p = p if p.is_absolute() else base / p
        try:
            engine = EngineCurve.from_csv(p, idle_rpm=idle)
        except ClutchfemError as exc:
            raise SpecError("settings.engine", v, f"a readable engine curve CSV ({exc})", source) from None
    ms = {}
    if "mesh_size" in raw:
        v = raw["mesh_size"]
        ms["size"] = _value(MeshSettings, "size", v, "settings.mesh_size", source)
    if "mesh_model" in raw:
        ms["model"] = _value(MeshSettings, "model", raw["mesh_model"], "settings.mesh_model", source)
    return {"op": op, "mesh": MeshSettings(**ms), "engine": engine, "idle_rpm": idle}


def _rpm_value(v) -> float:
    if isinstance(v, bool):
        raise ValueError
    if isinstance(v, str):
        s = v.strip()
        if s.endswith("rpm"):
            s = s[:-3]
        return float(s)
    return float(v)


# ---------------------------------------------------------------------------------------
# the example
# ---------------------------------------------------------------------------------------
EXAMPLE_SPEC = '''\
# clutchfem study spec: 12 designs of concept 4 (flexure thickness x shoe thickness).
#   clutchfem study --example > study.toml
#   clutchfem study study.toml --out out/study          (2 local worker processes)
# Values are in the parameter's unit (m, deg) or carry a suffix: "1.6mm", "90deg".
# Parameters and their ranges: clutchfem geometry --concept concept4 --list-params

[design]
concept = "concept4"          # or: mesh = "part.msh" (a user mesh, with settings.drum_radius)

[design.set]                  # concept parameters held fixed (the rest: the concept's defaults)
shoe_arc = "90deg"

[settings]
material = "51CrV4"           # 51CrV4 (SS 2230), titanium, aluminium
mu = 0.165                    # shoe-drum friction (seed 000)
rotation = "ccw"
mesh_size = "2mm"             # coarse, for a first look (the default 1.2mm for design work)
# engine = "engine.csv"       # full-throttle curve, columns rpm, torque [N m]
#                             # (default: built-in 56.5 cc saw curve, ASSUMED shape)
# idle_rpm = 2700

[requirements]                # a, b: ASSUMED defaults (confidential in the thesis)
a = 1.3                       # engagement (with speed ripple) > a x idle rpm
b = 1.0                       # slip rpm < b x rpm of the engine's maximum torque
min_safety_factor = 1.0       # peak von Mises at the engine's maximum speed <= yield / this

[errors]                      # the study's error, from a sample of its designs: each analysed again on
sample = 3                    # a mesh twice as fine (3x its time) plus the measured model-form terms

[vary]
method = "grid"               # grid | list | lhs | sobol (lhs, sobol: samples = N, seed = S)

[vary.params]
flexure_thickness = {min = "1.6mm", max = "2.2mm", steps = 4}   # beam thickness at the hub end
shoe_thickness = {values = ["5mm", "6mm", "7mm"]}               # radial shoe thickness: shoe mass
'''
