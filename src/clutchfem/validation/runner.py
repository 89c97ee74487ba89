"""Run every validation module, write the figures and a Markdown report, show a table.

Validation modules are discovered as concepts are: every module of the
``clutchfem.validation`` package (every ``*.py`` on the package's ``__path__``) that
defines a callable ``records() -> list[ValidationRecord]`` is run; dropping a file into
``src/clutchfem/validation/`` adds it to ``clutchfem validate`` and the report, with no
list to edit.  A module's optional attributes:

* ``SOURCE``: one line naming the source paper, the heading of the module's report section
  (a module without it is run, headed by its name, and a warning asks for it);
* ``ORDER``: a number, the module's place in the report and the table (ascending); modules
  without one follow, at :data:`DEFAULT_ORDER`; ties are broken by module name, so the
  order is stable;
* ``figures(out_dir) -> list[Path]`` and ``report_notes(records) -> str`` (Markdown).

Modules whose name starts with ``_`` are private helpers and are not discovered (as for
concepts); nor is a module without ``records`` (``records.py``, this runner).  A module
that fails to import is reported as a warning, since it may well be a validation module
(``strict=True`` re-raises instead), so a single broken module never hides the others.
Explicit module names (``collect(("chain",))``) are imported lazily the same way: one that
is not there yet is skipped with a recorded warning.

Usage::

    from clutchfem.validation.runner import run_all, write_report, print_table
    print_table(run_all())
    write_report(Path("out/validation"), Path("docs/validation.md"))

or ``python -m clutchfem.validation.runner OUT_DIR DOCS_MD``.
"""

from __future__ import annotations

import importlib
import json
import math
import numbers
import os
import pkgutil
import sys
import time
import warnings
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType

from rich import box
from rich.console import Console, Group
from rich.table import Table
from rich.text import Text

from ..core import InputError
from .records import ValidationRecord

PACKAGE = "clutchfem.validation"
#: report position of a module that sets no ``ORDER`` (after those that do)
DEFAULT_ORDER = 1000


class ValidationModuleWarning(UserWarning):
    """A validation module was skipped or failed; the run goes on without it."""


@dataclass
class ValidationRun:
    """What :func:`validate` reproduced: every record, the warnings, the seconds per module.

    Attributes
    ----------
    records : list of ValidationRecord
        One per paper number: its value, the reproduced one, the tolerance, the status and
        the reason of a difference.
    warnings : list of str
        Modules skipped or failed (never silent).
    seconds : dict
        Module name -> seconds.

    Examples
    --------
    >>> from clutchfem.validation import ValidationRun
    >>> ValidationRun().to_json()
    {'records': [], 'warnings': [], 'seconds': {}}
    """

    records: list[ValidationRecord] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    seconds: dict[str, float] = field(default_factory=dict)
    modules: dict[str, ModuleType] = field(default_factory=dict)

    def to_json(self) -> dict:
        """The records, warnings and seconds as a JSON-ready dict."""
        return {"records": [r.to_json() for r in self.records], "warnings": list(self.warnings),
                "seconds": dict(self.seconds)}

    def table(self):
        """The records as rich tables, one per module (:func:`render_table`)."""
        return render_table(self.records)


def load_module(name: str, *, strict: bool = False) -> tuple[ModuleType | None, str | None]:
    """Import ``clutchfem.validation.<name>``; (module, None) or (None, warning text)."""
    full = f"clutchfem.validation.{name}"
    try:
        return importlib.import_module(full), None
    except ModuleNotFoundError as exc:
        if strict or not (exc.name or "").startswith("clutchfem"):
            raise
        what = "not available yet" if exc.name == full else f"needs missing {exc.name}"
        return None, f"module '{name}' skipped: {what}"
    except Exception as exc:  # noqa: BLE001 - reported, not swallowed silently
        if strict:
            raise
        return None, f"module '{name}' failed to import: {type(exc).__name__}: {exc}"


def module_order(mod: ModuleType) -> float:
    """A module's ``ORDER`` (a real number), else :data:`DEFAULT_ORDER`."""
    order = getattr(mod, "ORDER", DEFAULT_ORDER)
    ok = isinstance(order, numbers.Real) and not isinstance(order, bool) and math.isfinite(order)
    return float(order) if ok else float(DEFAULT_ORDER)


def discover(*, strict: bool = False) -> tuple[list[str], list[str]]:
    """(names of the validation modules in report order, warnings): see the module
    docstring for the rules.  Every public module of the package is imported."""
    pkg = importlib.import_module(PACKAGE)
    found: list[tuple[float, str]] = []
    notes: list[str] = []
    seen: set[str] = set()
    for info in pkgutil.iter_modules(pkg.__path__):
        name = info.name
        if name.startswith("_") or name in seen:  # private helper; first path entry wins
            continue
        seen.add(name)
        mod, warn = load_module(name, strict=strict)
        if mod is None:
            notes.append(warn or f"module '{name}' skipped")
            continue
        if not callable(getattr(mod, "records", None)):
            continue  # a helper of the package, not a validation module
        order = getattr(mod, "ORDER", DEFAULT_ORDER)
        if module_order(mod) != order:
            notes.append(f"module '{name}': ORDER = {order!r} is not a finite number; "
                         f"placed at {DEFAULT_ORDER}")
        if not isinstance(getattr(mod, "SOURCE", None), str):
            notes.append(f"module '{name}' has no SOURCE string (its report heading): "
                         "add SOURCE = \"seed ...: the paper\"")
        found.append((module_order(mod), name))
    return [n for _, n in sorted(found)], notes


def module_names(*, strict: bool = False) -> tuple[str, ...]:
    """Names of the discovered validation modules, in report order (:func:`discover`)."""
    return tuple(discover(strict=strict)[0])


def source_of(name: str, module: ModuleType | None = None) -> str:
    """The report heading of module ``name``: its ``SOURCE``, else its name."""
    mod = module if module is not None else sys.modules.get(f"{PACKAGE}.{name}")
    src = getattr(mod, "SOURCE", None)
    return src if isinstance(src, str) else name


def collect(modules: Sequence[str] | None = None, *, strict: bool = False) -> ValidationRun:
    """Import each module (default: every discovered one, :func:`discover`) and call its
    ``records()``; problems become warnings."""
    run = ValidationRun()
    if modules is None:
        modules, run.warnings = discover(strict=strict)
    for name in modules:
        t0 = time.perf_counter()
        mod, warn = load_module(name, strict=strict)
        if mod is None:
            run.warnings.append(warn or f"module '{name}' skipped")
            continue
        try:
            recs = list(mod.records())
        except Exception as exc:  # noqa: BLE001
            if strict:
                raise
            run.warnings.append(f"module '{name}' records() failed: {type(exc).__name__}: {exc}")
            continue
        bad = [r for r in recs if not isinstance(r, ValidationRecord)]
        if bad:
            run.warnings.append(f"module '{name}' returned {len(bad)} non-ValidationRecord items "
                                "(ignored)")
        recs = [r for r in recs if isinstance(r, ValidationRecord)]
        for r in recs:
            if r.status == "differs" and not r.note.strip():
                run.warnings.append(f"record '{r.id}' differs without an explanation")
        run.records += recs
        run.modules[name] = mod
        run.seconds[name] = time.perf_counter() - t0
    dup = [i for i, n in Counter(r.id for r in run.records).items() if n > 1]
    if dup:
        run.warnings.append(f"duplicate record ids: {', '.join(sorted(dup))}")
    return run


def run_all(modules: Sequence[str] | None = None, *, strict: bool = False
            ) -> list[ValidationRecord]:
    """All records of all available modules; skipped modules raise a
    :class:`ValidationModuleWarning` (see :func:`collect` for the details)."""
    run = collect(modules, strict=strict)
    for w in run.warnings:
        warnings.warn(w, ValidationModuleWarning, stacklevel=2)
    return run.records


# --------------------------------------------------------------------------------------
# Formatting
# --------------------------------------------------------------------------------------


def fmt_value(x: float | None) -> str:
    """Compact number: 5 significant digits, '-' for None."""
    if x is None:
        return "-"
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return f"{x:.5g}"


def fmt_rel(r: ValidationRecord) -> str:
    """Relative difference in percent, '-' without a paper value."""
    return "-" if math.isnan(r.rel_diff) else f"{100 * r.rel_diff:+.2f} %"


def _md(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _status_counts(recs: Sequence[ValidationRecord]) -> Counter:
    return Counter(r.status for r in recs)


def render_markdown(run: ValidationRun, figures: dict[str, list[Path]], docs_md: Path) -> str:
    """The report text; figure links are relative to ``docs_md``'s folder."""
    lines = ["# Validation report", "",
             "Generated by `clutchfem.validation.runner`. One row per number of a source paper "
             "(`reproduced` within `tol`, `differs` with a reason, `computed` = no paper value). "
             "`tol` follows from the precision the paper prints (half a unit of its last digit, "
             "or the range its rounded inputs allow, computed in code: see each module), never "
             "tuned. Regenerate with `clutchfem validate --docs docs/validation.md --out "
             "docs/img/validation`.", ""]
    lines += ["| module | records | reproduced | differs | computed | seconds |",
              "| --- | ---: | ---: | ---: | ---: | ---: |"]
    names = list(dict.fromkeys(r.module for r in run.records))
    for name in names:
        c = _status_counts([r for r in run.records if r.module == name])
        secs = run.seconds.get(name, float("nan"))
        lines.append(f"| {name} | {sum(c.values())} | {c['reproduced']} | {c['differs']} | "
                     f"{c['computed']} | {secs:.1f} |")
    c = _status_counts(run.records)
    lines += [f"| **all** | {len(run.records)} | {c['reproduced']} | {c['differs']} | "
              f"{c['computed']} | {sum(run.seconds.values()):.1f} |", ""]
    if run.warnings:
        lines += ["## Warnings", ""] + [f"- {_md(w)}" for w in run.warnings] + [""]
    base = docs_md.parent
    for name in names:
        recs = [r for r in run.records if r.module == name]
        lines += [f"## {name}", "", f"Source: {source_of(name, run.modules.get(name))}.", ""]
        extra = getattr(run.modules.get(name), "report_notes", None)
        if callable(extra):  # optional module hook: Markdown paragraphs on its method
            lines += [extra(recs).strip(), ""]
        lines += [
                  "| module | quantity | paper | computed | unit | rel. diff | tol | status "
                  "| note |",
                  "| --- | --- | ---: | ---: | --- | ---: | ---: | --- | --- |"]
        for r in recs:
            status = f"**{r.status}**" if r.status == "differs" else r.status
            tol = "-" if r.paper is None else f"{100 * r.tol:.2g} %"
            lines.append(f"| {r.module} | {_md(r.quantity)} (`{r.id}`) | {fmt_value(r.paper)} | "
                         f"{fmt_value(r.computed)} | {_md(r.unit)} | {fmt_rel(r)} | {tol} | "
                         f"{status} | {_md(r.note)} |")
        differs = [r for r in recs if r.status == "differs"]
        if differs:
            lines += ["", "### Differences explained", ""]
            for r in differs:
                reason = r.note.strip() or "NO EXPLANATION GIVEN (reviewer attention)"
                lines.append(f"- `{r.id}`: paper {fmt_value(r.paper)}, computed "
                             f"{fmt_value(r.computed)} {_md(r.unit)} ({fmt_rel(r)}). "
                             f"{_md(reason)}.")
        figs = figures.get(name, [])
        if figs:
            lines += ["", "### Figures", ""]
            for p in figs:
                rel = Path(os.path.relpath(Path(p).resolve(), base.resolve())).as_posix()
                lines += [f"![{name}: {Path(p).stem}]({rel})", ""]
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"


def write_report(out_dir: Path, docs_md: Path, modules: Sequence[str] | None = None, *,
                 strict: bool = False) -> Path:
    """Run everything (:func:`collect`) and :func:`report_run` it; returns ``docs_md``."""
    run = collect(modules, strict=strict)
    report_run(run, out_dir, docs_md, strict=strict)
    for w in run.warnings:
        warnings.warn(w, ValidationModuleWarning, stacklevel=2)
    return docs_md


def report_run(run: ValidationRun, out_dir: Path, docs_md: Path, *, strict: bool = False
               ) -> Path:
    """Write the figures of ``run``'s modules under ``out_dir/figures/<module>/``, its
    records as ``out_dir/validation.json`` and the Markdown report at ``docs_md`` (no module
    is run again: ``clutchfem validate --docs`` collects once and reports that run).
    Figure failures are appended to ``run.warnings``; returns ``docs_md``."""
    out_dir, docs_md = Path(out_dir), Path(docs_md)
    figs: dict[str, list[Path]] = {}
    for name, mod in run.modules.items():
        fdir = out_dir / "figures" / name
        t0 = time.perf_counter()
        try:
            got = mod.figures(fdir)
            paths = [Path(p) for p in got] if got else []
        except Exception as exc:  # noqa: BLE001
            if strict:
                raise
            run.warnings.append(f"module '{name}' figures() failed: {type(exc).__name__}: {exc}")
            paths = []
        if not paths and fdir.is_dir():
            paths = sorted(p for p in fdir.iterdir() if p.suffix in (".png", ".svg"))
        figs[name] = paths
        run.seconds[name] = run.seconds.get(name, 0.0) + time.perf_counter() - t0
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "validation.json").write_text(json.dumps(
        {"records": [r.to_json() for r in run.records], "warnings": run.warnings,
         "seconds": run.seconds}, indent=1))
    docs_md.parent.mkdir(parents=True, exist_ok=True)
    docs_md.write_text(render_markdown(run, figs, docs_md))
    return docs_md


def render_table(records: Sequence[ValidationRecord], *, title: str = "clutchfem validation"):
    """The records as one compact :class:`rich.table.Table` per module, each followed by the
    reasons of its ``differs`` rows (wrapped), so that it reads in an 80-column terminal;
    a :class:`rich.console.Group`.  Status is coloured; the id column folds when narrow."""
    colour = {"reproduced": "green", "differs": "bold red", "computed": "cyan"}
    parts: list = [Text(title, style="bold")]
    for name in dict.fromkeys(r.module for r in records):
        recs = [r for r in records if r.module == name]
        c = _status_counts(recs)
        table = Table(title=f"{name}: {source_of(name)}", title_justify="left",
                      box=box.SIMPLE_HEAD, padding=(0, 1), pad_edge=False, expand=False,
                      caption=(f"{name}: {len(recs)} records, {c['reproduced']} reproduced, "
                               f"{c['differs']} differs, {c['computed']} computed"),
                      caption_justify="left")
        table.add_column(f"id ({name}.*)", overflow="fold", ratio=1, min_width=26)
        table.add_column("paper", justify="right", no_wrap=True)
        table.add_column("computed", justify="right", no_wrap=True)
        table.add_column("unit", no_wrap=True)
        table.add_column("diff", justify="right", no_wrap=True)
        table.add_column("status", no_wrap=True)
        for r in recs:
            short = r.id[len(name) + 1:] if r.id.startswith(f"{name}.") else r.id
            table.add_row(short, fmt_value(r.paper), fmt_value(r.computed), r.unit, fmt_rel(r),
                          f"[{colour[r.status]}]{r.status}[/]")
        parts.append(table)
        why = [r for r in recs if r.status == "differs"]
        if why:
            notes = Text(f"Why {name} rows differ:\n", style="bold")
            for r in why:
                notes.append("- ")
                notes.append(r.id, style="red")
                notes.append(f": {r.note.strip() or 'NO EXPLANATION GIVEN'}\n")
            parts.append(notes)
    c = _status_counts(records)
    parts.append(Text(f"{len(records)} records: {c['reproduced']} reproduced, {c['differs']} "
                      f"differs, {c['computed']} computed", style="bold"))
    return Group(*parts)



def print_table(records: Sequence[ValidationRecord], console=None) -> None:
    """Print :func:`render_table` to ``console`` (a new rich Console by default)."""
    (console or Console()).print(render_table(records))


def validate(modules: Sequence[str] | None = None, *, out: str | Path | None = None,
             docs: str | Path | None = None, strict: bool = False) -> ValidationRun:
    """Reproduce the source papers' numbers: run every validation module once.

    Parameters
    ----------
    modules : sequence of str, optional
        Module names of :mod:`clutchfem.validation` to run (default: every module that
        defines ``records()``).
    out : path, optional
        With ``docs``: the folder of the figures and ``validation.json``.
    docs : path, optional
        Write the Markdown report here (e.g. ``docs/validation.md``); needs ``out``.
    strict : bool
        Raise a module's error instead of recording it as a warning.

    Returns
    -------
    ValidationRun
        ``records`` (one :class:`ValidationRecord` per paper number: its value, the
        reproduced one, the tolerance and the reason of a difference), ``warnings``,
        ``seconds`` per module.

    Examples
    --------
    >>> import clutchfem as cf
    >>> run = cf.validate(["wiesik"])
    >>> r = next(r for r in run.records if r.id == "wiesik.Ms_new")  # seed 000: M_s = 10.23 N m
    >>> r.status, round(r.computed, 2), r.unit
    ('reproduced', 10.23, 'N m')
    """
    if docs is not None and out is None:
        raise InputError("validate(docs=...) needs out=: the folder of the report's figures")
    run = collect(modules, strict=strict)
    if docs is not None:
        report_run(run, Path(out), Path(docs), strict=strict)
    return run

