"""The meshed part: :class:`ClutchMesh`, a scikit-fem ``MeshTri2`` with its named groups and
what the FE stages need to know about it (sector, drum radius, thickness, gmsh data).

Conventions: metres, the part in the x-y plane, the rotation axis through the origin.  A
one-sector model of ``n_shoes_total`` identical shoes carries the boundary groups
``cut_a``/``cut_b``, cut_b being cut_a rotated by +``sector_angle`` about z.
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from skfem import MeshTri2

from ..core import MeshError


def groups_msh_path(msh: Path) -> Path:
    """The ``.msh`` with named physical groups that sits beside a cached mesh."""
    return msh.with_name(msh.stem + ".groups.msh")


@dataclass
class ClutchMesh:
    """A meshed clutch (or any 2-D part) ready for the FE model.

    ``mesh`` carries boundaries ``bore``, ``contact``, ``contact_<i>`` and, for a sector,
    ``cut_a``/``cut_b``; subdomains ``solid``, ``shoe_<i>``, ``flexure_<i>``, ``hub``
    where known.  ``sector_angle`` (rad) is set for a one-sector model of ``n_shoes_total``
    identical shoes (cut_b is cut_a rotated by +sector_angle).
    """

    mesh: MeshTri2
    source: str
    n_shoes_total: int = 1
    n_shoes_model: int = 1
    sector_angle: float | None = None
    drum_radius: float | None = None
    thickness: float | None = None
    params: dict = field(default_factory=dict)
    mesh_settings: dict = field(default_factory=dict)
    mass: dict = field(default_factory=dict)
    pivots: list = field(default_factory=list)
    contact_arcs: list = field(default_factory=list)
    mirrored: bool = False
    msh_path: Path | None = None
    mesh_time_s: float = 0.0
    cached: bool = False
    #: how a morphed mesh was made (:mod:`.morph`: reference, quality), or why a morph was
    #: refused; None for a mesh made from scratch without a reference
    morph: dict | None = None

    @property
    def sector_copies(self) -> int:
        """How many copies of the model make the whole part (n_shoes_total / n_shoes_model for
        a one-sector model, 1 for a full part)."""
        return self.n_shoes_total // max(self.n_shoes_model, 1) if self.sector_angle is not None else 1

    @property
    def n_elements(self) -> int:
        return int(self.mesh.t.shape[1])

    @property
    def n_nodes(self) -> int:
        return int(self.mesh.doflocs.shape[1])

    def write_msh(self, path) -> Path:
        """Write the mesh with its named physical groups (``contact``, ``bore``, the cut lines,
        the zones) to ``path``: a ``.msh`` that gmsh opens and ``clutchfem ... --mesh`` reads.
        Only a mesh made by clutchfem (it keeps that file beside its cache entry) has one."""
        src = groups_msh_path(self.msh_path) if self.msh_path is not None else None
        if src is None or not src.is_file():
            raise MeshError(f"the mesh from {self.source} has no .msh with named groups (only a concept's mesh, "
                            "made by clutchfem, keeps one)")
        path = Path(path)
        shutil.copyfile(src, path)
        return path

    def boundary(self, name: str) -> np.ndarray:
        """The facets of boundary group ``name`` (:func:`named_boundary`)."""
        return named_boundary(self.mesh, name, f"mesh from {self.source}")


def named_boundary(mesh, name: str, what: str) -> np.ndarray:
    """The facets of the boundary group ``name`` of a scikit-fem ``mesh`` (2-D or its 3-D
    extrusion); a missing group is refused naming ``what`` (the mesh) and the groups it has."""
    b = mesh.boundaries or {}
    if name not in b:
        raise MeshError(f"{what} has no boundary group '{name}'; available: {sorted(b)}")
    return np.asarray(b[name])
