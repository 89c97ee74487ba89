"""One gmsh model at a time: :func:`gmsh_session`.

gmsh is a process-global C++ library and not thread-safe: one model at a time per process,
guarded by a lock; parallel sweeps use processes.  Lives with the geometry (every gmsh
caller, from concept building to the mesh pipeline and the drawings, imports it from here).
"""

from __future__ import annotations

import contextlib
import threading

import gmsh

_GMSH_LOCK = threading.Lock()


@contextlib.contextmanager
def gmsh_session(name: str = "clutchfem"):
    """Initialise gmsh quietly for one model; always finalise."""
    with _GMSH_LOCK:
        # Ctrl-C stops a long meshing run (gmsh installs its SIGINT handler: possible only in
        # the main thread; worker threads run uninterruptible, their process can be stopped)
        gmsh.initialize(interruptible=threading.current_thread() is threading.main_thread())
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.option.setNumber("General.Verbosity", 1)
            gmsh.model.add(name)
            yield
        finally:
            gmsh.finalize()
