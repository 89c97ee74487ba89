"""Mesh pipeline: gmsh -> .msh -> meshio -> scikit-fem ``MeshTri2`` with named groups.

* :func:`mesh_concept` builds a concept with gmsh (see :mod:`clutchfem.geometry.build`),
  meshes it with second-order curved triangles and caches the ``.msh`` plus a JSON side-car
  on disk under a content hash of (concept source, parameters, mesh settings, gmsh version).
* :func:`load_msh` reads any ``.msh`` with meshio and returns a :class:`ClutchMesh`: the
  skfem mesh with boundary facets and element subdomains by name.  scikit-fem's meshio
  reader does not turn order-2 ``line3`` boundary cells into boundary tags, so the facets
  are matched here from the two end vertices of every boundary cell.
* :func:`load_user_geometry` imports a user's ``.msh`` or STEP file (metres, x-y plane,
  axis at the origin, physical curve groups ``bore`` and optionally ``contact``).

gmsh is a process-global C++ library and not thread-safe: one model at a time per process,
guarded by :func:`clutchfem.geometry.session.gmsh_session`; parallel sweeps use processes.
"""

from __future__ import annotations

import contextlib
import hashlib
import inspect
import io
import json
import logging
import os
import tempfile
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import gmsh
import meshio
import numpy as np
from skfem import MeshTri1, MeshTri2

from .. import __version__
from ..core import GeometryError, MeshError
from ..geometry import BuiltModel, Concept, ConceptParams, MeshSettings, build_model, gmsh_session, source_files


@dataclass
class ClutchMesh:
    """A meshed clutch (or any 2-D part) ready for the FE model.

    ``mesh`` carries boundaries ``bore``, ``contact``, ``contact_<i>`` and, for a sector,
    ``cut_a``/``cut_b``; subdomains ``solid``, ``shoe_<i>``, ``flexure_<i>``, ``hub``
    where known.  ``sector_angle`` (rad) is set for a one-sector model of ``n_shoes_total``
    identical shoes (cut_b is cut_a rotated by +sector_angle).
    """

    mesh: MeshTri2
    source: str
    n_shoes_total: int = 1
    n_shoes_model: int = 1
    sector_angle: float | None = None
    drum_radius: float | None = None
    thickness: float | None = None
    params: dict = field(default_factory=dict)
    mesh_settings: dict = field(default_factory=dict)
    mass: dict = field(default_factory=dict)
    pivots: list = field(default_factory=list)
    contact_arcs: list = field(default_factory=list)
    mirrored: bool = False
    msh_path: Path | None = None
    mesh_time_s: float = 0.0
    cached: bool = False

    @property
    def sector_copies(self) -> int:
        """How many copies of the model make the whole part (n_shoes_total / n_shoes_model for
        a one-sector model, 1 for a full part)."""
        return self.n_shoes_total // max(self.n_shoes_model, 1) if self.sector_angle is not None else 1

    @property
    def n_elements(self) -> int:
        return int(self.mesh.t.shape[1])

    @property
    def n_nodes(self) -> int:
        return int(self.mesh.doflocs.shape[1])

    def boundary(self, name: str) -> np.ndarray:
        b = self.mesh.boundaries or {}
        if name not in b:
            raise MeshError(f"mesh from {self.source} has no boundary group '{name}'; "
                            f"available: {sorted(b)}")
        return np.asarray(b[name])


# ---------------------------------------------------------------------------------------
# meshio -> skfem
# ---------------------------------------------------------------------------------------
def _facet_lookup(mesh) -> dict[tuple[int, int], int]:
    f = np.sort(mesh.facets, axis=0)
    return {(int(a), int(b)): k for k, (a, b) in enumerate(f.T)}


def meshio_to_skfem(m: meshio.Mesh, curve_groups: dict[str, set[int]],
                    surface_groups: dict[str, set[int]], key: str, source: str) -> MeshTri2:
    """Convert a meshio mesh of triangles (order 1 or 2) into a ``MeshTri2`` with named
    boundaries and subdomains.

    ``key`` is the meshio cell-data key that labels cells (``gmsh:physical`` for user
    files, ``gmsh:geometrical`` for our own cached models); ``curve_groups`` and
    ``surface_groups`` map a group name to the set of labels it contains (a label may sit
    in several groups, e.g. ``contact`` and ``contact_0``).
    """
    pts = np.asarray(m.points, dtype=float)
    if pts.shape[1] == 3:
        scale = max(float(np.ptp(pts[:, :2], axis=0).max()), 1e-300)
        if np.abs(pts[:, 2]).max() > 1e-9 * scale:
            raise MeshError(f"{source}: the mesh is not planar (z varies up to "
                            f"{np.abs(pts[:, 2]).max():.3g} m); expected a 2-D part in the x-y plane")
        pts = pts[:, :2]
    tri_type = "triangle6" if "triangle6" in m.cells_dict else ("triangle" if "triangle" in m.cells_dict else None)
    if tri_type is None:
        raise MeshError(f"{source}: no triangle elements found (cell types: {sorted(m.cells_dict)}); "
                        "expected a 2-D triangle mesh")
    t_all = np.vstack([c.data for c in m.cells if c.type == tri_type])
    if tri_type == "triangle6":
        # keep only the triangles' nodes: a gmsh file also holds nodes no triangle uses
        # (circle-arc centres, points of curves saved on their own), which MeshTri2 would
        # carry along as extra 'nodes'
        used = np.unique(t_all)
        t_all = np.searchsorted(used, t_all)
        pts = pts[used]
        line_map = used
        uniq = np.unique(t_all[:, :3])
        mesh = MeshTri2(np.ascontiguousarray(pts.T), np.ascontiguousarray(t_all.T))
    else:
        uniq = np.unique(t_all)
        line_map = None
        t = np.searchsorted(uniq, t_all).T
        mesh = MeshTri2.from_mesh(MeshTri1(np.ascontiguousarray(pts[uniq].T), np.ascontiguousarray(t)))
    labels = m.cell_data.get(key)
    sub: dict[str, np.ndarray] = {}
    bnd: dict[str, np.ndarray] = {}
    if labels is not None:
        tri_lab = np.concatenate([np.asarray(labels[i]) for i, c in enumerate(m.cells) if c.type == tri_type])
        for name, labs in surface_groups.items():
            sub[name] = np.nonzero(np.isin(tri_lab, list(labs)))[0].astype(np.int64)
        # boundaries: match every labelled line/line3 cell to a facet by its end vertices
        line_blocks = [(c.data, np.asarray(labels[i])) for i, c in enumerate(m.cells)
                       if c.type in ("line", "line3")]
        if line_blocks:
            raw = np.vstack([d[:, :2] for d, _ in line_blocks])
            if line_map is not None:  # file node numbers -> compacted numbers (-1: not a triangle node)
                pos = np.clip(np.searchsorted(line_map, raw), 0, len(line_map) - 1)
                raw = np.where(line_map[pos] == raw, pos, -1)
            ends = np.where(raw >= 0, np.searchsorted(uniq, raw), -1)
            lab = np.concatenate([lv for _, lv in line_blocks])
            lookup = _facet_lookup(mesh)
            facet = np.array([lookup.get((min(a, b), max(a, b)), -1) for a, b in ends], dtype=np.int64)
            for name, labs in curve_groups.items():
                sel = np.isin(lab, list(labs))
                if np.any(facet[sel] < 0):
                    raise MeshError(f"{source}: {int(np.sum(facet[sel] < 0))} cells of boundary group "
                                    f"'{name}' do not match any triangle edge")
                bnd[name] = np.unique(facet[sel])
    if bnd:
        mesh = mesh.with_boundaries(bnd)
    if sub:
        mesh = mesh.with_subdomains(sub)
    _check_orientation(mesh, source)
    return mesh


def _check_orientation(mesh: MeshTri2, source: str) -> None:
    """Refuse degenerate, inverted or folded elements.

    Two checks: (1) inside every element the Jacobian determinant keeps one sign and does not
    vanish (a curved P2 element whose mid-edge node is too far out fails this); (2) the two
    elements that share an interior edge lie on opposite sides of it (a flipped element in a
    fold fails this).  Elements may be oriented either way (gmsh keeps the orientation of
    mirrored surfaces), so the global sign is not checked.
    """
    from skfem import Basis, ElementTriP0

    basis = Basis(mesh, ElementTriP0(), intorder=4)
    detJ = basis.mapping.detDF(basis.X)
    scale = np.median(np.abs(detJ))
    pos = (detJ > 1e-10 * scale).all(axis=1)
    neg = (detJ < -1e-10 * scale).all(axis=1)
    bad = ~(pos | neg)
    p, t, f2t, facets = mesh.p, mesh.t, mesh.f2t, mesh.facets
    inner = np.nonzero(f2t[1] >= 0)[0]
    a, b = p[:, facets[0, inner]], p[:, facets[1, inner]]

    def side(elems):
        c = p[:, t[:, elems]].mean(axis=1)
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    folded = side(f2t[0, inner]) * side(f2t[1, inner]) >= 0
    nbad = int(bad.sum()) + int(folded.sum())
    if nbad:
        raise MeshError(f"{source}: {nbad} inverted, folded or degenerate element(s) (Jacobian "
                        "changes sign or vanishes, or neighbours overlap); fix or regenerate the mesh")


# ---------------------------------------------------------------------------------------
# concepts: build + mesh + cache
# ---------------------------------------------------------------------------------------
def cache_dir() -> Path:
    d = Path(os.environ.get("CLUTCHFEM_CACHE", Path.home() / ".cache" / "clutchfem")) / "meshes"
    d.mkdir(parents=True, exist_ok=True)
    return d


def source_hash(concept: Concept) -> str:
    """Hash of every source that shapes the mesh: the concept's module file and those of its
    base classes loaded from geometries/, plus the generic geometry code."""
    h = hashlib.sha256()
    files = {inspect.getfile(cls) for cls in type(concept).__mro__
             if cls.__module__.startswith("clutchfem_geometries.")}
    files |= {str(f) for f in source_files()}
    files.add(__file__)  # the meshing pipeline itself (high-order fix-up)
    for f in sorted(files):
        h.update(Path(f).read_bytes())
    return h.hexdigest()[:16]


def cache_key(concept: Concept, p: ConceptParams, ms: MeshSettings) -> str:
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
    cached = use_cache and msh.exists() and side.exists()
    if cached:
        try:
            meta = json.loads(side.read_text())
            cm = _load_generated(msh, meta, concept.name)
        except Exception as exc:  # noqa: BLE001 - a broken cache entry is rebuilt, not fatal
            warnings.warn(f"mesh cache file {msh} is unreadable ({type(exc).__name__}: {exc}); "
                          "deleted and rebuilt", stacklevel=2)
            for f in (msh, side, groups_msh_path(msh)):
                f.unlink(missing_ok=True)
            cached = False
    if not cached:
        t0 = time.perf_counter()
        built = _generate(concept, p, ms, msh, max_elements)
        meta = {"entity_groups": built.entity_groups, "group_dims": built.group_dims,
                "mass": built.mass, "pivots": built.pivots, "contact_arcs": built.contact_arcs,
                "n_shoes_total": built.n_shoes_total, "n_shoes_model": built.n_shoes_model,
                "sector_angle": built.sector_angle, "mirrored": built.mirrored,
                "mesh_time_s": time.perf_counter() - t0}
        tmp = side.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(meta))
        tmp.replace(side)
        cm = _load_generated(msh, meta, concept.name)
    cm.params = p.model_dump()
    cm.mesh_settings = ms.model_dump()
    cm.drum_radius = p.drum_radius
    cm.thickness = p.thickness
    cm.cached = cached
    cm.mesh_time_s = meta["mesh_time_s"]
    return cm


#: meshes estimated above this many elements are refused (a one-sector default mesh has ~2-3
#: thousand; 250 000 P2 triangles are ~1 M unknowns, minutes and GBs for one design)
MAX_ELEMENTS = 250_000
log = logging.getLogger("clutchfem")


def estimate_elements(built: BuiltModel, p: ConceptParams, ms: MeshSettings) -> int:
    """A lower estimate of the triangle count: ~2.3 equilateral-ish triangles per h^2 of area,
    with the flexure zones at their own size (boundary refinement at fillets and on the
    contact surface adds to it: the real count is 1-6x this, nearer 1x for fine meshes)."""
    A = float(built.mass.get("solid", {}).get("area", 0.0))
    Af = sum(float(v.get("area", 0.0)) for k, v in built.mass.items() if k.startswith("flexure"))
    h = ms.size
    ts = p.flexure_thicknesses()
    hf = min(h, ms.flexure_factor * min(ts)) if ts else h
    return int(2.3 * (max(A - Af, 0.0) / h ** 2 + Af / hf ** 2))


def _check_size(name: str, n_est: int, ms: MeshSettings, max_elements: int | None) -> None:
    limit = MAX_ELEMENTS if max_elements is None else max_elements
    if n_est > limit:
        fit = ms.size * (n_est / limit) ** 0.5
        raise MeshError(f"{name}: mesh size {ms.size * 1e3:g} mm would give about {n_est:,} elements (estimate), "
                        f"more than the limit {limit:,} (minutes of meshing and GBs of memory for one design); "
                        f"use a mesh size of at least {fit * 1e3:.2g} mm, or raise the limit "
                        "(max_elements=... in the API)")
    if n_est > 20_000:
        log.info("meshing %s: about %s elements (estimate)", name, f"{n_est:,}")


def _generate(concept: Concept, p: ConceptParams, ms: MeshSettings, msh: Path,
              max_elements: int | None = None) -> BuiltModel:
    with gmsh_session(concept.name):
        gmsh.option.setNumber("Geometry.Tolerance", 1e-10)
        gmsh.option.setNumber("Geometry.ToleranceBoolean", 1e-10)
        try:
            built = build_model(concept, p, ms)
            _check_size(concept.name, estimate_elements(built, p, ms), ms, max_elements)
            gmsh.option.setNumber("Mesh.Algorithm", 6)
            gmsh.option.setNumber("Mesh.ElementOrder", ms.order)
            gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
            gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
            gmsh.model.mesh.generate(2)
            if ms.order == 2:
                _fix_invalid_high_order()
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


def groups_msh_path(msh: Path) -> Path:
    """The ``.msh`` with named physical groups that sits beside a cached mesh."""
    return msh.with_name(msh.stem + ".groups.msh")


def _atomic_write(path: Path) -> None:
    fd, tmp = tempfile.mkstemp(suffix=".msh", dir=path.parent)
    os.close(fd)
    gmsh.write(tmp)
    os.replace(tmp, path)


def _meshio_read(path: Path) -> meshio.Mesh:
    """meshio.read without its stray prints on stdout (its gmsh reader prints an empty line
    per file, which breaks the CLI's tables and JSON output); real messages become warnings."""
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        m = meshio.read(path)
    if buf.getvalue().strip():
        warnings.warn(f"meshio ({path}): {buf.getvalue().strip()}", stacklevel=2)
    return m


def _fix_invalid_high_order() -> None:
    """Run gmsh's high-order optimiser if some curved element is invalid or nearly so
    (scaled Jacobian < 0.2): a valid but nearly singular P2 element gives garbage raw vertex
    stresses (several GPa where the field peaks at a few hundred MPa)."""
    types, tags, _ = gmsh.model.mesh.getElements(2)
    worst = 1.0
    for t in tags:
        q = gmsh.model.mesh.getElementQualities(t, "minSJ")
        if len(q):
            worst = min(worst, float(np.min(q)))
    if worst < 0.2:
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
        gmsh.model.mesh.optimize("HighOrder")


def _load_generated(msh: Path, meta: dict, source: str) -> ClutchMesh:
    m = _meshio_read(msh)
    groups, dims = meta["entity_groups"], meta["group_dims"]
    curves = {k: set(map(int, v)) for k, v in groups.items() if dims[k] == 1}
    surfaces = {k: set(map(int, v)) for k, v in groups.items() if dims[k] == 2}
    mesh = meshio_to_skfem(m, curves, surfaces, "gmsh:geometrical", source)
    return ClutchMesh(mesh=mesh, source=source, n_shoes_total=meta["n_shoes_total"],
                      n_shoes_model=meta["n_shoes_model"], sector_angle=meta["sector_angle"],
                      mass=meta["mass"], pivots=[tuple(p) for p in meta["pivots"]],
                      contact_arcs=[tuple(a) for a in meta["contact_arcs"]], mirrored=meta["mirrored"],
                      msh_path=msh)


# ---------------------------------------------------------------------------------------
# user geometry: .msh or STEP
# ---------------------------------------------------------------------------------------
def load_user_geometry(path: str | Path, *, mesh_size: float | None = None,
                       thickness: float | None = None, drum_radius: float | None = None) -> ClutchMesh:
    """Import a user's part: a gmsh ``.msh`` (any order; P1 is lifted to straight P2) with
    physical curve groups ``bore`` (clamped) and optionally ``contact``; or a STEP file
    (meshed here with second-order triangles; the bore is the boundary loop around the
    origin and, if ``drum_radius`` is given, the contact group is the set of boundary
    curves facing outward within 25 % of the largest radius).  Metres, x-y plane, rotation
    axis through the origin."""
    path = Path(path)
    if not path.exists():
        raise MeshError(f"mesh file {path} does not exist")
    suffix = path.suffix.lower()
    if suffix in (".step", ".stp"):
        return _load_step(path, mesh_size, thickness, drum_radius)
    if suffix != ".msh":
        raise MeshError(f"{path}: unsupported file type '{suffix}' (use a gmsh .msh or a STEP file)")
    try:
        m = _meshio_read(path)
    except (Exception, SystemExit) as exc:  # meshio calls sys.exit() on files it cannot identify
        raise MeshError(f"{path}: meshio cannot read it as a gmsh mesh ({exc or type(exc).__name__})") from None
    names: dict[str, tuple[int, int]] = {k: (int(v[0]), int(v[1])) for k, v in (m.field_data or {}).items()}
    curves = {k: {tag} for k, (tag, dim) in names.items() if dim == 1}
    surfaces = {k: {tag} for k, (tag, dim) in names.items() if dim == 2}
    if "bore" not in curves:
        raise MeshError(f"{path}: no physical curve group named 'bore' (the clamped crankshaft bore); "
                        f"groups found: {sorted(names) or 'none'}")
    key = "gmsh:physical"
    if m.cell_sets and all(k in m.cell_sets for k in names):
        # msh4: an element may sit in several physical groups (contact and contact_0, solid
        # and shoe_0), but meshio's per-cell 'gmsh:physical' keeps only one of them; its
        # cell_sets keep them all.  Label every cell by its index and map groups to indices.
        key = "clutchfem:cell"
        ids, off = [], 0
        for c in m.cells:
            ids.append(np.arange(off, off + len(c.data)))
            off += len(c.data)
        m.cell_data[key] = ids

        def members(name: str) -> set[int]:
            return {int(k) for blk, sel in zip(ids, m.cell_sets[name]) if sel is not None
                    for k in blk[np.asarray(sel, dtype=np.int64)]}

        curves = {k: members(k) for k in curves}
        surfaces = {k: members(k) for k in surfaces}
    elif key not in m.cell_data:
        raise MeshError(f"{path}: the file carries no physical tags")
    mesh = meshio_to_skfem(m, curves, surfaces, key, str(path))
    bnd = mesh.boundaries or {}
    if len(bnd.get("bore", [])) == 0:
        raise MeshError(f"{path}: the 'bore' group has no edges on the triangle mesh")
    if "contact" in curves and len(bnd.get("contact", [])) == 0:
        raise MeshError(f"{path}: the 'contact' group has no edges on the triangle mesh")
    if "contact" in bnd and "contact_0" not in bnd:
        mesh = mesh.with_boundaries({"contact_0": mesh.boundaries["contact"]})
    return ClutchMesh(mesh=mesh, source=str(path), thickness=thickness, drum_radius=drum_radius)


def _load_step(path: Path, mesh_size, thickness, drum_radius) -> ClutchMesh:
    with gmsh_session("step"):
        try:
            gmsh.model.occ.importShapes(str(path))
            gmsh.model.occ.synchronize()
        except Exception as exc:
            raise MeshError(f"{path}: gmsh cannot import the STEP file ({exc})") from None
        surfaces = [t for d, t in gmsh.model.getEntities(2)]
        if not surfaces or gmsh.model.getEntities(3):
            raise MeshError(f"{path}: expected a planar 2-D part (surfaces in the x-y plane, no solids)")
        # planarity from points on the boundary curves (OCC's bounding box is padded by its
        # tolerance, ~1e-7 m, so it cannot tell a flat part from a slightly tilted one)
        bnd = gmsh.model.getBoundary([(2, t) for t in surfaces], combined=True, oriented=False)
        curves = sorted({abs(t) for d, t in bnd})
        samples = []
        for c in curves:
            lo, hi = gmsh.model.getParametrizationBounds(1, c)
            samples.append(np.asarray(gmsh.model.getValue(1, c, np.linspace(lo[0], hi[0], 9))).reshape(-1, 3))
        xyz = np.vstack(samples)
        size = float(np.ptp(xyz[:, :2], axis=0).max())
        if np.ptp(xyz[:, 2]) > 1e-9 * size:
            raise MeshError(f"{path}: the part is not planar (z varies by {np.ptp(xyz[:, 2]):.3g} m); "
                            "expected a 2-D part in the x-y plane")
        rmin, rmax, bore, contact = [], [], [], []
        for xy in samples:
            r = np.hypot(xy[:, 0], xy[:, 1])
            rmin.append(r.min())
            rmax.append(r.max())
        r_in = min(rmin)
        R_out = max(rmax)
        for c, a, b in zip(curves, rmin, rmax):
            if b < r_in + 0.25 * (R_out - r_in) and b < 0.5 * R_out:
                bore.append(c)
            elif drum_radius is not None and a > R_out - 0.25 * (R_out - r_in):
                contact.append(c)
        gmsh.model.addPhysicalGroup(2, surfaces, name="solid")
        gmsh.model.addPhysicalGroup(1, bore, name="bore")
        if contact:
            gmsh.model.addPhysicalGroup(1, contact, name="contact")
        h = mesh_size or (R_out / 40.0)
        area = sum(gmsh.model.occ.getMass(2, t) for t in surfaces)
        n_est = int(2.3 * area / h ** 2)
        if n_est > MAX_ELEMENTS:
            raise MeshError(f"{path}: mesh size {h * 1e3:g} mm would give about {n_est:,} elements (estimate), "
                            f"more than the limit {MAX_ELEMENTS:,}; use a mesh size of at least "
                            f"{h * (n_est / MAX_ELEMENTS) ** 0.5 * 1e3:.2g} mm")
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        try:
            gmsh.model.mesh.generate(2)
        except Exception as exc:
            raise MeshError(f"{path}: gmsh could not mesh the part ({exc})") from None
        fd, tmp = tempfile.mkstemp(suffix=".msh")
        os.close(fd)
        gmsh.write(tmp)
    try:
        return load_user_geometry(tmp, thickness=thickness, drum_radius=drum_radius)
    finally:
        os.unlink(tmp)
