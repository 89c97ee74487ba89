"""The cyclic (rotated periodic) node pairing of a one-sector model: every node of the cut
line (or face) ``cut_a`` is matched to the node of ``cut_b`` at its position rotated by the
sector angle about the z axis.

    x_b[j[i]] = R_z(alpha) x_a[i],   R_z = [[c, -s], [s, c]] (in-plane; z kept in 3-D)

The 2-D and 3-D elastic models (vector unknowns, u_b = R u_a) and the heat model (a scalar,
T_b = T_a) all build their constraint maps on this one pairing.  The match is a KD-tree
nearest-node query; a mismatch above 1e-8 of the model size means the mesh generator did
not copy the nodes of one cut onto the other, and is refused.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from ..core import MeshError

#: largest accepted distance of a rotated cut_a node from its cut_b partner, relative to the
#: model size
CYCLIC_TOLERANCE = 1e-8


def cyclic_pairing(xa: np.ndarray, xb: np.ndarray, angle: float, *, scale: float, what: str) -> np.ndarray:
    """Index j (len(xa),) with ``xb[:, j[i]]`` the partner of ``xa[:, i]`` rotated by ``angle``
    [rad] about z.  ``xa``, ``xb``: node positions (2 or 3, n) [m] of cut_a and cut_b;
    ``scale``: the model size (e.g. max |coordinate|) for the tolerance; ``what``: the
    cut lines as named in the error (e.g. "concept1: the sector cut lines").  Raises
    :class:`MeshError` if the counts differ or a partner is further than the tolerance."""
    c, s = math.cos(angle), math.sin(angle)
    R = np.array([[c, -s], [s, c]])
    if xa.shape[0] == 3:
        R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    dist, j = cKDTree(xb.T).query((R @ xa).T)
    if xa.shape[1] != xb.shape[1] or (len(dist) and dist.max() > CYCLIC_TOLERANCE * scale):
        raise MeshError(f"{what} do not have matching nodes "
                        f"(worst mismatch {dist.max() if len(dist) else float('nan'):.3g} m)")
    return j
