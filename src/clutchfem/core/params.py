"""Typed parameter sets with units and declared valid ranges.

Every design input is a field of a frozen pydantic model declared with :func:`param`: a
default, a unit, a closed range and a one-line meaning.  Construction validates the ranges
and then the cross-parameter consistency rules of the subclass (:meth:`ParamSet.check`);
both raise :class:`~clutchfem.errors.ParameterError`, which names the parameter, its value
and what is allowed, before any geometry kernel runs.

Units: lengths in metres, angles in degrees (the unit designers read on drawings; converted
to radians where used), counts dimensionless.  A numeric field takes a number in its unit or
a string with a unit suffix of its dimension, from ``--set`` and from Python alike
(``1.8mm``, ``300um``, ``0.0018m``, ``80deg``; :func:`clutchfem.core.units.parse_quantity`);
messages show values in the field's display unit (mm, MPa).
"""

from __future__ import annotations

import contextvars
import math
import re
from typing import Any, ClassVar, Literal, get_args, get_origin

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from .errors import ClutchfemError, ParameterError
from .units import MINUS_SIGN, UnitError, format_quantity, parse_quantity
from .values import param_bounds, resolution

#: set while :meth:`ParamSet.feasible_range` probes values: no coupled-limit advice then
_PROBING: contextvars.ContextVar[bool] = contextvars.ContextVar("clutchfem_probing", default=False)
#: set only while :meth:`ParamSet.feasible_range` probes: nobody reads the refusals' messages
_QUIET: contextvars.ContextVar[bool] = contextvars.ContextVar("clutchfem_quiet", default=False)

_NUMBER_START = re.compile(r"\s*[-+]?(\d|\.\d|inf|nan)", re.IGNORECASE)

def param(default: Any, unit: str, lo: float | None = None, hi: float | None = None,
          doc: str = "", symbol: str = "") -> Any:
    """Declare a parameter: default, unit, closed range [lo, hi], meaning, drawing symbol."""
    extra = {"unit": unit, "symbol": symbol or ""}
    return Field(default, ge=lo, le=hi, description=doc, json_schema_extra=extra)


def choice(default: str, doc: str = "", symbol: str = "") -> Any:
    """Declare an option parameter (its Literal type lists the allowed values)."""
    return Field(default, description=doc, json_schema_extra={"unit": "-", "symbol": symbol})


def _fmt(x: float, unit: str) -> str:
    return format_quantity(x, unit, digits=6)


class ParamSet(BaseModel):
    """Base class of every parameter set (concept geometry, material, drum, analysis)."""

    model_config = ConfigDict(frozen=True, extra="forbid", validate_default=True)
    #: a label used in error messages (e.g. the concept name)
    context: ClassVar[str] = ""

    def __init__(self, **values: Any):
        for name, v in list(values.items()):
            if isinstance(v, str) and name in type(self).model_fields and type(self)._numeric(name):
                values[name] = type(self).parse_value(name, v)  # "2.4mm", "80deg", "200GPa"
        for name, v in values.items():  # pydantic's lax mode would read True as 1
            if isinstance(v, bool) and name in type(self).model_fields:
                ann = type(self).model_fields[name].annotation
                if ann in (int, float) or (get_args(ann) and all(a in (int, float, type(None))
                                                                   for a in get_args(ann))):
                    raise ParameterError(name, v, type(self).allowed(name) + " (a number, not True/False)",
                                         type(self).context or type(self).__name__)
        try:
            super().__init__(**values)
        except ValidationError as exc:
            raise self._translate(exc, values) from None
        try:
            self.check()
        except ParameterError as exc:  # a rule of another parameter that the values given break
            defaults = {n: f.default for n, f in type(self).model_fields.items()}
            given = [n for n in values if n != exc.name and values[n] != defaults.get(n)]
            raise type(self)._coupled(exc, values, given) from None

    # -- validation ---------------------------------------------------------------------
    @classmethod
    def _translate(cls, exc: ValidationError, values: dict) -> ParameterError:
        err = exc.errors()[0]
        name = str(err["loc"][0]) if err["loc"] else "?"
        inner = (err.get("ctx") or {}).get("error")
        if isinstance(inner, ClutchfemError):  # a validator's own message says it best
            return ParameterError(name, values.get(name, err.get("input")), str(inner),
                                  cls.context or cls.__name__)
        if err["type"] == "extra_forbidden":
            return ParameterError(name, values.get(name), "unknown parameter; known: "
                                  + ", ".join(cls.model_fields), cls.context or cls.__name__)
        value = values.get(name, err.get("input"))
        what = cls.model_fields[name].description if name in cls.model_fields else ""
        allowed = cls.allowed(name) + (f" ({what})" if what else "")
        return ParameterError(name, value, allowed, cls.context or cls.__name__, shown=cls.shown(name, value))

    @classmethod
    def shown(cls, name: str, value: Any) -> str:
        """``value`` of field ``name`` as a message shows it: a number in the field's display
        unit (``19 mm``), anything else as typed."""
        if name in cls.model_fields and isinstance(value, (int, float)) and not isinstance(value, bool):
            return format_quantity(value, cls.unit(name))
        return repr(value)

    @classmethod
    def allowed(cls, name: str) -> str:
        """Human-readable statement of what parameter ``name`` accepts."""
        f = cls.model_fields[name]
        ann = f.annotation
        if get_origin(ann) is Literal:
            return "one of " + ", ".join(repr(a) for a in get_args(ann))
        if ann is bool:
            return "true or false"
        lo = hi = None
        for m in f.metadata:
            lo = getattr(m, "ge", lo) if getattr(m, "ge", None) is not None else lo
            hi = getattr(m, "le", hi) if getattr(m, "le", None) is not None else hi
        unit = cls.unit(name)
        kind = "an integer" if ann is int else "a number"
        if lo is not None and hi is not None:
            return f"{kind} in [{_fmt(lo, unit)}, {_fmt(hi, unit)}]"
        if lo is not None:
            return f"{kind} >= {_fmt(lo, unit)}"
        if hi is not None:
            return f"{kind} <= {_fmt(hi, unit)}"
        return kind

    def check(self) -> None:
        """Cross-parameter consistency rules; subclasses raise :meth:`fail`."""

    @staticmethod
    def quiet() -> bool:
        """True while :meth:`feasible_range` probes values: a rule may then refuse without
        computing the limit its message would state (a bisection of its own: ~20 ms)."""
        return _QUIET.get()

    def fail(self, name: str, allowed: str) -> None:
        value = getattr(self, name)
        raise ParameterError(name, value, allowed, self.context or type(self).__name__, shown=self.shown(name, value))

    # -- introspection ------------------------------------------------------------------
    @classmethod
    def unit(cls, name: str) -> str:
        extra = cls.model_fields[name].json_schema_extra or {}
        return extra.get("unit", "-")

    @classmethod
    def symbol(cls, name: str) -> str:
        extra = cls.model_fields[name].json_schema_extra or {}
        return extra.get("symbol") or name

    @classmethod
    def describe(cls) -> list[dict]:
        """One row per parameter: name, unit, default, allowed, description."""
        rows = []
        for name, f in cls.model_fields.items():
            rows.append({"name": name, "unit": cls.unit(name), "default": f.default,
                         "allowed": cls.allowed(name), "description": f.description or ""})
        return rows

    def replace(self, **changes: Any):
        """A copy with some parameters changed (validated again).  A cross-parameter rule that
        the change breaks at another parameter is refused naming both (:meth:`_coupled`)."""
        values = {**self.model_dump(), **changes}
        outer = _PROBING.get()
        token = _PROBING.set(True)  # every value is given here: the advice is for the changed ones
        try:
            return type(self)(**values)
        except ParameterError as exc:
            if outer or exc.name in changes:
                raise
            err = exc
        finally:
            _PROBING.reset(token)
        raise type(self)._coupled(err, values, list(changes)) from None

    # -- coupled limits ----------------------------------------------------------------
    @classmethod
    def admits(cls, values: dict) -> bool:
        """True if the parameter set accepts ``values`` (declared ranges and cross-parameter
        rules), probed quietly: a refusal computes no limit for its message (~0.3 ms a probe
        instead of ~20 ms), for searches that test many designs against the rules.

        Examples
        --------
        >>> import clutchfem as cf
        >>> P = cf.get_concept("concept4").Params
        >>> P.admits({"flexure_thickness": 1.9e-3}), P.admits({"flexure_length": 30e-3})
        (True, False)
        """
        token, quiet = _PROBING.set(True), _QUIET.set(True)
        try:
            cls(**values)
            return True
        except (ValueError, ClutchfemError, ZeroDivisionError):  # pydantic's ValidationError is a ValueError
            return False
        finally:
            _PROBING.reset(token)
            _QUIET.reset(quiet)

    @classmethod
    def feasible_range(cls, values: dict, name: str) -> tuple[float | None, float | None]:
        """The interval of numeric parameter ``name`` that the parameter set accepts with the
        other parameters at ``values`` (its declared range cut by the cross-parameter rules),
        around the accepted value nearest to ``values[name]``; (None, None) if no value of it
        is accepted with the others as they are.  Each end is found by bisection to the
        parameter's resolution (:func:`~clutchfem.core.values.resolution`) between an
        accepted value and the declared end the rules refuse (~0.3 ms a probe: a few ms).

        Examples
        --------
        >>> import clutchfem as cf
        >>> P = cf.get_concept("concept4").Params
        >>> lo, hi = P.feasible_range(P().model_dump(), "flexure_thickness")
        >>> round(lo * 1e3, 2), round(hi * 1e3, 2)
        (0.5, 2.11)
        """
        if not cls._numeric(name):
            raise ParameterError("name", name, "a numeric parameter of " + (cls.context or cls.__name__))
        lo, hi = param_bounds(cls, name)
        x0 = values.get(name, cls.model_fields[name].default)
        if isinstance(x0, str):
            x0 = cls.parse_value(name, x0)
        integer = cls.model_fields[name].annotation is int
        token, quiet = _PROBING.set(True), _QUIET.set(True)
        try:
            def ok(x) -> bool:
                return cls.admits({**values, name: int(round(x)) if integer else float(x)})

            if lo is None or hi is None:  # an open range: only the rules' side is searched
                return (lo, hi) if ok(x0) else (None, None)
            if x0 is None or not ok(x0):  # the accepted value nearest to the one given
                grid = sorted((lo + (hi - lo) * k / 32 for k in range(33)),
                              key=lambda x: abs(x - (x0 if x0 is not None else (lo + hi) / 2)))
                x0 = next((x for x in grid if ok(x)), None)
                if x0 is None:
                    return None, None
            tol = 1.0 if integer else resolution(cls, name) / 2

            def edge(good: float, end: float) -> float:
                if ok(end):
                    return end
                while abs(end - good) > tol:
                    mid = (good + end) / 2
                    good, end = (mid, end) if ok(mid) else (good, mid)
                return good

            return float(edge(x0, lo)), float(edge(x0, hi))
        finally:
            _PROBING.reset(token)
            _QUIET.reset(quiet)

    @classmethod
    def _coupled(cls, exc: ParameterError, values: dict, given: list[str]) -> ParameterError:
        """``exc`` (a rule refusing parameter ``exc.name``) with the way out at the parameters
        the user gave (``given``): "or, with the others as they are, flexure_thickness (now
        2.4 mm) within [0.5 mm, 2.15 mm]" -- a rule another parameter's change breaks names
        both (issue 37).  Unchanged while probing or when nothing numeric was given."""
        if _PROBING.get():
            return exc
        ways = []
        values = {n: cls.parse_value(n, v) if isinstance(v, str) and n in cls.model_fields and cls._numeric(n)
                  else v for n, v in values.items()}
        for n in given:
            if n not in cls.model_fields or n == exc.name or not cls._numeric(n) or values.get(n) is None:
                continue
            lo, hi = cls.feasible_range(values, n)
            if lo is None:
                continue
            unit = cls.unit(n)
            ways.append(f"{n} (now {cls.shown(n, values[n])}) within [{format_quantity(lo, unit, 4)}, "
                        f"{format_quantity(hi, unit, 4)}]")
        if not ways:
            return exc
        ways = ways[:3]
        return ParameterError(exc.name, exc.value, f"{exc.allowed}; or, with the others as they are, "
                              + " or ".join(ways), exc.context, shown=exc.shown)

    # -- parsing ------------------------------------------------------------------------
    @classmethod
    def parse_assignments(cls, assignments: list[str] | tuple[str, ...]) -> dict[str, Any]:
        """Parse ``name=value`` strings (with optional unit suffix) into typed values; a
        parameter given twice is refused (which one was meant?)."""
        out: dict[str, Any] = {}
        for item in assignments:
            if "=" not in item:
                raise ParameterError(item, None, "expected the form name=value", cls.context)
            name, raw = (s.strip() for s in item.split("=", 1))
            if name not in cls.model_fields:
                raise ParameterError(name, raw, "unknown parameter; known: "
                                     + ", ".join(cls.model_fields), cls.context or cls.__name__)
            if name in out:
                raise ParameterError(name, raw, f"one value (it is given twice: also {name}="
                                     f"{out[name]!r})", cls.context or cls.__name__)
            out[name] = cls.parse_value(name, raw)
        return out

    @classmethod
    def _numeric(cls, name: str) -> bool:
        ann = cls.model_fields[name].annotation
        args = [a for a in get_args(ann) if a is not type(None)]
        return ann in (int, float) or bool(args and all(a in (int, float) for a in args))

    @classmethod
    def parse_value(cls, name: str, raw: str) -> Any:
        """A ``--set`` / CLI / API string to the field's type; numbers may carry a unit suffix of
        the field's own dimension (``1.8mm`` for a length, ``80deg`` for an angle, ``8000rpm``
        for a speed: :func:`~clutchfem.core.units.parse_quantity`); any other suffix is
        refused, naming the unit expected."""
        ann = cls.model_fields[name].annotation
        if get_origin(ann) is Literal or not cls._numeric(name):
            return raw
        ctx = cls.context or cls.__name__
        unit = cls.unit(name)
        try:
            value = parse_quantity(raw, unit)
        except UnitError as exc:
            if not _NUMBER_START.match(str(raw).replace(MINUS_SIGN, "-")):  # not a number at all
                raise ParameterError(name, raw, cls.allowed(name), ctx) from None
            raise ParameterError(name, raw, exc.expected, ctx) from None
        if ann is int:
            if not math.isfinite(value) or value != int(value):
                raise ParameterError(name, raw, cls.allowed(name), ctx)
            return int(value)
        if not math.isfinite(value):
            raise ParameterError(name, raw, cls.allowed(name), ctx)
        return value


    @classmethod
    def from_assignments(cls, assignments: list[str] | tuple[str, ...] = ()):
        return cls(**cls.parse_assignments(assignments))
