"""Sparse direct solvers behind one tiny interface: ``factorize(A).solve(B)``.

Back-ends, chosen by ``CLUTCHFEM_SOLVER`` (``auto`` default):
* ``cholmod``: supernodal Cholesky from SuiteSparse via scikit-sparse (optional extra
  ``clutchfem[cholmod]``; needs Debian's libsuitesparse-dev to build);
* ``superlu``: scipy's SuperLU in symmetric mode (minimum-degree ordering of A + A',
  no off-diagonal pivoting), always available: the fallback.
``auto`` takes CHOLMOD when it imports and SuperLU otherwise.  The figures behind this
choice are in BENCHMARKS.md (benchmarks/bench_solvers.py).
"""

from __future__ import annotations

import os

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .errors import SolverError


class _SuperLU:
    name = "superlu"

    def __init__(self, A: sp.spmatrix):
        try:
            self._lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A",
                                 diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        except RuntimeError as exc:  # "Factor is exactly singular"
            raise SolverError(f"stiffness matrix is singular ({exc}): is the part clamped "
                              "(bore group) and connected?") from None

    def solve(self, B: np.ndarray) -> np.ndarray:
        B = np.asarray(B, dtype=float)
        if B.ndim == 1 or B.shape[1] <= _BLOCK:
            return self._lu.solve(B)
        # multi-column triangular solves: blocks of 16 columns, one BLAS thread (multi-threaded
        # OpenBLAS gains nothing here and is up to 90x slower when the cores are shared)
        with _one_blas_thread():
            return np.hstack([self._lu.solve(np.asfortranarray(B[:, j:j + _BLOCK]))
                              for j in range(0, B.shape[1], _BLOCK)])


_BLOCK = 16


def _one_blas_thread():
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # optional: without it the default BLAS threading applies
        import contextlib

        return contextlib.nullcontext()
    return threadpool_limits(1, user_api="blas")


class _Cholmod:
    name = "cholmod"

    def __init__(self, A: sp.spmatrix):
        from sksparse.cholmod import CholmodNotPositiveDefiniteError, cholesky

        try:
            self._f = cholesky(sp.csc_matrix(A))
        except CholmodNotPositiveDefiniteError as exc:
            raise SolverError(f"stiffness matrix is not positive definite ({exc}): is the part "
                              "clamped (bore group) and connected?") from None

    def solve(self, B: np.ndarray) -> np.ndarray:
        return self._f(np.asarray(B, dtype=float))


def available() -> list[str]:
    out = ["superlu"]
    try:
        import sksparse.cholmod  # noqa: F401

        out.insert(0, "cholmod")
    except Exception:  # ImportError or a broken shared library
        pass
    return out


def factorize(A: sp.spmatrix, backend: str | None = None):
    """Factorise the symmetric positive definite matrix A."""
    backend = (backend or os.environ.get("CLUTCHFEM_SOLVER", "auto")).lower()
    if backend == "auto":
        backend = available()[0]
    if backend == "cholmod":
        return _Cholmod(A)
    if backend == "superlu":
        return _SuperLU(A)
    raise SolverError(f"unknown solver back-end '{backend}': use auto, cholmod or superlu")
