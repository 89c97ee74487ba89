"""A quick picture of a mesh with its named boundary groups (PNG, matplotlib Agg)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..core import figure
from .clutch_mesh import ClutchMesh


def draw_mesh(cm: ClutchMesh, path: Path, dpi: int = 120) -> Path:
    """Quick picture of a mesh with its named boundary groups."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    m = cm.mesh
    mm = 1e3
    fig, ax = figure(figsize=(8.0, 8.0))
    ax.triplot(m.p[0] * mm, m.p[1] * mm, m.t[:3].T, lw=0.25, color="0.35")
    colours = {"bore": "#2c7bb6", "cut_a": "#1a9641", "cut_b": "#a6611a"}
    seen = set()
    for name, fac in sorted((m.boundaries or {}).items()):
        if name == "contact":
            continue
        col = colours.get(name, "#d7191c")
        label = "contact_i" if name.startswith("contact_") else name
        segs = m.p[:, m.facets[:, fac]] * mm  # 2 x 2 x k
        for k in range(segs.shape[2]):
            ax.plot(segs[0, :, k], segs[1, :, k], color=col, lw=1.8,
                    label=label if label not in seen else None)
            seen.add(label)
    if cm.drum_radius:
        th = np.linspace(0, 2 * np.pi, 721)
        ax.plot(cm.drum_radius * mm * np.cos(th), cm.drum_radius * mm * np.sin(th), "--", color="0.4", lw=0.8,
                label="drum")
    ax.set_aspect("equal")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(f"{cm.source}: {cm.n_elements} elements, {cm.n_nodes} nodes"
                 + (f", sector of {cm.n_shoes_total}" if cm.sector_angle else ""), fontsize=10)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    return path
