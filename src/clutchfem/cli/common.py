"""The command line's plumbing: consoles, the error exit, output folders and the list of files
written, and the design, operating point, material, engine and requirements read from the
options (one parser for every quantity, refusals naming the option the user typed).

The API is imported on first use (inside the functions): ``clutchfem --help`` and a refused
option then answer in a fraction of a second instead of loading the FE stack (~3 s)."""

from __future__ import annotations

import contextlib
import math
import os
import sys
import time
from pathlib import Path
from typing import Optional

import typer
from rich import box
from rich.console import Console
from rich.markup import escape
from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn  # 0.04 s
from rich.table import Table
from rich.text import Text

from .. import InputError, ParameterError, UnitError, parse_quantity
from . import clear_early


def fitted(table: Table, width: int) -> list:
    """What prints ``table`` within ``width`` columns without cutting a number (issue 37):
    every cell wraps at its spaces and folds a word longer than its column (a path) instead of
    ending it with an ellipsis; a table whose narrowest layout (each column as wide as its
    longest word) is still wider than ``width`` is drawn compact (no vertical rules, one
    space between columns), and if that is still too wide, transposed: one small two-column
    table per row (its first cell the title; each other column's head beside its value),
    then its caption.  Returns the renderables to print, in order.

    Examples
    --------
    >>> from rich.table import Table
    >>> t = Table(title="t")
    >>> for c in ("a", "b"):
    ...     t.add_column(c)
    >>> t.add_row("x", "+1.25")
    >>> len(fitted(t, 80)), len(fitted(t, 5))
    (1, 1)
    """
    for col in table.columns:
        col.overflow = "fold"
        col.no_wrap = False
    probe = Console(width=max(width, 1) * 4, file=open(os.devnull, "w"))  # noqa: SIM115 (closed below)

    def whole_words() -> list:  # a column of single words (names, numbers) as wide as its longest: never folded
        for col in table.columns:
            words = [probe.measure(x) for x in col.cells if x is not None]
            if words and all(m.minimum == m.maximum for m in words):
                col.width = max([m.minimum for m in words] + [probe.measure(col.header).minimum])
        return [table]

    try:
        if probe.measure(table).minimum <= width:
            return whole_words()
        if len(table.columns) <= 2:
            return [table]
        # compact: no vertical rules, one space between the columns
        table.box, table.padding, table.show_edge = box.SIMPLE_HEAD, (0, 0), False
        if probe.measure(table).minimum <= width:
            return whole_words()
    finally:
        probe.file.close()
    cols = table.columns
    cells = [list(c.cells) for c in cols]
    out: list = [table.title] if table.title else []
    for r in range(table.row_count):
        t = Table(title=Text.assemble(str(cols[0].header), ": ", cells[0][r]) if str(cols[0].header)
                  else cells[0][r], show_header=False, title_justify="left")
        t.add_column("", overflow="fold", style="dim")
        t.add_column("", overflow="fold", justify="right")
        for c in range(1, len(cols)):
            t.add_row(cols[c].header, cells[c][r])
        out.append(t)
    if table.caption:
        out.append(table.caption)
    return out


class FitConsole(Console):
    """A rich ``Console`` whose tables fit its width (:func:`fitted`): an 80-column
    terminal shows every number whole."""

    def print(self, *objects, **kw):  # noqa: D102 (Console.print)
        clear_early()
        if len(objects) == 1 and isinstance(objects[0], Table):
            for r in fitted(objects[0], self.width):
                super().print(r, **kw)
            return
        super().print(*objects, **kw)


# Written to a file or a pipe, a message is one line however long (a script reads whole
# lines: a refusal or a WARNING wrapped at 80 columns lost its end); tables fit the width
# (80 columns on a pipe) without cutting a number.
console = FitConsole(soft_wrap=not sys.stdout.isatty())
err = FitConsole(stderr=True, soft_wrap=not sys.stderr.isatty())


@contextlib.contextmanager
def working(what: str):
    """Progress of a step that runs for seconds (meshing, solving, a report): a spinner with
    ``what``, the current stage and the elapsed time on standard error, cleared when the step
    ends.  Only on a terminal: a pipe or a file gets nothing, and standard output (--json) is
    never touched.  Yields ``stage(text)``, which names the current stage.

    Why a spinner and not a bar: one design's steps have no count to show (a study's points
    do: their bar, with rate and ETA, is the study engine's)."""
    if not err.is_terminal:
        yield lambda text: None
        return
    clear_early()  # the spinner replaces the start-up line
    bar = Progress(SpinnerColumn(), TextColumn("{task.description}"), TimeElapsedColumn(), console=err,
                   transient=True, redirect_stdout=False, redirect_stderr=False)
    with bar:
        task = bar.add_task(escape(what))
        # refresh at once: a stage shorter than the refresh tick is still shown (and seen by tests)
        yield lambda text: bar.update(task, description=escape(f"{what}: {text}"), refresh=True)

__all__ = ["names_from", "ranges_from", "working", "check_cluster", "check_out_dir", "console", "design_from", "engine_from", "err", "fail", "material_from",
           "operating_point", "quantity", "requirements_from", "build_geometry", "geometry_table", "print_settings", "study_settings", "wrote"]


def fail(exc: Exception) -> None:
    """Print a refusal (never a traceback) and exit with code 2."""
    err.print(f"[bold red]error:[/] {escape(str(exc))}", soft_wrap=True)
    raise typer.Exit(code=2)


def wrote(paths) -> None:
    """List the files a command wrote (on stderr: stdout stays one JSON document)."""
    for p in paths:
        err.print(f"wrote {escape(str(p))}", soft_wrap=True)


def check_out_dir(out: Optional[Path], option: str = "--out") -> Optional[Path]:
    """Refuse an output folder that cannot be written *before* any work: a file, a folder
    inside a file, or a folder without write permission (created if missing)."""
    if out is None:
        return None
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(f"{option} {out}: is a file, not a folder")
    parent = out
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise InputError(f"{option} {out}: {parent} is a file, so no folder can be made inside it")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option} {out}: no permission to write in {parent}")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"{option} {out}: cannot create the folder ({exc.strerror})") from None
    return out


def check_cluster(workers: Optional[int], scheduler: Optional[str]) -> Optional[str]:
    """Refuse, before any work, ``--workers`` with ``--scheduler``, a negative worker count
    and a scheduler address that is not one (``''``, ``http://...``, an unknown host); the
    address in Dask's form, or None."""
    if workers is not None and scheduler is not None:
        raise InputError("give --workers N (a local cluster) or --scheduler ADDRESS (an existing one), not both")
    if workers is not None and workers < 0:
        raise ParameterError("workers", workers, "an integer >= 0 (0: in this process, no Dask)", "option --workers")
    if scheduler is None:
        return None
    from .. import check_scheduler

    return check_scheduler(scheduler)


def quantity(option: str, raw: Optional[str], unit: str, lo: float | None = None, hi: float | None = None,
             *, above: float | None = None):
    """The value of a quantity option (``--idle-rpm 2700rpm``) in its SI/canonical ``unit``,
    or None; refusals name the option, the value and what it accepts."""
    if raw is None:
        return None
    name = option.lstrip("-").replace("-", "_")
    try:
        v = parse_quantity(raw, unit)
    except UnitError as exc:
        raise ParameterError(name, raw, exc.expected, f"option {option}") from None
    rng = None
    if lo is not None and hi is not None:
        rng = f"in [{lo:g}, {hi:g}]"
    elif above is not None:
        rng = f"> {above:g}"
    if not (v == v and abs(v) != float("inf")) or (lo is not None and v < lo) or (hi is not None and v > hi) \
            or (above is not None and v <= above):
        u = "" if unit in ("-", "") else f" {unit}"
        raise ParameterError(name, raw, f"a finite value {rng or ''}{u}".replace("  ", " "), f"option {option}")
    return v


def operating_point(base=None, **given):
    """An :class:`~clutchfem.OperatingPoint` from option strings (None: not given), each read
    with its unit and checked against its range; ``base``: the point to change."""
    from .. import OperatingPoint

    base = base if base is not None else OperatingPoint()
    if isinstance(given.get("drum_wall"), str) and given["drum_wall"].strip().lower() == "rigid":
        given = {**given, "drum_wall": "0"}  # --drum-wall rigid: the rigid drum (a wall of 0)
    try:
        values = OperatingPoint.parse_assignments([f"{k}={v}" for k, v in given.items()
                                                   if v is not None and k != "material"])
        if given.get("material") is not None:
            values["material"] = given["material"]
        return base.replace(**values) if values else base
    except ParameterError as exc:  # name the option the user typed
        opt = {"softening": "--spin-softening"}.get(exc.name, "--" + str(exc.name).replace("_", "-"))
        raise ParameterError(exc.name, exc.value, exc.allowed, f"option {opt}", shown=exc.shown) from None


def material_from(name: Optional[str], E: Optional[str] = None, nu: Optional[str] = None,
                  rho: Optional[str] = None):
    """The material of ``--material`` with ``--E``/``--nu``/``--rho`` overrides (units read)."""
    from .. import Material, get_material

    base = get_material(name or "51CrV4")
    if E is None and nu is None and rho is None:
        return base
    changes = {}
    for opt, field, raw in (("--E", "E", E), ("--nu", "nu", nu), ("--rho", "rho", rho)):
        if raw is not None:
            try:
                changes[field] = Material.parse_value(field, raw)
            except ParameterError as exc:
                raise ParameterError(exc.name, exc.value, exc.allowed, f"option {opt}") from None
    try:
        return Material(**{**base.model_dump(), **changes, "name": f"{base.name} (user)"})
    except ParameterError as exc:
        raise ParameterError(exc.name, exc.value, exc.allowed, f"option --{exc.name}", shown=exc.shown) from None


def engine_from(path: Optional[Path], idle_rpm: Optional[str] = None):
    """(engine curve, idle speed [rpm] or None): ``--engine`` (default: the built-in curve)
    and ``--idle-rpm`` (read with its unit; it must lie below the curve's top speed)."""
    from .. import EngineCurve

    idle = quantity("--idle-rpm", idle_rpm, "rpm", above=0.0)
    eng = EngineCurve.from_csv(path) if path is not None else EngineCurve.default()
    lo, hi = eng.rpm_range
    if idle is not None and idle >= hi:
        raise ParameterError("idle_rpm", idle_rpm, f"an idle speed below the engine curve's top speed {hi:g} rpm",
                             "option --idle-rpm")
    return eng, idle


def requirements_from(a: Optional[str], b: Optional[str]):
    """The requirement factors of ``--a``/``--b`` (defaults 1.3 and 1.0, ASSUMED)."""
    from .. import Requirements

    kw = {k: quantity(f"--{k}", v, "-") for k, v in (("a", a), ("b", b)) if v is not None}
    return Requirements(**kw)


#: the operating point's fields a user may try in ``--set`` and the option that sets each
OPERATING_OPTIONS = {"mu": "--mu", "rotation": "--rotation", "material": "--material", "softening": "--spin-softening",
                     "fidelity": "--fidelity", "formulation": "--formulation", "layers": "--layers",
                     "drum_wall": "--drum-wall", "drum_state": "--drum-state", "rpm": "--rpm"}


def operating_in_set(set_: list[str], params) -> None:
    """Refuse an operating-point quantity given to ``--set`` (which sets the concept's geometry),
    naming the option that sets it (``--set formulation=3d``: use ``--formulation 3d``)."""
    for item in set_:
        name, _, raw = (s.strip() for s in item.partition("="))
        if name in OPERATING_OPTIONS and name not in params:
            raise ParameterError(name, raw, f"not a geometry parameter: {name} is part of the operating point, set "
                                 f"by its own option: {OPERATING_OPTIONS[name]} {raw}", "option --set")


def design_from(concept: Optional[str], set_: list[str], mesh: Optional[Path], *, op=None,
                mesh_size: Optional[str] = None, model: str = "sector", drum_radius: Optional[str] = None,
                thickness: Optional[str] = None, solver=None, mesh_allowed: bool = True):
    """The design of the options: ``CONCEPT [--set ...]`` or ``--mesh FILE``.  A concept's
    drum radius and thickness are geometry parameters (``--set drum_radius=...``);
    ``--drum-radius``/``--thickness`` are a mesh part's operating point."""
    from .. import Design, MeshSettings, OperatingPoint, get_concept

    if concept is not None and mesh is not None:
        raise InputError("give exactly one of CONCEPT or --mesh FILE, not both")
    if concept is None and mesh is None:
        raise InputError("give exactly one of CONCEPT (clutchfem geometry --list shows them)"
                         + (" or --mesh FILE (your own part)" if mesh_allowed else ""))
    if mesh is not None and not mesh_allowed:
        raise InputError("--mesh: this command varies a concept's parameters; a user mesh has none (give a CONCEPT)")
    op = op if op is not None else OperatingPoint()
    if model not in ("sector", "full"):
        raise ParameterError("model", model, "'sector' or 'full'", "option --model")
    size = None
    if mesh_size is not None:
        try:
            size = MeshSettings.parse_value("size", mesh_size)
            MeshSettings(size=size)
        except ParameterError as exc:
            raise ParameterError(exc.name, exc.value, exc.allowed, "option --mesh-size", shown=exc.shown) from None
    if concept is not None:
        c = get_concept(concept)
        operating_in_set(set_, c.Params.model_fields)
        values = c.Params.parse_assignments(set_)
        for opt, name, raw in (("--drum-radius", "drum_radius", drum_radius), ("--thickness", "thickness", thickness)):
            if raw is not None:
                raise InputError(f"{opt} applies to a --mesh part: a concept's {name.replace('_', ' ')} is one of its "
                                 f"geometry parameters (the part is built against it): use --set {name}=...")
        ms = MeshSettings.preset(op.fidelity, model=model, **({} if size is None else {"size": size}))
        return Design.from_concept(c, c.Params(**values), op, ms, solver=solver)
    if set_:
        raise InputError("--set sets a concept's parameters; a --mesh part has none (use --drum-radius, "
                         "--thickness and the operating-point options)")
    op = operating_point(op, drum_radius=drum_radius, thickness=thickness)
    return Design.from_mesh(mesh, operating=op, mesh_size=size, solver=solver)


def grouped_assignments(items, groups: dict, option: str) -> dict:
    """``name=value`` strings (``option``, e.g. ``--thermal``) spread over several parameter
    sets: ``groups`` maps a prefix to a :class:`~clutchfem.core.ParamSet` class.  A name
    may be written plain when exactly one set has it (``face_htc=80``) and must carry its
    prefix when several do (``drum.conductivity=16``); units as in ``--set``.  Returns
    {prefix: {name: value}}; unknown, ambiguous or repeated names are refused, naming the
    option and every known name."""
    owners: dict[str, list[str]] = {}
    for prefix, cls in groups.items():
        for name in cls.model_fields:
            owners.setdefault(name, []).append(prefix)
    known = ", ".join(sorted(f"{p}.{n}" if len(owners[n]) > 1 else n
                             for p, c in groups.items() for n in c.model_fields))
    raw: dict[str, list[str]] = {p: [] for p in groups}
    for item in items:
        if "=" not in item:
            raise ParameterError(item, None, "expected the form name=value", f"option {option}")
        name, value = (s.strip() for s in item.split("=", 1))
        prefix, _, bare = name.rpartition(".")
        if prefix:
            if prefix not in groups or bare not in groups[prefix].model_fields:
                raise ParameterError(name, value, f"unknown parameter; known: {known}", f"option {option}")
        else:
            where = owners.get(bare)
            if not where:
                raise ParameterError(name, value, f"unknown parameter; known: {known}", f"option {option}")
            if len(where) > 1:
                raise ParameterError(name, value, "ambiguous: write " + " or ".join(f"{p}.{bare}" for p in where),
                                     f"option {option}")
            prefix = where[0]
        raw[prefix].append(f"{bare}={value}")
    out = {}
    for prefix, cls in groups.items():
        try:
            out[prefix] = cls.parse_assignments(raw[prefix])
        except ParameterError as exc:
            raise ParameterError(exc.name, exc.value, exc.allowed, f"option {option} ({cls.context})") from None
    return out


def build_params(cls, values: dict, option: str):
    """``cls(**values)``, its errors naming the option the user typed."""
    try:
        return cls(**values)
    except ParameterError as exc:
        raise ParameterError(exc.name, exc.value, exc.allowed, f"option {option} ({cls.context})",
                             shown=exc.shown) from None


def describe_groups(groups: dict) -> list[tuple[str, str, str, str]]:
    """(name as typed, unit, default in its display unit, allowed and meaning) of every
    parameter of ``groups``."""
    from .. import format_quantity

    owners: dict[str, int] = {}
    for cls in groups.values():
        for n in cls.model_fields:
            owners[n] = owners.get(n, 0) + 1
    rows = []
    for prefix, cls in groups.items():
        for r in cls.describe():
            name = f"{prefix}.{r['name']}" if owners[r["name"]] > 1 else r["name"]
            rows.append((name, r["unit"], format_quantity(r["default"], r["unit"]), f"{r['allowed']}: "
                         f"{r['description']}"))
    return rows


def print_settings(groups, option: str) -> None:
    """The table of a grouped option's settings (``--list-fatigue``, ``--list-thermal``)."""
    t = Table(title=f"{option} settings (name=value with its unit; ASSUMED defaults, sources in the docs)")
    for col in ("name", "unit", "default", "allowed: meaning"):
        t.add_column(col)
    for row in describe_groups(groups):
        t.add_row(*(escape(x) for x in row))
    console.print(t)


def names_from(text: Optional[str]) -> Optional[list[str]]:
    """A comma-separated list of names (``--free a,b``), or None when not given."""
    return [x.strip() for x in text.split(",") if x.strip()] if text else None


def ranges_from(P, items) -> dict:
    """``--range name=LO:HI`` items as ``name -> (lo, hi)`` in SI (each bound with its unit),
    refusing a malformed item or a name the parameter set ``P`` does not have."""
    ranges = {}
    for item in items:
        name, _, r = item.partition("=")
        if ":" not in r:
            raise ParameterError("range", item, "name=LO:HI (e.g. flexure_thickness=1.6mm:2.0mm)", "option --range")
        name = name.strip()
        if name not in P.model_fields:
            raise ParameterError(name, item, "a parameter of the concept; known: " + ", ".join(P.model_fields),
                                 "option --range")
        lo, hi = r.split(":", 1)
        ranges[name] = (P.parse_value(name, lo), P.parse_value(name, hi))
    return ranges


def tolerances_from(P, items) -> dict:
    """``--tol name=+-value`` items -> {name: half-width in SI} for parameter class ``P``
    (each dimension once)."""
    from .. import parse_tolerance

    tols: dict = {}
    for item in items:
        name, half = parse_tolerance(P, item)
        if name in tols:
            raise ParameterError(name, item, "one tolerance per dimension (given twice)", "option --tol")
        tols[name] = half
    return tols


def study_settings(concept, set_, mesh_size, mu, engine, idle_rpm, a, b, out, sf: float = 1.5, fidelity=None):
    """(EvalSettings, base Design) of a design-to-targets command: the base design (meshed, so
    a bad --set is refused before any study work) with its engine, idle speed, requirement
    factors and the store in ``out``."""
    from .. import EvalSettings

    req = requirements_from(a, b)
    eng, idle = engine_from(engine, idle_rpm)
    design = design_from(concept, set_, None, op=operating_point(mu=mu, fidelity=fidelity), mesh_size=mesh_size,
                         mesh_allowed=False)
    s = EvalSettings.from_design(design, engine=engine if engine is not None else None, idle_rpm=idle,
                                 requirements=req, min_safety_factor=sf, out=out)
    return s, design


def build_geometry(c, set_, out: Path, mesh_size, model: str, drawing: bool) -> dict:
    """Mesh one concept (its ``--set`` texts) and write its files into ``out``, named after the
    design's label; returns a summary row with the files."""
    from .. import draw_concept, dumps

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    with working(f"geometry {c.name}") as stage:
        stage("building and meshing")
        design = design_from(c.name, list(set_), None, mesh_size=mesh_size, model=model)
    wall = time.perf_counter() - t0
    cm, p = design.cm, design.params
    label = design.label
    msh = cm.write_msh(out / f"{label}.msh")  # not with_suffix: 'concept3.1' would lose its '.1'
    files = [msh]
    if drawing:
        files += draw_concept(c, p, out / label, cm)
    rho, h = design.op.material.rho, p.thickness
    shoe = cm.mass.get("shoe_0", {})
    info = {"concept": c.name, "label": label, "elements": cm.n_elements, "nodes": cm.n_nodes,
            "material": design.op.material.name, "density_kg_m3": rho,
            "shoe_mass_kg": shoe.get("area", math.nan) * rho * h, "R_Tp_m": shoe.get("radius", math.nan),
            "part_mass_kg": cm.mass["solid"]["area"] * rho * h * (cm.n_shoes_total if cm.sector_angle else 1),
            "mesh_time_s": cm.mesh_time_s, "cached": cm.cached, "wall_time_s": wall}
    summary = out / f"{label}.json"
    files.append(summary)
    info["files"] = [str(f) for f in files]
    summary.write_text(dumps({**info, "params": p.model_dump(), "mass": cm.mass}, indent=2))
    return info


def geometry_table(rows: list[dict]) -> None:
    """The summary table of built concepts (an error row says why a concept failed)."""
    t = Table(title="concept geometries (51CrV4 steel, rho = 7850 kg/m^3)")
    for col in ("concept", "elements", "nodes", "shoe mass [g]", "R_Tp [mm]", "part mass [g]", "mesh time [s]"):
        # escaped: rich would eat '[g]' as markup; names never wrap ('concept3.1')
        t.add_column(escape(col), justify="right", no_wrap=col == "concept", min_width=10 if col == "concept" else None)
    for r in rows:
        if "error" in r:
            t.add_row(r["concept"], "-", "-", "-", "-", "-", f"[red]{escape(r['error'][:60])}[/]")
            continue
        t.add_row(r["concept"], str(r["elements"]), str(r["nodes"]), f"{r['shoe_mass_kg'] * 1e3:.2f}",
                  f"{r['R_Tp_m'] * 1e3:.2f}", f"{r['part_mass_kg'] * 1e3:.1f}",
                  f"{r['mesh_time_s']:.2f}" + ("*" if r.get("cached") else ""))
    if any(r.get("cached") for r in rows):
        t.caption = "* mesh read from the cache; the time is that of its original meshing"
    console.print(t)
