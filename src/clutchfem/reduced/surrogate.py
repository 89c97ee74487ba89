"""The reduced model of one answer over a region: a Gaussian process on a linear trend, and
the classifier of where the full FE answers at all.

**Why non-intrusive, and why a Gaussian process** (issue 36; the measurements are in
BENCHMARKS.md, section 22).  The answers of the best path are the end of a long chain: a mesh
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
whose refined mesh fails, ...), a Gaussian-process classifier of the training designs' status
says so: a design whose probability of an answer is below :data:`OK_PROBABILITY` gets none
from the reduced model (the FE is asked instead, and it says why).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.gaussian_process import GaussianProcessClassifier, GaussianProcessRegressor
from sklearn.gaussian_process.kernels import RBF, ConstantKernel, Matern, WhiteKernel

__all__ = ["OK_PROBABILITY", "AnswerModel", "StatusModel"]

#: below this probability that the full FE answers at a design, the reduced model gives none
OK_PROBABILITY = 0.8
#: maximum-likelihood restarts of the hyper-parameters (the first from the defaults)
RESTARTS = 3


@dataclass
class AnswerModel:
    """One answer's model over the unit box: ``log(y) = a + U b + GP(U)`` (module docstring).

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
    gp: GaussianProcessRegressor

    @classmethod
    def fit(cls, U: np.ndarray, y: np.ndarray, seed: int = 0) -> "AnswerModel":
        """Fit to the unit-box points ``U`` (n, d) and their positive answers ``y`` (n,)."""
        U = np.asarray(U, dtype=float)
        z = np.log(np.asarray(y, dtype=float))
        A = np.hstack([np.ones((len(U), 1)), U])
        trend, *_ = np.linalg.lstsq(A, z, rcond=None)
        r = z - A @ trend
        d = U.shape[1]
        kernel = (ConstantKernel(1e-4, (1e-10, 1e2)) * Matern(np.ones(d), (1e-2, 1e3), nu=2.5)
                  + WhiteKernel(1e-8, (1e-12, 1e-3)))
        gp = GaussianProcessRegressor(kernel, normalize_y=False, n_restarts_optimizer=RESTARTS,
                                      random_state=seed)
        with warnings.catch_warnings():  # a length at its bound: that dimension is (nearly) linear
            warnings.simplefilter("ignore", ConvergenceWarning)
            gp.fit(U, r)
        return cls(trend=trend, gp=gp)

    def predict(self, U: np.ndarray) -> np.ndarray:
        """The answers at the unit-box points ``U`` (m, d)."""
        U = np.atleast_2d(np.asarray(U, dtype=float))
        z = self.trend[0] + U @ self.trend[1:] + self.gp.predict(U)
        return np.exp(z)


@dataclass
class StatusModel:
    """Where the full FE answers: a Gaussian-process classifier of the training designs'
    status (answered or not), or a constant where every design answered (or none did).

    Examples
    --------
    >>> import numpy as np
    >>> from clutchfem.reduced import StatusModel
    >>> U = np.linspace(0, 1, 21)[:, None]
    >>> s = StatusModel.fit(U, U[:, 0] < 0.7)
    >>> p = s.probability(np.array([[0.2], [0.95]]))
    >>> bool(p[0] > 0.5 > p[1])
    True
    """

    constant: float | None
    clf: GaussianProcessClassifier | None = None

    @classmethod
    def fit(cls, U: np.ndarray, ok: np.ndarray, seed: int = 0) -> "StatusModel":
        ok = np.asarray(ok, dtype=bool)
        if ok.all() or not ok.any():
            return cls(constant=float(ok.all()))
        d = np.asarray(U).shape[1]
        clf = GaussianProcessClassifier(ConstantKernel(10.0, (1e-2, 1e4)) * RBF(np.full(d, 0.5), (1e-2, 1e2)),
                                        n_restarts_optimizer=RESTARTS, random_state=seed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            clf.fit(np.asarray(U, dtype=float), ok.astype(int))
        return cls(constant=None, clf=clf)

    def probability(self, U: np.ndarray) -> np.ndarray:
        """The probability that the full FE answers at each unit-box point of ``U``."""
        U = np.atleast_2d(np.asarray(U, dtype=float))
        if self.clf is None:
            return np.full(len(U), self.constant)
        return self.clf.predict_proba(U)[:, 1]
