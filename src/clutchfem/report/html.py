"""The one-page report: one self-contained HTML page (images embedded as data URIs) and the
same content in Markdown (images beside it as files), for a design and for a run
(optimisation, tolerance Monte Carlo, compensation, or any folder of tables and charts).

A :class:`Page` is data (title, verdicts, headline answers, a hero chart, sections of tables,
figures and text, the full design inputs); :func:`write_page` renders it twice and keeps the
spec as ``page.json`` so that ``clutchfem report --run DIR`` can render a run folder again.

Layout, for a designer who reads the answers on one screen (checked in headless Chromium at
1280 x 800): the verdicts (PASS / FAIL against the targets) in one row, then the headline
answers (every number with its unit) beside the main chart; details (drawing, all answers,
inputs, material, tables) below the fold.  Plain HTML and one small inline style sheet: no
script, no external resource, so the file opens anywhere and archives as one file.
"""

from __future__ import annotations

import base64
import html
import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..core import InputError, clean
from ..core import write as write_json
from .readback import read_csv, read_json

CSS = """
body{font-family:-apple-system,'Segoe UI',Helvetica,Arial,sans-serif;font-size:13px;margin:14px 22px;color:#222;
max-width:1400px}
h1{font-size:20px;margin:0 0 2px 0}h2{font-size:15px;margin:18px 0 6px 0;border-bottom:1px solid #ddd}
.sub{color:#555;margin-bottom:8px}
.verdicts{display:flex;flex-wrap:wrap;gap:6px;margin:6px 0 10px 0}
.v{padding:4px 8px;border-radius:4px;font-weight:600;font-size:12px}
.pass{background:#e3f4e6;color:#17632a;border:1px solid #9ed3a8}.fail{background:#fde8e8;color:#9b1c1c;
border:1px solid #f1a9a9}.info{background:#eef2f8;color:#234;border:1px solid #c8d3e6}
.top{display:grid;grid-template-columns:minmax(380px,46%) 1fr;gap:16px;align-items:start}
table{border-collapse:collapse;width:100%}td,th{border-bottom:1px solid #e6e6e6;padding:3px 6px;text-align:left;
vertical-align:top}th{background:#f6f6f6;font-weight:600}td.num{text-align:right;white-space:nowrap}
.ans td:first-child{color:#444}.ans td:last-child{font-weight:600;text-align:right;overflow-wrap:anywhere}
.top>div{min-width:0}
img{max-width:100%;height:auto;border:1px solid #eee}.fig img{max-width:min(100%,960px)}
.fig{margin:6px 0 12px 0}.cap{color:#555;font-size:12px}
.warn{background:#fff6e0;border-left:3px solid #e0a800;padding:3px 8px;margin:3px 0}
.small{font-size:11px;color:#555}details{margin:6px 0}pre{font-size:11px;background:#f8f8f8;padding:6px;
overflow-x:auto;white-space:pre-wrap;overflow-wrap:anywhere}
.grid2{display:grid;grid-template-columns:1fr 1fr;gap:12px}
"""


@dataclass
class Table:
    title: str
    columns: list[str]
    rows: list[list]
    note: str = ""


@dataclass
class Figure:
    title: str
    file: str  # file name inside the output folder
    caption: str = ""


@dataclass
class Text:
    title: str
    lines: list[str]
    kind: str = "list"  # list | warn | pre | para | links (file names beside the page)


@dataclass
class Page:
    title: str
    subtitle: str = ""
    verdicts: list = field(default_factory=list)  # [label, True/False/None, detail]
    headline: list = field(default_factory=list)  # [quantity, value with unit]
    hero: list = field(default_factory=list)  # [Figure]
    sections: list = field(default_factory=list)  # [(title, [Table | Figure | Text])]
    inputs: dict = field(default_factory=dict)
    kind: str = "design"

    def to_json(self) -> dict:
        def blk(b):
            d = asdict(b)
            d["type"] = type(b).__name__
            return d

        return clean({"kind": self.kind, "title": self.title, "subtitle": self.subtitle, "verdicts": self.verdicts,
                      "headline": self.headline, "hero": [blk(f) for f in self.hero],
                      "sections": [{"title": t, "blocks": [blk(b) for b in bs]} for t, bs in self.sections],
                      "design_hash": (self.inputs or {}).get("design_hash"), "inputs": self.inputs})

    @classmethod
    def from_json(cls, d: dict) -> "Page":
        types = {"Table": Table, "Figure": Figure, "Text": Text}

        def blk(b):
            b = dict(b)
            return types[b.pop("type")](**b)

        return cls(title=d["title"], subtitle=d.get("subtitle", ""), verdicts=d.get("verdicts", []),
                   headline=d.get("headline", []), hero=[blk(f) for f in d.get("hero", [])],
                   sections=[(s["title"], [blk(b) for b in s["blocks"]]) for s in d.get("sections", [])],
                   inputs=d.get("inputs", {}), kind=d.get("kind", "run"))


def _e(x) -> str:
    return html.escape(str(x))


def _data_uri(path: Path) -> str:
    mime = {"png": "image/png", "svg": "image/svg+xml", "jpg": "image/jpeg"}.get(path.suffix.lower()[1:], "image/png")
    return f"data:{mime};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def _cell(v) -> tuple[str, bool]:
    if isinstance(v, float):
        if not math.isfinite(v):
            return "-", True
        return f"{v:.4g}", True
    if isinstance(v, (int,)) and not isinstance(v, bool):
        return str(v), True
    return ("-" if v is None else str(v)), False


def _html_block(b, folder: Path) -> str:
    if isinstance(b, Table):
        head = "".join(f"<th>{_e(c)}</th>" for c in b.columns)
        body = []
        for r in b.rows:
            cells = []
            for v in r:
                t, num = _cell(v)
                cells.append(f"<td class='num'>{_e(t)}</td>" if num else f"<td>{_e(t)}</td>")
            body.append("<tr>" + "".join(cells) + "</tr>")
        note = f"<div class='small'>{_e(b.note)}</div>" if b.note else ""
        title = f"<h3 style='font-size:13px;margin:8px 0 4px'>{_e(b.title)}</h3>" if b.title else ""
        return f"{title}<table><tr>{head}</tr>{''.join(body)}</table>{note}"
    if isinstance(b, Figure):
        p = folder / b.file
        if not p.exists():
            return f"<div class='warn'>figure {_e(b.file)} is missing</div>"
        cap = f"<div class='cap'>{_e(b.caption)}</div>" if b.caption else ""
        return (f"<div class='fig'><div><b>{_e(b.title)}</b></div><img alt='{_e(b.title)}' "
                f"src='{_data_uri(p)}'>{cap}</div>")
    if isinstance(b, Text):
        title = f"<div><b>{_e(b.title)}</b></div>" if b.title else ""
        if b.kind == "warn":
            return title + "".join(f"<div class='warn'>{_e(x)}</div>" for x in b.lines)
        if b.kind == "pre":
            return title + f"<pre>{_e(chr(10).join(b.lines))}</pre>"
        if b.kind == "para":
            return title + "".join(f"<p>{_e(x)}</p>" for x in b.lines)
        if b.kind == "links":
            return title + "<ul>" + "".join(f"<li><a href='{_e(x)}'>{_e(x)}</a></li>" for x in b.lines) + "</ul>"
        return title + "<ul>" + "".join(f"<li>{_e(x)}</li>" for x in b.lines) + "</ul>"
    raise TypeError(type(b))


def render_html(page: Page, folder: Path) -> str:
    v = "".join(f"<span class='v {'pass' if ok else ('fail' if ok is False else 'info')}'>"
                f"{'PASS' if ok else ('FAIL' if ok is False else '')} {_e(label)}"
                f"{(': ' + _e(detail)) if detail else ''}</span>" for label, ok, detail in page.verdicts)
    ans = "".join(f"<tr><td>{_e(q)}</td><td>{_e(val)}</td></tr>" for q, val in page.headline)
    hero = "".join(_html_block(f, folder) for f in page.hero)
    secs = []
    for title, blocks in page.sections:
        secs.append(f"<h2>{_e(title)}</h2>" + "".join(_html_block(b, folder) for b in blocks))
    inputs = json.dumps(clean(page.inputs), indent=1, sort_keys=True)
    return (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{_e(page.title)}</title>"
            f"<style>{CSS}</style></head><body><h1>{_e(page.title)}</h1><div class='sub'>{_e(page.subtitle)}</div>"
            f"<div class='verdicts'>{v}</div><div class='top'><div><table class='ans'>{ans}</table></div>"
            f"<div>{hero}</div></div>{''.join(secs)}"
            f"<h2>Design inputs (full record)</h2><details><summary>every input that defines these answers "
            f"(also in inputs.json)</summary><pre>{_e(inputs)}</pre></details></body></html>")


def _md_cell(v) -> str:
    t, _ = _cell(v)
    return t.replace("|", "\\|")


def _md_block(b) -> list[str]:
    if isinstance(b, Table):
        out = [f"**{b.title}**", ""] if b.title else []
        out += ["| " + " | ".join(b.columns) + " |", "|" + "---|" * len(b.columns)]
        out += ["| " + " | ".join(_md_cell(v) for v in r) + " |" for r in b.rows]
        if b.note:
            out += ["", f"*{b.note}*"]
        return out + [""]
    if isinstance(b, Figure):
        return [f"**{b.title}**", "", f"![{b.title}]({b.file})", ""] + ([f"*{b.caption}*", ""] if b.caption else [])
    if isinstance(b, Text):
        out = [f"**{b.title}**", ""] if b.title else []
        if b.kind == "warn":
            out += [f"> **WARNING:** {x}" for x in b.lines]
        elif b.kind == "pre":
            out += ["```"] + list(b.lines) + ["```"]
        elif b.kind == "para":
            out += [x + "\n" for x in b.lines]
        elif b.kind == "links":
            out += [f"* [{x}]({x})" for x in b.lines]
        else:
            out += [f"* {x}" for x in b.lines]
        return out + [""]
    raise TypeError(type(b))


def render_md(page: Page) -> str:
    lines = [f"# {page.title}", "", page.subtitle, ""]
    if page.verdicts:
        lines += [" · ".join(f"**{'PASS' if ok else ('FAIL' if ok is False else '')} {label}**"
                             + (f": {detail}" if detail else "") for label, ok, detail in page.verdicts), ""]
    lines += ["| answer | value |", "|---|---|"] + [f"| {q} | {v} |" for q, v in page.headline] + [""]
    for f in page.hero:
        lines += _md_block(f)
    for title, blocks in page.sections:
        lines += [f"## {title}", ""]
        for b in blocks:
            lines += _md_block(b)
    lines += ["## Design inputs (full record)", "", "See `inputs.json`.", ""]
    return "\n".join(lines)


def write_page(page: Page, folder: Path, stem: str = "report") -> tuple[Path, Path]:
    """Write ``<stem>.html`` (self-contained), ``<stem>.md``, ``page.json`` and
    ``inputs.json`` into ``folder``; returns (html, md)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    h = folder / f"{stem}.html"
    m = folder / f"{stem}.md"
    h.write_text(render_html(page, folder), encoding="utf-8")
    m.write_text(render_md(page), encoding="utf-8")
    write_json(folder / "page.json", page.to_json(), indent=1)
    if page.inputs:
        write_json(folder / "inputs.json", page.inputs, indent=1)
    return h, m


def folder_page(folder: Path) -> Page:
    """A page for any run folder: its ``page.json`` if there is one, else every PNG and the
    first rows of every CSV in it (a sweep folder of the study engine, a hand-made folder)."""
    folder = Path(folder)
    spec = folder / "page.json"
    if spec.exists():
        doc = read_json(spec, "run page")
        try:
            return Page.from_json(doc)
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise InputError(f"run page {spec}: JSON, but not a page clutchfem wrote ({type(exc).__name__}: {exc}); "
                             "remove it to show the folder's tables and charts instead") from None
    sections = []
    figs = [Figure(p.stem.replace("_", " "), p.name) for p in sorted(folder.glob("*.png"))]
    tabs = []
    for p in sorted(folder.glob("*.csv")):
        df = read_csv(p)
        tabs.append(Table(f"{p.name} ({len(df)} rows; first 40 shown)", [str(c) for c in df.columns],
                          df.head(40).values.tolist()))
    if tabs:
        sections.append(("Tables", tabs))
    if figs[1:]:
        sections.append(("Charts", figs[1:]))
    inputs = {}
    if (folder / "inputs.json").exists():
        inputs = read_json(folder / "inputs.json", "design inputs")
    return Page(title=f"Run {folder.name}", subtitle=f"every table and chart in {folder}", hero=figs[:1],
                sections=sections, inputs=inputs, kind="run")
