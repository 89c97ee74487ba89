"""The forward model of a calibration and its posterior: the answers of a part as built from
its uncertain inputs, the likelihood of the measurements, and two ways to the posterior
(emcee's ensemble sampler; a Laplace approximation).

**How each uncertain input enters** (:class:`Forward`):

* the shape parameters, ``mu`` and ``drum_wall`` are axes of the reduced model's region
  (:class:`clutchfem.reduced.Region`; its key includes them and their bounds): the FE's
  answers over a box that holds the whole prior (a uniform prior's range, +-4 sigma of a
  normal one), fitted and measured like every region.  Why ``mu`` as an axis and not the
  analytic plus/minus-shoe formula's mu dependence (thesis eq 7): the FE's torque comes from the
  exact contact with friction, whose normal forces themselves move with mu on a minus
  shoe (friction pulls it in); the formula needs the pivot distance and the lining's angles
  of a rigid shoe, which a compliant shoe does not have, and the engagement does not depend
  on mu at all (no sliding before contact: the reduced model finds that itself).
* ``E`` and ``density`` enter by **exact similarity**: with the geometry fixed, the
  equilibrium of a part whose stress is E times a function of the strain (linear
  elasticity, the pre-stress softening and the geometric non-linearity alike) under the
  centrifugal load rho omega^2 r depends on rho omega^2 / E only, so every displacement at
  speed omega of a part of (E, rho) is the one at omega' = omega sqrt(rho E0 / (rho0 E)) of
  the reference material: the engagement speed (a displacement reaching the clearance)
  scales with sqrt(E rho0 / (E0 rho)), exactly, while the drum is rigid or of the same
  material; the masses scale with rho.  The slip speed, the torque and the stress scale
  too, but at another speed (the torque as E/E0 times the reference torque at omega'), and
  the reduced model holds them at one speed only: with E or density uncertain, those
  measurements are refused (make the material a region axis: not built).  The engine's
  speed ripple depends on the speed itself, so the engagement *with ripple* scales only
  approximately (within the ripple's own share, ~3 %).

**Several parts** (:class:`Posterior` ``views``): theta holds the shared inputs once and each
part's own (its geometry as built); each part's answers come from the forward model at its
view of theta.  The model's error is taken independent from part to part (ASSUMED: the
parts' geometries differ; a model error common to all parts would need its own parameter).

**Likelihood**: each measurement is normal about the model's answer with the variance of its
standard uncertainty plus the model's: the reduced model's band of that answer (the best
path's band of its training designs plus its own error measured on held-out designs,
:meth:`clutchfem.reduced.ReducedModel.predict`) taken as +-2 sigma (ASSUMED: a 95 % band).
A measured dimension is normal about the input itself.  Where the full FE gives no answer
(:class:`~clutchfem.reduced.StatusModel`) the likelihood is zero: no part could have been
measured there.

**Priors**: uniform on a range, or normal truncated at +-4 sigma (:mod:`.inputs`).
"""

from __future__ import annotations

import logging
import math

import numpy as np

from ..core import ParameterError
from ..reduced.model import UNUSABLE, row_band
from ..reduced.surrogate import OK_PROBABILITY

__all__ = ["BAND_SIGMAS", "Forward", "Posterior", "emcee_samples", "laplace"]

#: a model band is this many standard deviations (ASSUMED: a 95 % band)
BAND_SIGMAS = 2.0
#: answers scaled by the similarity of E and density: answer -> (power of E/E0, power of rho/rho0)
SCALED = {"engagement_rpm": (0.5, -0.5), "engagement_rpm_with_ripple": (0.5, -0.5), "mass_kg": (0.0, 1.0),
          "shoe_mass_kg": (0.0, 1.0)}


class Forward:
    """The answers of parts as built: ``theta`` (m, k) SI values of the ``uncertain`` inputs
    -> the reduced model's answers (module docstring).

    Examples
    --------
    See :func:`clutchfem.calibrate`.
    """

    def __init__(self, model, uncertain, design):
        reg = model.region
        self.model, self.uncertain, self.region = model, list(uncertain), reg
        names = [u.name for u in self.uncertain]
        self.axis = [names.index(n) if n in names else None for n in reg.names]
        missing = [u.name for u in self.uncertain if u.axis == "region" and u.name not in reg.names]
        if missing:
            raise ParameterError(missing[0], None, f"an axis of the reduced model's region ({reg.describe()})",
                                 "calibration")
        self.lo, self.hi = np.array(reg.lo), np.array(reg.hi)
        self.span = self.hi - self.lo
        self.base = np.array([reg.base[n] for n in reg.names])
        # the region's columns theta sets, and theta's column for each (built once, not per call)
        self.cols = np.array([j for j, i in enumerate(self.axis) if i is not None], dtype=int)
        self.of_theta = np.array([i for i in self.axis if i is not None], dtype=int)
        self.iE = names.index("E") if "E" in names else None
        self.irho = names.index("density") if "density" in names else None
        self.E0, self.rho0 = float(design.op.material.E), float(design.op.material.rho)
        self.rel_band = {}
        for a in model.models:
            own = model.own_error(a)
            if not math.isfinite(own) or own > UNUSABLE:
                continue
            fe = max((row_band(r, a) or 0.0) for r in model.rows)
            self.rel_band[a] = fe + own / (1.0 - own)

    @property
    def answers(self) -> list[str]:
        """The answers it gives (those whose measured error is usable)."""
        return list(self.rel_band)

    def unit_points(self, theta: np.ndarray) -> np.ndarray:
        """The region's unit-box points (m, d) of the rows of ``theta`` (m, k): the region's
        base values where theta has no column."""
        theta = np.atleast_2d(theta)
        X = np.empty((len(theta), len(self.base)))
        X[:] = self.base
        X[:, self.cols] = theta[:, self.of_theta]
        return (X - self.lo) / self.span

    def __call__(self, theta: np.ndarray, answers=None) -> tuple[dict, np.ndarray]:
        """(answer -> values (m,), ok (m,)): ``ok`` where the point lies in the region and
        the full FE answers there."""
        theta = np.atleast_2d(np.asarray(theta, dtype=float))
        U = self.unit_points(theta)
        ok = ((U >= -1e-9) & (U <= 1 + 1e-9)).all(axis=1)
        ok &= self.model.status.probability(U) >= OK_PROBABILITY
        out = {}
        X = self.model.coords(U)
        scaled = self.iE is not None or self.irho is not None
        for a in (answers or self.answers):
            v = self.model.models[a].predict(X)
            if scaled and a in SCALED:
                pe, pr = SCALED[a]
                if self.iE is not None:
                    v = v * (theta[:, self.iE] / self.E0) ** pe
                if self.irho is not None:
                    v = v * (theta[:, self.irho] / self.rho0) ** pr
            out[a] = v
        return out, ok

    def sigma_model(self, answer: str, value: np.ndarray) -> np.ndarray:
        """The model's standard deviation of ``answer`` at ``value``: its band / 2."""
        return self.rel_band[answer] * np.abs(value) / BAND_SIGMAS


class Posterior:
    """The log posterior of the uncertain inputs given the measurements (module docstring),
    vectorised over rows of ``theta``."""

    def __init__(self, forward: Forward, uncertain, measured, views=None):
        self.f, self.uncertain, self.measured = forward, list(uncertain), list(measured)
        # a part's view: the columns of theta that are its inputs, in the forward model's order
        self.views = views if views is not None else [(None, list(range(len(self.uncertain))))]
        self.view_of = {p: np.asarray(idx) for p, idx in self.views}
        self.answers = sorted({m.answer for m in self.measured if not m.is_dimension})
        self.dim_index = [int(self.view_of[m.part][[u.name for u in forward.uncertain].index(m.name)])
                          if m.is_dimension else None for m in self.measured]
        # built once for the sampler's many calls (each a batch of walkers): the priors as arrays,
        # the parts whose answers are measured, each measurement's value, variance and model band
        self._lo = np.array([u.lo for u in self.uncertain], dtype=float)
        self._hi = np.array([u.hi for u in self.uncertain], dtype=float)
        self._mean = np.array([u.mean for u in self.uncertain], dtype=float)
        self._sd = np.array([u.sd for u in self.uncertain], dtype=float)
        self._normal = np.array([u.kind != "uniform" for u in self.uncertain])
        self._forward_views = [(p, np.asarray(idx)) for p, idx in self.views
                               if self.answers and any(m.part == p and not m.is_dimension for m in self.measured)]
        self._value = np.array([m.value for m in self.measured], dtype=float)
        self._var = np.array([m.sd ** 2 for m in self.measured], dtype=float)
        self._band = [None if i is not None else self.f.rel_band[m.answer]
                      for m, i in zip(self.measured, self.dim_index)]
        self._model_cols = np.array([k for k, i in enumerate(self.dim_index) if i is None], dtype=int)

    def prior(self, theta: np.ndarray) -> np.ndarray:
        """The log prior density (up to a constant) of each row of ``theta`` (m, k): the sum of
        each input's (:meth:`Uncertain.logpdf <clutchfem.calibration.inputs.Uncertain.logpdf>`),
        -inf outside the support."""
        theta = np.atleast_2d(np.asarray(theta, dtype=float))
        v = np.where(self._normal, -0.5 * ((theta - self._mean) / self._sd) ** 2, 0.0)
        v = np.where((theta >= self._lo) & (theta <= self._hi), v, -np.inf)
        out = v[:, 0].copy()
        for i in range(1, v.shape[1]):  # column by column, in the inputs' order (as a sum of theirs)
            out += v[:, i]
        return out

    def residuals(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, dict, np.ndarray]:
        """(z (m, n) standardised residuals, sigma (m, n), answers (by measurement key), ok (m,))."""
        theta = np.atleast_2d(np.asarray(theta, dtype=float))
        ok = np.ones(len(theta), bool)
        per_part = {}
        for p, idx in self._forward_views:
            a, o = self.f(theta[:, idx], self.answers)
            per_part[p] = a
            ok &= o
        pred = np.empty((len(theta), len(self.measured)))
        s = np.empty_like(pred)
        ans = {}
        for k, (m, i, band) in enumerate(zip(self.measured, self.dim_index, self._band)):
            if i is not None:
                pred[:, k] = theta[:, i]
                s[:, k] = m.sd
            else:
                v = pred[:, k] = ans[m.key] = per_part[m.part][m.answer]
                s[:, k] = band * np.abs(v) / BAND_SIGMAS  # the model's sigma (:meth:`Forward.sigma_model`)
        mc = self._model_cols
        if len(mc):
            s[:, mc] = np.sqrt(self._var[mc] + s[:, mc] ** 2)
        z = (self._value - pred) / s
        return z, s, ans, ok

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        theta = np.atleast_2d(np.asarray(theta, dtype=float))
        lp = self.prior(theta)
        out = np.full(len(theta), -np.inf)
        fin = np.isfinite(lp)
        if fin.all():  # (the usual batch: no copy of the rows)
            z, s, _, ok = self.residuals(theta)
            ll = -0.5 * (z ** 2).sum(axis=1) - np.log(s).sum(axis=1)
            return np.where(ok, lp + ll, -np.inf)
        if fin.any():
            z, s, _, ok = self.residuals(theta[fin])
            ll = -0.5 * (z ** 2).sum(axis=1) - np.log(s).sum(axis=1)
            out[fin] = np.where(ok, lp[fin] + ll, -np.inf)
        return out

    def start(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` prior draws where the posterior is finite (refused where too few are)."""
        pts = []
        for _ in range(20):
            th = np.column_stack([u.sample(rng, 4 * n) for u in self.uncertain])
            pts.append(th[np.isfinite(self(th))])
            if sum(len(p) for p in pts) >= n:
                return np.concatenate(pts)[:n]
        raise ParameterError("uncertain", [u.text for u in self.uncertain], "priors under which the full FE answers "
                             "(the reduced model's region gives no answer over them)", "calibration")

    def best(self, rng: np.random.Generator, n: int = 256) -> np.ndarray:
        """The posterior's mode: the best of ``n`` prior draws, polished by L-BFGS-B in
        prior-scaled coordinates within the prior's support."""
        from scipy.optimize import minimize

        th = self.start(rng, n)
        lp = self(th)
        mu = np.array([u.mean for u in self.uncertain])
        sd = np.array([u.sd for u in self.uncertain])
        bounds = [((u.lo - m) / s, (u.hi - m) / s) for u, m, s in zip(self.uncertain, mu, sd)]
        f = lambda z: -float(self((mu + sd * z)[None, :])[0]) if np.isfinite(self((mu + sd * z)[None, :])[0]) else 1e30
        best = None
        for x0 in th[np.argsort(-lp)[:3]]:
            r = minimize(f, (x0 - mu) / sd, method="L-BFGS-B", bounds=bounds)
            if best is None or r.fun < best.fun:
                best = r
        return mu + sd * best.x


def emcee_samples(post: Posterior, *, seed: int = 0, walkers: int = 32, steps: int = 5000, burn: int = 500,
                  thin: int = 5) -> tuple[np.ndarray, dict]:
    """(samples (n, k), info): emcee's affine-invariant ensemble sampler (Goodman & Weare's
    stretch move), the walkers started from prior draws where the posterior is finite,
    ``burn`` steps discarded; ``info``: acceptance, the integrated autocorrelation time and the
    effective sample size."""
    import emcee

    rng = np.random.default_rng(seed)
    k = len(post.uncertain)
    walkers = max(walkers, 2 * k + 2)
    p0 = post.start(rng, walkers)
    s = emcee.EnsembleSampler(walkers, k, post, vectorize=True)
    s.random_state = np.random.RandomState(seed).get_state()
    s.run_mcmc(p0, steps, progress=False)
    chain = s.get_chain(discard=burn, thin=thin, flat=True)
    lg = logging.getLogger("emcee")
    level = lg.level
    lg.setLevel(logging.ERROR)  # its "chain shorter than 50 tau" warning: reported in info instead
    try:
        tau = s.get_autocorr_time(discard=burn, quiet=True)
    finally:
        lg.setLevel(level)
    n_eff = float((steps - burn) * walkers / np.max(tau))
    return chain, {"method": "emcee", "walkers": walkers, "steps": steps, "burn": burn, "thin": thin,
                   "acceptance": float(np.mean(s.acceptance_fraction)), "autocorr_steps": float(np.max(tau)),
                   "effective_samples": n_eff, "evaluations": walkers * steps,
                   "chain_long_enough": bool(steps - burn >= 50 * np.max(tau))}


def laplace(post: Posterior, *, seed: int = 0, n: int = 8000, mode: np.ndarray | None = None
            ) -> tuple[np.ndarray, dict]:
    """(samples (n, k), info): a Laplace approximation -- the posterior's mode and the inverse
    of the Hessian of -log posterior there (central differences in prior-scaled coordinates)
    as a normal, truncated to the priors' support.  ``info["gaussian"]`` is False where the
    Hessian is not positive definite (a ridge or a mode on the support's edge: then the
    normal is not the posterior; use emcee)."""
    rng = np.random.default_rng(seed)
    mode = post.best(rng) if mode is None else mode
    sd = np.array([u.sd for u in post.uncertain])
    k = len(sd)
    h = 1e-3
    f = lambda z: -float(post((mode + sd * z)[None, :])[0])
    H = np.zeros((k, k))
    f0 = f(np.zeros(k))
    E = np.eye(k) * h
    for i in range(k):
        for j in range(i, k):
            if i == j:
                H[i, i] = (f(E[i]) - 2 * f0 + f(-E[i])) / h ** 2
            else:
                H[i, j] = H[j, i] = (f(E[i] + E[j]) - f(E[i] - E[j]) - f(-E[i] + E[j]) + f(-E[i] - E[j])) / (4 * h * h)
    ok = bool(np.all(np.isfinite(H)))
    try:
        C = np.linalg.inv(H) if ok else None
        ok = ok and bool(np.all(np.linalg.eigvalsh(0.5 * (C + C.T)) > 0))
    except np.linalg.LinAlgError:
        ok = False
    info = {"method": "laplace", "gaussian": ok, "mode": mode.tolist(), "evaluations": 2 * k * k + 1}
    if not ok:
        return np.empty((0, k)), info
    C = (sd[:, None] * C) * sd[None, :]
    draws = rng.multivariate_normal(mode, 0.5 * (C + C.T), size=2 * n)
    draws = draws[np.isfinite(post.prior(draws))][:n]
    return draws, info
