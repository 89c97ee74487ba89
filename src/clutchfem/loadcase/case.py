"""Load cases and speed sweeps: one FE model, one factorisation, any number of speeds.

A :class:`LoadCase` is (FE model, drum contact, spin-softening strategy): the drum with its
friction coefficient and sense of rotation, on a model shared with every other load case
of the same design (friction off, mu +-30 %, other softening strategies re-use its K, its
factorisation and its condensed contact columns).  It answers

* the **engagement speed**: without contact the free response is w^2 u1 (plus the softening
  terms), so the first gap closes at w0^2 = min_i g0_i / (B u1)_i in closed form; with spin
  softening the root of min_i (g0_i - B u_free(w)_i) is bracketed from w0 and refined with
  ``brentq`` (1e-10 relative);
* the **contact state at a speed**: below engagement nothing is solved; above it the small
  LCP of :mod:`clutchfem.contact.lcp` with q = g0 - B u_free(w), warm-started from the previous speed.

:func:`sweep` solves a list of speeds and returns a frozen :class:`~clutchfem.loadcase.SweepResult`
with the curve, per-shoe table and every state's displacement (reduced basis), and checks
itself (:mod:`clutchfem.loadcase.checks`: equilibrium residual and torque balance at every speed,
condition estimate; past their thresholds it refuses instead of answering).
"""

from __future__ import annotations

import math
import time
from functools import cached_property
from itertools import combinations

import numpy as np

from ..contact import DrumContact, contact_modulus, lazy, smooth_lcp, solve_lcp
from ..core import SolverError, brentq, rad_s_to_rpm, rpm_to_rad_s
from ..fe import one_blas_thread
from ..softening import Ritz, Softening, get_softening
from .checks import check_numerics, condition_estimate, equilibrium
from .operating import parse_rpm
from .results import Fields, SweepResult, curve_table, first_touch, shoe_table

__all__ = ["LoadCase", "sweep"]

#: contact states a load case remembers (oldest dropped first): bounds its memory
MEMO_STATES = 4096
#: half-width (relative) of the bracket a non-linear engagement search tries first around an
#: engagement hint (the pre-stress Ritz and per-speed engagements agree to ~1e-6)
ENGAGEMENT_HINT_BAND = 2e-5


class LoadCase:
    """(FE model, drum contact or None, spin-softening strategy): see module docstring."""

    def __init__(self, model, contact: DrumContact | None = None, softening: Softening | str = Ritz(),
                 engagement_hint: float | None = None):
        self.model = model
        self.contact = contact
        #: a close estimate of the engagement speed [rad/s] (e.g. another softening strategy's
        #: on the same model): a non-linear search first brackets the root within
        #: ENGAGEMENT_HINT_BAND of it (a per-speed strategy factorises once per trial speed)
        self.engagement_hint = engagement_hint
        self.softening = get_softening(softening)
        t0 = time.perf_counter()
        self.response = self.softening.bind(model, contact)
        self.setup_s = time.perf_counter() - t0
        self._memo: dict[float, tuple[np.ndarray, np.ndarray]] = {}

    @property
    def omega_limit(self) -> float | None:
        """Divergence speed [rad/s] of the free part (Ritz softening), else None."""
        return self.response.omega_limit

    @cached_property
    def engagement(self) -> tuple[float | None, int | None]:
        """(engagement speed [rad/s], index of the first contact node), or (None, None).  Found
        once per model, contact nodes, drum, strategy and hint: the load cases of a design that
        differ in friction alone (mu x 0.7 / x 1.3, mu = 0, ...) engage at the same speed, which
        a per-speed strategy's search pays with a factorisation per trial speed."""
        if self.contact is None:
            return None, None
        if self.response.linear:
            return self._engagement()
        c = self.contact
        cache = self.model.__dict__.setdefault("_engagement_cache", {})
        key = (self.softening, id(c.nodes), id(c.drum), self.engagement_hint, self.response.omega_limit)
        if key not in cache:  # (the nodes and the drum kept alive with their answer: ids are not reused)
            cache[key] = (c.nodes, c.drum, self._engagement())
        return cache[key][2]

    def _engagement(self) -> tuple[float | None, int | None]:
        """:attr:`engagement`'s search."""
        g0 = self.contact.nodes.gap0
        # a spinning elastic drum expands with w^2 too: it adds to the closing speed's gap
        out = self.contact.nodes.normal_displacement(self.model.u1) - self.contact.drum_gap(1.0)
        pos = out > 0
        if not pos.any():
            return None, None
        ratio = np.full_like(g0, np.inf)
        ratio[pos] = g0[pos] / out[pos]
        i0 = int(np.argmin(ratio))
        w0 = math.sqrt(ratio[i0])
        r = self.response
        if r.linear or w0 == 0.0:  # w0 = 0: touching at rest (contact nodes refuse it; kept safe here)
            return w0, i0

        def h(w):
            return float(np.min(g0 + self.contact.drum_gap(w) - r.free_normal(w)))

        hint = self.engagement_hint
        if hint is not None and hint > 0 and (r.omega_limit is None or hint * (1 + ENGAGEMENT_HINT_BAND) < r.omega_limit):
            lo, hi = hint * (1 - ENGAGEMENT_HINT_BAND), hint * (1 + ENGAGEMENT_HINT_BAND)
            if h(lo) > 0 >= h(hi):  # else: the full search below
                w = brentq(h, lo, hi, xtol=1e-10 * hi, rtol=1e-13)
                return w, int(np.argmin(g0 + self.contact.drum_gap(w) - r.free_normal(w)))
        hi = w0
        limit = r.omega_limit * (1 - 1e-6) if r.omega_limit else 10 * w0
        while h(hi) > 0:
            hi = min(hi * 1.05, limit)
            if hi >= limit:
                return None, None
        w = brentq(h, 0.0, hi, xtol=1e-10 * hi, rtol=1e-13)
        return w, int(np.argmin(g0 + self.contact.drum_gap(w) - r.free_normal(w)))

    @property
    def known_engagement(self) -> float | None:
        """The engagement speed [rad/s] if this case has computed it (None: not yet, or never
        engages): a hint for another strategy's search, at no cost."""
        return self.__dict__["engagement"][0] if "engagement" in self.__dict__ else None

    @property
    def engagement_rpm(self) -> float | None:
        w = self.engagement[0]
        return None if w is None else rad_s_to_rpm(w)

    def engaged(self, omega: float) -> bool:
        w = self.engagement[0]
        return w is not None and omega >= w * (1 - 1e-12)

    def solve(self, omega: float, active0: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray | None]:
        """(nodal contact forces lam [N], active set) at speed ``omega`` [rad/s].  Solved states
        are memoised (a slip search and a sweep of the same case share their speeds)."""
        m = 0 if self.contact is None else self.contact.nodes.m
        lim = self.response.omega_limit
        beyond = lim is not None and omega >= lim * (1 - 1e-9)
        if beyond and (self.contact is None or not self.engaged(omega)):
            raise SolverError(f"speed {rad_s_to_rpm(omega):.0f} rpm reaches the spin-softening divergence speed "
                              f"{rad_s_to_rpm(lim):.0f} rpm of the free part before its shoes touch the drum: the "
                              "shoes would fly out (stiffer flexures or lower speed)")
        if self.contact is None or not self.engaged(omega):
            return np.zeros(m), None
        key = float(omega)
        if key in self._memo:
            lam, act = self._memo[key]
            return lam.copy(), act.copy()
        q = self.contact.nodes.gap0 + self.contact.drum_gap(omega) - self.response.free_normal(omega)
        if active0 is None or not active0.any():  # first contact: start from the deepest node
            active0 = np.zeros(len(q), dtype=bool)  # (every node with q < 0 would condense
            active0[int(np.argmin(q))] = True  # many columns the solution does not need)
        G = self.response.columns(omega)
        Cd = self.contact.drum_compliance
        if Cd is not None:  # elastic drum: G + C_d
            G = lazy(lambda idx, G=G: G(idx) + Cd[:, idx])
        try:
            # loops of small dense solves: one BLAS thread (threaded BLAS gains nothing on them
            # and, on a busy 2-core machine, cost ~25x the CPU: clutchfem.fe.one_blas_thread)
            with one_blas_thread():
                if beyond:  # several complementary solutions: the one the drum holds (see _check_held)
                    self._omega_now = omega
                    lam, act = self._held_state(G, q, active0)
                else:
                    lam, act = solve_lcp(G, q, active0)
                    if self.contact.smoothing > 0:  # the smoothed law, from the exact state
                        lam, act = smooth_lcp(G, q, lam, self.contact.smoothing)
        except SolverError as exc:
            if beyond:
                raise
            if self.contact.mu == 0.0:
                lim = "" if self.omega_limit is None else f"; the free part diverges at {rad_s_to_rpm(self.omega_limit):.0f} rpm"
                raise SolverError(f"no bounded frictionless contact solution at {rad_s_to_rpm(omega):.0f} rpm: the drum "
                                  f"does not hold the shoe (too soft flexures for this speed{lim}) ({exc})") from None
            raise SolverError(f"no bounded contact solution at {rad_s_to_rpm(omega):.0f} rpm with mu = "
                              f"{self.contact.mu:g}: friction wedges the shoe into the drum (a self-locking plus "
                              "shoe: unbounded torque in the rigid-drum model, a grabbing clutch in reality); "
                              f"lower mu or use the minus arrangement ({exc})") from None
        if beyond:
            self._check_held(omega, G, act)
        if len(self._memo) >= MEMO_STATES:
            self._memo.pop(next(iter(self._memo)))
        self._memo[key] = (lam.copy(), act.copy())
        return lam, act

    def solved(self, omega: float) -> np.ndarray | None:
        """The contact nodes of the state solved at ``omega`` [rad/s], if it was (memo)."""
        hit = self._memo.get(float(omega))
        return None if hit is None else hit[1]

    def _held_state(self, G, q: np.ndarray, active0: np.ndarray):
        """Past divergence the LCP is not a P-matrix problem: besides the state the drum holds
        it has the free (lam = 0, unstable) one.  The active-set iteration from the contact
        set of the speed before (continuation) finds the held one; its complementarity is
        checked as usual and its stability by :meth:`_check_held`."""
        m = len(q)
        act = active0.copy() if active0 is not None and active0.any() else np.eye(m, dtype=bool)[int(np.argmin(q))]
        tol = 1e-9 * max(float(np.max(np.abs(q))), 1e-300)  # q grows large near a pole: its round-off
        k = self.response.unstable_count(self._omega_now) if hasattr(self.response, "unstable_count") else 0

        def trial(A):
            GA = np.asarray(G(A))
            lam = np.zeros(m)
            if len(A):
                lam[A] = np.linalg.solve(GA[A], -q[A])
            return lam, q + (GA @ lam[A] if len(A) else 0.0), GA

        def held(A, lam, w, GA) -> bool:
            if np.any(lam < 0) or np.any(np.delete(w, A) < -tol):
                return False
            S = 0.5 * (GA[A] + GA[A].T)
            return int(np.count_nonzero(np.linalg.eigvalsh(S) < 0)) == k if len(A) else k == 0

        seen, visited = set(), set(np.nonzero(act)[0].tolist())
        for _ in range(4 * m + 20):  # one node in or out per step (a principal-pivoting walk)
            A = np.nonzero(act)[0]
            lam, w, GA = trial(A)
            bad_lam = np.nonzero(lam < 0)[0]
            bad_w = np.nonzero((w < -tol) & ~act)[0]
            if not len(bad_lam) and not len(bad_w):
                return lam, act
            key = act.tobytes()
            if key in seen:
                break  # cycling (the matrix is not a P-matrix): search the nodes the walk visited
            seen.add(key)
            if len(bad_lam):
                act[bad_lam[np.argmin(lam[bad_lam])]] = False
            else:
                act[bad_w[np.argmin(w[bad_w])]] = True
                visited.add(int(bad_w[np.argmin(w[bad_w])]))
        U = sorted(visited)
        if len(U) > 12:
            raise SolverError("the contact state past the divergence speed did not converge")
        for r in range(1, len(U) + 1):
            for A in combinations(U, r):
                A = np.array(A)
                lam, w, GA = trial(A)
                if held(A, lam, w, GA):
                    act = np.zeros(m, dtype=bool)
                    act[A] = True
                    return lam, act
        raise SolverError("no contact state past the divergence speed in which the drum holds the part")

    def _check_held(self, omega: float, G, active: np.ndarray) -> None:
        """Past the free part's divergence speed the drum must hold the diverging modes: the
        equilibrium is stable iff K - w^2 M is positive definite on the displacements that keep
        the active gaps closed, i.e. (Haynsworth inertia additivity) iff the condensed
        compliance of the active nodes G_AA has as many negative eigenvalues as K - w^2 M has
        (the symmetric part of G_AA with friction)."""
        k = self.response.unstable_count(omega) if hasattr(self.response, "unstable_count") else 0
        if k == 0:
            return
        A = np.nonzero(active)[0]
        GA = np.asarray(G(A))[A] if len(A) else np.zeros((0, 0))
        n_neg = int(np.count_nonzero(np.linalg.eigvalsh(0.5 * (GA + GA.T)) < 0)) if len(A) else 0
        if n_neg != k:
            raise SolverError(f"speed {rad_s_to_rpm(omega):.0f} rpm is past the divergence speed "
                              f"{rad_s_to_rpm(self.response.omega_limit):.0f} rpm of the free part and the drum does "
                              f"not hold it there ({k} diverging mode(s), {n_neg} held by the {len(A)} contact "
                              "nodes): the equilibrium is unstable (stiffer flexures or lower speed)")

    def torque(self, omega: float, active0=None) -> float:
        """Friction torque [N m] of the whole clutch at speed ``omega`` (drum held)."""
        if self.contact is None:
            return 0.0
        lam, _ = self.solve(omega, active0)
        return self.friction_torque(lam)

    def friction_torque(self, lam: np.ndarray, mu: float | None = None) -> float:
        """Friction torque [N m] of the whole clutch for this case's nodal contact forces
        ``lam`` [N]: M = mu R_d sum(lam) x (n_total / n_model), the one definition (full slip,
        the forces act on the drum circle).  ``mu``: default the case's own; another value
        reads the torque a state would carry with that friction (the frictionless case's
        forces give M_0 = mu R_d N_0).  0 without a drum."""
        if self.contact is None:
            return 0.0
        mu = self.contact.mu if mu is None else mu
        return float(mu * self.contact.drum_radius * lam.sum() * self.scale)

    def stresses(self, omegas, lams) -> np.ndarray:
        """Vertex stresses (c, npts, n) of this case's solved contact states (speeds ``omegas``
        [rad/s], nodal forces ``lams`` (n, m)) from its reduced-basis fields: no new
        factorisation.  c = 3 (sxx, syy, sxy) in 2-D, 6 (Voigt) for the thick and 3-D models."""
        om = np.atleast_1d(np.asarray(omegas, dtype=float))
        basis, coef, U = self.response.fields(om, np.asarray(lams))
        u = U if U is not None else basis @ coef
        s = self.model.stress(u)
        return s.reshape(s.shape[0], -1, len(om))

    @property
    def contact_modulus(self) -> float:
        """E* [Pa] of the part's surface (:func:`clutchfem.contact.contact_modulus`)."""
        m = self.model.material
        return contact_modulus(m.E, m.nu, getattr(self.model, "formulation", "plane-stress"))

    def gaps(self, omega: float, lam: np.ndarray) -> np.ndarray:
        """(m,) gaps [m] of the contact nodes at speed ``omega`` [rad/s] with nodal forces
        ``lam`` [N] (an LCP solution of this case): w = q + G lam."""
        c = self.contact
        q = c.nodes.gap0 + c.drum_gap(omega) - self.response.free_normal(omega)
        A = np.nonzero(lam)[0]
        if not len(A):
            return q
        G = self.response.columns(omega)(A)
        if c.drum_compliance is not None:
            G = G + c.drum_compliance[:, A]
        return q + G @ lam[A]

    @property
    def scale(self) -> float:
        """Totals of the whole clutch / totals of the model (sector and mid-plane symmetry)."""
        return self.model.cm.sector_copies * getattr(self.model, "symmetry_factor", 1.0)


def sweep(case: LoadCase, rpm, *, stresses: bool = True) -> SweepResult:
    """Solve every speed in ``rpm`` (a spec or numbers, ascending or not) for ``case``."""
    t0 = time.perf_counter()
    rpm = parse_rpm(rpm)
    omegas = rpm_to_rad_s(rpm)
    w_eng, i_eng = case.engagement
    t1 = time.perf_counter()
    m = 0 if case.contact is None else case.contact.nodes.m
    lam = np.zeros((len(rpm), m))
    active = None
    keep = getattr(case.response, "keep", None)  # a per-speed factorisation: the fields while it is at hand
    for k, w in enumerate(omegas):
        lam[k], act = case.solve(float(w), active)
        if act is not None:
            active = act
        if keep is not None:
            keep(float(w), lam[k])
    t2 = time.perf_counter()
    basis, coef, U = case.response.fields(omegas, lam)
    model = case.model
    fields = Fields(basis=basis, coef=coef, U=U, stress=model.stress, fe_basis=model.basis)
    modulus = case.contact_modulus
    curve, gaps = curve_table(rpm, omegas, lam, case.contact, case.scale, fields, stresses,
                              model.material.yield_strength, model.thickness, modulus)
    t3 = time.perf_counter()
    # is it right? equilibrium residual and torque balance per speed, conditioning
    # (a strategy that changes the softening operator, e.g. nonlinear.PrestressRitz, names the
    # model whose M it solves with)
    resid, torque_err = equilibrium(getattr(case.response, "check_model", model), case.contact,
                                    case.softening.name != "off", fields, omegas, lam,
                                    preconditioned=getattr(case.response, "precondition_check", False))
    cond = condition_estimate(model)
    warns = check_numerics(resid, cond, rpm, preconditioned=getattr(case.response, "precondition_check", False))
    curve["residual"] = resid
    curve["torque_balance_error"] = torque_err
    t4 = time.perf_counter()
    nominal = list(model.cm.contact_arcs)
    where, angle = first_touch(case.contact, i_eng, nominal)
    div = case.omega_limit
    timings = {"engagement_s": t1 - t0, "contact_s": t2 - t1, "post_s": t3 - t2, "checks_s": t4 - t3,
               "sweep_s": t4 - t0, **model.timings, "case_setup_s": case.setup_s}
    return SweepResult(rpm=rpm, omega=omegas, lam=lam, engagement_rpm=None if w_eng is None else rad_s_to_rpm(w_eng),
                       first_touch=where, first_touch_angle_deg=angle,
                       divergence_rpm=None if div is None else rad_s_to_rpm(div), contact=case.contact,
                       scale=case.scale, thickness=model.thickness, softening=case.softening.name,
                       curve=curve, shoes=shoe_table(rpm, lam, case.contact, nominal, gaps, model.thickness, modulus),
                       fields=fields, gaps=gaps, contact_modulus=modulus,
                       condition=cond, warnings=warns, timings=timings)
