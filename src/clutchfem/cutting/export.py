"""From a design to the files a cutter and a reviewer take: :func:`export` (``cf.export``,
``clutchfem export``).

In order, and nothing is written until every check has passed:

1. the whole part's exact outline (:func:`~.outline.part_outline`);
2. its features measured (:mod:`.features`) and, with a process (or explicit limits),
   checked: a feature below a limit refuses the export (:class:`~.features.CuttingError`,
   naming the feature, its size, the limit and the process);
3. the tool path: the outline offset by half the kerf into the waste (:mod:`.offset`; the
   nominal part is never moved: the DXF's part layers are the same with or without it);
4. the answers for the drawing: the given :class:`~clutchfem.Analysis`, or ``analyze`` with
   its error bands; and, on request, the as-cut variants (:mod:`.ascut`);
5. the files: DXF (:mod:`.dxf`), STEP (:mod:`.step`), the drawing sheet (:mod:`.sheet`,
   PDF/SVG and a PNG preview), ``export.json`` (what was written and measured) and
   ``inputs.json`` (the design, its hash, the clutchfem version) in every folder written to.

File names: with ``out`` alone every file is named after the design's label
(``<label>.dxf``, ``<label>.step``, ``<label>_drawing.pdf``); ``dxf=``, ``step=``,
``drawing=`` name a file explicitly (the label is then in its content: the DXF's TEXT layer,
the STEP header, the sheet's title block).  A path that is a folder, or whose folder is a
file, is refused before any work.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .._version import __version__
from ..analysis import analyze
from ..clutch import EngineCurve
from ..core import InputError, ParameterError, clean, parse_quantity, write
from ..loadcase import Design, design_hash, design_inputs, design_label
from .ascut import as_cut as run_as_cut
from .dxf import UNITS, write_dxf
from .features import CuttingError, check, measure
from .ligament import thinnest_ligament
from .offset import offset_loops
from .outline import part_outline
from .rules import ProcessRules
from .sheet import draw_sheet
from .step import write_step

DRAWING_SUFFIXES = (".pdf", ".svg", ".png")


@dataclass
class ExportResult:
    """What :func:`export` wrote and measured (lengths in m, areas m^2, volumes m^3);
    :meth:`to_json` is ``export.json``.

    Attributes
    ----------
    label, design_hash : str
        The design's label (the files' names) and hash.
    files : list of Path
    area_m2, thickness_m, volume_m3, mass_kg, outer_radius_m : float
        The whole part as cut (nominal contour).
    features : dict
        The measured inside radii, slots and webs.
    rules : ProcessRules or None
        The process checked against (None: unchecked); ``violations``: what failed.
    analysis : Analysis or None
        The answers on the drawing.

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.cutting import ExportResult
    >>> r = ExportResult("concept1", "abc123def456", [], area_m2=1.0e-3, thickness_m=0.011, volume_m3=1.1e-5,
    ...                  mass_kg=0.0864, outer_radius_m=0.0338, features={}, rules=cf.ProcessRules.of("laser"))
    >>> j = r.to_json()                      # the process's limits at this thickness: slots >= 0.7 t
    >>> j["process"]["process"], round(j["process"]["limits_m"]["min_slot"] * 1e3, 2), j["answers"]
    ('laser', 7.7, None)
    """

    label: str
    design_hash: str
    files: list[Path]
    area_m2: float
    thickness_m: float
    volume_m3: float | None
    mass_kg: float
    outer_radius_m: float
    features: dict
    rules: ProcessRules | None
    violations: list[str] = field(default_factory=list)
    analysis: object = None
    as_cut: dict | None = None
    units: str = "mm"
    outline: object = None
    toolpath: list | None = None
    #: the thinnest section of the part (:mod:`.ligament`)
    ligament: object = None

    def to_json(self) -> dict:
        return clean({
            "label": self.label, "design_hash": self.design_hash, "clutchfem": __version__,
            "files": [str(p) for p in self.files], "units": self.units,
            "area_m2": self.area_m2, "thickness_m": self.thickness_m, "volume_m3": self.volume_m3,
            "mass_kg": self.mass_kg, "outer_radius_m": self.outer_radius_m,
            "process": None if self.rules is None else {**self.rules.model_dump(), "sources": self.rules.sources(),
                                                        "limits_m": self.rules.limits(self.thickness_m)},
            "features": {k: [f.to_json() for f in v] for k, v in self.features.items()},
            "violations": self.violations, "as_cut": self.as_cut,
            "thinnest_ligament": None if self.ligament is None else self.ligament.to_json(),
            "answers": None if self.analysis is None else {
                "engagement_rpm": self.analysis.engagement_rpm, "slip_rpm": self.analysis.slip_rpm,
                "max_von_mises_Pa": self.analysis.max_von_mises_Pa, "errors": self.analysis.errors}})


def _target(path, out, default_name: str, option: str, suffixes) -> Path | None:
    if path is None and out is None:
        return None
    p = Path(path) if path is not None else Path(out) / default_name
    if p.suffix.lower() not in suffixes:
        raise InputError(f"{option} {p}: the file name must end in " + " or ".join(suffixes))
    if p.exists() and not p.is_file():
        raise InputError(f"{option} {p}: is a folder (or not a file): give a file name")
    parent = p.parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise InputError(f"{option} {p}: {parent} is a file, so no folder can be made inside it")
    writable(p, parent, option)
    return p


def writable(p: Path, parent: Path, option: str) -> None:
    """Refuse ``p`` unless it can be written: the file itself if it exists (opened for
    appending, nothing changed), else a probe file made and removed in ``parent``, its nearest
    existing folder (a real write: permission bits, read-only mounts and ``/proc`` alike)."""
    try:
        if p.exists():
            with open(p, "ab"):
                pass
        else:
            with tempfile.NamedTemporaryFile(dir=parent, prefix=".clutchfem-probe-"):
                pass
    except OSError as exc:
        raise InputError(f"{option} {p}: cannot be written ({exc.strerror or exc}); nothing was written: "
                         "choose a folder you can write to") from None


def export(design, out=None, *, dxf=None, step=None, drawing=None, process: str | None = None, kerf=None,
           min_inside_radius=None, min_slot=None, min_web=None, units: str = "mm", analysis=None,
           analyze_design: bool = True, as_cut: bool = False, kerf_error=None, mesh_size=None,
           engine: EngineCurve | None = None, tolerances: dict | None = None) -> ExportResult:
    """Cutting files, manufacturability check and drawing sheet of a concept design.

    Parameters
    ----------
    design : Design
        A concept design (``Design.from_concept``); its whole part (every shoe) is exported.
    out : path, optional
        Folder for every file, named after the design's label (``<label>.dxf``, ``.step``,
        ``_drawing.pdf``) unless named below.
    dxf, step, drawing : path, optional
        Explicit file names (the drawing: ``.pdf``, ``.svg`` or ``.png``).
    process : {"laser", "waterjet", "wire-edm"}, optional
        The cutting process: its rules check the part and give the tool path
        (:class:`ProcessRules`); None with no limit given: nominal contour only, unchecked.
    kerf, min_inside_radius, min_slot, min_web : float or str, optional
        Override the process's values (``"0.3mm"``); given alone: a ``custom`` process.
    units : {"mm", "in"}
        Unit of the DXF and the drawing (the STEP is always in mm, which it declares).
    analysis : Analysis, optional
        The design's answers for the drawing (default: ``analyze`` with error bands, unless
        ``analyze_design`` is False).
    as_cut : bool
        Also analyse the part cut with a kerf error of +-``kerf_error`` (default: the
        process's) and its taper (``mesh_size``: element size of those meshes).
    engine : EngineCurve, optional
        Full-throttle torque curve for the slip speed (default: built-in, ASSUMED shape).
    tolerances : dict, optional
        ``{parameter: half-width}`` in the parameter's SI unit (``--tol``): printed on the
        drawing's dimensions that equal that parameter.

    Returns
    -------
    ExportResult
        The files written, the area, volume and mass, the measured features, the rules and
        the answers.

    Examples
    --------
    >>> import clutchfem as cf, tempfile
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> r = cf.export(d, tempfile.mkdtemp(), process="wire-edm", analyze_design=False)
    >>> sorted(p.suffix for p in r.files)
    ['.dxf', '.json', '.json', '.pdf', '.png', '.step']
    >>> abs(r.outer_radius_m - (0.0344 - 0.0006)) < 1e-9, abs(r.volume_m3 / (r.area_m2 * 0.011) - 1) < 1e-6
    (True, True)
    """
    if not isinstance(design, Design):
        raise ParameterError("design", type(design).__name__, "a clutchfem Design (Design.from_concept)")
    if design.params is None or design.concept is None:
        raise InputError("export needs a concept design (CONCEPT --set ...): a --mesh part has no exact outline "
                         "to cut from (its CAD file already is the cutting geometry)")
    if units not in UNITS:
        raise ParameterError("units", units, "'mm' or 'in'", "export")
    limits = {"kerf": kerf, "min_inside_radius": min_inside_radius, "min_slot": min_slot, "min_web": min_web}
    rules = None
    if process is not None or any(v is not None for v in limits.values()):
        rules = ProcessRules.of(process or "custom", **limits)
    if kerf_error is not None and not as_cut:
        raise ParameterError("kerf_error", kerf_error, "None unless as_cut is True (the as-cut analysis is what "
                             "it is for)", "export")
    if as_cut and kerf_error is not None:
        kerf_error = parse_quantity(kerf_error, "m") if isinstance(kerf_error, str) else float(kerf_error)
        if rules is not None:
            rules.check_kerf_error(kerf_error)
    label = design_label(design)
    f_dxf = _target(dxf, out, f"{label}.dxf", "--dxf", (".dxf",))
    f_step = _target(step, out, f"{label}.step", "--step", (".step", ".stp"))
    f_draw = _target(drawing, out, f"{label}_drawing.pdf", "--drawing", DRAWING_SUFFIXES)
    if f_draw is not None and f_draw.suffix.lower() != ".png":  # (its PNG preview beside it)
        _target(f_draw.with_suffix(".png"), None, "", "--drawing", DRAWING_SUFFIXES)
    p = design.params
    outline = part_outline(design.concept, p)
    features = measure(outline)
    ligament = thinnest_ligament(outline)
    violations = check(features, rules, p.thickness) if rules is not None else []
    if violations:
        raise CuttingError(violations, rules)
    toolpath = offset_loops(outline.loops, 0.5 * rules.kerf) if rules is not None else None
    an = analysis
    if an is None and analyze_design:
        an = analyze(design, engine=engine)
    ascut = None
    if as_cut:
        err = kerf_error if kerf_error is not None else (rules.kerf_error if rules is not None else 0.02e-3)
        ascut = run_as_cut(outline, design, kerf_error=float(err), taper=rules.taper if rules else 0.0,
                           mesh_size=mesh_size, engine=engine)
    h = design_hash(design)
    rho = design.model.material.rho
    mat = design.model.material.name
    text = [f"clutchfem part {label}", f"design hash {h}", f"concept {design.name}", f"material {mat}",
            f"thickness {p.thickness * 1e3:g} mm", f"units {units}", f"clutchfem {__version__}"]
    if rules is not None:
        text.append(f"TOOLPATH: {rules.process} kerf {rules.kerf * 1e3:g} mm compensated (offset "
                    f"{rules.kerf * 500:g} mm into the waste)")
    files: list[Path] = []
    volume = None
    for target in (f_dxf, f_step, f_draw):
        if target is not None:
            target.parent.mkdir(parents=True, exist_ok=True)
    if f_dxf is not None:
        files.append(write_dxf(f_dxf, outline.loops, units=units, toolpath=toolpath, text=text))
    if f_step is not None:
        path, volume = write_step(f_step, list(outline.loops), p.thickness, label=label,
                                  description=[f"clutchfem part {label}", f"design hash {h}",
                                               f"material {mat}", f"thickness {p.thickness * 1e3:g} mm",
                                               "length unit mm"])
        files.append(path)
    area = outline.area
    result = ExportResult(label, h, files, area, p.thickness, volume, area * p.thickness * rho,
                          outline.max_radius(), features, rules, violations, an, ascut, units, outline, toolpath,
                          ligament)
    if f_draw is not None:
        paths = [f_draw] + ([f_draw.with_suffix(".png")] if f_draw.suffix.lower() != ".png" else [])
        files += draw_sheet(paths, outline=outline, features=features, rules=rules, toolpath=toolpath, label=label,
                            design_hash=h, material=mat, analysis=an, as_cut=ascut, units=units,
                            mass_kg=result.mass_kg, tolerances=tolerances, fidelity=_fidelity(design, an),
                            ligament=ligament)
    folders = sorted({f.parent for f in files})
    record = {**design_inputs(design), "design_hash": h, "label": label}
    for folder in folders:
        names = [f.name for f in files if f.parent == folder]
        doc = {**result.to_json(), "files": names}
        files.append(write(folder / "export.json", doc, indent=1))
        files.append(write(folder / "inputs.json", {**record, "export": {"files": names, "units": units}}, indent=1))
    result.files = files
    return result



def _fidelity(design, an) -> str:
    """The model the drawing's answers came from, in words (issue 37: never a fixed "FE,
    plane stress")."""
    if an is None:
        return ""
    op = design.op
    wall = op.drum_wall_m
    by = getattr(an, "answered_by", "FE")
    return (f"{by}, fidelity {op.fidelity}: {op.model_formulation} model, "
            + ("rigid drum" if wall is None else f"elastic drum {wall * 1e3:g} mm wall") + "; ± error band")
