"""The app's pictures: the part at one speed (deformed shape with the drum, von Mises in MPa
with its peak marked) as a PNG, and the option dictionaries of the interactive charts
(torque vs speed with the engine curve, engagement and slip markers and the requirement
bands; contact pressure along the shoe), with a pinned design drawn against the current one.

Every picture states its quantity with its unit (rpm, N m, MPa, deg, mm) and marks the
answer it is there for.  The peak von Mises marked is the raw element-vertex maximum, the
number the answers table reports; the colours are averaged to the vertices (stated).
"""

from __future__ import annotations

import io
import math

import numpy as np

from ..core import figure
from ..core.figures import clipped_texts
from ..loadcase import SweepResult

__all__ = ["field_png", "pressure_chart", "torque_chart"]

#: deformation scale of the part picture (the clearance is 0.6 mm on a 34 mm drum: x1 shows nothing)
DEFORMATION_SCALE = 10.0


def field_png(design, res: SweepResult, rpm: float, scale: float = DEFORMATION_SCALE) -> tuple[bytes, dict]:
    """The part at ``rpm`` (the whole part rebuilt from a sector) deformed x ``scale``, von
    Mises [MPa] averaged to the vertices, the raw peak (as the table) marked, the drum circle
    (with the gap scaled like the deformation);
    returns (PNG bytes, {"peak_MPa", "peak_xy_mm", "max_displacement_mm", "colour_bar_MPa" (the
    colour bar's range: it reaches the marked peak), "clipped" (texts a reader sees cut,
    :func:`clutchfem.core.figures.clipped_texts`: none expected)})."""
    cm = design.cm
    mesh = cm.mesh
    k = res.index(float(rpm))
    u = res.displacement(k)
    fields = res.fields
    # (3, ne*3) raw vertex stresses; the thick model: (6, levels*ne*3), its peak measure as the table's
    s = fields.stress(u, finite=True) if getattr(fields.stress, "FINITE", False) else fields.stress(u)
    t = mesh.t  # (3, ne) vertex indices
    # the largest over the thick model's through-thickness levels (mid-plane, face)
    vm = fields.stress.von_mises(s).reshape(-1, t.shape[1], 3).max(axis=0)  # (ne, 3)
    nv = mesh.p.shape[1]
    acc = np.zeros(nv)
    cnt = np.zeros(nv)
    np.add.at(acc, t.T.ravel(), vm.ravel())
    np.add.at(cnt, t.T.ravel(), 1.0)
    vm_nodal = acc / np.maximum(cnt, 1) / 1e6
    ux, uy = u[0::2][:nv], u[1::2][:nv]  # P2 dofs: vertices first (skfem's order)
    peak_e = int(np.argmax(vm.max(axis=1)))
    peak_v = int(t[int(np.argmax(vm[peak_e])), peak_e])
    peak = float(vm.max()) / 1e6
    fig, ax = figure(figsize=(6.4, 6.0))
    copies = cm.sector_copies
    x0, y0 = mesh.p[0], mesh.p[1]
    xd, yd = x0 + scale * ux, y0 + scale * uy
    vmax = float(vm_nodal.max()) if vm_nodal.size else 1.0
    tpc = None
    for c in range(copies):
        a = c * (cm.sector_angle or 0.0)
        ca, sa = math.cos(a), math.sin(a)
        X = 1e3 * (ca * xd - sa * yd)
        Y = 1e3 * (sa * xd + ca * yd)
        tpc = ax.tripcolor(X, Y, t.T, vm_nodal, shading="gouraud", cmap="turbo", vmin=0.0, vmax=vmax)
    R = design.drum_radius
    nodes = design.nodes
    reach = float(np.hypot(xd, yd).max())
    if R and nodes is not None:
        # the drum drawn in the picture's own (exaggerated) gap: over each contact node at
        # R + (scale - 1) g0, g0 its clearance at rest, so a node touches the drawn drum when it
        # touches the real one (the part's displacement is drawn x scale too)
        xs = nodes.xy[0] + scale * u[nodes.dof_x]
        ys = nodes.xy[1] + scale * u[nodes.dof_y]
        th_def = np.unwrap(np.arctan2(ys, xs)[np.argsort(nodes.angle)])
        th, g0 = th_def, nodes.gap0[np.argsort(nodes.angle)]
        r_shown = R + (scale - 1.0) * g0
        for c in range(copies):
            a = c * (cm.sector_angle or 0.0)
            ax.plot(1e3 * r_shown * np.cos(th + a), 1e3 * r_shown * np.sin(th + a), color="0.25", lw=2.2,
                    solid_capstyle="butt")
        reach = max(reach, float(r_shown.max()))
        ax.text(0.0, -1e3 * reach * 1.0, f"drum R = {R * 1e3:.1f} mm: drawn over the shoes with the gap x{scale:g}",
                ha="center", va="top", fontsize=8, color="0.25")
    px, py = 1e3 * xd[peak_v], 1e3 * yd[peak_v]
    ax.plot([px], [py], marker="o", mfc="none", mec="k", ms=12, mew=1.6)
    # the label toward the part's centre from the peak (the peak sits on the outline; outward,
    # the label ran under the colour bar: issue 37)
    right, upper = px > 0, py > 0
    ax.annotate(f"peak {peak:.0f} MPa", (px, py), xytext=(-14 if right else 14, -18 if upper else 18),
                textcoords="offset points", fontsize=9, ha="right" if right else "left",
                va="top" if upper else "bottom", bbox={"boxstyle": "round", "fc": "white", "alpha": 0.85})
    # the colour bar reaches the marked peak (the raw vertex maximum, above the averaged colours)
    for coll in ax.collections:
        if hasattr(coll, "set_clim") and coll.get_array() is not None:
            coll.set_clim(0.0, max(vmax, peak))
    cb = fig.colorbar(tpc, ax=ax, shrink=0.82, pad=0.02)
    cb.set_label("von Mises [MPa] (vertex average; peak: raw vertex max, as the table)")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"{design.name} at {rpm:.0f} rpm, deformation x{scale:g}", fontsize=10)
    lim = 1e3 * reach * 1.1
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    disp = float(np.hypot(ux, uy).max()) * 1e3
    return buf.getvalue(), {"peak_MPa": peak, "peak_xy_mm": [px, py], "max_displacement_mm": disp,
                            "colour_bar_MPa": [float(cb.vmin), float(cb.vmax)], "clipped": clipped_texts(fig)}


def _line(name: str, x, y, color: str, dashed: bool = False, width: float = 2.0) -> dict:
    return {"type": "line", "name": name, "showSymbol": False, "data": [[float(a), float(b)] for a, b in zip(x, y)
                                                                        if math.isfinite(b)],
            "lineStyle": {"color": color, "type": "dashed" if dashed else "solid", "width": width},
            "itemStyle": {"color": color}}


def torque_chart(an, pinned=None) -> dict:
    """ECharts options: FE torque vs rpm of the current design (and the pinned one, dashed),
    the engine curve, engagement and slip markers, the requirement bands."""
    c = an.curves
    req = an.requirements
    series = [_line("engine (full throttle)", c["rpm"], c["engine_torque_Nm"], "#444444", width=1.5)]
    if "fe_torque_Nm" in c:
        series.append(_line(f"clutch (FE) {an.label or an.design}", c["rpm"], c["fe_torque_Nm"], "#1f77b4"))
    else:  # a live answer: the torque at the rpm of max engine torque only (the curve needs the FE)
        series.append({"type": "scatter", "name": f"clutch (live) {an.label or an.design}", "symbolSize": 10,
                       "itemStyle": {"color": "#1f77b4"},
                       "data": [[float(an.rpm_max_engine_torque), float(an.torque_at_max_engine_torque_Nm)]]})
    marks = []
    if an.engagement_rpm is not None:
        marks.append({"xAxis": float(an.engagement_rpm), "name": f"engagement {an.engagement_rpm:.0f} rpm",
                      "lineStyle": {"color": "#2ca02c"}})
    if an.slip_rpm is not None:
        marks.append({"xAxis": float(an.slip_rpm), "name": f"slip {an.slip_rpm:.0f} rpm",
                      "lineStyle": {"color": "#d62728"}})
    series[1]["markLine"] = {"symbol": "none", "label": {"formatter": "{b}", "position": "insideEndTop"},
                             "data": marks}
    bands = [[{"xAxis": 0, "name": "engagement must lie above"},
              {"xAxis": float(req["engagement_limit_rpm"])}],
             [{"xAxis": float(req["slip_limit_rpm"]), "name": "slip must lie below"},
              {"xAxis": float(c["rpm"].max())}]]
    series[0]["markArea"] = {"silent": True, "itemStyle": {"color": "rgba(220,50,47,0.07)"},
                             "label": {"color": "#999", "fontSize": 10}, "data": bands}
    if pinned is not None and "fe_torque_Nm" in pinned.curves:
        p = pinned.curves
        series.append(_line(f"pinned {pinned.label or pinned.design}", p["rpm"], p["fe_torque_Nm"], "#ff7f0e",
                            dashed=True))
    return {"animation": False, "tooltip": {"trigger": "axis"}, "legend": {"top": 0, "type": "scroll"},
            "grid": {"left": 55, "right": 30, "top": 40, "bottom": 45, "containLabel": True},
            "xAxis": {"type": "value", "name": "engine speed [rpm]", "nameLocation": "middle", "nameGap": 28,
                      "min": 0},
            "yAxis": {"type": "value", "name": "torque [N m]", "nameLocation": "middle", "nameGap": 38},
            "series": series}


def pressure_chart(res: SweepResult, rpm: float, pinned: SweepResult | None = None) -> dict:
    """ECharts options: contact pressure [MPa] along the shoe (polar angle [deg]) at ``rpm``."""
    series = []
    for r, name, color, dashed in ((res, "current", "#1f77b4", False), (pinned, "pinned", "#ff7f0e", True)):
        if r is None or r.contact is None:
            continue
        df = r.pressure(float(rpm))
        for shoe, g in df.groupby("shoe"):
            p = g["pressure_Pa"].fillna(0.0).to_numpy() / 1e6
            series.append(_line(f"{name} shoe {shoe}", g["angle_deg"], p, color, dashed=dashed))
    return {"animation": False, "tooltip": {"trigger": "axis"}, "legend": {"top": 0, "type": "scroll"},
            "grid": {"left": 55, "right": 30, "top": 40, "bottom": 45, "containLabel": True},
            "xAxis": {"type": "value", "name": "polar angle along the shoe [deg]", "nameLocation": "middle",
                      "nameGap": 28, "scale": True},
            "yAxis": {"type": "value", "name": f"contact pressure at {rpm:.0f} rpm [MPa]", "nameLocation": "middle",
                      "nameGap": 38},
            "series": series}
