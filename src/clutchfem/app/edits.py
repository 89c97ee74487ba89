"""The edits of one tab (a mixin of :class:`~clutchfem.app.page.DesignPage`): a value typed or
slid, refused at its control or scheduled for analysis; the sliders' feasible ranges (the
concept's coupled rules given the other parameters); the concept, requirements, engine and
part uploads (sizes checked here too, not only by the browser); the field speed; pin and swap."""

from __future__ import annotations

import asyncio
import math
from pathlib import Path

from nicegui import run, ui

from ..core import ClutchfemError
from .limits import MAX_CSV_BYTES, MAX_PART_BYTES

__all__ = ["DEBOUNCE_S", "Edits", "upload_refusal"]

#: wait after the last change before an analysis starts [s]
DEBOUNCE_S = 0.15


def upload_refusal(what: str, size: int, limit: int) -> str | None:
    """The refusal of an uploaded file larger than ``limit`` bytes, else None."""
    if size <= limit:
        return None
    return f"refused: {what} is {size / 1024:.0f} kB, the limit is {limit / 1024:.0f} kB"


class Edits:
    """Handlers of the panel's controls (they use the page's session ``s``, ``values``,
    ``widgets``, ``messages``, ``range_labels``, ``panel``, ``answers`` and ``status``)."""

    # -- edits -----------------------------------------------------------------------------
    def on_edit(self, name: str, value) -> None:
        if value is None or value == self.values.get(name):
            return
        self.values[name] = value
        for w in self.widgets.get(name, ()):
            if w.value != value:
                w.value = value
        msg = self.s.set_value(name, value)
        self.messages[name].set_text(msg or "")
        if msg is not None and self.outcome is not None:  # the answers on screen are another design's: say so
            self.answers.classes(add="opacity-50")
            unit = next((c.unit for c in self.s.controls() if c.name == name), "")
            shown = f"{value:g} {unit}".strip() if isinstance(value, (int, float)) else str(value)
            self.status.set_text(f"{self.outcome.label}: answers of the last valid design (greyed); {name} = {shown} "
                                 "refused, see the message under it")
        if msg is None:
            if name in ("profile", "fidelity"):  # other parameters become active; the drum wall used changes
                self.values.clear()
                self.widgets.clear()
                self.messages.clear()
                self.panel.refresh()
            self.schedule()

    def schedule_ranges(self) -> None:
        """Recompute the sliders' feasible ranges (the others' values cut them) off the loop."""
        if self.ranges_task is not None and not self.ranges_task.done():
            self.ranges_task.cancel()
        self.ranges_task = asyncio.get_event_loop().create_task(self.update_ranges(self.s.generation))

    async def update_ranges(self, gen: int) -> None:
        """Each slider spans what the concept's rules allow with the other parameters as they
        are; its label states the declared range and, where a rule cuts it, the feasible one."""
        await asyncio.sleep(DEBOUNCE_S)
        feas = await run.io_bound(self.s.feasible)
        if gen != self.s.generation:
            return
        for name, (lo, hi) in feas.items():
            if name not in self.range_labels or name not in self.widgets:
                continue
            label, head, c = self.range_labels[name]
            unit = f" {c.unit}" if c.unit else ""
            cut = abs(lo - c.lo) > 1e-9 * max(1.0, abs(c.lo)) or abs(hi - c.hi) > 1e-9 * max(1.0, abs(c.hi))
            label.set_text(f"{head} ({c.lo:g}..{c.hi:g}{unit}" + (f"; with the others now {lo:.4g}..{hi:.4g}{unit}"
                                                                  if cut else "") + ")")
            slider = self.widgets[name][0]
            slider.props(f"min={lo:.6g} max={hi:.6g}")

    def on_concept(self, name: str) -> None:
        try:
            self.s.select(name)
        except ClutchfemError as exc:
            ui.notify(str(exc), type="negative")
            return
        self.values.clear()
        self.widgets.clear()
        self.messages.clear()
        self.panel.refresh()
        self.schedule()

    def on_requirements(self, a=None, b=None) -> None:
        msg = self.s.set_requirements(a, b)
        if msg:
            ui.notify(msg, type="negative")
        else:
            self.schedule()

    async def on_engine_upload(self, e) -> None:
        if self.dir is None:
            return
        msg = upload_refusal("engine curve CSV", e.file.size(), MAX_CSV_BYTES)
        if msg:
            self.messages["engine"].set_text(msg)
            return
        data = await e.file.read()
        path = self.dir / "engine.csv"
        path.write_bytes(data)
        msg = self.s.set_engine_csv(path)
        self.messages["engine"].set_text(msg or "")
        if msg is None:
            self.panel.refresh()
            self.schedule()

    async def on_part_upload(self, e) -> None:
        name = Path(e.file.name).name  # no folders from the browser
        suffix = Path(name).suffix.lower()
        if suffix not in (".msh", ".step", ".stp"):
            self.messages["part"].set_text(f"refused: {name}: a gmsh .msh or a STEP file (.step, .stp)")
            return
        msg = upload_refusal(name, e.file.size(), MAX_PART_BYTES)
        if msg or self.dir is None:
            self.messages["part"].set_text(msg or "")
            return
        path = self.dir / f"part{suffix}"
        path.write_bytes(await e.file.read())
        msg = self.s.set_part(path)
        if msg:
            self.messages["part"].set_text(msg)
            return
        self.values.clear()
        self.widgets.clear()
        self.messages.clear()
        self.panel.refresh()
        ui.notify(f"{name}: give the drum's inner radius", type="info")

    def on_field_rpm(self, value) -> None:
        if value is None or not math.isfinite(float(value)) or float(value) <= 0:
            return
        self.field_rpm = float(value)
        if self.outcome is not None:
            asyncio.get_event_loop().create_task(self.update_field(self.s.generation))

    def on_pin(self) -> None:
        self.s.pin()
        self.pinned_res = self.field_res
        ui.notify(f"pinned {self.s.pinned.label if self.s.pinned else '-'}")
        self.show(self.s.generation)

    def on_swap(self) -> None:
        if self.s.pinned is None:
            ui.notify("pin a design first")
            return
        self.s.swap()
        self.pinned_res, self.field_res = self.field_res, self.pinned_res
        self.values.clear()
        self.widgets.clear()
        self.messages.clear()
        self.panel.refresh()
        self.schedule()

