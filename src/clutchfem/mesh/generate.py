"""Meshing a concept: gmsh builds and meshes it with second-order curved triangles, the
``.msh`` and a JSON side-car are cached on disk, and both are read back as a
:class:`~clutchfem.mesh.ClutchMesh`.

* The cache key is a content hash of (concept name, parameters, mesh settings, gmsh and
  clutchfem versions, :func:`source_hash` of every source that shapes the mesh): a changed
  input or code gives a new file, never a stale mesh.
* Before meshing, the element count is estimated from the areas and local sizes
  (:func:`estimate_elements`); a mesh above :data:`MAX_ELEMENTS` is refused with a size
  that fits.
* The cache (:mod:`.cache`) lives in the platform's cache folder or ``$CLUTCHFEM_CACHE``
  and is bounded: a hit marks its entry used, a new entry evicts the least recently used.
  Processes meshing the same design at once take turns on its entry lock
  (:func:`.cache.entry_lock`): the first meshes, the others read its files; each file is
  written under a temporary name of its own and renamed into place.
* The cache file is saved with every element's entity tag and no physical groups (meshio's
  msh4 reader wants all or none); the side-car maps entity tags to group names.  A second
  file, :func:`groups_msh_path`, keeps the named physical groups for the user.

gmsh is a process-global C++ library and not thread-safe: one model at a time per process,
guarded by :func:`clutchfem.geometry.gmsh_session`; parallel sweeps use processes.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import logging
import os
import tempfile
import time
import warnings
from pathlib import Path

import gmsh
import numpy as np

from .._version import __version__
from ..core import GeometryError, MeshError
from ..geometry import (
    BuiltModel,
    Concept,
    ConceptParams,
    MeshSettings,
    build_model,
    gmsh_session,
    occ_tolerances,
    source_hash,
)
from .cache import TMP_PREFIX, cache_dir, entry_lock, evict, touch
from .clutch_mesh import ClutchMesh, groups_msh_path
from .convert import meshio_to_skfem, read_cached_msh
from .highorder import guard_high_order, optimise_high_order

#: meshes estimated above this many elements are refused (a one-sector default mesh has ~2-3
#: thousand; 250 000 P2 triangles are ~1 M unknowns, minutes and GBs for one design)
MAX_ELEMENTS = 250_000
log = logging.getLogger("clutchfem")


def cache_key(concept: Concept, p: ConceptParams, ms: MeshSettings) -> str:
    """Content hash naming the cached mesh of ``concept`` with ``p`` and ``ms`` (module docstring)."""
    payload = json.dumps({"concept": concept.name, "params": p.model_dump(), "mesh": ms.model_dump(),
                          "gmsh": gmsh.__version__, "clutchfem": __version__,
                          "source": source_hash(concept)}, sort_keys=True, default=str)
    return hashlib.sha256(payload.encode()).hexdigest()[:24]


def mesh_concept(concept: Concept, p: ConceptParams, ms: MeshSettings | None = None, *,
                 use_cache: bool = True, max_elements: int | None = None) -> ClutchMesh:
    """Build and mesh ``concept`` with parameters ``p`` (cached on disk).

    Before meshing, the element count is estimated from the areas and the local sizes
    (:func:`estimate_elements`); above ``max_elements`` (default :data:`MAX_ELEMENTS`) the
    mesh is refused with the estimate and a size that fits.  A cached file that cannot be
    read (truncated, corrupted) is deleted, named in a warning, and rebuilt."""
    ms = ms or MeshSettings()
    if not isinstance(ms, MeshSettings):
        raise MeshError(f"mesh settings must be a MeshSettings, not {type(ms).__name__}")
    key = cache_key(concept, p, ms)
    d = cache_dir()
    msh, side = d / f"{concept.name}-{key}.msh", d / f"{concept.name}-{key}.json"
    cm = _read_cached(msh, side, concept.name) if use_cache else None
    if cm is None:
        # one writer per entry: processes meshing the same design at once (a study's or the
        # test suite's workers sharing one cache) wait for the first, then read its files
        with entry_lock(d, msh.stem):
            cm = _read_cached(msh, side, concept.name) if use_cache else None
            if cm is None:
                t0 = time.perf_counter()
                built = _generate(concept, p, ms, msh, max_elements)
                meta = {"entity_groups": built.entity_groups, "group_dims": built.group_dims,
                        "mass": built.mass, "pivots": built.pivots, "contact_arcs": built.contact_arcs,
                        "n_shoes_total": built.n_shoes_total, "n_shoes_model": built.n_shoes_model,
                        "sector_angle": built.sector_angle, "mirrored": built.mirrored,
                        "mesh_time_s": time.perf_counter() - t0}
                text = json.dumps(meta)
                _atomic_write_text(side, text)
                # read back as a cache hit reads it (the same function, file and side-car
                # text): the design asked for again in this process is then not read twice
                st = msh.stat()
                cm = dataclasses.replace(_loaded(str(msh), (st.st_mtime_ns, st.st_size), text, concept.name))
                cm.cached, cm.mesh_time_s = False, meta["mesh_time_s"]
                n, freed = evict(d=d)
                if n:
                    log.info("mesh cache %s: %d least recently used meshes deleted (%.0f MB) to stay within its "
                             "bound (CLUTCHFEM_CACHE_SIZE)", d, n, freed / 1e6)
    cm.params = p.model_dump()
    cm.mesh_settings = ms.model_dump()
    cm.drum_radius = p.drum_radius
    cm.thickness = p.thickness
    return cm


def _read_cached(msh: Path, side: Path, source: str) -> ClutchMesh | None:
    """The cached mesh of an entry, or None if there is none; a cached file that cannot be
    read is deleted, named in a warning, and None returned (it is rebuilt)."""
    if not (msh.exists() and side.exists()):
        return None
    try:
        text = side.read_text()
        st = msh.stat()
        # a copy: the caller sets its own attributes (parameters, cache flag, morph record)
        cm = dataclasses.replace(_loaded(str(msh), (st.st_mtime_ns, st.st_size), text, source))
        meta = json.loads(text)
        touch(side)
    except Exception as exc:  # noqa: BLE001 - a broken cache entry is rebuilt, not fatal
        warnings.warn(f"mesh cache file {msh} is unreadable ({type(exc).__name__}: {exc}); "
                      "deleted and rebuilt", stacklevel=3)
        for f in (msh, side, groups_msh_path(msh)):
            f.unlink(missing_ok=True)
        return None
    cm.cached, cm.mesh_time_s = True, meta["mesh_time_s"]
    return cm


@functools.lru_cache(maxsize=16)
def _loaded(msh: str, stamp: tuple[int, int], meta: str, source: str) -> ClutchMesh:
    """A cache entry read once per process and state of its file (``stamp``: modification
    time, size): a design asked for again (the test suite's workers read ~600 such) costs no
    read and no conversion.  The mesh arrays are shared, never written to."""
    return _load_generated(Path(msh), json.loads(meta), source)


def estimate_elements(built: BuiltModel, p: ConceptParams, ms: MeshSettings) -> int:
    """A lower estimate of the triangle count: ~2.3 equilateral-ish triangles per h^2 of area,
    with the flexure zones at their own size (boundary refinement at fillets and on the
    contact surface adds to it: the real count is 1-6x this, nearer 1x for fine meshes)."""
    A = float(built.mass.get("solid", {}).get("area", 0.0))
    Af = sum(float(v.get("area", 0.0)) for k, v in built.mass.items() if k.startswith("flexure"))
    h = ms.size
    ts = p.flexure_thicknesses()
    hf = min(h, ms.flexure_factor * min(ts)) if ts else h
    n = 2.3 * (max(A - Af, 0.0) / h ** 2 + Af / hf ** 2)
    if ms.refine_radius > 0 and ms.refine_size < h:  # the refined disc (at most the whole part)
        n += 2.3 * min(np.pi * ms.refine_radius ** 2, A) / ms.refine_size ** 2
    return int(n)


def _check_size(name: str, n_est: int, ms: MeshSettings, max_elements: int | None) -> None:
    limit = MAX_ELEMENTS if max_elements is None else max_elements
    if n_est > limit:
        fit = ms.size * (n_est / limit) ** 0.5
        if ms.refine_radius > 0 and ms.refine_size < ms.size:
            raise MeshError(f"{name}: a refined disc of radius {ms.refine_radius * 1e3:g} mm at {ms.refine_size * 1e3:g} mm "
                            f"elements would give about {n_est:,} elements (estimate), more than the limit {limit:,}; "
                            "use a larger refine_size or a smaller refine_radius")
        raise MeshError(f"{name}: mesh size {ms.size * 1e3:g} mm would give about {n_est:,} elements (estimate), "
                        f"more than the limit {limit:,} (minutes of meshing and GBs of memory for one design); "
                        f"use a mesh size of at least {fit * 1e3:.2g} mm, or raise the limit "
                        "(max_elements=... in the API)")
    if n_est > 20_000:
        log.info("meshing %s: about %s elements (estimate)", name, f"{n_est:,}")


def _generate(concept: Concept, p: ConceptParams, ms: MeshSettings, msh: Path,
              max_elements: int | None = None) -> BuiltModel:
    with gmsh_session(concept.name):
        occ_tolerances()
        try:
            built = build_model(concept, p, ms)
            _check_size(concept.name, estimate_elements(built, p, ms), ms, max_elements)
            gmsh.option.setNumber("Mesh.Algorithm", 6)
            gmsh.option.setNumber("Mesh.ElementOrder", ms.order)
            gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
            gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
            gmsh.model.mesh.generate(2)
            if ms.order == 2:
                optimise_high_order()
                g = guard_high_order(concept.name, mirrored=built.mirrored, reshape_below=ms.reshape_below)
                if g.moved_interior or g.moved_outline:
                    log.info("%s: distorted curved elements repaired (worst scaled Jacobian %.2g -> %.2g; "
                             "%d interior mid-side nodes moved, %d outline ones straightened, chord error <= %.2g um)",
                             concept.name, g.worst_before, g.worst_after, g.moved_interior, g.moved_outline,
                             g.max_sagitta * 1e6)
            if built.mirrored:  # minus arrangement: reflect the canonical mesh, y -> -y
                gmsh.model.mesh.affineTransform([1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0])
        except (GeometryError, MeshError):
            raise
        except Exception as exc:  # gmsh raises bare Exceptions with its log message
            raise GeometryError(f"gmsh failed to build/mesh concept '{concept.name}': {exc}",
                                p.model_dump()) from None
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        # the user-facing file keeps the named physical groups ...
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        _atomic_write(groups_msh_path(msh))
        # ... the cache file is read back by meshio, whose msh4 reader wants all or no
        # physical tags: save every element with its entity tag and no groups; the JSON
        # side-car maps entity tags to group names
        gmsh.model.removePhysicalGroups()
        gmsh.option.setNumber("Mesh.SaveAll", 1)
        _atomic_write(msh)
    return built


def _atomic_write(path: Path) -> None:
    fd, tmp = tempfile.mkstemp(prefix=TMP_PREFIX, suffix=".msh", dir=path.parent)
    os.close(fd)
    gmsh.write(tmp)
    os.replace(tmp, path)


def _atomic_write_text(path: Path, text: str) -> None:
    """Write ``path`` through a temporary file of its own and an atomic rename: a reader sees
    the old file or the whole new one, and two writers never share a temporary file."""
    fd, tmp = tempfile.mkstemp(prefix=TMP_PREFIX, suffix=".json.tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _load_generated(msh: Path, meta: dict, source: str) -> ClutchMesh:
    m = read_cached_msh(msh)
    groups, dims = meta["entity_groups"], meta["group_dims"]
    curves = {k: set(map(int, v)) for k, v in groups.items() if dims[k] == 1}
    surfaces = {k: set(map(int, v)) for k, v in groups.items() if dims[k] == 2}
    mesh = meshio_to_skfem(m, curves, surfaces, "gmsh:geometrical", source)
    return ClutchMesh(mesh=mesh, source=source, n_shoes_total=meta["n_shoes_total"],
                      n_shoes_model=meta["n_shoes_model"], sector_angle=meta["sector_angle"],
                      mass=meta["mass"], pivots=[tuple(p) for p in meta["pivots"]],
                      contact_arcs=[tuple(a) for a in meta["contact_arcs"]], mirrored=meta["mirrored"],
                      msh_path=msh)
