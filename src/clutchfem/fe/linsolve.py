"""Sparse direct solvers behind one tiny interface: ``factorize(A).solve(B)``.

The back-end is *injected* where a model is built (``FEModel(..., solver=...)``, in the way
scikit-fem's ``solve(A, b, solver=...)`` takes one): a back-end name, or any callable
``A -> object with .solve(B)`` (e.g. a PARDISO or an iterative wrapper of your own).  The
environment variable ``CLUTCHFEM_SOLVER`` only sets the default (``auto``).  Back-ends:
* ``cholmod``: Cholesky from SuiteSparse via scikit-sparse, simplicial up to
  ``SIMPLICIAL_MAX_N`` unknowns (faster than supernodal on these problems, measured), CHOLMOD's
  choice above (optional extra
  ``clutchfem[cholmod]``; needs Debian's libsuitesparse-dev to build);
* ``superlu``: scipy's SuperLU in symmetric mode (minimum-degree ordering of A + A',
  no off-diagonal pivoting), always available: the fallback.
``auto`` takes CHOLMOD when it imports and SuperLU otherwise.  The figures behind this
choice are in BENCHMARKS.md (benchmarks/bench_solvers.py).
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections import Counter
from typing import Any, Callable, Union

import cachetools
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..core import SolverError


class _SuperLU:
    name = "superlu"

    def __init__(self, A: sp.spmatrix):
        try:
            self._lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A",
                                 diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        except RuntimeError as exc:  # "Factor is exactly singular"
            raise SolverError(f"stiffness matrix is singular ({exc}): is the part clamped "
                              "(bore group) and connected?") from None

    def negative_pivots(self) -> int:
        """Negative pivots of the symmetric-mode LU (no off-diagonal pivoting): by Sylvester's
        law of inertia, the negative eigenvalues of a symmetric A."""
        return int(np.count_nonzero(self._lu.U.diagonal() < 0))

    def solve(self, B: np.ndarray) -> np.ndarray:
        B = np.asarray(B, dtype=float)
        if B.ndim == 1 or B.shape[1] <= _BLOCK:
            return self._lu.solve(B)
        # multi-column triangular solves: blocks of 16 columns, one BLAS thread (multi-threaded
        # OpenBLAS gains nothing here and is up to 90x slower when the cores are shared)
        with one_blas_thread():
            return np.hstack([self._lu.solve(np.asfortranarray(B[:, j:j + _BLOCK]))
                              for j in range(0, B.shape[1], _BLOCK)])


_BLOCK = 16


#: the BLAS libraries of this process (threadpoolctl), scanned again only when modules were
#: imported since (a new module may bring a new BLAS): (module count, controller)
_BLAS: list = [0, None]


def one_blas_thread():
    """Context: one BLAS thread inside (threadpoolctl), or nothing if it is not installed or
    every BLAS already runs one thread.  Loops of many small dense products or triangular
    solves (multi-column solves here, the heat model's time steps) gain nothing from threaded
    BLAS and are up to ~1000x slower when the cores are shared (measured on a 2-core machine).
    The libraries are scanned once, not on every call: a scan costs ~2 ms, a design calls this
    ~140 times (~30 % of its CPU when it scanned each time)."""
    try:
        from threadpoolctl import ThreadpoolController
    except ImportError:  # optional: without it the default BLAS threading applies
        return contextlib.nullcontext()
    if _BLAS[1] is None or _BLAS[0] != len(sys.modules):
        _BLAS[:] = [len(sys.modules), ThreadpoolController().select(user_api="blas")]
    blas = _BLAS[1]
    if all(lib.num_threads == 1 for lib in blas.lib_controllers):
        return contextlib.nullcontext()
    return blas.limit(limits=1)


#: size up to which CHOLMOD's simplicial factorisation is used (above it CHOLMOD chooses):
#: on the 2-D models (4k-34k dofs) and the 3-D one (51k) it factorises 1.0-2x and back-solves
#: 1.3-3x faster than the supernodal one CHOLMOD's own heuristic picks (BENCHMARKS.md,
#: solvers), with one BLAS thread or the default threads
SIMPLICIAL_MAX_N = 100_000


#: CHOLMOD's symbolic analyses (fill-reducing ordering, elimination tree, column counts) of
#: the last few sparsity patterns, kept with the pattern they were made from.  A design
#: factorises matrices of one pattern many times (K - w^2 M at each speed of the exact
#: softening reference, K + w^2 K_sigma1 of the pre-stressed one): the analysis, ~30 % of a
#: 2-D factorisation, is done once per pattern.  It reads only where entries are stored, so
#: the numeric factor, and every answer, is the same bit for bit (tests/test_core_internals.py).
_SYMBOLIC: cachetools.LRUCache = cachetools.LRUCache(maxsize=6)
_SYMBOLIC_LOCK = threading.Lock()


def _symbolic(A: sp.csc_matrix, mode: str):
    """The symbolic analysis of ``A``'s pattern for ``mode``: a cached one when a matrix of the
    same pattern (compared entry by entry, not by a hash alone) was analysed before."""
    from sksparse.cholmod import analyze

    key = (A.shape[0], A.nnz, mode, hash(A.indices[::61].tobytes()))
    with _SYMBOLIC_LOCK:
        hit = _SYMBOLIC.get(key)
    if hit is not None and np.array_equal(hit[0], A.indptr) and np.array_equal(hit[1], A.indices):
        return hit[2]
    symbolic = analyze(A, mode=mode)
    with _SYMBOLIC_LOCK:
        _SYMBOLIC[key] = (A.indptr.copy(), A.indices.copy(), symbolic)
    return symbolic


class _Cholmod:
    name = "cholmod"

    def __init__(self, A: sp.spmatrix):
        from sksparse.cholmod import CholmodNotPositiveDefiniteError

        A = sp.csc_matrix(A)
        try:
            self._f = _symbolic(A, "simplicial" if A.shape[0] <= SIMPLICIAL_MAX_N else "auto").cholesky(A)
        except CholmodNotPositiveDefiniteError as exc:
            raise SolverError(f"stiffness matrix is not positive definite ({exc}): is the part "
                              "clamped (bore group) and connected?") from None

    def negative_pivots(self) -> int:
        """Negative entries of D in CHOLMOD's P A P' = L D L' (simplicial: LDL', which an
        indefinite A also has; supernodal LL' refuses one): the negative eigenvalues of A."""
        return int(np.count_nonzero(self._f.D() < 0))

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


#: what ``solver=`` accepts: None (the default back-end), a back-end name, or a factory
Solver = Union[None, str, Callable[[sp.spmatrix], Any]]

#: factorisations done in this process, by kind ('K': stiffness, 'shifted': K - w^2 M of the
#: exact spin-softening reference); tests read it to check that work is not repeated
COUNTS: Counter = Counter()


def factorize(A: sp.spmatrix, backend: Solver = None, kind: str = "K"):
    """Factorise the symmetric positive definite matrix A with ``backend`` (see module doc)."""
    COUNTS[kind] += 1
    if callable(backend):
        f = backend(A)
        if not hasattr(f, "solve"):
            raise SolverError(f"solver factory {backend!r} returned {type(f).__name__}, which has no "
                              ".solve(B) method")
        return f
    if backend is not None and not isinstance(backend, str):
        raise SolverError(f"solver={backend!r} is not allowed: use None, 'auto', 'cholmod', 'superlu' "
                          "or a callable A -> object with .solve(B)")
    backend = (backend or os.environ.get("CLUTCHFEM_SOLVER", "auto")).lower()
    if backend == "auto":
        backend = available()[0]
    if backend == "cholmod":
        return _Cholmod(A)
    if backend == "superlu":
        return _SuperLU(A)
    raise SolverError(f"unknown solver back-end '{backend}': use auto, cholmod or superlu")
