"""The studies of the app's current design: guidelines, tolerances and a short optimisation,
run in a worker thread of this process with a progress bar, their tables and charts, and
"apply the optimum" (a mixin of :class:`~clutchfem.app.page.DesignPage`)."""

from __future__ import annotations

import base64
from pathlib import Path

from nicegui import run, ui

from ..core import ClutchfemError
from ..guidelines import run_guidelines
from ..report import draw_guideline_charts
from ..targets import optimize
from ..tolerances import tolerance

__all__ = ["StudiesPanel"]


class StudiesPanel:
    """Handlers of the studies expansion (they use the page's session ``s``, ``outcome``,
    ``dir`` and widgets)."""

    # -- studies -----------------------------------------------------------------------------
    async def _study(self, label: str, fn):
        if self.outcome is None:
            ui.notify("wait for the design's answers first")
            return None
        self.progress.set_visibility(True)
        self.progress.props("indeterminate")
        self.study_log.set_text(f"{label} ...")
        lines: list[str] = []

        def log(m: str) -> None:
            lines.append(m)

        try:
            result = await run.io_bound(fn, log)
        except ClutchfemError as exc:
            ui.notify(str(exc), type="negative", multi_line=True)
            result = None
        finally:
            self.progress.set_visibility(False)
        self.study_log.set_text(lines[-1] if lines else "")
        return result

    async def run_guidelines(self) -> None:
        d = self.outcome.design if self.outcome else None
        names = [n for n in ("flexure_thickness", "shoe_thickness", "clearance") if d is not None
                 and n in type(d.params).model_fields]
        res = await self._study("guidelines", lambda log: draw_guideline_charts(run_guidelines(
            d, self.dir / "guidelines", params=names, engine=self.s.engine, requirements=self.s.requirements,
            workers=0, progress=False)))
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
            d, tol, n=32, shifts=False, engine=self.s.engine, requirements=self.s.requirements, workers=0, log=log))
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
        res = await self._study("optimisation (a short search: gradient method on morphed meshes, 40 designs)",
                                lambda log: optimize(d, sample=8, max_evals=40, engine=self.s.engine,
                                                     requirements=self.s.requirements, workers=0, log=log))
        if res is None:
            return
        self.optimum = res
        self.study_out.clear()
        with self.study_out:
            ui.label(res.message)
            rows = [{"parameter": n, "start": res.start_texts.get(n, ""), "optimum": res.params_texts.get(n, "")}
                    for n in res.free]
            ui.table(columns=[{"name": k, "label": k, "field": k} for k in ("parameter", "start", "optimum")],
                     rows=rows).props("dense flat")
        self.apply_button.set_visibility(True)

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
