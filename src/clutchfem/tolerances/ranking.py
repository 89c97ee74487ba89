"""The ranking of the toleranced dimensions by their standardised regression coefficients
(SRC) over the Monte Carlo parts, with percentile bootstrap intervals (:func:`tolerance`'s
``ranking``)."""

from __future__ import annotations

import math
import warnings

import numpy as np
from scipy.stats import bootstrap

__all__ = ["bootstrap_src", "src"]


def src(X: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """(standardised regression coefficients, R^2, raw slopes) of y on the columns of X."""
    Xc = X - X.mean(axis=0)
    yc = y - y.mean()
    A = np.hstack([np.ones((len(y), 1)), Xc])
    coef, *_ = np.linalg.lstsq(A, yc, rcond=None)
    b = coef[1:]
    resid = yc - A @ coef
    ss = float(yc @ yc)
    r2 = 1.0 - float(resid @ resid) / ss if ss > 0 else math.nan
    sx, sy = X.std(axis=0, ddof=1), y.std(ddof=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(sy > 0, b * sx / sy, np.nan)
    return s, r2, b


def bootstrap_src(X: np.ndarray, y: np.ndarray, B: int = 1000, seed: int = 0):
    """95 % percentile bootstrap intervals of the SRCs and of R^2: (lo, hi, r2_lo, r2_hi).
    The parts are resampled in pairs (x, y) by :func:`scipy.stats.bootstrap`; a resample in
    which a dimension or the answer does not vary has no regression and is left out of the
    percentiles (NaN in the bootstrap distribution)."""
    n, k = X.shape

    def stat(idx, axis=-1):
        """:func:`src` of every resample at once (``idx``: (..., n) indices; the resamples
        scipy draws do not depend on the statistic being vectorised): the least squares of
        each resample as :func:`numpy.linalg.lstsq` solves it (its SVD, its cut-off of the
        singular values), 1000 resamples in one batched SVD instead of 1000 calls (a
        tolerance run's six answers: ~1 s -> ~20 ms)."""
        i = np.moveaxis(np.asarray(idx), axis, -1).astype(int)
        shape = i.shape[:-1]
        i = i.reshape(-1, n)
        Xi, yi = X[i], y[i]  # (m, n, k), (m, n)
        Xc, yc = Xi - Xi.mean(axis=1, keepdims=True), yi - yi.mean(axis=1, keepdims=True)
        A = np.concatenate([np.ones((len(i), n, 1)), Xc], axis=2)
        U, S, Vt = np.linalg.svd(A, full_matrices=False)
        keep = S > np.finfo(float).eps * max(n, k + 1) * S[:, :1]  # lstsq's rcond=None
        inv = np.where(keep, 1.0 / np.where(keep, S, 1.0), 0.0)
        coef = np.einsum("mji,mj,mlj,ml->mi", Vt, inv, U, yc)
        resid = yc - np.einsum("mnj,mj->mn", A, coef)
        ss = np.einsum("mn,mn->m", yc, yc)
        with np.errstate(divide="ignore", invalid="ignore"):
            r2 = np.where(ss > 0, 1.0 - np.einsum("mn,mn->m", resid, resid) / np.where(ss > 0, ss, 1.0), np.nan)
            sx, sy = Xi.std(axis=1, ddof=1), yi.std(axis=1, ddof=1)
            s = np.where(sy[:, None] > 0, coef[:, 1:] * sx / sy[:, None], np.nan)
        out = np.concatenate([s, r2[:, None]], axis=1)
        flat = np.any(Xi.std(axis=1) == 0, axis=1) | (yi.std(axis=1) == 0)  # no regression: NaN
        out[flat] = np.nan
        return np.moveaxis(out.reshape(*shape, k + 1), -1, 0)

    with warnings.catch_warnings():  # NaN resamples: said in the docstring, percentiles taken without them
        warnings.simplefilter("ignore")
        res = bootstrap((np.arange(n),), stat, n_resamples=B, vectorized=True, method="percentile",
                        random_state=np.random.default_rng(seed))
    dist = res.bootstrap_distribution  # (k + 1, B)
    lo, hi = np.nanpercentile(dist, 2.5, axis=1), np.nanpercentile(dist, 97.5, axis=1)
    return lo[:k], hi[:k], float(lo[k]), float(hi[k])
