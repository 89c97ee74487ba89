"""Base layer: errors, units and quantity parsing, typed parameter sets, materials, strict JSON,
pyplot-free figures, root finding and process settings.  Imports nothing else of clutchfem.
"""

from .errors import ClutchfemError, GeometryError, InputError, MeshError, ParameterError, SolverError
from .figures import figure, figure_record, save_figure, tag_png
from .jsonio import clean, dumps, write
from .materials import Material, get_material
from .params import ParamSet, choice, param
from .roots import brentq
from .runtime import tune_malloc
from .units import UnitError, expected_text, format_quantity, parse_quantity, rad_s_to_rpm, rpm_to_rad_s, wrap_angle

__all__ = ["UnitError", "expected_text", "format_quantity", "parse_quantity", "ClutchfemError", "GeometryError", "InputError", "Material", "MeshError", "ParamSet", "ParameterError", "SolverError", "brentq", "choice", "clean", "dumps", "figure", "get_material", "param", "rad_s_to_rpm", "figure_record", "save_figure", "tag_png", "rpm_to_rad_s", "tune_malloc", "wrap_angle", "write"]
