"""Field output: .vtu files (meshio) that open in ParaView, and off-screen PNG renders."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np

from .fem import von_mises
from .units import rpm_to_rad_s


def _p2_cells(solver) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3), cells (ne, 6)) of the quadratic triangle mesh: every P2 node once, in
    VTK's triangle6 order (3 corners, then mid-edges 01, 12, 20: scikit-fem's order too)."""
    b = solver.fe.basis
    ed = b.element_dofs  # (12, ne); vector dof = 2 * node + component
    cells = (ed[0::2] // 2).T
    xy = b.doflocs[:, 0::2]
    return np.column_stack([xy.T, np.zeros(xy.shape[1])]), cells


def _p2_nodal_stress(solver, u: np.ndarray, cells: np.ndarray, n: int) -> np.ndarray:
    """Element-vertex stresses averaged to the P2 nodes: corners averaged over the elements
    that share them, mid-edge nodes the mean of the edge's two corner values (the P2 strain
    is linear along a straight edge).  (3, n)."""
    sv = solver.vertex_stresses(u).reshape(3, -1, 3)  # (3, ne, 3 vertices)
    corners = cells[:, :3].ravel()
    acc = np.zeros((3, n))
    cnt = np.bincount(corners, minlength=n).astype(float)
    for c in range(3):
        acc[c] = np.bincount(corners, weights=sv[c].ravel(), minlength=n)
    acc[:, cnt > 0] /= cnt[cnt > 0]
    for k, (i, j) in enumerate(((0, 1), (1, 2), (2, 0))):
        acc[:, cells[:, 3 + k]] = 0.5 * (acc[:, cells[:, i]] + acc[:, cells[:, j]])
    return acc


def write_vtk(solver, rpms, out: Path, render: bool = True) -> list[Path]:
    """One .vtu per speed on the quadratic (triangle6) mesh: displacement, stresses and von
    Mises (averaged to the nodes: the raw element-vertex peak is in the sweep table), and
    the contact pressure at the contact nodes."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    pts, cells = _p2_cells(solver)
    n = len(pts)
    files = []
    for rpm in rpms:
        st, _ = solver.state(rpm_to_rad_s(rpm), None, engaged=_engaged(solver, rpm))
        u = solver.displacement(st)
        disp = np.zeros((n, 3))
        disp[:, 0] = u[0::2]
        disp[:, 1] = u[1::2]
        s = _p2_nodal_stress(solver, u, cells, n)
        press = np.zeros(n)
        if solver.nodes is not None and st.lam.any():
            nd = solver.nodes
            press[nd.dof_x // 2] = st.lam / (solver.fe.thickness * np.maximum(nd.weight, 1e-300))
        m = meshio.Mesh(pts, [("triangle6", cells)],
                        point_data={"displacement_m": disp, "sxx_Pa": s[0], "syy_Pa": s[1], "sxy_Pa": s[2],
                                    "von_mises_Pa": von_mises(s), "contact_pressure_Pa": press})
        f = out / f"fields_{int(round(rpm))}rpm.vtu"
        m.write(f)
        files.append(f)
        if render:
            png = render_png(f, f.with_suffix(".png"), title=f"von Mises at {rpm:.0f} rpm")
            if png:
                files.append(png)
    return files


def _engaged(solver, rpm) -> bool:
    w, _ = solver.engagement()
    return w is not None and rpm_to_rad_s(rpm) >= w


def render_png(vtu: Path, png: Path, title: str = "") -> Path | None:
    """Off-screen pyvista render of von Mises on the deformed shape (x50); None if no
    off-screen OpenGL is available (OSMesa/EGL)."""
    try:
        import pyvista as pv

        pv.OFF_SCREEN = True
        grid = pv.read(vtu)
        warped = grid.warp_by_vector("displacement_m", factor=5.0)
        pl = pv.Plotter(off_screen=True, window_size=(900, 800))
        pl.add_mesh(warped, scalars="von_mises_Pa", cmap="turbo", show_edges=False,
                    scalar_bar_args={"title": "von Mises [Pa]"})
        pl.add_text(title + " (deformation x5)", font_size=10)
        pl.view_xy()
        pl.screenshot(str(png))
        pl.close()
        return png
    except Exception:  # no off-screen GL on this machine: the .vtu is still written
        return None
