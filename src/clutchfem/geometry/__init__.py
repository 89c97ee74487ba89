"""Parametric concept geometries (gmsh OCC) and their discovery."""

from .base import Annotation, Concept, ConceptParams, MeshSettings, Shapes
from .registry import concepts, get_concept

__all__ = ["Annotation", "Concept", "ConceptParams", "MeshSettings", "Shapes", "concepts", "get_concept"]
