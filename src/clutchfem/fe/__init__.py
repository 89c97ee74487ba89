"""FE stage: the 2-D, thick plane (2-D with through-thickness modes) and 3-D linear-elastic models of the spinning part (K, f1, constraints,
one factorisation), stress recovery with the one von Mises, sparse direct solvers and
``.vtu`` field output."""

from .geometric import Kinematics, geometric_stiffness
from .linsolve import COUNTS, Solver, available, factorize, one_blas_thread
from .model import ConstrainedOperators, FEModel, constraint_map, contact_weights
from .model3d import (
                      ExtrudedMesh,
                      ExtrusionSettings,
                      FEModel3D,
                      build_fe_model_3d,
                      component_dofs,
                      contact_area_weights,
                      extrude,
                      geometric_stiffness_3d,
                      lame_3d,
)
from .peak import PeakLevel, PeakStress, free_spin_peak, peak_disc, peak_stress_converged, richardson
from .ring import CELL_EDGES, ZONES, RingMesh, pvd_text, ring_stresses, zone_ids
from .size3d import check_3d_size, estimate_3d, max_model_memory
from .stress import VertexStress, VertexStress3D, p2_vertex_gradients, von_mises
from .thick import FEModelThick, ThickSettings, ThickStress, thick_modes
from .vtu import Frames2D, in_plane_stresses, write_vtk
from .vtu3d import Frames3D, tetra10_cells

__all__ = ["PeakLevel", "PeakStress", "free_spin_peak", "peak_disc", "peak_stress_converged", "richardson", "COUNTS", "ConstrainedOperators", "ExtrudedMesh", "ExtrusionSettings", "FEModel", "FEModel3D",
           "FEModelThick", "ThickSettings", "ThickStress", "p2_vertex_gradients", "thick_modes",
           "Kinematics", "geometric_stiffness",
           "Solver", "VertexStress", "VertexStress3D", "available", "build_fe_model_3d", "component_dofs",
           "constraint_map", "contact_area_weights", "contact_weights", "extrude", "factorize",
           "geometric_stiffness_3d", "lame_3d", "check_3d_size", "estimate_3d", "max_model_memory", "one_blas_thread", "von_mises", "write_vtk",
           "CELL_EDGES", "Frames2D", "Frames3D", "tetra10_cells", "ZONES", "RingMesh", "in_plane_stresses", "pvd_text", "ring_stresses", "zone_ids"]
