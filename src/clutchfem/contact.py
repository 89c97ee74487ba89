"""Rigid-drum contact: the contact nodes and a small linear complementarity solver.

The drum is rigid, coaxial, of inner radius R_d.  Contact is node-to-circle at the P2 nodes
(vertices and mid-edge nodes) of the ``contact`` boundary: node i at x_i has the exact
initial gap g0_i = R_d - |x_i| and outward normal n_i = x_i/|x_i| (the drum's, evaluated on
the exact circle, so a coarse chord does not eat the 0.6 mm clearance).  With small
displacements the gap is g_i = g0_i - n_i . u_i.

A compressive nodal force lam_i >= 0 acts on the part along -n_i; with the drum held and
the hub turning in direction s (+1 ccw, -1 cw) the shoe slides along s e_theta, so full-slip
Coulomb friction adds -s mu lam_i t_i (t_i = e_theta).  With the condensed compliance the
contact conditions at one speed are the LCP

    w = q + G lam >= 0,  lam >= 0,  w . lam = 0

with w the gaps.  G is m x m (m = contact nodes), symmetric positive definite without
friction and non-symmetric with it (still a P-matrix for moderate mu, so the solution is
unique).  :func:`solve_lcp` uses a primal-dual active set (exact after finitely many steps,
warm-started from the previous speed) and falls back to Lemke's complementary pivoting.
A result that does not satisfy the conditions to tolerance raises :class:`SolverError`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.spatial import cKDTree
from skfem import Basis

from .errors import MeshError, SolverError
from .mesh import ClutchMesh


@dataclass
class ContactNodes:
    """The candidate contact nodes of a model (m of them)."""

    dof_x: np.ndarray
    dof_y: np.ndarray
    xy: np.ndarray  # (2, m) positions [m]
    normal: np.ndarray  # (2, m) outward unit normals
    tangent: np.ndarray  # (2, m) e_theta (ccw)
    gap0: np.ndarray  # (m,) initial gaps [m]
    _weight: object  # callable () -> (m,) weights, evaluated once on first use
    shoe: np.ndarray  # (m,) index of the shoe the node belongs to (-1 if unknown)
    angle: np.ndarray  # (m,) polar angle [rad]

    @property
    def m(self) -> int:
        return len(self.gap0)

    @property
    def weight(self) -> np.ndarray:
        """(m,) tributary length int phi_i ds [m] of each node (pressure = force / (h weight));
        computed on first use: only pressure output needs it."""
        if callable(self._weight):
            self._weight = self._weight()
        return self._weight


def contact_nodes(cm: ClutchMesh, basis: Basis, drum_radius: float) -> ContactNodes:
    """Collect contact nodes from the ``contact`` group (per shoe from ``contact_<i>``)."""
    from .fem import contact_weights

    mesh = cm.mesh
    b = mesh.boundaries or {}
    if "contact" not in b:
        raise MeshError(f"{cm.source}: no 'contact' boundary group; cannot model the drum")
    facets = cm.boundary("contact")
    d = basis.get_dofs(facets)
    dx = np.concatenate([d.nodal["u^1"], d.facet["u^1"]])
    dy = np.concatenate([d.nodal["u^2"], d.facet["u^2"]])
    order = np.argsort(dx)
    dx, dy = dx[order], dy[order]
    xy = basis.doflocs[:, dx]
    r = np.hypot(xy[0], xy[1])
    n = xy / r
    t = np.vstack([-n[1], n[0]])
    gap0 = drum_radius - r
    if np.any(gap0 < -1e-9 * drum_radius):
        worst = float(-gap0.min())
        raise MeshError(f"drum radius {drum_radius * 1e3:.4f} mm lies inside the part: contact nodes "
                        f"overlap the drum by up to {worst * 1e3:.4f} mm (drum radius must exceed "
                        f"{r.max() * 1e3:.4f} mm)")
    # the contact surface must face the drum: outward boundary normals point away from the axis
    _check_facing(cm, facets)
    dx_all, merge = dx, None
    # one-sector model: a contact node on cut_b is the rotated copy of a node on cut_a (the
    # same node of the full part, u_b = R u_a).  Keep one of each pair, with both weights:
    # two copies would make G singular and split their force arbitrarily.
    if cm.sector_angle is not None and "cut_b" in b:
        db = basis.get_dofs(cm.boundary("cut_b"))
        copy = np.isin(dx, np.concatenate([db.nodal["u^1"], db.facet["u^1"]]))
        if copy.any():
            cs, sn = math.cos(cm.sector_angle), math.sin(cm.sector_angle)
            back = np.array([[cs, sn], [-sn, cs]]) @ xy[:, copy]  # rotated by -sector_angle
            keep = np.nonzero(~copy)[0]
            dist, j = cKDTree(xy[:, keep].T).query(back.T)
            if dist.max() > 1e-8 * drum_radius:
                raise MeshError(f"{cm.source}: a contact node on cut_b has no partner on cut_a "
                                f"(mismatch {dist.max():.3g} m)")
            merge = (keep, j, copy)
            dx, dy, xy, n, t, gap0 = (a[..., keep] for a in (dx, dy, xy, n, t, gap0))

    def weights() -> np.ndarray:
        w = contact_weights(cm, basis, facets)[dx_all]
        if merge is not None:
            keep, j, copy = merge
            np.add.at(w, keep[j], w[copy])
            w = w[keep]
        return w

    shoe = -np.ones(len(dx), dtype=np.int64)
    for name, fac in b.items():
        if name.startswith("contact_"):
            i = int(name.split("_")[1])
            dd = basis.get_dofs(np.asarray(fac))
            ids = np.concatenate([dd.nodal["u^1"], dd.facet["u^1"]])
            shoe[np.isin(dx, ids)] = i
    if np.all(shoe < 0):
        shoe[:] = 0
    return ContactNodes(dof_x=dx, dof_y=dy, xy=xy, normal=n, tangent=t, gap0=np.maximum(gap0, 0.0),
                        _weight=weights, shoe=shoe, angle=np.arctan2(xy[1], xy[0]))


def _check_facing(cm: ClutchMesh, facets: np.ndarray) -> None:
    mesh = cm.mesh
    p = mesh.p
    f = mesh.facets[:, facets]
    mid = 0.5 * (p[:, f[0]] + p[:, f[1]])
    elem = mesh.f2t[0, facets]
    cen = p[:, mesh.t[:, elem]].mean(axis=1)
    outward = mid - cen  # points out of the element, roughly along the facet normal
    radial = np.sum(outward * mid, axis=0) / np.linalg.norm(mid, axis=0)
    if np.mean(radial > 0) < 0.9:
        raise MeshError(f"{cm.source}: the 'contact' group faces inwards (its outward normals point "
                        "towards the axis); it must be the shoes' outer surface facing the drum")


# ---------------------------------------------------------------------------------------
# LCP
# ---------------------------------------------------------------------------------------
def lcp_residual(G, q: np.ndarray, lam: np.ndarray) -> float:
    """Max violation of the LCP conditions, scaled to gap units.  ``G`` as in :func:`solve_lcp`."""
    cols = _as_columns(G)
    S = np.nonzero(lam)[0]
    GS = cols(S)
    w = q + GS @ lam[S]
    d = np.abs(GS[S, np.arange(len(S))]) if len(S) else np.zeros(0)
    scale = float(np.max(d, initial=0.0)) if isinstance(G, _Lazy) else float(np.max(np.abs(np.diag(G))))
    return float(max(np.max(-w, initial=0.0), np.max(-lam, initial=0.0) * scale,
                     np.max(np.abs(w * lam), initial=0.0) / max(np.max(lam, initial=0.0), 1e-300)))


class _Lazy:
    """Columns of G on demand: ``cols(idx) -> G[:, idx]``."""

    def __init__(self, cols):
        self.cols = cols

    def __call__(self, idx):
        return self.cols(np.asarray(idx, dtype=np.int64))


def lazy(cols) -> _Lazy:
    """Wrap a column provider ``cols(idx) -> G[:, idx]`` (m x len(idx)) for :func:`solve_lcp`."""
    return _Lazy(cols)


def _as_columns(G):
    if isinstance(G, _Lazy):
        return G
    G = np.asarray(G)
    return lambda idx: G[:, idx]


def solve_lcp(G, q: np.ndarray, active0: np.ndarray | None = None,
              tol: float = 1e-12, max_iter: int = 100) -> tuple[np.ndarray, np.ndarray]:
    """Solve w = q + G lam, 0 <= lam perp w >= 0.  Returns (lam, active mask).

    ``G`` is the m x m matrix, or ``lazy(cols)``: a provider of its columns.  The active-set
    method only ever needs the columns of the nodes it makes active (a handful of the m
    contact nodes: the shoes touch the drum on a short arc), so a lazy G saves the
    condensation of all the others; the Lemke fallback asks for every column.
    ``tol`` is in gap units (metres); the check is relative to the problem scale."""
    m = len(q)
    scale_q = max(float(np.max(np.abs(q))), 1e-300)
    if np.all(q >= 0):
        return np.zeros(m), np.zeros(m, dtype=bool)
    lam, active = _active_set(G, q, active0, max_iter)
    res = math.inf if lam is None else lcp_residual(G, q, lam)
    if res > max(tol, 1e-9 * scale_q):
        lam = _lemke(_as_columns(G)(np.arange(m)), q)
        active = lam > 0
        res = lcp_residual(G, q, lam)
    if res > max(tol, 1e-9 * scale_q) * 10:
        raise SolverError(f"contact solve did not converge (complementarity residual {res:.3g} m)")
    return lam, active


def _active_set(G, q, active0, max_iter):
    m = len(q)
    cols = _as_columns(G)
    active = (q < 0) if active0 is None else active0.copy()
    if not active.any():
        active = q < 0
    c = None  # 1 / mean diagonal: balances forces against gaps
    seen = set()
    for _ in range(max_iter):
        lam = np.zeros(m)
        A = np.nonzero(active)[0]
        GA = cols(A)
        if len(A):
            if c is None:
                c = 1.0 / np.mean(np.diag(GA[A]))
            try:
                lam[A] = sla.solve(GA[A], -q[A])
            except (sla.LinAlgError, ValueError):
                return None, active
        w = q + GA @ lam[A]
        new = (lam - (c or 0.0) * w) > 0 if c is not None else w < 0
        key = new.tobytes()
        if np.array_equal(new, active):
            return lam, active
        if key in seen:  # cycling
            return None, active
        seen.add(key)
        active = new
    return None, active


def _lemke(M: np.ndarray, q: np.ndarray, max_iter: int | None = None) -> np.ndarray:
    """Lemke's complementary pivoting with covering vector e (dense tableau)."""
    n = len(q)
    max_iter = max_iter or 50 * n + 100
    # tableau [I, -M, -e, q] for w - M z - e z0 = q
    T = np.hstack([np.eye(n), -M, -np.ones((n, 1)), q.reshape(-1, 1)]).astype(float)
    basis = list(range(n))  # w variables basic
    z0 = 2 * n
    r = int(np.argmin(q))
    entering = z0
    for _ in range(max_iter):
        # pivot on (r, entering)
        T[r] /= T[r, entering]
        for i in range(n):
            if i != r and T[i, entering] != 0.0:
                T[i] -= T[i, entering] * T[r]
        leaving = basis[r]
        basis[r] = entering
        if leaving == z0:
            break
        # complement of the leaving variable enters
        entering = leaving + n if leaving < n else leaving - n
        col = T[:, entering]
        pos = col > 1e-14 * np.max(np.abs(col))
        if not pos.any():
            raise SolverError("contact solve failed: Lemke ray termination (no solution found)")
        ratios = np.full(n, np.inf)
        ratios[pos] = T[pos, -1] / col[pos]
        rmin = ratios.min()
        cand = np.nonzero(ratios <= rmin * (1 + 1e-12) + 1e-300)[0]
        # prefer z0 leaving to terminate
        r = next((i for i in cand if basis[i] == z0), int(cand[0]))
    else:
        raise SolverError("contact solve failed: Lemke iteration limit reached")
    z = np.zeros(2 * n + 1)
    for i, bvar in enumerate(basis):
        z[bvar] = T[i, -1]
    return np.maximum(z[n:2 * n], 0.0)
