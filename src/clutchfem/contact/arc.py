"""The contact arc of solved states: its ends found between the nodes, from the gap and the
pressure interpolated along the P2 boundary, and their error.

The contact problem is solved at the P2 nodes of the contact surface (:mod:`.lcp`): a node
either touches (gap 0, force > 0) or not (gap > 0, force 0), so an arc counted in nodes
moves in steps of one node spacing (0.5 deg on the default mesh, a third of a 1.5 deg arc).
The continuous surface's contact ends lie between a touching node and an open one.

**Signed gap.**  One field that is negative where the surface touches and positive where it
is open, continuous in the speed and the parameters at every node:

    phi_i = g_i                              at an open node (lam_i = 0),
    phi_i = -kappa p_i l_i / E*               at a touching node (g_i = 0),

g_i the node's gap [m], p_i its pressure [Pa] (force / tributary area), l_i the node spacing
there [m] (half a facet), E* the plane modulus of the part (E in plane stress, E / (1 - nu^2)
in plane strain and 3-D) and kappa = :data:`EDGE_COMPLIANCE`: p l / E* is the opening a
pressure p over one node spacing holds closed at an elastic surface, so a node that is
about to open (p -> 0) and one that is about to touch (g -> 0) both have phi -> 0.  Along
each P2 facet phi is interpolated by the quadratic through its three nodes (end, mid-edge,
end: the element's own interpolation), and a contact end is the root of that quadratic:
where the interpolated gap and pressure vanish together.  Where a node touches at the end
of the contact surface (the shoe's tip or root, a sector cut) the arc ends there exactly.
(The gap alone cannot place the end: it is zero at the touching node and its interpolant
has no root between; the pressure alone vanishes at the open node.)

A 3-D model's nodes at one in-plane position (its levels) are one position along the arc:
its gap is their smallest, its pressure their total force over their total area (from the
facets' lengths: the consistent shares L/6, 2L/3, L/6 of a straight P2 facet).

**Error (ASSUMED from measurements).**  kappa = 1/2 and the error were calibrated against
the same designs with a contact mesh ten times finer (``MeshSettings(contact_factor=0.05)``,
its nodes 0.05 deg apart): on concepts 1 and 4 (default mesh, 0.51 deg node spacing, every
25 rpm from engagement to 14 000 rpm) the ends' rms error is 0.055 deg (0.11 node spacings),
the largest 0.15 deg (0.29 spacings), the arc's mean error +0.02..+0.04 deg; kappa = 1/3 .. 1
gives rms errors within 0.02 deg of that, a larger kappa a smoother but longer arc
(``benchmarks/bench_contact_arc.py``, BENCHMARKS.md "Contact arc between nodes"); against a
case whose arc is known (a ring segment pressed into the drum, Hertz's half-width
b = sqrt(4 P R_eff / (pi E*)): ``tests/test_contact_arc.py``) it is within its error too.
Each end therefore carries :data:`END_ERROR` = 0.4 node spacings of the facet half it lies
in (0 at the end of the contact surface), and the arc the sum of its two ends' errors (a
bound, as every error band of clutchfem).  The whole-node staircase it replaces (nodes in
contact plus half a spacing at each end) erred by up to 0.79 spacings per end.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..core import wrap_angle

__all__ = ["EDGE_COMPLIANCE", "END_ERROR", "arc_error_deg", "contact_ends", "contact_modulus", "signed_gap"]

#: kappa: the opening a pressure p over one node spacing l holds closed is kappa p l / E*
EDGE_COMPLIANCE = 0.5
#: error of a contact end, in node spacings of the facet half it lies in (module docstring)
END_ERROR = 0.4


def contact_modulus(E: float, nu: float, formulation: str) -> float:
    """E* [Pa] of the part's surface: E in plane stress, E / (1 - nu^2) in plane strain and 3-D
    (the half-plane's modulus of each formulation)."""
    return float(E) if formulation == "plane-stress" else float(E) / (1.0 - float(nu) ** 2)


def _facet_lengths(nodes) -> np.ndarray:
    """(nf,) arc length [m] of each contact facet along the drum circle."""
    a = nodes.facet_angle
    return nodes.drum_radius * np.abs(wrap_angle(a[:, 2] - a[:, 0]))


def _per_position(nodes, share: tuple[float, float, float]) -> np.ndarray:
    """(k,) sum over the facets at each position of ``share`` x the facet length [m]."""
    L = _facet_lengths(nodes)
    out = np.zeros(int(nodes.position.max()) + 1)
    for c in range(3):
        np.add.at(out, nodes.facets[:, c], share[c] * L)
    return out


def _position_values(nodes, lam: np.ndarray, gaps: np.ndarray, thickness: float):
    """(touch (ns, k) bool, gap (ns, k), pressure (ns, k)) per in-plane position; the
    pressure is the position's force over its tributary area, thickness x (L/6, 2L/3, L/6)
    of the P2 facets at it (the consistent share of a uniform pressure on a straight facet:
    computed from the facets, no quadrature on the curved mesh)."""
    pos = nodes.position
    k = int(pos.max()) + 1
    ns = lam.shape[0]
    touch = np.zeros((ns, k), dtype=bool)
    np.logical_or.at(touch.T, pos, (lam > 0).T)
    gap = np.full((ns, k), np.inf)
    np.minimum.at(gap.T, pos, gaps.T)
    force = np.zeros((ns, k))
    np.add.at(force.T, pos, lam.T)
    w = _per_position(nodes, (1 / 6, 2 / 3, 1 / 6))
    press = force / (thickness * np.where(w > 0, w, np.inf))
    return touch, gap, press


def _spacing(nodes) -> np.ndarray:
    """(k,) node spacing l [m] at each position: half its facets' length (their mean)."""
    n = np.zeros(int(nodes.position.max()) + 1)
    for c in range(3):
        np.add.at(n, nodes.facets[:, c], 1.0)
    return 0.5 * _per_position(nodes, (1.0, 1.0, 1.0)) / np.maximum(n, 1.0)


def signed_gap(nodes, lam: np.ndarray, gaps: np.ndarray, thickness: float, modulus: float) -> np.ndarray:
    """phi (ns, positions) [m]: the signed gap of the module docstring at every in-plane
    position, for nodal forces ``lam`` (ns, m) [N] and gaps ``gaps`` (ns, m) [m]."""
    lam, gaps = np.atleast_2d(lam), np.atleast_2d(gaps)
    touch, gap, press = _position_values(nodes, lam, gaps, thickness)
    return np.where(touch, -EDGE_COMPLIANCE * press * _spacing(nodes)[None, :] / modulus, np.maximum(gap, 0.0))


def contact_ends(nodes, lam: np.ndarray, gaps: np.ndarray, thickness: float, modulus: float,
                 shoe: int = 0) -> np.ndarray:
    """(ns, 4): start and end polar angle [rad] of shoe ``shoe``'s contact and their errors
    [rad] (NaN where it does not touch), for nodal forces ``lam`` (ns, m) [N] and gaps ``gaps``
    (ns, m) [m] of the nodes ``nodes`` (:class:`~clutchfem.contact.ContactNodes`), a part of
    axial thickness ``thickness`` [m] and plane modulus ``modulus`` [Pa]
    (:func:`contact_modulus`).  Start < end in the polar angle (unwrapped around the shoe)."""
    lam, gaps = np.atleast_2d(lam), np.atleast_2d(gaps)
    ns = lam.shape[0]
    out = np.full((ns, 4), np.nan)
    f_shoe = _facet_shoe(nodes)
    sel = np.nonzero(f_shoe == shoe)[0]
    if not len(sel) or not ns:
        return out
    phi = signed_gap(nodes, lam, gaps, thickness, modulus)
    F = nodes.facets[sel]
    ang = nodes.facet_angle[sel]
    ref = float(np.angle(np.exp(1j * ang).mean()))
    ang = wrap_angle(ang, ref)
    v = phi[:, F]  # (ns, nf, 3) at t = 0, 1/2, 1
    # the quadratic through (0, a), (1/2, b), (1, c): A t^2 + B t + C
    a, b, c = v[..., 0], v[..., 1], v[..., 2]
    A, B, C = 2 * a - 4 * b + 2 * c, -3 * a + 4 * b - c, a
    lo_t, hi_t = _contact_span(A, B, C)  # (ns, nf): first and last t with phi <= 0 (NaN: none)
    # only facets with a touching node (an open facet whose interpolant dips below zero
    # between open nodes is no contact the solution has)
    none = ~(v <= 0).any(axis=-1)
    lo_t[none] = np.nan
    hi_t[none] = np.nan
    # polar angle along the facet: the quadratic through its three nodes' angles
    a0, a1, a2 = ang[:, 0], ang[:, 1], ang[:, 2]
    qa, qb = 2 * a0 - 4 * a1 + 2 * a2, -3 * a0 + 4 * a1 - a2

    def at(t):
        return qa * t * t + qb * t + a0

    p_lo, p_hi = at(lo_t), at(hi_t)
    lo_ang, hi_ang = np.fmin(p_lo, p_hi), np.fmax(p_lo, p_hi)
    lo_t_of = np.where(p_lo <= p_hi, lo_t, hi_t)  # the t of the smaller angle
    hi_t_of = np.where(p_lo <= p_hi, hi_t, lo_t)
    hit = np.isfinite(lo_ang).any(axis=1)
    if not hit.any():
        return out
    i_lo = np.nanargmin(np.where(np.isfinite(lo_ang), lo_ang, np.inf), axis=1)
    i_hi = np.nanargmax(np.where(np.isfinite(hi_ang), hi_ang, -np.inf), axis=1)
    r = np.arange(ns)
    out[hit, 0] = lo_ang[r, i_lo][hit]
    out[hit, 1] = hi_ang[r, i_hi][hit]
    out[hit, 2] = _end_error(lo_t_of[r, i_lo], ang[i_lo])[hit]
    out[hit, 3] = _end_error(hi_t_of[r, i_hi], ang[i_hi])[hit]
    return out


def _facet_shoe(nodes) -> np.ndarray:
    """(nf,) shoe of each facet (of its mid-edge node's position)."""
    k = int(nodes.position.max()) + 1
    shoe_of = np.full(k, -1, dtype=np.int64)
    shoe_of[nodes.position] = nodes.shoe
    return shoe_of[nodes.facets[:, 1]]


def _contact_span(A, B, C) -> tuple[np.ndarray, np.ndarray]:
    """First and last t in [0, 1] with A t^2 + B t + C <= 0 (NaN where there is none): among
    t = 0, t = 1 (where the quadratic is <= 0 there) and its real roots in [0, 1]."""
    with np.errstate(invalid="ignore", divide="ignore"):
        disc = B * B - 4 * A * C
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        quad = np.abs(A) > 1e-12 * (np.abs(B) + np.abs(C))
        lin = np.where(B != 0, -C / np.where(B != 0, B, 1.0), np.nan)
        r1 = np.where(quad, (-B - sq) / (2 * np.where(quad, A, 1.0)), lin)
        r2 = np.where(quad, (-B + sq) / (2 * np.where(quad, A, 1.0)), np.nan)
    T = np.stack([np.where(C <= 0, 0.0, np.nan), np.where(A + B + C <= 0, 1.0, np.nan),
                  np.where((r1 >= 0) & (r1 <= 1), r1, np.nan), np.where((r2 >= 0) & (r2 <= 1), r2, np.nan)], axis=-1)
    with warnings.catch_warnings():  # (all-NaN rows: no contact on that facet)
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmin(T, axis=-1), np.nanmax(T, axis=-1)


def _end_error(t: np.ndarray, ang: np.ndarray) -> np.ndarray:
    """Error [rad] of contact ends at parameter ``t`` of facets with node angles ``ang``
    (ns, 3): :data:`END_ERROR` node spacings of the facet half holding the end; 0 at a
    facet's end node (only the contact surface's end is an end there)."""
    half = np.where(t <= 0.5, np.abs(ang[:, 1] - ang[:, 0]), np.abs(ang[:, 2] - ang[:, 1]))
    at_node = (t == 0.0) | (t == 1.0)
    return np.where(at_node, 0.0, END_ERROR * half)


def arc_error_deg(ends: np.ndarray) -> np.ndarray:
    """Error [deg] of the arc end - start of :func:`contact_ends` rows (0 where no contact)."""
    return np.degrees(np.nan_to_num(ends[:, 2] + ends[:, 3]))

