"""The Dask side of the study engine: the scheduler's address checked and probed with a
timeout, the local cluster sized to what the machine holds, the workers warmed up, the
points run one per worker thread, and the faults of a distributed run named.

Faults and what the user is told (issue 24: each used to be a raw traceback, a hang or a
silent wait):

* **address**: ``tcp://HOST:PORT``, ``tls://HOST:PORT`` or ``HOST:PORT`` (``HOST`` alone:
  Dask's default port 8786); anything else (``''``, ``http://...``: the dashboard's
  address, a port that is not a number) is refused before Dask sees it, naming what is
  wrong; an unknown host is refused by name;
* **nothing Dask at the address**: a TCP connect with a timeout of
  :data:`CONNECT_TIMEOUT_S`, then the scheduler's greeting within :data:`GREETING_S` (a
  Dask server speaks first: its handshake names ``pickle-protocol``; a silent server is
  asked ``HEAD /`` to tell an HTTP server); an HTTP server, the dashboard or a silent port
  is refused within seconds instead of hanging;
* **no workers** (at the start, or all of them gone mid-study, e.g. the only worker of an
  external cluster died): said at once on stderr, waited for up to
  :data:`WAIT_WORKERS_S`, then :class:`ClusterError` with the count of finished points (all
  stored) and what to start;
* **the scheduler lost mid-study**: :class:`ClusterError` (not a "failed" row per design:
  the designs did not fail, and a rerun computes them);
* **worker counts the machine cannot hold**: a local cluster gets at most one worker per
  core and per :data:`WORKER_MEMORY` of available memory (more processes than cores only
  wait for a core; ``--workers 200`` would need ~100 GB); the cap is logged, never silent;
  and never more workers than points to compute.

Memory allocator: distributed's nannies set ``MALLOC_TRIM_THRESHOLD_=65536`` in their
workers by default; that switches off glibc's dynamic mmap threshold and every large numpy
array is then mapped and unmapped afresh (measured: a design took 1.8x as long).  The
private local cluster unsets it (:mod:`.runner` has the details).
"""

from __future__ import annotations

import logging
import os
import re
import signal
import socket
import threading
import time

import psutil

from ..core import ClutchfemError, InputError
from .point import evaluate, failed_row, warm_up

log = logging.getLogger("clutchfem")

#: seconds to connect to a scheduler and hear its greeting
CONNECT_TIMEOUT_S = 10.0
#: seconds a scheduler has to greet a new connection (a Dask server speaks first, at once)
GREETING_S = 5.0
#: seconds a study waits for a worker (none at the start, or all gone) before it stops
WAIT_WORKERS_S = 60.0
#: memory one local worker process needs [bytes] (ASSUMED: measured ~0.2 GB idle with the
#: analysis stack loaded, a concept design at the default mesh ~0.3 GB more at its peak)
WORKER_MEMORY = 0.5e9
_SCHEMES = ("tcp", "tls")


class ClusterError(ClutchfemError):
    """The distributed engine cannot go on (no workers, the scheduler lost); the finished
    rows are stored and a rerun resumes."""


def default_workers() -> int:
    """One worker process per core this process may run on (its CPU affinity)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def workers_machine_holds(requested: int | None, points: int | None = None) -> tuple[int, str | None]:
    """(local worker processes to start, the reason when fewer than asked): one per core
    and per :data:`WORKER_MEMORY` of available memory, never more than ``points``."""
    cores = default_workers()
    mem = psutil.virtual_memory().available
    by_mem = max(1, int(mem // WORKER_MEMORY))
    n = cores if requested is None else requested
    limit = min(cores, by_mem)
    why = None
    if n > limit:
        why = (f"{requested if requested is not None else 'one per core'}: this machine holds {limit} worker "
               f"process(es) ({cores} core(s), {mem / 1e9:.1f} GB available, ~{WORKER_MEMORY / 1e9:.1f} GB per "
               f"worker ASSUMED): using {limit} (more processes than cores only wait for a core)")
        n = limit
    if points is not None and 0 < points < n:
        n = points
    return n, (f"--workers {why}" if why and requested is not None else why)


def check_scheduler(address, option: str = "--scheduler") -> str:
    """The scheduler's address in Dask's form (``tcp://HOST:PORT``), or an
    :class:`~clutchfem.core.InputError` naming what is wrong with it (module docstring).
    Nothing is connected to (the host name is only resolved).

    Parameters
    ----------
    address : str
        ``HOST``, ``HOST:PORT`` or ``tcp://`` / ``tls://`` ``HOST:PORT`` (port 8786 when none).
    option : str
        The option the messages name.

    Returns
    -------
    str
        ``scheme://HOST:PORT``.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.check_scheduler("127.0.0.1"), cf.check_scheduler("tls://127.0.0.1:9000")
    ('tcp://127.0.0.1:8786', 'tls://127.0.0.1:9000')
    >>> cf.check_scheduler("http://127.0.0.1:8787")
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.InputError: --scheduler 'http://127.0.0.1:8787': an http address is a web page (the Dask ...
    """
    if not isinstance(address, str) or not address.strip():
        raise InputError(f"{option} {address!r}: empty; give the address of a dask scheduler, e.g. "
                         "tcp://10.0.0.5:8786 (the scheduler prints it when it starts)")
    a = address.strip()
    web = re.match(r"(https?)://", a, flags=re.I)
    if web:
        raise InputError(f"{option} {address!r}: an {web.group(1).lower()} address is a web page (the Dask dashboard, "
                         "port 8787 by default), not the scheduler; give the scheduler's tcp://HOST:PORT (port 8786 by "
                         "default)")
    m = re.fullmatch(r"(?:(?P<scheme>[A-Za-z][\w+.-]*)://)?(?P<host>\[[0-9A-Fa-f:.]+\]|[^\s:/\[\]]+)"
                     r"(?::(?P<port>[^/\s]*))?/?", a)
    if m is None:
        raise InputError(f"{option} {address!r}: not an address; expected tcp://HOST:PORT (e.g. tcp://10.0.0.5:8786)")
    scheme = (m.group("scheme") or "tcp").lower()
    if scheme not in _SCHEMES:
        raise InputError(f"{option} {address!r}: unknown protocol {scheme!r}; expected tcp:// or tls://")
    port = m.group("port")
    if port is None or port == "":
        port = "8786"
    if not port.isdigit() or not 0 < int(port) < 65536:
        raise InputError(f"{option} {address!r}: port {port!r} is not a port number (1..65535)")
    host = m.group("host")
    try:
        socket.getaddrinfo(host.strip("[]"), int(port), type=socket.SOCK_STREAM)
    except (socket.gaierror, UnicodeError) as exc:
        raise InputError(f"{option} {address!r}: host {host!r} is not known ({exc.strerror or exc})") from None
    return f"{scheme}://{host}:{int(port)}"


def probe_scheduler(address: str, option: str = "--scheduler") -> None:
    """Refuse, within seconds, an address where no Dask server answers (module docstring);
    a tls:// address is left to Dask's own handshake."""
    timeout = CONNECT_TIMEOUT_S
    scheme, rest = address.split("://", 1)
    if scheme != "tcp":
        return
    host, port = rest.rsplit(":", 1)
    try:
        s = socket.create_connection((host.strip("[]"), int(port)), timeout=timeout)
    except OSError as exc:
        raise InputError(f"{option} {address}: nothing listens there ({exc.strerror or exc}); start a scheduler "
                         "with `dask scheduler` and workers with `dask worker ADDRESS --nthreads 1`") from None
    try:
        s.settimeout(GREETING_S)
        greeting = s.recv(512)
    except OSError:
        greeting = b""
    http = b""
    if not greeting:  # silent: an HTTP server waits for a request (ask it to say what it is)
        try:
            s.settimeout(2.0)
            s.sendall(b"HEAD / HTTP/1.0\r\n\r\n")
            http = s.recv(64)
        except OSError:
            http = b""
    s.close()
    if b"pickle-protocol" not in greeting and b"compression" not in greeting:
        what = ("an HTTP server (the Dask dashboard?)" if (greeting or http)[:5] == b"HTTP/" else
                f"a server that did not greet as Dask does within {GREETING_S:g} s" if not greeting else
                "a server that does not speak Dask's protocol")
        raise InputError(f"{option} {address}: {what} listens there, not a dask scheduler; give the scheduler's "
                         "address (port 8786 by default; the dashboard is on 8787)")


def connect(scheduler: str | None, n_workers: int, concept: str | None, version: str):
    """(client, local cluster or None, worker threads) with the workers warmed up; a
    ``scheduler`` is checked and probed first (module docstring)."""
    from distributed import Client

    cluster = None
    if scheduler is not None:
        address = check_scheduler(scheduler)
        probe_scheduler(address)
        try:
            client = Client(address, timeout=f"{CONNECT_TIMEOUT_S:g}s")
        except (OSError, TimeoutError) as exc:
            raise InputError(f"--scheduler {scheduler}: the dask scheduler does not answer ({exc})") from None
    else:
        cluster = local_cluster(n_workers)
        client = Client(cluster)
        client.register_plugin(_as_worker_plugin(concept))
    try:
        if cluster is not None:
            client.wait_for_workers(1, timeout=WAIT_WORKERS_S)
        elif not client.nthreads():
            wait_for_workers(client, scheduler, done=0, total=None)
        versions = client.run(warm_up, concept)
        odd = {w: v for w, v in versions.items() if v != version}
        if odd:
            w, v = next(iter(odd.items()))
            raise InputError(f"worker {w} runs clutchfem model version {v}, this client {version}: the workers "
                             "must run the same clutchfem (same source, gmsh and scikit-fem versions)")
    except BaseException:
        client.close(timeout=10)
        if cluster is not None:
            cluster.close(timeout=10)
        raise
    return client, cluster


def wait_for_workers(client, where: str, done: int, total: int | None, timeout: float | None = None) -> None:
    """Wait (said at once on stderr) up to ``timeout`` (default :data:`WAIT_WORKERS_S`) for a
    worker to join the scheduler; :class:`ClusterError` if none does."""
    timeout = WAIT_WORKERS_S if timeout is None else timeout
    log.warning(f"the scheduler at {where} has no workers: waiting up to {timeout:g} s for one (start one with "
                f"`dask worker {where} --nthreads 1`)")
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        if client.status != "running":
            raise ClusterError(f"lost the connection to the scheduler at {where}" + _progress(done, total))
        if client.nthreads():
            log.warning(f"a worker joined {where}: going on")
            return
        time.sleep(0.25)
    raise ClusterError(f"the scheduler at {where} has had no workers for {timeout:g} s" + _progress(done, total)
                       + f"; start workers (`dask worker {where} --nthreads 1`) and run the same command again")


def _progress(done: int, total: int | None) -> str:
    if total is None:
        return ""
    return f": {done} of {total} points are finished and stored, the rest is not computed"


def rows_on_dask(todo: list[str], tasks: dict, settings, version: str, n_workers: int, scheduler: str | None,
                 want_errors=frozenset()):
    """Rows as they finish, computed on a dask.distributed cluster, one point in flight per
    worker thread (a crash takes only its own design); yields ``{"__start__": threads}``
    once the cluster is up."""
    from distributed import as_completed

    client, cluster = connect(scheduler, n_workers, settings.concept, version)
    where = scheduler or "the local cluster"
    futures: dict = {}
    finished = 0
    try:
        tag = version.rsplit("+", 1)[-1]
        pending = iter(todo)
        done = as_completed()
        seen = {"n": 1, "at": -1.0}

        def threads() -> int:  # asked of the scheduler at most once a second (a round trip)
            now = time.monotonic()
            if now - seen["at"] > 1.0:
                seen.update(n=sum(client.nthreads().values()), at=now)
            return seen["n"]

        def submit_more() -> None:
            while len(futures) < max(1, threads()):
                h = next(pending, None)
                if h is None:
                    return
                e = h in want_errors
                fut = client.submit(evaluate, tasks[h], settings, h, e, key=f"clutchfem-point-{h}-{tag}{'-e' * e}")
                futures[fut] = h
                done.add(fut)

        submit_more()
        yield {"__start__": len(client.nthreads())}
        while futures:
            batch = done.next_batch(block=False)
            if not batch:
                if client.status != "running":
                    raise ClusterError(f"lost the connection to the scheduler at {where}"
                                       + _progress(finished, len(todo)) + "; run the same command again to resume")
                if threads() == 0:
                    wait_for_workers(client, where, finished, len(todo))
                    seen["at"] = -1.0
                time.sleep(0.05)
                continue
            for fut in batch:
                h = futures.pop(fut)
                if fut.status == "finished":
                    row = fut.result()
                else:
                    try:
                        exc = fut.exception()
                    except Exception as e:  # noqa: BLE001 - cancelled by the scheduler, lost
                        exc = e
                    if exc is None or type(exc).__name__ in ("CancelledError", "FutureCancelledError") \
                            or client.status != "running":
                        raise ClusterError(f"lost the scheduler at {where}: the point {h} was dropped (its "
                                           "connection closed or the task was cancelled)"
                                           + _progress(finished, len(todo)) + "; run the same command again to "
                                           "resume")
                    row = failed_row(tasks[h], settings, h, version, killed_message(exc))
                fut.release()
                finished += 1
                yield row
            submit_more()
    finally:
        try:
            if futures:
                client.cancel(list(futures), force=True)
        except Exception:  # noqa: BLE001 - shutting down anyway
            pass
        client.close(timeout=10)
        if cluster is not None:
            cluster.close(timeout=10)


def killed_message(exc: BaseException) -> str:
    """The ``failed`` row's message of a point whose task raised on the cluster."""
    name = type(exc).__name__
    if name == "KilledWorker":
        return ("the worker process died while computing this design (a crash in gmsh or the solver, or out of "
                f"memory); its nanny restarted it and the study went on ({exc})")
    return f"{name}: {exc}"


def setup_worker(concept: str | None) -> None:
    """On a worker of the private local cluster: ignore SIGINT (the client stops the cluster
    on Ctrl-C) and import the analysis stack once, also on a worker a nanny restarts."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    warm_up(concept)


def _as_worker_plugin(concept: str | None):
    """:func:`setup_worker` as a ``distributed`` WorkerPlugin (imported lazily, so the module
    imports without distributed)."""
    from distributed.diagnostics.plugin import WorkerPlugin

    class Setup(WorkerPlugin):
        name = "clutchfem-study-setup"

        def __init__(self, concept):
            self.concept = concept

        def setup(self, worker):
            setup_worker(self.concept)

    return Setup(concept)


def local_cluster(n_workers: int):
    """A private local cluster of ``n_workers`` process workers, one thread each, with the
    study engine's settings (no task retry after a worker died on a design, glibc's dynamic
    mmap threshold left on)."""
    import dask
    from distributed import LocalCluster

    with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        return LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                            # its HTTP server (health routes) on a free port: two local clusters at once
                            # (two test workers, two commands) no longer race for 8787 and warn
                            dashboard_address=":0", scheduler_kwargs={"allowed_failures": 0},
                            silence_logs=logging.CRITICAL)
