"""Checks that a user's part is what the model assumes, each refusal with its own message:
triangles only (no element type dropped), a size plausible in metres (the unit), one piece
joined to the bore (no floating island), and the rotation axis at the bore's centre.

Why each check exists (issue 24): every one of these used to give a silent wrong answer or
a refusal that pointed elsewhere.  A part moved 0.2 mm off the origin was spun about the
wrong axis (engagement 3241 instead of 3935 rpm, stress 1123 instead of 896 MPa); a part
in millimetres was read as metres and refused with "a larger drum"; quadrilaterals were
dropped and a floating island was refused as "the shoes would fly out".

Conventions and tolerances:

* **Unit.** A ``.msh`` carries no unit: clutchfem reads metres.  A STEP file names its
  unit; gmsh is told to convert it to metres (``Geometry.OCCTargetUnit = M``) and the unit
  found in the file is named in a refusal.  Plausible sizes: outer radius (from the axis)
  :data:`PLAUSIBLE_RADIUS` = 5 mm .. 0.5 m (ASSUMED: model-aircraft clutches are ~30 mm
  across, go-kart clutches ~150 mm; no centrifugal shoe clutch is a metre across or
  smaller than a coin).
* **Axis.** The axis is the centre of the bore: of each bore loop, the circle through most
  of its nodes (circumcircles of node triples, the one with most nodes within 1e-5 r, then
  a least-squares Kasa fit on those: a keyway's nodes are outliers); a bore loop with no
  circle through half its nodes (a hex or spline bore) has its centre at the
  length-weighted centroid of its edges; several loops (a bolt circle)
  share their mean centre.  Tolerance :data:`AXIS_TOLERANCE` = 1 um: measured on concept
  1, the engagement speed moves 1.6 % for 20 um of offset (0.08 %/um), so 1 um stays below
  the answers' discretisation error; a CAD export is centred to ~1e-9 m.
* **Connectivity.** Triangles are joined through shared edges (two pieces touching in one
  node are not joined: a hinge without stiffness).  Every piece must hold a bore edge.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from ..core import MeshError
from .topology import element_components, element_set_area

#: plausible outer radius of a clutch [m] (ASSUMED, module docstring)
PLAUSIBLE_RADIUS = (5e-3, 0.5)
#: largest distance of the bore's centre from the origin (the rotation axis) [m]
AXIS_TOLERANCE = 1e-6

#: the cell types of a 2-D triangle mesh that the converter reads (besides one triangle type)
_READ = {"vertex", "line", "line3"}
_NAMES = {"quad": "4-node quadrilateral", "quad8": "8-node quadrilateral", "quad9": "9-node quadrilateral",
          "polygon": "polygon", "tetra": "tetrahedral (3-D)", "tetra10": "10-node tetrahedral (3-D)",
          "hexahedron": "hexahedral (3-D)", "wedge": "prism (3-D)", "pyramid": "pyramid (3-D)",
          "triangle": "3-node triangle", "triangle6": "6-node triangle"}
#: STEP length units (the ``SI_UNIT`` prefix or a ``CONVERSION_BASED_UNIT`` name) -> [m]
_STEP_UNITS = {"MILLI": ("millimetre", 1e-3), "CENTI": ("centimetre", 1e-2), "DECI": ("decimetre", 0.1),
               "MICRO": ("micrometre", 1e-6), "KILO": ("kilometre", 1e3), "": ("metre", 1.0),
               "INCH": ("inch", 0.0254), "FOOT": ("foot", 0.3048), "MM": ("millimetre", 1e-3),
               "MILLIMETRE": ("millimetre", 1e-3), "METRE": ("metre", 1.0), "CM": ("centimetre", 1e-2)}

__all__ = ["AXIS_TOLERANCE", "PLAUSIBLE_RADIUS", "bore_centre", "check_cell_types", "check_connected",
           "check_axis", "check_size", "step_length_unit"]


def check_cell_types(cells_dict: dict, source: str) -> str:
    """The triangle type a mesh is read with (``triangle6`` or ``triangle``); refuses a mesh
    whose other elements would be dropped (quadrilaterals, polygons, a second triangle
    order) or that is 3-D (tetrahedra, hexahedra ...)."""
    counts = {k: len(v) for k, v in cells_dict.items() if len(v)}
    solid = sorted(k for k in counts if k.startswith(("tetra", "hexahedron", "wedge", "pyramid")))
    if solid:
        raise MeshError(f"{source}: a 3-D mesh ({', '.join(f'{counts[k]:,} {_NAMES.get(k, k)}' for k in solid)} "
                        "elements); expected a 2-D part meshed with triangles in the x-y plane (clutchfem "
                        "extrudes it itself with --formulation 3d)")
    tri = [k for k in ("triangle6", "triangle") if k in counts]
    other = sorted(k for k in counts if k not in _READ and k not in tri)
    if len(tri) == 2:
        raise MeshError(f"{source}: mixes {counts['triangle6']:,} 6-node and {counts['triangle']:,} 3-node "
                        "triangles; clutchfem reads one element order, so one kind would be dropped: mesh the "
                        "whole part with one order (gmsh: Mesh.ElementOrder = 2 for all surfaces)")
    if other:
        what = ", ".join(f"{counts[k]:,} {_NAMES.get(k, k)}" for k in other)
        raise MeshError(f"{source}: holds {what} element(s), which clutchfem does not read (triangles only): "
                        "those parts of the mesh would be dropped; remesh with triangles (gmsh: no "
                        "Recombine / Mesh.RecombineAll = 0)")
    if not tri:
        raise MeshError(f"{source}: no triangle elements found (cell types: {sorted(counts) or 'none'}); "
                        "expected a 2-D triangle mesh")
    return tri[0]


def step_length_unit(path: str | Path) -> tuple[str, float] | None:
    """(name, metres per unit) of the length unit a STEP file declares, or None when it
    names none that is known (read from the text: ``LENGTH_UNIT ... SI_UNIT(.MILLI.,.METRE.)``
    or ``CONVERSION_BASED_UNIT('INCH', ...)``)."""
    try:
        text = Path(path).read_text(encoding="latin-1", errors="replace")
    except OSError:
        return None
    ents = {}
    for ent in text.split(";"):  # one STEP entity per ';' (strings with ';' do not name units)
        m = re.match(r"\s*#(\d+)\s*=(.*)", ent, flags=re.S)
        if m:
            ents[m.group(1)] = re.sub(r"\s+", "", m.group(2).upper())
    lengths = [k for k, e in ents.items() if "LENGTH_UNIT(" in e]
    # the unit the geometry uses: the length unit of the GLOBAL_UNIT_ASSIGNED_CONTEXT
    # (a conversion-based unit such as INCH refers to its SI base unit, also a LENGTH_UNIT)
    for e in ents.values():
        g = re.search(r"GLOBAL_UNIT_ASSIGNED_CONTEXT\(\(([^)]*)\)", e)
        if g:
            used = [k.lstrip("#") for k in g.group(1).split(",")]
            lengths = [k for k in used if k in lengths] + lengths
            break
    for k in lengths:
        e = ents[k]
        conv = re.search(r"CONVERSION_BASED_UNIT\('([^']*)'", e)
        if conv:
            name = conv.group(1).strip()
            return _STEP_UNITS.get(name, (name.lower(), float("nan")))
        si = re.search(r"SI_UNIT\((?:\.(\w+)\.|\$),\.METRE\.\)", e)
        if si:
            prefix = si.group(1) or ""
            return _STEP_UNITS.get(prefix, (f"{prefix.lower()}metre", float("nan")))
    return None


def check_size(points: np.ndarray, source: str, unit: tuple[str, float] | None = None,
               step: bool = False) -> float:
    """The part's outer radius (largest distance from the axis) [m]; refuses a size no
    clutch has, naming the unit the file was read in and the likely mistake."""
    pts = np.asarray(points, dtype=float)[:2]
    size = float(np.hypot(pts[0], pts[1]).max())
    lo, hi = PLAUSIBLE_RADIUS
    if lo <= size <= hi:
        return size
    across = f"outer radius is {size:.6g} m"
    if step:
        name = unit[0] if unit else None
        read = (f"read in the file's own unit ({name}, converted to metres)" if name else
                "the file declares no length unit that is known, so its numbers were read as metres")
        raise MeshError(f"{source}: the part's {across}, {read}; a clutch's is {lo * 1e3:g} mm to "
                        f"{hi:g} m: the file's unit does not match its numbers (the CAD model was drawn in "
                        "one unit and saved declaring another): export it again with the unit it was drawn in")
    fits = [(name, f) for name, f in (("millimetres", 1e-3), ("centimetres", 1e-2), ("inches", 0.0254))
            if lo <= size * f <= hi]
    hint = ""
    if fits:
        hint = (" (it looks like " + " or ".join(f"{name} (scale the mesh by {f:g})" for name, f in fits)
                + "; gmsh scales a mesh it saves by Mesh.ScalingFactor)")
    raise MeshError(f"{source}: the part's {across}; lengths in a .msh are read as metres, not mm, and a "
                    f"clutch's outer radius is {lo * 1e3:g} mm to {hi:g} m{hint}")


def check_connected(mesh, source: str) -> None:
    """Refuse pieces of the mesh that are joined to the bore by no element edge (a floating
    island, a separately meshed part whose nodes are not shared): they have no stiffness
    against the spin."""
    comps = element_components(mesh, np.arange(mesh.t.shape[1]))
    if len(comps) <= 1:
        return
    bore = (mesh.boundaries or {}).get("bore")
    held = set() if bore is None else set(np.unique(mesh.f2t[0, bore]).tolist())
    loose = [c for c in comps if not held.intersection(c.tolist())]
    if not loose:
        return
    loose.sort(key=len, reverse=True)
    c = loose[0]
    ctr = mesh.p[:, mesh.t[:, c].ravel()].mean(axis=1) * 1e3
    area = element_set_area(mesh, c) * 1e6
    raise MeshError(f"{source}: {len(loose)} piece(s) of the mesh are joined to the bore by no element edge "
                    f"(the largest: {len(c)} elements, {area:.3g} mm^2, around ({ctr[0]:.3g}, {ctr[1]:.3g}) mm): "
                    "a floating piece has no stiffness against the spin; join it to the part (shared nodes: "
                    "gmsh Coherence / BooleanFragments before meshing) or delete it")


def bore_centre(mesh) -> tuple[np.ndarray, str]:
    """(centre (2,) [m], how it was found) of the bore: module docstring."""
    bore = np.asarray(mesh.boundaries["bore"])
    f = mesh.facets[:, bore]
    nodes, inv = np.unique(f, return_inverse=True)
    inv = inv.reshape(f.shape)
    n = len(nodes)
    _, label = connected_components(coo_matrix((np.ones(inv.shape[1]), (inv[0], inv[1])), shape=(n, n)),
                                    directed=False)
    centres, hows = [], []
    for k in np.unique(label):
        sel = nodes[label == k]
        edges = bore[np.isin(f[0], sel)]
        c, how = _loop_centre(mesh, sel, edges)
        centres.append(c)
        hows.append(how)
    how = hows[0] if len(hows) == 1 else f"the mean centre of {len(hows)} bore loops"
    return np.mean(centres, axis=0), how


def _loop_centre(mesh, nodes: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, str]:
    xy = mesh.p[:, nodes]
    n = xy.shape[1]
    if n >= 3:
        # the circle through most nodes: circumcircles of node triples (all of them for a
        # small loop, 400 deterministic ones for a large one), the one most nodes lie on
        # (within 1e-5 r) wins and is refitted on them; a keyway's nodes are outliers
        if n <= 24:
            tri = np.array([(i, j, k) for i in range(n) for j in range(i + 1, n) for k in range(j + 1, n)])
        else:
            tri = np.sort(np.random.default_rng(0).choice(n, size=(400, 3)), axis=1)
            tri = tri[(tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2])]
        c, r = _circumcircles(xy[:, tri[:, 0]], xy[:, tri[:, 1]], xy[:, tri[:, 2]])
        ok = np.isfinite(r) & (r > 0)
        if ok.any():
            c, r = c[:, ok], r[ok]
            res = np.abs(np.hypot(xy[0][:, None] - c[0], xy[1][:, None] - c[1]) - r)
            count = (res <= 1e-5 * r).sum(axis=0)
            best = int(np.argmax(count))
            on = res[:, best] <= 1e-5 * r[best]
            if on.mean() >= 0.5:
                cc, rr = _circle_fit(xy[:, on])
                return (cc if np.isfinite(rr) else c[:, best]), "the centre of the bore circle"
    a, b = mesh.p[:, mesh.facets[0, edges]], mesh.p[:, mesh.facets[1, edges]]
    w = np.linalg.norm(b - a, axis=0)
    return ((a + b) / 2 * w).sum(axis=1) / w.sum(), "the centroid of the (non-circular) bore"


def _circumcircles(a, b, c) -> tuple[np.ndarray, np.ndarray]:
    """Centres (2, k) and radii (k,) of the circles through the columns of a, b, c (inf for
    collinear points)."""
    bx, by = b[0] - a[0], b[1] - a[1]
    cx, cy = c[0] - a[0], c[1] - a[1]
    d = 2 * (bx * cy - by * cx)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / d
        uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / d
    return np.vstack([a[0] + ux, a[1] + uy]), np.hypot(ux, uy)


def _circle_fit(xy: np.ndarray) -> tuple[np.ndarray, float]:
    """Algebraic least-squares circle (Kasa): x^2 + y^2 = 2 a x + 2 b y + c."""
    x0 = xy.mean(axis=1, keepdims=True)
    x, y = xy - x0
    A = np.column_stack([2 * x, 2 * y, np.ones_like(x)])
    sol, *_ = np.linalg.lstsq(A, x * x + y * y, rcond=None)
    c = sol[:2] + x0[:, 0]
    r2 = sol[2] + sol[0] ** 2 + sol[1] ** 2
    return c, float(np.sqrt(r2)) if r2 > 0 else float("nan")


def check_axis(mesh, source: str) -> None:
    """Refuse a part whose bore is not centred on the origin (the rotation axis), naming the
    offset and the translation that fixes it."""
    c, how = bore_centre(mesh)
    off = float(np.hypot(*c))
    if off <= AXIS_TOLERANCE:
        return
    raise MeshError(f"{source}: the rotation axis is the origin, but {how} is at ({_mm(c[0])}, {_mm(c[1])}) mm, "
                    f"{_mm(off)} mm off it (allowed: {AXIS_TOLERANCE * 1e6:g} um); spun about the wrong axis every "
                    f"answer would be wrong: move the part by ({_mm(-c[0])}, {_mm(-c[1])}) mm so that the bore "
                    "is centred on the origin")


def _mm(x: float) -> str:
    """A length [m] in mm to 0.1 um, without float noise (2.5e-17 mm is 0)."""
    return f"{round(x * 1e3, 4) + 0.0:g}"
