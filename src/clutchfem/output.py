"""Field output: .vtu files (meshio) that open in ParaView, and off-screen PNG renders."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np

from .fem import von_mises
from .units import rpm_to_rad_s


def _nodal_average(solver, u: np.ndarray) -> np.ndarray:
    """Element-vertex stresses averaged to mesh vertices: (3, nvertices)."""
    mesh = solver.fe.cm.mesh
    s = solver.fe.stress_at_vertices(u)  # (3, ne, 3)
    nv = mesh.p.shape[1]
    acc = np.zeros((3, nv))
    cnt = np.bincount(mesh.t.T.ravel(), minlength=nv).astype(float)
    for c in range(3):
        acc[c] = np.bincount(mesh.t.T.ravel(), weights=s[c].ravel(), minlength=nv)
    return acc / np.maximum(cnt, 1.0)


def write_vtk(solver, rpms, out: Path, render: bool = True) -> list[Path]:
    """One .vtu per speed: displacement, stresses, von Mises (vertex-averaged), contact
    pressure at the contact nodes (vertex values), on the corner-node triangle mesh."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    mesh = solver.fe.cm.mesh
    b = solver.fe.basis
    nv = mesh.p.shape[1]
    files = []
    for rpm in rpms:
        st, _ = solver.state(rpm_to_rad_s(rpm), None, engaged=_engaged(solver, rpm))
        u = solver.displacement(st)
        disp = np.zeros((nv, 3))
        disp[:, 0] = u[b.nodal_dofs[0]]
        disp[:, 1] = u[b.nodal_dofs[1]]
        s = _nodal_average(solver, u)
        press = np.zeros(nv)
        if solver.nodes is not None:
            tab = solver.pressure_table(st)
            verts = np.isin(solver.nodes.dof_x, b.nodal_dofs[0])
            vid = np.searchsorted(b.nodal_dofs[0], solver.nodes.dof_x[verts])
            press[vid] = (st.lam / (solver.fe.thickness * np.maximum(solver.nodes.weight, 1e-300)))[verts]
            del tab
        pts = np.column_stack([mesh.p.T, np.zeros(nv)])
        m = meshio.Mesh(pts, [("triangle", mesh.t.T)],
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
