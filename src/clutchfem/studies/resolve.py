"""Reading a study spec: TOML text -> a validated, frozen :class:`~.spec.StudySpec`.

Validation happens here, before any worker starts: first the raw structure
(:mod:`.schema`: unknown keys, types, simple ranges), then every value against the
concept's own parameter set.  An error (:class:`~.schema.SpecError`) names the key
(``vary.params.flexure_thickness.min``), its value and what is allowed.  Values are read in
the parameter's own unit (m, deg, -) and may carry a unit suffix of its dimension
(``"1.5mm"``, ``"80deg"``), through the concept's own :class:`~clutchfem.core.ParamSet`: its
declared ranges and choices are the allowed values.  Cross-parameter rules of the concept
(a fillet larger than its slot ...) are checked per point: such a point is stored as
*refused* with the concept's message, and the study goes on.

A name in ``[vary.params]`` is a concept parameter if the concept has it, else an
operating-point setting (``mu``, ``material`` ...); for a concept, ``drum_radius`` and
``thickness`` are concept parameters only.  A grid range gives ``steps`` values (ends
included) or values ``step`` apart from ``min``; every value is rounded to 12 significant
digits (:func:`~.values.round12`), integers to integers.  A user mesh (``mesh = FILE``)
travels with the settings as bytes (remote workers need no shared disk); its thickness is
:data:`USER_THICKNESS` unless the settings give one, its drum radius must be given.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path
from typing import Any, Literal, get_args, get_origin

import numpy as np
from pydantic import ValidationError

from ..clutch import EngineCurve
from ..core import ClutchfemError, InputError, ParameterError, get_material, param_bounds, round12
from ..evaluation import Settings
from ..geometry import MeshSettings, concepts, get_concept
from ..loadcase import USER_THICKNESS, OperatingPoint
from .schema import MAX_POINTS, MISSING, AxisTable, SpecError, SpecTable, translate_error
from .spec import Axis, StudySpec

#: operating-point fields a spec may set (or vary); rpm is the analysis's own business
_OP_EXCLUDED = ("rpm",)
#: settings that are not operating-point fields
_EXTRA_SETTINGS = ("engine", "idle_rpm", "mesh_size", "mesh_model", "live_outside")


def load_study(path: str | Path) -> StudySpec:
    """Read and validate a study spec file (relative paths inside it are relative to its
    folder).

    Parameters
    ----------
    path : str or Path
        A TOML spec (``clutchfem study --example`` prints a commented one).

    Returns
    -------
    StudySpec

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> from clutchfem.studies import EXAMPLE_SPEC
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "study.toml"
    >>> _ = p.write_text(EXAMPLE_SPEC)
    >>> len(cf.load_study(p).points())
    12
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"study spec {path}: file not found (write one with `clutchfem study --example > "
                         f"{path.name}`)")
    try:
        text = path.read_text(encoding="utf-8-sig")  # a byte-order mark (Windows editors) is no TOML error
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"study spec {path}: cannot be read as UTF-8 text ({exc})") from None
    return parse_spec(text, source=str(path), base=path.parent)


def toml_context(text: str, message: str) -> str:
    """The line a TOML error points at, and for a key given twice its name and the line of
    its first definition (tomllib names neither: "Cannot overwrite a value (at line 6,
    column 9)")."""
    m = re.search(r"at line (\d+)", message)
    lines = text.splitlines()
    if not m or not 0 < int(m.group(1)) <= len(lines):
        return ""
    n = int(m.group(1))
    line = lines[n - 1].strip()
    out = f": line {n} is {line!r}"
    key = re.match(r"\s*([\w.\-\"' ]+?)\s*=", lines[n - 1])
    if ("overwrite" in message or "twice" in message) and key:
        name = key.group(1).strip().strip("\"'")
        table = ""
        for k in range(n - 1, 0, -1):  # the table the key is in
            t = re.match(r"\s*\[+\s*([^\]]+?)\s*\]+", lines[k - 1])
            if t:
                table = t.group(1) + "."
                break
        first = next((k for k in range(1, n) if re.match(rf"\s*{re.escape(name)}\s*=", lines[k - 1])), None)
        out = f": key '{table}{name}' is given twice (line {n}" + (f", first on line {first}" if first else "") + \
            "); keep one"
    return out


def parse_spec(text: str, source: str = "<text>", base: Path | None = None) -> StudySpec:
    """Validate the TOML ``text`` of a spec (see module docstring)."""
    text = text.removeprefix("\ufeff")  # a byte-order mark that a reader left in the text
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"study spec {source}: not valid TOML ({exc}){toml_context(text, str(exc))}") from None
    try:
        t = SpecTable.model_validate(raw)
    except ValidationError as exc:
        raise translate_error(exc, raw, source) from None
    base = base or Path.cwd()
    design = t.design
    if (design.concept is None) == (design.mesh is None):
        raise SpecError("design", {k: v for k, v in raw["design"].items() if k in ("concept", "mesh")},
                        "exactly one of concept = NAME or mesh = FILE", source)
    concept = params_cls = None
    mesh_file = mesh_bytes = None
    if design.concept is not None:
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
                raise SpecError(key, ax.raw(), f"varied or fixed, not both (also in [design.set]: "
                                f"{name} = {design.set[name]!r})", source)
        elif name in op_fields and not (concept is not None and name in ("drum_radius", "thickness")):
            cls, target = OperatingPoint, "settings"
            if name in t.settings:
                raise SpecError(key, ax.raw(), f"varied or fixed, not both (also in [settings]: "
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
                raise SpecError(f"vary.params.{a.name}", vary.params[a.name].raw(),
                                "a list {values = [..]} (method 'list' zips lists of equal length)", source)
        if len(set(lens.values())) > 1:
            raise SpecError("vary.params", lens, "lists of one length (method 'list' zips them: point i "
                            "takes the i-th value of each)", source)
        rows = list(zip(*(a.values for a in axes)))
        seen: dict = {}
        for i, r in enumerate(rows, start=1):
            if r in seen:
                raise SpecError("vary.params", {a.name: list(a.values) for a in axes},
                                f"distinct designs: points {seen[r]} and {i} are the same design "
                                f"({', '.join(f'{a.name} = {v!r}' for a, v in zip(axes, r))}); drop one", source)
            seen[r] = i
    samples = None
    if method in ("lhs", "sobol"):
        if vary.samples is None:
            raise SpecError("vary.samples", MISSING, f"the number of {method} samples (an integer >= 1)", source)
        samples = vary.samples
        if method == "sobol" and samples & (samples - 1):
            lo = 1 << (samples.bit_length() - 1)
            raise SpecError("vary.samples", samples, f"a power of 2 for sobol (its balance properties need it), "
                            f"e.g. {lo} or {2 * lo}", source)
        if not any(a.sampled for a in axes):
            raise SpecError("vary.params", sorted(vary.params), f"at least one range {{min = .., max = ..}} to "
                            f"sample with {method}", source)
    live_outside = settings_kw.pop("live_outside")
    settings = Settings(concept=concept.name if concept else None, fixed=tuple(sorted(fixed.items())),
                        mesh_file=mesh_file, mesh_bytes=mesh_bytes, **settings_kw,
                        a=t.requirements.a, b=t.requirements.b,
                        min_safety_factor=t.requirements.min_safety_factor)
    spec = StudySpec(source=source, settings=settings, axes=tuple(axes), method=method, samples=samples,
                     seed=vary.seed, text=text, error_sample=t.errors.sample, live_outside=live_outside)
    n = spec.count()
    if n > MAX_POINTS:
        raise SpecError("vary", f"{n} points", f"at most {MAX_POINTS} points in one spec (split the study)", source)
    return spec


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
        v = cls.parse_value(name, raw) if isinstance(raw, str) else raw
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
    lo, hi = param_bounds(cls, name)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise SpecError(key, raw, cls.allowed(name) + _unit_hint(cls, name), source)
    return v if integer else round12(v)  # "1.8mm" is 0.0018, not 0.0018000000000000002


def _axis(cls, name: str, ax: AxisTable, method: str, key: str, source: str, target: str) -> Axis:
    unit = cls.unit(name)
    if ax.values is not None:
        if any(v is not None for v in (ax.min, ax.max, ax.steps, ax.step)):
            raise SpecError(key, ax.raw(), "either values = [..] or a range min/max, not both", source)
        if not ax.values:
            raise SpecError(f"{key}.values", [], "at least one value", source)
        vals = tuple(_value(cls, name, v, f"{key}.values[{i}]", source) for i, v in enumerate(ax.values))
        if method != "list" and len(set(vals)) != len(vals):
            raise SpecError(f"{key}.values", ax.values, "distinct values (a repeated value is the same design)", source)
        return Axis(name, unit, target, values=vals)
    for which in ("min", "max"):
        if getattr(ax, which) is None:
            raise SpecError(f"{key}.{which}", MISSING, f"a range needs min and max (in {unit}; "
                            f"{cls.allowed(name)}), or give values = [..]", source)
    ann = cls.model_fields[name].annotation
    if get_origin(ann) is Literal or name == "material":
        raise SpecError(key, ax.raw(), f"a list values = [..]: {name} is a choice ({cls.allowed(name)})",
                        source)
    lo = _value(cls, name, ax.min, f"{key}.min", source)
    hi = _value(cls, name, ax.max, f"{key}.max", source)
    integer = isinstance(lo, int)
    if not lo < hi:
        raise SpecError(f"{key}.max", ax.max, f"a value above min = {ax.min!r}", source)
    if method in ("lhs", "sobol"):
        if ax.steps is not None or ax.step is not None:
            raise SpecError(key, ax.raw(), f"min and max only: method '{method}' samples the range "
                            "(steps/step apply to method 'grid')", source)
        return Axis(name, unit, target, lo=lo, hi=hi, integer=integer)
    if method == "list":
        raise SpecError(key, ax.raw(), "a list {values = [..]} (method 'list' zips lists)", source)
    if (ax.steps is None) == (ax.step is None):
        raise SpecError(key, ax.raw(), "a grid range with exactly one of steps = N (>= 2 values, ends "
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
        out = tuple(round12(float(v)) for v in vals)
    return Axis(name, unit, target, values=out, integer=integer)


def _value_step(cls, name: str, raw: Any, key: str, source: str) -> float:
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
        raise SpecError(key, raw, f"a step in {cls.unit(name)}", source)
    try:
        return float(cls.parse_value(name, raw)) if isinstance(raw, str) else float(raw)
    except ParameterError as exc:
        raise SpecError(key, raw, exc.allowed, source) from None


def _settings(raw: dict, is_concept: bool, base: Path, source: str) -> dict:
    """The fixed settings: operating point, engine curve, idle speed, mesh settings."""
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
            raise SpecError("settings.drum_radius", MISSING, "the drum's inner radius for a user mesh (e.g. "
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
    top = (engine or EngineCurve.default()).rpm_range[1]
    if idle is not None and idle >= top:
        raise SpecError("settings.idle_rpm", raw["idle_rpm"], f"an idle speed below the engine curve's top speed "
                        f"{top:g} rpm ({'settings.engine' if engine else 'the built-in curve'})", source)
    ms = {}
    if "mesh_size" in raw:
        v = raw["mesh_size"]
        ms["size"] = _value(MeshSettings, "size", v, "settings.mesh_size", source)
    if "mesh_model" in raw:
        ms["model"] = _value(MeshSettings, "model", raw["mesh_model"], "settings.mesh_model", source)
    outside = raw.get("live_outside", "refuse")
    if outside not in ("refuse", "fe"):
        raise SpecError("settings.live_outside", outside, "refuse or fe: what a point of a live study that no "
                        "cached reduced model holds gets", source)
    if "live_outside" in raw and op.fidelity != "live":
        raise SpecError("settings.live_outside", outside, f"nothing for fidelity {op.fidelity!r} (it applies to "
                        "fidelity = \"live\")", source)
    if op.fidelity == "live" and not is_concept:
        raise SpecError("settings.fidelity", "live", "best or fast for a user mesh (it has no parameters to "
                        "reduce over)", source)
    return {"op": op, "mesh": MeshSettings.preset(op.fidelity, **ms), "engine": engine, "idle_rpm": idle,
            "live_outside": outside}


def _rpm_value(v) -> float:
    if isinstance(v, bool):
        raise ValueError
    if isinstance(v, str):
        s = v.strip()
        if s.endswith("rpm"):
            s = s[:-3]
        return float(s)
    return float(v)
