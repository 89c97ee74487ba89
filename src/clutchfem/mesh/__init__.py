"""Meshing stage: gmsh model -> curved P2 ``ClutchMesh`` with named groups, the on-disk mesh
cache, user ``.msh``/STEP import.
"""

from .meshing import ClutchMesh, groups_msh_path, load_user_geometry, mesh_concept, source_hash
from .properties import element_moments, mesh_area_properties, mesh_mass_properties

__all__ = ["ClutchMesh", "groups_msh_path", "load_user_geometry", "mesh_concept", "source_hash",
           "element_moments", "mesh_area_properties", "mesh_mass_properties"]
