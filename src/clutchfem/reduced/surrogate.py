"""The reduced model of one answer over a region: a Gaussian process on a linear trend, and
the classifier of where the full FE answers at all.

**Why non-intrusive, and why a Gaussian process** (issue 36; the measurements are in
BENCHMARKS.md, section 24).  The answers of the best path are the end of a long chain: a mesh
of the design's geometry, the thick plane model, the elastic drum, the pre-stress softening,
the exact contact with friction, the error step's corrections (geometric non-linearity,
Richardson's extrapolation of the peak, one more mesh level where the band asks for it).  A
projection-based reduced basis would have to reproduce each of them on morphed meshes with
an affine (or empirically interpolated) decomposition of every operator, and the corrections
still on top.  Over a designer's region the answers themselves are smooth in the
parameters (their kinks at contact events are small: BENCHMARKS.md 18), so a regression of
the answers is both simpler and as exact as its measured error says.  Per answer:

* the answer ``y`` is modelled as ``z = log(y)`` (every answer here is positive; a log makes
  the engagement's and the slip's near power laws in the dimensions close to linear);
* a linear trend ``z ~ a + U b`` in the unit-box coordinates ``U`` (least squares) carries
  the first-order effect of every dimension (the guidelines' elasticities);
* a Gaussian process on the residual (scikit-learn's ``GaussianProcessRegressor``: a
  constant times an anisotropic Matern 5/2 kernel, one length per dimension, plus a white
  noise term for the remeshing noise of designs meshed from scratch; its hyper-parameters by
  maximum likelihood with restarts) carries the curvature and the interactions.  Matern 5/2
  and not the squared exponential: it is twice differentiable, not infinitely, so a kink at a
  contact event bends it locally instead of ringing through the region.

Its own error is not the process's variance (which assumes the kernel is right): it is
*measured* on designs it was not fitted to (:mod:`.build`), and the reduced model's band of
an answer is the best path's band plus that measured error.

Where the full FE has no answer (a design that diverges below the engine's maximum speed,
whose refined mesh fails, ...), a classifier of the training designs' status says so
(:class:`StatusModel`): a design whose probability of an answer is below :data:`OK_PROBABILITY` gets none
from the reduced model (the FE is asked instead, and it says why).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..clutch.ripple import effective_engagement_rpms

__all__ = ["OK_PROBABILITY", "AnswerModel", "RippleAnswer", "StatusModel", "quadratic_features", "sq_distances"]

#: below this probability that the full FE answers at a design, the reduced model gives none
OK_PROBABILITY = 0.8
#: maximum-likelihood restarts of the hyper-parameters (the first from the defaults)
RESTARTS = 3


@dataclass
class AnswerModel:
    """One answer's model over the unit box: ``log(y) = a + U b + GP(U)`` (module docstring).
    Fitted with scikit-learn; kept as plain arrays (the training points, the weights, the
    kernel's amplitude and lengths), so that an answer costs one kernel evaluation with numpy
    and loading a model imports nothing more.

    Examples
    --------
    >>> import numpy as np
    >>> from clutchfem.reduced import AnswerModel
    >>> rng = np.random.default_rng(0)
    >>> U = rng.random((40, 2))
    >>> y = 5000 * np.exp(0.3 * U[:, 0] - 0.2 * U[:, 1] ** 2)
    >>> m = AnswerModel.fit(U, y)
    >>> u = np.array([[0.5, 0.5]])
    >>> bool(abs(m.predict(u)[0] / (5000 * np.exp(0.15 - 0.05)) - 1) < 1e-3)
    True
    """

    trend: np.ndarray
    X: np.ndarray
    alpha: np.ndarray
    amplitude: float
    lengths: np.ndarray
    noise: float = 0.0

    @classmethod
    def fit(cls, U: np.ndarray, y: np.ndarray, seed: int = 0, like: "AnswerModel | None" = None) -> "AnswerModel":
        """Fit to the unit-box points ``U`` (n, d) and their positive answers ``y`` (n,);
        ``like``: a model of the same answer whose kernel (amplitude, lengths, noise) starts the
        maximum likelihood instead of the restarts (a refit with more designs of the same
        region: the hyper-parameters move little, the restarts cost most of a fit).  Measured
        on concept 4 (BENCHMARKS.md section 24): keeping that kernel fixed instead doubled the
        engagement's error on new designs (p95 0.23 -> 0.47 %)."""
        # scikit-learn (~0.6 s to import) only to fit: a fitted model answers with numpy alone
        from sklearn.exceptions import ConvergenceWarning
        from sklearn.gaussian_process import GaussianProcessRegressor
        from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel

        U = np.asarray(U, dtype=float)
        if like is not None and len(np.atleast_1d(like.lengths)) != U.shape[1]:
            like = None  # (another set of coordinates: its kernel cannot start this one)
        z = np.log(np.asarray(y, dtype=float))
        A = np.hstack([np.ones((len(U), 1)), U])
        trend, *_ = np.linalg.lstsq(A, z, rcond=None)
        r = z - A @ trend
        d = U.shape[1]
        scale = float(np.var(r)) or 1e-12
        kernel = (ConstantKernel(scale, (1e-6 * scale, 1e3 * scale)) * Matern(np.ones(d), (1e-2, 1e3), nu=2.5)
                  + WhiteKernel(1e-6 * scale, (1e-12 * scale, 1e-1 * scale)))
        if like is not None:  # its kernel the likelihood's start, no restarts (kept, the refit lost accuracy)
            amp_b, noise_b = (1e-6 * scale, 1e3 * scale), (1e-12 * scale, 1e-1 * scale)
            kernel = (ConstantKernel(float(np.clip(like.amplitude, *amp_b)), amp_b)
                      * Matern(np.clip(like.lengths, 1e-2, 1e3), (1e-2, 1e3), nu=2.5)
                      + WhiteKernel(float(np.clip(like.noise, *noise_b)), noise_b))
        gp = GaussianProcessRegressor(kernel, normalize_y=False, n_restarts_optimizer=0 if like else RESTARTS,
                                      optimizer="fmin_l_bfgs_b", random_state=seed)
        with warnings.catch_warnings():  # a length at its bound: that dimension is (nearly) linear
            warnings.simplefilter("ignore", ConvergenceWarning)
            gp.fit(U, r)
        k = gp.kernel_
        return cls(trend=trend, X=np.array(gp.X_train_), alpha=np.array(gp.alpha_).ravel(),
                   amplitude=float(k.k1.k1.constant_value), lengths=np.atleast_1d(k.k1.k2.length_scale).astype(float),
                   noise=float(k.k2.noise_level))

    def predict(self, U: np.ndarray) -> np.ndarray:
        """The answers at the unit-box points ``U`` (m, d): the trend and the process's mean,
        ``amplitude * Matern52(|U - X| / lengths) @ alpha``.  The distances by one matrix
        product, |u|^2 + |x|^2 - 2 u.x in the scaled coordinates (not an (m, n, d) array of
        differences): 10,000 points 22x faster, the same answers to 1e-15."""
        U = np.atleast_2d(np.asarray(U, dtype=float))
        Xs, xx = self._scaled_training()
        z = self.trend[0] + U @ self.trend[1:] + self._matern(sq_distances(U / self.lengths, Xs, xx)) @ self.alpha
        return np.exp(z)

    def kernel(self, A: np.ndarray, B: np.ndarray) -> np.ndarray:
        """The fitted covariance (m, n) of the process between the points ``A`` (m, d) and
        ``B`` (n, d): ``amplitude * Matern52(|A - B| / lengths)`` (without the noise term)."""
        return self._matern(sq_distances(A / self.lengths, B / self.lengths))

    def _matern(self, d2: np.ndarray) -> np.ndarray:
        s5 = math.sqrt(5.0) * np.sqrt(d2)
        return self.amplitude * (1.0 + s5 + s5 * s5 / 3.0) * np.exp(-s5)

    def _scaled_training(self) -> tuple[np.ndarray, np.ndarray]:
        """The training points in the kernel's scaled coordinates and their squared norms, built
        on the first :meth:`predict` and kept (a sampler asks for a few points thousands of
        times: the same numbers, not rebuilt per call); not pickled."""
        c = self.__dict__.get("_scaled")
        if c is None:
            Xs = self.X / self.lengths
            c = self.__dict__["_scaled"] = (Xs, (Xs * Xs).sum(axis=1))
        return c

    def __getstate__(self):
        return {k: v for k, v in self.__dict__.items() if k != "_scaled"}


@dataclass
class RippleAnswer:
    """The engagement with the 2-stroke speed ripple, derived exactly from the static
    engagement's model as the FE derives it (:func:`clutchfem.clutch.ripple.effective_engagement_rpm`:
    the mean crank speed at which the ripple's 3-sigma peak reaches the static speed; the
    default ripple model, the one a region's study rows are computed with), not a model of its
    own: fitted on its own it was further from the FE than the static one (concept 4, 240
    designs: 0.47 against 0.28 % on the held-out designs), though it is a function of it.

    Examples
    --------
    >>> import numpy as np
    >>> from clutchfem.reduced import AnswerModel
    >>> from clutchfem.reduced.surrogate import RippleAnswer
    >>> U = np.random.default_rng(0).random((20, 1))
    >>> static = AnswerModel.fit(U, 3000.0 * (1 + 0.2 * U[:, 0]))
    >>> w = RippleAnswer(static).predict(np.array([[0.5]]))[0]
    >>> bool(3000 < w < 3300), round(float(w) / 3300, 3)      # below the static 3300 rpm
    (True, 0.972)
    """

    static: AnswerModel
    k_sigma: float = 3.0

    def predict(self, U: np.ndarray) -> np.ndarray:
        return self.from_static(self.static.predict(U))

    def from_static(self, static_rpm: np.ndarray) -> np.ndarray:
        """The engagement with ripple of static engagements already predicted [rpm]."""
        return effective_engagement_rpms(static_rpm, k_sigma=self.k_sigma)


def sq_distances(A: np.ndarray, B: np.ndarray, bb: np.ndarray | None = None) -> np.ndarray:
    """Squared distances (m, n) between the rows of ``A`` (m, d) and ``B`` (n, d) by one matrix
    product, |a|^2 + |b|^2 - 2 a.b, clipped at 0 (round-off), without an (m, n, d) array;
    ``bb``: the rows' |b|^2 if known."""
    if bb is None:
        bb = (B * B).sum(axis=1)
    d2 = (A * A).sum(axis=1)[:, None] + bb[None, :] - 2.0 * (A @ B.T)
    return np.maximum(d2, 0.0)


def quadratic_features(U: np.ndarray) -> np.ndarray:
    """The unit-box coordinates, their squares and products: ``[U, U_i U_j (i <= j)]``."""
    U = np.atleast_2d(np.asarray(U, dtype=float))
    i, j = np.triu_indices(U.shape[1])
    return np.hstack([U, U[:, i] * U[:, j]])


@dataclass
class StatusModel:
    """Where the full FE answers: a logistic regression of the training designs' status
    (answered or not) on the quadratic features of the unit box, or a constant where every
    design answered (or none did).  Why logistic and quadratic: the FE's refusals in a
    designer's region are the designs whose free part diverges below the engine's top speed
    (the divergence speed is a smooth function of the dimensions, so its level set is a
    smooth surface); on concept 4's default region it told 40 held-out designs apart
    without a miss (a Gaussian-process classifier missed 3 at the same threshold,
    BENCHMARKS.md section 24).

    Examples
    --------
    >>> import numpy as np
    >>> from clutchfem.reduced import StatusModel
    >>> U = np.random.default_rng(0).random((60, 2))
    >>> s = StatusModel.fit(U, U[:, 0] + U[:, 1] ** 2 < 1.0)
    >>> p = s.probability(np.array([[0.2, 0.2], [0.9, 0.9]]))
    >>> bool(p[0] > 0.9 and p[1] < 0.1)
    True
    """

    constant: float | None
    coef: np.ndarray | None = None
    intercept: float = 0.0

    @classmethod
    def fit(cls, U: np.ndarray, ok: np.ndarray, seed: int = 0) -> "StatusModel":
        ok = np.asarray(ok, dtype=bool)
        if ok.all() or not ok.any():
            return cls(constant=float(ok.all()))
        from sklearn.exceptions import ConvergenceWarning
        from sklearn.linear_model import LogisticRegression

        clf = LogisticRegression(C=10.0, max_iter=20000, random_state=seed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            clf.fit(quadratic_features(U), ok.astype(int))
        return cls(constant=None, coef=clf.coef_.ravel().copy(), intercept=float(clf.intercept_[0]))

    def probability(self, U: np.ndarray) -> np.ndarray:
        """The probability that the full FE answers at each unit-box point of ``U``."""
        U = np.atleast_2d(np.asarray(U, dtype=float))
        if self.coef is None:
            return np.full(len(U), self.constant)
        z = quadratic_features(U) @ self.coef + self.intercept
        return 1.0 / (1.0 + np.exp(-np.clip(z, -500, 500)))
