"""Meshing stage: gmsh model -> curved P2 ``ClutchMesh`` with named groups, the on-disk mesh
cache, user ``.msh``/STEP import.
"""

from .generate import ClutchMesh, groups_msh_path, load_user_geometry, mesh_concept, source_hash

__all__ = ["ClutchMesh", "groups_msh_path", "load_user_geometry", "mesh_concept", "source_hash"]
