"""Output of a slip-heat run: the temperature fields as a .vtu (ParaView), the transient as a
ParaView time series (``.pvd``), and a PNG of each node's maximum temperature with the probe
time series.

All on the quadratic (triangle6) mesh, one value per scalar P2 node
(:func:`clutchfem.mesh.p2_cells`); the time series and the picture show the whole clutch, a
sector model's copies rotated by the sector angle (:class:`clutchfem.fe.RingMesh`).  The
series' frames are the fields the run kept (the start, about 60 evenly spaced steps and the
end of every slip and pause), its ``timestep`` the time in seconds from the start of the
first slip event; point data ``temperature_C`` [C], cell data ``zone_id`` (0 hub,
1 flexure, 2 shoe) and ``shoe_id``.
"""

from __future__ import annotations

import math
from pathlib import Path

import meshio
import numpy as np

from ..core import InputError, figure, save_figure
from ..fe import RingMesh, pvd_text, zone_ids
from ..mesh import ClutchMesh, p2_cells
from .result import SlipHeatResult

__all__ = ["render_png", "write_series", "write_vtu"]


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


def write_series(cm: ClutchMesh, result: SlipHeatResult, pvd: str | Path, folder: str | Path,
                 name: str | None = None) -> Path:
    """The run's temperature frames as a ParaView time series (module docstring): one .vtu per
    frame of the whole part into ``folder``, and the ``.pvd`` at ``pvd`` listing them by
    time [s] (as ``name/<file>``: the folder's final name, ``folder``'s own by default)."""
    pvd, folder = Path(pvd), Path(folder)
    if result.frames_C is None or not len(result.frames_C):
        raise InputError("write_series: the run kept no frames (heat_transient keeps them)")
    pts, cells = p2_cells(cm.mesh)
    if result.frames_C.shape[1] != len(pts):
        raise InputError(f"write_series: the frames have {result.frames_C.shape[1]} nodes, the mesh {len(pts)}")
    folder.mkdir(parents=True, exist_ok=True)
    ring = RingMesh(pts, cells, cm.sector_angle, cm.sector_copies)
    zone, shoe = zone_ids(cm.mesh)
    cell_data = {"zone_id": [np.tile(zone, ring.copies)], "shoe_id": [np.tile(shoe, ring.copies)]}
    entries = []
    for k, (t, T) in enumerate(zip(result.frame_times_s, result.frames_C)):
        f = folder / f"frame_{k:03d}.vtu"
        meshio.Mesh(ring.points, [("triangle6", ring.cells)], point_data={"temperature_C": ring.scalar(T)},
                    cell_data=cell_data).write(f)
        entries.append((float(t), f"{name or folder.name}/{f.name}"))
    pvd.write_text(pvd_text(entries))
    return pvd


def render_png(cm: ClutchMesh, result: SlipHeatResult, path: str | Path, *, title: str = "",
               full_part: bool = True, answer: dict | None = None) -> Path:
    """Picture (matplotlib without pyplot, :func:`clutchfem.core.figure`): each node's maximum
    temperature over the run (left; the whole clutch for a sector model when ``full_part``)
    and the probe time series (right).  ``answer``: the run's JSON document; when its
    transient was cut at a model limit (``stopped_at_s``, :mod:`.validity`) the labels state
    the document's peaks and time to the limit (the answers, up to the cut), the curves and the
    map the run continued past it, and the cut is drawn."""
    from matplotlib.tri import Triangulation

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    pts, cells = p2_cells(cm.mesh)
    sub = np.vstack([cells[:, [0, 3, 5]], cells[:, [3, 1, 4]], cells[:, [5, 4, 2]], cells[:, [3, 4, 5]]])
    val = np.asarray(result.nodal_max_C)
    copies = 1
    if full_part and cm.sector_angle is not None:
        copies = cm.sector_copies
    fig, (ax, ax2) = figure(1, 2, figsize=(12.5, 6.2), layout="constrained")
    vmin, vmax = float(val.min()), float(val.max())
    for c in range(copies):
        a = c * (cm.sector_angle or 0.0)
        x = math.cos(a) * pts[:, 0] - math.sin(a) * pts[:, 1]
        y = math.sin(a) * pts[:, 0] + math.cos(a) * pts[:, 1]
        tp = ax.tripcolor(Triangulation(x * 1e3, y * 1e3, sub), val, shading="gouraud", cmap="inferno",
                          vmin=vmin, vmax=vmax)
    fig.colorbar(tp, ax=ax, label="maximum temperature over the run [C]")
    cut = (answer or {}).get("stopped_at_s")
    if cut is None:
        peak = f"peak {result.peak_temperature_C:.0f} C at {result.peak_time_s:.1f} s ({result.peak_zone})"
        flex = (f"flexure peak {result.flexure_peak_C:.0f} C at {result.flexure_peak_time_s:.1f} s"
                if result.flexure_peak_C is not None else "")
        to_limit = result.time_to_limit_s
    else:  # the answers end at the cut; the map and curves go on (not valid there)
        peak = (f"peak {answer['peak_temperature_C']:.0f} C at {answer['peak_time_s']:.1f} s (answer, up to the cut "
                f"at {cut:.1f} s); the run continued: {result.peak_temperature_C:.0f} C, not valid")
        flex = (f"flexure peak {answer['flexure_temperature_C']:.0f} C at {answer['flexure_peak_time_s']:.1f} s "
                "(answer, up to the cut)" if answer.get("flexure_temperature_C") is not None else "")
        to_limit = answer.get("time_to_limit_s")
    ax.plot(result.peak_xy_m[0] * 1e3, result.peak_xy_m[1] * 1e3, "c*", ms=12, label=peak)
    if result.flexure_peak_xy_m is not None and flex:
        ax.plot(result.flexure_peak_xy_m[0] * 1e3, result.flexure_peak_xy_m[1] * 1e3, "co", mfc="none",
                ms=10, label=flex)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=8)
    t = result.times_s
    if result.flexure_C is not None:
        ax2.plot(t, result.flexure_C, label="flexure (hottest point)")
    ax2.plot(t, result.shoe_face_C, label="shoe face (hottest point)")
    ax2.plot(t, result.hub_C, label="hub (mean)")
    if result.part_mean_C is not None:
        ax2.plot(t, result.part_mean_C, "k:", label="whole part (mean)")
    reach = ("never reached by the flexure" if to_limit is None else f"flexure reaches it at {to_limit:.1f} s")
    ax2.axhline(result.limit_temperature_C, color="r", ls="--", lw=1,
                label=f"limit {result.limit_temperature_C:.0f} C (tempering, ASSUMED): {reach}")
    if to_limit is not None:
        ax2.plot([to_limit], [result.limit_temperature_C], "ro", mfc="none", ms=9, mew=1.5)
    if cut is not None:
        ax2.axvline(cut, color="0.3", ls="-.", lw=1.2, label=f"model limit: answers cut at {cut:.1f} s (beyond: not valid)")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("temperature [C]")
    ax2.grid(alpha=0.3)
    ax2.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=8, ncol=2)
    fig.suptitle(title or f"slip heat: {result.slip_power_W:.0f} W at {result.slip_rpm:.0f} rpm, "
                          f"{result.partition.fraction_part:.0%} into the part")
    return save_figure(fig, path)
