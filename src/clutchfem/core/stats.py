"""Binomial shares with their interval: the share of made parts in (or out of) spec that a
Monte Carlo counts, with the 95 % Wilson score interval (scipy's :func:`scipy.stats.binomtest`;
Wilson's rather than the normal approximation: it stays inside [0, 1] and is right near 0 and
1, where a yield of 99 % sits)."""

from __future__ import annotations

import math

__all__ = ["wilson"]


def wilson(k: int, n: int) -> tuple[float, float]:
    """The 95 % Wilson score interval of the binomial share ``k / n``; NaN for ``n = 0``.

    Examples
    --------
    >>> from clutchfem.core import wilson
    >>> lo, hi = wilson(990, 1000)
    >>> round(lo, 4), round(hi, 4)
    (0.9817, 0.9946)
    """
    if n <= 0:
        return (math.nan, math.nan)
    from scipy.stats import binomtest  # deferred: scipy.stats costs ~0.4 s, and every face imports the base layer

    ci = binomtest(int(k), int(n)).proportion_ci(confidence_level=0.95, method="wilson")
    return (float(ci.low), float(ci.high))
