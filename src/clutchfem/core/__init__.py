"""Base layer: errors, units and quantity parsing, typed parameter sets and the parameter values
that survive ``--set`` (:mod:`.values`), materials, strict JSON,
pyplot-free figures, root finding and process settings.  Imports nothing else of clutchfem.

The names are imported on first use (PEP 562, as :mod:`clutchfem` does): an error class
or the unit parser does not load scipy (``roots``: 0.7 s) or pydantic (``params``), so
``clutchfem --help``, a refusal and a rerun of a finished study answer quickly.
"""

from __future__ import annotations

from .lazy import lazy_names

#: public name -> the module of this package it lives in
_NAMES: dict[str, str | None] = {
    "changed_texts": "values",
    "exact_text": "values",
    "param_bounds": "values",
    "resolution": "values",
    "round12": "values",
    "values": None,
    "as_bool": "args",
    "as_path": "args",
    "brentq": "roots",
    "wilson": "stats",
    "choice": "params",
    "clean": "jsonio",
    "ClutchfemError": "errors",
    "dumps": "jsonio",
    "expected_text": "units",
    "figure": "figures",
    "figure_record": "figures",
    "format_quantity": "units",
    "GeometryError": "errors",
    "get_material": "materials",
    "header_unit": "units",
    "header_units": "units",
    "EquilibriumError": "errors",
    "InputError": "errors",
    "Material": "materials",
    "MeshError": "errors",
    "param": "params",
    "ParameterError": "errors",
    "ParamSet": "params",
    "parse_quantity": "units",
    "rad_s_to_rpm": "units",
    "rpm_to_rad_s": "units",
    "save_figure": "figures",
    "SolverError": "errors",
    "tag_png": "figures",
    "tune_malloc": "runtime",
    "default_fidelity": "runtime",
    "FIDELITY_ENV": "runtime",
    "lazy_names": "lazy",
    "UnitError": "units",
    "wrap_angle": "units",
    "write": "jsonio",
}

__all__ = sorted(_NAMES)


__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
