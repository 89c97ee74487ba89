"""Scalar root finding that does not keep the function alive.

scipy's ``brentq`` wraps the function in a closure that refers to itself (it counts its
calls), a reference cycle that only Python's garbage collector frees.  A function that holds
a load case holds its FE model, so a finished design's matrices and factorisation would
outlive it until some later collection (in a study of thousands of designs: memory that
comes and goes at random, and time charged to whichever design runs then).  :func:`brentq`
hands scipy a small wrapper and drops the function from it when the search returns.
"""

from __future__ import annotations

__all__ = ["brentq"]


class _Released:
    __slots__ = ("f",)

    def __init__(self, f):
        self.f = f

    def __call__(self, x, *args):
        return self.f(x, *args)


def brentq(f, a: float, b: float, **kw) -> float:
    """``scipy.optimize.brentq(f, a, b, **kw)``; ``f`` is released when it returns."""
    import scipy.optimize as optimize  # deferred: scipy.optimize costs ~0.7 s, and the base layer is imported by every face

    g = _Released(f)
    try:
        return optimize.brentq(g, a, b, **kw)
    finally:
        g.f = None
