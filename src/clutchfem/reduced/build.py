"""Building a region's reduced model on the study engine, and keeping it on disk.

**The build** (:func:`reduce`): ``n`` training designs and ``held_out`` more drawn apart from
them (a scrambled Sobol sample of the region, another seed), every one through the full best
path (``analyze`` with its error step: the corrected answers and their
bands) on the study engine (:func:`clutchfem.evaluation.run_points`: Dask workers or this
process, each finished design committed to the region's store as it arrives, so a build
that is interrupted or killed resumes where it stopped).  The model is fitted to the
training designs, its error measured on the held-out ones
(:meth:`~.model.ReducedModel.measure`), then fitted again to all of them (the error stated is
the one measured with fewer designs: conservative).  The training designs come in two stages:
half of them (:data:`ADAPTIVE`) a scrambled Sobol sample of the region (the concept's rules
applied), then a first fit to them picks the other half where it knows least
(:meth:`~.model.ReducedModel.most_uncertain`: the box's corners and faces, which a
space-filling sample of nine dimensions leaves far from every design; measured on concept 4,
BENCHMARKS.md section 24).  The picks are written to the region's folder before they are
solved, so a resumed build solves the same designs.

**The cache**: ``$CLUTCHFEM_CACHE/reduced/<concept>-<key>/`` (else the platform's user cache
folder), one folder per region (:meth:`~.region.Region.key`: concept, bounds, fixed
parameters, operating point, engine, requirement factors, code version) holding the store
(``results.sqlite``), the region (``region.json``) and the fitted model (``model.pkl``,
written atomically last: its presence means a finished build).  A later call with the same
region loads it in milliseconds; a live answer looks for a cached region that contains its
design (:func:`find`) before building one.  The cache deletes only what it wrote: a folder
it did not make is never touched.
"""

from __future__ import annotations

import functools
import importlib.metadata
import json
import logging
import os
import pickle
import time
from pathlib import Path

import platformdirs
from cachetools import LRUCache, cached

from ..core import InputError, ParameterError, dumps
from ..evaluation import STORE_NAME, ResultStore
from .model import ReducedModel
from .region import SPAN, Region

__all__ = ["ADAPTIVE", "DEFAULT_HELD_OUT", "DEFAULT_N", "cache_root", "find", "load", "outside_why", "reduce", "save",
           "split"]

log = logging.getLogger("clutchfem")

#: training designs of a default build (BENCHMARKS.md section 24: accuracy against designs)
DEFAULT_N = 330
#: the share of the training designs a build places where its first fit knows least (the rest
#: space-filling; BENCHMARKS.md section 24)
ADAPTIVE = 0.5
#: the candidate points (a scrambled Sobol sample of the box) the adaptive designs are picked from
POOL = 4096
#: held-out designs the model's error is measured on
DEFAULT_HELD_OUT = 30
#: a file in every folder the cache made (only such folders are ever deleted)
MARK = ".clutchfem-reduced"


def cache_root() -> Path:
    """The folder of the reduced models: ``$CLUTCHFEM_CACHE/reduced`` if the variable is set,
    else the platform's user cache folder's ``reduced``."""
    env = os.environ.get("CLUTCHFEM_CACHE")
    root = Path(env) if env else Path(platformdirs.user_cache_dir("clutchfem"))
    return root / "reduced"


def _claim(region: Region) -> Path:
    """The cache folder of ``region``, made and marked as the cache's own (with its
    ``region.json``); a folder of that name the cache did not make is refused, not used."""
    folder = _folder(region)
    if folder.exists() and not (folder / MARK).exists():
        raise InputError(f"{folder}: a folder the reduced-model cache did not make is in its way; move it "
                         "(the cache never deletes what it did not write)")
    folder.mkdir(parents=True, exist_ok=True)
    (folder / MARK).touch()
    (folder / "region.json").write_text(dumps(region.to_json(), indent=1))
    return folder


def _folder(region: Region) -> Path:
    return cache_root() / f"{region.concept}-{region.key()}"


@cached(LRUCache(maxsize=8), key=lambda path, mtime: (str(path), mtime))
def _read(path: Path, mtime: float) -> dict | None:
    """A model file's document, kept in this process while the file is unchanged."""
    try:
        with open(path, "rb") as fh:
            return pickle.load(fh)
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError):
        return None


@functools.cache
def _sklearn_version() -> str:
    """The installed scikit-learn's version (from its metadata: no import)."""
    return importlib.metadata.version("scikit-learn")


def load(region: Region) -> ReducedModel | None:
    """The finished reduced model of ``region`` from the cache, or None (read once per process
    while the file is unchanged)."""
    path = _folder(region) / "model.pkl"
    try:
        mtime = path.stat().st_mtime
    except OSError:
        return None
    doc = _read(path, mtime)
    if not doc or doc.get("sklearn") != _sklearn_version() or doc.get("key") != region.key():
        return None
    return doc["model"]


def find(design, *, engine=None, requirements=None) -> ReducedModel | None:
    """A cached reduced model whose region contains ``design`` (the same concept, fixed
    parameters, operating point, engine and requirements; its free parameters in the box),
    or None."""
    root = cache_root()
    if not root.is_dir() or design.params is None:
        return None
    for folder in sorted(root.glob(f"{design.name}-*")):
        try:
            doc = json.loads((folder / "region.json").read_text())
        except (OSError, ValueError):
            continue
        names = list(doc.get("free", {}))
        try:
            region = Region.around(design, free=names, ranges={n: tuple(v) for n, v in doc["free"].items()},
                                   engine=engine, requirements=requirements)
        except ParameterError:
            continue
        if region.key() != doc.get("key") or not region.contains(region.design_values(design)):
            continue
        model = load(region)
        if model is not None:
            return model
    return None


def outside_why(design, *, engine=None, requirements=None) -> str:
    """Why no cached region holds ``design``: the bounds of each finished region of the same
    fixed inputs (concept, fixed parameters, operating point, engine, requirements) it lies
    outside of, else that there is none.

    Examples
    --------
    >>> import os, tempfile, clutchfem as cf
    >>> from clutchfem.reduced import outside_why
    >>> os.environ["CLUTCHFEM_CACHE"] = tempfile.mkdtemp()      # an empty cache
    >>> outside_why(cf.Design.from_concept("concept1", fidelity="live"))
    'no cached region of these fixed inputs'
    """
    root = cache_root()
    found = []
    for folder in sorted(root.glob(f"{design.name}-*")) if root.is_dir() and design.params is not None else ():
        try:
            doc = json.loads((folder / "region.json").read_text())
            r = Region.around(design, free=list(doc["free"]), ranges={n: tuple(v) for n, v in doc["free"].items()},
                              engine=engine, requirements=requirements)
        except (OSError, ValueError, KeyError, ParameterError):
            continue
        if r.key() == doc.get("key") and (folder / "model.pkl").exists():
            found.append(f"region {r.key()}: " + "; ".join(r.outside(r.design_values(design))))
    return ("outside the cached region(s): " + " | ".join(found)) if found else "no cached region of these fixed inputs"


def split(n: int, dim: int, adaptive: float = ADAPTIVE) -> tuple[int, int]:
    """(space-filling, adaptive) training designs of a build of ``n`` over ``dim`` free
    parameters: the ``adaptive`` share of ``n`` picked where the first fit knows least, when
    the space-filling ones are enough for that fit (at least ``2 (dim + 2)``); else all
    space-filling.

    Examples
    --------
    >>> from clutchfem.reduced.build import split
    >>> split(330, 9), split(240, 9, adaptive=1 / 3), split(3, 1), split(12, 1, adaptive=0.0)
    ((165, 165), (160, 80), (3, 0), (12, 0))
    """
    k = int(adaptive * n + 1e-9)
    return (n - k, k) if k and n - k >= 2 * (dim + 2) else (n, 0)


def reduce(design, *, span: float = SPAN, ranges: dict | None = None, free=None, n: int = DEFAULT_N,
           held_out: int = DEFAULT_HELD_OUT, adaptive: float = ADAPTIVE, engine=None, requirements=None,
           workers: int | None = None, scheduler: str | None = None, progress: bool = True,
           seed: int = 0) -> ReducedModel:
    """Build (or load) the reduced model of the region around ``design``.

    Parameters
    ----------
    design : Design
        A concept's design: the region is +-``span`` of its free parameters (clipped to
        their declared ranges), or ``ranges``.
    span : float
        The relative half-width of the region (default 0.05: :mod:`clutchfem.reduced.region`
        says why).
    ranges : dict, optional
        ``name -> (lo, hi)`` (SI or texts with a unit): these parameters' bounds instead.
    free : list of str, optional
        The free parameters (default: the concept's shape parameters).
    n, held_out : int
        Training designs, and designs the model's error is measured on.
    adaptive : float
        The share of the training designs picked where a first fit to the others knows least
        (in [0, 0.5]; 0: all space-filling; :func:`split`).
    engine, requirements : optional
        The engine curve and requirement factors the answers are computed against.
    workers, scheduler, progress
        The study engine's controls (``workers=0``: in this process).
    seed : int
        The Sobol sequence's scrambling.

    Returns
    -------
    ReducedModel
        Its answers in milliseconds (:meth:`~clutchfem.reduced.ReducedModel.predict`) and
        their measured error (``accuracy``).

    Examples
    --------
    The reduced model of the fast path over concept 1's flexure thickness (a live design's is
    the best path's; this one is quicker to build), from 3 designs fitted and 2 held out (too
    few for designs picked where a first fit knows least: those need ``2 (dim + 2)``
    space-filling ones first, :func:`split`):

    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"), fidelity="fast")
    >>> m = cf.reduce(d, free=["flexure_thickness"], n=3, held_out=2, workers=0, progress=False)
    >>> m.region.names, m.info["n_adaptive"], m.info["fe_designs"], len(m.rows), m.accuracy["engagement_rpm"]["n"]
    (('flexure_thickness',), 0, 5, 5, 2)
    >>> bool(m.accuracy["engagement_rpm"]["max_rel"] < 0.01)      # measured on the 2 held out
    True
    """
    for name, v, lo in (("n", n, 3), ("held_out", held_out, 2)):
        if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= 5000:
            raise ParameterError(name, v, f"an integer in [{lo}, 5000]", "reduced model")
    if isinstance(adaptive, bool) or not isinstance(adaptive, (int, float)) or not 0.0 <= adaptive <= 0.5:
        raise ParameterError("adaptive", adaptive, "a share in [0, 0.5] of the training designs", "reduced model")
    region = Region.around(design, span=span, ranges=ranges, free=free, engine=engine, requirements=requirements)
    cached = load(region)
    if cached is not None and cached.info.get("n_train", 0) >= n and cached.info.get("n_held_out", 0) >= held_out:
        return cached
    folder = _claim(region)
    t0 = time.perf_counter()
    n_fill, n_adapt = split(n, region.dim, adaptive)
    train = region.sample(n_fill, seed=seed)
    test = region.sample(held_out, seed=seed + 1)
    log.info(f"reduce {region.concept}: {n_fill + held_out} designs through the best path ({n_fill} to fit, "
             f"{held_out} to measure its error{f', then {n_adapt} more where that fit knows least' if n_adapt else ''}) "
             f"in {region.describe()}")
    run = _Runner(region, folder, workers, scheduler, progress)
    rows = run(train + test, "reduce")
    rows_train, rows_test = rows[:n_fill], rows[n_fill:]
    if n_adapt:
        extra = _adaptive(ReducedModel.fit(region, rows_train, seed=seed), folder, n_adapt, seed)
        rows_train = rows_train + run(extra, "reduce, adaptive")
    model = ReducedModel.fit(region, rows_train, seed=seed)
    model.measure(rows_test)
    accuracy = model.accuracy
    rows = rows_train + rows_test
    final = ReducedModel.fit(region, rows, seed=seed, like=model)  # every design, its kernels the start
    final.accuracy = accuracy
    final.info.update(n_train=n, n_held_out=held_out, n_adaptive=n_adapt, build_s=time.perf_counter() - t0,
                      fe_designs=len(rows), fe_ok=sum(r.get("status") == "ok" for r in rows),
                      compute_s=run.compute_s, workers=run.workers)
    save(final)
    return final


class _Runner:
    """Runs a build's designs through the best path on the study engine into the region's
    store (each with its error step) and gives their rows in point order; sums the compute time."""

    def __init__(self, region: Region, folder: Path, workers, scheduler, progress: bool):
        self.region, self.store, self.kw = region, folder / STORE_NAME, dict(workers=workers, scheduler=scheduler,
                                                                             progress=progress)
        self.compute_s, self.workers = 0.0, None

    def __call__(self, points: list[dict], desc: str) -> list[dict]:
        from ..evaluation.point import COLUMNS  # (the FE evaluation of the training designs: a build's only)
        from ..evaluation.runner import run_points

        res = run_points(points, self.region.settings.study(), self.store, source=f"reduce {self.region.concept}",
                         desc=desc, error_points=list(range(len(points))), **self.kw)
        self.compute_s += res.compute_s
        self.workers = res.workers
        with ResultStore(self.store, COLUMNS, context=res.context_hash) as rs:
            df = rs.frame(res.model_version, list(res.keys))
        by_key = {r["design_hash"]: r for r in json.loads(df.to_json(orient="records"))}
        return [by_key[k] for k in res.keys if k in by_key]  # in point order (repeats counted once)


def _adaptive(first: ReducedModel, folder: Path, k: int, seed: int) -> list[dict]:
    """The ``k`` designs ``first`` knows least about (:meth:`ReducedModel.most_uncertain` over
    :data:`POOL` Sobol points of another seed), written to ``adaptive.json`` in the region's
    folder before they are solved, and read from it when a build resumes (a refit on another
    machine's arithmetic could pick others, and the finished ones would be lost)."""
    region = first.region
    path = folder / "adaptive.json"
    key = {"n_fill": len(first.rows), "k": k, "seed": seed, "pool": POOL}
    try:
        doc = json.loads(path.read_text())
        if doc.get("key") == key and len(doc.get("points", ())) == k:
            return doc["points"]
    except (OSError, ValueError):
        pass
    from scipy.stats import qmc  # (a build's only)

    pool = qmc.Sobol(region.dim, scramble=True, seed=seed + 2).random(POOL)
    picks = first.most_uncertain(pool, k, admissible=lambda i: region.admissible(region.values_at(pool[i])))
    points = [region.values_at(pool[i]) for i in picks]
    tmp = folder / "adaptive.json.tmp"
    tmp.write_text(dumps({"key": key, "points": points}, indent=1))
    tmp.replace(path)
    return points


def save(model: ReducedModel) -> Path:
    """Write ``model`` to the cache folder of its region (``region.json`` and ``model.pkl``,
    the latter atomically: its presence means a finished model), where :func:`find` and
    :func:`load` read it; returns the folder.  :func:`reduce` saves what it builds; a model
    fitted to rows of one's own (:meth:`ReducedModel.fit`) is saved the same way.

    Examples
    --------
    >>> import json, os, tempfile, clutchfem as cf
    >>> from clutchfem.reduced import ReducedModel, Region, find, save
    >>> os.environ["CLUTCHFEM_CACHE"] = tempfile.mkdtemp()
    >>> d = cf.Design.from_concept("concept1", fidelity="live")
    >>> r = Region.around(d, free=["flexure_thickness"])
    >>> row = lambda t: {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}),
    ...                  "engagement_rpm": 2.0e6 * t, "engagement_err_rpm": 20.0}
    >>> m = ReducedModel.fit(r, [row(t) for t in (2.1e-3, 2.13e-3, 2.17e-3, 2.2e-3, 2.26e-3, 2.3e-3)])
    >>> folder = save(m)
    >>> find(d).region.key() == r.key()
    True
    """
    region = model.region
    folder = _claim(region)
    tmp = folder / "model.pkl.tmp"
    with open(tmp, "wb") as fh:
        pickle.dump({"model": model, "key": region.key(), "sklearn": _sklearn_version()}, fh)
    tmp.replace(folder / "model.pkl")
    return folder
