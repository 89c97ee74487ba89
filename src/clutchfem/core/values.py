"""Parameter values that survive the round trip through ``--set name=value``.

An optimiser, a compensation or a tolerance study proposes real numbers; a designer reads
them, types them into ``clutchfem analyze --set ...`` and must get *the same design*, bit
for bit (the mesh cache key is a hash of the parameters: 2.1000000000000001 mm is another
mesh).  So every proposed value is snapped to a resolution, written as text with its unit
suffix (``"2.13mm"``, ``"31.4deg"``, ``"1.285"``) and read back through the parameter set's
own parser (:meth:`clutchfem.core.ParamSet.parse_value`); the design that is evaluated
is the one built from that text.

Resolutions (ASSUMED, a drawing's usual precision): lengths 0.01 mm (clearances 0.001 mm;
the table profile's clearances 1 nm, a model input: see :mod:`clutchfem.targets.compensation`
for why), angles 0.1 deg, dimensionless 0.001.

Also here, for every study: a parameter's declared range (:func:`param_bounds`) and the
12-significant-digit rounding (:func:`round12`) that makes ``"1.8mm"`` the value 0.0018
(not 0.0018000000000000002) in a spec, a grid, a finite-difference step and a design hash.
"""

from __future__ import annotations

import math

from .errors import ParameterError

#: snapping resolution per unit (in the unit's SI value), see module docstring
RESOLUTION = {"m": 1e-5, "deg": 0.1, "-": 1e-3, "": 1e-3}
#: finer resolution for these parameters
FINE = {"m": 1e-6}
#: the table profile's clearances: 1 nm (the contact pressure on a rigid drum moves by
#: ~7 MPa per um of profile error on concept 4: see clutchfem.targets.compensation)
TABLE = 1e-9


def round12(x: float) -> float:
    """``x`` rounded to 12 significant digits: the float arithmetic of a unit suffix, a grid
    or a step (0.0018000000000000002) falls back on the value typed (0.0018)."""
    return float(f"{x:.12g}")


def param_bounds(P, name: str) -> tuple[float | None, float | None]:
    """(lo, hi) of parameter ``name`` of ParamSet ``P``: its declared range (None: open)."""
    lo = hi = None
    for m in P.model_fields[name].metadata:
        lo = m.ge if getattr(m, "ge", None) is not None else lo
        hi = m.le if getattr(m, "le", None) is not None else hi
    return lo, hi


def resolution(P, name: str) -> float:
    unit = P.unit(name)
    if name.startswith("table_c"):
        return TABLE
    if name in ("clearance", "clearance_tip", "eccentricity"):
        return FINE.get(unit, RESOLUTION.get(unit, 1e-3))
    return RESOLUTION.get(unit, 1e-3)


def _decimals(step: float, scale: float) -> int:
    return max(0, int(round(-math.log10(step / scale))))


def _num(x: float, nd: int) -> str:
    """``x`` with at most ``nd`` decimals, trailing zeros dropped (``2.10`` -> ``2.1``)."""
    t = f"{round(x, nd):.{nd}f}"
    if "." in t:
        t = t.rstrip("0").rstrip(".")
    return "0" if t in ("-0", "") else t


def to_text(P, name: str, value) -> str:
    """``value`` (SI, as stored) written for ``--set``: lengths in mm, angles in deg, others
    plain; snapped to :func:`resolution`."""
    ann = P.model_fields[name].annotation
    if isinstance(value, str):
        return value
    if ann is int:
        return str(int(round(value)))
    unit = P.unit(name)
    step = resolution(P, name)
    if unit == "m":
        return _num(value / 1e-3, _decimals(step, 1e-3)) + "mm"
    return _num(value, _decimals(step, 1.0)) + ("deg" if unit == "deg" else "")


def exact_text(P, name: str, value) -> str:
    """Text that ``--set`` reads back as exactly ``value`` (the shortest of the unit-suffixed
    forms with 0..12 decimals that does; else the value in SI units, ``repr`` digits)."""
    if isinstance(value, str) or P.model_fields[name].annotation is int:
        return to_text(P, name, value)
    unit = P.unit(name)
    scale, suffix = {"m": (1e-3, "mm"), "deg": (1.0, "deg")}.get(unit, (1.0, ""))
    for nd in range(0, 13):
        txt = f"{value / scale:.{nd}f}{suffix}"
        try:
            if from_text(P, name, txt) == value:
                return txt
        except ParameterError:
            break
    return repr(float(value))


def from_text(P, name: str, text: str):
    """The value ``--set name=text`` gives (the parameter set's own parser)."""
    if name not in P.model_fields:
        raise ParameterError(name, text, "a parameter of " + (P.context or P.__name__) + "; known: "
                             + ", ".join(P.model_fields), P.context or P.__name__)
    return P.parse_value(name, text)


def snap(P, name: str, value):
    """(value, text): ``value`` snapped and read back from its ``--set`` text."""
    text = to_text(P, name, value)
    return from_text(P, name, text), text


def snap_all(P, values: dict) -> tuple[dict, dict]:
    """Snap every entry of ``values``: (values read back, texts)."""
    vals, texts = {}, {}
    for k, v in values.items():
        vals[k], texts[k] = snap(P, k, v)
    return vals, texts


def assignments(texts: dict) -> list[str]:
    """``["name=text", ...]`` for ``--set`` (sorted by name for a stable command line)."""
    return [f"{k}={v}" for k, v in texts.items()]


def changed_texts(p, base=None) -> dict:
    """``--set`` texts of every parameter of ``p`` that differs from ``base`` (default: the
    parameter set's defaults); choices as they are.  The table profile's control values are
    listed whenever the profile is 'table'."""
    P = type(p)
    base = base if base is not None else P()
    out = {}
    for name in P.model_fields:
        v, b = getattr(p, name), getattr(base, name)
        table = name.startswith("table_c") and getattr(p, "profile", None) == "table"
        if v != b or table:
            out[name] = exact_text(P, name, v)
    return out
