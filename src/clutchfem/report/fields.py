"""The field picture of a solved state: von Mises stress on the whole part at one speed, the
drum, the contact arcs and the peak, in the units a designer reads (MPa, mm).

Drawn with matplotlib (:func:`clutchfem.core.figure`; no OpenGL needed) from a
:class:`~clutchfem.loadcase.SweepResult`: the sector rebuilt into the whole part
(:class:`clutchfem.fe.RingMesh`), deformed at true scale (the shoes sit on the drum circle
they touch), coloured by the *largest element-vertex* von Mises at each node -- the
unaveraged value whose maximum is the table's peak (``max_von_mises_Pa``, the safety
factor's), so the picture and the tables agree; the element-averaged peak (ParaView's
``von_mises_Pa`` of :func:`clutchfem.fe.write_vtk`) is named beside it, their difference
being a measure of the mesh's stress error at the peak.  The right panel zooms on the
peak.  The drum's inner circle is drawn, and on it each shoe's contact arc with its value.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..core import figure, save_figure
from ..fe import RingMesh, in_plane_stresses, ring_stresses
from ..mesh import p2_cells

#: half-width of the zoom window around the peak [m]
ZOOM = 3e-3


def _subtriangles(cells: np.ndarray) -> np.ndarray:
    """The four straight triangles of each triangle6 cell (for Gouraud shading of P2 data)."""
    return np.vstack([cells[:, [0, 3, 5]], cells[:, [3, 1, 4]], cells[:, [5, 4, 2]], cells[:, [3, 4, 5]]])


def field_picture(res, rpm: float, path, cm=None, title: str = "") -> Path:
    """PNG of von Mises [MPa] on the whole part at sweep speed ``rpm`` of ``res`` (module
    docstring); ``cm`` (the design's :class:`~clutchfem.mesh.ClutchMesh`) for the sector's
    copies.  Returns the path.

    Parameters
    ----------
    res : SweepResult
        A solved sweep (with stresses).
    rpm : float
        One of its speeds [rpm].
    path : path
        The PNG to write.
    cm : ClutchMesh, optional
        The design's mesh (``design.cm``): the sector drawn as the whole part (without it:
        the model as solved).
    title : str, optional
        Default: ``von Mises at <rpm> rpm``.

    Returns
    -------
    Path
        The PNG written.

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> png = cf.field_picture(d.sweep("14000"), 14000, pathlib.Path(tempfile.mkdtemp()) / "vm.png", cm=d.cm)
    >>> png.name, png.stat().st_size > 10_000
    ('vm.png', True)
    """
    from matplotlib.tri import Triangulation

    k = res.index(float(rpm))
    f_ = res.fields
    pts, cells = p2_cells(f_.fe_basis.mesh)
    angle = getattr(cm, "sector_angle", None)
    ring = RingMesh(pts, cells, angle, getattr(cm, "sector_copies", 1) if angle else 1)
    u = res.displacement(k)
    sv = in_plane_stresses(f_.stress(u), len(cells))
    s_avg, vmax = ring_stresses(ring, sv, cells, f_.stress.von_mises)
    vm_avg = f_.stress.von_mises(s_avg)
    disp = ring.vector(np.column_stack([u[0:2 * len(pts):2], u[1:2 * len(pts):2]]))
    xy = (ring.points[:, :2] + disp[:, :2]) * 1e3  # deformed, true scale [mm]
    tri = Triangulation(xy[:, 0], xy[:, 1], _subtriangles(ring.cells))
    peak = float(res.curve["max_von_mises_Pa"].iloc[k])
    at = np.array([res.curve["max_vm_x_m"].iloc[k], res.curve["max_vm_y_m"].iloc[k]]) * 1e3
    i_peak = int(np.argmax(vmax))
    p_xy = xy[i_peak] if np.hypot(*(ring.points[i_peak, :2] * 1e3 - at)) < 1e-6 else \
        xy[int(np.argmin(np.hypot(*(ring.points[:, :2].T * 1e3 - at[:, None]))))]
    fig, (a1, a2) = figure(1, 2, figsize=(13.0, 6.6), layout="constrained", gridspec_kw={"width_ratios": [1.35, 1]})
    # the colour bar reaches the marked peak (the table's): on the thick model that peak is the
    # largest over the through-thickness levels, above the mid-plane field drawn (issue 37)
    vmin, vtop = 0.0, max(float(np.max(vmax)), peak) / 1e6
    for ax in (a1, a2):
        tp = ax.tripcolor(tri, vmax / 1e6, shading="gouraud", cmap="turbo", vmin=vmin, vmax=vtop)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
    fig.colorbar(tp, ax=[a1, a2], location="right", shrink=0.9,
                 label="von Mises [MPa]: largest element-vertex value at each node (unaveraged)")
    handles = []
    if res.contact is not None:
        R = res.contact.drum_radius * 1e3
        t = np.linspace(0, 2 * math.pi, 721)
        for ax in (a1, a2):
            ax.plot(R * np.cos(t), R * np.sin(t), color="0.25", lw=1.0)
        handles.append(a1.plot([], [], color="0.25", lw=1.0, label=f"drum, inner radius {R:.1f} mm")[0])
        arcs = []
        for shoe in res.contact.nodes.shoes:
            e = res.contact_extent(shoe)[k]
            if not np.isfinite(e[0]):
                continue
            arcs.append(math.degrees(e[1] - e[0]))
            for c in range(ring.copies):
                a = np.linspace(e[0], e[1], 30) + c * ring.angle
                for ax in (a1, a2):
                    ax.plot(R * np.cos(a), R * np.sin(a), color="lime", lw=4, solid_capstyle="butt")
        if arcs:
            err = float(res.curve["contact_arc_error_deg"].iloc[k])
            handles.append(a1.plot([], [], color="lime", lw=4,
                                   label=f"contact arc {np.mean(arcs):.2f} deg +- {err:.2f} deg per shoe")[0])
    for ax in (a1, a2):
        ax.plot(*p_xy, marker="o", ms=14, mfc="none", mec="magenta", mew=2.5)
    r_mm = float(np.hypot(*at))
    handles.append(a1.plot([], [], ls="", marker="o", ms=10, mfc="none", mec="magenta", mew=2.5,
                           label=f"peak {peak / 1e6:.0f} MPa at r = {r_mm:.2f} mm (the tables' maximum)")[0])
    handles.append(a1.plot([], [], " ", label=f"averaged over the elements at a node (ParaView's "
                                              f"von_mises_Pa): peak {float(np.max(vm_avg)) / 1e6:.0f} MPa")[0])
    a2.set_xlim(p_xy[0] - ZOOM * 1e3, p_xy[0] + ZOOM * 1e3)
    a2.set_ylim(p_xy[1] - ZOOM * 1e3, p_xy[1] + ZOOM * 1e3)
    a1.set_title("whole part (deformed, true scale)", fontsize=10)
    a2.set_title(f"zoom on the peak ({2 * ZOOM * 1e3:.0f} mm window)", fontsize=10)
    fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=8)
    fig.suptitle(title or f"von Mises at {float(rpm):.0f} rpm", fontsize=11)
    return save_figure(fig, Path(path))
