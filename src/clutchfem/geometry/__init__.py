"""Geometry stage: concepts as plug-ins (one file each in ``geometries/``), the generic gmsh
OCC pipeline that turns a concept and its parameters into a meshable model, and drawings."""

from .concept import Annotation, BuiltModel, Concept, ConceptParams, MeshSettings, Shapes, build_model
from .drawing import draw_concept, draw_mesh, fmt_param_value
from .profile import MIN_PROFILE_CLEARANCE, TABLE_FIELDS, TABLE_N, table_spline
from .registry import concepts, get_concept, load_concept_file
from .session import gmsh_session

__all__ = ["MIN_PROFILE_CLEARANCE", "TABLE_FIELDS", "TABLE_N", "Annotation", "BuiltModel", "Concept", "ConceptParams", "MeshSettings",
           "Shapes", "build_model", "concepts", "draw_concept", "draw_mesh", "fmt_param_value", "get_concept", "gmsh_session", "load_concept_file", "table_spline"]
