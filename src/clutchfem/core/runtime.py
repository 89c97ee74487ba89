"""Process settings for the processes clutchfem owns (the CLI, sweep workers, benchmarks).

:func:`tune_malloc`: glibc's allocator hands arrays above a (dynamic) threshold straight
back to the operating system when they are freed, so the next design's arrays of the same
sizes are page-faulted in afresh.  A design allocates and frees tens of MB of matrices,
fields and factor columns; keeping freed memory in the heap for the next one saves ~10 % of
a sweep or an analysis (BENCHMARKS.md, section 4).  Called where clutchfem owns the process,
never on import: a library does not change its host's allocator.

:func:`default_fidelity`: the session's default analysis fidelity, from the environment
variable ``CLUTCHFEM_FIDELITY`` (``best`` when unset): the operating point and a study
rerun's fingerprint read it alike.
"""

from __future__ import annotations

import ctypes
import os
import sys

from .errors import ParameterError

__all__ = ["FIDELITIES", "FIDELITY_ENV", "default_fidelity", "tune_malloc"]

#: the environment variable that sets the default fidelity of a session
FIDELITY_ENV = "CLUTCHFEM_FIDELITY"
#: the analysis fidelities (clutchfem.loadcase.OperatingPoint.fidelity)
FIDELITIES = ("best", "fast")


def default_fidelity() -> str:
    """The default fidelity: ``CLUTCHFEM_FIDELITY`` if set (``best`` or ``fast``, any case and
    spacing), else ``best``; another value is refused naming the variable."""
    v = os.environ.get(FIDELITY_ENV, "").strip().lower()
    if not v:
        return "best"
    if v not in FIDELITIES:
        raise ParameterError(FIDELITY_ENV, os.environ[FIDELITY_ENV], "best or fast (or unset: best)",
                             "environment variable")
    return v

#: mallopt parameters (glibc malloc.h)
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3
#: arrays up to this size come from the heap (glibc's maximum for the threshold on 64-bit)
MMAP_THRESHOLD = 32 * 1024 * 1024
#: free memory at the top of the heap kept for reuse
TRIM_THRESHOLD = 1024 * 1024 * 1024

_done: bool | None = None


def tune_malloc() -> bool:
    """Keep freed memory in the heap (glibc only; elsewhere a no-op; module docstring).  For
    processes clutchfem owns (a script that analyses design after design), never called on
    import.

    Returns
    -------
    bool
        Whether the allocator took the settings (False off glibc); the same answer on every
        call (idempotent: the settings are made once).

    Examples
    --------
    >>> import clutchfem as cf
    >>> took = cf.tune_malloc()
    >>> isinstance(took, bool), cf.tune_malloc() is took
    (True, True)
    """
    global _done
    if _done is None:
        _done = False
        if sys.platform.startswith("linux"):
            try:
                libc = ctypes.CDLL("libc.so.6")
                _done = bool(libc.mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(
                    libc.mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))
            except (OSError, AttributeError):  # not glibc
                _done = False
    return _done
