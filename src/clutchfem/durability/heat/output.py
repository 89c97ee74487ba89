"""Output of a slip-heat run: the temperature fields as a .vtu (ParaView) and a PNG of each
node's maximum temperature with the probe time series.

Both on the quadratic (triangle6) mesh, one value per scalar P2 node
(:func:`clutchfem.mesh.p2_cells`); a sector model is drawn as the whole clutch by rotating
copies of the sector by the sector angle.
"""

from __future__ import annotations

import math
from pathlib import Path

import meshio
import numpy as np

from ...core import InputError, figure
from ...mesh import ClutchMesh, p2_cells
from .result import SlipHeatResult

__all__ = ["render_png", "write_vtu"]


def write_vtu(cm: ClutchMesh, result: SlipHeatResult, path: str | Path) -> Path:
    """The final temperature field and each node's maximum over the run [C] as a .vtu on
    the quadratic (triangle6) mesh (opens in ParaView)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    pts, cells = p2_cells(cm.mesh)
    if len(pts) != len(result.final_field_C):
        raise InputError(f"write_vtu: the result has {len(result.final_field_C)} nodes, the mesh {len(pts)}")
    meshio.Mesh(pts, [("triangle6", cells)],
                point_data={"temperature_C": np.asarray(result.final_field_C),
                            "max_temperature_C": np.asarray(result.nodal_max_C)}).write(path)
    return path


def render_png(cm: ClutchMesh, result: SlipHeatResult, path: str | Path, *, title: str = "",
               full_part: bool = True) -> Path:
    """Picture (matplotlib without pyplot, :func:`clutchfem.core.figure`): each node's maximum
    temperature over the run (left; the whole clutch for a sector model when ``full_part``)
    and the probe time series (right)."""
    from matplotlib.tri import Triangulation

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    pts, cells = p2_cells(cm.mesh)
    sub = np.vstack([cells[:, [0, 3, 5]], cells[:, [3, 1, 4]], cells[:, [5, 4, 2]], cells[:, [3, 4, 5]]])
    val = np.asarray(result.nodal_max_C)
    copies = 1
    if full_part and cm.sector_angle is not None:
        copies = cm.sector_copies
    fig, (ax, ax2) = figure(1, 2, figsize=(12, 5.2))
    vmin, vmax = float(val.min()), float(val.max())
    for c in range(copies):
        a = c * (cm.sector_angle or 0.0)
        x = math.cos(a) * pts[:, 0] - math.sin(a) * pts[:, 1]
        y = math.sin(a) * pts[:, 0] + math.cos(a) * pts[:, 1]
        tp = ax.tripcolor(Triangulation(x * 1e3, y * 1e3, sub), val, shading="gouraud", cmap="inferno",
                          vmin=vmin, vmax=vmax)
    fig.colorbar(tp, ax=ax, label="maximum temperature over the run [C]")
    ax.plot(result.peak_xy_m[0] * 1e3, result.peak_xy_m[1] * 1e3, "c*", ms=12, label="peak")
    if result.flexure_peak_xy_m is not None:
        ax.plot(result.flexure_peak_xy_m[0] * 1e3, result.flexure_peak_xy_m[1] * 1e3, "co", mfc="none",
                ms=10, label="flexure peak")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(loc="lower left", fontsize=8)
    t = result.times_s
    if result.flexure_C is not None:
        ax2.plot(t, result.flexure_C, label="flexure (hottest point)")
    ax2.plot(t, result.shoe_face_C, label="shoe face (hottest point)")
    ax2.plot(t, result.hub_C, label="hub (mean)")
    if result.part_mean_C is not None:
        ax2.plot(t, result.part_mean_C, "k:", label="whole part (mean)")
    ax2.axhline(result.limit_temperature_C, color="r", ls="--", lw=1, label="limit temperature")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("temperature [C]")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.suptitle(title or f"slip heat: {result.slip_power_W:.0f} W at {result.slip_rpm:.0f} rpm, "
                          f"{result.partition.fraction_part:.0%} into the part")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path
