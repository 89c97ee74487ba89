"""A whole parameter study (:func:`run_study`): a spec's points on the study engine
(:mod:`clutchfem.evaluation`), this spec's rows as a table in designers' units, the error of
the sampled designs' answers, and ``summary.json`` (:class:`StudyResult`)."""

from __future__ import annotations

import json
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import pandas as pd

from ..core import write
from ..evaluation import COLUMNS, ERROR_COLUMNS, STORE_NAME, ResultStore, RunResult, run_points
from .live import live_rows
from .rerun import fingerprint
from .spec import StudySpec, display_value


# ---------------------------------------------------------------------------------------
# a whole study: run, export, summary (its charts are the report stage's, drawn by the faces)
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StudyResult:
    """A parameter study run into its folder (:func:`run_study`): the counts of the run, this
    spec's rows and the files written; :meth:`to_json` is ``summary.json``.

    Attributes
    ----------
    spec : StudySpec
        The study that ran.
    run : RunResult
        What the study engine did (points, ok, refused, failed, computed, skipped, times).
    frame : pandas.DataFrame
        This spec's rows in point order, the varied inputs first in the charts' units
        (``flexure_thickness [mm]``), then every answer in SI (``results.csv``).
    out : Path
        The study's folder (store, ``results.csv``, ``summary.json``, charts).
    files : tuple of Path
        The files written, ``summary.json`` last.
    errors : dict
        The error of the sampled designs' answers (:func:`error_summary`).
    charts : bool
        True once the charts are drawn into ``out/charts`` (:meth:`with_files`).

    Examples
    --------
    >>> import clutchfem as cf, tempfile
    >>> from clutchfem.studies import EXAMPLE_SPEC, parse_spec
    >>> spec = parse_spec(EXAMPLE_SPEC)
    >>> spec.method, len(spec.points())            # run_study(spec, out) runs them
    ('grid', 12)
    """

    spec: StudySpec
    run: RunResult
    frame: pd.DataFrame = field(repr=False)
    out: Path
    fingerprint: str | None
    errors: dict = field(repr=False, default_factory=dict)
    files: tuple[Path, ...] = ()
    charts: bool = False

    @property
    def feasible(self) -> int:
        """Designs that meet every requirement of the spec."""
        return int(self.frame["feasible"].fillna(0).astype(int).sum()) if len(self.frame) else 0

    @property
    def summary_path(self) -> Path:
        return self.out / "summary.json"

    def to_json(self) -> dict:
        """The summary (``summary.json``): the run's counts and times, the design, method and
        spec, the feasible count, the error summary and the files."""
        s = self.run.to_json()
        s["errors"] = self.errors
        s.update(design=self.spec.design, method=self.spec.method, spec=self.spec.source, out=str(self.out),
                 feasible=self.feasible,
                 files=[str(f) for f in self.files], charts=self.charts, keys=list(self.run.keys),
                 fingerprint=self.fingerprint)
        return s

    def with_files(self, files, *, charts: bool = False) -> "StudyResult":
        """This result with ``files`` (the charts a face drew into its folder) added to its
        record, and ``summary.json`` written again with them."""
        done = tuple(f for f in self.files if f != self.summary_path)
        new = replace(self, files=(*done, *map(Path, files), self.summary_path), charts=self.charts or charts)
        write(new.summary_path, new.to_json(), indent=1)
        return new


def run_study(spec, out: str | Path, *, workers: int | None = None, scheduler: str | None = None,
              retry_failed: bool = False, progress: bool = True) -> StudyResult:
    """Run a parameter study into a folder, resumably: every point through the full
    analysis on the study engine (Dask: local process workers, or the cluster at
    ``scheduler``), each finished row committed to the store as it arrives.

    Parameters
    ----------
    spec : StudySpec
        From :func:`~clutchfem.load_study`.
    out : path
        The store (``results.sqlite``), ``results.csv`` (this spec's rows, inputs in
        designers' units) and ``summary.json``.  The charts are drawn by the faces
        (:func:`clutchfem.report.study_charts`).
    workers, scheduler
        Local workers (``0``: in this process) or an existing scheduler's address.
    retry_failed : bool
        Recompute the points stored as failed (finished points are otherwise skipped).
    progress : bool
        A progress bar on standard error.

    Returns
    -------
    StudyResult
        The counts (also on :class:`StudyInterrupted`, via its ``result``), the rows, the
        error summary and the files written.

    Examples
    --------
    >>> import clutchfem as cf, tempfile
    >>> from clutchfem.studies import parse_spec
    >>> spec = parse_spec('''
    ... [design]
    ... concept = "concept1"
    ... [settings]
    ... mesh_size = "3mm"
    ... [errors]
    ... sample = 0
    ... [vary]
    ... method = "grid"
    ... [vary.params]
    ... flexure_thickness = {values = ["2.0mm", "2.4mm"]}
    ... ''')
    >>> s = cf.run_study(spec, tempfile.mkdtemp(), workers=0, progress=False)
    >>> s.run.points, s.run.ok, list(s.frame["flexure_thickness [mm]"])
    (2, 2, [2.0, 2.4])

    With ``fidelity = "live"`` under ``[settings]`` each point is answered by the cached
    reduced model whose region holds it, in milliseconds (:mod:`clutchfem.studies.live`):
    the rows say ``answered_by`` and carry the live band; a point no region holds is refused
    (or, with ``live_outside = "fe"``, answered by the full FE), said in its row."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    points = spec.points()
    if spec.settings.op is not None and spec.settings.op.fidelity == "live":
        return _run_live(spec, points, out, workers=workers, scheduler=scheduler, progress=progress)
    res = run_points(points, spec.settings, out / STORE_NAME, workers=workers, scheduler=scheduler,
                     retry_failed=retry_failed, progress=progress, source=spec.source, spec_text=spec.text,
                     error_points=spec.error_points(len(points)))
    frame = table(spec, res)
    csv = out / "results.csv"
    frame.to_csv(csv, index=False)
    result = StudyResult(spec=spec, run=res, frame=frame, out=out, fingerprint=fingerprint(spec.source, spec.text), errors=error_summary(frame),
                         files=(csv, out / "summary.json"))
    write(result.summary_path, result.to_json(), indent=1)
    return result


def _run_live(spec, points, out: Path, *, workers, scheduler, progress) -> StudyResult:
    """A live study (:mod:`.live`): the rows from the reduced models, ``results.csv`` and
    ``summary.json``."""
    rows, res = live_rows(points, spec.settings, outside=spec.live_outside, store=out / STORE_NAME,
                          workers=workers, scheduler=scheduler, progress=progress, source=spec.source)
    df = pd.DataFrame(rows)
    front = pd.DataFrame({a.label(): [display_value(p.get(a.name), a.unit) for p in points] for a in spec.axes},
                         index=df.index)
    frame = pd.concat([front, df], axis=1)
    csv = out / "results.csv"
    frame.to_csv(csv, index=False)
    errors = error_summary(frame)
    errors["method"] = ("live: each answer's band is the best path's band of the reduced model's nearest training "
                        "designs plus the reduced model's own error measured on held-out designs (the rows of "
                        "answered_by 'FE (fallback)': the best path's own band)")
    errors["answered_by"] = {k: int(v) for k, v in frame["answered_by"].value_counts().items()}
    result = StudyResult(spec=spec, run=res, frame=frame, out=out, fingerprint=fingerprint(spec.source, spec.text),
                         errors=errors, files=(csv, out / "summary.json"))
    write(result.summary_path, result.to_json(), indent=1)
    return result


def error_summary(frame) -> dict:
    """The study's error from its sampled designs: per answer, the median and largest band
    (discretisation + model form) relative to the answer [%], and the discretisation part."""
    sel = frame[(frame["status"] == "ok") & (frame["errors_estimated"].fillna(0) == 1)]
    out: dict = {"sampled": int(len(sel)),
                 "method": "designs evenly spaced in the spec, analysed again on a mesh twice as fine "
                           "(discretisation 2|a_h - a_h/2|) plus the measured model-form terms (clutchfem.errorest)"}
    for ans, tot, disc, unit in ERROR_COLUMNS:
        v = sel[ans].astype(float).abs()
        rel_t = (sel[tot].astype(float) / v * 100).replace([np.inf, -np.inf], np.nan).dropna()
        rel_d = (sel[disc].astype(float) / v * 100).replace([np.inf, -np.inf], np.nan).dropna()
        out[ans] = {"band_median_pct": float(rel_t.median()) if len(rel_t) else None,
                    "band_max_pct": float(rel_t.max()) if len(rel_t) else None,
                    "discretisation_median_pct": float(rel_d.median()) if len(rel_d) else None,
                    "discretisation_max_pct": float(rel_d.max()) if len(rel_d) else None}
    return out


def table(spec, res: RunResult):
    """This spec's rows (point order) with one column per varied input, in the units of the
    charts (lengths in mm: ``flexure_thickness [mm]``), before the answers."""
    with ResultStore(res.store, COLUMNS, context=res.context_hash) as st:
        df = st.frame(res.model_version, res.keys)
    cols = {}
    for a in spec.axes:
        cols[a.label()] = [display_value(json.loads(p).get(a.name), a.unit) for p in df["point_json"]]
    front = pd.DataFrame(cols, index=df.index)
    return pd.concat([front, df], axis=1)
