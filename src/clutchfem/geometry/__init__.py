"""Geometry stage: concepts as plug-ins (one file each in ``geometries/``), the generic gmsh
OCC pipeline that turns a concept and its parameters into a meshable model, and drawings.

A concept file imports what it needs from here: the contract (:class:`Concept`,
:class:`ConceptParams`, :class:`Shapes`, :class:`Annotation`) and the drawing toolkits
:mod:`.occ` (rounded annular sectors and other OCC primitives) and :mod:`.sketch` (one
analytic outline with exact tangent fillets)."""

from . import occ, sketch
from .build import MESH_PIPELINE, BuiltModel, build_model, disc_size_field, source_files, source_hash
from .concept import MESH_PRESETS, Annotation, Concept, ConceptParams, MeshSettings, Shapes, default_free, worn_from
from .curves import OCC_TOLERANCE, CurveFrame, curve_frame, occ_tolerances
from .drawing import draw_concept, fmt_param_value
from .profile import MIN_PROFILE_CLEARANCE, TABLE_FIELDS, TABLE_N, table_cardinal, table_spline
from .registry import broken_concepts, concepts, get_concept, load_concept_file
from .session import gmsh_session

__all__ = ["default_free", "MESH_PRESETS", "broken_concepts", "MIN_PROFILE_CLEARANCE", "TABLE_FIELDS", "TABLE_N", "Annotation", "BuiltModel", "Concept", "ConceptParams",
           "MeshSettings", "Shapes", "OCC_TOLERANCE", "CurveFrame", "curve_frame", "occ_tolerances", "build_model", "disc_size_field", "concepts", "draw_concept", "fmt_param_value",
           "get_concept", "gmsh_session", "load_concept_file", "occ", "sketch", "source_files", "source_hash", "MESH_PIPELINE", "table_cardinal", "worn_from",
           "table_spline"]
