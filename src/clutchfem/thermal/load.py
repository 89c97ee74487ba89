"""The heat load of a slip state: the friction power at the contact nodes, from the contact
solver's nodal forces (:class:`SlipHeatLoad`, :func:`slip_heat_load`).

The contact solver's nodal forces are consistent: lam_i = int p phi_i h ds over the contact
surface, for the full axial thickness h.  The consistent nodal heat load of the flux
gamma mu v p on that surface is therefore exactly

    Q_i = int gamma mu v p phi_i h ds = gamma mu v lam_i     [W],

no pressure reconstruction, no tributary lengths; v = omega R_d the sliding speed, gamma
the part's share (:mod:`.partition`).  This module holds the friction power mu v lam_i
(gamma = 1).  Node ids are scalar P2 nodes of the clutch mesh (:mod:`clutchfem.mesh.topology`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..core import InputError, ParameterError
from ..mesh import ClutchMesh, p2_basis
from .params import finite_positive

__all__ = ["SlipHeatLoad", "slip_heat_load"]


@dataclass(frozen=True)
class SlipHeatLoad:
    """Friction heat at the contact nodes of one slip state (the model: sector or full part).

    ``node_index`` (m,): scalar P2 node ids on the clutch mesh (= the dofs of skfem's
    ``ElementTriP2`` basis: vertices first, then one per edge; a vector P2 dof d of the
    elastic model belongs to node d // 2).  ``lam_N`` (m,): normal contact forces [N] at
    those nodes, consistent nodal forces for the full axial thickness, >= 0.  ``mu``:
    friction coefficient; ``omega_rad_s``: slip speed of the hub relative to the held drum;
    ``drum_radius_m``: R_d, so v = omega R_d.  Nodal friction power: mu v lam_i [W]
    (before the partition)."""

    node_index: np.ndarray
    lam_N: np.ndarray
    mu: float
    omega_rad_s: float
    drum_radius_m: float

    def __post_init__(self):
        idx = np.asarray(self.node_index)
        lam = np.asarray(self.lam_N, dtype=float) if np.size(self.lam_N) else np.zeros(0)
        if idx.ndim != 1 or lam.ndim != 1 or len(idx) != len(lam):
            raise InputError(f"SlipHeatLoad: node_index and lam_N must be 1-D arrays of equal length "
                             f"(got shapes {np.shape(self.node_index)} and {np.shape(self.lam_N)})")
        if len(idx) == 0:
            raise InputError("SlipHeatLoad: no contact nodes given (node_index is empty)")
        if not np.issubdtype(idx.dtype, np.integer):
            if not np.all(np.isfinite(idx)) or np.any(idx != np.round(idx)):
                raise ParameterError("node_index", self.node_index, "integer node ids >= 0")
            idx = idx.astype(np.int64)
        if np.any(idx < 0):
            raise ParameterError("node_index", int(idx.min()), "integer node ids >= 0")
        if len(np.unique(idx)) != len(idx):
            raise InputError("SlipHeatLoad: node_index lists a node more than once")
        if np.any(~np.isfinite(lam)) or np.any(lam < 0):
            bad = lam[~np.isfinite(lam) | (lam < 0)][0]
            raise ParameterError("lam_N", float(bad), "finite nodal contact forces >= 0 N")
        if not lam.any():
            raise ParameterError("lam_N", 0.0, "at least one contact force > 0 N (the clutch must touch the drum)")
        object.__setattr__(self, "node_index", idx.astype(np.int64))
        object.__setattr__(self, "lam_N", lam)
        mu = finite_positive("mu", self.mu, "a friction coefficient in (0, 1]")
        if mu > 1.0:
            raise ParameterError("mu", self.mu, "a friction coefficient in (0, 1]")
        object.__setattr__(self, "mu", mu)
        object.__setattr__(self, "omega_rad_s", finite_positive(
            "omega_rad_s", self.omega_rad_s, "a slip speed > 0 rad/s (and <= 5000 rad/s)"))
        if self.omega_rad_s > 5000.0:
            raise ParameterError("omega_rad_s", self.omega_rad_s, "a slip speed > 0 rad/s (and <= 5000 rad/s)")
        R = finite_positive("drum_radius_m", self.drum_radius_m, "a drum radius in (0, 1] m")
        if R > 1.0:
            raise ParameterError("drum_radius_m", self.drum_radius_m, "a drum radius in (0, 1] m")
        object.__setattr__(self, "drum_radius_m", R)

    @property
    def slip_speed_m_s(self) -> float:
        """Sliding speed v = omega R_d [m/s]."""
        return self.omega_rad_s * self.drum_radius_m

    @property
    def nodal_power_W(self) -> np.ndarray:
        """Friction power mu v lam_i per node [W] (shoe + drum)."""
        return self.mu * self.slip_speed_m_s * self.lam_N

    @property
    def power_W(self) -> float:
        """Friction power of the model (sector or full part) [W]."""
        return float(self.nodal_power_W.sum())


def slip_heat_load(cm: ClutchMesh, xy, lam_N, *, mu: float, omega_rad_s: float,
                   drum_radius_m: float) -> SlipHeatLoad:
    """Build a :class:`SlipHeatLoad` from contact-node positions ``xy`` (2, m) [m] and forces
    ``lam_N`` (m,) [N] (e.g. ``ContactNodes.xy`` and ``SpeedState.lam`` of the slip state):
    each position is matched to the P2 node of ``cm`` at that place (tolerance 1e-8 of the
    part size)."""
    xy = np.asarray(xy, dtype=float)
    if xy.ndim != 2 or xy.shape[0] != 2:
        raise InputError(f"slip_heat_load: xy must have shape (2, m) (got {xy.shape})")
    if np.any(~np.isfinite(xy)):
        raise InputError("slip_heat_load: xy contains non-finite coordinates")
    nodes = p2_basis(cm.mesh).doflocs
    dist, idx = cKDTree(nodes.T).query(xy.T)
    scale = float(np.max(np.abs(nodes)))
    if len(dist) and dist.max() > 1e-8 * scale:
        k = int(np.argmax(dist))
        raise InputError(f"slip_heat_load: contact point {k} at ({xy[0, k]:.6g}, {xy[1, k]:.6g}) m is "
                         f"{dist[k]:.3g} m from the nearest P2 node of {cm.source}: not a node of this mesh")
    return SlipHeatLoad(node_index=idx, lam_N=lam_N, mu=mu, omega_rad_s=omega_rad_s,
                        drum_radius_m=drum_radius_m)
