"""Units: the one parser of quantities with a unit suffix, and how a quantity is shown.

SI inside clutchfem, with three exceptions designers expect in parameter sets: angles in
degrees, speeds in rpm and temperatures in degrees Celsius.  Every quantity a user types,
in ``--set name=value``, a CLI option (``--drum-radius 34.4mm``, ``--E 200GPa``,
``--idle-rpm 2700rpm``) or the Python API (``OperatingPoint(drum_radius="34.4mm")``), goes
through :func:`parse_quantity`: a number with an optional unit suffix *of the field's own
dimension* (a length takes ``mm``, never ``deg``), converted exactly (decimal arithmetic: ``9mm``
is 0.009 m, not 0.009000000000000001).  Every value a user reads goes through
:func:`format_quantity`, in the unit designers use for it (mm for lengths, MPa for stresses).

Why not pint: clutchfem needs a closed table of about a dozen dimensions, exact decimal
conversion and messages that name the accepted suffixes; pint adds ~0.4 s to the import,
its own error types and floating-point conversion factors.
"""

from __future__ import annotations

import math
import re
from decimal import Decimal, InvalidOperation

import numpy as np

__all__ = ["DISPLAY", "RPM_PER_RAD_S", "UnitError", "accepted_suffixes", "deg", "dimension", "display_value",
           "format_quantity", "header_unit", "header_units", "mm", "parse_quantity", "rad_s_to_rpm", "rpm_to_rad_s", "wrap_angle"]

RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)

#: the accepted suffixes of each canonical unit: suffix -> (factor, offset) with
#: value_canonical = number * factor + offset.  The canonical unit is the one a parameter is
#: declared in (``param(default, "m", ...)``).
_TABLE: dict[str, dict[str, tuple[str, str]]] = {
    "m": {"m": ("1", "0"), "cm": ("0.01", "0"), "mm": ("0.001", "0"), "um": ("0.000001", "0"),
          "µm": ("0.000001", "0"), "in": ("0.0254", "0")},
    "deg": {"deg": ("1", "0"), "°": ("1", "0"), "rad": (repr(180.0 / math.pi), "0")},
    "Pa": {"Pa": ("1", "0"), "kPa": ("1000", "0"), "MPa": ("1000000", "0"), "GPa": ("1000000000", "0"),
           "N/mm2": ("1000000", "0"), "N/mm^2": ("1000000", "0"), "psi": (repr(6894.757293168361), "0"),
           "ksi": (repr(6894757.293168361), "0")},
    "rpm": {"rpm": ("1", "0"), "1/min": ("1", "0"), "rad/s": (repr(RPM_PER_RAD_S), "0"), "Hz": ("60", "0")},
    "kg": {"kg": ("1", "0"), "g": ("0.001", "0")},
    "kg/m^3": {"kg/m^3": ("1", "0"), "kg/m3": ("1", "0"), "g/cm^3": ("1000", "0"), "g/cm3": ("1000", "0")},
    "N m": {"Nm": ("1", "0"), "N m": ("1", "0"), "N*m": ("1", "0"), "N·m": ("1", "0"), "Ncm": ("0.01", "0"),
            "N cm": ("0.01", "0"), "kgf m": ("9.80665", "0"), "kgfm": ("9.80665", "0"),
            "lbf ft": (repr(1.3558179483314004), "0"), "ft lbf": (repr(1.3558179483314004), "0"),
            "lbf in": (repr(0.1129848290276167), "0"), "in lbf": (repr(0.1129848290276167), "0")},
    "s": {"s": ("1", "0"), "ms": ("0.001", "0"), "min": ("60", "0"), "h": ("3600", "0")},
    "C": {"C": ("1", "0"), "°C": ("1", "0"), "degC": ("1", "0"), "K": ("1", "-273.15")},
    "kg m^2": {"kg m^2": ("1", "0"), "kg m2": ("1", "0"), "kgm^2": ("1", "0"), "kgm2": ("1", "0"),
               "kg*m^2": ("1", "0"), "g cm^2": ("0.0000001", "0"), "g cm2": ("0.0000001", "0")},
    "W/(m^2 K)": {"W/(m^2 K)": ("1", "0"), "W/m^2K": ("1", "0"), "W/m2K": ("1", "0"), "W/(m2 K)": ("1", "0")},
    "W/(m K)": {"W/(m K)": ("1", "0"), "W/mK": ("1", "0"), "W/(mK)": ("1", "0")},
    "J/(kg K)": {"J/(kg K)": ("1", "0"), "J/kgK": ("1", "0"), "J/(kgK)": ("1", "0")},
    "W": {"W": ("1", "0"), "kW": ("1000", "0")},
    "1/h": {"1/h": ("1", "0"), "/h": ("1", "0"), "1/min": ("60", "0")},
}
#: units written in table headers (an engine curve's CSV: ``torque [lbf ft]``, ``speed
#: (U/min)``), keyed by the compact form :func:`header_unit` reduces a header's unit to
#: (lower case, no spaces or separators ``· . * - _``): canonical unit -> {compact: factor}.
#: Only unit names whose meaning does not depend on the case of a prefix letter are here
#: (no mN m / MN m); the factors are exact or the defined conversions (1 lbf = 4.4482216152605 N,
#: 1 ft = 0.3048 m, 1 in = 0.0254 m, 1 kgf = 1 kp = 9.80665 N, 1 ozf = 0.27801385095378125 N).
_HEADER_UNITS: dict[str, dict[str, str]] = {
    "N m": {"nm": "1", "newtonmetre": "1", "newtonmeter": "1", "ncm": "0.01", "nmm": "0.001", "knm": "1000",
            "kgfm": "9.80665", "kpm": "9.80665", "kgm": "9.80665", "kgfcm": "0.0980665", "kpcm": "0.0980665",
            "lbfft": "1.3558179483314004", "ftlbf": "1.3558179483314004", "lbft": "1.3558179483314004",
            "ftlb": "1.3558179483314004", "ftlbs": "1.3558179483314004", "lbsft": "1.3558179483314004",
            "lbfin": "0.1129848290276167", "inlbf": "0.1129848290276167", "lbin": "0.1129848290276167",
            "inlb": "0.1129848290276167", "inlbs": "0.1129848290276167", "lbsin": "0.1129848290276167",
            "ozfin": "0.007061551814226", "ozin": "0.007061551814226", "inoz": "0.007061551814226"},
    "rpm": {"rpm": "1", "1/min": "1", "min^1": "1", "min1": "1", "/min": "1", "r/min": "1", "rev/min": "1",
            "revmin": "1", "u/min": "1", "upm": "1", "tr/min": "1", "obmin": "1", "об/мин": "1", "obr/min": "1",
            "rps": "60", "r/s": "60", "rev/s": "60", "hz": "60", "rad/s": repr(RPM_PER_RAD_S),
            "krpm": "1000"},
}
#: the dimension's name, for messages
_NAMES = {"m": "a length", "deg": "an angle", "Pa": "a stress", "rpm": "a speed", "kg": "a mass",
          "kg/m^3": "a density", "N m": "a torque", "s": "a time", "C": "a temperature", "kg m^2": "an inertia",
          "W/(m^2 K)": "a heat transfer coefficient", "W/(m K)": "a conductivity",
          "J/(kg K)": "a specific heat", "W": "a power",
          "1/h": "a rate (events per hour)"}
#: the unit a value of each canonical unit is shown in, with its factor (shown = value * factor)
DISPLAY: dict[str, tuple[str, float]] = {"m": ("mm", 1e3), "Pa": ("MPa", 1e-6)}
#: the typographic minus sign (U+2212, what a word processor or a web page puts for "-"): read as "-"
MINUS_SIGN = "\u2212"
#: a number written with a decimal comma (``2,4mm``): said as such, not as a wrong unit
_DECIMAL_COMMA = re.compile(r"\s*([-+]?\d+),(\d+)\s*(.*?)\s*$")
_NUMBER = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?inf|nan)\s*(.*?)\s*$", re.IGNORECASE)


class UnitError(ValueError):
    """A quantity that cannot be read; ``expected`` says what the field accepts.

    Attributes
    ----------
    raw : object
        What was given.
    expected : str
        What the field accepts (its dimension, canonical unit and suffixes).

    Examples
    --------
    >>> import clutchfem as cf
    >>> try:
    ...     cf.parse_quantity("80deg", "m")            # an angle where a length is wanted
    ... except cf.UnitError as e:
    ...     print(e.raw, "|", e.expected)
    80deg | a length in m (unit suffix m, cm, mm, um, µm, in)
    """

    def __init__(self, raw, expected: str):
        self.raw = raw
        self.expected = expected
        super().__init__(f"{raw!r}: expected {expected}")


def dimension(unit: str) -> str:
    """The dimension's name of a canonical unit (``"m"`` -> ``"a length"``)."""
    return _NAMES.get(unit, "a number")


def accepted_suffixes(unit: str) -> list[str]:
    """The unit suffixes a field declared in ``unit`` accepts (none for a dimensionless one)."""
    return list(_TABLE.get(unit, {}))


def expected_text(unit: str) -> str:
    """What a field in ``unit`` accepts, for messages: ``a length in m (suffix m, cm, mm, ...)``."""
    if unit in _TABLE:
        return f"{dimension(unit)} in {unit} (unit suffix {', '.join(_TABLE[unit])})"
    if unit in ("-", ""):
        return "a plain number (dimensionless: no unit suffix)"
    return f"a plain number in {unit} (no unit suffix)"


def parse_quantity(raw, unit: str) -> float:
    """The value in canonical ``unit`` of ``raw``: a number, or a string ``"<number>[suffix]"``
    whose suffix belongs to ``unit``'s dimension (:data:`_TABLE`; a dimensionless field takes
    no suffix).  Raises :class:`UnitError` (what was given, what is accepted); the caller
    names the parameter.  Non-finite values are returned as they are (ranges refuse them).

    Parameters
    ----------
    raw : float or str
        A number (already in ``unit``) or a text such as ``"9mm"``, ``"200GPa"``, ``"2700 rpm"``.
    unit : str
        The field's canonical unit: ``"m"``, ``"deg"``, ``"Pa"``, ``"rpm"``, ``"C"``, ... or
        ``"-"`` (dimensionless).

    Returns
    -------
    float
        The value in ``unit``, converted exactly (decimal arithmetic).

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.parse_quantity("9mm", "m"), cf.parse_quantity("2700 rpm", "rpm"), cf.parse_quantity(" 80deg", "deg")
    (0.009, 2700.0, 80.0)
    >>> cf.parse_quantity("200GPa", "Pa"), cf.parse_quantity("673.15K", "C"), cf.parse_quantity(0.3, "-")
    (200000000000.0, 400.0, 0.3)
    """
    if isinstance(raw, bool):
        raise UnitError(raw, expected_text(unit))
    if isinstance(raw, (int, float, np.integer, np.floating)):
        return float(raw)
    if not isinstance(raw, str):
        raise UnitError(raw, expected_text(unit))
    text = raw.replace(MINUS_SIGN, "-")  # the typographic minus (Unicode U+2212) is a minus
    comma = _DECIMAL_COMMA.fullmatch(text)
    if comma:
        raise UnitError(raw, f"a number with a decimal point, not a decimal comma ({comma.group(1)}."
                             f"{comma.group(2)}{comma.group(3)}); {expected_text(unit)}")
    m = _NUMBER.fullmatch(text)
    if not m:
        raise UnitError(raw, expected_text(unit))
    number, suffix = m.group(1), m.group(2).strip()
    try:
        d = Decimal(number)
    except InvalidOperation:
        raise UnitError(raw, expected_text(unit)) from None
    if not suffix:
        return float(d)
    table = _TABLE.get(unit)
    match = None
    if table is not None:
        match = table.get(suffix) or next((v for k, v in table.items() if k.lower() == suffix.lower()
                                           and _case_insensitive(k)), None)
    if match is None:
        raise UnitError(raw, expected_text(unit))
    if not d.is_finite():
        return float(d)
    factor, offset = match
    return float(d * Decimal(factor) + Decimal(offset))


def _case_insensitive(suffix: str) -> bool:
    # mm/MM and rpm/RPM are the same; m (milli) and M (mega) prefixes are not: only suffixes
    # without a prefix letter that changes meaning with case are matched case-insensitively
    return suffix.lower() in {"rpm", "deg", "rad", "nm", "n m", "kg", "in", "hz", "psi", "ksi", "degc"}


def header_unit(text: str, unit: str) -> float | None:
    """The factor to the canonical ``unit`` (``"N m"`` or ``"rpm"``) of a unit written in a
    table header (``"lbf ft"``, ``"N·m"``, ``"U/min"``: :data:`_HEADER_UNITS`), or None when
    it is not a known unit of that dimension.

    >>> round(header_unit("lbf·ft", "N m"), 12), header_unit("N cm", "N m"), header_unit("1/min", "rpm")
    (1.355817948331, 0.01, 1.0)
    >>> header_unit("bar", "N m") is None
    True
    """
    compact = re.sub(r"[\s·.*\-_]+", "", str(text)).lower().replace("⁻¹", "^1").replace("^-1", "^1")
    factor = _HEADER_UNITS.get(unit, {}).get(compact)
    return None if factor is None else float(Decimal(factor))


def header_units(unit: str) -> list[str]:
    """Examples of the header units :func:`header_unit` knows for ``unit``, for messages."""
    return {"N m": ["N m", "N cm", "N mm", "kN m", "kgf m", "kgf cm", "lbf ft", "lbf in", "ozf in"],
            "rpm": ["rpm", "1/min", "r/min", "U/min", "tr/min", "rev/s", "Hz", "rad/s"]}.get(unit, [])


def display_value(value: float, unit: str) -> tuple[float, str]:
    """``(value, unit)`` in the unit a designer reads (:data:`DISPLAY`: mm, MPa)."""
    if unit in DISPLAY:
        u, f = DISPLAY[unit]
        return value * f, u
    return value, unit


def format_quantity(value, unit: str, digits: int = 6) -> str:
    """``value`` (canonical ``unit``) as text in its display unit with ``digits`` significant
    digits and no float noise: ``format_quantity(0.019, "m")`` -> ``'19 mm'``.

    Parameters
    ----------
    value : float
        The value in ``unit`` (anything else is shown as ``str(value)``).
    unit : str
        Its canonical unit; lengths are shown in mm and stresses in MPa (:data:`DISPLAY`),
        other units as they are, ``"-"`` without a unit.
    digits : int
        Significant digits.

    Returns
    -------
    str
        The number and its display unit.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.format_quantity(0.009000000000000001, "m"), cf.format_quantity(1.25e9, "Pa")
    ('9 mm', '1250 MPa')
    >>> cf.format_quantity(8123.4567, "rpm", digits=4), cf.format_quantity(0.3, "-")
    ('8123 rpm', '0.3')
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        return str(value)
    v, u = display_value(float(value), unit)
    text = f"{v:.{digits}g}"
    return text if u in ("-", "") else f"{text} {u}"


def rpm_to_rad_s(rpm):
    """Angular speed in rpm -> rad/s (works on floats and numpy arrays)."""
    if np.ndim(rpm):
        return np.asarray(rpm, dtype=float) / RPM_PER_RAD_S
    return float(rpm) / RPM_PER_RAD_S


def rad_s_to_rpm(omega):
    """Angular speed in rad/s -> rpm (works on floats and numpy arrays)."""
    if np.ndim(omega):
        return np.asarray(omega, dtype=float) * RPM_PER_RAD_S
    return float(omega) * RPM_PER_RAD_S


def mm(x: float) -> float:
    """Millimetres -> metres (for readable defaults: ``mm(34.4)``)."""
    return x * 1e-3


def deg(x: float) -> float:
    """Degrees -> radians."""
    return math.radians(x)


def wrap_angle(a, ref: float = 0.0):
    """Angle(s) [rad] shifted by whole turns into [ref - pi, ref + pi): the one place where
    polar angles are unwrapped (around a shoe, a pivot ray, a mean direction)."""
    out = ref + (np.asarray(a, dtype=float) - ref + math.pi) % (2 * math.pi) - math.pi
    return float(out) if np.ndim(out) == 0 else out
