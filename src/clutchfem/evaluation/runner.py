"""Running a study's points on Dask, with resume, progress and a summary.

:func:`run_points` is the study engine (the ``study`` and ``guidelines`` commands both run
on it):

1. every point gets its design hash (:mod:`.hashing`) and the run its model version
   (:func:`~.point.model_version`); the store (:mod:`.store`) says which (hash, version)
   pairs are finished: those are skipped (``retry_failed`` recomputes the *failed* ones);
2. the rest run on ``dask.distributed``: by default a private ``LocalCluster`` of
   ``workers`` **process** workers with one thread each (gmsh is a process-global C++
   library and not thread-safe; one thread per process also keeps BLAS single-threaded,
   the nannies set ``OMP/MKL/OPENBLAS_NUM_THREADS=1``), or an existing cluster at
   ``scheduler`` (``tcp://HOST:PORT``) through exactly the same code (``Client.submit``,
   ``as_completed``).  ``workers=0`` runs in this process, without Dask (examples, tests,
   debugging; a crash of gmsh then ends the run);
3. each finished point's row is committed to the store *by this process* as it arrives
   (workers never touch the store, so remote workers need no shared disk);
4. a progress bar (tqdm: rate, ETA and the ok/refused/failed counts) runs on stderr.

Memory allocator: distributed's nannies set ``MALLOC_TRIM_THRESHOLD_=65536`` in their
workers by default (to hand memory back to the OS sooner).  Setting it switches off glibc's
dynamic mmap threshold, and every large numpy array is then mapped and unmapped afresh:
measured here, a design took 1.8x as long (assembly 3x).  The private local cluster unsets
it; for a remote cluster start the workers with
``DASK_DISTRIBUTED__NANNY__PRE_SPAWN_ENVIRON__MALLOC_TRIM_THRESHOLD_=None dask worker ...``.

Worker processes are reused for every point (imports, the concept's code and the
process's gmsh library are loaded once: a warm-up runs on every worker before the first
point); meshes go through the mesh cache (content hash), so a rerun of a design with other
settings does not mesh again.

Crashes: if a worker process dies while computing a design (gmsh segfault, out of memory),
its nanny restarts it and the point is stored as *failed* with the scheduler's message.  On
the private local cluster the scheduler marks the task failed at the first death
(``allowed_failures=0``).  The client keeps only as many points in flight as the cluster
has worker threads (the next is submitted when one finishes), so each worker holds one
design at a time and a crash can only take its own design with it; the cost is one round
trip (a few ms) per design, measured in the benchmark as scheduling time.  A remote scheduler keeps its own
policy (by default a task is retried on 3 more workers before it is declared failed).

Ctrl-C: the pending tasks are cancelled, the cluster is shut down (its worker processes
ignore SIGINT, so that the client, not a signal race, stops them) and
:class:`StudyInterrupted` is raised with the counts; every finished row is already
committed, and running the same spec again resumes.
"""

from __future__ import annotations

import logging
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

from ..core import ClutchfemError, InputError
from .cluster import check_scheduler, rows_on_dask, workers_machine_holds
from .hashing import context_hash, design_hash
from .point import COLUMNS, Settings, evaluate, failed_row, model_version
from .store import ResultStore, StoreLocked

log = logging.getLogger("clutchfem")

#: a study with at most this many points to compute runs them in this process when no
#: worker count is given: below it a local cluster's start (20-25 s for 2 workers, warm-up
#: included, on the shared 2-core machine; some starts took ~95 s) costs more than the second
#: worker saves (measured: 8 points 13.7 s in process against 37.2 s on 2 workers;
#: BENCHMARKS.md, "Study reruns and the in-process crossover")
IN_PROCESS_MAX = 8


@dataclass(frozen=True)
class RunResult:
    """What :func:`run_points` did.  points: distinct designs asked for; done: those with a
    stored row now (any status); computed: rows written by this run; skipped: finished
    before this run; wall_s: this run's wall time (cluster start-up included); compute_s:
    from the first submitted point to the last finished one."""

    points: int
    done: int
    ok: int
    refused: int
    failed: int
    computed: int
    skipped: int
    store: Path
    model_version: str
    wall_s: float
    compute_s: float
    workers: int | None
    scheduler: str
    keys: tuple[str, ...] = field(repr=False, default=())
    interrupted: bool = False
    error_keys: tuple[str, ...] = field(repr=False, default=())
    #: points as listed (repeats of one design are computed and counted once: ``points``)
    listed: int | None = None
    #: the study context of the rows (:func:`~clutchfem.evaluation.hashing.context_hash`): open the
    #: store with it to read this run's rows (``ResultStore(store, COLUMNS, context=...)``)
    context_hash: str | None = None

    @property
    def designs_per_min(self) -> float | None:
        """Designs computed per minute (start-up excluded), or None if none were computed."""
        return 60.0 * self.computed / self.compute_s if self.computed and self.compute_s > 0 else None

    def to_json(self) -> dict:
        """The counts and times as a JSON-ready dict."""
        return {"points": self.points, "listed": self.listed if self.listed is not None else self.points,
                "done": self.done, "ok": self.ok, "refused": self.refused,
                "failed": self.failed, "computed": self.computed, "skipped": self.skipped,
                "store": str(self.store), "model_version": self.model_version, "wall_s": self.wall_s,
                "compute_s": self.compute_s, "designs_per_min": self.designs_per_min, "workers": self.workers,
                "scheduler": self.scheduler, "interrupted": self.interrupted}


class StudyInterrupted(ClutchfemError):
    """Ctrl-C during a run: finished rows are stored; ``result`` has the counts.

    Attributes
    ----------
    result : RunResult
        What the run did until then (``points``, ``done``, ``computed``, ``store``, ...); a
        rerun of the same study computes only the rest.

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.evaluation import RunResult
    >>> res = RunResult(points=12, done=5, ok=5, refused=0, failed=0, computed=5, skipped=0,
    ...                 store="out/results.sqlite", model_version="v1", wall_s=40.0, compute_s=35.0,
    ...                 workers=2, scheduler="local", interrupted=True)
    >>> e = cf.StudyInterrupted(res)
    >>> isinstance(e, cf.ClutchfemError), e.result.done
    (True, 5)
    >>> print(e)
    interrupted (Ctrl-C): 5 of 12 points are finished and stored in out/results.sqlite (5 in this run); run the
    same command again to compute the rest
    """

    def __init__(self, result: RunResult):
        self.result = result
        super().__init__(f"interrupted (Ctrl-C): {result.done} of {result.points} points are finished and stored "
                         f"in {result.store} ({result.computed} in this run); run the same command again to "
                         "compute the rest")


def _counts(store: ResultStore, version: str, keys: list[str]) -> dict:
    st = store.finished(version, keys)
    vals = list(st.values())
    return {"done": len(st), "ok": vals.count("ok"), "refused": vals.count("refused"),
            "failed": vals.count("failed")}


def run_points(points: list[dict], settings: Settings, store_path: str | Path, *, workers: int | None = None,
               scheduler: str | None = None, retry_failed: bool = False, progress: bool = True,
               source: str = "", spec_text: str = "", desc: str = "study", error_points=()) -> RunResult:
    """Compute the rows of ``points`` not yet in the store (see module docstring).
    ``error_points``: indices of the points whose answers also get their error estimate (a
    finished row of such a point without one is computed again, with it)."""
    t_start = time.perf_counter()
    if scheduler is not None and workers is not None:
        raise InputError("give --workers N (a local cluster) or --scheduler ADDRESS (an existing one), not both")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 0):
        raise InputError(f"workers = {workers!r} is not allowed: an integer >= 0 (0: in this process, no Dask)")
    if scheduler is not None:
        scheduler = check_scheduler(scheduler)  # before any work: a typo is said at once
    version = model_version(settings.concept)
    keys, tasks, hashes = [], {}, []
    for p in points:
        h = design_hash(p, settings)
        hashes.append(h)
        if h not in tasks:
            keys.append(h)
            tasks[h] = p
    want_errors = {hashes[i] for i in error_points}
    ctx = context_hash(settings)
    store = ResultStore(store_path, COLUMNS, context=ctx)
    try:
        finished = store.select(version, keys, ["status", "errors_estimated"])
        todo = [h for h in keys if h not in finished or (retry_failed and finished[h][0] == "failed")
                or (h in want_errors and finished[h][0] == "ok" and finished[h][1] != 1)]
        run = store.start_run(source, version, len(keys), len(todo), spec_text)
        if scheduler is not None:
            n_workers, label = None, scheduler
        elif workers == 0:
            n_workers, label = 0, "in process"
        elif workers is None and len(todo) <= IN_PROCESS_MAX:
            # a handful of points: faster here than a cluster start (BENCHMARKS.md, crossover)
            n_workers, label = 0, f"in process ({len(todo)} point(s) to compute: fewer than a cluster start pays for)"
        else:
            n_workers, why = workers_machine_holds(workers, len(todo))
            if why:
                log.warning(why)
            label = f"local cluster, {n_workers} process workers"
        computed, interrupted, t_first, t_last = 0, False, None, None
        bar = None
        tally = {"ok": 0, "refused": 0, "failed": 0}
        try:
            if todo:
                if progress and not (n_workers == 0 and scheduler is None):
                    log.info(f"{desc}: {len(todo)} design(s) to compute; starting {label} (its workers load "
                             "the FE stack: seconds before the first design)" if scheduler is None else
                             f"{desc}: {len(todo)} design(s) to compute; connecting to the scheduler at {label}")
                rows = (_in_process(todo, tasks, settings, want_errors) if n_workers == 0 and scheduler is None
                        else rows_on_dask(todo, tasks, settings, version, n_workers, scheduler, want_errors))
                for row in rows:
                    if "__start__" in row:  # the back-end is up and the points are submitted
                        n_workers = row["__start__"]
                        t_first = time.perf_counter()
                        bar = _bar(len(todo), desc, progress)
                        continue
                    if row.get("model_version") != version:
                        row = failed_row(tasks[row["design_hash"]], settings, row["design_hash"], version,
                                         f"the worker {row.get('worker')} runs model version "
                                         f"{row.get('model_version')}, this client {version}: install the same "
                                         "clutchfem on every worker")
                    store.put(row)
                    computed += 1
                    tally[row["status"]] = tally.get(row["status"], 0) + 1
                    t_last = time.perf_counter()
                    if bar is not None:
                        el = max(t_last - (t_first or t_last), 1e-9)
                        bar.set_postfix_str(f"ok {tally['ok']}, refused {tally['refused']}, failed {tally['failed']}"
                                            f"; {60 * computed / el:.0f} designs/min", refresh=False)
                        bar.update(1)
        except KeyboardInterrupt:
            interrupted = True
        except BaseException as exc:
            if not isinstance(exc, StoreLocked):  # a locked store cannot record the end either
                store.end_run(run, computed, f"error: {type(exc).__name__}: {exc}"[:500])
            raise
        finally:
            if bar is not None:
                bar.close()
        c = _counts(store, version, keys)
        store.end_run(run, computed, "interrupted" if interrupted else "finished")
    finally:
        store.close()
    compute_s = (t_last - t_first) if (t_first is not None and t_last is not None) else 0.0
    if len(keys) < len(points):
        log.warning(f"{len(points)} points listed, {len(keys)} distinct designs: a repeated design is computed "
                    "and counted once")
    res = RunResult(points=len(keys), listed=len(points), computed=computed, skipped=len(keys) - len(todo), store=Path(store_path),
                    model_version=version, wall_s=time.perf_counter() - t_start, compute_s=compute_s,
                    workers=n_workers, scheduler=label, keys=tuple(keys), interrupted=interrupted,
                    error_keys=tuple(h for h in keys if h in want_errors), context_hash=ctx, **c)
    if interrupted:
        raise StudyInterrupted(res)
    return res


def _bar(total: int, desc: str, progress: bool):
    if not progress or total == 0:
        return None
    return tqdm(total=total, desc=desc, unit="design", file=sys.stderr, dynamic_ncols=True, mininterval=0.5,
                smoothing=0.1)


# ---------------------------------------------------------------------------------------
# back-ends: in this process, or on dask.distributed (.cluster)
# ---------------------------------------------------------------------------------------
def _in_process(todo: list[str], tasks: dict, settings: Settings, want_errors=frozenset()):
    yield {"__start__": 0}
    for h in todo:
        yield evaluate(tasks[h], settings, h, h in want_errors)
