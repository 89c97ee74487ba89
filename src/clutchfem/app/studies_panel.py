"""The studies of the app's current design: guidelines, tolerances and a short optimisation,
run in a worker thread of this process with a progress bar and the time left, a cancel
button, their tables and charts, and "apply the optimum" (a mixin of
:class:`~clutchfem.app.page.DesignPage`).

A study stops when its cancel button is pressed or its tab goes (:meth:`StudiesPanel.
cancel_study`): the optimisation at its next step (its log is the cancellation point), the
guidelines and tolerances at the end of the batch of designs in flight (their result is
dropped).  The optimiser's result is said in the designer's words
(:func:`optimum_summary`): each target the page states, met or missed and by how much (by
the answers of ``analyze`` for the final design), the targets the search aimed at where they
differ from the page's and why; "apply the optimum" is offered only for a design that meets
every target.
"""

from __future__ import annotations

import base64
import math
import re
import time
from pathlib import Path

from nicegui import run, ui

from ..core import ClutchfemError
from ..guidelines import run_guidelines
from ..report import draw_guideline_charts
from ..targets import optimize
from ..tolerances import tolerance

__all__ = ["StudiesPanel", "StudyCancelled", "StudyProgress", "optimum_summary"]

#: the optimisation's budget of designs (the check rounds with analyze add up to half of it each)
OPT_EVALS = 40


class StudyCancelled(Exception):
    """A study stopped by its cancel button or because its tab went (not a ClutchfemError: no
    handler of the study's own takes it for a refused design)."""


class StudyProgress:
    """The progress of a study for its bar: the share done and the time left, from the study's
    own count where its log gives one ("n of at most N"), else from the time a design takes
    (the first pass of the current design) and the number of designs.

    Parameters
    ----------
    designs : int
        The designs the study evaluates (at most).
    seconds_per_design : float
        The time one design takes [s].

    Examples
    --------
    >>> from clutchfem.app.studies_panel import StudyProgress
    >>> p = StudyProgress(40, 2.0)
    >>> p.t0 -= 20.0                          # 20 s in
    >>> round(p.share(), 2), p.left_text()
    (0.25, 'about 60 s left')
    >>> p.saw("poll 3 (step 0.06 of the ranges): ... [30 of at most 40 evaluations, 20 s]")
    >>> round(p.share(), 2), p.left_text()
    (0.75, 'about 7 s left')
    """

    _COUNT = re.compile(r"\[(\d+) of at most (\d+) (?:evaluations|designs)")

    def __init__(self, designs: int, seconds_per_design: float):
        self.designs = max(1, int(designs))
        self.per = max(0.05, float(seconds_per_design))
        self.t0 = time.monotonic()
        self.done: tuple[int, int] | None = None
        self.cancelled = False

    def saw(self, line: str) -> None:
        """Read a log line of the study (its count of designs, when it gives one)."""
        m = self._COUNT.search(line)
        if m:
            self.done = (int(m.group(1)), max(1, int(m.group(2))))

    def elapsed(self) -> float:
        return time.monotonic() - self.t0

    def share(self) -> float:
        """The share done, in [0, 0.99] (a study may end before its budget: never 1 before it ends)."""
        if self.done is not None and self.done[0] > 0:
            s = self.done[0] / self.done[1]
        else:
            s = self.elapsed() / (self.designs * self.per)
        return min(0.99, max(0.0, s))

    def left_seconds(self) -> float:
        s, el = self.share(), self.elapsed()
        if self.done is not None and self.done[0] > 0:
            return el / s * (1 - s) if s > 0 else self.designs * self.per
        return max(self.designs * self.per - el, 0.0)

    def left_text(self) -> str:
        left = self.left_seconds()
        if self.share() >= 0.99:
            return "finishing"
        if left < 60:
            return f"about {max(1, round(left))} s left"
        return f"about {round(left / 60)} min left"


def _fmt(key: str, v) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return {"slip_rpm": "never slips to a hold (no slip speed)",
                "engagement_rpm_with_ripple": "never engages"}.get(key, "no answer")
    return f"{v:.2f}" if key in ("safety_factor", "fatigue_safety_factor") else f"{v:.0f} rpm"


#: the targets as the page states them (answer key -> the words of the answers table)
_WORDS = {"engagement_rpm_with_ripple": "engagement with 2-stroke ripple", "slip_rpm": "slip speed",
          "safety_factor": "safety factor (yield) at the engine's top speed",
          "fatigue_safety_factor": "fatigue safety factor"}
_LIMIT_FIELD = {("engagement_rpm_with_ripple", ">="): "engage_rpm_lo", ("engagement_rpm_with_ripple", "<="):
                "engage_rpm_hi", ("slip_rpm", "<="): "slip_rpm_max", ("safety_factor", ">="): "safety_factor_min",
                ("fatigue_safety_factor", ">="): "fatigue_min"}


def optimum_summary(res) -> tuple[list[str], bool]:
    """(lines in the designer's words, whether to offer "apply the optimum") of an
    :class:`~clutchfem.targets.OptimizationResult`: the verdict, each target as the page
    states it met or missed and by how much (the final design's answers from ``analyze``,
    corrected, against the page's targets), the targets the search aimed at where they
    differ and why, the parameters changed.  Apply is offered only when the final design
    meets every target as ``analyze`` answers it.

    Parameters
    ----------
    res : OptimizationResult
        What :func:`clutchfem.optimize` returned.

    Returns
    -------
    lines : list of str
    can_apply : bool

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.targets import OptimizationResult
    >>> t = cf.Targets(3510, None, 8000, 1.5)
    >>> best = {"params": {}, "mass_kg": 0.05, "assessment": t.assess({"status": "ok", "mass_kg": 0.05,
    ...         "torque_margin_Nm": 1.0, "engagement_rpm_with_ripple": 3600.0, "slip_rpm": 8200.0,
    ...         "safety_factor": 1.6})}
    >>> r = OptimizationResult("concept4", t, ["flexure_thickness"], {}, best, False, {}, [], [], {"ok": 9},
    ...                        12.0, 3, "no feasible design found")
    >>> lines, ok = optimum_summary(r)
    >>> ok, lines[0]
    (False, 'No design found that meets every target: the best one misses 1 of 3 (nothing to apply).')
    >>> lines[3]
    'slip speed <= 8000 rpm: MISSED by 200 rpm (8200 rpm)'
    """
    best = res.best or {}
    cons = (best.get("assessment") or {}).get("constraints") or []
    missed = [c for c in cons if c["violated"]]
    can_apply = bool(res.feasible and not missed and res.params_texts)
    lines = []
    if can_apply:
        lines.append(f"A design meets every target ({len(cons)}): "
                     + ("its changes below can be applied." if res.params_texts else "the start design itself."))
    elif not missed and res.feasible:
        lines.append("The start design already meets every target at least mass found: nothing to apply.")
    else:
        lines.append(f"No design found that meets every target: the best one misses {len(missed)} of {len(cons)} "
                     "(nothing to apply).")
    lines.append("Targets (as the page states them; the final design's answers as analyze gives them):")
    for c in cons:
        key, lim, sense = c["key"], c["limit"], c["sense"]
        word = _WORDS.get(key, key)
        limit = _fmt(key, lim)
        v, slack = c.get("value"), c.get("slack")
        by = "" if slack is None or not math.isfinite(slack) else _fmt(key, abs(slack))
        if c["violated"]:
            lines.append(f"{word} {sense} {limit}: MISSED" + (f" by {by}" if by else "") + f" ({_fmt(key, v)})")
        else:
            lines.append(f"{word} {sense} {limit}: met" + (f" with {by} to spare" if by else "") + f" ({_fmt(key, v)})")
    est = res.best_estimate or {}
    searched = est.get("targets_searched") or {}
    ratios = est.get("ratios") or {}
    for c in cons:
        fld = _LIMIT_FIELD.get((c["key"], c["sense"]))
        aim = searched.get(fld) if fld else None
        if aim is None or not math.isfinite(aim) or abs(aim - c["limit"]) <= 1e-9 * abs(c["limit"]):
            continue
        r = ratios.get(c["key"])
        why = ("" if r is None else f": analyze's corrected answer is {100 * (r - 1):+.1f} % of the search's "
               "design-mesh answer")
        lines.append(f"The search aimed at {_WORDS.get(c['key'], c['key'])} {c['sense']} {_fmt(c['key'], aim)}, not "
                     f"{_fmt(c['key'], c['limit'])}: the target moved inward by analyze's correction (non-linearity, "
                     f"mesh extrapolation) so that analyze meets the page's target{why}.")
    if res.params_texts:
        lines.append("Changes: " + ", ".join(f"{n} {res.start_texts.get(n, '?')} -> {t}"
                                            for n, t in res.params_texts.items()))
    lines.append(f"{sum(res.evaluations.values())} designs evaluated in {res.seconds:.0f} s.")
    return lines, can_apply


class StudiesPanel:
    """Handlers of the studies expansion (they use the page's session ``s``, ``outcome``,
    ``dir`` and widgets)."""

    def study_widgets(self) -> None:
        """The buttons, the progress bar with the time left and the cancel button."""
        with ui.row().classes("items-center"):
            ui.button("guidelines", on_click=self.run_guidelines).props("data-testid=study-guidelines")
            ui.button("tolerances", on_click=self.run_tolerance).props("data-testid=study-tolerance")
            ui.button("optimise (least mass)", on_click=self.run_optimize).props("data-testid=study-optimize")
            self.cancel_button = ui.button("cancel the study", on_click=self.cancel_study).props(
                "color=negative data-testid=study-cancel")
            self.cancel_button.set_visibility(False)
            self.apply_button = ui.button("apply the optimum", on_click=self.apply_optimum).props(
                "data-testid=study-apply")
            self.apply_button.set_visibility(False)
        self.progress = ui.linear_progress(value=0.0, show_value=False).classes("w-full")
        self.progress.set_visibility(False)
        self.study_log = ui.label("").classes("text-xs").props("data-testid=study-log")
        self.study_out = ui.column().classes("w-full")

    def cancel_study(self) -> None:
        """Stop the study running (the cancel button; the tab going)."""
        prog = getattr(self, "study_progress", None)
        if prog is not None:
            prog.cancelled = True

    # -- studies -----------------------------------------------------------------------------
    async def _study(self, label: str, fn, designs: int):
        if self.outcome is None:
            ui.notify("wait for the design's answers first")
            return None
        if getattr(self, "study_progress", None) is not None:
            ui.notify("a study is running: cancel it first")
            return None
        prog = self.study_progress = StudyProgress(designs, self.outcome.seconds)
        self.apply_button.set_visibility(False)
        self.cancel_button.set_visibility(True)
        self.progress.set_visibility(True)
        self.progress.set_value(0.0)
        self.study_log.set_text(f"{label} ...")
        lines: list[str] = []

        def log(m: str) -> None:  # the study's own thread: its cancellation point
            lines.append(m)
            prog.saw(m)
            if prog.cancelled:
                raise StudyCancelled(f"{label}: cancelled")

        def tick() -> None:
            self.progress.set_value(prog.share())
            self.study_log.set_text(f"{label}: {100 * prog.share():.0f} %, {prog.left_text()} ({prog.elapsed():.0f} s "
                                    "so far)" + (f"; {lines[-1]}" if lines else ""))

        timer = ui.timer(1.0, tick)
        result = None
        try:
            result = await run.io_bound(fn, log)
            if getattr(self, "closed", False):  # the tab went meanwhile: nothing to show
                return None
            if prog.cancelled:
                result = None
                self.study_log.set_text(f"{label}: cancelled after {prog.elapsed():.0f} s")
            else:
                self.study_log.set_text(f"{label}: done in {prog.elapsed():.0f} s")
        except StudyCancelled:
            if getattr(self, "closed", False):
                return None
            self.study_log.set_text(f"{label}: cancelled after {prog.elapsed():.0f} s")
        except ClutchfemError as exc:
            ui.notify(str(exc), type="negative", multi_line=True)
        finally:
            timer.cancel()
            self.study_progress = None
            if not getattr(self, "closed", False):
                self.progress.set_visibility(False)
                self.cancel_button.set_visibility(False)
        return result

    async def run_guidelines(self) -> None:
        d = self.outcome.design if self.outcome else None
        names = [n for n in ("flexure_thickness", "shoe_thickness", "clearance") if d is not None
                 and n in type(d.params).model_fields]
        res = await self._study("guidelines", lambda log: draw_guideline_charts(run_guidelines(
            d, self.dir / "guidelines", params=names, engine=self.s.engine, requirements=self.s.requirements,
            workers=0, progress=False)), designs=1 + 2 * len(names))
        if res is None:
            return
        self.study_out.clear()
        with self.study_out:
            rows = [{"parameter": r["parameter"], "answer": r["label"], "elasticity": f"{r['E']:+.2f}"
                     if r.get("E") is not None else "-", "verdict": r.get("verdict", ""),
                     "method": r.get("method", "")} for r in res.table]
            ui.table(columns=[{"name": k, "label": k, "field": k} for k in ("parameter", "answer", "elasticity",
                                                                            "verdict", "method")],
                     rows=rows).props("dense flat")
            for f in res.files:
                if str(f).endswith(".png"):
                    ui.image(_data_url(Path(f))).classes("w-[48rem]")

    async def run_tolerance(self) -> None:
        d = self.outcome.design if self.outcome else None
        tol = {n: v for n, v in (("flexure_thickness", "0.05mm"), ("clearance", "0.02mm")) if d is not None
               and n in type(d.params).model_fields}
        res = await self._study("tolerances (32 parts)", lambda log: tolerance(
            d, tol, n=32, shifts=False, engine=self.s.engine, requirements=self.s.requirements, workers=0, log=log),
            designs=33)
        if res is None:
            return
        self.study_out.clear()
        with self.study_out:
            ui.label(f"tolerances (normal, +-3 sigma): {', '.join(f'{k} +-{v}' for k, v in tol.items())}")
            rows = [{"spec": k, "out of spec": f"{100 * v['share']:.1f} % [{100 * v['ci95'][0]:.1f}, "
                                               f"{100 * v['ci95'][1]:.1f}] ({v['k']} of {v['n']})"}
                    for k, v in res.out_of_spec.items()]
            ui.table(columns=[{"name": k, "label": k, "field": k} for k in ("spec", "out of spec")],
                     rows=rows).props("dense flat")

    async def run_optimize(self) -> None:
        d = self.outcome.design if self.outcome else None
        self.optimum = None
        res = await self._study(f"optimisation (least mass, at most {OPT_EVALS} designs)",
                                lambda log: optimize(d, sample=8, max_evals=OPT_EVALS, engine=self.s.engine,
                                                     requirements=self.s.requirements, workers=0, log=log),
                                designs=OPT_EVALS)
        if res is None:
            return
        lines, can_apply = optimum_summary(res)
        self.optimum = res if can_apply else None
        self.study_out.clear()
        with self.study_out:
            for i, line in enumerate(lines):
                ui.label(line).classes("text-sm" + (" font-bold" if i == 0 else "")).props(
                    f"data-testid=optimum-{i}")
            rows = [{"parameter": n, "start": res.start_texts.get(n, ""), "optimum": res.params_texts.get(n, "")}
                    for n in res.free]
            ui.table(columns=[{"name": k, "label": k, "field": k} for k in ("parameter", "start", "optimum")],
                     rows=rows).props("dense flat")
            with ui.expansion("the search's own log", value=False).classes("w-full text-xs"):
                ui.label(res.message).classes("text-xs")
        self.apply_button.set_visibility(can_apply)

    def apply_optimum(self) -> None:
        res = getattr(self, "optimum", None)
        if res is None:
            return
        for n, text in res.params_texts.items():
            msg = self.s.set_value(n, text)
            if msg:
                ui.notify(msg, type="negative")
        self.values.clear()
        self.widgets.clear()
        self.messages.clear()
        self.panel.refresh()
        self.schedule()


def _data_url(path: Path) -> str:
    return "data:image/png;base64," + base64.b64encode(path.read_bytes()).decode()
