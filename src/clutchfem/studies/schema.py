"""The raw TOML structure of a study spec, and its validation errors in the spec's own words.

The structure is checked by pydantic models (:class:`SpecTable` and its tables): unknown
keys, types (strict: ``"3"`` is no integer, ``3`` no text) and the simple ranges that need
no parameter set (``steps >= 2``, ``samples <= MAX_POINTS``, ``a > 0`` ...).  The first
pydantic error becomes a :class:`SpecError` that names the key
(``vary.params.flexure_thickness.steps``), its value and what is allowed there
(:func:`translate_error`).  Everything that depends on the concept (its parameters, their
units, ranges and choices) is checked afterwards, when the spec is resolved
(:mod:`.resolve`).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, Strict, ValidationError

from ..core import InputError

#: more points than this in one spec are refused (split the study)
MAX_POINTS = 100_000

#: the value of a :class:`SpecError` whose key is missing
MISSING = object()


class SpecError(InputError):
    """A study spec key has a value that is not allowed (names key, value and what is allowed)."""

    def __init__(self, key: str, value: Any, allowed: str, source: str = ""):
        self.key, self.value, self.allowed, self.source = key, value, allowed, source
        where = f"study spec {source}" if source else "study spec"
        if value is MISSING:
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


class StrictTable(BaseModel):
    """A TOML table: unknown keys refused, frozen."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class DesignTable(StrictTable):
    """``[design]``: a concept (with ``[design.set]``) or a user mesh."""

    concept: Text | None = None
    mesh: Text | None = None
    set: dict[str, Any] = {}


class RequirementsTable(StrictTable):
    """``[requirements]``: the factors a, b and the minimum yield safety factor."""

    a: Annotated[Float, Field(gt=0, allow_inf_nan=False)] = 1.3
    b: Annotated[Float, Field(gt=0, allow_inf_nan=False)] = 1.0
    min_safety_factor: Annotated[Float, Field(ge=0, allow_inf_nan=False)] = 1.0


class AxisTable(StrictTable):
    """One varied parameter of ``[vary.params]``: a range or a list of values."""

    min: Any = None
    max: Any = None
    steps: Annotated[Int, Field(ge=2, le=MAX_POINTS)] | None = None
    step: Any = None
    values: list[Any] | None = None

    def raw(self) -> dict:
        """The keys given (for an error message)."""
        return self.model_dump(exclude_none=True)


class VaryTable(StrictTable):
    """``[vary]``: the method, its samples and seed, and the varied parameters."""

    method: Literal["grid", "list", "lhs", "sobol"] = "grid"
    samples: Annotated[Int, Field(ge=1, le=MAX_POINTS)] | None = None
    seed: Annotated[Int, Field(ge=0, le=2 ** 63 - 1)] = 0
    params: dict[str, AxisTable]


class ErrorsTable(StrictTable):
    """``[errors]``: how many designs also get their error estimate."""

    sample: Annotated[Int, Field(ge=0, le=1000)] = 3


class SpecTable(StrictTable):
    """The whole spec file."""

    design: DesignTable
    settings: dict[str, Any] = {}
    requirements: RequirementsTable = RequirementsTable()
    errors: ErrorsTable = ErrorsTable()
    vary: VaryTable


_TABLES = {(): SpecTable, ("design",): DesignTable, ("requirements",): RequirementsTable, ("vary",): VaryTable,
           ("errors",): ErrorsTable}


def translate_error(exc: ValidationError, raw: dict, source: str) -> SpecError:
    """The first error of a failed :class:`SpecTable` validation of ``raw`` (the parsed
    TOML) as a :class:`SpecError` naming the key, its value and what is allowed."""
    err = exc.errors()[0]
    loc = tuple(str(x) for x in err["loc"])
    key = ".".join(loc) or "(top level)"
    value: Any = raw
    for part in loc:
        value = value.get(part, MISSING) if isinstance(value, dict) else MISSING
    kind = err["type"]
    if kind == "missing":
        what = {"design": "a [design] table with concept = NAME or mesh = FILE",
                "vary": "a [vary] table with [vary.params] (the varied parameters)",
                "vary.params": "the varied parameters, e.g. flexure_thickness = {min = \"1.5mm\", max = \"2.5mm\", "
                               "steps = 3}"}
        return SpecError(key, MISSING, what.get(key, "required"), source)
    if kind == "extra_forbidden":
        parent = loc[:-1]
        if len(parent) == 3 and parent[:2] == ("vary", "params"):
            known = list(AxisTable.model_fields)
        else:
            known = list(_TABLES.get(parent, SpecTable).model_fields)
        return SpecError(key, err.get("input"), "unknown key; allowed here: " + ", ".join(known), source)
    if kind == "literal_error":
        return SpecError(key, err.get("input"), "one of " + str(err["ctx"]["expected"]).replace(" or ", ", "), source)
    allowed = err["msg"].replace("Input should be ", "")
    for words, sym in (("greater than or equal to ", ">= "), ("less than or equal to ", "<= "),
                       ("greater than ", "> "), ("less than ", "< ")):
        allowed = allowed.replace(words, sym)
    if kind in ("greater_than_equal", "less_than_equal", "greater_than", "less_than") and key.endswith(
            ("steps", "samples", "seed")):
        allowed = "an integer " + allowed
    if kind in ("float_type", "int_type", "string_type", "dict_type", "list_type", "model_type"):
        allowed = {"float_type": "a number", "int_type": "an integer (no quotes, no decimals)",
                   "string_type": "a text in quotes", "dict_type": "a table",
                   "list_type": "a list [..]", "model_type": "a table"}[kind]
        if key.startswith("vary.params.") and len(loc) == 3:
            allowed = ("a table {min = .., max = .., steps = ..} or {values = [..]}")
    return SpecError(key, err.get("input", value), allowed, source)
