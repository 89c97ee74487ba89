"""Field output for ParaView: one ``.pvd`` time series over the speeds of a sweep, each speed a
``.vtu`` of the whole part (meshio), written from a :class:`~clutchfem.loadcase.SweepResult`'s
stored states (no solving again).  The 3-D model's frames (tetra10, mirrored to the full
thickness) are :mod:`clutchfem.fe.vtu3d`'s; the ring and the ``.pvd`` :mod:`clutchfem.fe.ring`'s.

What a 2-D file holds (SI units, the names say them):

* the quadratic triangle6 mesh of the **whole part**: a one-sector model is rebuilt into the
  full ring by rotating copies of the sector by the sector angle (positions, displacements
  and stress tensors rotated; the copies' shared cut-line nodes merged), so the ring's
  fields are what the cyclic model stands for;
* point data: ``displacement_m`` (x, y, 0), ``sxx_Pa``, ``syy_Pa``, ``sxy_Pa`` and
  ``von_mises_Pa`` from the element-vertex stresses *averaged* over the elements at a node
  (smooth, what ParaView users expect), ``von_mises_max_Pa`` the *largest* element-vertex
  von Mises at a node (unaveraged: its maximum over the part is the sweep table's
  ``max_von_mises_Pa``, the peak the safety factor uses; averaging lowers a fillet's peak,
  e.g. concept 1 at 14 000 rpm: 833 MPa averaged, 896 MPa unaveraged), mid-edge nodes the
  mean of their edge's corner values (the P2 strain is linear along a straight edge);
  ``contact_pressure_Pa`` and ``gap_m`` at the contact nodes (0 elsewhere);
* cell data: ``zone_id`` (0 hub, 1 flexure, 2 shoe, -1 unknown: a user mesh without
  zones), ``shoe_id`` (the shoe a shoe or flexure element belongs to, -1 for the hub) and
  ``sector_id`` (the copy of the sector it is in).

The ``.pvd`` lists the files (``<stem>_fields_<rpm>rpm.vtu``) with the engine speed in rpm
as their ``timestep``: ParaView's time slider runs over the speed range.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import meshio
import numpy as np

from ..core.figures import tag_png
from ..mesh import p2_cells
from .ring import RingMesh, pvd_text, ring_stresses, zone_ids
from .vtu3d import Frames3D

#: deformation scale of :func:`render_png` (a quick look at one ``.vtu``; ``solve --vtk``'s
#: picture is :func:`clutchfem.report.field_picture`, true scale, in MPa)
RENDER_SCALE = 5.0


def in_plane_stresses(sv: np.ndarray, ne: int) -> np.ndarray:
    """Element-vertex stresses (3, ne, 3) [Pa], xx, yy, xy, for the ring fields: a 2-D model's
    as they are; the thick plane model's (6 Voigt components at its through-thickness levels,
    mid-plane then face) at the free face, where the out-of-plane components vanish (traction
    free), so its von Mises there is the plane one (issue 20).  The answer table's peak (the
    finite-rotation measure, the larger of both levels) can be higher: concept 4 at 14 000 rpm
    2157 MPa on the face against 2335 MPa (measured 2026-11-26)."""
    if sv.shape[0] == 6:
        face = sv.reshape(6, -1, ne * 3)[:, -1]
        return np.stack([face[0], face[1], face[5]]).reshape(3, ne, 3)
    return sv.reshape(3, -1, 3)


def write_vtk(res, rpms, out: Path, stem: str = "", cm=None, full_thickness: bool = True) -> list[Path]:
    """The ``.pvd`` time series of ``res`` (a SweepResult; each rpm of ``rpms`` one of its
    speeds) and its ``.vtu`` files, one per speed, of the whole part (module docstring);
    ``cm`` (the design's :class:`~clutchfem.mesh.ClutchMesh`) gives the sector angle and
    the number of copies (without it: the model as solved).  A 3-D result is written as
    tetra10 (:mod:`clutchfem.fe.vtu3d`), mirrored about the mid-plane to the full thickness
    unless ``full_thickness`` is False.  Returns [pvd, vtu...].

    Parameters
    ----------
    res : SweepResult
        A solved sweep (its stored states are written, nothing is solved again).
    rpms : sequence of float
        Speeds of the sweep [rpm], one ``.vtu`` each.
    out : path
        The folder (made if needed).
    stem : str
        File name prefix: ``<stem>_fields.pvd``, ``<stem>_fields_<rpm>rpm.vtu``.
    cm : ClutchMesh, optional
    full_thickness : bool

    Returns
    -------
    list of Path
        The ``.pvd`` first, then the ``.vtu`` files in the order of ``rpms``.

    Examples
    --------
    >>> import clutchfem as cf, tempfile, meshio
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> r = d.sweep("0:14000:7000")
    >>> files = cf.write_vtk(r, [7000, 14000], tempfile.mkdtemp(), stem="c1", cm=d.cm)
    >>> [f.name for f in files]
    ['c1_fields.pvd', 'c1_fields_7000rpm.vtu', 'c1_fields_14000rpm.vtu']
    >>> vm = meshio.read(files[2]).point_data["von_mises_max_Pa"]     # its maximum is the table's peak
    >>> bool(abs(vm.max() / r.curve["max_von_mises_Pa"].iloc[-1] - 1) < 1e-9)
    True
    """
    frames = Frames3D(res, cm, full_thickness) if res.fields.fe_basis.mesh.dim() == 3 else Frames2D(res, cm)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    base = f"{stem + '_' if stem else ''}fields"
    files, entries = [], []
    for rpm in rpms:
        f = out / f"{base}_{int(round(float(rpm)))}rpm.vtu"
        frames.mesh(res.index(float(rpm))).write(f)
        files.append(f)
        entries.append((float(rpm), f.name))
    pvd = out / f"{base}.pvd"
    pvd.write_text(pvd_text(entries))
    return [pvd] + files


class Frames2D:
    """The ``.vtu`` frames of a 2-D (or thick plane) sweep result (module docstring)."""

    def __init__(self, res, cm=None):
        self.res = res
        mesh = res.fields.fe_basis.mesh
        self.pts, self.cells = p2_cells(mesh)
        angle = getattr(cm, "sector_angle", None)
        self.ring = RingMesh(self.pts, self.cells, angle, getattr(cm, "sector_copies", 1) if angle else 1)
        zone, shoe = zone_ids(mesh)
        ne, cp = len(self.cells), self.ring.copies
        self.cell_data = {"zone_id": [np.tile(zone, cp)], "shoe_id": [np.tile(shoe, cp)],
                          "sector_id": [np.repeat(np.arange(cp), ne)]}

    def mesh(self, k: int) -> meshio.Mesh:
        """The frame of sweep speed index ``k``."""
        res, ring, pts, f_ = self.res, self.ring, self.pts, self.res.fields
        u = res.displacement(k)
        sv = in_plane_stresses(f_.stress(u), len(self.cells))
        s, vmax = ring_stresses(ring, sv, self.cells, f_.stress.von_mises)
        press = np.zeros(len(pts))
        gap = np.zeros(len(pts))
        if res.contact is not None:
            nd = res.contact.nodes
            if res.lam[k].any():
                press[nd.dof_x // 2] = np.nan_to_num(res.contact.pressure(res.lam[k], res.thickness))
            if res.gaps.size:
                gap[nd.dof_x // 2] = res.gaps[k]
        return meshio.Mesh(ring.points, [("triangle6", ring.cells)],
                           point_data={"displacement_m": ring.vector(np.column_stack([u[0:2 * len(pts):2],
                                                                                      u[1:2 * len(pts):2]])),
                                       "sxx_Pa": s[0], "syy_Pa": s[1], "sxy_Pa": s[2],
                                       "von_mises_Pa": f_.stress.von_mises(s), "von_mises_max_Pa": vmax,
                                       "contact_pressure_Pa": ring.scalar(press, "max"), "gap_m": ring.scalar(gap)},
                           cell_data=self.cell_data)


def render_png(vtu: Path, png: Path, title: str = "", scale: float = RENDER_SCALE) -> Path | None:
    """Off-screen pyvista render of von Mises on the shape deformed x ``scale``; None if no
    off-screen OpenGL is available (OSMesa/EGL).

    On a machine without a display (no ``DISPLAY``) VTK first tries X, logs ``bad X server
    connection`` on standard error and falls back to EGL/OSMesa; that warning says nothing to
    the user (the picture is rendered), so VTK's log is silenced for this render only there
    (issue 24)."""
    try:
        import pyvista as pv

        quiet = pv.vtk_verbosity("off") if not os.environ.get("DISPLAY") else contextlib.nullcontext()
        with quiet:
            return _render(pv, vtu, png, title, scale)
    except Exception:  # no off-screen GL on this machine: the .vtu is still written
        return None


def _render(pv, vtu: Path, png: Path, title: str, scale: float) -> Path:
    """The render of :func:`render_png`."""
    pv.OFF_SCREEN = True
    grid = pv.read(vtu)
    warped = grid.warp_by_vector("displacement_m", factor=scale)
    pl = pv.Plotter(off_screen=True, window_size=(900, 800))
    # in MPa, the colour bar reaching the peak the tables report (the unaveraged element-vertex
    # maximum ``von_mises_max_Pa``, above the averaged colours; issue 37), that peak stated
    vm = np.asarray(warped.point_data["von_mises_Pa"], dtype=float) / 1e6
    raw = warped.point_data["von_mises_max_Pa"] if "von_mises_max_Pa" in warped.point_data else None
    peak = float(np.max(raw)) / 1e6 if raw is not None else float(np.max(vm))
    top = max(peak, float(np.max(vm)))
    warped.point_data["von Mises [MPa]"] = vm
    pl.add_mesh(warped, scalars="von Mises [MPa]", cmap="turbo", show_edges=False, clim=(0.0, top),
                scalar_bar_args={"title": "von Mises [MPa]", "position_x": 0.78, "position_y": 0.1,
                                 "vertical": True, "width": 0.08, "height": 0.8})
    pl.add_text(f"{title} (deformation x{scale:g}); peak {peak:.0f} MPa (unaveraged, as the tables)",
                font_size=9)
    pl.view_xy()
    pl.screenshot(str(png))
    pl.close()
    tag_png(png, {"figure": [f"{title} (deformation x{scale:g})", f"peak {peak:.0f} MPa"], "axes": [],
                  "figure_legends": [], "legend_covers": [], "clipped": [],
                  "colour_bar_MPa": [0.0, top], "peak_MPa": peak})
    return png
