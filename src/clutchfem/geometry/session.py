"""One gmsh model at a time: :func:`gmsh_session`.

gmsh is a process-global C++ library and not thread-safe: one model at a time per process,
guarded by a lock; parallel sweeps use processes.  Lives with the geometry (every gmsh
caller, from concept building to the mesh pipeline and the drawings, imports it from here).
"""

from __future__ import annotations

import contextlib
import ctypes
import signal
import threading

import gmsh

_GMSH_LOCK = threading.Lock()


@contextlib.contextmanager
def gmsh_session(name: str = "clutchfem"):
    """Initialise gmsh quietly for one model; always finalise."""
    with _GMSH_LOCK:
        # Ctrl-C stops a long meshing run (gmsh installs its SIGINT handler: possible only in
        # the main thread; worker threads run uninterruptible, their process can be stopped).
        # gmsh.initialize sets SIGINT to SIG_DFL and its finalize means to restore the previous
        # handler but never does (gmsh 4.15 assigns prev_interrupt_handler as a local): without
        # the restore below every Ctrl-C after a meshing run killed the process outright (exit
        # -2, no message, no cleanup) instead of raising KeyboardInterrupt.
        main = threading.current_thread() is threading.main_thread()
        previous = signal.getsignal(signal.SIGINT) if main else None
        gmsh.initialize(interruptible=main)
        keep_sigpipe_ignored()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.option.setNumber("General.Verbosity", 1)
            # OpenCASCADE keeps the STEP length unit of the last import in a process-global
            # static: after a user STEP read in metres (mesh.user) every later STEP written in
            # this process was scaled by 1000.  Each session starts from OCC's default.
            gmsh.option.setString("Geometry.OCCTargetUnit", "MM")
            gmsh.model.add(name)
            yield
        finally:
            gmsh.finalize()
            keep_sigpipe_ignored()
            if previous is not None:
                signal.signal(signal.SIGINT, previous)


def keep_sigpipe_ignored() -> None:
    """Put SIGPIPE back to ignored where Python has it so (its default): gmsh.initialize sets
    it to SIG_DFL for the whole process at the C level, from any thread, after which a write
    to a closed socket or pipe killed the process outright (exit 141, no message): the app's
    server, meshing in a worker thread, died when a browser went away mid-answer.  Through
    libc (Python's own ``signal.signal`` works in the main thread only)."""
    if not hasattr(signal, "SIGPIPE") or signal.getsignal(signal.SIGPIPE) != signal.SIG_IGN:
        return
    try:
        libc = ctypes.CDLL(None)
        libc.signal.restype = ctypes.c_void_p
        libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]
        libc.signal(int(signal.SIGPIPE), ctypes.c_void_p(1))  # SIG_IGN
    except (OSError, AttributeError):  # no C library to call: nothing gmsh could have changed either
        pass
