"""Meshing stage: gmsh model -> curved P2 ``ClutchMesh`` with named groups, the on-disk mesh
cache, user ``.msh``/STEP import, and the mesh topology the later stages share.

* :mod:`.clutch_mesh` -- :class:`ClutchMesh`, the meshed part and its named groups;
* :mod:`.convert` -- meshio -> scikit-fem ``MeshTri2``, the element orientation check;
* :mod:`.generate` -- a concept meshed by gmsh, the cache keys, the size estimate;
* :mod:`.cache` -- the on-disk mesh cache: its folder, bound and eviction;
* :mod:`.user` -- a user's ``.msh``, STEP or DXF file;
* :mod:`.user_checks` -- what a user's part must be: axis, unit, one piece, triangles;
* :mod:`.outline` -- a part's exact 2-D outline (lines, arcs, B-splines), its loops chained
  from loose segments, and its OCC face;
* :mod:`.cad` -- a STEP (in its declared unit; a prism along z) or DXF part as planar surfaces;
* :mod:`.dxf` -- a DXF drawing's outline (what a cutter's file holds) as outline loops;
* :mod:`.topology` -- P2 nodes, facet nodes and cells, areas and perimeters of element sets;
* :mod:`.cyclic` -- the node pairing of the two cut lines of a one-sector model;
* :mod:`.morph` -- a design's mesh moved from a reference design's (mesh morphing);
* :mod:`.quality` -- element quality, and of a moved mesh against its reference;
* :mod:`.highorder` -- the guard against nearly degenerate curved elements after meshing;
* :mod:`.properties` -- area, first moments and mass properties of the mesh (per zone);
* :mod:`.picture` -- a quick picture of a mesh with its named boundary groups;
* :mod:`.location` -- the name of a place in the part (zone, flexure end, boundary): the worst
  fatigue point, the hottest slip-heat points.
"""

from .cache import CacheEntry, cache_dir, cache_entries, cache_foreign_files, cache_limit, clear_cache, evict
from .cad import import_planar, step_unit
from .clutch_mesh import ClutchMesh, named_boundary
from .convert import check_orientation, meshio_to_skfem, read_msh
from .cyclic import cyclic_pairing
from .generate import MAX_ELEMENTS, cache_key, estimate_elements, groups_msh_path, mesh_concept, source_hash
from .highorder import GUARD_MIN_SJ, MAX_SAGITTA, GuardReport, guard_high_order, p2_scaled_jacobian
from .location import Location, describe_node, name_location, zone_of_node
from .morph import (
                       CACHE_SIZE,
                       MorphReference,
                       MorphRefused,
                       morph_or_mesh,
                       morph_reference,
                       morph_to,
                       quality_of,
                       reference_key,
)
from .outline import Loop, Segment, chain_loops, fit_spline, loops_to_occ, orient_loops
from .picture import draw_mesh
from .properties import element_moments, mesh_area_properties, mesh_mass_properties
from .quality import MAX_DISTORTION, MIN_SCALED_JACOBIAN, MorphQuality, assess, distortion, scaled_jacobian
from .topology import (
                       element_components,
                       element_set_area,
                       element_set_perimeter,
                       facet_nodes,
                       facet_numbers,
                       is_quadratic,
                       p2_basis,
                       p2_cells,
                       p2_nodes,
)
from .user import load_user_geometry
from .user_checks import AXIS_TOLERANCE, PLAUSIBLE_RADIUS, bore_centre, step_length_unit

__all__ = ["Location", "describe_node", "name_location", "zone_of_node", "draw_mesh", "GUARD_MIN_SJ", "MAX_SAGITTA", "GuardReport", "guard_high_order", "p2_scaled_jacobian", "CACHE_SIZE", "MAX_DISTORTION", "MIN_SCALED_JACOBIAN", "MorphQuality", "MorphReference", "MorphRefused",
           "assess", "distortion", "morph_or_mesh", "morph_reference", "morph_to", "quality_of", "reference_key",
           "scaled_jacobian", "AXIS_TOLERANCE", "MAX_ELEMENTS", "PLAUSIBLE_RADIUS", "CacheEntry", "ClutchMesh", "Loop", "Segment",
           "bore_centre", "cache_entries", "cache_foreign_files", "chain_loops", "cache_limit", "clear_cache", "evict", "fit_spline", "import_planar",
           "loops_to_occ", "orient_loops", "step_length_unit", "step_unit", "cache_dir", "cache_key",
           "check_orientation", "cyclic_pairing",
           "element_components", "element_moments", "element_set_area", "element_set_perimeter",
           "estimate_elements", "facet_numbers", "facet_nodes", "groups_msh_path", "is_quadratic",
           "load_user_geometry", "mesh_area_properties", "mesh_concept", "mesh_mass_properties", "meshio_to_skfem", "named_boundary",
           "p2_basis", "p2_cells", "p2_nodes", "read_msh", "source_hash"]
