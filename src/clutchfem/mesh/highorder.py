"""The high-order guard: nearly degenerate curved P2 elements left by gmsh get their interior
mid-side nodes reshaped, short outline edges straightened within 1 um, else a refusal
naming the place.

Why: the raw P2 vertex stress of a valid but nearly degenerate curved element is garbage
(BENCHMARKS.md sections 12-13: 82 000 against 5 400 MPa/(rad/s)^2 x 1e-6 on concept 4 at
fillet factor 0.0625, 6.5-7x the field's peak on concept 1 designs on the refined best
preset).  Measured cause (2026-11-26): a zone-partition curve (an interior curve of the
part, e.g. concept 4's R 27.8 mm shoe-zone circle, concept 1's flexure-zone line) meets
a fillet of the outline *tangentially*.  The two curves leave their common point in the
same direction and part as s^2 (1/R1 - 1/R2) / 2, so any mesh conforming to both has a
sliver there (concept 4: vertices 1.7 um apart, 0.05 mm long) whose curved mid-side nodes
fold it (scaled Jacobian 2e-4).  gmsh's high-order optimiser cannot move it (all its
vertices and edge nodes sit on CAD curves); this guard runs after it:

1. **Measure**: the scaled Jacobian of every curved triangle, min / max det J over the
   15-point lattice (:func:`clutchfem.mesh.scaled_jacobian`'s definition, computed here
   from the gmsh nodes), against :data:`GUARD_MIN_SJ`.
2. **Reshape interior edges**: the mid-side nodes of a bad element that lie inside a
   surface or on a zone-partition curve (not on the part's outline) are placed, among
   {where they are, their chord's midpoint, that midpoint shifted by the bow of each of
   the element's outline edges}, where the worst scaled Jacobian of the elements sharing
   them is best.  A sliver between an outline arc and a tangent partition curve is valid
   once its long interior edge bows like the arc: no outline moves, the zone partition
   moves by less than the arc's sagitta over the edge (concept 4 at fillet factor 0.0625:
   0.00021 -> 0.12; concept 1 design lhs04 on the refined best mesh: 0.00088 -> 0.10).
3. **Straighten short outline edges** (if still bad): a bad element's outline edge is replaced by its
   chord if the chord is within :data:`MAX_SAGITTA` of the curve (ASSUMED 1 um: far below
   any cutting process' tolerance, 10-50 um for laser / wire EDM / fine blanking).
4. **Refuse**: an element still below the threshold raises :class:`MeshError` with its
   position, its scaled Jacobian and the cure (a different fillet factor or mesh size).

Two thresholds.  Below :data:`GUARD_MIN_SJ` = 0.05 an element is repaired or refused:
every mesh measured with its worst element at 0.09-0.16 read a plane-stress vertex peak
within 1.07x of the quadrature-point peak, the degenerate ones are at 2e-4 to 1e-3.  Above
it, ``MeshSettings.reshape_below`` (0.05 for the fast preset, whose mesh stays bit for bit
as it was; 0.2 for the best preset and the peak-stress refinement) sends the elements below
it to step 2 only: the thick plane model (:class:`clutchfem.fe.FEModelThick`) is sensitive
to curved cusp slivers at 0.1-0.14 that plane stress does not notice (concept 1 design
lhs03, refined best mesh, 14 000 rpm: 1427 MPa at the sliver against 1077 MPa at the
fillet once reshaped; engagement and torque moved by 1e-6).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import gmsh
import numpy as np

from ..core import MeshError

#: elements below this scaled Jacobian are repaired or refused (module docstring)
GUARD_MIN_SJ = 0.05
#: the largest chord error [m] accepted when an outline edge of a bad element is straightened
MAX_SAGITTA = 1e-6
#: gmsh's high-order optimiser runs when its own minimum scaled Jacobian is below this
OPTIMISE_BELOW = 0.2
_P2_TRIANGLE = 9  # gmsh element type: 6-node second order triangle
_EDGES = ((0, 1), (1, 2), (2, 0))  # the vertices of mid-side nodes 3, 4, 5


@dataclass(frozen=True)
class GuardReport:
    """What the guard did to one mesh: the worst scaled Jacobian before and after, the
    mid-side nodes moved (inside the part / on its outline) and the largest chord error."""

    worst_before: float
    worst_after: float
    moved_interior: int
    moved_outline: int
    max_sagitta: float


def p2_scaled_jacobian(x: np.ndarray) -> np.ndarray:
    """(ne,) min det J / max det J over the 4th-order lattice of every P2 triangle, signed by
    its median orientation; ``x`` (ne, 6, 2): vertices, then mid-sides 01, 12, 20 (gmsh's
    and scikit-fem's order).  Equal to :func:`clutchfem.mesh.scaled_jacobian` (tested)."""
    x = np.asarray(x, dtype=float)
    pts = [(i / 4, j / 4) for j in range(5) for i in range(5 - j)]
    dets = []
    for s, t in pts:
        gs = np.array([-3 + 4 * s + 4 * t, 4 * s - 1, 0.0, 4 - 8 * s - 4 * t, 4 * t, -4 * t])
        gt = np.array([-3 + 4 * s + 4 * t, 0.0, 4 * t - 1, -4 * s, 4 * s, 4 - 4 * s - 8 * t])
        ds, dt = x.transpose(0, 2, 1) @ gs, x.transpose(0, 2, 1) @ gt  # (ne, 2) each
        dets.append(ds[:, 0] * dt[:, 1] - ds[:, 1] * dt[:, 0])
    det = np.stack(dets, axis=1)
    det = det * np.sign(np.median(det, axis=1))[:, None]
    big = np.max(det, axis=1)
    return np.min(det, axis=1) / np.where(big > 0, big, 1.0)


def optimise_high_order() -> None:
    """gmsh's high-order optimiser if some curved element's gmsh minSJ < :data:`OPTIMISE_BELOW`."""
    worst = 1.0
    for tags in gmsh.model.mesh.getElements(2)[1]:
        q = gmsh.model.mesh.getElementQualities(tags, "minSJ")
        if len(q):
            worst = min(worst, float(np.min(q)))
    if worst < OPTIMISE_BELOW:
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
        # gmsh raises its optimiser's "Failed to reach critical value ... ScaledJac" as an error:
        # from inside an OpenMP region that is std::terminate (the process aborts, measured in a
        # robust-design run), elsewhere an exception that refused a usable design.  The optimiser
        # then hands back the mesh it started from; :func:`guard_high_order` judges (and repairs
        # or refuses) it after this, so gmsh only reports here (AbortOnError 1) instead of throwing.
        # A failed optimisation may leave a worse mesh than it started from: it is undone.
        tags, coords, _ = gmsh.model.mesh.getNodes(-1, -1, includeBoundary=True, returnParametricCoord=False)
        prev = gmsh.option.getNumber("General.AbortOnError")
        gmsh.option.setNumber("General.AbortOnError", 1)
        gmsh.logger.start()
        try:
            gmsh.model.mesh.optimize("HighOrder")
            failed = any(m.startswith("Error") for m in gmsh.logger.get())
        finally:
            gmsh.logger.stop()
            gmsh.option.setNumber("General.AbortOnError", prev)
        if failed:
            xyz = np.asarray(coords).reshape(-1, 3)
            for t, c in zip(tags, xyz):
                gmsh.model.mesh.setNode(int(t), c.tolist(), [])


def guard_high_order(where: str, *, mirrored: bool = False, threshold: float = GUARD_MIN_SJ,
                     reshape_below: float | None = None, max_sagitta: float = MAX_SAGITTA) -> GuardReport:
    """Repair or refuse the nearly degenerate curved triangles of the current gmsh model
    (module docstring); ``where`` names the part in a refusal, ``mirrored``: the mesh will
    be reflected y -> -y afterwards (the refusal names the final position);
    ``reshape_below`` (default ``threshold``): elements below it get step 2 (reshaping their
    interior mid-side nodes); below ``threshold`` steps 3 and 4."""
    target = threshold if reshape_below is None else max(reshape_below, threshold)
    etags, enodes = gmsh.model.mesh.getElementsByType(_P2_TRIANGLE)
    if not len(etags):
        return GuardReport(1.0, 1.0, 0, 0, 0.0)
    ntags, coords, _ = gmsh.model.mesh.getNodes(-1, -1, includeBoundary=True, returnParametricCoord=False)
    ntags = np.asarray(ntags, dtype=np.int64)
    index = np.full(int(ntags.max()) + 1, -1, dtype=np.int64)
    index[ntags] = np.arange(len(ntags))
    xy = np.asarray(coords, dtype=float).reshape(-1, 3)[:, :2].copy()
    conn = index[np.asarray(enodes, dtype=np.int64).reshape(-1, 6)]
    sj = p2_scaled_jacobian(xy[conn])
    worst0 = float(np.min(sj))
    if worst0 >= target:
        return GuardReport(worst0, worst0, 0, 0, 0.0)
    outline = _outline_nodes(index)
    moved_in: set[int] = set()
    moved_out: set[int] = set()
    sag_max = 0.0
    owners = _mid_owners(conn, len(xy))
    for e in np.argsort(sj)[: int(np.sum(sj < target))]:
        if sj[e] < target:
            moved_in |= _reshape_interior(e, conn, xy, outline, owners)
    sj = p2_scaled_jacobian(xy[conn])
    for e in np.nonzero(sj < threshold)[0]:
        for k, (a, b) in enumerate(_EDGES):
            m = conn[e, 3 + k]
            mid = 0.5 * (xy[conn[e, a]] + xy[conn[e, b]])
            sag = float(np.hypot(*(xy[m] - mid)))
            if outline[m] and 0.0 < sag <= max_sagitta:
                xy[m] = mid
                moved_out.add(int(m))
                sag_max = max(sag_max, sag)
    sj = p2_scaled_jacobian(xy[conn])
    for m in moved_in | moved_out:
        gmsh.model.mesh.setNode(int(ntags[m]), [xy[m, 0], xy[m, 1], 0.0], [])
    worst = float(np.min(sj))
    if worst < threshold:
        e = int(np.argmin(sj))
        c = xy[conn[e, :3]].mean(axis=0) * [1.0, -1.0 if mirrored else 1.0] * 1e3
        raise MeshError(f"{where}: a curved element at ({c[0]:.3f}, {c[1]:.3f}) mm is nearly degenerate (scaled "
                        f"Jacobian {worst:.2g} < {threshold:g}; {int(np.sum(sj < threshold))} element(s)) and could "
                        "not be repaired: its raw vertex stresses would be meaningless; change the fillet factor or "
                        "the mesh size a little (two curves of the part meet at a very small angle there)")
    return GuardReport(worst0, worst, len(moved_in), len(moved_out), sag_max)


def _mid_owners(conn: np.ndarray, nnodes: int) -> np.ndarray:
    """(nnodes, 2) the (at most two) elements having each node as a mid-side node, -1 none."""
    flat = conn[:, 3:].ravel()
    el = np.repeat(np.arange(len(conn)), 3)
    order = np.argsort(flat, kind="stable")
    f, el = flat[order], el[order]
    first = np.r_[True, f[1:] != f[:-1]]
    own = np.full((nnodes, 2), -1, dtype=np.int64)
    own[f[first], 0] = el[first]
    own[f[~first], 1] = el[~first]
    return own


def _reshape_interior(e: int, conn: np.ndarray, xy: np.ndarray, outline: np.ndarray, owners: np.ndarray) -> set[int]:
    """Place the interior mid-side nodes of element ``e`` (not on the outline) where the
    smallest scaled Jacobian of the elements sharing them is largest, among: where they
    are, their edge's midpoint, and the midpoint shifted by the bow (mid-side node minus
    chord midpoint) of each of ``e``'s outline edges -- a sliver between an outline arc and
    a tangent partition curve becomes valid when its long interior edge bows like the arc.
    Modifies ``xy``; returns the nodes moved."""
    mids = conn[e, 3:]
    free = [k for k in range(3) if not outline[mids[k]]]
    if not free:
        return set()
    chord = {k: 0.5 * (xy[conn[e, a]] + xy[conn[e, b]]) for k, (a, b) in enumerate(_EDGES)}
    bows = [xy[mids[k]] - chord[k] for k in range(3) if outline[mids[k]]]
    options = {k: [xy[mids[k]].copy(), chord[k]] + [chord[k] + d for d in bows] for k in free}
    near = np.unique(owners[mids[free]])
    near = near[near >= 0]
    best, best_q = None, -np.inf
    for combo in itertools.product(*(range(len(options[k])) for k in free)):
        for k, i in zip(free, combo):
            xy[mids[k]] = options[k][i]
        q = float(np.min(p2_scaled_jacobian(xy[conn[near]])))
        if q > best_q + 1e-12:
            best, best_q = combo, q
    for k, i in zip(free, best):
        xy[mids[k]] = options[k][i]
    return {int(mids[k]) for k, i in zip(free, best) if i != 0}


def _outline_nodes(index: np.ndarray) -> np.ndarray:
    """(nnodes,) True for the nodes on the part's outline curves (the combined boundary of all
    its surfaces) or on geometry points."""
    surfaces = gmsh.model.getEntities(2)
    outline_curves = {abs(t) for d, t in gmsh.model.getBoundary(surfaces, combined=True, oriented=False) if d == 1}
    on = np.zeros(int(np.max(index)) + 1, dtype=bool)
    for c in outline_curves:
        tags = np.asarray(gmsh.model.mesh.getNodes(1, c, includeBoundary=True)[0], dtype=np.int64)
        on[index[tags]] = True
    for _, pt in gmsh.model.getEntities(0):
        tags = np.asarray(gmsh.model.mesh.getNodes(0, pt)[0], dtype=np.int64)
        on[index[tags]] = True
    return on
