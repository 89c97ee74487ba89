"""The page of the live design app (NiceGUI): the design panel, the answers with their
badges and bands, the charts, the part at a chosen speed, compare, studies and downloads.
One page per browser tab, each with its own :class:`~.session.DesignSession`.

Responsiveness: a change is debounced (:data:`DEBOUNCE_S`), the analysis runs in a worker
thread (the event loop never waits on it), one run at a time per tab; a run whose inputs
were changed again before it started is skipped (stale), and a result that is no longer the
newest is dropped.  The fast pass (answers, charts) is shown first; the part at the chosen
speed and the error bands follow once the designer pauses (:data:`EXTRAS_DELAY_S`) in a
second lane, so they never hold up the next answers, and a change skips them.
"""

from __future__ import annotations

import asyncio
import base64
import shutil
import tempfile
from pathlib import Path

from nicegui import Client, run, ui
from starlette.responses import HTMLResponse

from ..core import ClutchfemError
from . import limits
from .downloads import Downloads
from .edits import DEBOUNCE_S, Edits
from .figures import field_png, pressure_chart, torque_chart
from .limits import MAX_CSV_BYTES, MAX_PART_BYTES, upload_limits
from .session import FIRST_PASS, DesignSession, answer_rows
from .studies_panel import StudiesPanel

__all__ = ["build_page", "live_tabs"]

#: wait after the last change before an analysis starts [s]: the model ``live``'s own, shorter
#: (the others': :data:`.edits.DEBOUNCE_S`)
LIVE_DEBOUNCE_S = 0.05
#: wait after the answers before the part picture and the error bands start [s]
EXTRAS_DELAY_S = 0.5
#: the live tabs (connected pages with a session), by NiceGUI client id
live_tabs: dict[str, "DesignPage"] = {}
#: the pages built and not yet connected
pending_pages: dict[str, "DesignPage"] = {}


class DesignPage(Edits, StudiesPanel, Downloads):
    """The widgets and handlers of one tab (module docstring)."""

    def __init__(self, out_root: Path, client: Client | None = None):
        self.out_root = out_root
        self.client = client
        self.dir: Path | None = None  # the tab's folder: made when the page connects
        self.s = DesignSession("concept4")
        self.started = self.closed = False
        self.uploads: list[str] = []
        self.values: dict[str, object] = {}
        self.widgets: dict[str, tuple] = {}
        self.messages: dict[str, ui.label] = {}
        self.pending: asyncio.Task | None = None
        self.extras: asyncio.Task | None = None
        self.running = asyncio.Lock()
        self.secondary = asyncio.Lock()
        self.outcome = None
        self.bands: dict = {}
        self.range_labels: dict = {}
        self.ranges_task = None
        self.field_rpm = 8000.0
        self.field_res = None
        self.pinned_res = None

    # -- layout --------------------------------------------------------------------------
    def build(self) -> None:
        ui.page_title("clutchfem: live design")
        with ui.header().classes("items-center gap-4 bg-slate-800"):
            ui.label("clutchfem").classes("text-xl font-bold")
            ui.select(self.s.concept_names(), value=self.s.concept.name, label="concept",
                      on_change=lambda e: self.on_concept(e.value)).props(
                "dense dark outlined data-testid=concept").classes("w-40")
            ui.button("pin", on_click=self.on_pin).props("data-testid=pin flat color=white")
            ui.button("swap", on_click=self.on_swap).props("data-testid=swap flat color=white")
            with ui.button("files", icon="download").props("flat color=white data-testid=files"):
                with ui.menu():
                    ui.menu_item("report (HTML)", on_click=self.dl_report)
                    ui.menu_item("inputs.json", on_click=self.dl_inputs)
                    ui.menu_item("mesh (.msh)", on_click=self.dl_msh)
                    ui.menu_item("fields at the chosen speed (.vtu)", on_click=self.dl_vtu)
                    ui.menu_item("cutting files (.zip: DXF, STEP, drawing)", on_click=self.dl_cutting)
            self.status = ui.label("").classes("ml-auto text-sm").props("data-testid=status")
        with ui.row().classes("w-full no-wrap items-start"):
            with ui.column().classes("w-96 shrink-0"):
                self.panel()
            with ui.column().classes("grow"):
                self.results()

    # -- life of the tab ---------------------------------------------------------------------
    def start(self) -> None:
        """The page's websocket connected (a page in a browser): the tab becomes live (its
        folder, its session counted in :data:`~.limits.MAX_SESSIONS`) and its first analysis
        starts; a reconnection changes nothing.  Over the limit, the page says so instead."""
        if self.started or self.closed:
            return
        self.started = True
        pending_pages.pop(self.key, None)
        if len(live_tabs) >= limits.MAX_SESSIONS:
            self.closed = True
            self.status.set_text(too_many_tabs())
            ui.notify(too_many_tabs(), type="negative", multi_line=True, timeout=0)
            return
        live_tabs[self.key] = self
        self.dir = Path(tempfile.mkdtemp(prefix="tab-", dir=self.out_root))
        self.s.out_dir = self.dir
        self.schedule()

    def close(self) -> None:
        """The tab is gone (closed, or not reconnected in time): its tasks cancelled (a study
        stops at its next step), its upload routes, session and folder dropped."""
        self.closed = True
        self.cancel_study()
        for task in (self.pending, self.extras, self.ranges_task):
            if task is not None and not task.done():
                task.cancel()
        for url in self.uploads:
            upload_limits.pop(url, None)
        live_tabs.pop(self.key, None)
        pending_pages.pop(self.key, None)
        if self.dir is not None:
            shutil.rmtree(self.dir, ignore_errors=True)
        # the designs, meshes and answers it held: free to be collected (a worker thread still
        # running keeps its own until it ends; its result is dropped)
        self.outcome = self.field_res = self.pinned_res = None
        self.s.last = self.s.pinned = None

    @property
    def key(self) -> str:
        return self.client.id if self.client is not None else str(id(self))

    def _upload(self, limit: int, **kw) -> ui.upload:
        up = ui.upload(max_file_size=limit, auto_upload=True, **kw)
        url = up.props["url"]
        upload_limits[url] = limit  # the server refuses a larger body (limits.UploadLimit)
        self.uploads.append(url)
        return up

    @ui.refreshable
    def panel(self) -> None:
        groups: dict[str, list] = {}
        for c in self.s.controls():
            groups.setdefault(c.group, []).append(c)
        for group, ctrls in groups.items():
            with ui.expansion(group, value=True).classes("w-full"):
                for c in ctrls:
                    self.control(c)
        with ui.expansion("engine and requirements", value=False).classes("w-full"):
            ui.number("a: engagement > a x idle", value=self.s.requirements.a, step=0.05,
                      on_change=lambda e: self.on_requirements(a=e.value)).props("dense debounce=300")
            ui.number("b: slip < b x rpm of max torque", value=self.s.requirements.b, step=0.05,
                      on_change=lambda e: self.on_requirements(b=e.value)).props("dense debounce=300")
            ui.label(f"engine: {self.s.engine.source}").classes("text-xs")
            self._upload(MAX_CSV_BYTES, label="engine curve CSV (rpm, torque [N m])",
                         on_upload=self.on_engine_upload,
                         on_rejected=lambda: ui.notify(f"refused: larger than {MAX_CSV_BYTES // 1024} kB")).props(
                "dense accept=.csv")
            self.messages["engine"] = ui.label("").classes("text-xs text-red-600")
        with ui.expansion("your own part (.msh / STEP)", value=self.s.part is not None).classes("w-full"):
            self._upload(MAX_PART_BYTES,
                         label="part: gmsh .msh (curve groups bore, contact) or STEP; x-y plane, axis at the origin",
                         on_upload=self.on_part_upload,
                         on_rejected=lambda: ui.notify(f"refused: larger than {MAX_PART_BYTES >> 20} MB")).props(
                "dense accept=.msh,.step,.stp")
            self.messages["part"] = ui.label("" if self.s.part is None else f"analysing {self.s.part.name}").classes(
                "text-xs")

    def control(self, c) -> None:
        self.values[c.name] = c.value
        with ui.column().classes("w-full gap-0"):
            if c.kind == "choice":
                w = ui.select(list(c.choices), value=c.value, label=c.label,
                              on_change=lambda e, n=c.name: self.on_edit(n, e.value)).props(
                    f"dense data-testid=choice-{c.name}").classes("w-full")
                self.widgets[c.name] = (w,)
            else:
                unit = f" [{c.unit}]" if c.unit else ""
                with ui.row().classes("w-full items-center no-wrap gap-2"):
                    s = ui.slider(min=c.lo if c.lo is not None else 0.0, max=c.hi if c.hi is not None else 1.0,
                                  step=c.step, value=c.value,
                                  on_change=lambda e, n=c.name: self.on_edit(n, e.value)).props(
                        f"dense data-testid=slider-{c.name}").classes("grow")
                    n = ui.number(value=c.value, step=c.step, format=None,
                                  on_change=lambda e, n=c.name: self.on_edit(n, e.value)).props(
                        f"dense data-testid=num-{c.name}").classes("w-24")
                rng = "" if c.lo is None else f"{c.lo:g}..{c.hi:g}{(' ' + c.unit) if c.unit else ''}"
                self.range_labels[c.name] = (ui.label(f"{c.name}{unit}: {c.label} ({rng})").classes(
                    "text-xs text-gray-600").props(f"data-testid=range-{c.name}"), f"{c.name}{unit}: {c.label}", c)
                self.widgets[c.name] = (s, n)
            self.messages[c.name] = ui.label("").classes("text-xs text-red-600").props(
                f"data-testid=msg-{c.name}")

    def results(self) -> None:
        with ui.row().classes("w-full gap-6 items-start"):
            with ui.column():
                self.answers = ui.table(columns=self._columns(False), rows=[], row_key="answer").props(
                    "dense flat bordered data-testid=answers").classes("w-[46rem]")
                self.warnings = ui.column().classes("gap-0 w-[46rem]")
            with ui.column().classes("grow"):
                self.torque = ui.echart(torque_chart_placeholder()).classes("w-[40rem] h-80").props(
                    "data-testid=torque-chart")
        with ui.row().classes("w-full gap-6 items-start"):
            with ui.column():
                with ui.row().classes("items-center"):
                    ui.label("part at")
                    self.rpm_input = ui.number(value=self.field_rpm, step=250, suffix="rpm",
                                               on_change=lambda e: self.on_field_rpm(e.value)).props(
                        "dense debounce=400 data-testid=field-rpm").classes("w-32")
                self.field_img = ui.image().classes("w-[30rem]").props("data-testid=field")
            with ui.column().classes("grow"):
                self.pressure = ui.echart(torque_chart_placeholder()).classes("w-[40rem] h-72")
        with ui.expansion("studies of this design", value=False).classes("w-full"):
            self.study_widgets()

    @staticmethod
    def _columns(pinned: bool) -> list[dict]:
        cols = [{"name": "answer", "label": "answer", "field": "answer", "align": "left"},
                {"name": "value", "label": "value", "field": "value", "align": "right"},
                {"name": "verdict", "label": "requirement", "field": "verdict", "align": "left"}]
        if pinned:
            cols += [{"name": "pinned", "label": "pinned", "field": "pinned", "align": "right"},
                     {"name": "delta", "label": "difference", "field": "delta", "align": "right"}]
        return cols

    # -- the analysis ----------------------------------------------------------------------
    def schedule(self) -> None:
        if self.closed or not self.started:  # not live: no analysis (limits: only a connected page analyses)
            return
        self.schedule_ranges()
        if self.pending is not None and not self.pending.done():
            self.pending.cancel()
        self.pending = asyncio.get_event_loop().create_task(self.refresh(self.s.generation))

    async def refresh(self, gen: int) -> None:
        await asyncio.sleep(LIVE_DEBOUNCE_S if self.s.op.fidelity == "live" else DEBOUNCE_S)
        async with self.running:
            if gen != self.s.generation:  # changed again while waiting: a newer run follows
                return
            self.status.set_text("computing ...")
            try:
                out = await run.io_bound(self.s.run)
            except ClutchfemError as exc:
                self.status.set_text("")
                ui.notify(str(exc), type="negative", multi_line=True)
                return
            if out is None or gen != self.s.generation:
                return
            self.outcome, self.bands = out, (out.analysis.errors if out.live else {})  # live: its bands
            self.show(gen)
            self.status.set_text(f"{out.label}: first pass in {out.seconds:.2f} s; the answers of analyze (corrected, "
                                 "with error bands) ...")
        # the part picture and the error bands follow once the designer pauses: a change in
        # the meantime skips them (they never hold up the next answers)
        if self.extras is not None and not self.extras.done():
            self.extras.cancel()
        self.extras = asyncio.get_event_loop().create_task(self.follow_up(gen, out))

    async def follow_up(self, gen: int, out) -> None:
        await asyncio.sleep(EXTRAS_DELAY_S)
        async with self.secondary:
            if gen != self.s.generation:
                return
            await self.update_field(gen)
            if gen != self.s.generation:
                return
            if out.live:
                await self.check_live(gen, out)
                return
            full = await run.io_bound(self.s.complete, out)
            if full is None or gen != self.s.generation:
                return
            self.outcome, self.bands = full, full.analysis.errors
            self.show(gen)
            self.status.set_text(f"{out.label}: the answers of analyze, with error bands (first pass in "
                                 f"{out.seconds:.2f} s, these in {full.seconds:.2f} s)")

    async def check_live(self, gen: int, out) -> None:
        """The FE check of live answers (:meth:`~.session.DesignSession.verify`): they stay
        where the FE lies in their bands, else the FE's replace them and the page says so."""
        self.status.set_text(f"{out.label}: live answers in {out.seconds:.3f} s; the FE check (best path with its "
                             "error step) ...")
        shown, off = await run.io_bound(self.s.verify, out)
        if gen != self.s.generation:
            return
        if off:
            self.outcome, self.bands = shown, shown.analysis.errors
            self.show(gen)
            ui.notify("the FE differs from the live answers by more than their bands and replaced them: "
                      + "; ".join(off), type="warning", multi_line=True)
            self.status.set_text(f"{out.label}: FE answers (they replaced the live ones: {len(off)} outside the "
                                 f"band), FE in {shown.seconds:.2f} s")
        else:
            self.status.set_text(f"{out.label}: live answers in {out.seconds:.3f} s; the FE check ({shown.label}) "
                                 "lies in every band")

    def show(self, gen: int) -> None:
        out = self.outcome
        if out is None:
            return
        an = out.analysis
        rows = [{"answer": q, "value": v, "verdict": vd} for q, v, vd in answer_rows(an, self.bands)]
        pin = self.s.pinned
        self.answers.columns = self._columns(pin is not None)
        if pin is not None:
            prow = answer_rows(pin.analysis)
            for r, (q, v, _) in zip(rows, prow):
                r["pinned"] = v
                r["delta"] = _delta(r["value"], v)
        self.answers.rows = rows
        self.answers.classes(remove="opacity-50")  # the answers of the design on the panel
        self.answers.update()
        self.warnings.clear()
        with self.warnings:
            for w in an.warnings:
                ui.label(f"WARNING: {w}").classes("text-xs text-red-700")
        self.torque.options.clear()
        self.torque.options.update(torque_chart(an, pin.analysis if pin is not None else None))
        self.torque.update()

    async def update_field(self, gen: int) -> None:
        out = self.outcome
        if out is None:
            return
        rpm = self.field_rpm

        def work():
            res = self.s.field(out, rpm)
            png, info = field_png(out.fe_design, res, rpm)
            return res, png, info

        got = await run.io_bound(work)
        if got is None or gen != self.s.generation:
            return
        res, png, info = got
        self.field_res = res
        self.field_img.set_source("data:image/png;base64," + base64.b64encode(png).decode())
        self.pressure.options.clear()
        pinned = self.pinned_res if (self.pinned_res is not None and float(self.pinned_res.rpm[0]) == rpm) else None
        self.pressure.options.update(pressure_chart(res, rpm, pinned))
        self.pressure.update()

def _delta(a: str, b: str) -> str:
    """Difference of two shown values with the same unit (the leading number and the unit
    after it, before any band), else ''."""
    def parse(t: str):
        head = t.split(" +-")[0].replace(FIRST_PASS, "").split()
        return float(head[0]), " ".join(head[1:])

    try:
        (x, ux), (y, uy) = parse(a), parse(b)
    except (IndexError, ValueError):
        return ""
    if ux != uy:
        return ""
    return f"{x - y:+.4g} {ux}".rstrip()


def torque_chart_placeholder() -> dict:
    return {"animation": False, "xAxis": {"type": "value"}, "yAxis": {"type": "value"}, "series": []}


def too_many_tabs() -> str:
    return (f"refused: {limits.MAX_SESSIONS} tabs of this app are open already (the most it analyses at once, to "
            "bound its memory); close one, or start another app with clutchfem app --port ...")


def build_page(out_root: Path, client: Client | None = None) -> DesignPage | HTMLResponse:
    """The page of one tab (called by NiceGUI for every page request).  Only the widgets are
    built here: the session's folder and its analysis start when the page connects
    (:meth:`DesignPage.start`); a page not connected within :data:`~.limits.PENDING_S` is
    dropped, a closed tab is reclaimed (:meth:`DesignPage.close`).  With
    :data:`~.limits.MAX_SESSIONS` tabs live, or :data:`~.limits.MAX_PENDING` pages waiting to
    connect, a refusal (503) and nothing built."""
    busy = (too_many_tabs() if len(live_tabs) >= limits.MAX_SESSIONS else
            f"refused: {limits.MAX_PENDING} pages of this app are waiting for their browser to connect; try again in "
            f"{limits.PENDING_S:.0f} s" if len(pending_pages) >= limits.MAX_PENDING else None)
    if busy is not None:
        if client is not None:
            asyncio.get_event_loop().call_soon(client.delete)
        return HTMLResponse(f"<!doctype html><title>clutchfem: busy</title><p data-testid=refused>{busy}</p>",
                            status_code=503)
    page = DesignPage(out_root, client)
    page.build()
    if client is not None:
        pending_pages[page.key] = page
        client.on_connect(page.start)
        client.on_delete(page.close)

        def drop_if_unconnected() -> None:
            if not page.started and not client.is_deleted:
                client.delete()

        asyncio.get_event_loop().call_later(limits.PENDING_S, drop_if_unconnected)
    return page

