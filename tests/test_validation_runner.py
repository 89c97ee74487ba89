"""Validation runner: lazy module loading, warnings, Markdown report, rich table, run time."""

from __future__ import annotations

import json
import re
import sys
import time
import types
import warnings
from pathlib import Path

import pytest
from rich.console import Console

from clutchfem.validation import runner
from clutchfem.validation.records import ValidationRecord

MINE = ("chain", "shaft")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """One report of chain + shaft + a module that does not exist (written once)."""
    root = tmp_path_factory.mktemp("val")
    with pytest.warns(runner.ValidationModuleWarning, match="no_such_module"):
        md = runner.write_report(root / "out", root / "docs" / "validation.md",
                                 modules=MINE + ("no_such_module",))
    return root, md


def test_default_modules():
    assert runner.MODULE_NAMES == ("wiesik", "thesis", "chain", "shaft")


def test_missing_module_is_skipped_with_a_warning():
    run = runner.collect(("no_such_module", "chain"))
    assert any("no_such_module" in w and "skipped" in w for w in run.warnings)
    assert {r.module for r in run.records} == {"chain"}
    with pytest.warns(runner.ValidationModuleWarning):
        recs = runner.run_all(("no_such_module", "chain"))
    assert len(recs) == len(run.records)
    with pytest.raises(ModuleNotFoundError):
        runner.collect(("no_such_module",), strict=True)


def test_failing_module_is_reported_not_hidden(monkeypatch):
    def broken():
        raise RuntimeError("boom")

    fake = types.ModuleType("clutchfem.validation._fake_broken")
    fake.records = broken
    monkeypatch.setitem(sys.modules, "clutchfem.validation._fake_broken", fake)
    run = runner.collect(("_fake_broken", "chain"))
    assert any("_fake_broken" in w and "boom" in w for w in run.warnings)
    assert run.records and all(r.module == "chain" for r in run.records)
    with pytest.raises(RuntimeError):
        runner.collect(("_fake_broken",), strict=True)


def test_unexplained_differs_and_duplicates_are_flagged(monkeypatch):
    fake = types.ModuleType("clutchfem.validation._fake_dup")
    fake.records = lambda: [ValidationRecord("x.a", "x", "q", 1.0, 2.0, "-"),
                            ValidationRecord("x.a", "x", "q", 1.0, 1.0, "-")]
    monkeypatch.setitem(sys.modules, "clutchfem.validation._fake_dup", fake)
    run = runner.collect(("_fake_dup",))
    assert any("without an explanation" in w for w in run.warnings)
    assert any("duplicate" in w for w in run.warnings)


def test_report_contents(report):
    root, md = report
    text = md.read_text()
    data = json.loads((root / "out" / "validation.json").read_text())
    recs = [types.SimpleNamespace(**d) for d in data["records"]]
    assert {r.module for r in recs} == set(MINE)
    for r in recs:
        assert f"`{r.id}`" in text
    # every differs row is explained in its module's section
    for name in MINE:
        section = text.split(f"## {name}\n", 1)[1].split("\n## ", 1)[0]
        explained = section.split("### Differences explained", 1)[1]
        for r in recs:
            if r.module == name and r.status == "differs":
                assert f"- `{r.id}`:" in explained
    assert "## Warnings" in text and "no_such_module" in text
    # figures: relative links that resolve from the report's folder
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert len(links) == 4
    for link in links:
        assert not Path(link).is_absolute()
        assert (md.parent / link).resolve().is_file()
    assert {"id", "paper", "computed", "status", "rel_diff", "note"} <= set(data["records"][0])
    assert len(recs) == len({r.id for r in recs}) > 90


def test_rich_table_reads_at_80_columns():
    recs = runner.collect(("chain",)).records
    console = Console(record=True, width=80)
    runner.print_table(recs, console=console)
    out = console.export_text()
    assert max(len(line.rstrip()) for line in out.splitlines()) <= 80
    assert "id (chain.*)" in out and "Nu2_min " in out and "differs" in out
    # every differs row is listed with its reason under the module's table
    why = out.split("Why chain rows differ:", 1)[1]
    for r in recs:
        if r.status == "differs":
            assert f"- {r.id}:" in why
    assert f"{len(recs)} records" in out
    assert runner.rich_table is runner.render_table  # the name cli.py uses


def test_report_run_does_not_run_modules_again(monkeypatch, tmp_path):
    calls = []
    fake = types.ModuleType("clutchfem.validation._fake_once")
    fake.records = lambda: calls.append(1) or [ValidationRecord("y.a", "y", "q", 1.0, 1.0, "-")]
    fake.figures = lambda out: []
    monkeypatch.setitem(sys.modules, "clutchfem.validation._fake_once", fake)
    run = runner.collect(("_fake_once",))
    runner.report_run(run, tmp_path / "out", tmp_path / "v.md")
    assert calls == [1]
    assert "`y.a`" in (tmp_path / "v.md").read_text()


def test_full_run_is_fast(tmp_path):
    """Everything that exists (all four modules when present) in well under 60 s."""
    t0 = time.perf_counter()
    with warnings.catch_warnings():  # other engineers' modules may be missing: not our test
        warnings.simplefilter("ignore", runner.ValidationModuleWarning)
        runner.write_report(tmp_path / "out", tmp_path / "validation.md")
    assert time.perf_counter() - t0 < 60.0
    assert (tmp_path / "validation.md").stat().st_size > 1000


def test_cli_validate_docs_collects_once(monkeypatch, tmp_path):
    from typer.testing import CliRunner

    from clutchfem.cli import app

    calls = []
    real = runner.collect

    def counting(modules=runner.MODULE_NAMES, **kw):
        calls.append(kw)
        return real(("chain",), **kw)

    monkeypatch.setattr(runner, "collect", counting)
    res = CliRunner().invoke(app, ["validate", "--docs", str(tmp_path / "v.md"), "--out",
                                   str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert calls == [{}]
    assert (tmp_path / "v.md").is_file() and (tmp_path / "out" / "validation.json").is_file()
    res = CliRunner().invoke(app, ["validate", "--json"])
    data = json.loads(res.stdout)
    assert {"id", "paper", "computed", "unit", "status", "note"} <= set(data[0])
    # the crankshaft whirl left validation (clutch/whirl.py): --concept is gone, and an
    # unknown option is refused with a non-zero exit before any module runs
    calls.clear()
    for bad in (["--concept", "concept1"], ["--no-such-option"]):
        res = CliRunner().invoke(app, ["validate", *bad])
        assert res.exit_code != 0 and calls == []
