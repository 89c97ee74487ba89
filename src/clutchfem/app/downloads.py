"""The files of the app's current design as downloads: the one-page report, inputs.json, the
mesh, the fields at the chosen speed and the cutting files (DXF, STEP, drawing sheet), each written into the tab's own folder first (a
mixin of :class:`~clutchfem.app.page.DesignPage`)."""

from __future__ import annotations

import zipfile

from nicegui import run, ui

from ..core import ClutchfemError, dumps
from ..cutting import export
from ..fe import write_vtk
from ..loadcase import design_inputs
from ..report import write_report

__all__ = ["Downloads", "inputs_document"]


def inputs_document(outcome) -> dict:
    """The app's ``inputs.json`` of an outcome: the inputs of the design whose answers are
    shown (:func:`clutchfem.loadcase.design_inputs`, its ``design_hash`` included: the hash
    ``analyze``, ``solve``, ``report``, ``export`` and a study row give the same design), its
    label and who answered (the reduced model, the FE)."""
    return {**design_inputs(outcome.design), "label": outcome.label, "answered_by": outcome.analysis.answered_by}


class Downloads:
    """Handlers of the files menu (they use the page's session ``s``, ``outcome``, ``dir``,
    ``field_rpm`` and ``field_res``)."""

    # -- downloads ---------------------------------------------------------------------------
    def _ready(self) -> bool:
        if self.outcome is None:
            ui.notify("wait for the design's answers first")
            return False
        return True

    async def _of_record(self):
        """The outcome whose answers go into a file: ``analyze``'s (corrected, with bands).  A
        first pass still on screen is completed first (:meth:`~.session.DesignSession.complete`),
        so that no file carries the uncorrected design-mesh values without bands."""
        out = self.outcome
        if not out.live and not out.analysis.errors:
            out = await run.io_bound(self.s.complete, out)
        return out

    async def dl_report(self) -> None:
        if not self._ready():
            return
        rec = await self._of_record()
        out = self.dir / f"{rec.label}-report"
        files = await run.io_bound(lambda: write_report(rec.design, out, engine=self.s.engine,
                                                         requirements=self.s.requirements, errors=False,
                                                         analysis=rec.analysis))
        if files:
            ui.download(out / "report.html", f"{self.outcome.label}-report.html")

    def dl_inputs(self) -> None:
        if self._ready():
            ui.download(dumps(inputs_document(self.outcome), indent=1).encode(), f"{self.outcome.label}-inputs.json")

    def dl_msh(self) -> None:
        if not self._ready():
            return
        cm = self.outcome.design.cm
        if cm.msh_path is None:
            ui.notify("this mesh has no .msh file")
            return
        target = self.dir / f"{self.outcome.label}.msh"
        cm.write_msh(target)
        ui.download(target, target.name)

    async def dl_vtu(self) -> None:
        if not self._ready():
            return
        rpm = self.field_rpm
        res = self.field_res
        if res is None:
            return
        cm = getattr(self.outcome.design, "cm", None)  # the whole part from the sector
        files = await run.io_bound(lambda: write_vtk(res, [rpm], self.dir, stem=self.outcome.label, cm=cm))
        if files:  # [pvd, vtu]: the one frame is the .vtu (the .pvd names it, alone it shows nothing)
            ui.download(files[-1], files[-1].name)

    async def dl_cutting(self) -> None:
        """The cutting files of the current concept design as one zip: DXF (mm), STEP and
        the drawing sheet (PDF) with the answers already on screen, plus inputs.json."""
        if not self._ready():
            return
        d = self.outcome.design
        if d.params is None:
            ui.notify("cutting files come from a concept design (an uploaded part is already CAD)")
            return
        rec = await self._of_record()
        out = self.dir / f"{self.outcome.label}-cutting"
        try:
            res = await run.io_bound(lambda: export(d, out, analysis=rec.analysis))
        except ClutchfemError as e:
            ui.notify(str(e), type="negative", multi_line=True)
            return
        target = self.dir / f"{self.outcome.label}-cutting.zip"
        with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as z:
            for f in res.files:
                z.write(f, f.name)
        ui.download(target, target.name)
