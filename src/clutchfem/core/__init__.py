"""Base layer: errors, units and quantity parsing, typed parameter sets, materials, strict JSON,
pyplot-free figures, root finding and process settings.  Imports nothing else of clutchfem.

The names are imported on first use (PEP 562, as :mod:`clutchfem` does): an error class
or the unit parser does not load scipy (``roots``: 0.7 s) or pydantic (``params``), so
``clutchfem --help``, a refusal and a rerun of a finished study answer quickly.
"""

from __future__ import annotations

import importlib
from typing import Any

#: public name -> the module of this package it lives in
_NAMES: dict[str, str] = {
    "as_bool": "args",
    "as_path": "args",
    "brentq": "roots",
    "choice": "params",
    "clean": "jsonio",
    "ClutchfemError": "errors",
    "dumps": "jsonio",
    "expected_text": "units",
    "figure": "figures",
    "format_quantity": "units",
    "GeometryError": "errors",
    "get_material": "materials",
    "header_unit": "units",
    "header_units": "units",
    "InputError": "errors",
    "Material": "materials",
    "MeshError": "errors",
    "param": "params",
    "ParameterError": "errors",
    "ParamSet": "params",
    "parse_quantity": "units",
    "rad_s_to_rpm": "units",
    "rpm_to_rad_s": "units",
    "SolverError": "errors",
    "tune_malloc": "runtime",
    "UnitError": "units",
    "wrap_angle": "units",
    "write": "jsonio",
}

__all__ = sorted(_NAMES)


def __getattr__(name: str) -> Any:
    """Import a name on first use (PEP 562) and keep it."""
    if name not in _NAMES:
        raise AttributeError(f"module 'clutchfem.core' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_NAMES[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_NAMES))
