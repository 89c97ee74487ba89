"""One worn state of a part: its FE contact with the worn clearance, the answers the life
run reads from it (engagement, slip, torque, arc, the clutch torque and contact pressure
against speed), and the rebuild of the worn part (:class:`WornModel`, :func:`rebuild`).

The worn depth w_i [m] of contact node i (and the drum's uniform worn depth w_d) opens its
rest gap: the contact problem of :class:`~clutchfem.loadcase.LoadCase` with

    q(w) = g0_i + e_i + w_i + w_d + u_drum(w) - u_free,i(w),     e_i = c0(s_i) - g0_i,

on the same factorisation and condensed compliance (the part's stiffness and mass as
built): no assembly, no factorisation per worn state.  c0(s) is the *new* part's rest
clearance at arc fraction s along its shoe (0 root, 1 tip); e_i is zero on the new part and,
on a rebuilt part, the difference between the clearance the worn profile should have and
the one its mesh has (the 17-value table spline cannot follow a sharp wear scar: the
difference is kept in the gap, so the clearance is exact and only the stiffness and mass
follow the spline).

:func:`rebuild` makes the worn part anew (a concept design: the ``table`` profile of
:mod:`clutchfem.geometry` through c0 + w at its 17 knots, meshed and factorised again): the
shoe loses mass and stiffness as it wears.  How often this pays is the life run's
``rebuild_depth`` (its error measured in ``benchmarks/bench_life.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..contact import lazy, smooth_lcp, solve_lcp
from ..core import InputError, ParameterError, SolverError, brentq, rad_s_to_rpm, rpm_to_rad_s, wrap_angle
from ..geometry import TABLE_FIELDS, TABLE_N, MeshSettings, worn_from
from ..loadcase import Design, contact_extent

__all__ = ["RebuildRefused", "WornModel", "StateAnswers", "rebuild", "state_fields"]


class RebuildRefused(InputError):
    """The worn part cannot be made anew: a concept rule refuses its worn profile (say a face
    worn through to a rule that reads the face itself).  The message names the rule; the life
    can still run with the wear kept in the contact gaps (``rebuild_depth=None``).

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.lifetime import RebuildRefused
    >>> issubclass(RebuildRefused, cf.InputError)
    True
    """


@dataclass(frozen=True)
class StateAnswers:
    """The answers of one worn state (units in the names)."""

    engagement_rpm: float | None
    slip_rpm: float | None
    torque_at_max_engine_torque_Nm: float
    contact_arc_deg: float
    contact_share: float
    table_rpm: np.ndarray
    table_torque_Nm: np.ndarray
    table_pressure_Pa: np.ndarray  # (n speeds, m nodes)
    pressure_at_max_engine_torque_Pa: np.ndarray  # (m,)


class WornModel:
    """A design's contact problem with worn clearances (module docstring)."""

    def __init__(self, design: Design, c0=None, made=None):
        if not isinstance(design, Design):
            raise InputError(f"a worn model needs a Design (got {type(design).__name__})")
        self.design = design
        self.case = design.case()
        c = self.case.contact
        if c is None:
            raise InputError(f"{design.name}: the part has no contact surface facing a drum: nothing wears")
        self.contact = c
        nd = c.nodes
        self.m = nd.m
        arcs = list(design.cm.contact_arcs)
        s = np.zeros(self.m)
        for k, (root, tip) in enumerate(arcs):
            sel = nd.shoe == k
            ang = wrap_angle(nd.angle[sel], 0.5 * (root + tip))
            s[sel] = (ang - root) / (tip - root) if tip != root else 0.5
        self.s = s
        self.arc_deg = abs(math.degrees(arcs[0][1] - arcs[0][0])) if arcs else math.nan
        # the new part's clearance along the shoe (a function of s), and the gap correction e
        self.c0 = c0 if c0 is not None else (np.sort(s), nd.gap0[np.argsort(s)].copy())
        #: the concept parameters of the part as made (the rebuilds' design rules read them)
        self.made = made if made is not None else design.params
        self.base = np.interp(s, *self.c0) - nd.gap0
        self.thickness = design.thickness
        self.weight = nd.weight
        self.scale = self.case.scale

    # ------------------------------------------------------------------ contact
    def q(self, omega: float, extra: np.ndarray) -> np.ndarray:
        c = self.contact
        return c.nodes.gap0 + self.base + extra + c.drum_gap(omega) - self.case.response.free_normal(omega)

    def solve(self, omega: float, extra: np.ndarray, active0=None) -> tuple[np.ndarray, np.ndarray]:
        """(nodal contact forces [N], active set) at ``omega`` [rad/s] with the worn depths
        ``extra`` [m] added to the rest gaps."""
        q = self.q(omega, extra)
        if np.all(q >= 0):
            return np.zeros(self.m), np.zeros(self.m, dtype=bool)
        lim = self.case.omega_limit
        if lim is not None and omega >= lim * (1 - 1e-9):
            raise SolverError(f"{rad_s_to_rpm(omega):.0f} rpm is past the divergence speed "
                              f"{rad_s_to_rpm(lim):.0f} rpm of the free part: the worn state is not solved there")
        if active0 is None or not active0.any():
            active0 = np.zeros(self.m, dtype=bool)
            active0[int(np.argmin(q))] = True
        G = self.case.response.columns(omega)
        Cd = self.contact.drum_compliance
        if Cd is not None:
            G = lazy(lambda idx, G=G: G(idx) + Cd[:, idx])
        lam, act = solve_lcp(G, q, active0)
        if self.contact.smoothing > 0:
            lam, act = smooth_lcp(G, q, lam, self.contact.smoothing)
        return lam, act

    def pressure_jacobian(self, omega: float, active: np.ndarray) -> np.ndarray:
        """dp_A/dw_A [Pa/m] of the nodes ``active`` at ``omega`` [rad/s]: the worn depth opens
        the gap, lam_A = -G_AA^-1 q_A, p = lam / (h w)."""
        A = np.asarray(active)
        G = np.asarray(self.case.response.columns(omega)(A))[A]
        if self.contact.drum_compliance is not None:
            G = G + self.contact.drum_compliance[np.ix_(A, A)]
        return -np.linalg.inv(G) / (self.thickness * self.weight[A])[:, None]

    def torque(self, lam: np.ndarray) -> float:
        return self.case.friction_torque(lam)

    def pressure(self, lam: np.ndarray) -> np.ndarray:
        w = self.weight
        return np.where(w > 0, lam / (self.thickness * np.where(w > 0, w, 1.0)), 0.0)

    def engagement(self, extra: np.ndarray) -> float | None:
        """Engagement speed [rad/s] with the worn gaps (the root of the smallest gap)."""
        c, r = self.contact, self.case.response
        g = c.nodes.gap0 + self.base + extra
        out = c.nodes.normal_displacement(self.design.model.u1) - c.drum_gap(1.0)
        pos = out > 0
        if not pos.any():
            return None
        w0 = math.sqrt(float(np.min(g[pos] / out[pos])))
        if r.linear:
            return w0

        def h(w):
            return float(np.min(g + c.drum_gap(w) - r.free_normal(w)))

        lim = r.omega_limit * (1 - 1e-6) if r.omega_limit else 10 * w0
        lo, hi = 0.0, w0
        while h(hi) > 0:
            lo, hi = hi, min(hi * 1.05, lim)
            if hi >= lim:
                return None
        return brentq(h, lo, hi, xtol=1e-10 * hi, rtol=1e-13)

    def extent(self, omega: float, lam: np.ndarray, extra: np.ndarray) -> float:
        """Contact share of shoe 0's nominal arc at ``omega`` (0: no contact)."""
        q = self.q(omega, extra)
        A = np.nonzero(lam)[0]
        gaps = q.copy()
        if len(A):
            G = self.case.response.columns(omega)(A)
            if self.contact.drum_compliance is not None:
                G = G + self.contact.drum_compliance[:, A]
            gaps = q + G @ lam[A]
        # the contact ends need the gaps at the design's own rest gaps: shift them back
        e = contact_extent(self.contact, lam[None, :], gaps[None, :], self.thickness, self.case.contact_modulus, 0)[0]
        if not np.isfinite(e[0]):
            return 0.0
        root, tip = self.design.cm.contact_arcs[0]
        return float(abs(e[1] - e[0]) / abs(tip - root))

    # ------------------------------------------------------------------ answers
    def answers(self, extra: np.ndarray, engine, grid_rpm: np.ndarray) -> StateAnswers:
        """Engagement, slip (the first crossing of the clutch and engine torques, refined with
        FE solves), torque and contact arc at the rpm of maximum engine torque, and the
        tables of torque and pressure against speed on ``grid_rpm`` plus the engagement
        speed (no torque at and below it)."""
        w_eng = self.engagement(extra)
        n_eng = None if w_eng is None else rad_s_to_rpm(w_eng)
        grid = np.asarray(grid_rpm, dtype=float)
        if n_eng is not None:
            grid = np.union1d(grid, [n_eng])
        T = np.zeros(len(grid))
        P = np.zeros((len(grid), self.m))
        act = None
        for k, n in enumerate(grid):
            if n_eng is None or n <= n_eng:
                continue
            lam, act = self.solve(rpm_to_rad_s(n), extra, act)
            T[k], P[k] = self.torque(lam), self.pressure(lam)
        slip = self.slip_rpm(extra, engine, grid, T, n_eng)
        n_t = float(engine.rpm_max_torque)
        lam_t, _ = self.solve(rpm_to_rad_s(n_t), extra) if n_eng is not None and n_t > n_eng else \
            (np.zeros(self.m), None)
        share = self.extent(rpm_to_rad_s(n_t), lam_t, extra) if lam_t.any() else 0.0
        return StateAnswers(engagement_rpm=n_eng, slip_rpm=slip, torque_at_max_engine_torque_Nm=self.torque(lam_t),
                            contact_arc_deg=share * self.arc_deg, contact_share=share, table_rpm=grid,
                            table_torque_Nm=T, table_pressure_Pa=P,
                            pressure_at_max_engine_torque_Pa=self.pressure(lam_t))

    def slip_rpm(self, extra, engine, grid, T, n_eng) -> float | None:
        """First speed where the clutch torque reaches the engine torque, bracketed on the
        table and refined by Brent's method on FE solves (1e-9 relative)."""
        lo, hi = engine.rpm_range
        inside = (grid >= lo) & (grid <= hi)
        x, t = grid[inside], T[inside]
        d = t - np.asarray(engine.torque_at(x))
        hold = (d >= 0) & (t > 0)
        if not hold.any():
            return None
        k = int(np.argmax(hold))
        if k == 0:
            return float(x[0])

        def f(n):
            if n_eng is not None and n <= n_eng:
                return -float(engine.torque_at(n))
            lam, _ = self.solve(rpm_to_rad_s(n), extra)
            return self.torque(lam) - float(engine.torque_at(n))

        return brentq(f, float(x[k - 1]), float(x[k]), xtol=1e-9 * float(x[k]), rtol=1e-12)

    @cached_property
    def knots(self) -> np.ndarray:
        return np.linspace(0.0, 1.0, TABLE_N)


def rebuild(model: WornModel, worn: np.ndarray) -> tuple[WornModel, np.ndarray]:
    """The worn part made anew (module docstring): the concept's ``table`` profile through
    the worn clearance c0 + w at the 17 knots, meshed and solved again, and the worn depths
    carried over to its contact nodes (by arc fraction along the shoe).  Returns (the new
    model, the worn depths at its nodes).

    The concept's design rules read the part *as made* (:func:`clutchfem.geometry.worn_from`):
    wear takes material off the face, the flexures and heels stay where they were cut, so a
    design on a rule's bound (an optimum) stays buildable as it wears.  A worn profile that a
    rule still refuses raises :class:`RebuildRefused` naming the rule."""
    d = model.design
    if d.params is None or d.concept is None:
        raise InputError(f"{d.name}: a user mesh has no profile parameters: its wear is kept in the contact gaps only")
    s_sorted = np.argsort(model.s)
    c0 = model.c0
    knots = model.knots
    wk = np.interp(knots, model.s[s_sorted], worn[s_sorted])
    v = np.interp(knots, *c0) + wk
    vals = {n: float(x) for n, x in zip(TABLE_FIELDS, v)}
    ms = MeshSettings(**d.cm.mesh_settings) if d.cm.mesh_settings else None
    # the worn face of the part as made: the concept's rules that place its flexures against
    # the shoe's outer surface read the surface it was made with (wear does not move them)
    with worn_from(model.made):
        try:
            p = d.params.replace(profile="table", **vals)
        except ParameterError as exc:
            raise RebuildRefused(f"{d.name}: the part worn {1e6 * float(np.max(worn)):.1f} um deep cannot be rebuilt: "
                             f"{exc}; run the life with rebuild_depth=None (--rebuild-depth never): the wear "
                             "then stays in the contact gaps of the new part's model") from None
        nd = Design.from_concept(d.concept, p, d.op, ms)
    new = WornModel(nd, c0=c0, made=model.made)
    w_new = np.interp(new.s, model.s[s_sorted], worn[s_sorted])
    return new, w_new


def state_fields(model: WornModel, extra: np.ndarray, worn: np.ndarray, rpm: float, starts: float) -> dict:
    """The fields of one worn state for its .vtu (:func:`~clutchfem.lifetime.life_files`): the
    mesh of the part as it stands (rebuilt or new), the in-plane displacement [m] and the von
    Mises stress [Pa] at ``rpm`` with the worn gaps ``extra`` (the contact solved on the one
    factorised model; at each vertex the largest von Mises of its elements and stress levels)
    and the worn depth ``worn`` [m] at the contact vertices (0 elsewhere; on a rebuilt part
    the depth since the part as made).  A part whose mesh is not a plane triangle mesh keeps
    its geometry only (no fields)."""
    d = model.design
    mesh = d.model.cm.mesh
    nv = int(mesh.nvertices) if hasattr(mesh, "nvertices") else mesh.p.shape[1]
    out = {"starts": float(starts), "rpm": float(rpm), "points_m": np.asarray(mesh.p[:, :nv]).T.copy(),
           "triangles": None, "displacement_m": None, "von_mises_Pa": None, "worn_m": np.zeros(nv)}
    if mesh.p.shape[0] != 2 or mesh.t.shape[0] < 3:
        return out
    out["triangles"] = np.asarray(mesh.t[:3]).T.copy()
    basis = d.model.basis
    nodal = np.asarray(basis.nodal_dofs)
    vert_of_dof = {int(x): k for k, x in enumerate(nodal[0])}
    nodes = model.contact.nodes
    for i, dx in enumerate(np.asarray(nodes.dof_x)):
        k = vert_of_dof.get(int(dx))
        if k is not None:
            out["worn_m"][k] = float(worn[i])
    omega = rpm_to_rad_s(rpm)
    w_eng = model.engagement(extra)
    lam = model.solve(omega, extra)[0] if w_eng is not None and omega > w_eng else np.zeros(model.m)
    b, coef, U = model.case.response.fields(np.array([omega]), lam[None, :])
    u = np.asarray(U if U is not None else b @ coef)[:, 0]
    disp = np.zeros((nv, 3))
    disp[:, 0], disp[:, 1] = u[nodal[0]], u[nodal[1]]
    out["displacement_m"] = disp
    s = d.model.stress(u[:, None])
    vm = np.asarray(d.model.von_mises(s)).reshape(-1)
    tri = out["triangles"].ravel()
    levels = vm.size // tri.size
    v = np.zeros(nv)
    np.maximum.at(v, np.tile(tri, levels), vm[: levels * tri.size])
    out["von_mises_Pa"] = v
    return out
