"""Field output: .vtu files (meshio) that open in ParaView, and off-screen PNG renders.

Written from a :class:`~clutchfem.loadcase.SweepResult`'s stored states (no solving again):
displacement, stresses and von Mises on the quadratic triangle6 mesh, and the contact
pressure at the contact nodes.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import meshio
import numpy as np

from ..core import InputError
from ..mesh import p2_cells

#: deformation scale of the PNG renders (the .vtu holds the true displacement)
RENDER_SCALE = 5.0


def _p2_nodal_stress(stress, u: np.ndarray, cells: np.ndarray, n: int) -> np.ndarray:
    """Element-vertex stresses averaged to the P2 nodes: corners averaged over the elements
    that share them, mid-edge nodes the mean of the edge's two corner values (the P2 strain
    is linear along a straight edge).  (3, n)."""
    sv = stress(u).reshape(3, -1, 3)  # (3, ne, 3 vertices)
    corners = cells[:, :3].ravel()
    acc = np.zeros((3, n))
    cnt = np.bincount(corners, minlength=n).astype(float)
    for c in range(3):
        acc[c] = np.bincount(corners, weights=sv[c].ravel(), minlength=n)
    acc[:, cnt > 0] /= cnt[cnt > 0]
    for k, (i, j) in enumerate(((0, 1), (1, 2), (2, 0))):
        acc[:, cells[:, 3 + k]] = 0.5 * (acc[:, cells[:, i]] + acc[:, cells[:, j]])
    return acc


def write_vtk(res, rpms, out: Path, render: bool = True, stem: str = "") -> list[Path]:
    """One .vtu per speed of ``res`` (a SweepResult; each rpm must be one of its speeds) on
    the quadratic (triangle6) mesh: displacement, stresses and von Mises (averaged to the
    nodes: the raw element-vertex peak is in the sweep table), and the contact pressure at
    the contact nodes.  With ``render``, a PNG of von Mises on the shape deformed x
    :data:`RENDER_SCALE` beside each file."""
    f_ = res.fields
    if f_.fe_basis.mesh.dim() != 2:
        raise InputError("VTK output is written for the 2-D formulations only (the 3-D model's fields are "
                         "not exported yet): drop --vtk or use --formulation plane-stress/plane-strain")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    pts, cells = p2_cells(f_.fe_basis.mesh)
    n = len(pts)
    files = []
    for rpm in rpms:
        k = res.index(float(rpm))
        u = res.displacement(k)
        disp = np.zeros((n, 3))
        disp[:, 0] = u[0::2]
        disp[:, 1] = u[1::2]
        s = _p2_nodal_stress(f_.stress, u, cells, n)
        press = np.zeros(n)
        if res.contact is not None and res.lam[k].any():
            nd = res.contact.nodes
            press[nd.dof_x // 2] = res.contact.pressure(res.lam[k], res.thickness)
        m = meshio.Mesh(pts, [("triangle6", cells)],
                        point_data={"displacement_m": disp, "sxx_Pa": s[0], "syy_Pa": s[1], "sxy_Pa": s[2],
                                    "von_mises_Pa": f_.stress.von_mises(s), "contact_pressure_Pa": press})
        f = out / f"{stem + '_' if stem else ''}fields_{int(round(float(rpm)))}rpm.vtu"
        m.write(f)
        files.append(f)
        if render:
            png = render_png(f, f.with_suffix(".png"), title=f"von Mises at {float(rpm):.0f} rpm")
            if png:
                files.append(png)
    return files


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
    pl.add_mesh(warped, scalars="von_mises_Pa", cmap="turbo", show_edges=False,
                scalar_bar_args={"title": "von Mises [Pa]"})
    pl.add_text(f"{title} (deformation x{scale:g})", font_size=10)
    pl.view_xy()
    pl.screenshot(str(png))
    pl.close()
    return png
